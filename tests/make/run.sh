#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/make/run.sh: batch rendering (docs/farm.md). Runs
# stdlib-scenes/Makefile.example with make -j2 on a copy of the demo scenes
# plus two scenes with their own includes and image, at a tiny size and few
# light rays, and checks that a second run renders nothing and that touching
# one input re-renders exactly the images that read it (arvo -M). Then the
# farm paths of docs/farm.md: a frame range split over GNU Parallel jobs and
# over make -j gives the same frames, bit for bit, as one process rendering
# them in turn. One TAP line per case. Environment: ARVO (default ./arvo).
set -u
cd "$(dirname "$0")/../.." || exit 2
ARVO=${ARVO:-$PWD/arvo}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-make.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT INT TERM
n=0
# check NAME STATUS [DETAIL]: one TAP line.
check() {
	n=$((n + 1))
	if [ "$2" -eq 0 ]; then echo "ok $n - $1"; else echo "not ok $n - $1"; [ -n "${3:-}" ] && echo "$3" | sed 's/^/#   /'; fi
}

# The scene directory: the demos, t_a (t_a.inc, t_common.inc) and t_b
# (t_common.inc, t_b.png). A wrapper logs which image each arvo run renders.
S=$tmp/scenes
mkdir -p "$S"
cp stdlib-scenes/*.scn "$S/"
cp stdlib-scenes/Makefile.example "$S/Makefile"
cp tests/render/tex.png "$S/t_b.png"
printf '#declare Common = 0.6;\n' > "$S/t_common.inc"
printf '#declare Ball = 1;\n' > "$S/t_a.inc"
cat > "$S/t_a.scn" << 'SCN'
#include "t_common.inc"
#include "t_a.inc"
camera { location <0, 1, -4> look_at 0 }
light_source { <2, 5, -4>, rgb 100 }
sphere { 0, Ball pigment { rgb Common } }
SCN
cat > "$S/t_b.scn" << 'SCN'
#include "t_common.inc"
camera { location <0, 1, -4> look_at 0 }
light_source { <2, 5, -4>, rgb 100 }
plane { z, 1 pigment { image_map { png "t_b.png" } } }
sphere { 0, Common pigment { rgb 1 } }
SCN
cat > "$tmp/arvo" << SH
#!/bin/sh
for a; do case "\$a" in *.exr|*.png) echo "\$a" >> "$tmp/log"; break ;; esac; done
exec "$ARVO" "\$@"
SH
chmod +x "$tmp/arvo"
FLAGS="--width 24 --height 18 --rays 2000"
# mk: runs the example Makefile (-j2); the log lists the images rendered.
mk() {
	: > "$tmp/log"
	make -C "$S" -j2 --no-print-directory ARVO="$tmp/arvo" FLAGS="$FLAGS" FRAMES=3 "$@" > "$tmp/make.out" 2>&1
}
# rendered: the log's images, sorted, on one line.
rendered() { sed 's|.*/||' "$tmp/log" | LC_ALL=C sort | tr '\n' ' ' | sed 's/ $//'; }

mk; st=$?
scenes=$(cd "$S" && ls *.scn | sed 's/\.scn$//' | grep -v '^orbit$')
missing=
for s in $scenes; do for e in exr png; do [ -s "$S/out/$s.$e" ] || missing="$missing $s.$e"; done; done
for f in 0001 0002 0003; do [ -s "$S/out/orbit/orbit.$f.png" ] || missing="$missing orbit.$f.png"; done
[ "$st" -eq 0 ] && [ -z "$missing" ] && [ "$(wc -l < "$tmp/log")" -eq $(($(echo $scenes | wc -w) + 3)) ]
check "make -j2: every demo (EXR and PNG from one render each) and three animation frames" $? \
	"status $st; missing:$missing; $(tail -5 "$tmp/make.out")"

[ -z "$(find "$S/out" -name '*.tmp*')" ]; check "no temporary files left in out/" $?

mk; st=$?
[ "$st" -eq 0 ] && [ ! -s "$tmp/log" ] && grep -q "Nothing to be done" "$tmp/make.out"
check "a second make renders nothing" $? "$(rendered)"

make -C "$S" -q ARVO="$tmp/arvo" FLAGS="$FLAGS" FRAMES=3 > /dev/null 2>&1
check "make -q: everything up to date" $?

touch "$S/t_a.inc"; mk
[ "$(rendered)" = "t_a.exr" ]; check "touching t_a.inc re-renders only t_a" $? "rendered: $(rendered)"

touch "$S/t_common.inc"; mk
[ "$(rendered)" = "t_a.exr t_b.exr" ]; check "touching t_common.inc re-renders t_a and t_b only" $? "rendered: $(rendered)"

touch "$S/t_b.png"; mk
[ "$(rendered)" = "t_b.exr" ]; check "touching an image_map file re-renders the scene that reads it" $? "rendered: $(rendered)"

touch "$S/orbit.scn"; mk
[ "$(rendered)" = "orbit.%04d.png orbit.%04d.png orbit.%04d.png" ]
check "touching the animation's scene re-renders its three frames, nothing else" $? "rendered: $(rendered)"

rm "$S/out/demo.png"; mk
[ "$(rendered)" = "demo.exr" ] && [ -s "$S/out/demo.png" ]
check "a deleted PNG is made again by its one render" $? "rendered: $(rendered)"

rm "$S/t_a.inc"; sed -i '/t_a.inc/d; s/Ball/1/' "$S/t_a.scn"; mk; st=$?
[ "$st" -eq 0 ] && [ "$(rendered)" = "t_a.exr" ]
check "an include removed from the scene and the disk: no make error (phony targets, -MP)" $? "status $st; $(tail -3 "$tmp/make.out")"

# ---- farm paths (docs/farm.md) ------------------------------------------------
F=$tmp/farm
mkdir -p "$F/loop" "$F/par" "$F/make"
# the same scene path everywhere: the EXR header records it
scn=$PWD/stdlib-scenes/orbit.scn
"$ARVO" -q $FLAGS --frames 1:4 -o "$F/loop/f.%04d.exr" "$scn" > "$tmp/farm.log" 2>&1
check "one process renders --frames 1:4 in turn" $? "$(cat "$tmp/farm.log")"

if command -v parallel > /dev/null 2>&1; then
	parallel -j2 --halt now,fail=1 "$ARVO" -q $FLAGS --frames 1:4 --subset {}:{} -o "$F/par/f.%04d.exr" \
		"$scn" ::: 1 2 3 4 > "$tmp/farm.log" 2>&1
	st=$?
	same=0
	for f in 0001 0002 0003 0004; do cmp -s "$F/loop/f.$f.exr" "$F/par/f.$f.exr" || same=1; done
	[ "$st" -eq 0 ] && [ "$same" -eq 0 ]
	check "GNU Parallel, one job per frame (--subset N:N): the same frames bit for bit" $? "status $st; $(head -3 "$tmp/farm.log")"
else
	n=$((n + 1)); echo "ok $n - GNU Parallel farm # SKIP parallel is not installed (make deps)"
fi

cat > "$F/make/Makefile" << MK
FRAMES := 0001 0002 0003 0004
all: \$(FRAMES:%=f.%.exr)
f.%.exr: $scn
	"$ARVO" -q $FLAGS --frames 1:4 --subset \$*:\$* -o f.%04d.exr \$<
MK
make -C "$F/make" -j2 > "$tmp/farm.log" 2>&1; st=$?
same=0
for f in 0001 0002 0003 0004; do cmp -s "$F/loop/f.$f.exr" "$F/make/f.$f.exr" || same=1; done
[ "$st" -eq 0 ] && [ "$same" -eq 0 ]
check "make -j2, one rule per frame: the same frames bit for bit" $? "status $st; $(tail -3 "$tmp/farm.log")"

echo "1..$n"
exit 0
