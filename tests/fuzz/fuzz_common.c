/* SPDX-License-Identifier: MIT */
/* fuzz_common.c: the private directory the fuzz targets write inputs into. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz.h"

static char dir[64];
static char files[4][96];
static int nfiles;

static void cleanup(void)
{
	for (int i = 0; i < nfiles; i++)
		remove(files[i]);
	if (dir[0])
		rmdir(dir);
}

const char *fuzz_file(const char *name, const uint8_t *data, size_t size)
{
	if (!dir[0]) {
		const char *tmp = getenv("TMPDIR");
		snprintf(dir, sizeof dir, "%s/arvo-fuzz.XXXXXX", tmp && strlen(tmp) < 40 ? tmp : "/tmp");
		if (!mkdtemp(dir)) {
			perror("fuzz: mkdtemp");
			abort();
		}
		atexit(cleanup);
	}
	int i = 0;
	char path[96];
	snprintf(path, sizeof path, "%s/%s", dir, name);
	while (i < nfiles && strcmp(files[i], path) != 0)
		i++;
	if (i == nfiles && nfiles < 4)
		memcpy(files[nfiles++], path, sizeof path);
	FILE *f = fopen(files[i], "wb");
	if (!f || fwrite(data, 1, size, f) != size || fclose(f) != 0) {
		perror("fuzz: writing the input");
		abort();
	}
	return files[i];
}
