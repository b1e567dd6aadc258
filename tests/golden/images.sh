#!/bin/sh
# golden.sh: a golden-image suite for arvo (docs/golden.md). Renders every
# scene of a manifest and compares it with its expected image; one TAP line
# ("ok N - NAME" / "not ok N - NAME") per scene, exit status 1 if any fails.
#   manifest lines: NAME SCENE [arvo options...]   ('#' starts a comment)
#   UPDATE=1      rewrite the expected images from this build (then review
#                 them with `arvo compare` and commit them on purpose)
# Environment: ARVO (default: arvo), GOLDEN (the expected images' directory,
# default: the manifest's directory), COMPARE (arvo compare options, default:
# exactly), KEEP (a directory to keep failed renders and their differences).
set -u
manifest=${1:?usage: golden.sh MANIFEST}
ARVO=${ARVO:-arvo}
GOLDEN=${GOLDEN:-$(dirname "$manifest")}
COMPARE=${COMPARE:-}
out=$(mktemp -d "${TMPDIR:-/tmp}/golden.XXXXXX") || exit 2
trap 'rm -rf "$out"' EXIT INT TERM
n=0 failed=0
while read -r name scene opts; do
	case $name in '' | '#'*) continue ;; esac
	n=$((n + 1))
	# shellcheck disable=SC2086 # opts holds several options
	if ! "$ARVO" -q $opts -o "$out/$name.exr" "$scene" > "$out/log" 2>&1; then
		echo "not ok $n - $name: the render failed"
		sed 's/^/#   /' "$out/log"
		failed=$((failed + 1))
		continue
	fi
	if [ "${UPDATE:-0}" = 1 ]; then
		cp "$out/$name.exr" "$GOLDEN/$name.exr"
		echo "ok $n - $name # updated"
		continue
	fi
	# shellcheck disable=SC2086 # COMPARE holds several options
	"$ARVO" compare $COMPARE -o "$out/$name.diff.exr" "$GOLDEN/$name.exr" "$out/$name.exr" > "$out/log" 2>&1
	rc=$?
	if [ $rc -eq 0 ]; then
		echo "ok $n - $name"
		continue
	fi
	echo "not ok $n - $name ($([ $rc -eq 1 ] && echo differs || echo "cannot compare: exit $rc"))"
	sed 's/^/#   /' "$out/log"
	failed=$((failed + 1))
	if [ -n "${KEEP:-}" ] && mkdir -p "$KEEP"; then
		cp "$out/$name.exr" "$out/$name.diff.exr" "$KEEP/" 2> /dev/null
	fi
done < "$manifest"
[ $n -gt 0 ] || { echo "not ok 1 - no scenes in $manifest"; exit 1; }
[ $failed -eq 0 ]
