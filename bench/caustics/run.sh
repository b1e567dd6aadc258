#!/bin/sh
# SPDX-License-Identifier: MIT
# bench/caustics/run.sh: caustic speed and accuracy, arvo's light pass against
# POV-Ray 3.7's photons, on refs scene B (glass sphere r 1, ior 1.5, 7 below
# a point light, 3 above a diffuse floor; ideal transmission).
#
#   sh bench/caustics/run.sh            (from anywhere; ~3 minutes)
#
# arvo: builds libarvo.a with the Makefile into $BUILD (default
# build/caustics; or give LIBARVO=path/libarvo.a), then lightrays.c against
# it (same flags as the Makefile). For each floor map cell in $CELLS (the
# scene's `illum_map { cell }`, 0.01 as written) and each light-ray budget in
# $BUDGETS it times lp_run alone (clock_gettime), $RUNS times, on $THREADS
# threads, and bins the floor map's node energies into 0.05 annuli out to
# r = 3 (L1 against tests/accuracy/B_profile_binned_0.05.csv,
# flux_caustic_n1.50). Binning node energies smears each annulus edge by a
# cell, which sets a floor under L1 (about 0.85 % at cell 0.01, 0.25 % at
# 0.005): a finer cell lowers the floor and costs memory.
# POV-Ray: sphere.pov, ${W}x${W} EXR (+FE, float), -A, +WT$THREADS, for each
# photon `count` in $POV_COUNTS. The image holds the caustic only; povl1.c
# bins it into the same annuli, scales it to the reference flux on r ≤ 3 and
# takes the same L1. POV-Ray's time is its median wall time minus the median
# wall time of the same render with photons off (Count=0: start-up, parse,
# the 600x600 eye pass), i.e. what the photons cost: shooting, the photon map
# and the gathers.
# Columns of bench/results/caustics.csv:
#   tool,budget          arvo light rays | POV-Ray photon count setting
#   time_s               median over $RUNS (arvo: lp_run; POV-Ray: see above)
#   l1,l1_noise          flux-weighted relative L1, and the L1 photon noise
#                        alone would give with that many rays/photons shot
#   rays_per_s_per_core  rays (photons) shot / time_s / threads
#   rays_shot,segments   arvo: lp_stats; POV-Ray: photons shot, empty
#   wall_s               POV-Ray: median wall time of the photon render
#   cell                 arvo: the floor map's cell
# Then, for each L1 target in $TARGETS, the smallest time reaching it for
# each tool and their ratio (bench/results/caustics.txt), and the chart
# bench/results/caustics.png.
set -eu

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
res=$root/bench/results
POVRAY=${POVRAY:-povray}
THREADS=${THREADS:-2} RUNS=${RUNS:-3} W=${W:-600} TARGETS=${TARGETS:-0.02 0.01}
CELLS=${CELLS:-0.01 0.005}
BUDGETS=${BUDGETS:-30000 50000 100000 300000 1000000 3000000 10000000}
POV_COUNTS=${POV_COUNTS:-100000 300000 500000 1000000 3000000 10000000}
BUILD=${BUILD:-build/caustics}
REF=$root/tests/accuracy/B_profile_binned_0.05.csv
mkdir -p "$res"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-bench-caustics.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM

median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
now() { date +%s.%N; }
# kv KEY FILE: the value of KEY=value in FILE's last line.
kv() { tail -1 "$2" | tr ' ' '\n' | awk -F= -v k="$1" '$1 == k { print $2 }'; }

# ---- build ----------------------------------------------------------------
cd "$root"
if [ -z "${LIBARVO:-}" ]; then
	make -s -j"$THREADS" BUILD="$BUILD" "$BUILD/libarvo.a" > /dev/null
	LIBARVO=$root/$BUILD/libarvo.a
fi
WARN="-Wall -Wextra -Wpedantic -Wshadow -Wundef -Wpointer-arith -Wcast-align -Wwrite-strings
 -Wmissing-prototypes -Wstrict-prototypes -Wmissing-declarations -Wformat=2 -Wvla -Wold-style-definition"
PKG_CFLAGS=$(pkg-config --cflags OpenEXR OpenColorIO libpng freetype2)
PKG_LIBS="$(pkg-config --libs OpenEXR OpenColorIO libpng freetype2) -lembree3"
# shellcheck disable=SC2086
cc -std=c11 -O2 $WARN -pthread -D_DEFAULT_SOURCE $PKG_CFLAGS -o "$tmp/lightrays" \
	"$here/lightrays.c" "$LIBARVO" $PKG_LIBS -lstdc++ -lm -pthread
# shellcheck disable=SC2086
cc -std=c11 -O2 $WARN -D_DEFAULT_SOURCE -o "$tmp/povl1" "$here/povl1.c" -lm

echo "tool,budget,time_s,l1,l1_noise,rays_per_s_per_core,rays_shot,segments,wall_s,cell" > "$tmp/c.csv"

# ---- arvo -------------------------------------------------------------------
for cell in $CELLS; do
	sed "s/cell 0\.01/cell $cell/" tests/accuracy/sphere.scn > "$tmp/sphere.scn"
	for n in $BUDGETS; do
		: > "$tmp/a.log"
		for i in $(seq "$RUNS"); do
			"$tmp/lightrays" "$n" "$THREADS" "$tmp/sphere.scn" "$REF" >> "$tmp/a.log"
		done
		t=$(tr ' ' '\n' < "$tmp/a.log" | awk -F= '$1 == "time_s" { print $2 }' | median)
		rs=$(kv rays_shot "$tmp/a.log") sg=$(kv segments "$tmp/a.log")
		awk -v n="$n" -v t="$t" -v l="$(kv l1 "$tmp/a.log")" -v e="$(kv l1_noise "$tmp/a.log")" \
			-v r="$rs" -v s="$sg" -v th="$THREADS" -v c="$cell" \
			'BEGIN { printf "arvo,%d,%.4f,%.5f,%.5f,%.0f,%d,%d,,%s\n", n, t, l, e, r / t / th, r, s, c }' >> "$tmp/c.csv"
		tail -1 "$tmp/c.csv"
	done
done

# ---- POV-Ray ------------------------------------------------------------------
# pov COUNT: median wall time of $RUNS renders; the last image is $tmp/p.exr,
# its log $tmp/p.log.
pov() {
	for i in $(seq "$RUNS"); do
		t0=$(now)
		(cd "$tmp" && "$POVRAY" +I"$here/sphere.pov" +O"$tmp/p.exr" +FE +W"$W" +H"$W" -A -D \
			+WT"$THREADS" Declare=Count="$1" > /dev/null 2> "$tmp/p.log")
		awk -v a="$t0" -v b="$(now)" 'BEGIN { printf "%.4f\n", b - a }'
	done | median
}
if command -v "$POVRAY" > /dev/null 2>&1; then
	base=$(pov 0)
	echo "POV-Ray without photons: $base s wall (subtracted)"
	for c in $POV_COUNTS; do
		wall=$(pov "$c")
		shot=$(awk '/photons shot/ { print $NF; exit }' "$tmp/p.log")
		oiiotool --dumpdata "$tmp/p.exr" | "$tmp/povl1" 3 "$REF" "$shot" > "$tmp/l.txt"
		awk -v c="$c" -v w="$wall" -v b="$base" -v l="$(kv l1 "$tmp/l.txt")" \
			-v e="$(kv l1_noise "$tmp/l.txt")" -v r="$shot" -v th="$THREADS" \
			'BEGIN { t = w - b; printf "povray,%d,%.4f,%.5f,%.5f,%.0f,%d,,%.4f,\n", c, t, l, e, r / t / th, r, w }' \
			>> "$tmp/c.csv"
		tail -1 "$tmp/c.csv"
	done
else
	base=
	echo "bench/caustics: $POVRAY not found, arvo only" >&2
fi
cp "$tmp/c.csv" "$res/caustics.csv"

# ---- summary ---------------------------------------------------------------
# best TOOL TARGET: "time budget l1 cell" of the fastest row with l1 <= TARGET.
best() {
	awk -F, -v tool="$1" -v T="$2" 'NR > 1 && $1 == tool && $4 <= T && (b == "" || $3 < b) { b = $3; n = $2; l = $4; c = $10 }
		END { if (b != "") print b, n, l, c }' "$res/caustics.csv"
}
{
	echo "bench/caustics: scene B (tests/accuracy/sphere.scn, bench/caustics/sphere.pov), $THREADS threads, median of $RUNS"
	echo "POV-Ray: ${W}x${W}, -A, photons radius 0.05 jitter 0.4, time = wall - wall without photons (${base:-?} s)"
	echo "cpu: $(awk -F': ' '/model name/ { print $2; exit }' /proc/cpuinfo), $(nproc) online; load at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
	sed 's/,,/,-,/g; s/,,/,-,/g; s/,$/,-/' "$res/caustics.csv" | column -s, -t
	for T in $TARGETS; do
		a=$(best arvo "$T") p=$(best povray "$T")
		echo "time to L1 <= $T:"
		echo "  arvo:    ${a:-not reached} (s, rays, L1, cell)"
		echo "  POV-Ray: ${p:-not reached} (s, photon count, L1)"
		if [ -n "$a" ] && [ -n "$p" ]; then
			echo "$a $p" | awk '{ printf "  ratio POV-Ray / arvo: %.1fx (goal >= 10x at 0.02)\n", $5 / $1 }'
		fi
	done
} > "$res/caustics.txt"
cat "$res/caustics.txt"

if command -v gnuplot > /dev/null 2>&1; then
	awk -F, 'NR > 1 && $1 == "arvo" && $10 == 0.01 { print $3, $4, $2 }' "$res/caustics.csv" > "$tmp/a.dat"
	awk -F, 'NR > 1 && $1 == "arvo" && $10 == 0.005 { print $3, $4, $2 }' "$res/caustics.csv" > "$tmp/a2.dat"
	awk -F, 'NR > 1 && $1 == "povray" { print $3, $4, $2 }' "$res/caustics.csv" > "$tmp/p.dat"
	gnuplot <<GP
set terminal pngcairo size 900,560
set output "$res/caustics.png"
set title "bench/caustics: glass sphere caustic (refs scene B), $THREADS threads, median of $RUNS"
set logscale xy
set xlabel "time (s): arvo lp\\\\_run; POV-Ray wall minus no-photon wall"
set ylabel "flux-weighted relative L1 (0.05 annuli, r <= 3)"
set grid
set key right top
set format y "%g"
plot "$tmp/a.dat" using 1:2 with linespoints pt 7 title "arvo light pass, cell 0.01 (labels: rays)", \
     "$tmp/a.dat" using 1:2:(sprintf("%.0e", \$3)) with labels offset 0,-1 font ",8" notitle, \
     "$tmp/a2.dat" using 1:2 with linespoints pt 9 title "arvo light pass, cell 0.005", \
     "$tmp/p.dat" using 1:2 with linespoints pt 5 title "POV-Ray 3.7 photons (labels: count)", \
     "$tmp/p.dat" using 1:2:(sprintf("%.0e", \$3)) with labels offset 0,1 font ",8" notitle, \
     0.02 with lines dt 2 lc rgb "black" title "L1 = 0.02"
GP
fi
