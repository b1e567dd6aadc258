/* SPDX-License-Identifier: MIT */
/* pool.c: parallel_for over shared atomic counters (see pool.h). */
#include "pool.h"

#include <pthread.h>
#include <stdbool.h>
#include <stdlib.h>
#include <stdatomic.h>
#include <unistd.h>

#include "arena.h"

/* A run of items [next, end) that workers claim one at a time. */
struct pf_share {
	atomic_long next; /* next item to claim (may pass end) */
	long end;         /* one past the last item */
};

struct pf_job {
	pf_fn fn;                /* the work */
	void *ctx;               /* its context */
	struct pf_share *share;  /* the items, in nshares runs */
	int nshares;
};

struct pf_worker {
	struct pf_job *job;
	int id;          /* worker index */
};

/* Worker id empties its own share first (share id, or the only one), then
 * helps with the others, in turn. */
static void *run(void *arg)
{
	const struct pf_worker *w = arg;
	struct pf_job *j = w->job;
	for (int k = 0; k < j->nshares; k++) {
		struct pf_share *s = &j->share[(w->id + k) % j->nshares];
		long i;
		while ((i = atomic_fetch_add_explicit(&s->next, 1, memory_order_relaxed)) < s->end)
			j->fn(j->ctx, i, w->id);
	}
	return NULL;
}

/* Runs n items on up to `threads` threads: split into one share per
 * thread, or one share for all. */
static void run_all(long n, int threads, pf_fn fn, void *ctx, bool split)
{
	if (n <= 0)
		return;
	int nt = threads < 1 ? 1 : threads;
	if (nt > n)
		nt = (int)n;
	if (nt == 1) {
		for (long i = 0; i < n; i++)
			fn(ctx, i, 0);
		return;
	}
	int ns = split ? nt : 1;
	struct pf_share *sh = mem_calloc((size_t)ns, sizeof *sh);
	for (int k = 0; k < ns; k++) {
		atomic_init(&sh[k].next, n * k / ns);
		sh[k].end = n * (k + 1) / ns;
	}
	struct pf_job j = {fn, ctx, sh, ns};
	pthread_t *tid = mem_calloc((size_t)nt, sizeof *tid);
	struct pf_worker *ws = mem_calloc((size_t)nt, sizeof *ws);
	int started = 1;
	for (int k = 0; k < nt; k++)
		ws[k] = (struct pf_worker){&j, k};
	for (; started < nt; started++)
		if (pthread_create(&tid[started], NULL, run, &ws[started]) != 0)
			break;
	run(&ws[0]);
	for (int k = 1; k < started; k++)
		pthread_join(tid[k], NULL);
	free(ws);
	free(tid);
	free(sh);
}

void parallel_for(long n, int threads, pf_fn fn, void *ctx)
{
	run_all(n, threads, fn, ctx, false);
}

void parallel_for_shares(long n, int threads, pf_fn fn, void *ctx)
{
	run_all(n, threads, fn, ctx, true);
}

int pool_threads(int requested)
{
	if (requested > 0)
		return requested;
	long n = sysconf(_SC_NPROCESSORS_ONLN);
	return n > 0 ? (n > 256 ? 256 : (int)n) : 1;
}
