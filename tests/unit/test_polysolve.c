/* SPDX-License-Identifier: MIT */
/* test_polysolve.c: tracer/polysolve.c against polynomials built from known
 * roots: simple, clustered, near-double, exactly double, with a vanishing
 * leading coefficient, and restricted to an interval. */
#include <stdio.h>

#include "../../tracer/polysolve.h"
#include "test.h"

/* c = ∏ (x − r[i]) times lead, ascending coefficients; returns the degree. */
static int from_roots(const double *r, int n, double lead, double *c)
{
	c[0] = lead;
	for (int i = 1; i <= n; i++)
		c[i] = 0;
	for (int k = 0; k < n; k++) {
		for (int i = k + 1; i > 0; i--)
			c[i] = c[i - 1] - r[k] * c[i];
		c[0] = -r[k] * c[0];
	}
	return n;
}

static void t_simple(void)
{
	double r[4] = {-3, -0.5, 1, 2.25}, c[5], x[8];
	from_roots(r, 4, 2, c);
	int n = poly_roots(c, 4, -INFINITY, INFINITY, x);
	CHECK(n == 4);
	for (int i = 0; i < n && i < 4; i++)
		CHECK_NEAR(x[i], r[i], 1e-14);
	/* the open interval (−0.5, 2): only 1 */
	n = poly_roots(c, 4, -0.5, 2, x);
	CHECK(n == 1);
	CHECK_NEAR(x[0], 1, 1e-14);
}

static void t_degrees(void)
{
	double x[8];
	double lin[2] = {-3, 2}; /* 2x − 3 */
	CHECK(poly_roots(lin, 1, -10, 10, x) == 1);
	CHECK_NEAR(x[0], 1.5, 0);
	double quad[3] = {1, 0, 1}; /* x² + 1: none */
	CHECK(poly_roots(quad, 2, -INFINITY, INFINITY, x) == 0);
	double r6[6] = {-2.5, -1, -0.25, 0.5, 1.75, 3}, c6[7];
	from_roots(r6, 6, -0.7, c6);
	CHECK(poly_roots(c6, 6, -INFINITY, INFINITY, x) == 6);
	for (int i = 0; i < 6; i++)
		CHECK_NEAR(x[i], r6[i], 1e-13);
	/* a cubic with one real root: x³ + x + 10 = (x + 2)(x² − 2x + 5) */
	double cub[4] = {10, 1, 0, 1};
	CHECK(poly_roots(cub, 3, -INFINITY, INFINITY, x) == 1);
	CHECK_NEAR(x[0], -2, 1e-14);
}

/* Two roots 1e-6 apart (a ray grazing a surface) are both found. Rounding
 * the coefficients alone moves such a root by ε·|c|/|p′(r)| ≈ 1e-15/6e-6,
 * about 2e-10, so that is the tolerance there. */
static void t_near_double(void)
{
	double r[4] = {-2, 1, 1 + 1e-6, 3}, c[5], x[8];
	from_roots(r, 4, 1, c);
	int n = poly_roots(c, 4, -INFINITY, INFINITY, x);
	CHECK(n == 4);
	for (int i = 0; i < n && i < 4; i++)
		CHECK_NEAR(x[i], r[i], i == 1 || i == 2 ? 5e-10 : 1e-14);
	/* 1e-4 apart in a sextic */
	double r6[6] = {-1, 0.3, 0.5, 0.5001, 2, 4}, c6[7];
	from_roots(r6, 6, 1, c6);
	n = poly_roots(c6, 6, -INFINITY, INFINITY, x);
	CHECK(n == 6);
	for (int i = 0; i < n && i < 6; i++)
		CHECK_NEAR(x[i], r6[i], 1e-10);
}

/* An exact double root (a tangent ray): one root, located by the count. */
static void t_double(void)
{
	double r[4] = {-1, 0.5, 0.5, 2}, c[5], x[8];
	from_roots(r, 4, 1, c);
	int n = poly_roots(c, 4, -INFINITY, INFINITY, x);
	CHECK(n == 3);
	CHECK_NEAR(x[0], -1, 1e-14);
	CHECK_NEAR(x[1], 0.5, 1e-7);
	CHECK_NEAR(x[2], 2, 1e-14);
	/* (x − 1)² (x² + 1): the double root only */
	double q[5] = {1, -2, 2, -2, 1};
	n = poly_roots(q, 4, -INFINITY, INFINITY, x);
	CHECK(n == 1);
	CHECK_NEAR(x[0], 1, 1e-7);
}

/* A root at zero and a vanishing leading coefficient. */
static void t_degenerate(void)
{
	double x[8];
	double c[5] = {0, -6, 1, 1, 1e-20}; /* x(x² + x − 6) = x(x+3)(x−2), quartic term negligible */
	int n = poly_roots(c, 4, -INFINITY, INFINITY, x);
	CHECK(n == 3);
	CHECK_NEAR(x[0], -3, 1e-14);
	CHECK_NEAR(x[1], 0, 0);
	CHECK_NEAR(x[2], 2, 1e-14);
	double z[5] = {0, 0, 0, 0, 0};
	CHECK(poly_roots(z, 4, -1, 1, x) == 0);
	/* roots of very different sizes */
	double r[4] = {-1e3, 1e-3, 1, 1e4}, w[5];
	from_roots(r, 4, 1, w);
	n = poly_roots(w, 4, -INFINITY, INFINITY, x);
	CHECK(n == 4);
	for (int i = 0; i < n && i < 4; i++)
		CHECK_NEAR(x[i], r[i], 1e-12 * fabs(r[i]));
}

int main(void)
{
	RUN(t_simple);
	RUN(t_degrees);
	RUN(t_near_double);
	RUN(t_double);
	RUN(t_degenerate);
	return test_done();
}
