#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/povray-compat/photons.sh: POV-Ray's lights/phot_met_glass (a metal
# ring and cage around a glass sphere, caustics by photons) rendered by
# arvo's illumination maps and by POV-Ray 3.7's photon map, side by side:
# writes docs/img/phot_met_glass.png (arvo left, POV-Ray right) and prints
# the mean absolute difference of the two 8-bit images and both times.
# Run by `make povray-photons`; compat.sh installs the packages.
set -u
cd "$(dirname "$0")/../.." || exit 2
ARVO=${ARVO:-$PWD/arvo}
W=${W:-320} H=${H:-240}
scene=/usr/share/doc/povray/examples/lights/phot_met_glass.pov
[ -f "$scene" ] || { echo "no $scene: run make povray-compat first (it installs povray-examples)"; exit 1; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-photons.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
now() { date +%s.%N; }
dir=$(dirname "$scene")
t0=$(now)
(cd "$dir" && povray +Iphot_met_glass.pov +O"$tmp/pov.png" +FN +W$W +H$H -A -D +WT2 -GA > "$tmp/pov.log" 2>&1) ||
	{ echo "POV-Ray failed:"; tail -5 "$tmp/pov.log"; exit 1; }
t1=$(now)
(cd "$dir" && "$ARVO" -q --threads 2 --width $W --height $H -o "$tmp/arvo.png" phot_met_glass.pov) ||
	{ echo "arvo failed"; exit 1; }
t2=$(now)
mkdir -p docs/img
oiiotool "$tmp/arvo.png" "$tmp/pov.png" --mosaic 2x1 -o docs/img/phot_met_glass.png
diff=$(idiff -a "$tmp/arvo.png" "$tmp/pov.png" 2>/dev/null |
	awk '/Mean error/ { printf "%.2f", $4 * 100; exit } /^PASS/ { print "0.00"; exit }')
awk -v a="$t1" -v b="$t2" -v c="$t0" -v d="$diff" -v w=$W -v h=$H 'BEGIN {
	printf "phot_met_glass %dx%d, no antialiasing, 2 threads: mean difference %s %%; POV-Ray %.1f s, arvo %.1f s\n", w, h, d, a - c, b - a }'
echo "wrote docs/img/phot_met_glass.png (arvo left, POV-Ray right)"
