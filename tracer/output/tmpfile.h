/* SPDX-License-Identifier: MIT */
/* tmpfile.h: every output file is written to a temporary file beside it and
 * renamed into place only when complete (docs/design.md §6, "No partial
 * files"), so a failed or interrupted run never leaves a half-written file
 * and never touches an earlier file of that name.
 *
 * Open temporaries are registered, so that a signal handler can remove them
 * all with out_tmp_remove_all() before the process exits. */
#ifndef ARVO_TMPFILE_H
#define ARVO_TMPFILE_H

#include <stddef.h>

/* Creates "<path>.tmp.XXXXXX" (mode 0666 & ~umask) beside path; writes its
 * name into tmp (tmplen bytes), registers it and returns an open fd, or -1
 * (errno set). */
int out_tmp_create(const char *path, char *tmp, size_t tmplen);
/* Finishes a temp file: when ok, renames tmp to path; else (or when the
 * rename fails) removes tmp. Unregisters it. Returns 0, or -1 with errno set
 * when the rename failed. */
int out_tmp_finish(const char *tmp, const char *path, int ok);
/* Removes every registered temp file. Async-signal-safe: only unlink(2). */
void out_tmp_remove_all(void);

#endif
