#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: maps saved for one scene loaded into another, and an image file
# given as a map file: exit 66, before the eye pass writes anything.
. tests/hostile/data/io-lib.sh "$@"
caustic "$T/c.scn"
run --quiet --width 16 --height 12 --rays 20000 --save-maps "$T/c.maps" -o "$T/c.exr" "$T/c.scn"
[ "$rc" -eq 0 ] || why="could not save maps (exit $rc)"
scene "$T/s.scn"
run --quiet --width 16 --height 12 --load-maps "$T/c.maps" -o "$T/out.exr" "$T/s.scn"
want_rc 66
want_err "arvo: error: '\$T/c.maps' was saved for another scene: the objects, lights or settings differ (save the maps again with --save-maps)"
absent "$T/out.exr"
run --quiet --width 16 --height 12 --load-maps "$T/c.exr" -o "$T/out.exr" "$T/c.scn"
want_rc 66
want_err "arvo: error: '\$T/c.exr' is not an arvo map file"
absent "$T/out.exr"
done_case "foreign map files (another scene's, an EXR): exit 66"
