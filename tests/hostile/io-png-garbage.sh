#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: PNG signature followed by binary garbage, and a PNG whose pixel
# data is corrupted: exit 66 at the image_map, never a crash.
. tests/hostile/data/io-lib.sh "$@"
scene "$T/s.scn"
run --quiet --width 32 --height 32 -o "$T/good.png" "$T/s.scn"
scene "$T/t.scn" 'image_map { png "t.png" }'
{ printf '\211PNG\r\n\032\n'; head -c 4000 /dev/urandom; } > "$T/t.png"
run --quiet --width 8 --height 8 -o "$T/out.exr" "$T/t.scn"
want_rc 66
case $(head -n 1 "$T/.err") in
"$T/t.scn:3:37: error: cannot read image file 't.png': "*) ;;
*) why="${why:+$why; }garbage: unexpected first stderr line" ;;
esac
# corrupt the IDAT data of a real PNG (bytes 60.. of a 32x32 PNG) with 0xff
size=$(wc -c < "$T/good.png")
{ head -c 60 "$T/good.png"; head -c $((size - 72)) /dev/zero | tr '\0' '\377'; tail -c 12 "$T/good.png"; } > "$T/t.png"
run --quiet --width 8 --height 8 -o "$T/out.exr" "$T/t.scn"
want_rc 66
absent "$T/out.exr"
done_case "garbage and corrupted PNG image_map: exit 66"
