/* SPDX-License-Identifier: MIT */
/* diag.h: the diagnostics sink: "file:line:col: error: msg", the source line and a caret. */
#ifndef ARVO_DIAG_H
#define ARVO_DIAG_H

#include <stdio.h>

#include "srcloc.h"

enum diag_kind { DIAG_ERROR, DIAG_WARNING, DIAG_NOTE };

/* Why a stage failed. The values are the exit statuses main.c gives them
 * (README "Exit codes"); library code reports the reason to a diag, returns
 * one of these and never exits. */
enum fail {
	FAIL_NONE = 0,      /* success */
	FAIL_USAGE = 64,    /* a bad option value (unknown OCIO display or view) */
	FAIL_SCENE = 65,    /* the scene is invalid */
	FAIL_INPUT = 66,    /* an input file is missing, unreadable, broken or foreign */
	FAIL_INTERNAL = 70, /* a bug or an exhausted resource */
	FAIL_CREATE = 73,   /* an output file cannot be created */
	FAIL_WRITE = 74     /* an output file cannot be written (disk full, I/O error) */
};

/* Counts what was reported; library code reports here and never exits. */
struct diag {
	FILE *out;      /* where messages go (stderr); NULL: only counted and kept in last */
	int errors;     /* errors reported so far */
	int warnings;   /* warnings reported so far */
	int max_errors; /* stop quoting after this many errors (0: no limit) */
	char last[2048]; /* the text of the last error or warning, without location */
};

void diag_init(struct diag *d, FILE *out);
/* Reports a message at loc; a loc with file < 0 prints "arvo: " instead. */
void diag_report(struct diag *d, enum diag_kind kind, struct srcloc loc, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));
/* Reports an error at loc and returns status (for `return diag_fail(...)`). */
int diag_fail(struct diag *d, int status, struct srcloc loc, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));
#define diag_error(d, loc, ...) diag_report((d), DIAG_ERROR, (loc), __VA_ARGS__)
#define diag_warning(d, loc, ...) diag_report((d), DIAG_WARNING, (loc), __VA_ARGS__)
#define diag_note(d, loc, ...) diag_report((d), DIAG_NOTE, (loc), __VA_ARGS__)

/* A location with no file, for errors about the command line. */
static inline struct srcloc srcloc_none(void) { return (struct srcloc){-1, 0, 0}; }

#endif
