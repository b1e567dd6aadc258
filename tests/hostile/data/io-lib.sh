# SPDX-License-Identifier: MIT
# tests/hostile/data/io-lib.sh: helpers for the io-*.sh hostile cases, which
# source it as `. tests/hostile/data/io-lib.sh "$@"` (the runner's working
# directory is the repository root). Sets ARVO and T (the case's own empty
# directory) from the case's arguments.
ARVO=$1
T=$2
why=

# scene FILE [PIGMENT]: writes a small scene (a sphere lit by one light);
# PIGMENT (default: a red rgb) is the sphere's pigment body.
scene() {
	printf 'camera { location <0, 0, -3> look_at 0 }\nlight_source { <2, 4, -3>, rgb 1 }\nsphere { 0, 1 pigment { %s } }\n' \
		"${2:-rgb <1, 0, 0>}" > "$1"
}
# caustic FILE: a scene with a light pass (a glass sphere over a floor).
caustic() {
	printf '%s\n' 'camera { location <0, 2, -4> look_at 0 }' \
		'light_source { <0, 6, 0>, rgb 1 }' \
		'sphere { <0, 1, 0>, 0.8 pigment { rgbf 1 } interior { ior 1.5 } }' \
		'plane { y, 0 pigment { rgb 1 } }' > "$1"
}
# run ARGS...: runs arvo (stdin closed); rc, and stdout/stderr in $T/.out, $T/.err.
run() {
	timeout 15 "$ARVO" "$@" > "$T/.out" 2> "$T/.err" < /dev/null
	rc=$?
}
# want_rc N: the exit status must be N (and no signal death unless N says so).
want_rc() {
	[ "$rc" -eq "$1" ] || why="${why:+$why; }exit status $rc, expected $1"
}
# want_err TEXT: the first line of stderr must be TEXT ($T written as $T).
want_err() {
	got=$(head -n 1 "$T/.err" | awk -v t="$T" '{ while ((i = index($0, t)) > 0) $0 = substr($0, 1, i - 1) "$T" substr($0, i + length(t)); print }')
	[ "$got" = "$1" ] || why="${why:+$why; }first stderr line \"$got\", expected \"$1\""
}
# no_temps DIR: no temporary (*.tmp.*) may be left in DIR.
no_temps() {
	left=$(ls -A "$1" | grep '\.tmp\.' | tr '\n' ' ')
	[ -z "$left" ] || why="${why:+$why; }temporaries left behind: $left"
}
# same FILE TEXT: FILE must still hold exactly TEXT (an earlier output kept).
same() {
	[ "$(cat "$1" 2>/dev/null)" = "$2" ] || why="${why:+$why; }$1 was changed or removed"
}
# absent FILE: FILE must not exist.
absent() {
	[ ! -e "$1" ] || why="${why:+$why; }$1 exists"
}
# done_case NAME: prints the TAP line.
done_case() {
	if [ -z "$why" ]; then
		echo "ok - $1"
	else
		echo "not ok - $1"
		echo "#   $why"
		[ -s "$T/.err" ] && head -6 "$T/.err" | sed 's/^/#     /'
	fi
	exit 0
}

# signal_case SIG CODE: sends SIG to a render once its threads run; it must
# exit CODE, keep the earlier file of that name, and leave no temporary.
signal_case() {
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
	kill -"$1" "$pid"
	wait "$pid"
	rc=$?
	want_rc "$2"
	same "$T/out.exr" "earlier image"
	no_temps "$T"
	done_case "SIG$1 mid-render: exit $2, the earlier output kept, no temporary"
}
