#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: 100,000 opening parentheses in one expression.
. tests/hostile/data/lang-lib.sh "$@"
{ printf '#declare A = '; repeat_inline 100000 '('; } > "$T/s.scn"
expect 65 "$T/s.scn:1:213: error: nesting too deep (more than 200 levels)" --check "$T/s.scn"
done_case "100,000 nested parentheses: a located error, exit 65"
