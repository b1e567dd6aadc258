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

/* A 64-bit mixing function (SplitMix64's finaliser). Inline, with the
 * three below: a light ray or a camera sample draws a few numbers each. */
static inline uint64_t smp_mix(uint64_t x)
{
	x += 0x9e3779b97f4a7c15ull;
	x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
	x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
	return x ^ (x >> 31);
}

/* The top 53 bits of a hash as a double in [0,1). */
static inline double smp_unit(uint64_t h) { return (double)(h >> 11) * (1.0 / 9007199254740992.0); }

/* The key of (pixel, sample). */
static inline uint64_t smp_key(uint64_t pixel, uint32_t sample)
{
	return smp_mix(smp_mix(pixel) ^ ((uint64_t)sample * 0xd1b54a32d192ed03ull));
}

/* The number in [0,1) for (pixel, sample, dim). */
static inline double smp_get(uint64_t pixel, uint32_t sample, uint32_t dim)
{
	return smp_unit(smp_mix(smp_key(pixel, sample) + dim * 0x9e3779b97f4a7c15ull));
}

/* Starts the stream of (pixel, sample) at dimension 0. */
static inline struct smp_stream smp_start(uint64_t pixel, uint32_t sample)
{
	return (struct smp_stream){smp_key(pixel, sample), 0};
}

/* The next number in [0,1) of the stream. */
static inline double smp_next(struct smp_stream *s)
{
	uint32_t d = s->dim++;
	return smp_unit(smp_mix(s->key + d * 0x9e3779b97f4a7c15ull));
}
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
