/* SPDX-License-Identifier: MIT */
/* progress.h: a progress report for a long pass on stderr (docs/design.md §8).
 * On a terminal it is a bar redrawn in place with the time left; otherwise
 * one plain line at every tenth ("arvo: progress: eye pass 30% ..."), so
 * logs stay short; --quiet turns it off. Workers call progress_step from
 * any thread: an atomic add, and a lock only when the shown value changes.
 * It writes to stderr only and never touches what is rendered. */
#ifndef ARVO_PROGRESS_H
#define ARVO_PROGRESS_H

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>

enum progress_mode { PROGRESS_OFF, PROGRESS_BAR, PROGRESS_LINES };

struct progress {
	enum progress_mode mode; /* how it shows (PROGRESS_OFF: not at all) */
	FILE *f;                 /* where (stderr) */
	char what[64];           /* the pass's name, e.g. "light pass" */
	long total;              /* units of work in the pass */
	atomic_long done;        /* units finished */
	atomic_int shown;        /* last step shown: percent (bar) or tenth (lines) */
	double t0;               /* when the pass began (monotonic seconds) */
	pthread_mutex_t lock;    /* serialises the output */
};

/* The mode for a run: off when quiet, a bar when stderr is a terminal,
 * else plain lines. */
enum progress_mode progress_mode_for(int quiet);
void progress_init(struct progress *p, enum progress_mode mode, FILE *f);
/* Starts a pass of total units (again after each pass). */
void progress_begin(struct progress *p, const char *what, long total);
/* n more units done; p may be NULL. Thread-safe. */
void progress_step(struct progress *p, long n);
/* Ends the pass: the bar's last state and a newline, or a closing line. */
void progress_end(struct progress *p);
void progress_destroy(struct progress *p);

#endif
