/* SPDX-License-Identifier: MIT */
/* sampler.h: a counter-based random number generator (DESIGN.md §7).
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
/* A third stratified dimension for a side×side grid of samples numbered row
 * by row (i = x + side·y, 0 <= i < side², side < 2^21): smp_grid_stratum
 * gives sample i's stratum, a permutation of 0..side²−1 that steps by
 * about side²/ρ along x and side²/ρ² along y (ρ the plastic number, as in
 * Roberts' R2 sequence), so every small block of the grid takes strata
 * from the whole range. */
struct smp_grid {
	uint64_t side;  /* grid side */
	uint64_t m, q;  /* stratum = i·m mod side², m = side·p + q */
};

struct smp_grid smp_grid_make(uint64_t side);
uint64_t smp_grid_stratum(const struct smp_grid *g, uint64_t i);

#endif
