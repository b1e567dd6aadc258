#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/golden/run.sh: for every tests/golden/NAME.scn, compares
# `$ARVO --dump-ast` with NAME.ast and `$ARVO --dump-scene` with NAME.scene
# (two TAP lines per scene). `UPDATE=1 sh tests/golden/run.sh` rewrites the
# expected files from the current binary: read the diff before committing.
# Then the golden images, by the recipe of docs/golden.md: images.sh renders
# each scene of images/golden.list and compares it with images/NAME.exr
# through `arvo compare` (UPDATE=1 rewrites them too).
# Environment: ARVO (default ./arvo), UPDATE, TIMEOUT (seconds, 10).
set -u
cd "$(dirname "$0")/../.." || exit 2
ARVO=${ARVO:-$PWD/arvo}
TIMEOUT=${TIMEOUT:-10}
UPDATE=${UPDATE:-}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-golden.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT INT TERM

n=0
for f in $(find tests/golden -maxdepth 1 -name '*.scn' | LC_ALL=C sort); do
	base=${f%.scn}
	for kind in ast scene; do
		n=$((n + 1))
		want=$base.$kind
		timeout "$TIMEOUT" "$ARVO" --dump-$kind "$f" > "$tmp/out" 2> "$tmp/err" < /dev/null
		rc=$?
		if [ -n "$UPDATE" ] && [ "$rc" -eq 0 ]; then
			cp "$tmp/out" "$want"
		fi
		if [ "$rc" -ne 0 ]; then
			echo "not ok $n - $want"
			echo "#   arvo --dump-$kind $f exited with status $rc"
			head -10 "$tmp/err" | sed 's/^/#   /'
		elif [ ! -f "$want" ]; then
			echo "not ok $n - $want"
			echo "#   no expected file (UPDATE=1 sh tests/golden/run.sh writes it)"
		elif ! cmp -s "$want" "$tmp/out"; then
			echo "not ok $n - $want"
			echo "#   output differs (- expected, + actual):"
			diff -u "$want" "$tmp/out" | sed -n '3,$p' | head -30 | sed 's/^/#   /'
		elif [ -s "$tmp/err" ]; then
			echo "not ok $n - $want"
			echo "#   unexpected messages on stderr:"
			head -10 "$tmp/err" | sed 's/^/#   /'
		else
			echo "ok $n - $want"
		fi
	done
done
[ "$n" -gt 0 ] || echo "not ok 1 - no scenes in tests/golden"

# ---- golden images (docs/golden.md) ----
# Renders are bit-identical on one build; the tolerance absorbs a libm or
# compiler that rounds differently: no value off by more than 0.01 in more
# than 0.1 % of the pixels.
ARVO=$ARVO COMPARE="--tolerance 0.01 --failpercent 0.1" sh tests/golden/images.sh tests/golden/images/golden.list |
	sed 's/^\(\(not \)*ok\) [0-9]* - /\1 - image /'
exit 0
