#!/bin/sh
# SPDX-License-Identifier: MIT
# bench/caustics/ring.sh: issue 8's table, as a user measures it: the
# fold-ring scene (bench/caustics/ring.scn, a ball lens whose floor lies
# between its foci) rendered 800x800 straight down over x, z in [-1, 1]
# (-D View=1), its caustic layer binned into 0.02 annuli by renderl1.c and
# compared with the exact profile (flux-weighted L1). Point deposits at fixed
# cells and automatic, light shafts automatic, at 250k, 1M and 4M rays.
# Writes bench/results/ring.txt (L1, light-pass time and map memory from
# --stats).   sh bench/caustics/ring.sh    (from anywhere; ~3 minutes)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
ARVO=${ARVO:-$root/arvo}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-ring.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
cc -std=c11 -D_DEFAULT_SOURCE -O2 -o "$tmp/renderl1" "$here/renderl1.c" -lm
out=$root/bench/results/ring.txt
{
	echo "bench/caustics/ring.sh: fold-ring scene, 800x800 render of the caustic layer, 0.02 annuli, r <= 1"
	echo "method  cell   rays     l1       light_s  map_MiB"
	for m in "point 0.01" "point 0.005" "point 0.0025" "point auto" "shaft auto"; do
		set -- $m
		def=""
		[ "$2" = auto ] || def="-D Cell=$2"
		for n in 250000 1000000 4000000; do
			"$ARVO" -q --stats --method "$1" --rays $n -D View=1 $def --width 800 --height 800 \
				-o "$tmp/r.exr" "$here/ring.scn" 2> "$tmp/err"
			oiiotool "$tmp/r.exr" --ch caustic.G -o "$tmp/g.exr"
			l1=$(oiiotool --dumpdata "$tmp/g.exr" | "$tmp/renderl1" 1 | sed 's/l1=//')
			t=$(sed -n 's/^arvo: light pass *\([0-9.]*\) s.*/\1/p' "$tmp/err")
			mb=$(sed -n 's/^arvo: light pass .*maps, \([0-9.]*\) MiB.*/\1/p' "$tmp/err")
			printf '%-7s %-6s %-8s %-8s %-8s %s\n' "$1" "$2" "$n" "$l1" "$t" "$mb"
		done
	done
} > "$out"
cat "$out"
