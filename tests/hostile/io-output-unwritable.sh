#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: an output directory without write permission: exit 73 with the
# reason, before any work (root may write anywhere: skipped as root).
. tests/hostile/data/io-lib.sh "$@"
if [ "$(id -u)" -eq 0 ]; then
	echo "ok - unwritable output directory # SKIP root can write into a mode-555 directory"
	exit 0
fi
scene "$T/s.scn"
mkdir "$T/ro"
chmod 555 "$T/ro"
run --quiet --width 8 --height 8 -o "$T/ro/out.exr" "$T/s.scn"
chmod 755 "$T/ro"
want_rc 73
want_err "arvo: error: cannot create '\$T/ro/out.exr': Permission denied"
absent "$T/ro/out.exr"
no_temps "$T/ro"
done_case "unwritable output directory: exit 73"
