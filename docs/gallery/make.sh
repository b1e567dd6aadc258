#!/bin/sh
# SPDX-License-Identifier: MIT
# docs/gallery/make.sh (make gallery): renders every demo scene in
# stdlib-scenes/ at its default settings (320x240) to docs/gallery/NAME.png,
# timing each render, and rewrites the README's gallery section (between the
# <!-- gallery --> markers) with the pictures, their render times and the
# mean of the scene-linear image. Environment: ARVO (default ./arvo),
# THREADS (render threads; default: all cores).
set -eu
cd "$(dirname "$0")/../.."
ARVO=${ARVO:-$PWD/arvo}
out=docs/gallery
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-gallery.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
threads=${THREADS:+--threads $THREADS}
cores=${THREADS:-$(nproc)}

rows=
for scn in stdlib-scenes/*.scn; do
	name=$(basename "$scn" .scn)
	/usr/bin/time -f '%e %U %S' -o "$tmp/time" "$ARVO" --quiet $threads -o "$tmp/$name.exr" \
		-o "$out/$name.png" "$scn" > /dev/null
	secs=$(awk '{ printf "%.1f s (CPU %.1f s)", $1, $2 + $3 }' "$tmp/time")
	# R, G, B are the EXR's first channels
	mean=$(oiiotool --stats "$tmp/$name.exr" | awk '/Stats Avg/ { printf "%.3f", ($3 + $4 + $5) / 3; exit }')
	# the header comment's first sentence, after "NAME.scn: "
	what=$(awk 'NR == 1 { next } /^\/\/ *$/ || !/^\/\// { exit } { sub(/^\/\/ */, ""); printf "%s ", $0 }' "$scn" |
		sed 's/^[^:]*: *//; s/\([a-z0-9)][a-z0-9)][.:]\) .*/\1/; s/:$/./')
	echo "$name: $secs, mean $mean"
	rows="$rows| ![$name]($out/$name.png) | \`$name.scn\`: $what $secs, mean $mean |
"
done

section="<!-- gallery -->
Every demo in \`stdlib-scenes/\` at its default settings (320×240, physical
light model), rendered by \`make gallery\` with $cores threads: the render
time (wall clock from parse to PNG, and the CPU time, which depends less on
the machine's load) and the mean of the scene-linear R, G, B.

| picture | scene |
|---|---|
$rows<!-- /gallery -->"
printf '%s\n' "$section" > "$tmp/section"
awk -v f="$tmp/section" '
	/^<!-- gallery -->$/ { while ((getline l < f) > 0) print l; skip = 1; next }
	/^<!-- \/gallery -->$/ { skip = 0; next }
	!skip { print }' README.md > "$tmp/README.md"
cp "$tmp/README.md" README.md
