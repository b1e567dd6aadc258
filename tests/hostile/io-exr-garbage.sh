#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: the EXR magic number then garbage; a real EXR with its pixel
# chunks overwritten by random bytes.
. tests/hostile/data/io-lib.sh "$@"
scene "$T/s.scn"
run --quiet --width 32 --height 32 --compression none -o "$T/good.exr" "$T/s.scn"
scene "$T/t.scn" 'image_map { exr "t.exr" }'
{ printf 'v/1\001\002\000\000\000'; head -c 3000 /dev/urandom; } > "$T/t.exr"
run --quiet --width 8 --height 8 -o "$T/out.exr" "$T/t.scn"
want_rc 66
size=$(wc -c < "$T/good.exr")
{ head -c 1200 "$T/good.exr"; head -c $((size - 1200)) /dev/urandom; } > "$T/t.exr"
run --quiet --width 8 --height 8 -o "$T/out.exr" "$T/t.scn"
[ "$rc" -eq 0 ] || [ "$rc" -eq 66 ] || why="${why:+$why; }overwritten chunks: exit $rc, expected 0 or 66"
absent "$T/out.exr.tmp"
no_temps "$T"
done_case "garbage EXR image_map: exit 66, never a crash"
