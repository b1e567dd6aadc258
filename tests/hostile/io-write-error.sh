#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: a write error (the file size limit, as on a full disk): exit 74
# with the reason, the earlier file untouched, no temporary left.
. tests/hostile/data/io-lib.sh "$@"
scene "$T/s.scn"
echo "earlier image" > "$T/out.exr"
# SIGXFSZ ignored so the write fails with EFBIG (arvo ignores it too);
# 4 blocks are 2 KiB under dash, 4 KiB under bash: the image is 64 KiB.
(trap '' XFSZ; ulimit -f 4; exec timeout 15 "$ARVO" --quiet --width 64 --height 64 --compression none \
	-o "$T/out.exr" "$T/s.scn") > "$T/.out" 2> "$T/.err" < /dev/null
rc=$?
want_rc 74
want_err "arvo: error: cannot write '\$T/out.exr': File too large"
same "$T/out.exr" "earlier image"
no_temps "$T"
done_case "write error (ulimit -f): exit 74 with the reason, the earlier output kept"
