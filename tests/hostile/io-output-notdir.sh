#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: an output path through a regular file: exit 73 before the scene
# is read (its #debug line must not appear).
. tests/hostile/data/io-lib.sh "$@"
scene "$T/s.scn"
echo '#debug "read\n"' >> "$T/s.scn"
echo plain > "$T/file"
run --quiet --width 8 --height 8 -o "$T/file/out.exr" "$T/s.scn"
want_rc 73
want_err "arvo: error: cannot create '\$T/file/out.exr': Not a directory"
[ ! -s "$T/.out" ] || why="${why:+$why; }the scene was read before the check"
done_case "output under a regular file: exit 73 before any work"
