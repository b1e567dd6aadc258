#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: an empty image file, and a text file named .png.
. tests/hostile/data/io-lib.sh "$@"
scene "$T/t.scn" 'image_map { png "t.png" }'
: > "$T/t.png"
run --quiet --width 8 --height 8 -o "$T/out.exr" "$T/t.scn"
want_rc 66
want_err "\$T/t.scn:3:37: error: cannot read image file 't.png': empty file"
echo "not an image at all" > "$T/t.png"
run --quiet --width 8 --height 8 -o "$T/out.exr" "$T/t.scn"
want_rc 66
want_err "\$T/t.scn:3:37: error: cannot read image file 't.png': not a PNG or OpenEXR image"
absent "$T/out.exr"
done_case "empty and foreign image_map files: exit 66 with the reason"
