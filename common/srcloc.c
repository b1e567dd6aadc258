/* SPDX-License-Identifier: MIT */
/* srcloc.c: the table of source files read by a run. */
#include "srcloc.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "arena.h"

static struct srcfile *files; /* every file loaded, in order */
static int nfiles, capfiles;

int srcfile_add(char *name, char *text, size_t len)
{
	if (nfiles == capfiles) {
		capfiles = capfiles ? capfiles * 2 : 16;
		files = mem_realloc(files, sizeof *files * (size_t)capfiles);
	}
	files[nfiles] = (struct srcfile){name, text, len};
	return nfiles++;
}

const struct srcfile *srcfile_get(int file)
{
	return file >= 0 && file < nfiles ? &files[file] : NULL;
}

int srcfile_count(void) { return nfiles; }

void srcfile_free_all(void)
{
	for (int i = 0; i < nfiles; i++) {
		free(files[i].name);
		free(files[i].text);
	}
	free(files);
	files = NULL;
	nfiles = capfiles = 0;
}

char *srcfile_read(const char *path, size_t *len)
{
	FILE *fp = fopen(path, "rb");
	if (!fp)
		return NULL;
	size_t cap = 4096, n = 0;
	char *buf = mem_alloc(cap);
	for (;;) {
		if (n + 1 >= cap) {
			cap *= 2;
			buf = mem_realloc(buf, cap);
		}
		size_t got = fread(buf + n, 1, cap - n - 1, fp);
		n += got;
		if (got == 0)
			break;
	}
	int bad = ferror(fp);
	fclose(fp);
	if (bad) {
		free(buf);
		errno = EIO;
		return NULL;
	}
	buf[n] = '\0';
	*len = n;
	return buf;
}
