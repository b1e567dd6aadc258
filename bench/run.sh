#!/bin/sh
# SPDX-License-Identifier: MIT
# bench/run.sh: runs every bench/*/run.sh that exists (frontend, eye, ...),
# in name order, and exits non-zero if any of them failed. Each suite writes
# its results under bench/results/. Pass settings through the environment,
# e.g. ARVO=$PWD/build/bench/arvo sh bench/run.sh
set -u
here=$(cd "$(dirname "$0")" && pwd)
status=0
found=0
for suite in "$here"/*/run.sh; do
	[ -f "$suite" ] || continue
	found=1
	name=$(basename "$(dirname "$suite")")
	echo "==== bench/$name ===="
	if ! sh "$suite"; then
		echo "bench/$name: FAILED" >&2
		status=1
	fi
done
[ $found = 1 ] || echo "bench/run.sh: no bench/*/run.sh found" >&2
exit $status
