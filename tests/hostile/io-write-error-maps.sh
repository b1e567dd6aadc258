#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: a write error while saving maps (--save-maps): exit 74, no
# temporary, no image written, the earlier maps file untouched.
. tests/hostile/data/io-lib.sh "$@"
caustic "$T/c.scn"
echo "earlier maps" > "$T/c.maps"
(trap '' XFSZ; ulimit -f 1; exec timeout 15 "$ARVO" --quiet --width 16 --height 12 --rays 20000 \
	--save-maps "$T/c.maps" -o "$T/out.exr" "$T/c.scn") > "$T/.out" 2> "$T/.err" < /dev/null
rc=$?
want_rc 74
want_err "arvo: error: cannot write '\$T/c.maps': File too large"
same "$T/c.maps" "earlier maps"
absent "$T/out.exr"
no_temps "$T"
done_case "write error in --save-maps: exit 74, the earlier maps kept"
