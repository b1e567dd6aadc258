#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: a real scene cut off at 60 points: each prefix is either a valid
# scene (exit 0) or a located error (exit 65), never a crash or a hang.
. tests/hostile/data/lang-lib.sh "$@"
src=stdlib-scenes/demo.scn
size=$(wc -c < "$src")
step=$((size / 60 + 1))
n=0
while [ "$n" -lt "$size" ]; do
	head -c "$n" "$src" > "$T/s.scn"
	"$ARVO" --check "$T/s.scn" > "$T/out" 2> "$T/err" < /dev/null
	rc=$?
	if [ "$rc" -ne 0 ] && [ "$rc" -ne 65 ]; then
		why="${why:+$why; }cut at $n bytes: exit $rc"
	elif [ "$rc" -eq 65 ] && ! head -n 1 "$T/err" | grep -q "^$T/s.scn:[0-9]*:[0-9]*: error: "; then
		why="${why:+$why; }cut at $n bytes: $(head -n 1 "$T/err")"
	fi
	n=$((n + step))
done
done_case "demo.scn cut at 60 points: exit 0 or a located error each time"
