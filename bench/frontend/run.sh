#!/bin/sh
# SPDX-License-Identifier: MIT
# bench/frontend/run.sh: front-end benchmark, arvo against POV-Ray 3.7.
#
#   ARVO=$PWD/build/bench/arvo sh bench/frontend/run.sh
#
# Builds nothing: uses ${ARVO:-./arvo} (relative to the current directory) and
# ${POVRAY:-povray} (its columns are left empty when it is not installed).
# Scenes (both valid POV-Ray 3.7 SDL, read unchanged by both programs):
#   loop1m.scn     nested #while loops making N spheres, N in $SIZES
#   includes.scn   $REPS passes re-including a stdlib-like set + part.inc,
#                  then a 20,000-declaration file (inc/, see gen-includes.sh)
# Each measurement is the median of $RUNS runs (default 3), wall clock.
#   arvo_s          wall time of `arvo --check` (lex + parse + evaluate; no
#                   render), start-up included (about 2 ms)
#   povray_parse_s  the "Parse Time" POV-Ray prints in its statistics for
#                   `povray +Iscene -D -F +W1 +H1 +WT1 Declare=...` (no display,
#                   no output file, 1x1 image, one thread). Not -GA: it
#                   silences the statistics stream.
#   povray_wall_s   wall time of that whole povray run: start-up (~0.7 s),
#                   parse, bounding (BVH build: 3 s at 1M), 1-pixel render
#   ratio           povray_parse_s / arvo_s (above 1: arvo is faster)
#   tokens_per_s    lexer throughput: tokens printed by `arvo --dump-tokens`
#                   (one line per token, the EOF line not counted) over the
#                   wall time of `--dump-tokens FILE >/dev/null`, summed over
#                   every distinct file of the scene (for includes.scn: the
#                   scene and the six include files once each, 335k tokens).
#                   --dump-tokens lexes one file and follows no #include, so
#                   for loop1m.scn (~250 tokens) this is start-up dominated.
#   tokens          tokens the front end lexes in the --check run: the static
#                   count for loop1m.scn (its loops re-run an AST, not
#                   tokens); for includes.scn the scene + REPS x each file
#                   included in the loop + decls.inc (arvo re-reads and
#                   re-parses a file at every #include)
#   arvo_peak_kb, povray_peak_kb   peak RSS from /usr/bin/time (empty without)
# Writes bench/results/frontend.csv, frontend.txt (table and environment) and,
# with gnuplot, frontend.png (time against object count, loop1m.scn).
set -eu

SIZES=${SIZES:-10000 100000 1000000}
REPS=${REPS:-200}
RUNS=${RUNS:-3}
POVRAY=${POVRAY:-povray}
ARVO=${ARVO:-./arvo}

case $ARVO in
/*) ;;
*/*) ARVO=$(cd "$(dirname "$ARVO")" && pwd)/$(basename "$ARVO") ;;
*) ARVO=$(command -v "$ARVO" || echo "$ARVO") ;;
esac
[ -x "$ARVO" ] || { echo "run.sh: no arvo at '$ARVO' (set ARVO=...)" >&2; exit 1; }

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
results=$root/bench/results
mkdir -p "$results"
[ -f "$here/inc/decls.inc" ] || sh "$here/gen-includes.sh"
have_pov=0
command -v "$POVRAY" >/dev/null 2>&1 && have_pov=1
TIMEV=
[ -x /usr/bin/time ] && TIMEV=/usr/bin/time
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM

now() { date +%s.%N; }
sub() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.4f", b - a }'; }
median() { sort -g | awk '{ v[NR] = $1 } END { if (NR) print v[int((NR + 1) / 2)] }'; }

# run_arvo SCENE ARGS... : median wall and peak RSS of `arvo --check`
run_arvo() {
	: >"$tmp/t"; : >"$tmp/m"
	i=0
	while [ $i -lt "$RUNS" ]; do
		t0=$(now)
		if [ -n "$TIMEV" ]; then
			$TIMEV -f %M -o "$tmp/mem" "$ARVO" --check --max-objects 2000000 "$@" >/dev/null 2>"$tmp/err" || { cat "$tmp/err" >&2; return 1; }
		else
			"$ARVO" --check --max-objects 2000000 "$@" >/dev/null 2>"$tmp/err" || { cat "$tmp/err" >&2; return 1; }
		fi
		t1=$(now)
		sub "$t0" "$t1" >>"$tmp/t"; echo >>"$tmp/t"
		[ -n "$TIMEV" ] && tail -n 1 "$tmp/mem" >>"$tmp/m"
		i=$((i + 1))
	done
	arvo_s=$(median <"$tmp/t")
	arvo_kb=$(median <"$tmp/m")
}

# run_pov SCENE ARGS... : median parse time, wall time and peak RSS of povray
run_pov() {
	pov_parse=; pov_wall=; pov_kb=
	[ $have_pov = 1 ] || return 0
	: >"$tmp/pt"; : >"$tmp/pw"; : >"$tmp/pm"
	i=0
	while [ $i -lt "$RUNS" ]; do
		t0=$(now)
		if [ -n "$TIMEV" ]; then
			(cd "$here" && $TIMEV -f %M -o "$tmp/mem" "$POVRAY" "$@" >/dev/null 2>"$tmp/pov") || { tail -5 "$tmp/pov" >&2; return 0; }
		else
			(cd "$here" && "$POVRAY" "$@" >/dev/null 2>"$tmp/pov") || { tail -5 "$tmp/pov" >&2; return 0; }
		fi
		t1=$(now)
		sub "$t0" "$t1" >>"$tmp/pw"; echo >>"$tmp/pw"
		sed -n 's/.*Parse Time:.*(\([0-9.]*\) seconds).*/\1/p' "$tmp/pov" >>"$tmp/pt"
		[ -n "$TIMEV" ] && tail -n 1 "$tmp/mem" >>"$tmp/pm"
		i=$((i + 1))
	done
	pov_parse=$(median <"$tmp/pt")
	pov_wall=$(median <"$tmp/pw")
	pov_kb=$(median <"$tmp/pm")
}

# lex_rate FILE... : tokens (EOF excluded) and the median summed time of
# `arvo --dump-tokens FILE`, one process per file
lex_rate() {
	ntok=0
	for f in "$@"; do
		c=$("$ARVO" --dump-tokens "$f" | wc -l)
		ntok=$((ntok + c - 1))
	done
	: >"$tmp/lt"
	i=0
	while [ $i -lt "$RUNS" ]; do
		t0=$(now)
		for f in "$@"; do "$ARVO" --dump-tokens "$f" >/dev/null; done
		t1=$(now)
		sub "$t0" "$t1" >>"$tmp/lt"; echo >>"$tmp/lt"
		i=$((i + 1))
	done
	lex_s=$(median <"$tmp/lt")
	tok_per_s=$(awk -v n=$ntok -v t="$lex_s" 'BEGIN { printf "%.0f", n / t }')
}

toks() { c=$("$ARVO" --dump-tokens "$1" | wc -l); echo $((c - 1)); }
ratio() { [ -n "$1" ] && awk -v p="$1" -v a="$2" 'BEGIN { printf "%.2f", p / a }' || true; }

csv=$results/frontend.csv
txt=$results/frontend.txt
echo "scene,n,arvo_s,povray_parse_s,povray_wall_s,ratio,tokens_per_s,tokens,arvo_peak_kb,povray_peak_kb" >"$csv"
{
	echo "arvo front-end benchmark ($(date -u +%Y-%m-%dT%H:%MZ), median of $RUNS)"
	echo "host: load $(cut -d" " -f1-3 /proc/loadavg) at start, $(nproc) CPUs, $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -n 1)"
	echo "arvo: ${ARVO#"$root"/} (tree at $(cd "$root" && git describe --always --dirty 2>/dev/null || echo '?'))"
	[ $have_pov = 1 ] && echo "povray: $("$POVRAY" --version 2>&1 | sed -n 's/^POV-Ray \([0-9][^ ]*\).*/\1/p' | head -n 1)"
	printf '%-9s %8s %9s %12s %11s %7s %12s %9s %9s %9s\n' scene n arvo_s pov_parse_s pov_wall_s ratio tokens/s tokens arvo_MB pov_MB
} | tee "$txt"

row() { # scene n
	r=$(ratio "$pov_parse" "$arvo_s")
	echo "$1,$2,$arvo_s,$pov_parse,$pov_wall,$r,$tok_per_s,$tokens,$arvo_kb,$pov_kb" >>"$csv"
	am=$(awk -v k="$arvo_kb" 'BEGIN { if (k != "") printf "%.0f", k / 1024 }')
	pm=$(awk -v k="$pov_kb" 'BEGIN { if (k != "") printf "%.0f", k / 1024 }')
	printf '%-9s %8s %9s %12s %11s %7s %12s %9s %9s %9s\n' "$1" "$2" "$arvo_s" "${pov_parse:--}" \
		"${pov_wall:--}" "${r:--}" "$tok_per_s" "$tokens" "${am:--}" "${pm:--}" | tee -a "$txt"
}

# ---- loop1m.scn -------------------------------------------------------------
loop=$here/loop1m.scn
lex_rate "$loop"
tokens=$ntok
for n in $SIZES; do
	run_arvo -D N=$n "$loop"
	run_pov +I"$loop" -D -F +W1 +H1 +WT1 Declare=N=$n
	row loop1m "$n"
done

# ---- includes.scn -----------------------------------------------------------
inc=$here/inc
scn=$here/includes.scn
lex_rate "$scn" "$inc"/std_math.inc "$inc"/std_colors.inc "$inc"/std_finish.inc \
	"$inc"/std_shapes.inc "$inc"/part.inc "$inc"/decls.inc
per_pass=0
for f in std_math std_colors std_finish std_shapes part; do
	per_pass=$((per_pass + $(toks "$inc/$f.inc")))
done
tokens=$(($(toks "$scn") + REPS * per_pass + $(toks "$inc/decls.inc")))
run_arvo -I "$inc" -D Reps=$REPS "$scn"
run_pov +I"$scn" +L"$inc" -D -F +W1 +H1 +WT1 Declare=Reps=$REPS
row includes "$REPS"
awk -v n=$tokens -v t="$arvo_s" 'BEGIN { printf "includes.scn: %d tokens lexed, parsed and evaluated by arvo --check: %.2f M tokens/s end to end\n", n, n / t / 1e6 }' | tee -a "$txt"

# ---- chart --------------------------------------------------------------------
if command -v gnuplot >/dev/null 2>&1; then
	grep '^loop1m,' "$csv" | tr ',' ' ' >"$tmp/loop.dat"
	inc_line=$(grep '^includes,' "$csv" | awk -F, '{ printf "includes.scn (%s passes): arvo %s s, POV-Ray parse %s s", $2, $3, $4 }')
	gnuplot <<EOF
set terminal pngcairo size 900,600 font ",11"
set output "$results/frontend.png"
set title "Front end: nested #while loops making N spheres (loop1m.scn), median of $RUNS"
set xlabel "objects"
set ylabel "seconds"
set logscale xy
set grid
set key top left
set format x "%.0s%c"
set label 1 "$inc_line" at graph 0.02, graph 0.70
plot "$tmp/loop.dat" using 2:3 with linespoints lw 2 pt 7 title "arvo --check (wall)", \
     "$tmp/loop.dat" using 2:4 with linespoints lw 2 pt 5 title "POV-Ray 3.7 Parse Time", \
     "$tmp/loop.dat" using 2:5 with linespoints lw 2 pt 9 dt 2 title "POV-Ray 3.7 wall (start-up, parse, bounding, 1 px)"
EOF
	echo "wrote $csv, $txt, $results/frontend.png"
else
	echo "wrote $csv, $txt (no gnuplot: no chart)"
fi
