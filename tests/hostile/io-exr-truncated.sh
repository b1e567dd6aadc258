#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: an EXR image_map cut short in its header and in its pixels.
. tests/hostile/data/io-lib.sh "$@"
scene "$T/s.scn"
run --quiet --width 32 --height 32 -o "$T/good.exr" "$T/s.scn"
[ "$rc" -eq 0 ] || why="could not make the EXR (exit $rc)"
scene "$T/t.scn" 'image_map { exr "t.exr" }'
size=$(wc -c < "$T/good.exr")
for n in 4 20 100 400 $((size / 2)) $((size - 1)); do
	head -c "$n" "$T/good.exr" > "$T/t.exr"
	run --quiet --width 8 --height 8 -o "$T/out.exr" "$T/t.scn"
	want_rc 66
	case $(head -n 1 "$T/.err") in
	"$T/t.scn:3:37: error: cannot read image file 't.exr': "*) ;;
	*) why="${why:+$why; }cut at $n: unexpected first stderr line" ;;
	esac
	absent "$T/out.exr"
done
done_case "truncated EXR image_map: exit 66 at the image_map"
