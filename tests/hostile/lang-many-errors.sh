#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: 100,000 lines of stray tokens: reporting stops after 20 errors.
. tests/hostile/data/lang-lib.sh "$@"
repeat 100000 ') ; } #end' > "$T/s.scn"
expect 65 "$T/s.scn:1:1: error: unexpected ')'" --check "$T/s.scn"
[ "$(grep -c ': error: ' "$T/err")" -eq 20 ] || why="${why:+$why; }$(grep -c ': error: ' "$T/err") errors reported, expected 20"
tail -n 1 "$T/err" | grep -q '^arvo: too many errors; stopping here$' || why="${why:+$why; }no 'too many errors' line"
done_case "100,000 lines of stray tokens: 20 errors, then stop"
