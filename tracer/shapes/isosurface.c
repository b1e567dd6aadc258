/* SPDX-License-Identifier: MIT */
/* isosurface.c: isosurface { function { f } contained_by { box | sphere }
 * threshold t max_gradient g accuracy a [open] }.
 *
 * The solid is the part of the container where g(p) = f(p) − t < 0. Its
 * surface is g = 0 inside the container and, unless `open`, the container's
 * walls where g < 0 (the solid is cut by the container, as in POV-Ray).
 *
 * Root finding: along the ray, |g| cannot change faster than max_gradient
 * per unit length (the user's bound, POV-Ray's default 1.1), so from a point
 * where g has magnitude |g| no root lies nearer than |g|/max_gradient. The
 * march steps by that distance (at least `accuracy`) until g changes sign,
 * then bisects to the precision of doubles. A max_gradient below the function's true
 * gradient can step over thin parts, as in POV-Ray. The normal is the
 * gradient of f by central differences.
 *
 * (u,v): the radial parametrisation of the implicit surfaces about the
 * container's centre (docs/parametrisations.md, "Implicit surfaces"):
 * T(u,v) is the first surface point from the centre in the direction
 * (u,v), found by this same march. */
#include <math.h>

#include "../fn.h"
#include "prim.h"

#define ISO(o) ((o)->g.isosurface.iso)
#define MAX_STEPS 1000000 /* march steps per ray: bounds the time a ray can take */

/* g(p) = f(p) − threshold; NaN reads as outside. */
static double g_at(const struct isosurface *s, struct vec3 p)
{
	double a[FN_MAX_PARAMS] = {p.x, p.y, p.z};
	double v = fn_eval(s->fn, a) - s->threshold;
	return v == v ? v : INFINITY;
}

/* The container's entry and exit along the ray, and their normals. */
static bool container(const struct isosurface *s, const struct ray *r, double *t0, double *t1,
                      struct vec3 *n0, struct vec3 *n1)
{
	if (s->sphere) {
		struct vec3 f = v_sub(r->o, s->c);
		double a = v_dot(r->d, r->d), b = 2 * v_dot(f, r->d), c = v_dot(f, f) - s->r * s->r;
		if (!prim_quadratic(a, b, c, b * b - 4 * a * c, t0, t1))
			return false;
		*n0 = v_sub(ray_at(*r, *t0), s->c);
		*n1 = v_sub(ray_at(*r, *t1), s->c);
		return true;
	}
	double lo = -INFINITY, hi = INFINITY;
	double o[3] = {r->o.x, r->o.y, r->o.z}, d[3] = {r->d.x, r->d.y, r->d.z};
	double bl[3] = {s->lo.x, s->lo.y, s->lo.z}, bh[3] = {s->hi.x, s->hi.y, s->hi.z};
	int alo = 0, ahi = 0;
	double slo = -1, shi = 1;
	for (int k = 0; k < 3; k++) {
		if (d[k] == 0) {
			if (o[k] < bl[k] || o[k] > bh[k])
				return false;
			continue;
		}
		double ta = (bl[k] - o[k]) / d[k], tb = (bh[k] - o[k]) / d[k];
		double sa = -1, sb = 1;
		if (ta > tb) {
			double t = ta;
			ta = tb, tb = t, sa = 1, sb = -1;
		}
		if (ta > lo)
			lo = ta, alo = k, slo = sa;
		if (tb < hi)
			hi = tb, ahi = k, shi = sb;
	}
	if (!(lo <= hi))
		return false;
	double e0[3] = {0, 0, 0}, e1[3] = {0, 0, 0};
	e0[alo] = slo, e1[ahi] = shi;
	*t0 = lo, *t1 = hi;
	*n0 = v3(e0[0], e0[1], e0[2]);
	*n1 = v3(e1[0], e1[1], e1[2]);
	return true;
}

/* The gradient of f at p by central differences of step h. */
static struct vec3 gradient(const struct isosurface *s, struct vec3 p, double h)
{
	struct vec3 ex = v3(h, 0, 0), ey = v3(0, h, 0), ez = v3(0, 0, h);
	return v3(g_at(s, v_add(p, ex)) - g_at(s, v_sub(p, ex)), g_at(s, v_add(p, ey)) - g_at(s, v_sub(p, ey)),
	          g_at(s, v_add(p, ez)) - g_at(s, v_sub(p, ez)));
}

static struct vec3 centre(const struct isosurface *s)
{
	return s->sphere ? s->c : v_scale(v_add(s->lo, s->hi), 0.5);
}

/* Fills the hit at t with normal n (any length; the ray direction reversed
 * when it is degenerate). */
static void fill(const struct isosurface *s, const struct ray *r, double t, struct vec3 n, struct local_hit *lh)
{
	lh->t = t;
	lh->p = ray_at(*r, t);
	double l = v_len(n);
	n = l > 0 && isfinite(l) ? v_scale(n, 1 / l) : v_norm(v_neg(r->d));
	lh->n = n;
	prim_radial_hit(centre(s), lh);
}

static bool iso_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                          struct local_hit *lh)
{
	const struct isosurface *s = ISO(o);
	double ta, tb;
	struct vec3 na, nb;
	if (!container(s, r, &ta, &tb, &na, &nb))
		return false;
	double t0 = fmax(ta, tmin), t1 = fmin(tb, tmax), dl = v_len(r->d);
	if (!(t0 < t1) || !(dl > 0))
		return false;
	bool walls = !(o->flags & OF_OPEN);
	double t = t0, g = g_at(s, ray_at(*r, t));
	if (walls && ta > tmin && g < 0) { /* entering the solid through the container */
		fill(s, r, ta, na, lh);
		return true;
	}
	double lip = s->max_gradient * dl, min_step = s->accuracy / dl;
	for (long k = 0; k < MAX_STEPS && t < t1; k++) {
		double step = fabs(g) / lip;
		double tn = fmin(t + fmax(step, min_step), t1), gn = g_at(s, ray_at(*r, tn));
		if ((g < 0) != (gn < 0)) { /* a root in (t, tn]: bisect */
			double lo = t, hi = tn;
			bool lo_in = g < 0;
			/* to the last double: a spawned ray, 1e-7 off the surface, must
			 * not find this root again (docs/design.md §3) */
			for (int it = 0; it < 200; it++) {
				double mid = 0.5 * (lo + hi);
				if (!(mid > lo && mid < hi)) /* no double between them */
					break;
				if ((g_at(s, ray_at(*r, mid)) < 0) == lo_in)
					lo = mid;
				else
					hi = mid;
			}
			double th = 0.5 * (lo + hi);
			if (!(th > tmin))
				th = hi;
			struct vec3 p = ray_at(*r, th);
			fill(s, r, th, gradient(s, p, fmax(s->accuracy * 0.01, 1e-9 * (1 + v_len(p)))), lh);
			return true;
		}
		t = tn, g = gn;
	}
	if (walls && tb <= tmax && t >= t1 && g < 0) { /* leaving the solid through the container */
		fill(s, r, tb, nb, lh);
		return true;
	}
	return false;
}

static bool iso_inside(const struct object *o, struct vec3 p)
{
	const struct isosurface *s = ISO(o);
	if (s->sphere) {
		struct vec3 f = v_sub(p, s->c);
		if (!(v_dot(f, f) < s->r * s->r))
			return false;
	} else if (!(p.x > s->lo.x && p.x < s->hi.x && p.y > s->lo.y && p.y < s->hi.y && p.z > s->lo.z &&
	             p.z < s->hi.z)) {
		return false;
	}
	return g_at(s, p) < 0;
}

static struct bbox iso_bounds(const struct object *o)
{
	const struct isosurface *s = ISO(o);
	if (s->sphere)
		return (struct bbox){v_sub(s->c, v3(s->r, s->r, s->r)), v_add(s->c, v3(s->r, s->r, s->r))};
	return (struct bbox){s->lo, s->hi};
}

static void iso_dump(const struct object *o, FILE *out)
{
	const struct isosurface *s = ISO(o);
	fputs("function contained_by ", out);
	if (s->sphere)
		fputs("sphere ", out), prim_dump_vec(out, s->c), fprintf(out, " %.6g", s->r);
	else
		fputs("box ", out), prim_dump_vec(out, s->lo), fputc(' ', out), prim_dump_vec(out, s->hi);
	fprintf(out, " threshold %.6g max_gradient %.6g accuracy %.6g%s", s->threshold, s->max_gradient, s->accuracy,
	        o->flags & OF_OPEN ? " open" : "");
}

static bool iso_uv_point(const struct object *o, double u, double v, struct vec3 *p, struct vec3 *dpdu,
                         struct vec3 *dpdv)
{
	return prim_radial_point(o, centre(ISO(o)), iso_intersect, u, v, p, dpdu, dpdv);
}

static struct uv_range iso_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, true, false};
}

/* One 5×5 Gauss–Legendre rule over the cell, not the adaptive cubature of
 * the other implicit surfaces: each point is a march along a ray, and at
 * the container's edges (where the surface folds) the adaptive rule would
 * split the cell thousands of times. Smooth cells are good to about 1e-6. */
static double iso_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	static const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0, 0.5384693101056831,
	                            0.9061798459386640};
	static const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
	                            0.4786286704993665, 0.2369268850561891};
	v0 = fmax(v0, 0), v1 = fmin(v1, 1);
	if (!(u1 > u0) || !(v1 > v0))
		return 0;
	double hu = 0.5 * (u1 - u0), hv = 0.5 * (v1 - v0), sum = 0;
	for (int i = 0; i < 5; i++)
		for (int j = 0; j < 5; j++) {
			struct vec3 du, dv;
			if (shape_uv_point(o, u0 + hu * (1 + x[i]), v0 + hv * (1 + x[j]), NULL, &du, &dv))
				sum += w[i] * w[j] * v_len(v_cross(du, dv));
		}
	return sum * hu * hv;
}

const struct prim_ops shape_isosurface_ops = {
	iso_intersect, iso_inside, iso_bounds, iso_uv_point, iso_uv_range, iso_cell_area, iso_dump, NULL,
};
