#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: a valid 10 MB scene of 400,000 declarations reads within the time limit.
. tests/hostile/data/lang-lib.sh "$@"
awk 'BEGIN { for (i = 0; i < 400000; i++) printf "#declare V%d = <%d, %d.5, -%d>;\n", i % 1000, i, i, i }' > "$T/s.scn"
expect 0 "" --check "$T/s.scn"
done_case "400,000 declarations in a 10 MB scene: exit 0"
