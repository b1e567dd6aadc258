/* SPDX-License-Identifier: MIT */
/* sampler.h: a counter-based random number generator (docs/design.md §7).
 *
 * Every random number is a pure function of (pixel, sample, dimension): no
 * state is shared between threads or carried between pixels, so an image is
 * bit-identical for any thread count and any run. A stream walks the
 * dimensions of one (pixel, sample) in the order a path consumes them. */
#ifndef ARVO_SAMPLER_H
#define ARVO_SAMPLER_H

#include <stdint.h>

/* The random numbers of one camera sample. */
struct smp_stream {
	uint64_t key; /* hash of (pixel, sample) */
	uint32_t dim; /* next dimension to hand out */
};

/* A 64-bit mixing function (SplitMix64's finaliser). */
uint64_t smp_mix(uint64_t x);
/* The number in [0,1) for (pixel, sample, dim). */
double smp_get(uint64_t pixel, uint32_t sample, uint32_t dim);
/* Starts the stream of (pixel, sample) at dimension 0. */
struct smp_stream smp_start(uint64_t pixel, uint32_t sample);
/* The next number in [0,1) of the stream. */
double smp_next(struct smp_stream *s);
/* A keyed permutation of 0..n−1 (n < 2^62): a 4-round Feistel network on
 * the smallest even bit width that holds n, cycle-walked into [0, n). */
uint64_t smp_permute(uint64_t i, uint64_t n, uint64_t key);
/* One more stratified dimension for the sample (x, y) of a side×side grid,
 * in [0,1): a keyed Latin square, stratum (ρ(x) + π(y)) mod side with ρ, π
 * keyed permutations, jittered inside. Every row and every column of the
 * grid (and so any strip along either, and the whole grid) takes each of
 * the side strata once, in a scrambled order (no lattice pattern to alias). */
double smp_latin(uint64_t x, uint64_t y, uint64_t side, uint64_t key, double jitter);

#endif
