#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/run.sh: the command line: options, exit codes, messages and
# output files (after chibicc's test/driver.sh). One TAP line per case.
# Rendering cases are skipped (`ok N - name # SKIP`) while the binary cannot
# render yet. Environment: ARVO (default ./arvo), TIMEOUT (seconds, 20).
set -u
cd "$(dirname "$0")/../.." || exit 2
ARVO=${ARVO:-$PWD/arvo}
TIMEOUT=${TIMEOUT:-20}
D=tests/cli/data
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-cli.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT INT TERM

n=0
why=
# run ARGS...: runs arvo; sets rc, leaves stdout in $tmp/out, stderr in $tmp/err.
run() {
	timeout "$TIMEOUT" "$ARVO" "$@" > "$tmp/out" 2> "$tmp/err" < /dev/null
	rc=$?
	[ "$rc" -lt 124 ] || why="${why:+$why; }crashed or timed out (exit status $rc)"
}
# want_rc CODE...: the exit status must be one of CODE.
want_rc() {
	for c; do [ "$rc" -eq "$c" ] && return; done
	why="${why:+$why; }exit status $rc, expected $*"
}
# has FILE ERE: FILE must hold a line matching ERE (case-sensitive).
has() { grep -Eq -- "$2" "$tmp/$1" || why="${why:+$why; }$1 lacks /$2/"; }
# hasi FILE ERE: the same, ignoring case.
hasi() { grep -Eqi -- "$2" "$tmp/$1" || why="${why:+$why; }$1 lacks /$2/i"; }
# is FILE TEXT: FILE must be exactly TEXT plus a newline.
is() { printf '%s\n' "$2" | cmp -s - "$tmp/$1" || why="${why:+$why; }$1 is not \"$2\""; }
# empty FILE: FILE must be empty.
empty() { [ ! -s "$tmp/$1" ] || why="${why:+$why; }$1 is not empty"; }
# report NAME: prints the TAP line for the case just checked.
report() {
	n=$((n + 1))
	if [ -z "$why" ]; then
		echo "ok $n - $1"
	else
		echo "not ok $n - $1"
		echo "#   $why"
		for s in out err; do
			[ -s "$tmp/$s" ] && { echo "#   std$s:"; head -8 "$tmp/$s" | sed 's/^/#     /'; }
		done
	fi
	why=
}
skip() { n=$((n + 1)); echo "ok $n - $1 # SKIP $2"; }

# ---- information -----------------------------------------------------------
run --help
want_rc 0; hasi out 'usage'; has out -- '--check'; report "--help prints usage on stdout, exit 0"

run --version
want_rc 0; has out '^arvo [0-9]'; report "--version prints 'arvo VERSION', exit 0"

# ---- usage errors (64) ------------------------------------------------------
run --frobnicate $D/hello.scn
want_rc 64; has err '^arvo: error: .*--frobnicate'; empty out; report "unknown option: exit 64, names the option"

run +Q9 $D/hello.scn
want_rc 64; has err '^arvo: error: .*\+Q9'; report "unknown POV-Ray switch: exit 64"

run
want_rc 64; has err '^arvo: error: '; hasi err 'scene|usage'; report "no scene file: exit 64 with a message"

run --check
want_rc 64; has err '^arvo: error: '; report "--check without a scene: exit 64"

run $D/hello.scn $D/bad.scn
want_rc 64; has err '^arvo: error: '; report "two scene files: exit 64"

run --width $D/hello.scn
want_rc 64; has err '^arvo: error: .*width'; report "--width without a number: exit 64"

run --width abc --check $D/hello.scn
want_rc 64; has err '^arvo: error: .*abc'; report "--width abc: exit 64, names the bad value"

run --width 0 --check $D/hello.scn
want_rc 64; has err '^arvo: error: .*width'; report "--width 0: exit 64"

run -D --check $D/hello.scn
want_rc 64; has err '^arvo: error: '; report "-D without NAME=VALUE: exit 64"

run -D 9x=1 --check $D/hello.scn
want_rc 64; has err '^arvo: error: .*9x'; report "-D with an invalid name: exit 64"

run --max-iterations -5 --check $D/hello.scn
want_rc 64; has err '^arvo: error: .*max-iterations'; report "--max-iterations -5: exit 64"

run --passes rainbow --check $D/hello.scn
want_rc 64; is err "arvo: error: bad value for --passes: 'rainbow' (expected rgb or spectral)
(see 'arvo --help')"; empty out; report "--passes rainbow: exit 64, names the choices"

run --check $D/hello.scn --passes
want_rc 64; is err "arvo: error: option '--passes' needs a value
(see 'arvo --help')"; report "--passes without a value: exit 64"
run --method beam --check $D/hello.scn
want_rc 64; is err "arvo: error: bad value for --method: 'beam' (expected point or shaft)
(see 'arvo --help')"; empty out; report "--method beam: exit 64, names the choices"
run --tolerance 0 --check $D/hello.scn
want_rc 64; is err "arvo: error: bad value for --tolerance: '0' (expected 1e-5 to 0.5)
(see 'arvo --help')"; empty out; report "--tolerance 0: exit 64, names the range"

# ---- missing input (66) -----------------------------------------------------
run --check tests/cli/data/nope.scn
want_rc 66; is err "arvo: error: cannot open 'tests/cli/data/nope.scn': No such file or directory"; empty out
report "missing scene file: exit 66, 'cannot open' message"

run tests/cli/data/nope.scn
want_rc 66; has err "^arvo: error: cannot open 'tests/cli/data/nope.scn': No such file or directory"
report "missing scene file without --check: exit 66"

run --check $D
want_rc 66; has err "^arvo: error: .*'$D'"; report "a directory as the scene: exit 66"

# ---- bad scene (65) ---------------------------------------------------------
run --check $D/bad.scn
want_rc 65; empty out
has err "^$D/bad.scn:3:18: error: undeclared identifier 'Nope'"
report "scene error: exit 65, file:line:col message"

run --dump-scene $D/bad.scn
want_rc 65; has err "^$D/bad.scn:3:18: error: "; report "--dump-scene of a bad scene: exit 65"

run --dump-ast $D/bad.scn
want_rc 0; has out '.'; empty err; report "--dump-ast of a scene with an evaluation error succeeds (parsing only)"

# ---- --check, -D, clock, sizes ---------------------------------------------
run --check $D/hello.scn
want_rc 0; is out "hello"; empty err; report "--check prints #debug output, exit 0"

run --check $D/defines.scn
want_rc 0; has out '^N=-1.00 S=unset$'; has out '^clock=0.00 frame=0$'; has out '^size=320x240$'
report "defaults: no -D, clock 0, frame 0, 320x240"

run -D N=2.5 --check $D/defines.scn
want_rc 0; has out '^N=2.50 S=unset$'; report "-D NAME=VALUE declares a float"

run -D 'S="abc"' --check $D/defines.scn
want_rc 0; has out '^N=-1.00 S=abc$'; report "-D NAME=\"text\" declares a string"

run Declare=N=4 --check $D/defines.scn
want_rc 0; has out '^N=4.00 '; report "Declare=NAME=VALUE (POV-Ray form)"

run -D N=1 -D N=3 --check $D/defines.scn
want_rc 0; has out '^N=3.00 '; report "a later -D of the same name wins"

run --clock 0.25 --frame 7 --check $D/defines.scn
want_rc 0; has out '^clock=0.25 frame=7$'; report "--clock and --frame"

run --width 64 --height 48 --check $D/defines.scn
want_rc 0; has out '^size=64x48$'; report "--width and --height"

run +W80 +H60 --check $D/defines.scn
want_rc 0; has out '^size=80x60$'; report "+W and +H (POV-Ray switches)"

run -I $D/incdir --check $D/needs_inc.scn
want_rc 0; is out "inc=5"; report "-I DIR adds an include directory"

run +L$D/incdir --check $D/needs_inc.scn
want_rc 0; is out "inc=5"; report "+LDIR (POV-Ray switch) adds an include directory"

run --check $D/needs_inc.scn
want_rc 66; has err "^$D/needs_inc.scn:2:1: error: .*cli_only.inc"; report "include not found without -I: exit 66 (man arvo.1: missing input) with location"

run --max-iterations 100 --check $D/loop.scn
want_rc 65; has err "^$D/loop.scn:3:1: error: .*100"; report "--max-iterations stops a long loop"

run --max-iterations 10000 --check $D/loop.scn
want_rc 0; is out "I=5000"; report "--max-iterations above the need lets it finish"

run --quiet --check $D/hello.scn
want_rc 0; is out "hello"; empty err; report "--quiet still prints #debug output"

run --threads 2 --stats --check $D/hello.scn
want_rc 0; has out '^hello$'; report "--threads and --stats are accepted"

# ---- dumps stop before rendering --------------------------------------------
for k in tokens ast scene; do
	run --dump-$k -o "$tmp/dump-$k.exr" $D/hello.scn
	want_rc 0; has out '.'
	[ ! -e "$tmp/dump-$k.exr" ] || why="${why:+$why; }an image was written"
	grep -q '^hello$' "$tmp/out" && [ "$k" != scene ] && why="${why:+$why; }--dump-$k ran #debug"
	report "--dump-$k prints its text and writes no image"
done

# ---- rendering and output files (skipped until the tracer renders) ----------
run --quiet --width 8 --height 6 -o "$tmp/probe.exr" $D/hello.scn
if [ "$rc" -ne 0 ] || [ ! -s "$tmp/probe.exr" ]; then
	for c in "-o out.exr writes the image" "-o out.png writes a PNG" "+Oout.png (POV-Ray switch)" \
		"default output: the scene name with .exr" "output in a missing directory: exit 73/74, no file" \
		"a failed render leaves no output file" "an unbounded mirror under a parallel light warns where it is" \
		"passes spectral in the scene renders without a warning" "--passes spectral renders without a warning" \
		"--passes rgb overrides a scene's passes spectral (three channel passes)" \
		"--passes spectral overrides the scene's rgb (one spectral pass)" \
		"--passes spectral with --method shaft warns that the spectral pass deposits points"; do
		skip "$c" "rendering not available yet"
	done
	why=
else
	why=
	run --quiet --width 8 --height 6 -o "$tmp/a.exr" $D/hello.scn
	want_rc 0; [ -s "$tmp/a.exr" ] || why="no $tmp/a.exr"
	head -c 4 "$tmp/a.exr" | od -An -tx1 | grep -q '76 2f 31 01' || why="${why:+$why; }a.exr is not OpenEXR"
	report "-o out.exr writes the image"

	run --quiet --width 8 --height 6 -o "$tmp/b.png" $D/hello.scn
	want_rc 0; head -c 8 "$tmp/b.png" 2>/dev/null | od -An -c | grep -q 'P   N   G' || why="${why:+$why; }b.png is not a PNG"
	report "-o out.png writes a PNG"

	run --quiet +W8 +H6 "+O$tmp/c.png" $D/hello.scn
	want_rc 0; [ -s "$tmp/c.png" ] || why="${why:+$why; }no c.png"
	report "+Oout.png (POV-Ray switch)"

	mkdir -p "$tmp/def" && cp $D/hello.scn "$tmp/def/scene.scn"
	(cd "$tmp/def" && timeout "$TIMEOUT" "$ARVO" --quiet --width 8 --height 6 scene.scn > /dev/null 2>&1)
	rc=$?; want_rc 0; [ -s "$tmp/def/scene.exr" ] || why="${why:+$why; }no scene.exr next to the scene"
	report "default output: the scene name with .exr"

	run --quiet --width 8 --height 6 -o "$tmp/missing/dir/x.exr" $D/hello.scn
	want_rc 73 74; has err '^arvo: error: .*missing/dir'
	[ ! -e "$tmp/missing/dir/x.exr" ] || why="${why:+$why; }file left behind"
	report "output in a missing directory: exit 73/74, no file"

	run --quiet --width 8 --height 6 -o "$tmp/bad.exr" $D/bad.scn
	want_rc 65; [ ! -e "$tmp/bad.exr" ] || why="${why:+$why; }bad.exr was written"
	report "a failed render leaves no output file"

	run --quiet --width 8 --height 6 --rays 20000 -o "$tmp/sun.exr" $D/sun_mirror.scn
	want_rc 0; [ -s "$tmp/sun.exr" ] || why="${why:+$why; }no sun.exr"
	is err "$D/sun_mirror.scn:5:1: warning: under a parallel light this unbounded plane casts caustics only around the finite objects and the camera
plane { x, 3 pigment { rgb 0 } finish { reflection 1 } }
^"
	report "an unbounded mirror under a parallel light warns where it is"

	run --width 8 --height 6 -o "$tmp/spectral.exr" $D/spectral.scn
	want_rc 0; [ -s "$tmp/spectral.exr" ] || why="${why:+$why; }no spectral.exr"; empty err; empty out
	report "passes spectral in the scene renders without a warning"

	run --passes spectral --rays 3000 --width 8 --height 6 -o "$tmp/prism.exr" tests/accuracy/prism.scn
	want_rc 0; [ -s "$tmp/prism.exr" ] || why="${why:+$why; }no prism.exr"; empty err; empty out
	report "--passes spectral renders without a warning"

	run --quiet --stats --passes rgb --width 8 --height 6 -o "$tmp/rgb.exr" $D/spectral.scn
	want_rc 0; has err '^arvo: light pass .*, 3 maps,'
	report "--passes rgb overrides a scene's passes spectral (three channel passes)"

	run --quiet --stats --passes spectral --rays 3000 --width 8 --height 6 -o "$tmp/sp.exr" tests/accuracy/prism.scn
	want_rc 0; has err '^arvo: light pass .*, 1 maps,'
	report "--passes spectral overrides the scene's rgb (one spectral pass)"

	run --passes spectral --method shaft --rays 3000 --width 8 --height 6 -o "$tmp/sh.exr" tests/accuracy/prism.scn
	want_rc 0; is err "arvo: warning: passes spectral: light rays of different wavelengths part ways, so the dispersive light pass deposits points, not shafts"
	report "--passes spectral with --method shaft warns that the spectral pass deposits points"
fi
exit 0
