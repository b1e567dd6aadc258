#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: 100,000 nested [ entries (the colour_map entry syntax).
. tests/hostile/data/lang-lib.sh "$@"
repeat_inline 100000 '[' > "$T/s.scn"
expect 65 "$T/s.scn:1:201: error: nesting too deep (more than 200 levels)" --check "$T/s.scn"
done_case "100,000 nested [: a located error, exit 65"
