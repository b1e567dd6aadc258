#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/fuzz/run.sh: replays every regression input under tests/fuzz/<target>/
# through that target's LLVMFuzzerTestOneInput, linked with replay.c by the
# normal compiler ($BUILD/fuzz/replay_<target>, built by make unit): one TAP
# line per input; a crash, a sanitizer report or a hang (timeout 20) fails.
# The inputs are what make fuzz found (minimised) and the issue's crashers.
set -u
cd "$(dirname "$0")/../.." || exit 2
BUILD=${BUILD:-build/release}
for t in scene image; do
	bin=$BUILD/fuzz/replay_$t
	if [ ! -x "$bin" ]; then
		echo "not ok - fuzz/$t: no replay driver $bin (make unit builds it)"
		continue
	fi
	for f in tests/fuzz/$t/*; do
		[ -f "$f" ] || continue
		out=$(timeout 20 "$bin" "$f" 2>&1)
		rc=$?
		if [ "$rc" -eq 0 ]; then
			echo "ok - fuzz/$t/${f##*/}"
		else
			echo "not ok - fuzz/$t/${f##*/}: exit status $rc"
			printf '%s\n' "$out" | tail -n 8 | sed 's/^/#   /'
		fi
	done
done
