#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/install/run.sh: `make install PREFIX=… DESTDIR=…` installs the binary,
# the standard library and the man pages, and the installed binary finds its
# standard library and OCIO config without help (TAP).
cd "$(dirname "$0")/../.." || exit 2
dest=$(mktemp -d "${TMPDIR:-/tmp}/arvo-install.XXXXXX")
trap 'rm -rf "$dest"' EXIT INT TERM
n=0
ok() { n=$((n + 1)); echo "ok $n - $1"; }
no() { n=$((n + 1)); echo "not ok $n - $1"; }
if make -s install PREFIX=/usr/local DESTDIR="$dest" BUILD="${BUILD:-build/release}" >"$dest/log" 2>&1; then
	ok "make install succeeds"
else
	no "make install succeeds"; sed 's/^/#   /' "$dest/log"
fi
p=$dest/usr/local
for f in bin/arvo share/man/man1/arvo.1 share/man/man5/arvo-scn.5 share/arvo/include/colors.inc \
         share/arvo/ocio/config.ocio share/arvo/demo.scn; do
	if [ -f "$p/$f" ]; then ok "installed $f"; else no "installed $f"; fi
done
printf '#include "colors.inc"\n#debug concat(str(White.red, 0, 1), "\\n")\n' > "$dest/t.scn"
out=$(env -u ARVO_DATA_DIR "$p/bin/arvo" --check "$dest/t.scn" 2>&1)
if [ "$out" = "1.0" ]; then ok "installed arvo finds its standard library"; else no "installed arvo finds its standard library"; echo "#   got: $out"; fi
echo "1..$n"
