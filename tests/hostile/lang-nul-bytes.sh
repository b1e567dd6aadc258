#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: NUL bytes inside a scene, between and inside tokens.
. tests/hostile/data/lang-lib.sh "$@"
printf 'sphere { 0, 1 }\n#decl\000are A = 1;\n' > "$T/s.scn"
expect 65 "$T/s.scn:2:1: error: unknown directive '#decl'" --check "$T/s.scn"
done_case "NUL bytes in a scene: a located error, exit 65"
