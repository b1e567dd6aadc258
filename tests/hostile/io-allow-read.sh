#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: files beside the scene's directory: refused by default (with the
# option that grants them named), granted by --allow-read, by path or by
# an absolute name; an -I directory grants too.
. tests/hostile/data/io-lib.sh "$@"
mkdir "$T/scenes" "$T/shared"
echo '#declare Shared = 7;' > "$T/shared/lib.inc"
printf '#include "../shared/lib.inc"\n#debug concat(str(Shared, 0, 0), "\\n")\n' > "$T/scenes/a.scn"
printf '#include "%s/shared/lib.inc"\n#debug concat(str(Shared, 0, 0), "\\n")\n' "$T" > "$T/scenes/b.scn"
run --check "$T/scenes/a.scn"
want_rc 65
want_err "\$T/scenes/a.scn:1:1: error: include file '../shared/lib.inc' is outside the directories this scene may read (its own, -I directories and the library); --allow-read DIR grants more"
run --check --allow-read "$T/shared" "$T/scenes/a.scn"
want_rc 0
[ "$(cat "$T/.out")" = 7 ] || why="${why:+$why; }--allow-read: stdout is not 7"
run --check "$T/scenes/b.scn"
want_rc 65
run --check --allow-read "$T/shared" "$T/scenes/b.scn"
want_rc 0
run --check -I "$T/shared" "$T/scenes/a.scn"
want_rc 0
# a grant of one directory does not grant its parent
run --check --allow-read "$T/shared" "$T/scenes/b.scn"
printf '#include "../shared/../../etc/passwd"\n' > "$T/scenes/c.scn"
run --check --allow-read "$T/shared" "$T/scenes/c.scn"
want_rc 65
done_case "--allow-read grants a directory, nothing else"
