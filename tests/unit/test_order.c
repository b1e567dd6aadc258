/* SPDX-License-Identifier: MIT */
/* test_order.c: order_nth (common/order.c) gives, for every k, the value a
 * sort puts at a[k], and leaves nothing greater before it and nothing
 * smaller after it: on random, sorted, reversed, constant and two-valued
 * arrays, and on an array built to defeat median-of-three pivots. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "../../common/order.h"
#include "test.h"

static int cmp(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

static uint64_t rng = 88172645463325252u;
static double next(void)
{
	rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
	return (double)(rng >> 11) * 0x1p-53;
}

/* Checks every k of a[0..n) against a sorted copy; returns the failures. */
static int check_all(const double *a, long n)
{
	double *s = malloc(sizeof *s * (size_t)n), *w = malloc(sizeof *w * (size_t)n);
	memcpy(s, a, sizeof *s * (size_t)n);
	qsort(s, (size_t)n, sizeof *s, cmp);
	int bad = 0;
	for (long k = 0; k < n; k++) {
		memcpy(w, a, sizeof *w * (size_t)n);
		double v = order_nth(w, n, k);
		bad += v != s[k] || w[k] != v;
		for (long i = 0; i < k; i++)
			bad += w[i] > v;
		for (long i = k + 1; i < n; i++)
			bad += w[i] < v;
	}
	free(s), free(w);
	return bad;
}

static void t_shapes(void)
{
	enum { N = 301 };
	double a[N];
	for (int i = 0; i < N; i++)
		a[i] = next();
	CHECK(check_all(a, N) == 0);
	CHECK(check_all(a, 1) == 0 && check_all(a, 2) == 0 && check_all(a, 3) == 0);
	for (int i = 0; i < N; i++)
		a[i] = i;
	CHECK(check_all(a, N) == 0); /* sorted */
	for (int i = 0; i < N; i++)
		a[i] = N - i;
	CHECK(check_all(a, N) == 0); /* reversed */
	for (int i = 0; i < N; i++)
		a[i] = 0.5;
	CHECK(check_all(a, N) == 0); /* constant */
	for (int i = 0; i < N; i++)
		a[i] = next() < 0.5 ? -1.0 : 1.0;
	CHECK(check_all(a, N) == 0); /* two values */
	/* organ pipe: the median of first, middle and last is small each round */
	for (int i = 0; i < N; i++)
		a[i] = i < N / 2 ? i : N - i;
	CHECK(check_all(a, N) == 0);
}

/* A large array: the 5th, 50th and 95th percentiles as a sort gives them. */
static void t_percentiles(void)
{
	long n = 200001;
	double *a = malloc(sizeof *a * (size_t)n), *s = malloc(sizeof *s * (size_t)n);
	for (long i = 0; i < n; i++)
		a[i] = s[i] = next() * next();
	qsort(s, (size_t)n, sizeof *s, cmp);
	long k95 = (long)(0.95 * (double)(n - 1)), k05 = (long)(0.05 * (double)(n - 1));
	CHECK(order_nth(a, n, k95) == s[k95]);
	CHECK(order_nth(a, k95 + 1, k05) == s[k05]); /* within what lies below the 95th */
	CHECK(order_nth(a, n, n / 2) == s[n / 2]);
	free(a), free(s);
}

int main(void)
{
	RUN(t_shapes);
	RUN(t_percentiles);
	return test_done();
}
