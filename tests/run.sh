#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/run.sh: runs every suite and closes with "N passed, N failed".
# Each suite is a script tests/<suite>/run.sh that prints one "ok"/"not ok"
# line per case (TAP); unit test binaries under $BUILD/tests are run too.
# Environment: BUILD (build dir, from the Makefile), ARVO (the binary).
set -u
cd "$(dirname "$0")/.." || exit 2
BUILD=${BUILD:-build/release}
ARVO=${ARVO:-$PWD/arvo}
export BUILD ARVO
out=$(mktemp -d "${TMPDIR:-/tmp}/arvo-tests.XXXXXX")
trap 'rm -rf "$out"' EXIT INT TERM
pass=0 fail=0

# count FILE SUITE: tallies TAP lines of one suite's output.
count() {
	p=$(grep -c '^ok ' "$1") ; f=$(grep -c '^not ok ' "$1")
	pass=$((pass + p)); fail=$((fail + f))
	printf '%-24s %4d passed, %d failed\n' "$2" "$p" "$f"
	grep -B0 -A12 '^not ok ' "$1" | head -60
}

for t in "$BUILD"/tests/test_*; do
	[ -x "$t" ] || continue
	case "$t" in *.d) continue ;; esac
	name=unit/$(basename "$t")
	if ! "$t" > "$out/log" 2>&1; then
		grep -q '^not ok ' "$out/log" || echo "not ok - $name crashed or exited non-zero" >> "$out/log"
	fi
	count "$out/log" "$name"
done

for s in tests/*/run.sh; do
	[ -f "$s" ] || continue
	name=$(basename "$(dirname "$s")")
	sh "$s" > "$out/log" 2>&1 || grep -q '^not ok ' "$out/log" || echo "not ok - suite $name exited non-zero" >> "$out/log"
	count "$out/log" "$name"
done

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ] && [ "$pass" -gt 0 ]
