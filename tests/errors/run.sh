#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/errors/run.sh: the bad-input cases; same annotations as tests/lang.
cd "$(dirname "$0")/../.." || exit 2
exec sh tests/lang/run.sh tests/errors
