#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: a 2 MiB string literal (the limit is 1 MiB).
. tests/hostile/data/lang-lib.sh "$@"
{ printf '#declare S = "'; repeat_inline 2097152 'x'; echo '";'; } > "$T/s.scn"
expect 65 "$T/s.scn:1:14: error: string too long (2097152 bytes; the limit is 1048576)" --check "$T/s.scn"
done_case "2 MiB string literal: a located error, exit 65"
