/* SPDX-License-Identifier: MIT */
/* spectrum.c: observer, colour conversion, wavelength sampling and the
 * dispersion law of `passes spectral` (see spectrum.h). */
#include "spectrum.h"

#include <math.h>
#include <pthread.h>

#define NBINS 470      /* 1 nm sampling bins over [SPEC_MIN, SPEC_MAX] */
#define QSTEPS 20      /* Simpson intervals per bin (0.05 nm) */

struct m3 {
	double a[3][3]; /* row-major */
};

/* What is computed once: the conversion and the sampling tables. */
static struct {
	struct m3 T;          /* XYZ → linear Rec.709, equal-energy white → r = g = b */
	double ybar;          /* ∫ȳ dλ over the range */
	double norm[3];       /* ∫ (k_c + a) dλ: the area of each channel's weight */
	double mass[NBINS];   /* probability of each bin (sums to 1) */
	double cdf[NBINS + 1];/* running sums of mass */
	double x[3];          /* ⟨1/λ²⟩_c = ∫ w_c/λ² dλ (nm⁻²): the channels' centroids */
} tab;

static pthread_once_t tab_once = PTHREAD_ONCE_INIT;

/* ==== the observer ======================================================= */

/* A Gaussian with different widths left and right of its peak mu. */
static double lobe(double l, double mu, double s1, double s2)
{
	double t = (l - mu) / (l < mu ? s1 : s2);
	return exp(-0.5 * t * t);
}

/* Wyman, Sloan and Shirley's multi-lobe fit (their table 1, CIE 1931 2°). */
void spec_cie(double l, double xyz[3])
{
	xyz[0] = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) -
	         0.065 * lobe(l, 501.1, 20.4, 26.2);
	xyz[1] = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1);
	xyz[2] = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8);
}

/* ==== 3×3 matrices ======================================================= */

static struct m3 m3_mul(struct m3 x, struct m3 y)
{
	struct m3 r;
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			r.a[i][j] = x.a[i][0] * y.a[0][j] + x.a[i][1] * y.a[1][j] + x.a[i][2] * y.a[2][j];
	return r;
}

static void m3_vec(const struct m3 *x, const double v[3], double o[3])
{
	double r[3];
	for (int i = 0; i < 3; i++)
		r[i] = x->a[i][0] * v[0] + x->a[i][1] * v[1] + x->a[i][2] * v[2];
	o[0] = r[0], o[1] = r[1], o[2] = r[2];
}

/* The inverse by cofactors (the matrices here are well conditioned). */
static struct m3 m3_inv(struct m3 x)
{
	double (*a)[3] = x.a;
	double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
	             a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
	             a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
	struct m3 r;
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++) {
			int r1 = (j + 1) % 3, r2 = (j + 2) % 3, c1 = (i + 1) % 3, c2 = (i + 2) % 3;
			r.a[i][j] = (a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]) / det;
		}
	return r;
}

/* XYZ → Rec.709 from the primaries' and D65's chromaticities (ITU-R
 * BT.709), after a Bradford adaptation from illuminant E (X = Y = Z) to D65. */
static struct m3 make_matrix(void)
{
	static const double xy[4][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, {0.3127, 0.3290}};
	const struct m3 brad = {{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367},
	                         {0.0389, -0.0685, 1.0296}}};
	struct m3 P, M;
	double W[3], S[3];
	for (int c = 0; c < 4; c++) { /* XYZ with Y = 1 of each primary, then of white */
		double x = xy[c][0], y = xy[c][1], v[3] = {x / y, 1, (1 - x - y) / y};
		for (int i = 0; i < 3; i++)
			*(c < 3 ? &P.a[i][c] : &W[i]) = v[i];
	}
	struct m3 Pi = m3_inv(P);
	m3_vec(&Pi, W, S); /* scale the primaries so that r = g = b = 1 is D65 */
	for (int i = 0; i < 3; i++)
		for (int c = 0; c < 3; c++)
			M.a[i][c] = P.a[i][c] * S[c];
	double e[3] = {1, 1, 1}, ce[3], cw[3];
	m3_vec(&brad, e, ce);
	m3_vec(&brad, W, cw);
	struct m3 D = {{{cw[0] / ce[0], 0, 0}, {0, cw[1] / ce[1], 0}, {0, 0, cw[2] / ce[2]}}};
	return m3_mul(m3_inv(M), m3_mul(m3_inv(brad), m3_mul(D, brad)));
}

/* ==== weights and tables ================================================= */

/* k(λ) and the white a(λ) that brings it into the gamut, before tab exists
 * (ybar must be set). */
static double colour_and_white(double l, double k[3])
{
	double xyz[3];
	spec_cie(l, xyz);
	m3_vec(&tab.T, xyz, k);
	double lo = 0;
	for (int c = 0; c < 3; c++) {
		k[c] /= tab.ybar;
		lo = fmin(lo, k[c]);
	}
	return -lo;
}

/* The unnormalised weights k_c + a at l (tab.norm not applied). */
static void raw_weights(double l, double w[3])
{
	double a = colour_and_white(l, w);
	for (int c = 0; c < 3; c++)
		w[c] += a;
}

/* Simpson's rule for ∫ f over [a, b] in n (even) intervals, per component. */
static void simpson(void (*f)(double, double[3]), double a, double b, int n, double out[3])
{
	double h = (b - a) / n;
	out[0] = out[1] = out[2] = 0;
	for (int i = 0; i <= n; i++) {
		double v[3], k = i == 0 || i == n ? 1 : i % 2 ? 4 : 2;
		f(a + i * h, v);
		for (int c = 0; c < 3; c++)
			out[c] += k * v[c] * h / 3;
	}
}

static void cie3(double l, double v[3]) { spec_cie(l, v); }

static void raw_over_l2(double l, double w[3])
{
	raw_weights(l, w);
	for (int c = 0; c < 3; c++)
		w[c] /= l * l;
}

/* Builds tab: the matrix, ∫ȳ, each channel's area, and the bins' masses
 * ∝ ∫ (w_R + w_G + w_B) over each 1 nm bin. */
static void build(void)
{
	double xyz[3], raw[NBINS][3], total = 0;
	tab.T = make_matrix();
	simpson(cie3, SPEC_MIN, SPEC_MAX, NBINS * QSTEPS, xyz);
	tab.ybar = xyz[1];
	tab.norm[0] = tab.norm[1] = tab.norm[2] = 0;
	for (int b = 0; b < NBINS; b++) {
		simpson(raw_weights, SPEC_MIN + b, SPEC_MIN + b + 1, QSTEPS, raw[b]);
		for (int c = 0; c < 3; c++)
			tab.norm[c] += raw[b][c];
	}
	simpson(raw_over_l2, SPEC_MIN, SPEC_MAX, NBINS * QSTEPS, tab.x);
	for (int c = 0; c < 3; c++)
		tab.x[c] /= tab.norm[c];
	for (int b = 0; b < NBINS; b++) {
		double m = 0;
		for (int c = 0; c < 3; c++)
			m += raw[b][c] / tab.norm[c];
		tab.mass[b] = fmax(m, 1e-12); /* every bin can be drawn */
		total += tab.mass[b];
	}
	tab.cdf[0] = 0;
	for (int b = 0; b < NBINS; b++) {
		tab.mass[b] /= total;
		tab.cdf[b + 1] = tab.cdf[b] + tab.mass[b];
	}
	tab.cdf[NBINS] = 1;
}

static void ready(void) { pthread_once(&tab_once, build); }

void spec_xyz_to_rgb(const double xyz[3], double rgb[3])
{
	ready();
	m3_vec(&tab.T, xyz, rgb);
}

void spec_colour(double lambda, double k[3])
{
	ready();
	colour_and_white(lambda, k);
}

void spec_weights(double lambda, double w[3])
{
	ready();
	if (!(lambda >= SPEC_MIN && lambda <= SPEC_MAX)) {
		w[0] = w[1] = w[2] = 0;
		return;
	}
	raw_weights(lambda, w);
	for (int c = 0; c < 3; c++)
		w[c] /= tab.norm[c];
}

double spec_pdf(double lambda)
{
	ready();
	if (!(lambda >= SPEC_MIN && lambda < SPEC_MAX))
		return 0;
	return tab.mass[(int)(lambda - SPEC_MIN)]; /* bins are 1 nm wide */
}

double spec_sample(double u, double f[3])
{
	ready();
	u = u > 0 ? (u < 1 ? u : 1 - 1e-16) : 0;
	int lo = 0, hi = NBINS; /* the bin b with cdf[b] <= u < cdf[b+1] */
	while (hi - lo > 1) {
		int mid = (lo + hi) / 2;
		if (tab.cdf[mid] <= u)
			lo = mid;
		else
			hi = mid;
	}
	double t = (u - tab.cdf[lo]) / tab.mass[lo];
	double lambda = SPEC_MIN + lo + (t > 0 ? (t < 1 ? t : 1) : 0);
	double w[3];
	spec_weights(lambda, w);
	for (int c = 0; c < 3; c++)
		f[c] = w[c] / tab.mass[lo];
	return lambda;
}

/* ==== dispersion ========================================================= */

double spec_centroid(int c)
{
	ready();
	return 1 / sqrt(tab.x[c]);
}

double spec_ior(double ior, double D, double lambda)
{
	if (D == 1 || !(lambda > 0))
		return ior;
	ready();
	/* n = A + B·x, x = 1/λ²: n(x_B) = D·n(x_R) fixes q = A/B, n(x_G) = ior
	 * fixes B */
	double xr = tab.x[0], xg = tab.x[1], xb = tab.x[2];
	double q = (D * xr - xb) / (1 - D), B = ior / (q + xg);
	double n = B * (q + 1 / (lambda * lambda));
	return n > 1e-3 ? n : 1e-3; /* an absurd D can drive the law through 0 */
}
