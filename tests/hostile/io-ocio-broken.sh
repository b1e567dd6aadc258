#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: a broken OCIO config (YAML garbage, binary garbage, an empty
# file), given by --ocio-config or $OCIO: exit 66 with the reason, before
# the scene is read.
. tests/hostile/data/io-lib.sh "$@"
scene "$T/s.scn"
echo '#debug "read\n"' >> "$T/s.scn"
printf 'ocio_profile_version: 2\nroles: [\n' > "$T/yaml.ocio"
head -c 2000 /dev/urandom > "$T/bin.ocio"
: > "$T/empty.ocio"
for c in yaml bin empty; do
	run --quiet --width 8 --height 8 --ocio-config "$T/$c.ocio" -o "$T/out.png" "$T/s.scn"
	want_rc 66
	case $(head -n 1 "$T/.err") in
	"arvo: error: cannot load OCIO config '$T/$c.ocio': "*) ;;
	*) why="${why:+$why; }$c: unexpected first stderr line" ;;
	esac
	[ ! -s "$T/.out" ] || why="${why:+$why; }$c: the scene was read before the check"
	absent "$T/out.png"
done
OCIO=$T/yaml.ocio run --quiet --width 8 --height 8 -o "$T/out.png" "$T/s.scn"
want_rc 66
done_case "broken OCIO configs: exit 66 before any work"
