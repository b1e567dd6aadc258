#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/hostile/run.sh [CASE...]: the hostile-input suite. One case per file
# under tests/hostile (or the files named), one TAP line per case.
#
# NAME.scn: a scene, with header comment lines at its top:
#   // hostile: what it attacks (one line)
#   // args: extra options (sh words; $TMP is the case's own empty directory)
#   // exit: N                  the exact exit status required
#   // stderr: TEXT             the exact first line of stderr (omit only for
#                               exit 0); "$TMP" in TEXT stands for the case's
#                               directory
# The runner adds `--quiet --width 32 --height 24 --rays 2000 -o $TMP/out.exr`
# (--quiet: no progress lines before the message checked) unless the args
# say --check. Checked for every case: the exit status, the first line of
# stderr, no signal death (a status >= 128 fails unless the case expects 130
# or 143), nothing left in $TMP when the status is not 0 (no output, no
# temporary), and an end within $TIMEOUT seconds.
#
# NAME.sh: a case that generates its input or needs a set-up (an unwritable
# directory, `ulimit -f`, a signal). Run as `sh NAME.sh "$ARVO" "$TMP"` with
# its own empty $TMP; it prints one TAP line "ok - ..." or "not ok - ...".
#
# Only files directly under tests/hostile are cases; tests/hostile/data/
# holds small inputs and the helpers the io-*.sh cases source.
#
# Environment: ARVO (the binary; default ./arvo), TIMEOUT (seconds, 20).
set -u
cd "$(dirname "$0")/../.." || exit 2
ARVO=${ARVO:-$PWD/arvo}
TIMEOUT=${TIMEOUT:-20}
export ARVO
root=$(mktemp -d "${TMPDIR:-/tmp}/arvo-hostile.XXXXXX") || exit 2
trap 'chmod -R u+w "$root" 2>/dev/null; rm -rf "$root"' EXIT INT TERM

[ $# -gt 0 ] || set -- $(find tests/hostile -maxdepth 1 \( -name '*.scn' -o -name '*.sh' \) ! -name run.sh | LC_ALL=C sort)

n=0
# fresh: empties the case directory $TMP (a case may have made it read-only).
fresh() {
	chmod -R u+w "$root" 2>/dev/null
	rm -rf "$root/case"
	mkdir "$root/case" && TMP=$root/case
}
# report NAME WHY: prints the TAP line; WHY empty means the case passed.
report() {
	if [ -z "$2" ]; then
		echo "ok $n - $1"
	else
		echo "not ok $n - $1"
		echo "#   $2"
		if [ -s "$root/err" ]; then
			echo "#   stderr:"
			head -8 "$root/err" | sed 's/^/#     /'
		fi
	fi
}

for f; do
	n=$((n + 1))
	fresh || { echo "not ok $n - $f"; echo "#   cannot make a case directory"; continue; }
	: > "$root/err"
	case "$f" in
	*.sh)
		timeout "$TIMEOUT" sh "$f" "$ARVO" "$TMP" > "$root/out" 2> "$root/err" < /dev/null
		rc=$?
		lines=$(grep -c -E '^(not )?ok( |$)' "$root/out")
		if [ "$rc" -eq 124 ]; then
			report "$f" "timed out after ${TIMEOUT}s"
		elif [ "$lines" -ne 1 ]; then
			report "$f" "printed $lines TAP lines (exit status $rc), expected one"
			sed 's/^/#     /' "$root/out" | head -8
		elif grep -q '^ok' "$root/out"; then
			echo "ok $n - ${f##*/}: $(sed -n 's/^ok[ -]*//p' "$root/out")"
		else
			echo "not ok $n - ${f##*/}: $(sed -n 's/^not ok[ -]*//p' "$root/out")"
			grep -v -E '^(not )?ok' "$root/out" | head -12
			[ -s "$root/err" ] && head -8 "$root/err" | sed 's/^/#     /'
		fi
		continue
		;;
	esac

	# The header: exit, stderr and args lines before the first non-comment.
	want_rc= want_err= args= has_err=0
	while IFS= read -r line; do
		line=${line%"$(printf '\r')"}
		case "$line" in
		"// exit:"*) want_rc=$(echo "${line#// exit:}" | tr -d ' ') ;;
		"// stderr: "*) want_err=${line#// stderr: }; has_err=1 ;;
		"// args:"*) args="$args ${line#// args:}" ;;
		//*) ;;
		*) break ;;
		esac
	done < "$f"
	if [ -z "$want_rc" ]; then
		report "$f" "no '// exit:' line in the header"
		continue
	fi
	if [ "$has_err" -eq 0 ] && [ "$want_rc" -ne 0 ]; then
		report "$f" "no '// stderr:' line in the header (required unless exit 0)"
		continue
	fi
	eval "set -- $args"
	case " $args " in
	*" --check "*) ;;
	*) set -- --quiet --width 32 --height 24 --rays 2000 -o "$TMP/out.exr" "$@" ;;
	esac
	timeout "$TIMEOUT" "$ARVO" "$@" "$f" > "$root/out" 2> "$root/err" < /dev/null
	rc=$?

	why=
	if [ "$rc" -eq 124 ]; then
		why="timed out after ${TIMEOUT}s"
	elif [ "$rc" -ge 128 ] && [ "$rc" -ne 130 ] && [ "$rc" -ne 143 ]; then
		why="killed by signal $((rc - 128)) (exit status $rc)"
	elif [ "$rc" -ne "$want_rc" ]; then
		why="exit status $rc, expected $want_rc"
	fi
	if [ "$has_err" -eq 1 ]; then
		got=$(head -n 1 "$root/err" | awk -v t="$TMP" '{
			while ((i = index($0, t)) > 0) $0 = substr($0, 1, i - 1) "$TMP" substr($0, i + length(t))
			print }')
		[ "$got" = "$want_err" ] || why="${why:+$why; }first stderr line \"$got\", expected \"$want_err\""
	fi
	if [ "$rc" -ne 0 ] && [ -n "$(ls -A "$TMP")" ]; then
		why="${why:+$why; }exit $rc left files behind: $(ls -A "$TMP" | tr '\n' ' ')"
	fi
	report "$f" "$why"
done
[ "$n" -gt 0 ] || echo "not ok 1 - no hostile cases found"
exit 0
