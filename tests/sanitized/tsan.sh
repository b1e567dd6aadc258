#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/sanitized/tsan.sh: the threaded passes under ThreadSanitizer (make
# check-tsan builds $TSAN_BUILD, default build/$MODE-tsan): renders with the
# light pass, the tolerance loop and the eye pass on two and three threads.
# Any report fails the case.
set -u
cd "$(dirname "$0")/../.." || exit 2
TSAN_BUILD=${TSAN_BUILD:-build/${MODE:-release}-tsan}
ARVO=$TSAN_BUILD/arvo
export TSAN_OPTIONS="halt_on_error=1:exitcode=99:suppressions=$PWD/tests/sanitized/tsan.supp"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-tsan.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
n=0
render() {
	name=$1
	shift
	n=$((n + 1))
	"$ARVO" --quiet -o "$tmp/out.exr" "$@" > "$tmp/log" 2>&1
	rc=$?
	if [ "$rc" -eq 0 ] && [ -s "$tmp/out.exr" ] && ! grep -q 'ThreadSanitizer' "$tmp/log"; then
		echo "ok $n - tsan: $name"
	else
		echo "not ok $n - tsan: $name: exit status $rc"
		sed 's/^/#   /' "$tmp/log" | head -30
	fi
	rm -f "$tmp/out.exr"
}
render "glass, shafts, 2 threads" --threads 2 --width 32 --height 24 --rays 20000 tests/render/g_glass.scn
render "glass, points, 3 threads" --threads 3 --width 32 --height 24 --rays 20000 --method point tests/render/g_glass.scn
render "lights, spp 2, 2 threads" --threads 2 --width 32 --height 24 --rays 5000 --spp 2 tests/render/g_lights.scn
render "spectral, 2 threads" --threads 2 --width 24 --height 18 --rays 20000 --passes spectral tests/cli/data/spectral.scn
render "tolerance, 2 threads" --threads 2 --width 24 --height 18 --tolerance 0.2 tests/cli/data/sun_mirror.scn
render "mirror, 2 threads" --threads 2 --width 32 --height 24 --rays 20000 tests/render/mirror_a.scn
render "glass, 300000 rays, 64x48, 2 threads" --threads 2 --width 64 --height 48 --rays 300000 tests/render/g_glass.scn
render "fig3 lenses, 2 threads" --threads 2 --width 48 --height 36 --rays 200000 stdlib-scenes/fig3-lenses.scn
# several EXR chunks and OCIO chunks, each compressed or transformed on its own thread
render "EXR and PNG output, 200x120, 2 threads" --threads 2 --width 200 --height 120 --rays 0 -o "$tmp/out.png" \
	tests/render/g_lights.scn
