#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: 45,000 nested union { blocks stop at the 200-level guard.
. tests/hostile/data/lang-lib.sh "$@"
{ repeat 45000 'union {'; repeat 45000 '}'; } > "$T/s.scn"
expect 65 "$T/s.scn:201:1: error: nesting too deep (more than 200 levels)" --check "$T/s.scn"
done_case "45,000 nested union blocks: a located error, exit 65"
