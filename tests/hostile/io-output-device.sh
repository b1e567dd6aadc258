#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: an output name that leads to a device (a symlink to /dev/null)
# is refused before any work: a rename would replace the link, and writing
# through it is not an image.
. tests/hostile/data/io-lib.sh "$@"
scene "$T/s.scn"
ln -s /dev/null "$T/out.exr"
run --quiet --width 8 --height 8 -o "$T/out.exr" "$T/s.scn"
want_rc 73
want_err "arvo: error: cannot create '\$T/out.exr': not a regular file"
[ -L "$T/out.exr" ] || why="${why:+$why; }the symlink was replaced"
done_case "output that is a device: exit 73 before any work"
