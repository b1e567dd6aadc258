#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: 400 unclosed union{ then 400 } (was a parser loop to 7.5 GB: the
# failed guard left the depth raised and synchronize() did not advance).
. tests/hostile/data/lang-lib.sh "$@"
{ repeat 400 'union{'; repeat 400 '}'; } > "$T/s.scn"
expect 65 "$T/s.scn:201:1: error: nesting too deep (more than 200 levels)" --check "$T/s.scn"
done_case "400 unclosed union{ then 400 }: ends with a located error, exit 65"
