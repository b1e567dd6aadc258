#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/pipeline/run.sh: the pipeline around a render (TAP lines):
#   - the EXR header (camera matrices, render settings) and layer names;
#   - --region and --tile: data windows, `arvo merge` (and oiiotool) give
#     the whole frame back bit for bit, also with --load-maps on every tile;
#   - `arvo compare`: exit codes, tolerances, the difference image, and its
#     figures against OpenImageIO's idiff on the same pair;
#   - map files: fixed byte order and versioned header, refused for another
#     scene, another format, another arvo version, or when damaged;
#   - PNG: the sRGB chunk, the OCIO view in a text chunk, --png-depth 16.
# Environment: ARVO (default ./arvo).
set -u
cd "$(dirname "$0")/../.." || exit 2
ARVO=${ARVO:-$PWD/arvo}
T=tests/pipeline
tmp=$(mktemp -d "${TMPDIR:-/tmp}/arvo-pipeline.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT INT TERM
n=0 why=

TIMEOUT=${TIMEOUT:-120}
. tests/tap.sh
G="--width 64 --height 48 --rays 20000"

# ---- the EXR ---------------------------------------------------------------
run -q $G --spp 2 --seed 7 -o "$tmp/full.exr" tests/render/g_glass.scn
want_rc 0
exrheader "$tmp/full.exr" > "$tmp/hdr"
sed -n 's/^    \([^ ,]*\), 32-bit floating-point.*/\1/p' "$tmp/hdr" | tr '\n' ' ' > "$tmp/out"
echo >> "$tmp/out"
is out "A B G N.X N.Y N.Z P.X P.Y P.Z R Z albedo.B albedo.G albedo.R caustic.B caustic.G caustic.R direct.B direct.G direct.R emission.B emission.G emission.R specular.B specular.G specular.R "
report "the EXR holds the beauty, A, Z, and the layers N P albedo caustic direct emission specular"

cp "$tmp/hdr" "$tmp/out"
has out '^worldToCamera \(type m44f\)'; has out '^worldToNDC \(type m44f\)'; has out '^arvo:cameraToWorld \(type m44f\)'
has out '^arvo:spp \(type string\): "2"$'; has out '^arvo:rays \(type string\): "20000"$'
has out '^arvo:method \(type string\): "shaft"$'; has out '^arvo:passes \(type string\): "rgb"$'
has out '^arvo:seed \(type string\): "7"$'; has out '^arvo:scene \(type string\): "tests/render/g_glass.scn"$'
has out '^arvo:version \(type string\): "[0-9]+\.[0-9]+\.[0-9]+"$'; has out '^software \(type string\): "arvo '
# the camera of g_glass.scn sits at <0, 2.5, -6>: the last row of cameraToWorld
grep -A4 '^arvo:cameraToWorld' "$tmp/hdr" > "$tmp/out"
has out '^    0 2\.5 -6 1\)$'
report "the header records the camera matrices, spp, rays, method, passes, seed, scene and version"

run -q $G --spp 2 -o "$tmp/seed0.exr" tests/render/g_glass.scn
"$ARVO" compare "$tmp/full.exr" "$tmp/seed0.exr" > "$tmp/out" 2>&1
st=$?
[ $st -eq 1 ] || why="--seed 7 and seed 0 compare with exit $st, expected 1"
run -q $G --spp 2 --seed 0 -o "$tmp/seed0b.exr" tests/render/g_glass.scn
same seed0.exr seed0b.exr
report "--seed changes the samples; --seed 0 is the default, byte for byte"

# ---- tiles and merge -------------------------------------------------------
run -q $G -o "$tmp/whole.exr" tests/render/g_glass.scn
for i in 1 2 3; do "$ARVO" -q $G --tile $i/3 -o "$tmp/t$i.exr" tests/render/g_glass.scn || why="tile $i failed"; done
exrheader "$tmp/t2.exr" > "$tmp/out"
has out '^dataWindow \(type box2i\): \(0 16\) - \(63 31\)$'; has out '^displayWindow \(type box2i\): \(0 0\) - \(63 47\)$'
report "--tile 2/3 of a 64x48 frame: data window rows 16 to 31, display window the frame"

run merge -o "$tmp/merged.exr" "$tmp/t3.exr" "$tmp/t1.exr" "$tmp/t2.exr"
want_rc 0; same whole.exr merged.exr
report "arvo merge of the three tiles (any order) is the whole render, byte for byte"

"$ARVO" -q $G --region 0:20,0:48 -o "$tmp/r1.exr" tests/render/g_glass.scn
"$ARVO" -q $G --region 20:64,0:30 -o "$tmp/r2.exr" tests/render/g_glass.scn
"$ARVO" -q $G --region 20:64,30:48 -o "$tmp/r3.exr" tests/render/g_glass.scn
run merge -o "$tmp/merged2.exr" "$tmp/r1.exr" "$tmp/r2.exr" "$tmp/r3.exr"
want_rc 0; same whole.exr merged2.exr
report "arvo merge of three --region parts (columns and rows) is the whole render, byte for byte"

H="--width 40 --height 30 --rays 0 --half --compression piz"
"$ARVO" -q $H -o "$tmp/h.exr" tests/render/g_glass.scn
"$ARVO" -q $H --tile 1/2 -o "$tmp/h1.exr" tests/render/g_glass.scn
"$ARVO" -q $H --tile 2/2 -o "$tmp/h2.exr" tests/render/g_glass.scn
run merge -o "$tmp/hm.exr" "$tmp/h1.exr" "$tmp/h2.exr"
want_rc 0; same h.exr hm.exr
report "arvo merge keeps the parts' half pixels and piz compression: byte for byte again"

oiiotool "$tmp/t1.exr" "$tmp/t2.exr" "$tmp/t3.exr" --paste:all=1:mergeroi=1 auto -o "$tmp/oiio.exr" > "$tmp/out" 2>&1 ||
	why="oiiotool failed"
oiiotool "$tmp/whole.exr" --dumpdata > "$tmp/d1" 2>&1
oiiotool "$tmp/oiio.exr" --dumpdata > "$tmp/d2" 2>&1
same d1 d2
run compare "$tmp/whole.exr" "$tmp/oiio.exr"
want_rc 0
report "oiiotool --paste:all=1:mergeroi=1 auto assembles the tiles to the same pixels"

"$ARVO" -q $G --save-maps "$tmp/g.maps" -o "$tmp/lm.exr" tests/render/g_glass.scn
for i in 1 2; do "$ARVO" -q $G --load-maps "$tmp/g.maps" --tile $i/2 -o "$tmp/lt$i.exr" tests/render/g_glass.scn; done
"$ARVO" -q $G --load-maps "$tmp/g.maps" -o "$tmp/lw.exr" tests/render/g_glass.scn
run merge -o "$tmp/lmerged.exr" "$tmp/lt1.exr" "$tmp/lt2.exr"
want_rc 0; same lw.exr lmerged.exr
run compare "$tmp/lm.exr" "$tmp/lmerged.exr"
want_rc 0
report "the farm path: --save-maps once, --load-maps on each tile, merge: the pixels of one render"

run merge -o "$tmp/gap.exr" "$tmp/t1.exr" "$tmp/t3.exr"
want_rc 65; is err "arvo merge: error: no part covers pixel (0, 16)"; absent gap.exr
report "arvo merge with a missing tile: exit 65, names the first uncovered pixel"

run merge -o "$tmp/ov.exr" "$tmp/t1.exr" "$tmp/t2.exr" "$tmp/t2.exr" "$tmp/t3.exr"
want_rc 65; is err "arvo merge: error: '$tmp/t2.exr' overlaps an earlier part at pixel (0, 16)"; absent ov.exr
report "arvo merge with a part twice: exit 65, overlap named"

"$ARVO" -q --width 32 --height 48 --rays 0 --tile 1/2 -o "$tmp/small.exr" tests/render/g_glass.scn
run merge -o "$tmp/mix.exr" "$tmp/t1.exr" "$tmp/small.exr"
want_rc 65; is err "arvo merge: error: '$tmp/small.exr' does not fit: its frame is 32x48, the first part's 64x48"
report "arvo merge of parts of different frames: exit 65"

run merge -o "$tmp/x.exr" "$tmp/nothere.exr"
want_rc 66; has err "^arvo merge: error: cannot read '$tmp/nothere.exr'"
report "arvo merge of a missing part: exit 66"

run merge "$tmp/t1.exr"
want_rc 64; has err '^arvo merge: error: no output given \(-o FULL.exr\)$'
report "arvo merge without -o: exit 64"

run -q $G --region 0:65,0:10 -o "$tmp/x.exr" tests/render/g_glass.scn
want_rc 64; has err "^arvo: error: --region 0:65,0:10 lies outside the 64x48 image$"; absent x.exr
report "--region outside the frame: exit 64 before rendering"

run -q $G --region 10:5,0:10 -o "$tmp/x.exr" tests/render/g_glass.scn
want_rc 64; has err "^arvo: error: bad value for --region: '10:5,0:10' \(expected x0:x1,y0:y1 with 0 <= x0 < x1 and 0 <= y0 < y1\)$"
report "--region with x1 <= x0: exit 64"

run -q $G --tile 1/2 -o "$tmp/x.png" tests/render/g_glass.scn
want_rc 64; has err '^arvo: error: a partial render \(--region, --tile\) needs an .exr output$'; absent x.png
report "--tile to a PNG: exit 64"

run -q $G --tile 0/3 tests/render/g_glass.scn
want_rc 64; has err "^arvo: error: bad value for --tile: '0/3' \(expected i/n with 1 <= i <= n\)$"
report "--tile 0/3: exit 64"

run -q $G --tile 1/2 --region 0:1,0:1 tests/render/g_glass.scn
want_rc 64; has err '^arvo: error: --region and --tile cannot be used together$'
report "--tile with --region: exit 64"

# ---- compare ---------------------------------------------------------------
run compare "$tmp/whole.exr" "$tmp/merged.exr"
want_rc 0; has out '^arvo compare: the images match$'; has out '^\(all\) +0 +0 +0 +inf +0 +0 \(0%\)$'
report "arvo compare of equal images: exit 0, every figure 0"

run compare "$tmp/whole.exr" "$tmp/seed0.exr"
want_rc 1; has out '^arvo compare: the images differ$'; has out '^RGBA .* differs$'
report "arvo compare of different images: exit 1, the layers that differ marked"

run compare "$tmp/whole.exr" "$tmp/nothere.exr"
want_rc 2; has err "^arvo compare: error: cannot read '$tmp/nothere.exr'"
report "arvo compare of a missing image: exit 2"

printf 'not an image\n' > "$tmp/junk.exr"
run compare "$tmp/junk.exr" "$tmp/whole.exr"
want_rc 2
report "arvo compare of a file that is not an EXR: exit 2"

run compare "$tmp/whole.exr" "$tmp/t1.exr"
want_rc 1; is out "arvo compare: $tmp/whole.exr and $tmp/t1.exr differ: the images differ in size: 64x48 at (0,0) of 64x48 against 64x16 at (0,0) of 64x48"
report "arvo compare of a tile against the frame: exit 1, sizes named"

run compare --metric nope "$tmp/whole.exr" "$tmp/whole.exr"
want_rc 64; has err "^arvo compare: error: unknown metric 'nope' \(expected rmse, mean, max, psnr or rel\)$"
report "arvo compare --metric nope: exit 64"

# two images whose beauty differs everywhere: spp 1 and spp 2, beauty only
"$ARVO" -q --width 48 --height 36 --rays 0 --spp 1 -o "$tmp/s1.exr" tests/render/g_glass.scn
"$ARVO" -q --width 48 --height 36 --rays 0 --spp 2 -o "$tmp/s2.exr" tests/render/g_glass.scn
oiiotool "$tmp/s1.exr" --ch R,G,B -o "$tmp/a.exr" > /dev/null 2>&1
oiiotool "$tmp/s2.exr" --ch R,G,B -o "$tmp/b.exr" > /dev/null 2>&1
idiff "$tmp/a.exr" "$tmp/b.exr" > "$tmp/idiff" 2>&1
run compare --tolerance 1e-6 "$tmp/a.exr" "$tmp/b.exr"
want_rc 1
awk -v f="$tmp/out" '
	/Mean error/ { m = $4 } /RMS error/ { r = $4 } /Peak SNR/ { p = $4 } /Max error/ { x = $4 }
	/pixels .* over/ { o = $1 }
	END {
		while ((getline line < f) > 0) if (line ~ /^\(all\)/) split(line, a, " +")
		bad = 0
		if (m == "" || r == "" || p == "" || x == "") bad = 1
		if (!(a[2] + 0 == m + 0 && a[3] + 0 == r + 0 && a[4] + 0 == x + 0 && a[5] + 0 == p + 0 && a[7] + 0 == o + 0)) bad = 1
		printf "idiff mean %s rmse %s max %s psnr %s over %s; arvo %s %s %s %s %s\n", m, r, x, p, o, a[2], a[3], a[4], a[5], a[7]
		exit bad
	}' "$tmp/idiff" > "$tmp/err" || why="figures disagree with idiff"
report "arvo compare's mean, RMS, max, PSNR and pixels over 1e-6 are idiff's (to the 6 digits idiff prints)"
sed 's/^/# /' "$tmp/err"

run compare --metric rmse --tolerance 0.08 "$tmp/a.exr" "$tmp/b.exr"
want_rc 0
run compare --metric rmse --tolerance 0.07 "$tmp/a.exr" "$tmp/b.exr"
want_rc 1
report "--metric rmse: RMS 0.0757 matches under 0.08, not under 0.07"

run compare --metric psnr --tolerance 22 "$tmp/a.exr" "$tmp/b.exr"
want_rc 0
run compare --metric psnr --tolerance 23 "$tmp/a.exr" "$tmp/b.exr"
want_rc 1
report "--metric psnr: 22.4 dB passes 22, fails 23"

run compare --tolerance 0.1 --failpercent 13 "$tmp/a.exr" "$tmp/b.exr"
want_rc 0; has out '^RGBA .* 224 \(12.96%\)$'
run compare --tolerance 0.1 --failpercent 12.9 "$tmp/a.exr" "$tmp/b.exr"
want_rc 1
report "--tolerance 0.1: 224 pixels (12.96 %) over it; --failpercent 13 passes, 12.9 fails"

run compare -o "$tmp/diff.exr" "$tmp/a.exr" "$tmp/b.exr"
want_rc 1
oiiotool "$tmp/a.exr" "$tmp/b.exr" --absdiff -o "$tmp/absdiff.exr" > /dev/null 2>&1
oiiotool "$tmp/diff.exr" --dumpdata > "$tmp/d1" 2>&1
oiiotool "$tmp/absdiff.exr" --dumpdata > "$tmp/d2" 2>&1
same d1 d2
report "compare -o diff.exr writes |A - B|, as oiiotool --absdiff"

# ---- map files -------------------------------------------------------------
M="--width 32 --height 24 --rays 20000"
run -q $M --save-maps "$tmp/m.maps" -o "$tmp/m.exr" $T/maps.scn
want_rc 0
od -A n -t x1 -N 12 "$tmp/m.maps" | tr -s ' \n' ' ' > "$tmp/out"; echo >> "$tmp/out"
is out " 41 52 56 4f 4d 41 50 53 02 00 00 00 "
dd if="$tmp/m.maps" bs=1 skip=12 count=16 2> /dev/null | tr -d '\0' > "$tmp/out"; echo >> "$tmp/out"
is out "$("$ARVO" --version | sed 's/^arvo //')"
report "a map file starts ARVOMAPS, format 2 as a little-endian uint32, then the arvo version"

run -q $M --load-maps "$tmp/m.maps" -D CamZ=-7 -o "$tmp/m2.exr" $T/maps.scn
want_rc 0
report "maps load for the same scene seen from elsewhere (the camera is not part of the hash)"

run -q $M --load-maps "$tmp/m.maps" -D LightX=-1 -o "$tmp/x.exr" $T/maps.scn
want_rc 66; is err "arvo: error: '$tmp/m.maps' was saved for another scene: the objects, lights or settings differ (save the maps again with --save-maps)"; absent x.exr
report "maps of the scene with its light moved: refused, exit 66"

run -q $M --load-maps "$tmp/m.maps" -o "$tmp/x.exr" tests/render/g_glass.scn
want_rc 66; has err "was saved for another scene"; absent x.exr
report "maps of another scene: refused, exit 66"

{ printf 'ARVOMAP1'; head -c 40 /dev/zero; } > "$tmp/old.maps"
run -q $M --load-maps "$tmp/old.maps" -o "$tmp/x.exr" $T/maps.scn
want_rc 66; is err "arvo: error: '$tmp/old.maps' is a map file of format 1; this arvo reads format 2 (save the maps again with --save-maps)"
report "a format-1 map file: refused with its format, exit 66"

{ head -c 12 "$tmp/m.maps"; printf '0.0.9'; head -c 11 /dev/zero; tail -c +29 "$tmp/m.maps"; } > "$tmp/v.maps"
run -q $M --load-maps "$tmp/v.maps" -o "$tmp/x.exr" $T/maps.scn
want_rc 66; has err "^arvo: error: '$tmp/v.maps' was saved by arvo 0\.0\.9; this is arvo [0-9.]+ \(save the maps again with --save-maps\)$"
report "a map file of another arvo version: refused, exit 66"

head -c 10 "$tmp/m.maps" > "$tmp/cut.maps"
run -q $M --load-maps "$tmp/cut.maps" -o "$tmp/x.exr" $T/maps.scn
want_rc 66; is err "arvo: error: '$tmp/cut.maps' is damaged (cut short or corrupt)"; absent x.exr
report "a map file cut short within its format number: refused as damaged, exit 66"

head -c 100 "$tmp/m.maps" > "$tmp/cut.maps"
run -q $M --load-maps "$tmp/cut.maps" -o "$tmp/x.exr" $T/maps.scn
want_rc 66; is err "arvo: error: '$tmp/cut.maps' is damaged (cut short or corrupt)"
report "a map file cut short: refused as damaged, exit 66"

run -q $M --load-maps "$tmp/junk.exr" -o "$tmp/x.exr" $T/maps.scn
want_rc 66; is err "arvo: error: '$tmp/junk.exr' is not an arvo map file"
report "a file that is not a map file: refused, exit 66"

# ---- PNG -------------------------------------------------------------------
run -q --width 16 --height 12 --rays 0 --png-depth 16 -o "$tmp/p16.png" tests/render/g_glass.scn
want_rc 0
od -A n -t x1 -j 24 -N 2 "$tmp/p16.png" | tr -d ' \n' > "$tmp/out"; echo >> "$tmp/out"
is out "1002"
grep -a -q 'sRGB' "$tmp/p16.png" || why="${why:+$why; }no sRGB chunk"
grep -a -q 'OCIO view' "$tmp/p16.png" && grep -a -q 'ACES 1.0 - SDR Video' "$tmp/p16.png" || why="${why:+$why; }no OCIO view text"
report "--png-depth 16: a 16-bit RGB PNG with an sRGB chunk and the OCIO view in a text chunk"

# a config with a Display P3 display (no transform: only its name matters here)
sed -e 's/^active_displays: \[sRGB - Display\]$/  Display P3:\n    - !<View> {name: Standard, view_transform: Un-tone-mapped, display_colorspace: Display P3}\nactive_displays: [sRGB - Display, Display P3]/' \
    -e 's/^display_colorspaces:$/display_colorspaces:\n  - !<ColorSpace>\n    name: Display P3\n    family: Display\n    encoding: sdr-video/' \
    stdlib-scenes/ocio/config.ocio > "$tmp/p3.ocio"
run -q --ocio-config "$tmp/p3.ocio" --display "Display P3" --view Standard --width 8 --height 6 --rays 0 -o "$tmp/p3.png" tests/render/g_glass.scn
want_rc 0
od -A n -t x1 -j 33 -N 12 "$tmp/p3.png" | tr -s ' \n' ' ' > "$tmp/out"; echo >> "$tmp/out"
is out " 00 00 00 04 63 49 43 50 0c 0d 00 01 "
grep -a -q 'sRGB' "$tmp/p3.png" && why="${why:+$why; }an sRGB chunk beside cICP"
report "a Display P3 display: a cICP chunk (primaries 12, transfer 13, full range) right after IHDR"

run -q --png-depth 12 tests/render/g_glass.scn
want_rc 64; has err "^arvo: error: bad value for --png-depth: '12' \(expected 8 or 16\)$"
report "--png-depth 12: exit 64"

# ---- docs/golden.md ---------------------------------------------------------
sed -n '/^<!-- golden.sh -->$/,/^```$/p' docs/golden.md | sed '1,2d;$d' > "$tmp/out"
cmp -s "$tmp/out" tests/golden/images.sh || why="docs/golden.md's script is not tests/golden/images.sh"
report "docs/golden.md shows tests/golden/images.sh word for word"

mkdir -p "$tmp/golden"
printf '# a suite of one\nflat tests/render/flat.scn --width 8 --height 6\n' > "$tmp/golden/golden.list"
UPDATE=1 ARVO=$ARVO sh tests/golden/images.sh "$tmp/golden/golden.list" > "$tmp/out" 2>&1 || why="update failed"
is out "ok 1 - flat # updated"
ARVO=$ARVO sh tests/golden/images.sh "$tmp/golden/golden.list" > "$tmp/out" 2>&1 || why="check failed"
is out "ok 1 - flat"
printf 'flat tests/render/flat.scn --width 8 --height 6 -D Value=0.2\n' > "$tmp/golden/golden.list"
ARVO=$ARVO KEEP="$tmp/kept" sh tests/golden/images.sh "$tmp/golden/golden.list" > "$tmp/out" 2>&1 && why="a changed image passed"
has out '^not ok 1 - flat \(differs\)$'; has out '^#   RGBA .* differs$'
[ -f "$tmp/kept/flat.diff.exr" ] || why="${why:+$why; }no difference image kept"
report "the golden recipe: UPDATE=1 makes the image, a rerun passes, a change fails and keeps the difference"
echo "1..$n"
