#!/bin/sh
# SPDX-License-Identifier: MIT
# bench/speed/base.sh: this arvo against an earlier build of it, run by
# turns on the same machine the same day, so a change reads as a ratio that
# a slow day does not move (this machine's speed drifts by a third from day
# to day; run.sh's figures are absolute).
#
#   ARVO=$PWD/arvo ARVO_BASE=/path/to/older/arvo sh bench/speed/base.sh
#
# ARVO_BASE is required (build it from an older commit: git worktree add
# /tmp/old REV && make -C /tmp/old); BASE_LABEL names it in base.txt (say,
# the commit; not a path), NEW_LABEL the new one (default: this tree's
# commit, read at the start). RUNS (default 5) runs of each binary,
# alternating; every figure is a median. THREADS (default 2) as run.sh.
# Rows (the same commands as run.sh's):
#   eye spheres|grid N    eye-pass seconds (--stats), 640x480, N = 100k, 1M
#   eye prims             the same on bench/eye/prims.scn
#   light T thread(s)     light-pass seconds, tests/accuracy/sphere.scn,
#                         --method point, 1M rays, T = 1 and 2
#   shafts B T thread(s)  the same with light shafts (the default method)
#   shafts A, shafts C    the same on tests/accuracy/mirror.scn and slab.scn,
#                         $THREADS threads
#   demo light pass       light-pass seconds of stdlib-scenes/demo.scn (make
#                         demo's scene, its own settings)
#   demo peak MiB         its peak memory (--stats); speedup: base / new
#   loop1m                wall seconds of bench/frontend/loop1m.scn, 1x1
# Writes bench/results/base.csv (name,new,base,speedup) and base.txt;
# speedup = base / new (> 1: the new build is faster).
set -eu

ARVO=${ARVO:-./arvo}
: "${ARVO_BASE:?set ARVO_BASE to the arvo binary to compare against}"
RUNS=${RUNS:-5} THREADS=${THREADS:-2}
here=$(cd "$(dirname "$0")" && pwd)
root=$here/../..
res=$here/../results
mkdir -p "$res"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-bench-base.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
# a binary copied out of its tree finds the standard library here
ARVO_DATA_DIR=${ARVO_DATA_DIR:-$root/stdlib-scenes}
export ARVO_DATA_DIR
csv=$res/base.csv
# the tree's commit, read before this script writes its results into it
# (NEW_LABEL overrides: when ARVO is not this tree's build)
new_label=${NEW_LABEL:-$(git -C "$root" describe --always --dirty 2> /dev/null || echo "this tree")}

median() { sort -g | awk '{ v[NR] = $1 } END { if (NR) print v[int((NR + 1) / 2)] }'; }
stat_of() { awk -v k="$1" 'index($0, k) { for (i = 1; i <= NF; i++) if ($i ~ /^[0-9.]+$/) { print $i; exit } }' "$2"; }

# one BIN KIND ARGS...: the figure of one run (KIND: the --stats line to
# read, or "wall" for /usr/bin/time's)
one() {
	bin=$1 kind=$2; shift 2
	if [ "$kind" = wall ]; then
		/usr/bin/time -f "%e" -o "$tmp/t" "$bin" "$@" > /dev/null 2>&1
		cat "$tmp/t"
	else
		"$bin" --stats "$@" 2> "$tmp/log" > /dev/null
		stat_of "$kind" "$tmp/log"
	fi
}

# pair NAME KIND ARGS...: RUNS runs of each binary by turns; a row
pair() {
	name=$1 kind=$2; shift 2
	: > "$tmp/new"; : > "$tmp/base"
	for i in $(seq "$RUNS"); do
		one "$ARVO" "$kind" "$@" >> "$tmp/new"
		one "$ARVO_BASE" "$kind" "$@" >> "$tmp/base"
	done
	n=$(median < "$tmp/new") b=$(median < "$tmp/base")
	s=$(awk -v n="$n" -v b="$b" 'BEGIN { if (n + 0 > 0) printf "%.2f", b / n }')
	echo "$name,$n,$b,$s" >> "$csv"
	tail -1 "$csv"
}

echo "name,new,base,speedup" > "$csv"
eye="-q --max-objects 2000000 --rays 0 --threads $THREADS --spp 1 --width 640 --height 480 -o $tmp/a.png"
for sc in spheres grid; do
	for n in 100000 1000000; do
		# shellcheck disable=SC2086
		pair "eye $sc $n" "eye pass" $eye -D N="$n" "$root/bench/eye/$sc.scn"
	done
done
# shellcheck disable=SC2086
pair "eye prims" "eye pass" $eye "$root/bench/eye/prims.scn"
for t in 1 2; do
	pair "light $t thread(s)" "light pass" -q --method point --rays 1000000 --threads "$t" --width 64 \
		--height 64 -o "$tmp/b.exr" "$root/tests/accuracy/sphere.scn"
done
for t in 1 2; do
	pair "shafts B $t thread(s)" "light pass" -q --rays 1000000 --threads "$t" --width 64 --height 64 \
		-o "$tmp/b.exr" "$root/tests/accuracy/sphere.scn"
done
pair "shafts A" "light pass" -q --rays 1000000 --threads "$THREADS" --width 64 --height 64 -o "$tmp/b.exr" \
	"$root/tests/accuracy/mirror.scn"
pair "shafts C" "light pass" -q --rays 1000000 --threads "$THREADS" --width 64 --height 64 -o "$tmp/b.exr" \
	"$root/tests/accuracy/slab.scn"
pair "demo light pass" "light pass" -q --threads "$THREADS" -o "$tmp/d.exr" "$root/stdlib-scenes/demo.scn"
pair "demo peak MiB" "peak memory" -q --threads "$THREADS" -o "$tmp/d.exr" "$root/stdlib-scenes/demo.scn"
pair "loop1m" wall -q --max-objects 2000000 --rays 0 --threads "$THREADS" --width 1 --height 1 \
	-o "$tmp/f.exr" -D N=1000000 "$root/bench/frontend/loop1m.scn"

{
	echo "bench/speed/base.sh: medians of $RUNS runs by turns, $THREADS threads"
	echo "new:  $new_label ($("$ARVO" --version))"
	echo "base: ${BASE_LABEL:-ARVO_BASE} ($("$ARVO_BASE" --version))"
	echo "load average at the end: $(cut -d" " -f1-3 /proc/loadavg)"
	column -s, -t < "$csv"
} > "$res/base.txt"
cat "$res/base.txt"
