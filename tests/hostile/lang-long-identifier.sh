#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: a 4 MiB identifier.
. tests/hostile/data/lang-lib.sh "$@"
{ printf '#declare '; repeat_inline 4194304 'a'; echo ' = 1;'; } > "$T/s.scn"
expect 65 "$T/s.scn:1:10: error: identifier too long (4194304 characters; the limit is 1024)" --check "$T/s.scn"
done_case "4 MiB identifier: a located error, exit 65"
