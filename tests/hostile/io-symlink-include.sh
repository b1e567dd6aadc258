#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: symlinks a user placed inside allowed directories may point
# anywhere (a symlinked -I directory, a symlinked include file, a symlinked
# image), but '..' through a symlink cannot escape: "link/.." is the
# directory holding the link, not the parent of its target.
. tests/hostile/data/io-lib.sh "$@"
mkdir "$T/scenes" "$T/elsewhere" "$T/elsewhere/deep" "$T/libs"
echo '#declare FromLink = 3;' > "$T/elsewhere/real.inc"
echo '#declare Deep = 4;' > "$T/elsewhere/deep/d.inc"
ln -s "$T/elsewhere" "$T/libs/linked"        # a symlinked include directory
ln -s "$T/elsewhere/real.inc" "$T/scenes/near.inc"  # a symlinked include file
printf '#include "near.inc"\n#include "linked/deep/d.inc"\n#debug concat(str(FromLink + Deep, 0, 0), "\\n")\n' > "$T/scenes/a.scn"
run --check -I "$T/libs" "$T/scenes/a.scn"
want_rc 0
[ "$(cat "$T/.out")" = 7 ] || why="${why:+$why; }symlinked includes: stdout is not 7"
printf '#include "deep/d.inc"\n#debug concat(str(Deep, 0, 0), "\\n")\n' > "$T/scenes/c.scn"
run --check -I "$T/libs/linked" "$T/scenes/c.scn"   # -I names the symlink itself
want_rc 0
[ "$(cat "$T/.out")" = 4 ] || why="${why:+$why; }symlinked -I: stdout is not 4"
# "linked/../.." leads to $T lexically: outside libs and scenes
printf '#include "linked/../../elsewhere/real.inc"\n' > "$T/scenes/b.scn"
run --check -I "$T/libs" "$T/scenes/b.scn"
want_rc 65
# an image reached through a symlinked directory renders
scene "$T/s.scn"
run --quiet --width 16 --height 16 -o "$T/elsewhere/tex.png" "$T/s.scn"
scene "$T/scenes/img.scn" 'image_map { png "linked/tex.png" }'
ln -s "$T/elsewhere" "$T/scenes/linked"
run --quiet --width 8 --height 8 -o "$T/img.exr" "$T/scenes/img.scn"
want_rc 0
[ -s "$T/img.exr" ] || why="${why:+$why; }no image rendered through a symlinked directory"
done_case "symlinked include directories, files and images work; '..' through them does not escape"
