/* SPDX-License-Identifier: MIT */
/* test_pool.c: parallel_for and parallel_for_shares visit every item exactly
 * once, name workers in range, and fill the same slots for any thread
 * count. */
#include <stdatomic.h>
#include <stdlib.h>

#include "../../common/pool.h"
#include "test.h"

#define N 10007

struct ctx {
	atomic_int hits[N];  /* times item i ran */
	long out[N];         /* what item i wrote */
	int threads;         /* workers allowed */
	atomic_int bad;      /* worker index out of range */
};

static void item(void *arg, long i, int worker)
{
	struct ctx *c = arg;
	if (worker < 0 || worker >= c->threads)
		atomic_fetch_add(&c->bad, 1);
	atomic_fetch_add(&c->hits[i], 1);
	c->out[i] = i * i % 9973;
}

static void run_with(void (*pf)(long, int, pf_fn, void *), int threads, long n)
{
	struct ctx *c = calloc(1, sizeof *c);
	c->threads = threads;
	pf(n, threads, item, c);
	int once = 1, right = 1;
	for (long i = 0; i < N; i++) {
		once &= atomic_load(&c->hits[i]) == (i < n ? 1 : 0);
		right &= c->out[i] == (i < n ? i * i % 9973 : 0);
	}
	CHECK(once);
	CHECK(right);
	CHECK(atomic_load(&c->bad) == 0);
	free(c);
}

static void run(int threads, long n) { run_with(parallel_for, threads, n); }
static void run_shares(int threads, long n) { run_with(parallel_for_shares, threads, n); }

static void t_one_thread(void) { run(1, N); }
static void t_two_threads(void) { run(2, N); }
static void t_more_threads_than_items(void) { run(7, 3); }
static void t_no_items(void) { run(4, 0); }
/* shares: N = 10007 cut into 2, 3 and 7 runs of unequal length; fewer
 * items than threads; none */
static void t_shares(void)
{
	run_shares(1, N);
	run_shares(2, N);
	run_shares(3, N);
	run_shares(7, N);
	run_shares(7, 3);
	run_shares(4, 0);
}

static void t_default_threads(void)
{
	CHECK(pool_threads(3) == 3);
	CHECK(pool_threads(0) >= 1 && pool_threads(0) <= 256);
}

int main(void)
{
	RUN(t_one_thread);
	RUN(t_two_threads);
	RUN(t_more_threads_than_items);
	RUN(t_no_items);
	RUN(t_shares);
	RUN(t_default_threads);
	return test_done();
}
