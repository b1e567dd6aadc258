/* SPDX-License-Identifier: MIT */
/* pool.c: parallel_for over a shared atomic counter (see pool.h). */
#include "pool.h"

#include <pthread.h>
#include <stdlib.h>
#include <stdatomic.h>
#include <unistd.h>

#include "arena.h"

struct pf_job {
	long n;          /* items */
	pf_fn fn;        /* the work */
	void *ctx;       /* its context */
	atomic_long next; /* next item to claim */
};

struct pf_worker {
	struct pf_job *job;
	int id;          /* worker index */
};

static void *run(void *arg)
{
	const struct pf_worker *w = arg;
	struct pf_job *j = w->job;
	long i;
	while ((i = atomic_fetch_add_explicit(&j->next, 1, memory_order_relaxed)) < j->n)
		j->fn(j->ctx, i, w->id);
	return NULL;
}

void parallel_for(long n, int threads, pf_fn fn, void *ctx)
{
	if (n <= 0)
		return;
	int nt = threads < 1 ? 1 : threads;
	if (nt > n)
		nt = (int)n;
	struct pf_job j = {n, fn, ctx, 0};
	atomic_init(&j.next, 0);
	if (nt == 1) {
		for (long i = 0; i < n; i++)
			fn(ctx, i, 0);
		return;
	}
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
}

int pool_threads(int requested)
{
	if (requested > 0)
		return requested;
	long n = sysconf(_SC_NPROCESSORS_ONLN);
	return n > 0 ? (n > 256 ? 256 : (int)n) : 1;
}
