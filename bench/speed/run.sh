#!/bin/sh
# SPDX-License-Identifier: MIT
# bench/speed/run.sh: issue 13's speed targets, arvo against POV-Ray 3.7 in
# one script (same scenes, sizes and threads, antialiasing off: -A).
#
#   ARVO=$PWD/arvo sh bench/speed/run.sh          (about 5 minutes idle)
#
# Uses ${ARVO:-./arvo} and ${POVRAY:-povray}; builds nothing. Every figure is
# the median of $RUNS runs (default 3). The machine may be shared: compare
# the ratios, which come from runs made side by side, and the CPU times.
#   eye       each bench/eye scene in $SCENES with N in $SIZES, ${W}x${H},
#             $THREADS threads: spheres.scn (.pov), N spheres at random in a
#             box, and grid.scn (.pov), N spheres on a cubic grid in the same
#             box (the layout issue 13's Embree figures were measured on);
#             and prims.scn (.pov), seven primitives and a plane with
#             reflection and refraction (no N; its objects column says 8); arvo's eye-pass time (--stats) against POV-Ray's
#             "Trace Time" (no start-up, parsing or bounding); ratio =
#             povray / arvo (target >= 3); and arvo's rays/s/core (target
#             >= 5e6 at 100k spheres); eye_cpu: the same in CPU seconds
#             (POV-Ray's trace CPU-seconds; arvo's eye-pass CPU seconds as
#             --stats prints them), steadier than wall time on a busy machine
#             eye_rate_cpu: rays per CPU second of the eye pass (a core's
#             rate without the wall clock of a shared machine)
#   scaling   arvo's eye pass at the largest N over the smallest, per scene
#             (target <= 3)
#   threads   eye pass (spheres, N = 100000, ${TW}x${TH}) and light pass (scene B,
#             tests/accuracy/sphere.scn, --method point, 1M rays) on 1 and 2
#             threads, run by turns: time(1) / time(2) (target >= 1.85); and the same
#             ratio for bench/speed/ceiling.c, a perfectly parallel program
#             (arithmetic alone; fresh memory written; reads that wait on
#             memory, a random walk through 32 MiB), the most this
#             machine's two cores give (no target: the yardstick)
#   light     light-pass segments/s/core on 2 threads, 1M rays, isolated-
#             sample rule on, deposits included (target >= 1e7); and the
#             same scene with light shafts, the default method (no target:
#             its footprints cost more than its tracing): seconds and
#             segments/s/core on 2 threads, and 1 -> 2 threads by turns
#   frontend  bench/frontend/loop1m.scn (1M spheres) evaluated and bounded
#             (arvo: a 1x1 render without light pass; POV-Ray: its parse,
#             which bounds too): wall s, CPU s (user + sys) and peak MB
#             (/usr/bin/time); targets <= 1.5 s and <= 300 MB
# Writes bench/results/speed.csv (section,name,objects,threads,arvo,povray,
# ratio,unit,target,met), bench/results/speed.txt and, with gnuplot,
# docs/speed.png (eye pass against POV-Ray's trace, by sphere count).
set -eu

ARVO=${ARVO:-./arvo}
POVRAY=${POVRAY:-povray}
W=${W:-640} H=${H:-480} THREADS=${THREADS:-2} RUNS=${RUNS:-3}
TW=${TW:-1280} TH=${TH:-960} # the thread-scaling row: 4x the pixels, so a run
                             # lasts about a second, not a noisy 0.2 s
SIZES=${SIZES:-1000 10000 100000 1000000}
SCENES=${SCENES:-spheres grid}
FRONT_N=${FRONT_N:-1000000}
here=$(cd "$(dirname "$0")" && pwd)
root=$here/../..
res=$here/../results
mkdir -p "$res"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-bench-speed.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
have_pov=0
command -v "$POVRAY" > /dev/null 2>&1 && have_pov=1
csv=$res/speed.csv

median() { sort -g | awk '{ v[NR] = $1 } END { if (NR) print v[int((NR + 1) / 2)] }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (a == "" || b == "" || b + 0 == 0) print ""; else printf "%.2f", a / b }'; }
# met VALUE OP TARGET: yes/no (empty when the value is)
met() { awk -v v="$1" -v op="$2" -v t="$3" 'BEGIN { if (v == "") print ""; else if (op == ">=") print (v + 0 >= t + 0 ? "yes" : "no"); else print (v + 0 <= t + 0 ? "yes" : "no") }'; }
# row SECTION NAME OBJECTS THREADS ARVO POVRAY RATIO UNIT TARGET MET: a line
# of the CSV; stops the bench when arvo's figure is missing (a run failed:
# its messages are shown), rather than write an empty or NaN row as met
row() {
	if ! echo "$5" | grep -Eq '^[0-9]+([.][0-9]+)?$'; then
		echo "bench/speed: no figure for $1 $2 $3 (\"$5\"): an arvo run failed?" >&2
		cat "$tmp/a.log" "$tmp/l.log" 2> /dev/null | tail -5 >&2
		exit 1
	fi
	echo "$1,$2,$3,$4,$5,$6,$7,$8,$9,${10}" >> "$csv"; tail -1 "$csv"
}
stat_of() { awk -v k="$1" 'index($0, k) { for (i = 1; i <= NF; i++) if ($i ~ /^[0-9.]+$/) { print $i; exit } }' "$2"; }

# arvo_eye N THREADS [W H [SCENE]]: median eye-pass seconds; rays of the last run in
# $tmp/rays; the eye pass's median CPU seconds (all threads, as --stats
# reports them) in $tmp/acpu
arvo_eye() {
	ew=${3:-$W} eh=${4:-$H} es=${5:-spheres}
	: > "$tmp/ac"
	for i in $(seq "$RUNS"); do
		"$ARVO" -q --stats --max-objects 2000000 --rays 0 --threads "$2" \
			--spp 1 --width "$ew" --height "$eh" -D N="$1" -o "$tmp/a.png" "$root/bench/eye/$es.scn" 2> "$tmp/a.log"
		awk '/eye pass/ { for (i = 1; i <= NF; i++) if ($i == "CPU)") print $(i - 2) }' "$tmp/a.log" >> "$tmp/ac"
		stat_of "eye pass" "$tmp/a.log"
	done | median
	stat_of "rays traced" "$tmp/a.log" > "$tmp/rays"
	median < "$tmp/ac" > "$tmp/acpu"
}

# pov_trace N [SCENE]: median "Trace Time" seconds; its median CPU seconds in $tmp/pcpu
pov_trace() {
	: > "$tmp/pc"
	for i in $(seq "$RUNS"); do
		(cd "$tmp" && "$POVRAY" +I"$root/bench/eye/${2:-spheres}.pov" +O"$tmp/p.png" +FN +W"$W" +H"$H" -A -D \
			+WT"$THREADS" Declare=N="$1" > /dev/null 2> "$tmp/p.log")
		awk '/Trace Time:/ { getline; for (i = 1; i <= NF; i++) if ($i == "CPU-seconds") print $(i - 1); exit }' \
			"$tmp/p.log" >> "$tmp/pc"
		awk -F'[()]' '/Trace Time:/ { split($2, a, " "); print a[1]; exit }' "$tmp/p.log"
	done | median
	median < "$tmp/pc" > "$tmp/pcpu"
}

# arvo_light THREADS [METHOD]: median light-pass seconds; segments in $tmp/segs
arvo_light() {
	for i in $(seq "$RUNS"); do
		"$ARVO" -q --stats --method "${2:-point}" --rays 1000000 --threads "$1" --width 64 --height 64 \
			-o "$tmp/b.exr" "$root/tests/accuracy/sphere.scn" 2> "$tmp/l.log"
		stat_of "light pass" "$tmp/l.log"
	done | median
	awk '/light pass/ { for (i = 1; i <= NF; i++) if ($i ~ /^segments/) print $(i - 1) }' "$tmp/l.log" > "$tmp/segs"
}

# timed FILE CMD...: runs CMD under /usr/bin/time; "wall cpu MB" to FILE
timed() {
	f=$1; shift
	/usr/bin/time -f "%e %U %S %M" -o "$tmp/time" "$@" > /dev/null 2>&1 || true
	awk '{ printf "%s %.2f %.0f\n", $1, $2 + $3, $4 / 1024 }' "$tmp/time" >> "$f"
}
col_median() { awk -v c="$2" '{ print $c }' "$1" | median; }

echo "section,name,objects,threads,arvo,povray,ratio,unit,target,met" > "$csv"

# ---- eye pass against POV-Ray's trace time ----
for sc in $SCENES; do
first= last= first_c= last_c=
for n in $SIZES; do
	a=$(arvo_eye "$n" "$THREADS" "$W" "$H" "$sc"); rays=$(cat "$tmp/rays")
	p=
	[ "$have_pov" = 1 ] && p=$(pov_trace "$n" "$sc")
	r=$(ratio "$p" "$a")
	row eye "$sc" "$n" "$THREADS" "$a" "$p" "$r" s ">=3x" "$(met "$r" ">=" 3)"
	ac=$(cat "$tmp/acpu") pc=
	[ "$have_pov" = 1 ] && pc=$(cat "$tmp/pcpu")
	r=$(ratio "$pc" "$ac")
	row eye_cpu "$sc" "$n" "$THREADS" "$ac" "$pc" "$r" "CPU s" ">=3x" "$(met "$r" ">=" 3)"
	rate=$(awk -v r="$rays" -v t="$a" -v n="$THREADS" 'BEGIN { printf "%.0f", r / t / n }')
	crate=$(awk -v r="$rays" -v t="$ac" 'BEGIN { if (t > 0) printf "%.0f", r / t }')
	if [ "$n" = 100000 ]; then
		row eye_rate "$sc" "$n" "$THREADS" "$rate" "" "" "rays/s/core" ">=5e6" "$(met "$rate" ">=" 5000000)"
		row eye_rate_cpu "$sc" "$n" "$THREADS" "$crate" "" "" "rays/CPU s" ">=5e6" "$(met "$crate" ">=" 5000000)"
	else
		row eye_rate "$sc" "$n" "$THREADS" "$rate" "" "" "rays/s/core" "" ""
		row eye_rate_cpu "$sc" "$n" "$THREADS" "$crate" "" "" "rays/CPU s" "" ""
	fi
	[ -n "$first" ] || first=$a first_c=$ac
	last=$a last_c=$ac
done
g=$(ratio "$last" "$first")
row scaling "$sc $(echo $SIZES | awk '{ print $1 " -> " $NF }')" "" "$THREADS" "$g" "" "" "x" "<=3x" "$(met "$g" "<=" 3)"
g=$(ratio "$last_c" "$first_c")
row scaling_cpu "$sc $(echo $SIZES | awk '{ print $1 " -> " $NF }')" "" "$THREADS" "$g" "" "" "x (CPU)" "<=3x" "$(met "$g" "<=" 3)"
done

a=$(arvo_eye 0 "$THREADS" "$W" "$H" prims)
p=
[ "$have_pov" = 1 ] && p=$(pov_trace 0 prims)
r=$(ratio "$p" "$a")
row eye prims 8 "$THREADS" "$a" "$p" "$r" s ">=3x" "$(met "$r" ">=" 3)"
ac=$(cat "$tmp/acpu") pc=
[ "$have_pov" = 1 ] && pc=$(cat "$tmp/pcpu")
r=$(ratio "$pc" "$ac")
row eye_cpu prims 8 "$THREADS" "$ac" "$pc" "$r" "CPU s" ">=3x" "$(met "$r" ">=" 3)"

# ---- 1 -> 2 threads ----
# one run on 1 thread, then one on 2, by turns: a drift of this machine's
# speed (a fifth within minutes) then moves both sides alike, where all the
# runs on 1 thread and then all on 2 put the drift into the ratio
runs=$RUNS RUNS=1
: > "$tmp/e1"; : > "$tmp/e2"; : > "$tmp/l1"; : > "$tmp/l2"; : > "$tmp/s1"; : > "$tmp/s2"
for i in $(seq "$runs"); do
	arvo_eye 100000 1 "$TW" "$TH" >> "$tmp/e1"; arvo_eye 100000 2 "$TW" "$TH" >> "$tmp/e2"
done
for i in $(seq "$runs"); do
	arvo_light 1 >> "$tmp/l1"; arvo_light 2 >> "$tmp/l2"
done
cp "$tmp/segs" "$tmp/psegs"
for i in $(seq "$runs"); do
	arvo_light 1 shaft >> "$tmp/s1"; arvo_light 2 shaft >> "$tmp/s2"
done
cp "$tmp/segs" "$tmp/ssegs"
RUNS=$runs
e1=$(median < "$tmp/e1"); e2=$(median < "$tmp/e2"); r=$(ratio "$e1" "$e2")
row threads "eye pass" 100000 "1->2" "$r" "" "" "x" ">=1.85x" "$(met "$r" ">=" 1.85)"
l1=$(median < "$tmp/l1"); l2=$(median < "$tmp/l2"); segs=$(cat "$tmp/psegs"); r=$(ratio "$l1" "$l2")
row threads "light pass" 1000000 "1->2" "$r" "" "" "x" ">=1.85x" "$(met "$r" ">=" 1.85)"
s1=$(median < "$tmp/s1"); s2=$(median < "$tmp/s2"); ssegs=$(cat "$tmp/ssegs")
row threads "light pass (shafts)" 1000000 "1->2" "$(ratio "$s1" "$s2")" "" "" "x" "" ""
# the machine's own ceiling for the two rows above: a perfectly parallel
# program (ceiling.c) on 1 and 2 threads; no target, it is the yardstick
if cc -std=c11 -O2 -pthread -o "$tmp/ceiling" "$here/ceiling.c" 2> /dev/null; then
	for w in compute memory chase; do
		c1=$(for i in $(seq "$RUNS"); do "$tmp/ceiling" "$w" 1; done | median)
		c2=$(for i in $(seq "$RUNS"); do "$tmp/ceiling" "$w" 2; done | median)
		row threads "machine ceiling ($w)" "" "1->2" "$(ratio "$c1" "$c2")" "" "" "x" "" ""
	done
fi
rate=$(awk -v s="$segs" -v t="$l2" 'BEGIN { printf "%.0f", s / t / 2 }')
row light "segments/s/core" 1000000 2 "$rate" "" "" "segments/s/core" ">=1e7" "$(met "$rate" ">=" 10000000)"
row light "shafts seconds" 1000000 2 "$s2" "" "" "s" "" ""
row light "shafts segments/s/core" 1000000 2 "$(awk -v s="$ssegs" -v t="$s2" 'BEGIN { printf "%.0f", s / t / 2 }')" "" "" \
	"segments/s/core" "" ""

# ---- front end: 1M spheres evaluated and bounded ----
: > "$tmp/fa"; : > "$tmp/fp"
for i in $(seq "$RUNS"); do
	timed "$tmp/fa" "$ARVO" -q --max-objects 2000000 --rays 0 --threads "$THREADS" --width 1 --height 1 -o "$tmp/f.exr" \
		-D N="$FRONT_N" "$root/bench/frontend/loop1m.scn"
	[ "$have_pov" = 1 ] && [ "$i" = 1 ] &&
		(cd "$tmp" && timed "$tmp/fp" "$POVRAY" +I"$root/bench/frontend/loop1m.scn" +O"$tmp/f.png" -D +W1 +H1 -GA +WT1 Declare=N="$FRONT_N")
done
aw=$(col_median "$tmp/fa" 1) ac=$(col_median "$tmp/fa" 2) am=$(col_median "$tmp/fa" 3)
pw=$(col_median "$tmp/fp" 1) pc=$(col_median "$tmp/fp" 2) pm=$(col_median "$tmp/fp" 3)
row frontend "loop1m wall" "$FRONT_N" "$THREADS" "$aw" "$pw" "$(ratio "$pw" "$aw")" s "<=1.5" "$(met "$aw" "<=" 1.5)"
row frontend "loop1m cpu" "$FRONT_N" "$THREADS" "$ac" "$pc" "$(ratio "$pc" "$ac")" "s (user+sys)" "<=1.5" "$(met "$ac" "<=" 1.5)"
row frontend "loop1m memory" "$FRONT_N" "$THREADS" "$am" "$pm" "$(ratio "$pm" "$am")" MB "<=300" "$(met "$am" "<=" 300)"

{
	echo "bench/speed: ${W}x${H}, $THREADS threads, median of $RUNS (POV-Ray front end: 1 run)"
	echo "arvo: $("$ARVO" --version)   povray: $([ $have_pov = 1 ] && "$POVRAY" --version 2>&1 | grep -m1 "POV-Ray" || echo none)"
	echo "cpu: $(awk -F': ' '/model name/ { print $2; exit }' /proc/cpuinfo), $(nproc) online"
	echo "load average at the end: $(cut -d" " -f1-3 /proc/loadavg) (other work on the machine inflates times)"
	column -s, -t < "$csv"
} > "$res/speed.txt"
cat "$res/speed.txt"

if command -v gnuplot > /dev/null 2>&1; then
	for sc in $SCENES; do
		awk -F, -v sc="$sc" '$1 == "eye" && $2 == sc { print $3, $5, ($6 == "" ? "?" : $6) }' "$csv" > "$tmp/eye-$sc.dat"
	done
	gnuplot <<GP
set terminal pngcairo size 800,500
set output "$root/docs/speed.png"
set title "Eye pass, N spheres (bench/eye: $SCENES), ${W}x${H}, $THREADS threads (median of $RUNS)"
set logscale xy
set xlabel "spheres"
set ylabel "seconds"
set key left top
set datafile missing "?"
plot $(for sc in $SCENES; do printf '"%s" using 1:2 with linespoints title "arvo eye pass, %s", "%s" using 1:3 with linespoints title "POV-Ray trace time, %s", ' "$tmp/eye-$sc.dat" "$sc" "$tmp/eye-$sc.dat" "$sc"; done | sed 's/, $//')
GP
fi
