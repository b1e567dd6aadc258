#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: 45,000 nested #if (was a stack overflow, SIGSEGV) stop at the 200-level guard.
. tests/hostile/data/lang-lib.sh "$@"
{ repeat 45000 '#if (1)'; echo 'sphere { 0, 1 }'; repeat 45000 '#end'; } > "$T/s.scn"
expect 65 "$T/s.scn:200:6: error: nesting too deep (more than 200 levels)" --check "$T/s.scn"
done_case "45,000 nested #if: a located error, exit 65"
