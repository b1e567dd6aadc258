#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: an output name that is an existing directory: exit 73 before any work.
. tests/hostile/data/io-lib.sh "$@"
scene "$T/s.scn"
mkdir "$T/out.exr"
run --quiet --width 8 --height 8 -o "$T/out.exr" "$T/s.scn"
want_rc 73
want_err "arvo: error: cannot create '\$T/out.exr': Is a directory"
[ -d "$T/out.exr" ] || why="${why:+$why; }the directory was replaced"
[ ! -s "$T/.out" ] || why="${why:+$why; }the scene was read (stdout not empty)"
done_case "output that is a directory: exit 73"
