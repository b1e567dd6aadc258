#!/bin/sh
# SPDX-License-Identifier: MIT
# bench/eye/kernel.sh: the ray kernel alone against Embree's own best, on
# the camera rays of bench/eye's sphere scenes and on the shadow rays the
# eye pass casts from their hits (kernel.c says what each column times).
# One thread; every figure is the best of 5 passes.
#
#   sh bench/eye/kernel.sh          (about a minute; builds libarvo.a first)
#
# SIZES (default 1000 100000 1000000) and SCENES (spheres grid) choose the
# runs; LIBARVO=path/libarvo.a skips the build. Writes
# bench/results/kernel.csv (scene,spheres,rays,arvo_rays_per_s,
# points_rays_per_s,user_rays_per_s,agree,shadow_rays,arvo_shadow_per_s,
# points_shadow_per_s,user_shadow_per_s,arvo_mix_per_s,points_mix_per_s,
# user_mix_per_s) and kernel.txt:
#   arvo    arvo's hierarchy and callbacks as the eye pass traces camera
#           rays (packets) and shadow rays (one by one, any hit)
#   points  Embree with native sphere points (float)
#   user    Embree with user geometry and a float sphere test
#   agree   pixels where points and arvo hit the same sphere (or both miss)
#   *_shadow_per_s  the shadow rays alone
#   *_mix_per_s     camera and shadow rays together: the eye pass's ray mix
#           (its rays/s counts both), with no shading: the most each kernel
#           lets the eye pass reach
set -eu

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
res=$root/bench/results
BUILD=${BUILD:-build/release}
SIZES=${SIZES:-1000 100000 1000000}
SCENES=${SCENES:-spheres grid}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-bench-kernel.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
mkdir -p "$res"

cd "$root"
if [ -z "${LIBARVO:-}" ]; then
	make -s BUILD="$BUILD" "$BUILD/libarvo.a" > /dev/null
	LIBARVO=$root/$BUILD/libarvo.a
fi
WARN="-Wall -Wextra -Wpedantic -Wshadow -Wundef -Wpointer-arith -Wcast-align -Wwrite-strings
 -Wmissing-prototypes -Wstrict-prototypes -Wmissing-declarations -Wformat=2 -Wvla -Wold-style-definition"
PKG_CFLAGS=$(pkg-config --cflags OpenEXR OpenColorIO libpng freetype2)
PKG_LIBS=$(pkg-config --libs OpenEXR OpenColorIO libpng freetype2)
# shellcheck disable=SC2086
cc -std=c11 -O2 $WARN -pthread -D_DEFAULT_SOURCE $PKG_CFLAGS -o "$tmp/kernel" \
	"$here/kernel.c" "$LIBARVO" $PKG_LIBS -lembree3 -lstdc++ -lm -pthread

kv() { tr ' ' '\n' < "$2" | awk -F= -v k="$1" '$1 == k { print $2 }'; }
csv=$res/kernel.csv
cols="spheres rays arvo_rays_per_s points_rays_per_s user_rays_per_s agree shadow_rays arvo_shadow_per_s
 points_shadow_per_s user_shadow_per_s arvo_mix_per_s points_mix_per_s user_mix_per_s"
echo "scene,$(echo $cols | tr ' ' ',')" > "$csv"
for sc in $SCENES; do
	for n in $SIZES; do
		"$tmp/kernel" "$here/$sc.scn" "$n" > "$tmp/k.out"
		line=$sc
		for k in $cols; do
			line="$line,$(kv "$k" "$tmp/k.out")"
		done
		echo "$line" >> "$csv"
		tail -1 "$csv"
	done
done
{
	echo "bench/eye/kernel.sh: camera rays and their shadow rays, 640x480, 1 thread, best of 5 passes"
	echo "cpu: $(awk -F': ' '/model name/ { print $2; exit }' /proc/cpuinfo), $(nproc) online"
	echo "load average at the end: $(cut -d" " -f1-3 /proc/loadavg)"
	column -s, -t < "$csv"
} > "$res/kernel.txt"
cat "$res/kernel.txt"
