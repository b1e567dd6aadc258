#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: SIGINT in the middle of a render: exit 130, the earlier file of
# that name untouched, no temporary left.
. tests/hostile/data/io-lib.sh "$@"
signal_case INT 130
