#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: "color color color ... rgb 1", 100,000 colour keywords in a row.
. tests/hostile/data/lang-lib.sh "$@"
{ printf 'background { '; repeat_inline 100000 'color '; echo 'rgb 1 }'; } > "$T/s.scn"
expect 65 "$T/s.scn:1:1208: error: nesting too deep (more than 200 levels)" --check "$T/s.scn"
done_case "100,000 chained colour keywords: a located error, exit 65"
