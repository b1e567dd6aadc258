/* SPDX-License-Identifier: MIT */
/* progress.c: the progress bar and its plain-line form (progress.h). */
#include "progress.h"

#include <string.h>
#include <time.h>
#include <unistd.h>

static double seconds(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

enum progress_mode progress_mode_for(int quiet)
{
	return quiet ? PROGRESS_OFF : isatty(2) ? PROGRESS_BAR : PROGRESS_LINES;
}

void progress_init(struct progress *p, enum progress_mode mode, FILE *f)
{
	memset(p, 0, sizeof *p);
	p->mode = mode;
	p->f = f;
	atomic_init(&p->done, 0);
	atomic_init(&p->shown, -1);
	pthread_mutex_init(&p->lock, NULL);
}

void progress_begin(struct progress *p, const char *what, long total)
{
	if (!p || p->mode == PROGRESS_OFF)
		return;
	snprintf(p->what, sizeof p->what, "%s", what);
	p->total = total > 0 ? total : 1;
	atomic_store(&p->done, 0);
	atomic_store(&p->shown, -1);
	p->t0 = seconds();
	progress_step(p, 0);
}

/* Writes " 3.2 s left" style text for the time remaining into buf. */
static void eta(char *buf, size_t n, double elapsed, long done, long total)
{
	if (done <= 0 || done >= total) {
		snprintf(buf, n, "%.1f s", elapsed);
		return;
	}
	double left = elapsed * (double)(total - done) / (double)done;
	if (left < 1)
		snprintf(buf, n, "%.1f s, under 1 s left", elapsed);
	else if (left < 60)
		snprintf(buf, n, "%.1f s, about %.0f s left", elapsed, left);
	else
		snprintf(buf, n, "%.1f s, about %.0f min left", elapsed, left / 60 + 0.5);
}

/* Draws the state for `step` (percent for the bar, tenth for lines). */
static void draw(struct progress *p, long done, int step)
{
	char t[64];
	eta(t, sizeof t, seconds() - p->t0, done, p->total);
	if (p->mode == PROGRESS_BAR) {
		int width = 30, fill = step * width / 100;
		fprintf(p->f, "\rarvo: %-14s [%.*s%*s] %3d%%  %-28s", p->what, fill,
		        "##############################", width - fill, "", step, t);
	} else if (step > 0 && step < 10) {
		fprintf(p->f, "arvo: progress: %s %d%% (%s)\n", p->what, step * 10, t);
	}
	fflush(p->f);
}

void progress_step(struct progress *p, long n)
{
	if (!p || p->mode == PROGRESS_OFF)
		return;
	long done = atomic_fetch_add_explicit(&p->done, n, memory_order_relaxed) + n;
	if (done > p->total)
		done = p->total;
	int step = (int)(done * (p->mode == PROGRESS_BAR ? 100 : 10) / p->total);
	int last = atomic_load_explicit(&p->shown, memory_order_relaxed);
	if (step <= last)
		return;
	pthread_mutex_lock(&p->lock);
	/* another thread may have drawn it, or a later step: the lines show
	 * every tenth passed, in order, the bar only the latest */
	int from = atomic_load(&p->shown) + 1;
	if (step >= from) {
		atomic_store(&p->shown, step);
		for (int s = p->mode == PROGRESS_LINES ? from : step; s <= step; s++)
			draw(p, done, s);
	}
	pthread_mutex_unlock(&p->lock);
}

void progress_end(struct progress *p)
{
	if (!p || p->mode == PROGRESS_OFF)
		return;
	pthread_mutex_lock(&p->lock);
	double el = seconds() - p->t0;
	if (p->mode == PROGRESS_BAR) { /* the final time, then a new line */
		draw(p, p->total, 100);
		fputc('\n', p->f);
	} else {
		fprintf(p->f, "arvo: progress: %s done (%.1f s)\n", p->what, el);
	}
	fflush(p->f);
	pthread_mutex_unlock(&p->lock);
}

void progress_destroy(struct progress *p)
{
	if (p)
		pthread_mutex_destroy(&p->lock);
}
