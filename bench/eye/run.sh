#!/bin/sh
# SPDX-License-Identifier: MIT
# bench/eye/run.sh: eye-pass benchmark, arvo against POV-Ray 3.7.
#
#   ARVO=$PWD/build/bench/arvo sh bench/eye/run.sh
#
# Builds nothing: uses ${ARVO:-./arvo} and ${POVRAY:-povray} (its columns are
# left empty when it is not installed). Both render the same scene at the same
# size, without antialiasing, on the same number of threads, to PNG:
#   arvo -q --stats --rays 0 --threads $THREADS --spp 1 --width $W --height $H -o x.png
#   povray +Ix.pov +Ox.png +FN +W$W +H$H -A -D +WT$THREADS
# Scenes: prims.scn/.pov (a few primitives, reflection and refraction) and
# spheres.scn/.pov with N spheres for N in $SIZES (POV-Ray for $POV_SIZES;
# its 1M-sphere run parses for a long time, add it with POV_SIZES=...).
# Every time is the median of $RUNS runs (default 3; eye-pass and trace
# times are medians of their own), wall clock, start-up
# included (POV-Ray's is ~0.73 s even for one sphere; povray_trace_s
# is the "Trace Time" it prints, without start-up, parsing and bounding).
#   ratio             povray_s / arvo_s (above 1: arvo is faster)
#   trace_ratio       povray_trace_s / arvo_eye_s (tracing only)
#   arvo_rays         camera + reflected + refracted + shadow rays (--stats)
#   povray_rays       POV-Ray's "Rays:" statistic (camera, reflected and
#                     refracted rays; its shadow rays are not counted)
#   *_rays_per_s_core rays / trace time / threads
# Writes bench/results/eye.csv, eye.txt and (with gnuplot) eye-scaling.png;
# PLOT_ONLY=1 redraws the chart from an existing eye.csv.
set -eu

ARVO=${ARVO:-./arvo}
POVRAY=${POVRAY:-povray}
W=${W:-640} H=${H:-480} THREADS=${THREADS:-2} RUNS=${RUNS:-3}
SIZES=${SIZES:-1000 10000 100000 1000000}
POV_SIZES=${POV_SIZES:-1000 10000 100000}
here=$(cd "$(dirname "$0")" && pwd)
res=$here/../results
mkdir -p "$res"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-bench-eye.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
have_pov=0
command -v "$POVRAY" > /dev/null 2>&1 && have_pov=1

# median: the middle line of numbers on stdin.
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", b - a }'; }

# run_arvo SCENE N: median wall time; the median eye-pass time goes to
# $tmp/a.eye, the last --stats to $tmp/a.log.
run_arvo() {
	: > "$tmp/a.eyes"
	for i in $(seq "$RUNS"); do
		t0=$(now)
		"$ARVO" -q --stats --max-objects 2000000 --rays 0 --threads "$THREADS" --spp 1 --width "$W" --height "$H" \
			-D N="$2" -o "$tmp/a.png" "$1" 2> "$tmp/a.log"
		elapsed "$t0" "$(now)"; echo
		stat_arvo "eye pass" >> "$tmp/a.eyes"
	done | median
	median < "$tmp/a.eyes" > "$tmp/a.eye"
}

# run_pov SCENE N: the same for POV-Ray; median trace time in $tmp/p.trace,
# the last statistics in $tmp/p.log.
run_pov() {
	: > "$tmp/p.traces"
	for i in $(seq "$RUNS"); do
		t0=$(now)
		(cd "$tmp" && "$POVRAY" +I"$1" +O"$tmp/p.png" +FN +W"$W" +H"$H" -A -D +WT"$THREADS" \
			Declare=N="$2" > /dev/null 2> "$tmp/p.log")
		elapsed "$t0" "$(now)"; echo
		pov_trace >> "$tmp/p.traces"
	done | median
	median < "$tmp/p.traces" > "$tmp/p.trace"
}

stat_arvo() { awk -v k="$1" 'index($0, k) { for (i = 1; i <= NF; i++) if ($i ~ /^[0-9.]+$/) { print $i; exit } }' "$tmp/a.log"; }
pov_rays() { awk '/^Rays:/ { print $2; exit }' "$tmp/p.log"; }
pov_trace() { awk -F'[()]' '/Trace Time:/ { split($2, a, " "); print a[1]; exit }' "$tmp/p.log"; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (a == "" || b == "" || b + 0 == 0) print ""; else printf "%.2f", a / b }'; }
per_core() { awk -v r="$1" -v t="$2" -v n="$THREADS" 'BEGIN { if (r == "" || t == "" || t + 0 == 0) print ""; else printf "%.0f", r / t / n }'; }

# bench NAME SCENE N POV: one CSV row (POV-Ray too when POV is 1).
bench() {
	a=$(run_arvo "$here/$2.scn" "$3")
	ar=$(stat_arvo "rays traced"); ae=$(cat "$tmp/a.eye")
	p= pr= pt=
	if [ "$have_pov" = 1 ] && [ "$4" = 1 ]; then
		p=$(run_pov "$here/$2.pov" "$3"); pr=$(pov_rays); pt=$(cat "$tmp/p.trace")
	fi
	echo "$1,$3,$a,$p,$(ratio "$p" "$a"),$(ratio "$pt" "$ae"),$ar,$ae,$(per_core "$ar" "$ae"),$pr,$pt,$(per_core "$pr" "$pt")" >> "$res/eye.csv"
	tail -1 "$res/eye.csv"
}

# growth CSV: how arvo's wall and eye-pass times grow with the sphere count.
growth() {
	awk -F, '$1 == "spheres" { if (!f) { f = $3; e = $8; fn = $2 } l = $3; le = $8; ln = $2 }
		END { if (f) printf "arvo: %d -> %d spheres (x%d): wall %.3f -> %.3f s (x%.2f), eye pass %.3f -> %.3f s (x%.2f)\n",
			fn, ln, ln / fn, f, l, l / f, e, le, le / e }' "$1"
}

if [ "${PLOT_ONLY:-0}" != 1 ]; then
echo "scene,objects,arvo_s,povray_s,ratio,trace_ratio,arvo_rays,arvo_eye_s,arvo_rays_per_s_core,povray_rays,povray_trace_s,povray_rays_per_s_core" > "$res/eye.csv"
head -1 "$res/eye.csv"
bench prims prims 8 1
for n in $SIZES; do
	pov=0
	for m in $POV_SIZES; do [ "$m" = "$n" ] && pov=1; done
	bench spheres spheres "$n" $pov
done

{
	echo "bench/eye: ${W}x${H}, no antialiasing, $THREADS threads, median of $RUNS"
	echo "arvo: $("$ARVO" --version)   povray: $([ $have_pov = 1 ] && "$POVRAY" --version 2>&1 | grep -m1 "POV-Ray" || echo none)"
	echo "cpu: $(awk -F': ' '/model name/ { print $2; exit }' /proc/cpuinfo), $(nproc) online"
	echo "load average at the end: $(cut -d" " -f1-3 /proc/loadavg) (other work on the machine inflates times)"
	column -s, -t < "$res/eye.csv"
	growth "$res/eye.csv"
} > "$res/eye.txt"
fi
cat "$res/eye.txt"

if command -v gnuplot > /dev/null 2>&1; then
	awk -F, -v OFS=' ' '$1 == "spheres" { $1 = $1; for (i = 1; i <= NF; i++) if ($i == "") $i = "?"; print }' \
		"$res/eye.csv" > "$tmp/sph.dat"
	gnuplot <<GP
set terminal pngcairo size 800,500
set output "$res/eye-scaling.png"
set title "bench/eye: N spheres, ${W}x${H}, $THREADS threads (median of $RUNS)"
set logscale xy
set xlabel "spheres"
set ylabel "seconds"
set key left top
set datafile missing "?"
plot "$tmp/sph.dat" using 2:3 with linespoints title "arvo wall", \
     "$tmp/sph.dat" using 2:8 with linespoints title "arvo eye pass", \
     "$tmp/sph.dat" using 2:4 with linespoints title "POV-Ray wall", \
     "$tmp/sph.dat" using 2:11 with linespoints title "POV-Ray trace"
GP
fi
