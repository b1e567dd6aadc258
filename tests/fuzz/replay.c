/* SPDX-License-Identifier: MIT */
/* replay.c: runs a fuzz target's LLVMFuzzerTestOneInput on each file named
 * on the command line, without libFuzzer: the regression inputs under
 * tests/fuzz/<target>/ in make check (tests/fuzz/run.sh). A crash kills the
 * run; otherwise it prints one "ok" TAP line per file. */
#include <stdio.h>
#include <stdlib.h>

#include "../../common/arena.h"
#include "fuzz.h"

int main(int argc, char **argv)
{
	for (int i = 1; i < argc; i++) {
		FILE *f = fopen(argv[i], "rb");
		if (!f) {
			printf("not ok - %s: cannot open\n", argv[i]);
			continue;
		}
		size_t cap = 4096, n = 0, k;
		uint8_t *buf = mem_alloc(cap);
		while ((k = fread(buf + n, 1, cap - n, f)) > 0)
			if ((n += k) == cap)
				buf = mem_realloc(buf, cap *= 2);
		fclose(f);
		LLVMFuzzerTestOneInput(buf, n);
		free(buf);
		printf("ok - %s\n", argv[i]);
		fflush(stdout);
	}
	return 0;
}
