/* SPDX-License-Identifier: MIT */
/* leafbox.c: slab tests of a few boxes against one ray (see leafbox.h).
 *
 * A slab's t, (lo - o)·(1/d), is off by at most 3 ulps of itself (one
 * rounding each in lo - o, 1/d and the product), so the entry t0 is moved
 * 1e-12 of itself earlier and the exit t1 as much later before they are
 * compared. An axis along which the ray does not move gives ±inf (the ray
 * is inside the slab or never is: then t0 = +inf or t1 = -inf, and the
 * comparison of NaN fails), or NaN (0·inf) where it lies in a face's
 * plane; then the box may count as missed (leafbox.h). Defining LEAFBOX_SCALAR picks the plain C version
 * (other CPUs) on x86 too. */
#include "leafbox.h"

#include <math.h>
#if defined(__SSE2__) && !defined(LEAFBOX_SCALAR)
#include <immintrin.h>
/* AVX (four doubles an operation) where the CPU has it, chosen when the
 * boxes are set; the same operations on the same numbers as SSE2's. */
#if defined(__GNUC__) && defined(__x86_64__)
#define LEAFBOX_AVX 1
#endif
#endif

void leafbox_set(struct leafbox *lb, int n, const struct bbox *b)
{
	lb->n = n;
#ifdef LEAFBOX_AVX
	__builtin_cpu_init();
	lb->wide = __builtin_cpu_supports("avx");
#else
	lb->wide = false;
#endif
	for (int i = 0; i < LEAFBOX_MAX; i++) { /* a spare lane repeats the last box */
		struct bbox x = b[i < n ? i : n - 1];
		lb->lo[0][i] = x.lo.x, lb->lo[1][i] = x.lo.y, lb->lo[2][i] = x.lo.z;
		lb->hi[0][i] = x.hi.x, lb->hi[1][i] = x.hi.y, lb->hi[2][i] = x.hi.z;
	}
}

#ifdef LEAFBOX_AVX
__attribute__((target("avx"))) static unsigned hits4(const struct leafbox *lb, const struct ray *r, double tmin,
                                                     double tmax, double at[LEAFBOX_MAX])
{
	const __m256d ox = _mm256_set1_pd(r->o.x), oy = _mm256_set1_pd(r->o.y), oz = _mm256_set1_pd(r->o.z);
	const __m256d ix = _mm256_set1_pd(1 / r->d.x), iy = _mm256_set1_pd(1 / r->d.y), iz = _mm256_set1_pd(1 / r->d.z);
	const __m256d slack = _mm256_set1_pd(1e-12), sign = _mm256_set1_pd(-0.0);
	unsigned hits = 0;
	for (int i = 0; i < lb->n; i += 4) {
		__m256d t0 = _mm256_set1_pd(tmin), t1 = _mm256_set1_pd(tmax), a, c;
#define SLAB(k, o, iv)                                                                                 \
	a = _mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(&lb->lo[k][i]), o), iv);                         \
	c = _mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(&lb->hi[k][i]), o), iv);                         \
	t0 = _mm256_max_pd(_mm256_min_pd(a, c), t0); /* NaN: t0 kept */                               \
	t1 = _mm256_min_pd(_mm256_max_pd(a, c), t1);
		SLAB(0, ox, ix) SLAB(1, oy, iy) SLAB(2, oz, iz)
#undef SLAB
		__m256d e = _mm256_sub_pd(t0, _mm256_mul_pd(slack, _mm256_andnot_pd(sign, t0)));
		__m256d ok = _mm256_cmp_pd(e, _mm256_add_pd(t1, _mm256_mul_pd(slack, _mm256_andnot_pd(sign, t1))), _CMP_LE_OQ);
		_mm256_storeu_pd(&at[i], e);
		hits |= (unsigned)_mm256_movemask_pd(ok) << i;
	}
	return hits & ((1u << lb->n) - 1);
}
#endif

#if defined(__SSE2__) && !defined(LEAFBOX_SCALAR)
unsigned leafbox_hits(const struct leafbox *lb, const struct ray *r, double tmin, double tmax,
                      double at[LEAFBOX_MAX])
{
#ifdef LEAFBOX_AVX
	if (lb->wide)
		return hits4(lb, r, tmin, tmax, at);
#endif
	const __m128d ox = _mm_set1_pd(r->o.x), oy = _mm_set1_pd(r->o.y), oz = _mm_set1_pd(r->o.z);
	const __m128d ix = _mm_set1_pd(1 / r->d.x), iy = _mm_set1_pd(1 / r->d.y), iz = _mm_set1_pd(1 / r->d.z);
	const __m128d slack = _mm_set1_pd(1e-12), sign = _mm_set1_pd(-0.0);
	unsigned hits = 0;
	for (int i = 0; i < lb->n; i += 2) {
		__m128d t0 = _mm_set1_pd(tmin), t1 = _mm_set1_pd(tmax), a, c;
#define SLAB(k, o, iv)                                                                                 \
	a = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(&lb->lo[k][i]), o), iv);                                  \
	c = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(&lb->hi[k][i]), o), iv);                                  \
	t0 = _mm_max_pd(_mm_min_pd(a, c), t0); /* NaN: t0 kept */                                     \
	t1 = _mm_min_pd(_mm_max_pd(a, c), t1);
		SLAB(0, ox, ix) SLAB(1, oy, iy) SLAB(2, oz, iz)
#undef SLAB
		__m128d e = _mm_sub_pd(t0, _mm_mul_pd(slack, _mm_andnot_pd(sign, t0)));
		__m128d ok = _mm_cmple_pd(e, _mm_add_pd(t1, _mm_mul_pd(slack, _mm_andnot_pd(sign, t1))));
		_mm_storeu_pd(&at[i], e);
		hits |= (unsigned)_mm_movemask_pd(ok) << i;
	}
	return hits & ((1u << lb->n) - 1);
}
#else
unsigned leafbox_hits(const struct leafbox *lb, const struct ray *r, double tmin, double tmax,
                      double at[LEAFBOX_MAX])
{
	const double o[3] = {r->o.x, r->o.y, r->o.z}, iv[3] = {1 / r->d.x, 1 / r->d.y, 1 / r->d.z};
	unsigned hits = 0;
	for (int i = 0; i < lb->n; i++) {
		double t0 = tmin, t1 = tmax;
		for (int k = 0; k < 3; k++) {
			double a = (lb->lo[k][i] - o[k]) * iv[k], c = (lb->hi[k][i] - o[k]) * iv[k];
			double n = a < c ? a : c, f = a < c ? c : a;
			t0 = n > t0 ? n : t0;
			t1 = f < t1 ? f : t1;
		}
		at[i] = t0 - 1e-12 * fabs(t0);
		if (at[i] <= t1 + 1e-12 * fabs(t1))
			hits |= 1u << i;
	}
	return hits;
}
#endif
