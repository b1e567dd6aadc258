#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: 1 + 1 + ... with a million operators (was a stack overflow in the
# evaluator and in --dump-ast: each operator nests its left operand deeper).
. tests/hostile/data/lang-lib.sh "$@"
{ printf '#declare A = 1'; repeat_inline 1000000 '+1'; echo ';'; } > "$T/s.scn"
expect 65 "$T/s.scn:1:411: error: expression too long (more than 200 operators and levels of nesting)" --check "$T/s.scn"
expect 65 "$T/s.scn:1:411: error: expression too long (more than 200 operators and levels of nesting)" --dump-ast "$T/s.scn"
done_case "a million chained operators: a located error, exit 65"
