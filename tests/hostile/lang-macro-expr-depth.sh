#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: a macro that recurses from under 150 unary minus signs: the file
# is within the parser's limits, the evaluation nests 150 levels per call.
. tests/hostile/data/lang-lib.sh "$@"
{ echo '#macro M(N)'; repeat_inline 150 '-'; echo 'M(N + 1)'; echo '#end'; echo '#declare A = M(0);'; } > "$T/s.scn"
expect 65 "$T/s.scn:2:22: error: nesting too deep (more than 2000 levels of blocks, directives, macro calls, includes and expressions)" --check "$T/s.scn"
done_case "macro recursion under 150 unary minus signs: a located error, exit 65"
