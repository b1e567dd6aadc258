/* SPDX-License-Identifier: MIT */
/* poly.c: the polynomial surfaces F(x,y,z) = 0 of POV-Ray's poly { N, <…> },
 * quartic { <35 coefficients> }, cubic { <20> } and quadric { <A,B,C>,
 * <D,E,F>, <G,H,I>, J }, all kept as a list of non-zero terms a·xⁱyʲzᵏ of
 * total degree ≤ order (eval/geometry.c turns each syntax into it). As in
 * POV-Ray, the inside is F < 0 and the surface is unbounded unless a
 * clipped_by or bounded_by limits it.
 *
 * Intersection: along the ray from q, its point nearest the object origin,
 * with a unit direction d, each term's (q + s·d) powers multiply out into
 * one polynomial in s of degree ≤ order, whose roots in the ray's interval
 * come from Sturm sequences (tracer/polysolve.c), so POV-Ray's `sturm` is
 * always on. The normal is ∇F.
 *
 * Parametrisation: none is natural, so the radial one of implicit surfaces
 * about the object origin (prim.h; docs/parametrisations.md): (u,v) are the
 * sphere's angles of the direction from the origin, T(u,v) the first
 * surface point that way. Cell areas are integrated numerically. */
#include <math.h>

#include "../polysolve.h"
#include "prim.h"

#define PN POLY_MAX_DEGREE

/* The coefficients of (a + b·s)ⁱ, i = 0..n: out[i][k] is that of sᵏ. */
static void powers(double a, double b, int n, double out[PN + 1][PN + 1])
{
	out[0][0] = 1;
	for (int i = 1; i <= n; i++) {
		out[i][i] = out[i - 1][i - 1] * b;
		for (int k = i - 1; k >= 1; k--)
			out[i][k] = out[i - 1][k] * a + out[i - 1][k - 1] * b;
		out[i][0] = out[i - 1][0] * a;
	}
}

/* F(q + s·d) as a polynomial in s (c[0..order]). */
static void along(const struct polynomial *P, struct vec3 q, struct vec3 d, double *c)
{
	double px[PN + 1][PN + 1], py[PN + 1][PN + 1], pz[PN + 1][PN + 1];
	int n = P->order;
	powers(q.x, d.x, n, px);
	powers(q.y, d.y, n, py);
	powers(q.z, d.z, n, pz);
	for (int k = 0; k <= n; k++)
		c[k] = 0;
	for (int t = 0; t < P->nterms; t++) {
		const struct poly_term *T = &P->t[t];
		int i = T->e[0], j = T->e[1], l = T->e[2];
		double xy[2 * PN + 1];
		for (int k = 0; k <= i + j; k++)
			xy[k] = 0;
		for (int a = 0; a <= i; a++)
			for (int b = 0; b <= j; b++)
				xy[a + b] += px[i][a] * py[j][b];
		for (int a = 0; a <= i + j; a++)
			for (int b = 0; b <= l; b++)
				c[a + b] += T->a * xy[a] * pz[l][b];
	}
}

/* xⁱ for small integer i (0⁰ = 1). */
static double ipow(double x, int i)
{
	double r = 1;
	while (i-- > 0)
		r *= x;
	return r;
}

static double poly_value(const struct polynomial *P, struct vec3 p)
{
	double f = 0;
	for (int t = 0; t < P->nterms; t++)
		f += P->t[t].a * ipow(p.x, P->t[t].e[0]) * ipow(p.y, P->t[t].e[1]) *
		     ipow(p.z, P->t[t].e[2]);
	return f;
}

static struct vec3 poly_grad(const struct polynomial *P, struct vec3 p)
{
	double g[3] = {0, 0, 0}, x[3] = {p.x, p.y, p.z};
	for (int t = 0; t < P->nterms; t++) {
		const struct poly_term *T = &P->t[t];
		for (int k = 0; k < 3; k++) {
			if (T->e[k] == 0)
				continue;
			double m = T->a * T->e[k];
			for (int j = 0; j < 3; j++)
				m *= ipow(x[j], T->e[j] - (j == k));
			g[k] += m;
		}
	}
	return v3(g[0], g[1], g[2]);
}

static bool po_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	const struct polynomial *P = o->g.poly.p;
	double L = v_len(r->d);
	if (!(L > 0))
		return false;
	struct vec3 d = v_scale(r->d, 1 / L);
	double tc = -v_dot(r->o, d);
	struct vec3 q = v_madd(r->o, d, tc);
	double c[PN + 1], s[PN];
	along(P, q, d, c);
	int n = poly_roots(c, P->order, tmin * L - tc, tmax * L - tc, s);
	for (int i = 0; i < n; i++) {
		double t = (tc + s[i]) / L;
		if (!(t > tmin && t < tmax))
			continue;
		lh->t = t;
		lh->p = v_madd(q, d, s[i]);
		lh->n = poly_grad(P, lh->p);
		if (!(v_dot(lh->n, lh->n) > 0)) /* a singular point: face the ray */
			lh->n = v_neg(d);
		prim_radial_hit(v3(0, 0, 0), lh);
		return true;
	}
	return false;
}

static bool po_inside(const struct object *o, struct vec3 p)
{
	return poly_value(o->g.poly.p, p) < 0;
}

static struct bbox po_bounds(const struct object *o)
{
	(void)o;
	return prim_infinite_box();
}

static bool po_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	return prim_radial_point(o, v3(0, 0, 0), po_intersect, u, v, p, dpdu, dpdv);
}

static struct uv_range po_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, true, false};
}

static double po_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	return shape_integrate_area(o, u0, u1, fmax(v0, 0), fmin(v1, 1));
}

static void po_dump(const struct object *o, FILE *out)
{
	const struct polynomial *P = o->g.poly.p;
	fprintf(out, "order %d", P->order);
	for (int t = 0; t < P->nterms; t++)
		fprintf(out, " %.6g*x%dy%dz%d", P->t[t].a + 0.0, P->t[t].e[0], P->t[t].e[1],
		        P->t[t].e[2]);
}

const struct prim_ops shape_poly_ops = {
	po_intersect, po_inside, po_bounds, po_uv_point, po_uv_range, po_cell_area, po_dump, NULL,
};
