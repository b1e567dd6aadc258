# SPDX-License-Identifier: MIT
# tests/tap.sh: the TAP helpers the command-line suites share (sourced; not a
# suite). The caller sets ARVO, tmp (a scratch directory), n=0 and why=
# before using them; TIMEOUT bounds each run (default 20 s).
# run ARGS...: runs arvo; sets rc, leaves stdout in $tmp/out, stderr in $tmp/err.
run() {
	timeout "${TIMEOUT:-20}" "$ARVO" "$@" > "$tmp/out" 2> "$tmp/err" < /dev/null
	rc=$?
	[ "$rc" -lt 124 ] || why="${why:+$why; }crashed or timed out (exit status $rc)"
}
# want_rc CODE...: the exit status must be one of CODE.
want_rc() {
	for c; do [ "$rc" -eq "$c" ] && return; done
	why="${why:+$why; }exit status $rc, expected $*"
}
# has FILE ERE: FILE must hold a line matching ERE (case-sensitive).
has() { grep -Eq -- "$2" "$tmp/$1" || why="${why:+$why; }$1 lacks /$2/"; }
# hasi FILE ERE: the same, ignoring case.
hasi() { grep -Eqi -- "$2" "$tmp/$1" || why="${why:+$why; }$1 lacks /$2/i"; }
# is FILE TEXT: FILE must be exactly TEXT plus a newline.
is() { printf '%s\n' "$2" | cmp -s - "$tmp/$1" || why="${why:+$why; }$1 is not \"$2\""; }
# empty FILE: FILE must be empty.
empty() { [ ! -s "$tmp/$1" ] || why="${why:+$why; }$1 is not empty"; }
# absent FILE: FILE must not exist.
absent() { [ ! -e "$tmp/$1" ] || why="${why:+$why; }$1 exists"; }
# same A B: the two files must be identical.
same() { cmp -s "$tmp/$1" "$tmp/$2" || why="${why:+$why; }$1 and $2 differ"; }
# report NAME: prints the TAP line for the case just checked.
report() {
	n=$((n + 1))
	if [ -z "$why" ]; then
		echo "ok $n - $1"
	else
		echo "not ok $n - $1"
		echo "#   $why"
		for s in out err; do
			[ -s "$tmp/$s" ] && { echo "#   std$s:"; head -8 "$tmp/$s" | sed 's/^/#     /'; }
		done
	fi
	why=
}
# skip NAME WHY: a skipped case.
skip() { n=$((n + 1)); echo "ok $n - $1 # SKIP $2"; }
