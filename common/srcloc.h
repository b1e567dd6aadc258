/* SPDX-License-Identifier: MIT */
/* srcloc.h: source locations and the table of files read by a run. */
#ifndef ARVO_SRCLOC_H
#define ARVO_SRCLOC_H

#include <stddef.h>

struct srcloc {
	int file; /* index into the file table; -1 for "no location" (command line) */
	int line; /* 1-based line */
	int col;  /* 1-based column, in bytes */
};

/* One loaded source file; kept for the whole run so diagnostics can quote lines. */
struct srcfile {
	char *name; /* path as the user or #include named it */
	char *text; /* NUL-terminated contents */
	size_t len; /* length of text in bytes */
};

/* Registers a file (takes ownership of name and text); returns its index. */
int srcfile_add(char *name, char *text, size_t len);
/* The file with this index, or NULL. */
const struct srcfile *srcfile_get(int file);
/* Number of registered files. */
int srcfile_count(void);
/* Frees every registered file. */
void srcfile_free_all(void);
/* Reads a whole file; returns NULL (and sets errno) when it cannot. */
char *srcfile_read(const char *path, size_t *len);

#endif
