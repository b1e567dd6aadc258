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

/* The box of lane i (struct leafbox): a leaf's, or in a split set lane 3's
 * box around leaves 3 to n-1; a spare lane repeats the last leaf. A ray
 * that meets one of those leaves' boxes meets lane 3's too: its slabs hold
 * the leaf's, and the rounded (lo - o)·(1/d) and the slack are monotone in
 * lo, so its entry is no later and its exit no earlier. */
static struct bbox lane_box(int n, bool split, const struct bbox *b, int i)
{
	if (!split)
		return b[i < n ? i : n - 1];
	if (i != 3)
		return b[i < 3 ? i : i - 1 < n ? i - 1 : n - 1];
	struct bbox u = b[3];
	for (int k = 4; k < n; k++) {
		u.lo = v3(d_min(u.lo.x, b[k].lo.x), d_min(u.lo.y, b[k].lo.y), d_min(u.lo.z, b[k].lo.z));
		u.hi = v3(d_max(u.hi.x, b[k].hi.x), d_max(u.hi.y, b[k].hi.y), d_max(u.hi.z, b[k].hi.z));
	}
	return u;
}

void leafbox_set(struct leafbox *lb, int n, const struct bbox *b)
{
	lb->n = n;
	lb->split = n >= 5 && n <= 7;
#ifdef LEAFBOX_AVX
	__builtin_cpu_init();
	lb->wide = __builtin_cpu_supports("avx");
#else
	lb->wide = false;
#endif
	for (int i = 0; i < LEAFBOX_MAX; i++) {
		struct bbox x = lane_box(n, lb->split, b, i);
		lb->lo[0][i] = x.lo.x, lb->lo[1][i] = x.lo.y, lb->lo[2][i] = x.lo.z;
		lb->hi[0][i] = x.hi.x, lb->hi[1][i] = x.hi.y, lb->hi[2][i] = x.hi.z;
	}
}

#ifdef LEAFBOX_AVX
/* Lanes i to i+3: their entries into at[0..3], and which are met (bits). */
__attribute__((target("avx"), always_inline)) static inline unsigned lanes4(const struct leafbox *lb, int i,
                                                                          const __m256d o[3], const __m256d iv[3],
                                                                          double tmin, double tmax, double *at)
{
	const __m256d slack = _mm256_set1_pd(1e-12), sign = _mm256_set1_pd(-0.0);
	__m256d t0 = _mm256_set1_pd(tmin), t1 = _mm256_set1_pd(tmax), a, c;
#define SLAB(k)                                                                                        \
	a = _mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(&lb->lo[k][i]), o[k]), iv[k]);                   \
	c = _mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(&lb->hi[k][i]), o[k]), iv[k]);                   \
	t0 = _mm256_max_pd(_mm256_min_pd(a, c), t0); /* NaN: t0 kept */                               \
	t1 = _mm256_min_pd(_mm256_max_pd(a, c), t1);
	SLAB(0) SLAB(1) SLAB(2)
#undef SLAB
	__m256d e = _mm256_sub_pd(t0, _mm256_mul_pd(slack, _mm256_andnot_pd(sign, t0)));
	__m256d ok = _mm256_cmp_pd(e, _mm256_add_pd(t1, _mm256_mul_pd(slack, _mm256_andnot_pd(sign, t1))), _CMP_LE_OQ);
	_mm256_storeu_pd(at, e);
	return (unsigned)_mm256_movemask_pd(ok);
}

__attribute__((target("avx"))) unsigned leafbox_wide(const struct leafbox *lb, const struct ray *r, double tmin,
                                                     double tmax, double at[LEAFBOX_MAX])
{
	const __m256d o[3] = {_mm256_set1_pd(r->o.x), _mm256_set1_pd(r->o.y), _mm256_set1_pd(r->o.z)};
	const __m256d iv[3] = {_mm256_set1_pd(1 / r->d.x), _mm256_set1_pd(1 / r->d.y), _mm256_set1_pd(1 / r->d.z)};
	unsigned hits = lanes4(lb, 0, o, iv, tmin, tmax, at);
	if (lb->split) /* lanes 4-7 are leaves 3-6, tested when their box is met */
		hits = (hits & 7) | (hits & 8 ? lanes4(lb, 4, o, iv, tmin, tmax, at + 3) << 3 : 0);
	else if (lb->n > 4)
		hits |= lanes4(lb, 4, o, iv, tmin, tmax, at + 4) << 4;
	return hits & ((1u << lb->n) - 1);
}
#endif

#if defined(__SSE2__) && !defined(LEAFBOX_SCALAR)
/* Lanes i and i+1: their entries into at[0..1], and which are met (bits). */
static inline unsigned lanes2(const struct leafbox *lb, int i, const __m128d o[3], const __m128d iv[3], double tmin,
                              double tmax, double *at)
{
	const __m128d slack = _mm_set1_pd(1e-12), sign = _mm_set1_pd(-0.0);
	__m128d t0 = _mm_set1_pd(tmin), t1 = _mm_set1_pd(tmax), a, c;
#define SLAB(k)                                                                                        \
	a = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(&lb->lo[k][i]), o[k]), iv[k]);                            \
	c = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(&lb->hi[k][i]), o[k]), iv[k]);                            \
	t0 = _mm_max_pd(_mm_min_pd(a, c), t0); /* NaN: t0 kept */                                     \
	t1 = _mm_min_pd(_mm_max_pd(a, c), t1);
	SLAB(0) SLAB(1) SLAB(2)
#undef SLAB
	__m128d e = _mm_sub_pd(t0, _mm_mul_pd(slack, _mm_andnot_pd(sign, t0)));
	__m128d ok = _mm_cmple_pd(e, _mm_add_pd(t1, _mm_mul_pd(slack, _mm_andnot_pd(sign, t1))));
	_mm_storeu_pd(at, e);
	return (unsigned)_mm_movemask_pd(ok);
}

unsigned leafbox_narrow(const struct leafbox *lb, const struct ray *r, double tmin, double tmax,
                        double at[LEAFBOX_MAX])
{
	const __m128d o[3] = {_mm_set1_pd(r->o.x), _mm_set1_pd(r->o.y), _mm_set1_pd(r->o.z)};
	const __m128d iv[3] = {_mm_set1_pd(1 / r->d.x), _mm_set1_pd(1 / r->d.y), _mm_set1_pd(1 / r->d.z)};
	unsigned hits = 0;
	if (lb->split) { /* as leafbox_wide: lanes 0-3, then lanes 4 on (leaves 3 on) when lane 3 is met */
		hits = lanes2(lb, 0, o, iv, tmin, tmax, at) | lanes2(lb, 2, o, iv, tmin, tmax, at + 2) << 2;
		if (!(hits & 8))
			return hits & 7;
		hits &= 7;
		for (int i = 4; i <= lb->n; i += 2)
			hits |= lanes2(lb, i, o, iv, tmin, tmax, at + i - 1) << (i - 1);
		return hits & ((1u << lb->n) - 1);
	}
	for (int i = 0; i < lb->n; i += 2)
		hits |= lanes2(lb, i, o, iv, tmin, tmax, at + i) << i;
	return hits & ((1u << lb->n) - 1);
}
#else
/* Lane i: its entry into *at, and whether it is met. */
static bool lane1(const struct leafbox *lb, int i, const double o[3], const double iv[3], double tmin, double tmax,
                  double *at)
{
	double t0 = tmin, t1 = tmax;
	for (int k = 0; k < 3; k++) {
		double a = (lb->lo[k][i] - o[k]) * iv[k], c = (lb->hi[k][i] - o[k]) * iv[k];
		double n = a < c ? a : c, f = a < c ? c : a;
		t0 = n > t0 ? n : t0;
		t1 = f < t1 ? f : t1;
	}
	*at = t0 - 1e-12 * fabs(t0);
	return *at <= t1 + 1e-12 * fabs(t1);
}

unsigned leafbox_narrow(const struct leafbox *lb, const struct ray *r, double tmin, double tmax,
                        double at[LEAFBOX_MAX])
{
	const double o[3] = {r->o.x, r->o.y, r->o.z}, iv[3] = {1 / r->d.x, 1 / r->d.y, 1 / r->d.z};
	unsigned hits = 0;
	for (int i = 0; i < lb->n; i++) {
		if (lb->split && i == 3) { /* lane 3 bounds leaves 3 on, in lanes 4 on */
			double u;
			if (!lane1(lb, 3, o, iv, tmin, tmax, &u))
				break;
		}
		int lane = lb->split && i >= 3 ? i + 1 : i;
		hits |= (unsigned)lane1(lb, lane, o, iv, tmin, tmax, &at[i]) << i;
	}
	return hits;
}
#endif

#ifndef LEAFBOX_AVX
/* No AVX here: lb->wide is never set, and this is never called. */
unsigned leafbox_wide(const struct leafbox *lb, const struct ray *r, double tmin, double tmax,
                      double at[LEAFBOX_MAX])
{
	return leafbox_narrow(lb, r, tmin, tmax, at);
}
#endif
