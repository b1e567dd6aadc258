/* SPDX-License-Identifier: MIT */
/* tmpfile.c: temp file + rename, with a registry of open temporaries that a
 * signal handler can remove. */
#include "tmpfile.h"

#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAX_OPEN 16 /* temporaries open at once (one per output being written) */

/* A slot is published (used = 1) only after its name is complete, and
 * cleared before the name changes, so a handler that interrupts either step
 * sees a whole name or none. */
static struct {
	volatile sig_atomic_t used; /* 1 while name is a live temp file */
	char name[PATH_MAX + 32];   /* its path */
} slots[MAX_OPEN];
static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;

/* The process umask, read once (umask can only be read by setting it). */
static mode_t file_mode(void)
{
	static mode_t mode = 01000; /* sentinel: not read yet */
	if (mode == 01000) {
		mode_t m = umask(022);
		umask(m);
		mode = 0666 & ~m;
	}
	return mode;
}

/* Takes a free slot and fills it with the template tmp; -1 when all are
 * in use. The slot is published before mkstemp fills in the name and
 * creates the file, so a signal in any thread at any moment finds either
 * a name not created yet (unlink fails harmlessly) or the temporary. */
static int reg(const char *tmp)
{
	int k = -1;
	pthread_mutex_lock(&lock);
	for (int i = 0; i < MAX_OPEN && k < 0; i++)
		if (!slots[i].used) {
			strcpy(slots[i].name, tmp);
			slots[i].used = 1;
			k = i;
		}
	pthread_mutex_unlock(&lock);
	return k;
}

static void unreg(const char *tmp)
{
	pthread_mutex_lock(&lock);
	for (int i = 0; i < MAX_OPEN; i++)
		if (slots[i].used && strcmp(slots[i].name, tmp) == 0) {
			slots[i].used = 0;
			break;
		}
	pthread_mutex_unlock(&lock);
}

/* mkstemp beside the target (in the registered slot), then the mode a plain
 * fopen would have given. */
int out_tmp_create(const char *path, char *tmp, size_t tmplen)
{
	int n = snprintf(tmp, tmplen, "%s.tmp.XXXXXX", path);
	if (n < 0 || (size_t)n >= tmplen || (size_t)n >= sizeof slots[0].name) {
		errno = ENAMETOOLONG;
		return -1;
	}
	int k = reg(tmp);
	if (k < 0) {
		errno = EMFILE;
		return -1;
	}
	int fd = mkstemp(slots[k].name);
	int e = errno;
	strcpy(tmp, slots[k].name);
	if (fd < 0) {
		slots[k].used = 0;
	} else if (fchmod(fd, file_mode()) != 0) {
		e = errno;
		close(fd);
		out_tmp_finish(tmp, path, 0);
		fd = -1;
	}
	errno = e;
	return fd;
}

/* Commit (rename) or abandon (unlink) a temp file; unlink also after a failed
 * rename. The slot is freed last: a signal in between unlinks a name that
 * is gone (harmless). */
int out_tmp_finish(const char *tmp, const char *path, int ok)
{
	int rc = ok && rename(tmp, path) == 0 ? 0 : -1;
	int e = errno;
	if (rc != 0)
		unlink(tmp);
	unreg(tmp);
	errno = e;
	return ok ? rc : 0;
}

void out_tmp_remove_all(void)
{
	for (int i = 0; i < MAX_OPEN; i++)
		if (slots[i].used)
			unlink(slots[i].name);
}
