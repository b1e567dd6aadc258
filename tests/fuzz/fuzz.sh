#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/fuzz/fuzz.sh SECONDS TARGET...: runs each libFuzzer target (built by
# make fuzz-build into build/fuzz) for SECONDS, with per-input time and
# memory limits, on a corpus under build/fuzz/corpus/TARGET seeded from the
# repository's scenes and images (copied, never written back to the repo).
# Crashes, hangs and leaks land in build/fuzz/artifacts/TARGET/; each one
# found is minimised and kept as a regression input in tests/fuzz/TARGET/.
# FUZZ_FORK=1: keep going after a crash, hang or leak (long unattended runs);
# FUZZ_TIMEOUT=S: seconds per input (default 10; more on a loaded machine).
set -u
cd "$(dirname "$0")/../.." || exit 2
secs=${1:-60}
shift
B=build/fuzz
mkdir -p "$B"

seed_scene() {
	c=$B/corpus/scene
	mkdir -p "$c"
	find tests stdlib-scenes -name '*.scn' -o -name '*.inc' | while read -r f; do
		cp "$f" "$c/seed-$(echo "$f" | tr '/' '_')"
	done
	# the keywords and directives, as a libFuzzer dictionary
	grep -o '"#*[a-z_][a-z_0-9]*"' lexer/tokens.def | sort -u > "$B/scene.dict"
}

seed_image() {
	c=$B/corpus/image
	mkdir -p "$c"
	find tests stdlib-scenes -name '*.png' -o -name '*.exr' | while read -r f; do
		cp "$f" "$c/seed-$(echo "$f" | tr '/' '_')"
	done
	# a map file saved from the scene the target loads maps for
	./arvo -q --width 8 --height 6 --rays 3000 --save-maps "$c/seed-maps.map" -o "$B/maps.exr" tests/fuzz/maps.scn ||
		echo "fuzz.sh: could not save a seed map file" >&2
	rm -f "$B/maps.exr"
}

status=0
for t in "$@"; do
	"seed_$t"
	mkdir -p "$B/artifacts/$t"
	dict=
	[ -f "$B/$t.dict" ] && dict=-dict=$B/$t.dict
	echo "fuzz.sh: $t for $secs s"
	"$B/fuzz_$t" $dict -max_total_time="$secs" -timeout="${FUZZ_TIMEOUT:-10}" -rss_limit_mb=3072 -max_len=65536 \
		-print_final_stats=1 ${FUZZ_FORK:+-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1} \
		-artifact_prefix="$B/artifacts/$t/" "$B/corpus/$t" > "$B/$t.log" 2>&1 || status=1
	grep -E "^#[0-9]+[[:space:]].*(DONE|cov:)" "$B/$t.log" | tail -1
	grep -E '^stat::number_of_executed_units|ERROR|SUMMARY' "$B/$t.log" | head -5
	ls "$B/artifacts/$t" 2>/dev/null | sed "s|^|fuzz.sh: found $t: |"
done
exit $status
