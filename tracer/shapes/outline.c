/* SPDX-License-Identifier: MIT */
/* outline.c: 2D outlines of polynomial pieces (outline.h): roots, the
 * point-in-outline test and the fill side of each piece.
 *
 * The inside test casts a ray from the point towards +x and counts the
 * pieces crossing it. Each piece is split where y(s) turns, so every part is
 * monotone in y; a part crosses when one end is above the ray and the other
 * is not (the half-open rule, which counts a shared end point once and a
 * vertex the outline only touches zero or two times). End points are the
 * exact values the pieces share, not the polynomial evaluated at 0 and 1. */
#include "outline.h"
#include "../polysolve.h"

#include <math.h>
#include <stddef.h>


int outline_roots(const double *c, int n, double lo, double hi, double *out)
{
	while (n > 0 && c[n] == 0)
		n--;
	if (n == 0)
		return 0;
	if (n == 1) {
		double x = -c[0] / c[1];
		out[0] = x;
		return x >= lo && x <= hi;
	}
	double dc[6], b[8];
	for (int i = 1; i <= n; i++)
		dc[i - 1] = i * c[i];
	int m = outline_roots(dc, n - 1, lo, hi, b + 1), k = 0;
	b[0] = lo;
	b[m + 1] = hi;
	for (int i = 0; i <= m; i++) {
		double f0 = poly_eval(c, n, b[i], NULL), f1 = poly_eval(c, n, b[i + 1], NULL);
		if (f0 == 0) {
			if (k == 0 || out[k - 1] != b[i])
				out[k++] = b[i];
		} else if ((f0 < 0) != (f1 < 0) && f1 != 0) {
			out[k++] = poly_refine(c, n, b[i], b[i + 1], f0);
		}
	}
	if (poly_eval(c, n, hi, NULL) == 0 && (k == 0 || out[k - 1] != hi))
		out[k++] = hi;
	return k;
}

void curve2_eval(const struct curve2 *c, double s, double *x, double *y, double *dx, double *dy)
{
	double px = poly_eval(c->x, 3, s, dx), py = poly_eval(c->y, 3, s, dy);
	if (x)
		*x = s == 0 ? c->p0[0] : s == 1 ? c->p1[0] : px;
	if (y)
		*y = s == 0 ? c->p0[1] : s == 1 ? c->p1[1] : py;
}

struct curve2 curve2_make(const double cx[4], const double cy[4], const double p0[2],
                          const double p1[2])
{
	struct curve2 c = {.left = 1};
	for (int k = 0; k < 4; k++) {
		c.x[k] = cx[k];
		c.y[k] = cy[k];
	}
	c.p0[0] = p0[0], c.p0[1] = p0[1], c.p1[0] = p1[0], c.p1[1] = p1[1];
	/* bounds: the end points and the turning points of each coordinate */
	for (int a = 0; a < 2; a++) {
		const double *q = a ? c.y : c.x;
		double d[3] = {q[1], 2 * q[2], 3 * q[3]}, r[3];
		c.lo[a] = fmin(p0[a], p1[a]);
		c.hi[a] = fmax(p0[a], p1[a]);
		int m = outline_roots(d, 2, 0, 1, r);
		for (int i = 0; i < m; i++) {
			double v = poly_eval(q, 3, r[i], NULL);
			c.lo[a] = fmin(c.lo[a], v);
			c.hi[a] = fmax(c.hi[a], v);
		}
	}
	return c;
}

/* The crossings of the line at height y with piece c, right of x: their
 * x (INFINITY when the whole piece is right of xfar ≥ x, which needs no
 * solving) and direction (+1 upwards) into xs, ds; returns how many. The
 * half-open rule counts a part when one end is above y and the other is
 * not. */
static int crossings(const struct curve2 *c, double x, double xfar, double y, double *xs, int *ds)
{
	if (c->lo[1] > y || c->hi[1] < y || c->hi[0] <= x)
		return 0;
	double cut[4] = {0}, r[2];
	int nc = 1, k = 0;
	double d[3] = {c->y[1], 2 * c->y[2], 3 * c->y[3]};
	int m = outline_roots(d, 2, 0, 1, r);
	for (int i = 0; i < m; i++)
		if (r[i] > 0 && r[i] < 1)
			cut[nc++] = r[i];
	cut[nc++] = 1;
	double q[4] = {c->y[0] - y, c->y[1], c->y[2], c->y[3]};
	for (int i = 0; i + 1 < nc; i++) {
		double ya, yb;
		curve2_eval(c, cut[i], NULL, &ya, NULL, NULL);
		curve2_eval(c, cut[i + 1], NULL, &yb, NULL, NULL);
		bool a = ya > y, b = yb > y;
		if (a == b)
			continue;
		double px = INFINITY;
		if (!(c->lo[0] > xfar)) {
			double s = c->y[2] == 0 && c->y[3] == 0 ? (y - c->p0[1]) / (c->p1[1] - c->p0[1])
			                                         : poly_refine(q, 3, cut[i], cut[i + 1], ya - y);
			curve2_eval(c, s, &px, NULL, NULL, NULL);
		}
		if (px > x) {
			xs[k] = px;
			ds[k++] = b ? 1 : -1;
		}
	}
	return k;
}

/* Is a point with winding w (and crossing parity odd) filled? */
static bool filled(const struct outline *ol, int w, int odd) { return ol->nonzero ? w != 0 : odd; }

bool outline_inside(const struct outline *ol, double x, double y)
{
	if (x < ol->lo[0] || x > ol->hi[0] || y < ol->lo[1] || y > ol->hi[1])
		return false;
	int w = 0, odd = 0, ds[3];
	double xs[3];
	for (int i = 0; i < ol->n; i++) {
		int k = crossings(&ol->seg[i], x, x, y, xs, ds);
		for (int j = 0; j < k; j++)
			w += ds[j], odd ^= 1;
	}
	return filled(ol, w, odd);
}

void outline_finish(struct outline *ol)
{
	ol->lo[0] = ol->lo[1] = INFINITY;
	ol->hi[0] = ol->hi[1] = -INFINITY;
	for (int i = 0; i < ol->n; i++)
		for (int a = 0; a < 2; a++) {
			ol->lo[a] = fmin(ol->lo[a], ol->seg[i].lo[a]);
			ol->hi[a] = fmax(ol->hi[a], ol->seg[i].hi[a]);
		}
	double eps = 1e-7 * fmax(ol->hi[0] - ol->lo[0], ol->hi[1] - ol->lo[1]);
	/* which side of each piece is filled: probe just off its middle */
	for (int i = 0; i < ol->n; i++) {
		struct curve2 *c = &ol->seg[i];
		double px, py, tx, ty;
		curve2_eval(c, 0.5, &px, &py, &tx, &ty);
		double len = hypot(tx, ty);
		c->left = 1;
		if (!(len > 0))
			continue;
		double lx = -ty / len * eps, ly = tx / len * eps;
		bool l = outline_inside(ol, px + lx, py + ly), r = outline_inside(ol, px - lx, py - ly);
		if (r && !l)
			c->left = -1;
	}
}

double outline_rect_area(const struct outline *ol, double x0, double x1, double y0, double y1)
{
	x0 = fmax(x0, ol->lo[0]);
	x1 = fmin(x1, ol->hi[0]);
	y0 = fmax(y0, ol->lo[1]);
	y1 = fmin(y1, ol->hi[1]);
	if (!(x1 > x0) || !(y1 > y0))
		return 0;
	bool crossed = false;
	for (int i = 0; i < ol->n && !crossed; i++) {
		const struct curve2 *c = &ol->seg[i];
		crossed = c->lo[0] <= x1 && c->hi[0] >= x0 && c->lo[1] <= y1 && c->hi[1] >= y0;
	}
	double full = (x1 - x0) * (y1 - y0);
	if (!crossed)
		return outline_inside(ol, 0.5 * (x0 + x1), 0.5 * (y0 + y1)) ? full : 0;
	/* 16 rows of 16 points: each row's crossings once, then its points */
	int in = 0;
	for (int j = 0; j < 16; j++) {
		double y = y0 + (j + 0.5) / 16 * (y1 - y0), xs[64];
		int ds[64], nx = 0;
		for (int i = 0; i < ol->n; i++) {
			double cx[3];
			int cd[3], k = crossings(&ol->seg[i], x0, x1, y, cx, cd);
			for (int m = 0; m < k; m++) {
				if (nx == 64) /* more than 64 crossings in one row: test each point */
					goto slow;
				xs[nx] = cx[m], ds[nx++] = cd[m];
			}
		}
		for (int i = 0; i < 16; i++) {
			double x = x0 + (i + 0.5) / 16 * (x1 - x0);
			int w = 0, odd = 0;
			for (int m = 0; m < nx; m++)
				if (xs[m] > x)
					w += ds[m], odd ^= 1;
			in += filled(ol, w, odd);
		}
		continue;
	slow:
		for (int i = 0; i < 16; i++)
			in += outline_inside(ol, x0 + (i + 0.5) / 16 * (x1 - x0), y);
	}
	return full * in / 256.0;
}
