#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/stability/run.sh: scenes where light-pass methods are known to break
# (poles, apexes, seams, grazing light, total internal reflection, trapped
# rays, coincident surfaces, odd indices, extreme scales, degenerate
# objects, a point focus, sparse rays). Each .scn here says in its header
# what it probes and what is expected; docs/methods.md sums them up.
#
# Every rendering case is rendered small (32x24, --rays 20000, --stats) and
# must: exit 0 without a crash or sanitizer report; have no NaN in any
# channel of the EXR and no Inf but in Z (oiiotool --printstats); and balance the light
# pass's energy line on stderr,
#   arvo: light energy     emitted E W = deposited D + direct R + absorbed A + escaped X + cut C
# with D <= E·(1 + 1e-6) and |D + R + A + X + C − E| <= 1e-4·E. Some cases
# add a check of their own (see below). The invalid scenes must stop with
# "file:line:col: error: message", the source line and a caret, exit 65,
# and leave no image.
# Environment: ARVO (default ./arvo), TIMEOUT (seconds per run, 60).
set -u
cd "$(dirname "$0")/../.." || exit 2
ARVO=${ARVO:-$PWD/arvo}
TIMEOUT=${TIMEOUT:-60}
T=tests/stability
SIZE="--width 32 --height 24"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-stability.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT INT TERM

n=0
why=
# report NAME: prints the TAP line for the check just made (why empty = ok).
report() {
	n=$((n + 1))
	if [ -z "$why" ]; then
		echo "ok $n - $1"
	else
		echo "not ok $n - $1"
		printf '%s\n' "$why" | sed 's/^/#   /'
	fi
	why=
}
fail() { why="${why:+$why
}$*"; }

# render TAG SCENE ARGS...: renders SCENE into $tmp/TAG.exr with --stats;
# sets rc, leaves stderr in $tmp/TAG.err.
render() {
	tag=$1 scn=$2
	shift 2
	timeout "$TIMEOUT" "$ARVO" --stats $SIZE "$@" -o "$tmp/$tag.exr" "$scn" > "$tmp/$tag.out" 2> "$tmp/$tag.err" < /dev/null
	rc=$?
}

# ran_ok TAG: exit 0, no crash or timeout, no sanitizer-like report, an image.
ran_ok() {
	[ "$rc" -lt 124 ] || fail "crashed or timed out (exit status $rc)"
	[ "$rc" -eq 0 ] || fail "exit status $rc, expected 0"
	if grep -Eq 'runtime error|Sanitizer|Segmentation|Assertion|core dumped|stack-overflow' "$tmp/$1.err"; then
		fail "sanitizer-like output on stderr:"
		fail "$(grep -E 'runtime error|Sanitizer|Segmentation|Assertion|core dumped|stack-overflow' "$tmp/$1.err" | head -3)"
	fi
	[ -s "$tmp/$1.exr" ] || fail "no image written"
	[ "$rc" -eq 0 ] || fail "$(head -5 "$tmp/$1.err")"
}

# finite TAG: no NaN in any channel, no Inf in any but Z (+inf where no
# sample hit anything, by design). oiiotool --printstats prints "Stats
# NanCount: 0 0 ..." and "Stats InfCount: ..." (one count per channel, in
# the order of its "channel list"); a missing line is a failure, not a pass.
finite() {
	oiiotool "$tmp/$1.exr" --printstats > "$tmp/$1.stats" 2>&1
	chans=$(oiiotool --info -v "$tmp/$1.exr" 2>/dev/null | sed -n 's/^ *channel list: //p' | tr -d ',')
	for what in NanCount InfCount; do
		line=$(grep "Stats $what:" "$tmp/$1.stats")
		if [ -z "$line" ] || [ -z "$chans" ]; then
			fail "oiiotool printed no 'Stats $what:' line or channel list"
		elif ! printf '%s\n' "$line" | awk -v what="$what" -v chans="$chans" '{
				split(chans, c, " ")
				for (i = 3; i <= NF; i++) if ($i != "0" && !(what == "InfCount" && c[i - 2] == "Z")) exit 1
				exit NF < 3 }'; then
			fail "$line"
		fi
	done
}

# energy_read TAG: reads the light energy line from $tmp/TAG.err into
# e_emitted, e_deposited, e_direct, e_absorbed, e_escaped, e_cut; returns
# non-zero (with why set) when the line is missing or malformed. A light
# pass that shot no ray (nothing to aim at, e.g. glass of ior 1 that bends
# nothing) prints no energy line: all terms are then 0.
energy_read() {
	cnt=$(grep -c '^arvo: light energy ' "$tmp/$1.err")
	if [ "$cnt" -eq 0 ] && grep -q '^arvo: light pass .*(0 light rays' "$tmp/$1.err"; then
		e_emitted=0 e_deposited=0 e_direct=0 e_absorbed=0 e_escaped=0 e_cut=0
		return 0
	fi
	if [ "$cnt" -eq 0 ]; then
		fail "no light energy line ('arvo: light energy     emitted E W = deposited D + direct R + absorbed A + escaped X + cut C') in the --stats output"
		return 1
	fi
	if [ "$cnt" -gt 1 ]; then
		fail "$cnt light energy lines, expected one (summed over channels and passes)"
		return 1
	fi
	line=$(grep '^arvo: light energy ' "$tmp/$1.err")
	vals=$(printf '%s\n' "$line" | awk '
		function num(s) { return s ~ /^-?[0-9]+(\.[0-9]*)?([eE][-+]?[0-9]+)?$/ }
		NF == 21 && $4 == "emitted" && $6 == "W" && $7 == "=" && $8 == "deposited" && $11 == "direct" &&
		$14 == "absorbed" && $17 == "escaped" && $20 == "cut" && $10 == "+" && $13 == "+" && $16 == "+" &&
		$19 == "+" && num($5) && num($9) && num($12) && num($15) && num($18) && num($21) {
			print $5, $9, $12, $15, $18, $21; ok = 1 }
		END { exit !ok }')
	if [ -z "$vals" ]; then
		fail "malformed light energy line: $line"
		return 1
	fi
	set -- $vals
	e_emitted=$1 e_deposited=$2 e_direct=$3 e_absorbed=$4 e_escaped=$5 e_cut=$6
}

# energy TAG: energy_read, then the balance: no term below −1e-6·emitted
# (rounding), deposited <= emitted, the five terms sum to emitted.
energy() {
	energy_read "$1" || return 1
	for t in "emitted $e_emitted" "deposited $e_deposited" "direct $e_direct" "absorbed $e_absorbed" \
		"escaped $e_escaped" "cut $e_cut"; do
		set -- $t
		awk -v x="$2" -v e="$e_emitted" 'BEGIN { exit !(x >= -1e-6 * e) }' ||
			fail "$1 $2 W is negative: energy out of nothing"
	done
	set -- $e_emitted $e_deposited $e_direct $e_absorbed $e_escaped $e_cut
	awk -v e="$1" -v d="$2" -v r="$3" -v a="$4" -v x="$5" -v c="$6" 'BEGIN { exit !(d <= e * (1 + 1e-6)) }' ||
		fail "deposited $2 W > emitted $1 W: energy out of nothing"
	awk -v e="$1" -v d="$2" -v r="$3" -v a="$4" -v x="$5" -v c="$6" 'BEGIN {
		s = d + r + a + x + c; diff = s - e; if (diff < 0) diff = -diff; exit !(diff <= 1e-4 * e) }' ||
		fail "the terms sum to $(awk -v d="$2" -v r="$3" -v a="$4" -v x="$5" -v c="$6" 'BEGIN { printf "%.6g", d + r + a + x + c }') W, emitted $1 W (tolerance 1e-4 relative)"
	[ -z "$why" ]
}

# chmax TAG CHANNELS: the largest Stats Max over CHANNELS (comma-separated).
chmax() {
	oiiotool "$tmp/$1.exr" --ch "$2" --printstats 2>/dev/null |
		awk '$1 == "Stats" && $2 == "Max:" { m = $3; for (i = 4; i < NF; i++) if ($i > m) m = $i; print m; exit }'
}
# chavg TAG CHANNEL: the channel's Stats Avg.
chavg() {
	oiiotool "$tmp/$1.exr" --ch "$2" --printstats 2>/dev/null | awk '$1 == "Stats" && $2 == "Avg:" { print $3; exit }'
}
# is_zero X: X is a number equal to 0.
is_zero() { awk -v x="$1" 'BEGIN { exit !(x != "" && x + 0 == 0) }'; }

# same TAG REF CHANNELS: the channels of two renders agree to 1e-3.
same() {
	oiiotool "$tmp/$1.exr" --ch "$3" -o "$tmp/$1.sel.exr" > /dev/null 2>&1 &&
		oiiotool "$tmp/$2.exr" --ch "$3" -o "$tmp/$2.sel.exr" > /dev/null 2>&1 &&
		idiff -fail 0.001 "$tmp/$2.sel.exr" "$tmp/$1.sel.exr" > "$tmp/idiff.log" 2>&1 ||
		fail "channels $3 differ from the reference: $(grep -E 'Mean error|Max error' "$tmp/idiff.log" | tr -s ' ' | tr '\n' ';')"
}

# case_checks TAG SCENE ARGS...: renders and reports the three common checks.
case_checks() {
	tag=$1
	render "$@"
	ran_ok "$tag"; report "$tag: renders (exit 0, no crash, no sanitizer report)"
	if [ -s "$tmp/$tag.exr" ]; then finite "$tag"; else fail "no image"; fi
	report "$tag: no NaN in any channel, no Inf but Z's misses"
	energy "$tag"; report "$tag: light energy balances (deposited <= emitted, five terms sum to emitted)"
}

R="--rays 20000"

# ---- poles, apexes, seams ----------------------------------------------------
for c in pole_sphere pole_torus horn_torus cone_apex seam; do
	case_checks $c $T/$c.scn $R
done

# ---- grazing light, total internal reflection, trapped rays -------------------
for c in grazing prism light_in_glass trapped; do
	case_checks $c $T/$c.scn $R
done
case_checks prism_spectral $T/prism.scn $R --passes spectral
m=$(chmax light_in_glass direct.R,direct.G,direct.B)
is_zero "$m" || fail "direct layer max '$m', expected 0"
m=$(chmax light_in_glass caustic.R,caustic.G,caustic.B)
awk -v m="$m" 'BEGIN { exit !(m > 0.1) }' || fail "caustic layer max '$m', expected > 0.1"
report "light_in_glass: the glass blocks shadow rays (direct layer zero), the map carries the light"
if energy trapped; then
	awk -v c="$e_cut" -v e="$e_emitted" 'BEGIN { exit !(c > 1e-3 * e) }' || fail "cut $e_cut W of $e_emitted W: trapped rays not counted as cut"
fi
report "trapped: the energy of rays stopped at max_depth is counted as cut"

case_checks tilted_cube $T/tilted_cube.scn $R
case_checks tilted_cube_fresnel $T/tilted_cube.scn $R -D FRESNEL=1
if energy_read tilted_cube; then
	ideal=$e_deposited
	if energy_read tilted_cube_fresnel; then
		awk -v f="$e_deposited" -v i="$ideal" 'BEGIN { exit !(f <= i * (1 + 1e-5)) }' ||
			fail "Fresnel glass deposits $e_deposited W, ideal glass $ideal W"
	fi
fi
report "tilted_cube: Fresnel glass deposits no more than ideal glass"

# ---- coincident and touching surfaces, the camera inside glass, ior 1 and 10 --
for c in coincident touching camera_in_glass ior_one ior_ten; do
	case_checks $c $T/$c.scn $R
done
m=$(chmax camera_in_glass direct.R,direct.G,direct.B)
is_zero "$m" || fail "direct layer max '$m', expected 0"
m=$(chavg camera_in_glass R)
awk -v m="$m" 'BEGIN { exit !(m > 0.05) }' || fail "image mean '$m', expected > 0.05"
report "camera_in_glass: the first hit is an exit (direct layer zero), the scene is seen through it"
render ior_one_empty $T/ior_one.scn $R -D GLASS=0
ran_ok ior_one_empty
a=$(chavg ior_one R) b=$(chavg ior_one_empty R)
awk -v a="$a" -v b="$b" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(b > 0 && d <= 0.01 * b) }' ||
	fail "image mean '$a', without the sphere '$b' (tolerance 1 %)"
report "ior_one: glass of ior 1 renders as the empty scene (mean within 1 %)"

# ---- tiny and huge coordinates --------------------------------------------------
for c in tiny huge; do
	case_checks $c $T/$c.scn $R
	render ${c}_ref $T/$c.scn $R -D S=1
	ran_ok ${c}_ref
done
same tiny tiny_ref direct.R,direct.G,direct.B
report "tiny (1e-6): the direct layer matches the same scene at scale 1"
same huge huge_ref R,G,B,caustic.R,caustic.G,caustic.B,direct.R,direct.G,direct.B
report "huge (1e6): the image and its caustic match the same scene at scale 1"
if energy_read tiny_ref; then
	ref=$e_deposited
	if energy_read tiny; then
		awk -v a="$e_deposited" -v r="$ref" 'BEGIN { q = a / (r * 1e-12); exit !(r > 0 && q > 0.999 && q < 1.001) }' ||
			fail "deposited $e_deposited W, expected 1e-12 x $ref W"
	fi
fi
report "tiny (1e-6): the light pass deposits 1e-12 times the energy at scale 1"

# ---- a caustic focused to a point, very sparse rays -------------------------------
SIZE="--width 33 --height 25"
case_checks focus $T/focus.scn $R
oiiotool "$tmp/focus.exr" --ch caustic.G -o "$tmp/focus.g.exr" > /dev/null 2>&1
peak=$(oiiotool --dumpdata "$tmp/focus.g.exr" 2>/dev/null |
	awk '/Pixel/ { gsub(/[(),:]/, " "); if ($4 > m) { m = $4; p = $2 " " $3 } } END { print p, m }')
set -- $peak
[ "${1:-}" = 16 ] && [ "${2:-}" = 12 ] || fail "brightest caustic pixel at (${1:-?}, ${2:-?}), expected the focus at (16, 12)"
awk -v m="${3:-nan}" 'BEGIN { exit !(m > 100 && m < 1e6) }' || fail "peak caustic ${3:-?}, expected a finite peak > 100"
report "focus: the brightest caustic pixel is the focus, and it is finite"
SIZE="--width 32 --height 24"
case_checks sparse $T/sparse.scn --rays 10 --method point
rays=$(sed -n 's/^arvo: light pass .*(\([0-9]*\) light rays.*/\1/p' "$tmp/sparse.err")
[ -n "$rays" ] && [ "$rays" -ge 1 ] && [ "$rays" -le 10 ] || fail "light pass shot '${rays:-?}' rays, expected 1 to 10"
report "sparse: --rays 10 shoots at most 10 light rays"
case_checks sparse_shaft $T/sparse.scn --rays 10 --method shaft
rays=$(sed -n 's/^arvo: light pass .*(\([0-9]*\) light rays.*/\1/p' "$tmp/sparse_shaft.err")
[ -n "$rays" ] && [ "$rays" -ge 1 ] && [ "$rays" -le 200 ] || fail "light pass traced '${rays:-?}' rays, expected 1 to 200"
report "sparse shafts: --rays 10 traces a 2x2 grid of shafts and their splits (at most 200 rays)"

# ---- invalid scenes: located error, exit 65, no image -------------------------------
# invalid NAME LINE COL MESSAGE
invalid() {
	timeout "$TIMEOUT" "$ARVO" $SIZE --rays 1000 -o "$tmp/$1.exr" "$T/$1.scn" > "$tmp/$1.out" 2> "$tmp/$1.err" < /dev/null
	rc=$?
	[ "$rc" -lt 124 ] || fail "crashed or timed out (exit status $rc)"
	[ "$rc" -eq 65 ] || fail "exit status $rc, expected 65"
	{
		printf '%s\n' "$T/$1.scn:$2:$3: error: $4"
		sed -n "$2p" "$T/$1.scn"
		awk -v c="$3" 'BEGIN { s = ""; for (i = 1; i < c; i++) s = s " "; print s "^" }'
	} > "$tmp/$1.want"
	cmp -s "$tmp/$1.want" "$tmp/$1.err" || fail "stderr is not the located error with its source line and caret:" "$(sed 's/^/  /' "$tmp/$1.err" | head -6)"
	[ ! -e "$tmp/$1.exr" ] || fail "an image was written"
	report "$1: error at $2:$3, source line and caret, exit 65, no image"
}
invalid sphere_zero 7 21 "sphere radius must be positive, found 0"
invalid torus_thin 7 12 "torus minor radius must be positive, found 0"
invalid box_flat 8 20 "box has zero volume (both corners have y = 1)"

echo "1..$n"
