#!/bin/sh
# SPDX-License-Identifier: MIT
# hostile: SIGTERM in the middle of a render: exit 143, the earlier file of
# that name untouched, no temporary left.
. tests/hostile/data/io-lib.sh "$@"
signal_case TERM 143
