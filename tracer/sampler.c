/* SPDX-License-Identifier: MIT */
/* sampler.c: counter-based random numbers keyed by (pixel, sample, dim). */
#include "sampler.h"

uint64_t smp_mix(uint64_t x)
{
	x += 0x9e3779b97f4a7c15ull;
	x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
	x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
	return x ^ (x >> 31);
}

/* Maps the top 53 bits of a hash to a double in [0,1). */
static double to_unit(uint64_t h)
{
	return (double)(h >> 11) * (1.0 / 9007199254740992.0);
}

static uint64_t key_of(uint64_t pixel, uint32_t sample)
{
	return smp_mix(smp_mix(pixel) ^ ((uint64_t)sample * 0xd1b54a32d192ed03ull));
}

double smp_get(uint64_t pixel, uint32_t sample, uint32_t dim)
{
	return to_unit(smp_mix(key_of(pixel, sample) + dim * 0x9e3779b97f4a7c15ull));
}

struct smp_stream smp_start(uint64_t pixel, uint32_t sample)
{
	return (struct smp_stream){key_of(pixel, sample), 0};
}

double smp_next(struct smp_stream *s)
{
	uint32_t d = s->dim++;
	return to_unit(smp_mix(s->key + d * 0x9e3779b97f4a7c15ull));
}

static uint64_t gcd(uint64_t a, uint64_t b)
{
	while (b) {
		uint64_t t = a % b;
		a = b;
		b = t;
	}
	return a;
}

/* The stratum is i·m mod n with m = side·p + q, n = side²: a permutation
 * when gcd(q, side) = 1, with steps m/n ≈ p/side along x and q/side along y
 * (p ≈ side/ρ, q the integer coprime to side nearest side/ρ²). */
struct smp_grid smp_grid_make(uint64_t side)
{
	const double rho = 1.32471795724474602596; /* the real root of x³ = x + 1 */
	struct smp_grid g = {side, 0, 0};
	if (side <= 1)
		return g;
	uint64_t p = (uint64_t)((double)side / rho + 0.5) % side;
	uint64_t q0 = (uint64_t)((double)side / (rho * rho) + 0.5), q = q0;
	for (uint64_t k = 1; gcd(q % side, side) != 1; k++) /* nearest first: q0+1, q0-1, q0+2 ... */
		q = k % 2 ? q0 + (k + 1) / 2 : (q0 > k / 2 ? q0 - k / 2 : 1);
	g.q = q % side;
	g.m = side * p + g.q;
	return g;
}

/* i·m mod side², without overflow for side < 2^21: x·m < side³ and the
 * y part is side·(q·y mod side). */
uint64_t smp_grid_stratum(const struct smp_grid *g, uint64_t i)
{
	uint64_t side = g->side, n = side * side;
	if (side <= 1)
		return 0;
	uint64_t x = i % side, y = i / side % side;
	return (x * g->m % n + side * (g->q * y % side)) % n;
}
