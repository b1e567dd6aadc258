/* SPDX-License-Identifier: MIT */
/* superellipsoid.c: superellipsoid { <e, n> }, POV-Ray's
 *
 *     F(x,y,z) = (|x|^(2/e) + |y|^(2/e))^(e/n) + |z|^(2/n) − 1 = 0
 *
 * inside the box [−1,1]³, inside where F < 0. e = n = 1 is the unit sphere;
 * small exponents approach the cube, 2 the octahedron.
 *
 * Intersection: the ray is clipped to the box and cut where it crosses the
 * planes x = 0, y = 0, z = 0 (where F is not smooth); each piece is sampled
 * at 48 points, and the first sign change of F is refined by Illinois
 * regula falsi to 1e-13 of the box. A ray that only grazes the surface
 * between two samples (closer than 1/48 of the piece) can miss it.
 *
 * Parametrisation: the radial one of implicit surfaces about the origin
 * (prim.h; docs/parametrisations.md). The solid is star-shaped about its
 * centre, so every surface point has its own (u,v) and round trips hold. */
#include <math.h>

#include "prim.h"

#define SE_E(o) ((o)->g.superellipsoid.e)
#define SE_N(o) ((o)->g.superellipsoid.n)

static double se_f(double e, double n, struct vec3 p)
{
	double a = pow(fabs(p.x), 2 / e) + pow(fabs(p.y), 2 / e);
	return pow(a, e / n) + pow(fabs(p.z), 2 / n) - 1;
}

static struct vec3 se_grad(double e, double n, struct vec3 p)
{
	double ax = fabs(p.x), ay = fabs(p.y), az = fabs(p.z);
	double a = pow(ax, 2 / e) + pow(ay, 2 / e);
	double k = a > 0 ? (2 / n) * pow(a, e / n - 1) : 0;
	double gx = ax > 0 ? k * pow(ax, 2 / e - 1) : 0, gy = ay > 0 ? k * pow(ay, 2 / e - 1) : 0;
	double gz = az > 0 ? (2 / n) * pow(az, 2 / n - 1) : 0;
	return v3(copysign(gx, p.x), copysign(gy, p.y), copysign(gz, p.z));
}

/* The root of F along the ray in [a,b], F(a) = fa and F(b) = fb of
 * opposite signs (Illinois variant of regula falsi). */
static double se_refine(double e, double n, const struct ray *r, double a, double b, double fa,
                        double fb, double tol)
{
	int side = 0;
	for (int it = 0; it < 100 && b - a > tol; it++) {
		double m = (a * fb - b * fa) / (fb - fa);
		if (!(m > a && m < b))
			m = 0.5 * (a + b);
		double fm = se_f(e, n, v_madd(r->o, r->d, m));
		if (fm == 0)
			return m;
		if ((fm < 0) == (fb < 0)) {
			b = m, fb = fm;
			if (side == -1)
				fa *= 0.5;
			side = -1;
		} else {
			a = m, fa = fm;
			if (side == 1)
				fb *= 0.5;
			side = 1;
		}
	}
	return (a * fb - b * fa) / (fb - fa);
}

static bool se_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	double e = SE_E(o), n = SE_N(o), t0 = tmin, t1 = tmax;
	/* clip to the box [−1,1]³ (padded a little) */
	for (int k = 0; k < 3; k++) {
		double ok = v_comp(r->o, k), dk = v_comp(r->d, k);
		if (dk == 0) {
			if (fabs(ok) > 1 + 1e-9)
				return false;
			continue;
		}
		double a = (-1 - 1e-9 - ok) / dk, b = (1 + 1e-9 - ok) / dk;
		t0 = fmax(t0, fmin(a, b));
		t1 = fmin(t1, fmax(a, b));
	}
	if (!(t1 > t0))
		return false;
	/* cut where a coordinate changes sign */
	double cut[5] = {t0};
	int nc = 1;
	for (int k = 0; k < 3; k++) {
		double dk = v_comp(r->d, k);
		if (dk != 0) {
			double t = -v_comp(r->o, k) / dk;
			if (t > t0 && t < t1)
				cut[nc++] = t;
		}
	}
	cut[nc++] = t1;
	for (int i = 1; i < nc; i++) /* insertion sort of the few cuts */
		for (int j = i; j > 0 && cut[j] < cut[j - 1]; j--) {
			double tmp = cut[j];
			cut[j] = cut[j - 1];
			cut[j - 1] = tmp;
		}
	double tol = 1e-13 * fmax(fabs(t0), fabs(t1)) + 1e-300;
	double pa = cut[0], fpa = se_f(e, n, v_madd(r->o, r->d, pa));
	for (int i = 0; i + 1 < nc; i++) {
		double a = cut[i], b = cut[i + 1];
		for (int s = 1; s <= 48; s++) {
			double tb = a + (b - a) * s / 48, fb = se_f(e, n, v_madd(r->o, r->d, tb));
			if ((fpa < 0) != (fb < 0)) {
				double t = fb == 0 ? tb : se_refine(e, n, r, pa, tb, fpa, fb, tol);
				if (t >= tmax)
					return false;
				if (t > tmin) {
					lh->t = t;
					lh->p = v_madd(r->o, r->d, t);
					lh->n = se_grad(e, n, lh->p);
					if (!(v_dot(lh->n, lh->n) > 0))
						lh->n = lh->p;
					prim_radial_hit(v3(0, 0, 0), lh);
					return true;
				}
			}
			pa = tb, fpa = fb;
		}
	}
	return false;
}

static bool se_inside(const struct object *o, struct vec3 p)
{
	return fabs(p.x) <= 1 && fabs(p.y) <= 1 && fabs(p.z) <= 1 && se_f(SE_E(o), SE_N(o), p) < 0;
}

static struct bbox se_bounds(const struct object *o)
{
	(void)o;
	return (struct bbox){v3(-1, -1, -1), v3(1, 1, 1)};
}

static bool se_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	return prim_radial_point(o, v3(0, 0, 0), se_intersect, u, v, p, dpdu, dpdv);
}

static struct uv_range se_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, true, false};
}

static double se_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	return shape_integrate_area(o, u0, u1, fmax(v0, 0), fmin(v1, 1));
}

static void se_dump(const struct object *o, FILE *out)
{
	fprintf(out, "e %.6g n %.6g", SE_E(o), SE_N(o));
}

const struct prim_ops shape_superellipsoid_ops = {
	se_intersect, se_inside, se_bounds, se_uv_point, se_uv_range, se_cell_area, se_dump, NULL,
};
