# SPDX-License-Identifier: MIT
# tests/hostile/data/lang-lib.sh: sourced by the lang-*.sh hostile cases as
# `. tests/hostile/data/lang-lib.sh "$@"`: $ARVO the binary, $T the case's
# empty directory. Generated inputs go to $T; nothing large is committed.
ARVO=$1
T=$2
why=
# repeat N TEXT: TEXT N times, one per line (awk: no shell loop of 45,000).
repeat() { awk -v n="$1" -v t="$2" 'BEGIN { for (i = 0; i < n; i++) print t }'; }
# repeat_inline N TEXT: TEXT N times, no newline.
repeat_inline() { awk -v n="$1" -v t="$2" 'BEGIN { for (i = 0; i < n; i++) printf "%s", t }'; }
# expect RC LINE ARGS...: runs arvo with ARGS; the exit status must be RC and
# the first line of stderr exactly LINE; no signal death.
expect() {
	want=$1 line=$2
	shift 2
	"$ARVO" "$@" > "$T/out" 2> "$T/err" < /dev/null
	rc=$?
	got=$(head -n 1 "$T/err")
	[ "$rc" -eq "$want" ] || why="${why:+$why; }exit status $rc, expected $want"
	[ "$got" = "$line" ] || why="${why:+$why; }first stderr line \"$got\", expected \"$line\""
}
# done_case TEXT: the case's one TAP line.
done_case() {
	if [ -z "$why" ]; then
		echo "ok - $1"
	else
		echo "not ok - $1: $why"
	fi
}
