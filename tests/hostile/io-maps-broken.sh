#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: --load-maps files that are truncated, garbage, or flipped at
# random bytes: exit 66 with the reason (or a render, when a flip lands on
# a harmless byte), never a crash, hang or half-written image.
. tests/hostile/data/io-lib.sh "$@"
caustic "$T/c.scn"
run --quiet --width 16 --height 12 --rays 20000 --save-maps "$T/good.maps" -o "$T/out.exr" "$T/c.scn"
[ "$rc" -eq 0 ] || why="could not save maps (exit $rc)"
rm -f "$T/out.exr"
size=$(wc -c < "$T/good.maps")
for n in 0 7 8 12 16 40 $((size / 2)) $((size - 1)); do
	head -c "$n" "$T/good.maps" > "$T/t.maps"
	run --quiet --width 16 --height 12 --load-maps "$T/t.maps" -o "$T/out.exr" "$T/c.scn"
	want_rc 66
	case $(head -n 1 "$T/.err") in  # which reason depends on where the cut falls
	"arvo: error: '$T/t.maps' is not an arvo map file" | "arvo: error: '$T/t.maps' is damaged (cut short or corrupt)" | \
	"arvo: error: '$T/t.maps' is a map file of format "* | "arvo: error: '$T/t.maps' was saved "*) ;;
	*) why="${why:+$why; }cut at $n: unexpected first stderr line" ;;
	esac
	absent "$T/out.exr"
done
head -c 5000 /dev/urandom > "$T/t.maps"
run --quiet --width 16 --height 12 --load-maps "$T/t.maps" -o "$T/out.exr" "$T/c.scn"
want_rc 66
# 40 copies with 4 random bytes set to random values past the magic
k=0
while [ "$k" -lt 40 ]; do
	cp "$T/good.maps" "$T/t.maps"
	for b in 1 2 3 4; do
		off=$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')
		off=$((8 + off % (size - 8)))
		head -c 1 /dev/urandom | dd of="$T/t.maps" bs=1 seek="$off" conv=notrunc 2>/dev/null
	done
	run --quiet --width 16 --height 12 --load-maps "$T/t.maps" -o "$T/out.exr" "$T/c.scn"
	if [ "$rc" -ne 0 ] && [ "$rc" -ne 66 ]; then
		why="${why:+$why; }flipped copy $k: exit $rc"
		cp "$T/t.maps" "$T/../io-maps-broken.failed.maps" 2>/dev/null
	fi
	[ "$rc" -eq 0 ] || absent "$T/out.exr"
	rm -f "$T/out.exr"
	k=$((k + 1))
done
no_temps "$T"
done_case "truncated, garbage and bit-flipped --load-maps files: exit 66, never a crash"
