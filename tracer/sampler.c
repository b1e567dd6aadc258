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

uint64_t smp_permute(uint64_t i, uint64_t n, uint64_t key)
{
	if (n <= 1)
		return 0;
	int h = 1; /* half the bit width: 4^h >= n */
	while (h < 31 && (1ull << (2 * h)) < n)
		h++;
	uint64_t mask = (1ull << h) - 1;
	do { /* a bijection of [0, 4^h), applied again until it lands below n */
		uint64_t l = i >> h, r = i & mask;
		for (uint64_t round = 0; round < 4; round++) {
			uint64_t t = l ^ (smp_mix(r ^ key ^ round * 0x9e3779b97f4a7c15ull) & mask);
			l = r;
			r = t;
		}
		i = l << h | r;
	} while (i >= n);
	return i;
}

double smp_latin(uint64_t x, uint64_t y, uint64_t side, uint64_t key, double jitter)
{
	uint64_t a = smp_permute(x, side, smp_mix(key)), b = smp_permute(y, side, smp_mix(~key));
	return ((double)((a + b) % side) + jitter) / (double)side;
}
