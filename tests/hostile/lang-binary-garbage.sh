#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: 64 KiB of binary garbage (a fixed pseudo-random stream) as a scene.
. tests/hostile/data/lang-lib.sh "$@"
awk 'BEGIN { srand(7); for (i = 0; i < 65536; i++) printf "%c", int(rand() * 255) + 1 }' > "$T/s.scn"
"$ARVO" --check "$T/s.scn" > "$T/out" 2> "$T/err" < /dev/null
rc=$?
[ "$rc" -eq 65 ] || why="exit status $rc, expected 65"
head -n 1 "$T/err" | grep -q "^$T/s.scn:[0-9]*:[0-9]*: error: " || why="${why:+$why; }first stderr line is not a located error: $(head -n 1 "$T/err" | cut -c1-120)"
done_case "64 KiB of binary garbage: located errors, exit 65"
