#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: a PNG image_map cut short (a real PNG that arvo wrote, truncated
# at several lengths): each exits 66 at the image_map, no crash, no output.
. tests/hostile/data/io-lib.sh "$@"
scene "$T/s.scn"
run --quiet --width 32 --height 32 -o "$T/good.png" "$T/s.scn"
[ "$rc" -eq 0 ] || why="could not make the PNG (exit $rc)"
scene "$T/t.scn" 'image_map { png "t.png" }'
for n in 9 33 60 100 $(($(wc -c < "$T/good.png") - 1)); do
	head -c "$n" "$T/good.png" > "$T/t.png"
	run --quiet --width 8 --height 8 -o "$T/out.exr" "$T/t.scn"
	want_rc 66
	want_err "\$T/t.scn:3:37: error: cannot read image file 't.png': the file ends early (truncated)"
	absent "$T/out.exr"
done
done_case "truncated PNG image_map: exit 66 at the image_map"
