#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: a render that fails after the scene was read (a broken image_map)
# leaves the earlier output of that name as it was: never half-written.
. tests/hostile/data/io-lib.sh "$@"
scene "$T/t.scn" 'image_map { png "t.png" }'
echo "garbage" > "$T/t.png"
for ext in exr png; do
	echo "earlier $ext" > "$T/out.$ext"
	run --quiet --width 8 --height 8 -o "$T/out.$ext" "$T/t.scn"
	want_rc 66
	same "$T/out.$ext" "earlier $ext"
done
no_temps "$T"
done_case "failed render keeps the earlier EXR and PNG as they were"
