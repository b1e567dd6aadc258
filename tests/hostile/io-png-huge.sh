#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: a 41-byte PNG whose header claims 30000x30000 RGBA (3.6 GB of
# floats): refused from the header (exit 66) before any pixel is allocated.
. tests/hostile/data/io-lib.sh "$@"
scene "$T/t.scn" 'image_map { png "t.png" }'
# signature, IHDR 30000x30000 8-bit RGBA with its CRC, then an empty IDAT header
printf '\211PNG\r\n\032\n\000\000\000\015IHDR\000\000\165\060\000\000\165\060\010\006\000\000\000\146\047\370\272\000\000\000\000IDAT' > "$T/t.png"
run --quiet --width 8 --height 8 -o "$T/out.exr" "$T/t.scn"
want_rc 66
want_err "\$T/t.scn:3:37: error: cannot read image file 't.png': image too large (more than 2^28 samples)"
absent "$T/out.exr"
done_case "PNG header claiming 30000x30000: exit 66 before allocating"
