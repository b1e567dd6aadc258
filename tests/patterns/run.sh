#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/patterns/run.sh: POV-Ray's patterns, warps, maps and normals
# against POV-Ray itself. Each scene *.pov is a plane showing one feature;
# its golden *.png is POV-Ray 3.7's render (regen.sh). arvo renders the
# scene at the same 40x30 and the mean absolute difference of the two 8-bit
# images (idiff -a) must be at most LIMIT % of full scale: most are
# identical; wood's turbulence and the wave patterns differ in a few pixels.
set -u
cd "$(dirname "$0")/../.." || exit 2
ARVO=${ARVO:-$PWD/arvo}
LIMIT=${LIMIT:-0.5}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-patterns.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
n=0
for f in tests/patterns/*.pov; do
	n=$((n + 1))
	name=$(basename "$f" .pov)
	what=$(sed -n '1s|^// ||p' "$f")
	if ! "$ARVO" -q --width 40 --height 30 -o "$tmp/$name.png" "$f" > "$tmp/log" 2>&1; then
		echo "not ok $n - $name: arvo failed"
		sed 's/^/#   /' "$tmp/log" | head -5
		continue
	fi
	d=$(idiff -a "$tmp/$name.png" "tests/patterns/$name.png" 2>/dev/null |
		awk '/Mean error/ { printf "%.3f", $4 * 100; exit } /^PASS/ { print "0.000"; exit }')
	if [ -n "$d" ] && awk "BEGIN { exit !($d <= $LIMIT) }"; then
		echo "ok $n - $name ($what): mean difference $d %"
	else
		echo "not ok $n - $name ($what): mean difference ${d:-?} %, limit $LIMIT %"
	fi
done
echo "1..$n"
