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
. tests/tap.sh

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
want_rc 0; has out '^hello$'; report "-D without NAME=VALUE is POV-Ray's display off: ignored"

run +SR10 +ER20 --check $D/hello.scn
want_rc 64; has err "^arvo: error: POV-Ray's partial render switches .* arvo renders the whole image"; report "+SR/+ER: exit 64 naming what arvo does"

run render.ini --check $D/hello.scn
want_rc 64; has err '^arvo: error: POV-Ray INI files are not read .*render.ini.*--width 640'; report "an INI file: exit 64 naming the options"

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

run -D N=1e-310 --check $D/defines.scn
want_rc 0; has out '^N=0.00 '; report "-D takes a number too small for a normal double, as #declare does"

run -D clock=7 --check $D/defines.scn
want_rc 64; is err "arvo: error: bad declaration 'clock=7': 'clock' is a built-in name and cannot be declared (see --clock)
(see 'arvo --help')"; empty out; report "-D of a built-in name: exit 64, as #declare refuses it"

run -D sphere=1 --check $D/defines.scn
want_rc 64; has err "^arvo: error: bad declaration 'sphere=1': 'sphere' is a reserved word and cannot be declared$"
report "-D of a reserved word: exit 64"

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
want_rc 66; has err "^$D/needs_inc.scn:2:1: error: cannot find include file .cli_only.inc.$"; report "include not found without -I: exit 66 with location"

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

	run --quiet --width 8 --height 6 -o "$tmp/spectral.exr" $D/spectral.scn
	want_rc 0; [ -s "$tmp/spectral.exr" ] || why="${why:+$why; }no spectral.exr"; empty err; empty out
	report "passes spectral in the scene renders without a warning"

	run --quiet --passes spectral --rays 3000 --width 8 --height 6 -o "$tmp/prism.exr" tests/accuracy/prism.scn
	want_rc 0; [ -s "$tmp/prism.exr" ] || why="${why:+$why; }no prism.exr"; empty err; empty out
	report "--passes spectral renders without a warning"

	run --quiet --stats --passes rgb --width 8 --height 6 -o "$tmp/rgb.exr" $D/spectral.scn
	want_rc 0; has err '^arvo: light pass .*, 3 maps,'
	report "--passes rgb overrides a scene's passes spectral (three channel passes)"

	run --quiet --stats --passes spectral --rays 3000 --width 8 --height 6 -o "$tmp/sp.exr" tests/accuracy/prism.scn
	want_rc 0; has err '^arvo: light pass .*, 1 maps,'
	report "--passes spectral overrides the scene's rgb (one spectral pass)"

	run --quiet --passes spectral --method shaft --rays 3000 --width 8 --height 6 -o "$tmp/sh.exr" tests/accuracy/prism.scn
	want_rc 0; is err "arvo: warning: passes spectral: light rays of different wavelengths part ways, so the dispersive light pass deposits points, not shafts"
	report "--passes spectral with --method shaft warns that the spectral pass deposits points"
fi

# ---- animation: --frames, POV-Ray's +KFI +KFF +KI +KF, --subset --------------
run --check --frames 0:2 $D/anim.scn
want_rc 0; is out "f=0 clock=0.000 on=1 delta=0.500
range=0:2 clocks=0.00:1.00
f=1 clock=0.500 on=1 delta=0.500
range=0:2 clocks=0.00:1.00
f=2 clock=1.000 on=1 delta=0.500
range=0:2 clocks=0.00:1.00"; empty err
report "--frames 0:2: the scene evaluated per frame, clock 0 to 1, clock_on 1 from frame 0"

run --check +KFI1 +KFF3 +KI2 +KF4 $D/anim.scn
want_rc 0; has out '^f=1 clock=2.000 on=1 delta=1.000$'; has out '^f=3 clock=4.000 on=1 delta=1.000$'
has out '^range=1:3 clocks=2.00:4.00$'; report "+KFI1 +KFF3 +KI2 +KF4: clock from 2 to 4 over frames 1 to 3"

run --check --frames 1:10 --subset 3:4 $D/anim.scn
want_rc 0; is out "f=3 clock=0.222 on=1 delta=0.111
range=1:10 clocks=0.00:1.00
f=4 clock=0.333 on=1 delta=0.111
range=1:10 clocks=0.00:1.00"; report "--subset 3:4 of --frames 1:10: the full range's clock"

run --check +KFF4 +SF4 +EF4 $D/anim.scn
want_rc 0; has out '^f=4 clock=1.000 on=1 delta=0.333$'; report "+KFF4 +SF4 +EF4: only the last frame (POV-Ray's defaults: first frame 1)"

run --check $D/anim.scn
want_rc 0; has out '^f=0 clock=0.000 on=0 delta=0.000$'; has out '^range=0:0 clocks=0.00:0.00$'
report "no animation: clock_on 0, the range constants 0"

run --check --clock 0 $D/anim.scn
want_rc 0; has out '^f=0 clock=0.000 on=1 '; report "--clock 0 sets clock_on (POV-Ray's +K0)"

run --check --frames 3:1 $D/anim.scn
want_rc 64; is err "arvo: error: bad value for --frames: '3:1' (expected FIRST:LAST, 0 <= FIRST <= LAST)
(see 'arvo --help')"; report "--frames 3:1: exit 64"
run --check --subset 1:2 $D/anim.scn
want_rc 64; has err "^arvo: error: --subset .*needs a frame range"; report "--subset without a range: exit 64"
run --check --frames 1:4 --subset 2:7 $D/anim.scn
want_rc 64; has err "^arvo: error: --subset 2:7 is not inside --frames 1:4$"; report "--subset outside the range: exit 64"
run --check --frames 1:4 --clock 0.5 $D/anim.scn
want_rc 64; has err "^arvo: error: --clock and --frame cannot be combined"; report "--clock with --frames: exit 64"
run --frames 1:2 -o "$tmp/bad.%x.exr" $D/anim.scn
want_rc 64; has err "^arvo: error: bad frame pattern in '.*bad.%x.exr'"; [ ! -e "$tmp/bad.%x.exr" ] || why="a file"
report "a bad frame pattern: exit 64 before any work"
run --frames 1:2 --save-maps "$tmp/s.maps" -o "$tmp/s.%d.exr" $D/anim.scn
want_rc 64; has err "^arvo: error: --save-maps '.*s.maps' would be overwritten by every frame"
report "--save-maps without a pattern over several frames: exit 64"

run --quiet --width 8 --height 6 --rays 0 --frames 1:3 -o "$tmp/an.%03d.exr" $D/anim.scn
want_rc 0; empty err
for f in 001 002 003; do [ -s "$tmp/an.$f.exr" ] || why="${why:+$why; }no an.$f.exr"; done
cmp -s "$tmp/an.001.exr" "$tmp/an.003.exr" && why="${why:+$why; }frames 1 and 3 are the same image"
report "--frames 1:3 -o an.%03d.exr: three frames, each its own image"

run --quiet --width 8 --height 6 --rays 0 --clock 1 -o "$tmp/k1.exr" $D/anim.scn
want_rc 0; cmp -s "$tmp/k1.exr" "$tmp/an.003.exr" || why="frame 3 of 1:3 differs from --clock 1"
report "the last frame of --frames 1:3 is the render at --clock 1"

run --quiet --width 8 --height 6 --rays 0 --frames 1:10 --subset 9:10 -o "$tmp/pov.png" $D/anim.scn
want_rc 0; [ -s "$tmp/pov09.png" ] && [ -s "$tmp/pov10.png" ] || why="no pov09.png and pov10.png"
report "a frame range without a pattern: POV-Ray's numbering (pov09.png, pov10.png)"

run --width 8 --height 6 --rays 0 --frames 1:2 -o "$tmp/msg.%d.exr" $D/anim.scn
want_rc 0; has err "^arvo: frame 1 \(1 to 2\), clock 0: .*msg.1.exr$"; has err "^arvo: frame 2 \(1 to 2\), clock 1: .*msg.2.exr$"
report "each frame is announced on stderr (not under --quiet)"

# ---- several outputs from one render ------------------------------------------
run --width 16 --height 12 --rays 0 -o "$tmp/two.exr" -o "$tmp/two.png" $D/hello.scn
want_rc 0; [ -s "$tmp/two.exr" ] && [ -s "$tmp/two.png" ] || why="both files not written"
[ "$(grep -c '^arvo: progress: eye pass done' "$tmp/err")" -eq 1 ] || why="${why:+$why; }not exactly one eye pass"
report "-o a.exr -o a.png: one render, two files"
run --quiet --width 16 --height 12 --rays 0 -o "$tmp/one.exr" $D/hello.scn
cmp -s "$tmp/one.exr" "$tmp/two.exr" || why="the EXR differs from a render with one -o"
run --quiet --width 16 --height 12 --rays 0 -o "$tmp/one.png" $D/hello.scn
cmp -s "$tmp/one.png" "$tmp/two.png" || why="${why:+$why; }the PNG differs from a render with one -o"
report "several outputs hold the same pixels as separate renders"
run --width 16 --height 12 -o "$tmp/x.exr" -o "$tmp/x.tif" $D/hello.scn
want_rc 64; has err "^arvo: error: unknown output format .*x.tif"; [ ! -e "$tmp/x.exr" ] || why="${why:+$why; }x.exr written"
report "an unknown format among several outputs: exit 64 before any work"

# ---- -M: every file the render read -------------------------------------------
DD=$D/deps
# deps_line FILE: the first rule of a depfile on one line
deps_line() { sed -n '1,/[^\\]$/p' "$1" | tr -d '\\\n' | tr -s ' '; }
run --quiet --width 8 --height 6 --rays 0 -M "$tmp/d.d" -o "$tmp/d.exr" -o "$tmp/d.png" $DD/deps.scn
want_rc 0
deps_line "$tmp/d.d" | grep -q "^$tmp/d.exr $tmp/d.png: $DD/deps.scn " || why="targets and the scene first: $(deps_line "$tmp/d.d")"
for f in "$(cd $DD && pwd -P)/part.inc" "$(cd $DD && pwd -P)/tex.png" "$(cd stdlib-scenes/ocio && pwd -P)/config.ocio"; do
	grep -q "^$f:\$" "$tmp/d.d" || why="${why:+$why; }no phony target for $f"
	deps_line "$tmp/d.d" | grep -q " $f\( \|\$\)" || why="${why:+$why; }$f not a prerequisite"
done
grep -q "^$DD/deps.scn:" "$tmp/d.d" && why="${why:+$why; }a phony target for the scene"
report "-M names the scene, its include, its image_map and the OCIO config (PNG), with phony targets"

run --quiet --width 8 --height 6 --rays 0 -M "$tmp/e.d" -o "$tmp/e.exr" $D/hello.scn
want_rc 0; is e.d "$tmp/e.exr: $D/hello.scn"
report "-M for an EXR of a scene that reads nothing else: one line, no OCIO config"

run --quiet --width 8 --height 6 --rays 20000 --save-maps "$tmp/g.maps" -o "$tmp/g.exr" tests/render/g_glass.scn
run --quiet --width 8 --height 6 --load-maps "$tmp/g.maps" -M "$tmp/g.d" -o "$tmp/g2.exr" tests/render/g_glass.scn
want_rc 0; grep -q "^$tmp/g.maps:\$" "$tmp/g.d" || why="no $tmp/g.maps in: $(cat "$tmp/g.d")"
report "-M names the --load-maps file"

run --quiet --check --frames 1:2 -M "$tmp/f.d" -o "$tmp/f.%d.exr" $D/anim.scn
want_rc 0; is f.d "$tmp/f.1.exr $tmp/f.2.exr: $D/anim.scn"
report "-M with a frame range: every frame's file is a target"

run --quiet --check -M "$tmp/sp.d" -o "$tmp/a b\$c.exr" $D/hello.scn
want_rc 0; is sp.d "$tmp/a\\ b\$\$c.exr: $D/hello.scn"
report "-M escapes spaces and dollars for make"

run --check -M "$tmp/nd.d" $D/needs_inc.scn
want_rc 66; [ ! -e "$tmp/nd.d" ] || why="a depfile for a failed scene"; report "-M writes nothing when the scene fails"
exit 0
