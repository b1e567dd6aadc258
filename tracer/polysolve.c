/* SPDX-License-Identifier: MIT */
/* polysolve.c: real polynomial roots by Sturm sequences.
 *
 * The Sturm chain of p is s₀ = p, s₁ = p′, sₖ₊₁ = −(sₖ₋₁ mod sₖ). For x not a
 * root, the number of sign changes V(x) along the chain falls by one at each
 * distinct real root, so V(a) − V(b) counts the roots in (a,b]. Intervals are
 * bisected until each holds one root; a simple root then shows as a sign
 * change of p and is refined by Newton steps kept inside the bracket. A root
 * of even multiplicity shows no sign change: its interval is bisected on the
 * count alone until it is as narrow as doubles allow.
 *
 * Floating-point remainders never cancel to exactly zero: each coefficient of
 * a remainder carries a running bound of the rounding in the products and
 * sums that made it, and a coefficient below that bound is taken as zero. The
 * chain then ends at the numerical gcd, as it would for a multiple root. */
#include "polysolve.h"

#include <float.h>
#include <stdbool.h>
#include <stddef.h>
#include <math.h>

#define NMAX POLY_MAX_DEGREE

double poly_eval(const double *c, int n, double x, double *d)
{
	double p = c[n], dp = 0;
	for (int i = n - 1; i >= 0; i--) {
		dp = dp * x + p;
		p = p * x + c[i];
	}
	if (d)
		*d = dp;
	return p;
}

struct chain {
	int len;                   /* polynomials in the chain */
	int deg[NMAX + 1];         /* degree of each */
	double c[NMAX + 1][NMAX + 1]; /* their coefficients, ascending, leading ±1 */
};

/* Scales c so its leading coefficient has magnitude 1. */
static void unit_lead(double *c, int n)
{
	double s = 1 / fabs(c[n]);
	for (int i = 0; i <= n; i++)
		c[i] *= s;
}

/* −(a mod b) into r with its degree, coefficients within their rounding
 * bound set to zero; -1 when the remainder vanishes. b's leading
 * coefficient is ±1. */
static int neg_rem(const double *a, int na, const double *b, int nb, double *r)
{
	double w[NMAX + 1], e[NMAX + 1];
	for (int i = 0; i <= na; i++) {
		w[i] = a[i];
		e[i] = fabs(a[i]);
	}
	for (int k = na - nb; k >= 0; k--) {
		double q = w[k + nb] / b[nb];
		for (int j = 0; j <= nb; j++) {
			double t = q * b[j];
			w[k + j] -= t;
			e[k + j] += fabs(t);
		}
		w[k + nb] = 0;
	}
	int nr = nb - 1;
	for (int i = 0; i <= nr; i++)
		r[i] = fabs(w[i]) <= 32 * DBL_EPSILON * e[i] ? 0 : -w[i];
	while (nr >= 0 && r[nr] == 0)
		nr--;
	return nr;
}

static void build(struct chain *s, const double *c, int n)
{
	for (int i = 0; i <= n; i++)
		s->c[0][i] = c[i];
	s->deg[0] = n;
	unit_lead(s->c[0], n);
	for (int i = 1; i <= n; i++)
		s->c[1][i - 1] = i * s->c[0][i];
	s->deg[1] = n - 1;
	unit_lead(s->c[1], n - 1);
	s->len = 2;
	while (s->deg[s->len - 1] > 0) {
		int k = s->len;
		int d = neg_rem(s->c[k - 2], s->deg[k - 2], s->c[k - 1], s->deg[k - 1], s->c[k]);
		if (d < 0)
			break;
		unit_lead(s->c[k], d);
		s->deg[k] = d;
		s->len++;
	}
}

/* Sign changes along the chain at x (zeros skipped). */
static int changes(const struct chain *s, double x)
{
	int v = 0;
	double last = 0;
	for (int i = 0; i < s->len; i++) {
		double f = poly_eval(s->c[i], s->deg[i], x, NULL);
		if (f == 0)
			continue;
		if (last != 0 && (f < 0) != (last < 0))
			v++;
		last = f;
	}
	return v;
}

double poly_refine(const double *c, int n, double lo, double hi, double flo)
{
	double x = 0.5 * (lo + hi);
	for (int it = 0; it < 200; it++) {
		double d, f = poly_eval(c, n, x, &d);
		if (f == 0)
			return x;
		if ((f < 0) == (flo < 0))
			lo = x;
		else
			hi = x;
		double nx = d != 0 ? x - f / d : 0.5 * (lo + hi);
		if (!(nx > lo && nx < hi))
			nx = 0.5 * (lo + hi);
		if (nx == x || hi - lo <= 2 * DBL_EPSILON * fmax(fabs(lo), fabs(hi)))
			return nx;
		x = nx;
	}
	return x;
}

/* Roots in (a,b], given the sign-change counts at both ends. */
static void isolate(const struct chain *s, double a, double b, int va, int vb, int depth,
                    double *out, int *k)
{
	int nr = va - vb;
	if (nr <= 0)
		return;
	const double *p = s->c[0];
	int n = s->deg[0];
	if (nr == 1) {
		double fa = poly_eval(p, n, a, NULL), fb = poly_eval(p, n, b, NULL);
		if (fb == 0) {
			out[(*k)++] = b;
			return;
		}
		if (fa != 0 && (fa < 0) != (fb < 0)) {
			out[(*k)++] = poly_refine(p, n, a, b, fa);
			return;
		}
	}
	double m = 0.5 * (a + b);
	if (depth >= 200 || !(m > a && m < b) || b - a <= 4 * DBL_EPSILON * fmax(fabs(a), fabs(b))) {
		out[(*k)++] = m; /* a multiple root, or a cluster doubles cannot split */
		return;
	}
	int vm = changes(s, m);
	isolate(s, a, m, va, vm, depth + 1, out, k);
	isolate(s, m, b, vm, vb, depth + 1, out, k);
}

int poly_roots(const double *c, int n, double lo, double hi, double *roots)
{
	if (n > NMAX || !(hi > lo))
		return 0;
	double big = 0;
	for (int i = 0; i <= n; i++)
		big = fmax(big, fabs(c[i]));
	if (!(big > 0) || !isfinite(big))
		return 0;
	while (n > 0 && fabs(c[n]) <= 1e-14 * big)
		n--;
	int low = 0; /* a root at 0 of this multiplicity */
	while (low < n && c[low] == 0)
		low++;
	double q[NMAX + 1];
	for (int i = low; i <= n; i++)
		q[i - low] = c[i];
	n -= low;
	int k = 0;
	double tmp[NMAX + 1];
	if (n == 1) {
		tmp[k++] = -q[0] / q[1];
	} else if (n == 2) {
		double disc = q[1] * q[1] - 4 * q[2] * q[0];
		if (disc >= 0) {
			double h = -0.5 * (q[1] + copysign(sqrt(disc), q[1]));
			double r0 = h / q[2], r1 = h != 0 ? q[0] / h : r0;
			tmp[k++] = fmin(r0, r1);
			if (r1 != r0)
				tmp[k++] = fmax(r0, r1);
		}
	} else if (n > 2) {
		/* every root lies within Cauchy's bound 1 + max |qᵢ/qₙ| */
		double bound = 0;
		for (int i = 0; i < n; i++)
			bound = fmax(bound, fabs(q[i] / q[n]));
		bound = 1 + bound;
		double a = fmax(lo, -bound), b = fmin(hi, bound);
		if (b > a) {
			struct chain s;
			build(&s, q, n);
			isolate(&s, a, b, changes(&s, a), changes(&s, b), 0, tmp, &k);
		}
	}
	/* merge in the zero root, keep (lo,hi), ascending (isolate's order) */
	int m = 0;
	bool zero_done = low == 0;
	for (int i = 0; i <= k; i++) {
		if (!zero_done && (i == k || tmp[i] >= 0)) {
			if (0 > lo && 0 < hi)
				roots[m++] = 0;
			zero_done = true;
		}
		if (i < k && tmp[i] > lo && tmp[i] < hi && !(m > 0 && roots[m - 1] == tmp[i]))
			roots[m++] = tmp[i];
	}
	return m;
}
