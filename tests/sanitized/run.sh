#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/sanitized/run.sh: the subset make check runs against an ASan + UBSan
# build ($SAN_BUILD, default build/$MODE-san, built by make check): the
# hostile-input suite, the fuzz regression replay and small renders with the
# light pass on two threads. A sanitizer report or a leak fails the case.
# Under `make check SANITIZE=...` every suite is sanitized already: nothing
# to add. tests/sanitized/tsan.sh is the ThreadSanitizer run (make check-tsan).
set -u
cd "$(dirname "$0")/../.." || exit 2
if [ -n "${SANITIZE:-}" ]; then
	echo "ok - sanitized subset # SKIP every suite runs under SANITIZE=$SANITIZE already"
	exit 0
fi
SAN_BUILD=${SAN_BUILD:-build/${MODE:-release}-san}
if [ ! -x "$SAN_BUILD/arvo" ]; then
	echo "not ok - sanitized: no ASan build at $SAN_BUILD (make check builds it)"
	exit 0
fi
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:exitcode=99
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1:exitcode=99
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-san.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM

# The suites, prefixed so their lines read as this suite's.
if [ -f tests/hostile/run.sh ]; then
	ARVO=$PWD/$SAN_BUILD/arvo TIMEOUT=60 sh tests/hostile/run.sh | sed -e 's/^ok [0-9]* - /ok - san: hostile: /' \
		-e 's/^not ok [0-9]* - /not ok - san: hostile: /'
fi
BUILD=$SAN_BUILD sh tests/fuzz/run.sh | sed -e 's/^ok - /ok - san: /' -e 's/^not ok - /not ok - san: /'

# render NAME ARGS...: a render that must exit 0 with an image and no report.
render() {
	name=$1
	shift
	"$SAN_BUILD/arvo" --quiet --threads 2 -o "$tmp/out.exr" "$@" > "$tmp/log" 2>&1
	rc=$?
	if [ "$rc" -eq 0 ] && [ -s "$tmp/out.exr" ] && ! grep -q -E 'Sanitizer|runtime error' "$tmp/log"; then
		echo "ok - san: render $name"
	else
		echo "not ok - san: render $name: exit status $rc"
		sed 's/^/#   /' "$tmp/log" | head -20
	fi
	rm -f "$tmp/out.exr"
}
render hello --width 32 --height 24 --rays 2000 tests/cli/data/hello.scn
render glass --width 32 --height 24 --rays 20000 tests/render/g_glass.scn
render spectral --width 24 --height 18 --rays 20000 --passes spectral tests/cli/data/spectral.scn
render texture --width 32 --height 24 --rays 0 --spp 2 tests/render/flags.scn
