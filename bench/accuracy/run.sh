#!/bin/sh
# SPDX-License-Identifier: MIT
# bench/accuracy/run.sh: caustic error against time for every light-pass
# method of arvo and for POV-Ray 3.7's photons, on the three analytic
# references of tests/accuracy (A mirror, B glass sphere, C glass slab).
#
#   make bench-accuracy                 (or sh bench/accuracy/run.sh; ~15 min)
#
# arvo: accuracy.c (built here against $LIBARVO, default the libarvo.a of
# `make all`, build/release) runs lp_run once per call and times it alone; the error is the
# flux-weighted relative L1 of what the eye pass reads (every map level's
# node irradiance spread over its bilinear tent) against the exact binned
# flux: A 0.1 cells over x in [-3, 1], z in [-4, 4] without the column at the
# mirror's foot (x in [0.9, 1]: tents there reach under the mirror), column 5
# (Ebar_refl_R1) of A_grid_cellavg_0.1.csv; B 0.05 annuli to r = 3, column 3
# of B_profile_binned_0.05.csv; C the same, column 6 of
# C_profile_binned_0.05.csv. The renderer's settings (the isolated-sample rule
# on; B and C follow refraction only, as their references hold only
# twice-transmitted light). Series (the scene's `illum_map { cell 0.01 }`
# replaced, by sed, in a copy):
#   point-0.01  point-0.005   point deposits, fixed floor cell
#   point-0.01-kept           point-0.01 with the isolated-sample rule off
#                             (as bench/caustics measures it): what the rule
#                             costs at fixed cells
#   point-auto                point deposits, no illum_map (automatic cell)
#   shaft-auto  shaft-0.01    light shafts, automatic / fixed finest cell
#   tol-0.01                  the light pass's own accuracy target T (arvo
#                             --tolerance T: rounds of 4x more rays until its
#                             error estimate is at most T), shafts, the
#                             scene's cell 0.01, T in $TOLERANCES (budget
#                             column: T); the ladder stops before a target
#                             predicted to take over $TOL_MAXT s
#   tol-auto                  the same without illum_map, for T in $TOL_AUTO
#                             (none by default: the automatic cell refines
#                             with every round, so the estimate falls slowly;
#                             B at 0.005 took minutes and 2.4 GB of maps)
# each at the ray budgets $POINT_BUDGETS (point-0.005: $FINE_BUDGETS, -kept:
# $KEPT_BUDGETS) or $SHAFT_BUDGETS; a ladder stops before a rung predicted
# (time x ray ratio) to take more than $MAXT seconds a run, so a loaded
# machine drops the top rungs rather than run for an hour.
# POV-Ray: the same scenes (mirror.pov, slab.pov here, and
# bench/caustics/sphere.pov), an orthographic view straight down of the
# caustic alone, EXR (+FE), -A, +WT$THREADS, photons `count` in $POV_COUNTS,
# radius 0.05, jitter 0.4, gather 20, 100 (the ladder stops before a count
# predicted to take over $POV_MAXT s); povbin.c bins each image like the
# reference and scales it to the exact flux (POV-Ray's units differ). Its
# time is its median wall time minus the median wall time of the same render
# with photons off (Count=0: start-up, parse, eye pass).
# Every point is the median of $RUNS runs: times, and POV-Ray's L1 (its
# photons are jittered); arvo's maps are bit-identical from run to run, so
# its L1 is computed on the first run (accuracy.c --time-only for the rest).
# Writes bench/results/accuracy.csv, accuracy.txt and the chart
# docs/accuracy.svg, docs/accuracy.png (gnuplot). PLOT_ONLY=1 redoes the
# summary and chart from an existing accuracy.csv.
# Columns of accuracy.csv:
#   scene            A, B or C
#   method           a series above, or povray
#   budget           light rays asked for | tolerance target | photon count
#   time_s           median: lp_run | POV-Ray wall minus wall without photons
#   l1               median flux-weighted relative L1 (the metric)
#   map_bytes        memory the light pass's maps hold (arvo)
#   l1_nodes         node energies binned by node position (smeared by a cell)
#   l1_noise         what photon noise alone would give with that many
#                    box-binned rays (arvo's stratified rays can be below it)
#   flux_ratio       read flux / exact flux over the bins (arvo)
#   rays_shot        arvo: light rays traced | POV-Ray: photons shot
#   cell, levels     arvo: the floor map's finest cell, and its levels
#   time_min,time_max  fastest and slowest run (arvo; POV-Ray: wall)
#   tol_estimate     tolerance series: the pass's own error estimate at its stop
set -eu

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
res=$root/bench/results
docs=$root/docs
POVRAY=${POVRAY:-povray}
THREADS=${THREADS:-2} RUNS=${RUNS:-3} MAXT=${MAXT:-8} POV_MAXT=${POV_MAXT:-15}
SCENES=${SCENES:-A B C}
POINT_BUDGETS=${POINT_BUDGETS:-10000 30000 100000 300000 1000000 3000000 10000000}
SHAFT_BUDGETS=${SHAFT_BUDGETS:-10000 30000 100000 300000 1000000 3000000}
KEPT_BUDGETS=${KEPT_BUDGETS:-10000 30000 100000 300000 1000000}
FINE_BUDGETS=${FINE_BUDGETS:-10000 30000 100000 300000 1000000 3000000}
POV_COUNTS=${POV_COUNTS:-100000 300000 1000000 3000000 10000000 30000000}
TOLERANCES=${TOLERANCES:-0.02 0.01 0.005 0.002} TOL_MAXT=${TOL_MAXT:-12} TOL_AUTO=${TOL_AUTO:-}
TARGETS=${TARGETS:-0.02 0.01 0.005 0.001}
mkdir -p "$res" "$docs"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-bench-accuracy.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
csv=$res/accuracy.csv
ta=$root/tests/accuracy

median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
now() { date +%s.%N; }
# kv KEY FILE...: KEY's values (key=value pairs), one a line.
kv() { k=$1; shift; cat "$@" | tr ' ' '\n' | awk -F= -v k="$k" '$1 == k { print $2 }'; }

# scene_def A|B|C: sets scn, ref, paths (accuracy.c option), pov, pw, ph, box.
scene_def() {
	case $1 in
	A) scn=$ta/mirror.scn ref=cells:$ta/A_grid_cellavg_0.1.csv:5:0.9 paths=--all-paths
	   pov=$here/mirror.pov pw=400 ph=800 box="-3 1 -4 4" ;;
	B) scn=$ta/sphere.scn ref=annuli:$ta/B_profile_binned_0.05.csv:3 paths=
	   pov=$root/bench/caustics/sphere.pov pw=600 ph=600 box="-3 3 -3 3" ;;
	C) scn=$ta/slab.scn ref=annuli:$ta/C_profile_binned_0.05.csv:6 paths=
	   pov=$here/slab.pov pw=600 ph=600 box="-3 3 -3 3" ;;
	*) echo "bench/accuracy: unknown scene $1" >&2; exit 2 ;;
	esac
}

HEADER="scene,method,budget,time_s,l1,map_bytes,l1_nodes,l1_noise,flux_ratio,rays_shot,cell,levels,time_min,time_max,tol_estimate"

if [ -z "${PLOT_ONLY:-}" ]; then
# ---- build -------------------------------------------------------------------
cd "$root"
if [ -z "${LIBARVO:-}" ]; then # the release library `make all` builds (a no-op when current)
	make -s -j"$THREADS" MODE=release build/release/libarvo.a > /dev/null
	LIBARVO=$root/build/release/libarvo.a
fi
WARN="-Wall -Wextra -Wpedantic -Wshadow -Wundef -Wpointer-arith -Wcast-align -Wwrite-strings
 -Wmissing-prototypes -Wstrict-prototypes -Wmissing-declarations -Wformat=2 -Wvla -Wold-style-definition"
PKG_CFLAGS=$(pkg-config --cflags OpenEXR OpenColorIO libpng freetype2)
PKG_LIBS="$(pkg-config --libs OpenEXR OpenColorIO libpng freetype2) -lembree3"
# shellcheck disable=SC2086
cc -std=c11 -O2 $WARN -pthread -D_DEFAULT_SOURCE $PKG_CFLAGS -o "$tmp/accuracy" \
	"$here/accuracy.c" "$LIBARVO" $PKG_LIBS -lstdc++ -lm -pthread
# shellcheck disable=SC2086
cc -std=c11 -O2 $WARN -D_DEFAULT_SOURCE -o "$tmp/povbin" "$here/povbin.c" -lm

echo "$HEADER" > "$tmp/c.csv"
t_start=$(now) load_start=$(cut -d' ' -f1-3 /proc/loadavg)

# arvo_point SCENE SERIES METHOD SCN RAYS LABEL [OPTION...]: RUNS light
# passes, one CSV row (LABEL in the budget column); sets t, the median time.
arvo_point() {
	sc=$1 series=$2 meth=$3 file=$4 n=$5 label=$6
	shift 6
	: > "$tmp/a.log"
	for i in $(seq "$RUNS"); do
		only=--time-only # the maps are bit-identical from run to run: one metric
		[ "$i" = 1 ] && only=
		# shellcheck disable=SC2086
		if ! "$tmp/accuracy" "$file" "$ref" "$meth" "$n" "$THREADS" $paths $only "$@" >> "$tmp/a.log" 2> "$tmp/a.err"; then
			echo "bench/accuracy: $sc $series $n failed: $(head -3 "$tmp/a.err")" >&2
			return 1
		fi
	done
	t=$(kv time_s "$tmp/a.log" | median)
	tmin=$(kv time_s "$tmp/a.log" | sort -g | head -1) tmax=$(kv time_s "$tmp/a.log" | sort -g | tail -1)
	l=$(kv l1 "$tmp/a.log" | median)
	last=$(head -1 "$tmp/a.log")
	echo "$last" | tr ' ' '\n' | awk -F= -v sc="$sc" -v se="$series" -v n="$label" -v t="$t" -v l="$l" \
		-v a="$tmin" -v b="$tmax" '{ v[$1] = $2 }
		END { printf "%s,%s,%s,%.4f,%.6f,%s,%s,%s,%s,%s,%s,%s,%.4f,%.4f,%s\n", sc, se, n, t, l, v["map_bytes"],
			v["l1_nodes"], v["l1_noise"], v["flux_ratio"], v["rays_shot"], v["cell"], v["levels"], a, b,
			v["tol_estimate"] }' \
		>> "$tmp/c.csv"
	tail -1 "$tmp/c.csv"
}

# ladder SCENE SERIES METHOD SCN BUDGETS [OPTION...]: the rungs in order;
# stops before a rung whose time, predicted from the last one (time x ray
# ratio), would exceed $MAXT.
ladder() {
	sc=$1 series=$2 meth=$3 file=$4 budgets=$5
	shift 5
	for n in $budgets; do
		if [ -n "${t:-}" ] && [ -n "${n_last:-}" ] &&
			! awk -v t="$t" -v a="$n_last" -v b="$n" -v m="$MAXT" 'BEGIN { exit !(t * b / a <= m) }'; then
			echo "  ($series: $n rays would take about $(awk -v t="$t" -v a="$n_last" -v b="$n" 'BEGIN { printf "%.0f", t * b / a }') s > MAXT=$MAXT s: ladder stops)"
			break
		fi
		arvo_point "$sc" "$series" "$meth" "$file" "$n" "$n" "$@" || break
		n_last=$n
	done
	t='' n_last=''
}

# the scene with its floor's `illum_map { cell 0.01 }` replaced by $2 (empty: none)
variant() {
	grep -q 'illum_map { cell 0\.01 }' "$1" || { echo "bench/accuracy: $1 has no 'illum_map { cell 0.01 }'" >&2; exit 1; }
	sed "s/illum_map { cell 0\.01 }/$2/" "$1"
}

# pov COUNT: RUNS renders; wall times to $tmp/p.walls, L1s to $tmp/p.l1s,
# photons shot to $tmp/p.shot.
pov() {
	: > "$tmp/p.walls"
	: > "$tmp/p.l1s"
	for i in $(seq "$RUNS"); do
		t0=$(now)
		(cd "$tmp" && "$POVRAY" +I"$pov" +O"$tmp/p.exr" +FE +W"$pw" +H"$ph" -A -D \
			+WT"$THREADS" Declare=Count="$1" > /dev/null 2> "$tmp/p.log")
		awk -v a="$t0" -v b="$(now)" 'BEGIN { printf "%.4f\n", b - a }' >> "$tmp/p.walls"
		if [ "$1" != 0 ]; then
			# shellcheck disable=SC2086
			oiiotool --dumpdata "$tmp/p.exr" | "$tmp/povbin" $box "$ref" > "$tmp/p.l1"
			kv l1 "$tmp/p.l1" >> "$tmp/p.l1s"
		fi
	done
	awk '/photons shot/ { print $NF; exit }' "$tmp/p.log" > "$tmp/p.shot"
}

have_pov=0
command -v "$POVRAY" > /dev/null 2>&1 && command -v oiiotool > /dev/null 2>&1 && have_pov=1
[ $have_pov = 1 ] || echo "bench/accuracy: $POVRAY or oiiotool not found: arvo only" >&2

for sc in $SCENES; do
	scene_def "$sc"
	echo "==== scene $sc ($(basename "$scn"))"
	variant "$scn" 'illum_map { cell 0.01 }' > "$tmp/$sc-0.01.scn"
	variant "$scn" 'illum_map { cell 0.005 }' > "$tmp/$sc-0.005.scn"
	variant "$scn" '' > "$tmp/$sc-auto.scn"
	ladder "$sc" point-0.01 point "$tmp/$sc-0.01.scn" "$POINT_BUDGETS"
	ladder "$sc" point-0.01-kept point "$tmp/$sc-0.01.scn" "$KEPT_BUDGETS" --keep-isolated
	ladder "$sc" point-0.005 point "$tmp/$sc-0.005.scn" "$FINE_BUDGETS"
	ladder "$sc" point-auto point "$tmp/$sc-auto.scn" "$POINT_BUDGETS"
	ladder "$sc" shaft-auto shaft "$tmp/$sc-auto.scn" "$SHAFT_BUDGETS"
	ladder "$sc" shaft-0.01 shaft "$tmp/$sc-0.01.scn" "$SHAFT_BUDGETS"
	# the light pass's own accuracy target, loosest first
	# (a target the last run's own estimate already meets stops at the same
	# round: same time; any other needs one more round at least: 4x)
	est=''
	for T in $TOLERANCES; do
		if [ -n "$est" ]; then
			p=$(awk -v t="$t" -v e="$est" -v T="$T" 'BEGIN { print (e <= T ? t : 4 * t) }')
			if ! awk -v p="$p" -v m="$TOL_MAXT" 'BEGIN { exit !(p <= m) }'; then
				echo "  (tol-0.01: tolerance $T would take about $p s > TOL_MAXT=$TOL_MAXT s: ladder stops)"
				break
			fi
		fi
		arvo_point "$sc" tol-0.01 shaft "$tmp/$sc-0.01.scn" 1 "$T" --tolerance "$T" || break
		est=$(tail -1 "$tmp/c.csv" | cut -d, -f15)
	done
	for T in $TOL_AUTO; do
		arvo_point "$sc" tol-auto shaft "$tmp/$sc-auto.scn" 1 "$T" --tolerance "$T" || break
	done

	[ $have_pov = 1 ] || continue
	pov 0
	base=$(median < "$tmp/p.walls")
	echo "  POV-Ray without photons: $base s wall (subtracted)"
	echo "$base" > "$tmp/base-$sc"
	c_last='' t_pov=''
	for c in $POV_COUNTS; do
		# POV-Ray's time grows more slowly than its count (measured: about
		# as count^0.75 from 1e6 to 1e7), so the prediction uses that
		if [ -n "$c_last" ] && ! awk -v t="$t_pov" -v a="$c_last" -v b="$c" -v m="$POV_MAXT" 'BEGIN { exit !(t * (b / a) ^ 0.75 <= m) }'; then
			echo "  (POV-Ray: count $c would take about $(awk -v t="$t_pov" -v a="$c_last" -v b="$c" 'BEGIN { printf "%.0f", t * (b / a) ^ 0.75 }') s > POV_MAXT=$POV_MAXT s: ladder stops)"
			break
		fi
		pov "$c"
		wall=$(median < "$tmp/p.walls")
		awk -v sc="$sc" -v c="$c" -v w="$wall" -v b="$base" -v l="$(median < "$tmp/p.l1s")" \
			-v r="$(cat "$tmp/p.shot")" -v a="$(sort -g "$tmp/p.walls" | head -1)" \
			-v z="$(sort -g "$tmp/p.walls" | tail -1)" \
			'BEGIN { printf "%s,povray,%s,%.4f,%.6f,,,,,%s,,,%.4f,%.4f,\n", sc, c, w - b, l, r, a, z }' >> "$tmp/c.csv"
		tail -1 "$tmp/c.csv"
		c_last=$c t_pov=$(awk -v w="$wall" -v b="$base" 'BEGIN { print w - b }')
	done
done
cp "$tmp/c.csv" "$csv"
total=$(awk -v a="$t_start" -v b="$(now)" 'BEGIN { printf "%.0f", b - a }')
bases=$(for sc in $SCENES; do [ -f "$tmp/base-$sc" ] && printf ' %s %ss' "$sc" "$(cat "$tmp/base-$sc")"; done; :)
{
	echo "run: $(date -u +%Y-%m-%d), $total s in all; cpu: $(awk -F': ' '/model name/ { print $2; exit }' /proc/cpuinfo), $(nproc) online; load (1, 5, 15 min) at the start: $load_start, at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
	echo "POV-Ray without photons (subtracted):${bases:- -}"
} > "$res/accuracy.meta"
fi

# ---- summary -------------------------------------------------------------------
[ -f "$csv" ] || { echo "bench/accuracy: no $csv" >&2; exit 1; }
# reach SCENE METHOD T: "time budget" where METHOD's ladder first reaches
# L1 <= T: the time interpolated log-log between the rung before (L1 > T)
# and the first rung at or below T, and that rung's budget; a ladder whose
# first rung is already below T gives that rung's time (an upper bound, "<").
# Tolerance series are not interpolated (a target between two of theirs
# costs a whole round of 4x the rays): the first rung that reached T.
reach() {
	awk -F, -v sc="$1" -v m="$2" -v T="$3" 'NR > 1 && $1 == sc && $2 == m { n++; b[n] = $3; t[n] = $4; l[n] = $5 }
	END {
		for (i = 1; i <= n; i++) if (l[i] <= T) break
		if (i > n) exit
		if (m ~ /^tol-/) { printf "%s %s\n", t[i], b[i]; exit }
		if (i == 1 || l[i] <= 0) { printf "%s %s <\n", t[i], b[i]; exit }
		f = (log(l[i - 1]) - log(T)) / (log(l[i - 1]) - log(l[i]))
		printf "%.4g %s\n", exp(log(t[i - 1]) + f * (log(t[i]) - log(t[i - 1]))), b[i]
	}' "$csv"
}
methods_of() { awk -F, -v sc="$1" 'NR > 1 && $1 == sc && !s[$2]++ { print $2 }' "$csv"; }
{
	echo "bench/accuracy: caustic error (flux-weighted relative L1 against the exact binned flux) against time"
	echo "$THREADS threads, median of $RUNS runs per point. arvo: lp_run alone (accuracy.c), the renderer's"
	echo "settings; POV-Ray 3.7: wall minus wall without photons (radius 0.05, jitter 0.4, gather 20, 100)."
	echo "Scenes: A mirror (0.1 cells), B glass sphere, C glass slab (0.05 annuli to r = 3); tests/accuracy."
	[ -f "$res/accuracy.meta" ] && cat "$res/accuracy.meta"
	echo "Made by: make bench-accuracy (sh bench/accuracy/run.sh)"
	for sc in $SCENES; do
		echo
		echo "== scene $sc"
		awk -F, -v sc="$sc" 'NR == 1 || $1 == sc { print $2, $3, $4, $5, ($6 == "" ? "-" : sprintf("%.1f", $6 / 1048576)),
			($9 == "" ? "-" : $9), ($11 == "" ? "-" : $11), ($10 == "" ? "-" : $10) }' "$csv" |
			sed '1s/.*/method budget time_s l1 map_MiB flux_ratio cell rays_shot/' | column -t
		echo "time to reach L1 <= target, s (interpolated log-log between rungs; the budget of the rung that reached it):"
		printf '  %-16s' "target"
		for T in $TARGETS; do printf '%-20s' "$T"; done
		echo
		for m in $(methods_of "$sc"); do
			printf '  %-16s' "$m"
			for T in $TARGETS; do
				r=$(reach "$sc" "$m" "$T")
				if [ -n "$r" ]; then
					printf '%-20s' "$(echo "$r" | awk '{ printf "%s%.3g (%s)", $3, $1, $2 }')"
				else
					printf '%-20s' "not reached"
				fi
			done
			echo
		done
		printf '  %-16s' "POV-Ray/arvo"
		for T in $TARGETS; do
			a=$(for m in $(methods_of "$sc"); do [ "$m" = povray ] || reach "$sc" "$m" "$T" | sed "s/\$/ $m/"; done | sort -g | head -1)
			p=$(reach "$sc" povray "$T")
			if [ -n "$a" ] && [ -n "$p" ]; then
				# a time marked "<" is an upper bound: the ratio is then a bound too
				printf '%-20s' "$(awk -v p="$p" -v a="$a" 'BEGIN { np = split(p, P, " "); na = split(a, A, " ")
					al = A[3] == "<"; pl = P[3] == "<"
					printf "%s%.0fx %s", al && pl ? "~" : al ? ">" : pl ? "<" : "", P[1] / A[1], A[na] }')"
			elif [ -n "$a" ]; then
				printf '%-20s' "POV: not reached"
			else
				printf '%-20s' "-"
			fi
		done
		echo
		echo "  (POV-Ray's time over the fastest arvo method's, which is named; > where arvo's first rung was"
		echo "   already below the target, so its time is an upper bound)"
		awk -F, -v sc="$sc" 'NR > 1 && $1 == sc && $2 ~ /^tol-/ { n++; m[n] = $2; T[n] = $3; t[n] = $4; l[n] = $5; e[n] = $15; r[n] = $10 }
		END { if (n) print "the accuracy target (--tolerance T): asked, measured L1, the pass'"'"'s own estimate, time, rays:"
			for (i = 1; i <= n; i++) printf "  %-16s T %-6s L1 %-9.2g estimate %-9.2g %8.3g s  %d rays (L1/T %.2f)\n", m[i], T[i], l[i], e[i], t[i], r[i], l[i] / T[i] }' "$csv"
		echo "where each method's error stops falling (L1 along its ladder, budgets in order):"
		for m in $(methods_of "$sc" | grep -v '^tol-'); do
			awk -F, -v sc="$sc" -v m="$m" 'NR > 1 && $1 == sc && $2 == m { n++; b[n] = $3; l[n] = $5 }
			END {
				lo = 1; for (i = 2; i <= n; i++) if (l[i] < l[lo]) lo = i
				s = ""; for (i = 1; i <= n; i++) s = s sprintf("%s%.2g", i > 1 ? " " : "", l[i])
				if (n < 2) v = "one point only"
				else if (lo == n && l[n] < 0.7 * l[n - 1]) v = sprintf("still falling at the largest budget, %s (L1 %.2g): no floor within the ladder", b[n], l[n])
				else if (lo == n) v = sprintf("flattening: %s -> %s gained only %.0f %% (L1 %.2g)", b[n - 1], b[n], 100 * (1 - l[n] / l[n - 1]), l[n])
				else v = sprintf("floor: best L1 %.2g at %s; more did not lower it (last %.2g)", l[lo], b[lo], l[n])
				w = ""; for (i = 2; i <= n; i++) if (l[i] > 1.2 * l[i - 1]) w = w sprintf(" %s->%s (%.2g->%.2g)", b[i - 1], b[i], l[i - 1], l[i])
				printf "  %-16s %s\n  %-16s [%s]\n", m, v, "", s
				if (w != "") printf "  %-16s WORSE with more rays:%s\n", "", w
			}' "$csv"
		done
	done
} > "$res/accuracy.txt"
cat "$res/accuracy.txt"

# ---- chart -------------------------------------------------------------------------
if command -v gnuplot > /dev/null 2>&1; then
	plots='' keyplot='' keyseen=''
	n=$(echo "$SCENES" | wc -w)
	k=0
	for sc in $SCENES; do
		i=0
		plot="plot"
		for m in $(methods_of "$sc"); do
			i=$((i + 1))
			awk -F, -v sc="$sc" -v m="$m" 'NR > 1 && $1 == sc && $2 == m { print $4, $5, $3 }' "$csv" > "$tmp/$sc-$i.dat"
			case $m in
			povray) st="lw 2.5 lc rgb 'black' pt 5" t="POV-Ray 3.7 photons" ;;
			point-0.01) st="lc rgb '#1f77b4' pt 7" t=$m ;;
			point-0.005) st="lc rgb '#17becf' pt 9" t=$m ;;
			point-0.01-kept) st="lc rgb '#1f77b4' dt 3 pt 6" t="point-0.01, isolated kept" ;;
			point-auto) st="lc rgb '#2ca02c' pt 13" t=$m ;;
			shaft-auto) st="lc rgb '#d62728' pt 11" t=$m ;;
			shaft-0.01) st="lc rgb '#ff7f0e' pt 6" t=$m ;;
			tol-0.01) st="lc rgb '#9467bd' lw 2 pt 3" t="--tolerance T (shaft, cell 0.01)" ;;
			tol-auto) st="lc rgb '#8c564b' lw 2 pt 2" t="--tolerance T (shaft, automatic)" ;;
			*) st="lc rgb '#9467bd' pt 3" t=$m ;;
			esac
			plot="$plot '$tmp/$sc-$i.dat' using 1:2 with linespoints $st ps 0.8 notitle,"
			# the key (a panel of its own under the others): each method once
			case " $keyseen " in *" $m "*) ;; *)
				keyseen="${keyseen:-} $m"
				keyplot="${keyplot:+$keyplot,} 2 with linespoints $st ps 0.8 title '$t'" ;;
			esac
		done
		case $sc in
		A) name="A: mirror" ;;
		B) name="B: glass sphere" ;;
		C) name="C: glass slab" ;;
		*) name=$sc ;;
		esac
		plots="$plots
set origin $(awk -v k="$k" -v n="$n" 'BEGIN { print k / n }'),0.16
set title '$name'
$plot 0.01 with lines dt 2 lc rgb 'gray' notitle"
		k=$((k + 1))
	done
	for term in "svg size 1500,600 font 'sans,11'" "pngcairo size 1500,600 font 'sans,10'"; do
		case $term in svg*) out=$docs/accuracy.svg ;; *) out=$docs/accuracy.png ;; esac
		gnuplot <<GP
set terminal $term
set output "$out"
set multiplot title "Caustic error against time: arvo light-pass methods vs POV-Ray 3.7 photons ($THREADS threads, median of $RUNS; make bench-accuracy)"
set size $(awk -v n="$n" 'BEGIN { print 1 / n }'),0.78
set logscale xy
set xlabel "time (s): arvo lp\\\\_run; POV-Ray wall minus no-photon wall"
set ylabel "flux-weighted relative L1 (dashed: 1 %)"
set format x "%g"
set format y "%g"
set grid
unset key
set xrange [1e-3:100]
set yrange [5e-5:2]
$plots
set origin 0,0
set size 1,0.15
unset logscale
unset border
unset tics
unset grid
unset title
unset xlabel
unset ylabel
set xrange [0:1]
set yrange [0:1]
set key center center horizontal maxrows 2 width 2
plot $keyplot
unset multiplot
GP
	done
	echo "chart: docs/accuracy.svg, docs/accuracy.png ($(wc -c < "$docs/accuracy.png") bytes)"
fi
