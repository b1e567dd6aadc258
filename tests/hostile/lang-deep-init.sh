#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: 100,000 nested { in an array initialiser.
. tests/hostile/data/lang-lib.sh "$@"
{ printf '#declare A = array[1] '; repeat_inline 100000 '{'; } > "$T/s.scn"
expect 65 "$T/s.scn:1:222: error: nesting too deep (more than 200 levels)" --check "$T/s.scn"
done_case "100,000 nested initialiser braces: a located error, exit 65"
