#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: SIGTERM in the middle of a render: exit 143, the earlier file of
# that name untouched, no temporary left.
. tests/hostile/data/io-lib.sh "$@"
scene "$T/s.scn"
echo "earlier image" > "$T/out.exr"
"$ARVO" --quiet --threads 2 --spp 256 --width 500 --height 400 -o "$T/out.exr" "$T/s.scn" \
	> /dev/null 2> "$T/.err" < /dev/null &
pid=$!
# wait until the render threads run (Linux: /proc/PID/task), at most 10 s
i=0
while [ "$i" -lt 200 ] && [ -d "/proc/$pid/task" ] && [ "$(ls "/proc/$pid/task" 2>/dev/null | wc -l)" -lt 2 ]; do
	sleep 0.05
	i=$((i + 1))
done
kill -TERM "$pid"
wait "$pid"
rc=$?
want_rc 143
same "$T/out.exr" "earlier image"
no_temps "$T"
done_case "SIGTERM mid-render: exit 143, the earlier output kept, no temporary"
