#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: a recursive macro whose body nests 190 #if: each file is within the
# parser's 200 levels, the evaluation is not (was 38,000 C frames deep).
. tests/hostile/data/lang-lib.sh "$@"
{ echo '#macro M(N)'; repeat 190 '#if (1)'; echo 'M(N + 1)'; repeat 190 '#end'; echo '#end'; echo 'M(0)'; } > "$T/s.scn"
expect 65 "$T/s.scn:90:6: error: nesting too deep (more than 2000 levels of blocks, directives, macro calls, includes and expressions)" --check "$T/s.scn"
done_case "recursive macro nesting 190 #if: a located error at 2000 levels, exit 65"
