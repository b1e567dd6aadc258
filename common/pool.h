/* SPDX-License-Identifier: MIT */
/* pool.h: the one way arvo runs work in parallel (docs/design.md §7).
 *
 * parallel_for runs fn(ctx, i, worker) for every i in [0, n) on up to
 * `threads` threads, the caller's included, and returns when all are done.
 * Items are claimed in order from a shared counter; `worker` (0 ≤ worker <
 * threads) names the thread running the item, for per-thread scratch. The
 * result is the same for any thread count as long as what fn writes depends
 * on i alone (its own output slot, or sums that are exact in any order). When
 * a thread cannot be started the others take its share. */
#ifndef ARVO_POOL_H
#define ARVO_POOL_H

typedef void (*pf_fn)(void *ctx, long i, int worker);

void parallel_for(long n, int threads, pf_fn fn, void *ctx);
/* As parallel_for, but the items are first cut into one run of consecutive
 * items per thread: thread k claims the items of run k in order, then helps
 * with the other runs. Neighbouring items (the tiles of a band of the
 * image) stay on one core, whose cache then holds the part of the scene
 * they see, instead of both cores fetching the same parts. */
void parallel_for_shares(long n, int threads, pf_fn fn, void *ctx);
/* The number of threads to use: `requested` when positive, else one per
 * online CPU (at most 256). */
int pool_threads(int requested);

#endif
