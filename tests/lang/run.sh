#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/lang/run.sh [DIR...]: runs every annotated scene under DIR (default
# tests/lang) through `$ARVO --check` and prints one TAP line per case.
#
# Annotations (anywhere on a line, usually at its end):
#   // expect: TEXT            the next line of stdout is exactly TEXT
#                              (no expect lines: stdout must be empty)
#   // error: L:C: MESSAGE     stderr holds "<case>:L:C: error: MESSAGE", then
#                              the quoted source line and a caret under C
#   // error: PATH:L:C: MSG    the same in another file (PATH relative to the
#                              case's directory, e.g. inc/loop.inc)
#   // error: -: MESSAGE       "arvo: error: MESSAGE" (no location)
#   // warning: …              the same forms for warnings
#   // exit: N                 expected exit status (default: 65 when an error
#                              is expected, else 0)
#   // args: ARGS              extra arguments before the file (sh quoting)
# Diagnostics must appear in the order of the annotations and there must be
# no others. Each case runs under `timeout`; a status >= 128 is a crash.
# Environment: ARVO (the binary; default ./arvo), TIMEOUT (seconds, 10).
set -u
cd "$(dirname "$0")/../.." || exit 2
ARVO=${ARVO:-$PWD/arvo}
TIMEOUT=${TIMEOUT:-10}
# the cases do not depend on whether POV-Ray's include files are installed
export ARVO_POVRAY_INCLUDE=
[ $# -gt 0 ] || set -- tests/lang
dirs=$*
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-lang.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT INT TERM

# diag: prints "# " before every line of stdin.
diag() { sed 's/^/#   /'; }

n=0
for f in $(find "$@" -name '*.scn' | LC_ALL=C sort); do
	n=$((n + 1))
	dir=${f%/*}
	why=

	# Annotations, in one pass: want.out gets the expect lines, want.diag the
	# diagnostics; stdout is "EXIT ARGS".
	meta=$(awk -v wout="$tmp/want.out" -v wdiag="$tmp/want.diag" '
	BEGIN { printf "" > wout; printf "" > wdiag; rc = ""; args = ""; errs = 0 }
	{ sub(/\r$/, "") }
	match($0, /\/\/ expect:/) { s = substr($0, RSTART + RLENGTH); sub(/^ /, "", s); print s > wout }
	match($0, /\/\/ exit: *[0-9]+/) { if (rc == "") { s = substr($0, RSTART, RLENGTH); gsub(/[^0-9]/, "", s); rc = s } }
	match($0, /\/\/ args: /) { args = args " " substr($0, RSTART + RLENGTH) }
	match($0, /\/\/ (error|warning): /) {
		s = substr($0, RSTART + 3, RLENGTH - 3); kind = substr(s, 1, index(s, ":") - 1)
		if (kind == "error") errs++
		rest = substr($0, RSTART + RLENGTH)
		if (rest ~ /^-: /) { print kind "\t-\t0\t0\t" substr(rest, 4) > wdiag; next }
		file = "="
		if (rest !~ /^[0-9]/) { i = index(rest, ":"); file = substr(rest, 1, i - 1); rest = substr(rest, i + 1) }
		i = index(rest, ":"); l = substr(rest, 1, i - 1); rest = substr(rest, i + 1)
		i = index(rest, ":"); c = substr(rest, 1, i - 1); rest = substr(rest, i + 2)
		print kind "\t" file "\t" l "\t" c "\t" rest > wdiag
	}
	END { if (rc == "") rc = errs ? 65 : 0; print rc " " args }' "$f")
	want_rc=${meta%% *}
	args=${meta#* }

	# Run.
	eval "set -- $args"
	timeout "$TIMEOUT" "$ARVO" --check "$@" "$f" > "$tmp/out" 2> "$tmp/err" < /dev/null
	rc=$?

	if [ "$rc" -eq 124 ]; then
		why="timed out after ${TIMEOUT}s"
	elif [ "$rc" -ge 126 ]; then
		why="crashed or could not run (exit status $rc)"
	elif [ "$rc" -ne "$want_rc" ]; then
		why="exit status $rc, expected $want_rc"
	fi
	if ! cmp -s "$tmp/want.out" "$tmp/out"; then
		why="${why:+$why; }stdout differs"
	fi
	awk -v cs="$f" -v dir="$dir" -v wantf="$tmp/want.diag" '
	function srcline(path, k,   line, i, r) {
		line = ""
		for (i = 1; i <= k; i++) { r = (getline line < path); if (r <= 0) { line = ""; break } }
		close(path); sub(/\r$/, "", line); return line
	}
	function fail(msg) { print msg; bad = 1 }
	BEGIN {
		nw = 0
		while ((getline w < wantf) > 0) {
			split(w, p, "\t"); nw++
			wk[nw] = p[1]; wf[nw] = p[2]; wl[nw] = p[3] + 0; wc[nw] = p[4] + 0
			wm[nw] = substr(w, length(p[1] p[2] p[3] p[4]) + 5)
		}
		k = 0; bad = 0
	}
	{ L[NR] = $0 }
	END {
		for (i = 1; i <= NR; i++) {
			s = L[i]
			if (s !~ /^[^ ]*: (error|warning): /) continue
			k++
			if (k > nw) { fail("unexpected diagnostic: " s); continue }
			if (wf[k] == "-") {
				e = "arvo: " wk[k] ": " wm[k]
				if (s != e) fail("diagnostic " k ": expected \"" e "\", got \"" s "\"")
				continue
			}
			path = (wf[k] == "=") ? cs : dir "/" wf[k]
			head = wl[k] ":" wc[k] ": " wk[k] ": "
			e = head wm[k]
			if (wf[k] == "=") {
				okpath = index(s, cs ":" e) == 1 && length(s) == length(cs ":" e)
			} else {
				j = index(s, wf[k] ":" e)
				okpath = j > 0 && j + length(wf[k] ":" e) - 1 == length(s) && (j == 1 || substr(s, j - 1, 1) == "/")
			}
			if (!okpath) { fail("diagnostic " k ": expected \"" (wf[k] == "=" ? cs : ".../" wf[k]) ":" e "\", got \"" s "\""); continue }
			src = srcline(path, wl[k])
			if (L[i + 1] != src) { fail("diagnostic " k ": quoted line \"" L[i + 1] "\", expected \"" src "\""); continue }
			c = wc[k]; if (c > length(src) + 1) c = length(src) + 1
			caret = L[i + 2]
			if (caret !~ /^[ \t]*\^$/ || length(caret) != c) fail("diagnostic " k ": caret line \"" caret "\" does not point at column " wc[k])
		}
		for (k++; k <= nw; k++) {
			fail("missing diagnostic: " (wf[k] == "=" ? cs : wf[k]) ":" wl[k] ":" wc[k] ": " wk[k] ": " wm[k])
		}
		exit bad
	}' "$tmp/err" > "$tmp/diagmsg"
	[ $? -eq 0 ] || why="${why:+$why; }stderr differs"

	if [ -z "$why" ]; then
		echo "ok $n - $f"
	else
		echo "not ok $n - $f"
		echo "#   $why"
		if ! cmp -s "$tmp/want.out" "$tmp/out"; then
			echo "#   stdout (- expected, + actual):"
			diff "$tmp/want.out" "$tmp/out" | sed -n 's/^\([<>]\)/\1/p; s/^\\/\\/p' | sed 's/^</-/; s/^>/+/' | head -20 | diag
		fi
		if [ -s "$tmp/diagmsg" ]; then
			head -10 "$tmp/diagmsg" | diag
		fi
		if [ -s "$tmp/err" ]; then
			echo "#   stderr:"
			head -12 "$tmp/err" | diag
		fi
	fi
done
[ "$n" -gt 0 ] || echo "not ok 1 - no cases found under $dirs"
exit 0
