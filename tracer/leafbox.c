/* SPDX-License-Identifier: MIT */
/* leafbox.c: slab tests of a few boxes against one ray (see leafbox.h).
 *
 * A slab's t, (lo - o)·(1/d), is off by at most 3 ulps of itself (one
 * rounding each in lo - o, 1/d and the product), so a box counts as met
 * when the interval's ends t0 <= t1 hold within 1e-12 of their magnitudes,
 * and its entry is moved 1e-12 of itself earlier. An axis along which the
 * ray does not move gives ±inf (the ray is inside the slab or never is),
 * or NaN (0·inf) where it lies in a face's plane; then the box may count
 * as missed (leafbox.h). Defining LEAFBOX_SCALAR picks the plain C version
 * (other CPUs) on x86 too. */
#include "leafbox.h"

#include <math.h>
#if defined(__SSE2__) && !defined(LEAFBOX_SCALAR)
#include <emmintrin.h>
#endif

void leafbox_set(struct leafbox *lb, int n, const struct bbox *b)
{
	lb->n = n;
	for (int i = 0; i < LEAFBOX_MAX; i++) { /* a spare lane repeats the last box */
		struct bbox x = b[i < n ? i : n - 1];
		lb->lo[0][i] = x.lo.x, lb->lo[1][i] = x.lo.y, lb->lo[2][i] = x.lo.z;
		lb->hi[0][i] = x.hi.x, lb->hi[1][i] = x.hi.y, lb->hi[2][i] = x.hi.z;
	}
}

#if defined(__SSE2__) && !defined(LEAFBOX_SCALAR)
unsigned leafbox_hits(const struct leafbox *lb, const struct ray *r, double tmin, double tmax,
                      double at[LEAFBOX_MAX])
{
	const __m128d ox = _mm_set1_pd(r->o.x), oy = _mm_set1_pd(r->o.y), oz = _mm_set1_pd(r->o.z);
	const __m128d ix = _mm_set1_pd(1 / r->d.x), iy = _mm_set1_pd(1 / r->d.y), iz = _mm_set1_pd(1 / r->d.z);
	const __m128d slack = _mm_set1_pd(1e-12), sign = _mm_set1_pd(-0.0);
	unsigned hits = 0;
	for (int i = 0; i < lb->n; i += 2) {
		__m128d t0 = _mm_set1_pd(tmin), t1 = _mm_set1_pd(tmax), a, c;
#define SLAB(k, o, iv)                                                                                 \
	a = _mm_mul_pd(_mm_sub_pd(_mm_load_pd(&lb->lo[k][i]), o), iv);                                  \
	c = _mm_mul_pd(_mm_sub_pd(_mm_load_pd(&lb->hi[k][i]), o), iv);                                  \
	t0 = _mm_max_pd(_mm_min_pd(a, c), t0); /* NaN: t0 kept */                                     \
	t1 = _mm_min_pd(_mm_max_pd(a, c), t1);
		SLAB(0, ox, ix) SLAB(1, oy, iy) SLAB(2, oz, iz)
#undef SLAB
		__m128d a0 = _mm_andnot_pd(sign, t0), a1 = _mm_andnot_pd(sign, t1);
		__m128d ok = _mm_cmple_pd(t0, _mm_add_pd(t1, _mm_mul_pd(slack, _mm_add_pd(a0, a1))));
		_mm_storeu_pd(&at[i], _mm_sub_pd(t0, _mm_mul_pd(slack, a0)));
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
		if (t0 <= t1 + 1e-12 * (fabs(t0) + fabs(t1)))
			hits |= 1u << i;
	}
	return hits;
}
#endif
