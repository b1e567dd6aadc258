#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: 100,000 unary minus signs before a number.
. tests/hostile/data/lang-lib.sh "$@"
{ printf '#declare A = '; repeat_inline 100000 '-'; echo '1;'; } > "$T/s.scn"
expect 65 "$T/s.scn:1:213: error: nesting too deep (more than 200 levels)" --check "$T/s.scn"
done_case "100,000 unary minus: a located error, exit 65"
