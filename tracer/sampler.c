/* SPDX-License-Identifier: MIT */
/* sampler.c: the keyed permutations and Latin squares of sampler.h (its
 * counter-based numbers are inline there). */
#include "sampler.h"

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
