#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/man/run.sh: the man pages are clean under mandoc -Tlint (TAP).
cd "$(dirname "$0")/../.." || exit 2
n=0
for page in man/arvo.1 man/arvo-scn.5; do
	n=$((n + 1))
	out=$(mandoc -Tlint -W warning "$page" 2>&1)
	if [ $? -eq 0 ] && [ -z "$out" ]; then
		echo "ok $n - mandoc -Tlint $page"
	else
		echo "not ok $n - mandoc -Tlint $page"
		printf '%s\n' "$out" | sed 's/^/#   /'
	fi
done
echo "1..$n"
