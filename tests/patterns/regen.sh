#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/patterns/regen.sh: renders each scene's golden with POV-Ray 3.7
# (40x30, no antialiasing, 8-bit PNG). The goldens are POV-Ray's images,
# never arvo's: run this only to add a scene.
set -eu
cd "$(dirname "$0")"
for f in ${1:-*.pov}; do
	povray +I"$f" +O"${f%.pov}.png" +FN +W40 +H30 -A -D +WT1 -GA > /dev/null 2>&1
done
