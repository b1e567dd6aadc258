/* SPDX-License-Identifier: MIT */
/* cylinder.c: cylinder { a, b, r [open] }.
 *
 * Parametrisation (object frame): the axis frame is w = (b − a)/h, h = |b − a|,
 * e1, e2 = shape_basis(w). u goes around the axis, φ = 2πu; v runs along
 * the meridian by arc length, from the centre of the cap at a, out along the
 * cap, up the side, and in along the cap at b to its centre, so the capped
 * cylinder is covered like a sphere with "poles" at the cap centres:
 *
 *     L = r + h + r (capped) or h (open);  s = v·L  (s = v·h when open)
 *     cap a   (s ≤ r):       T = a + s·R(φ)
 *     side    (r ≤ s ≤ r+h): T = a + r·R(φ) + (s − r)·w
 *     cap b   (s ≥ r+h):     T = b + (L − s)·R(φ)
 *     with R(φ) = cosφ·e1 + sinφ·e2
 *
 *     ∂T/∂u = 2πρ·(−sinφ·e1 + cosφ·e2), ρ the distance from the axis;
 *     ∂T/∂v = L·R(φ) on cap a, L·w on the side, −L·R(φ) on cap b;
 *     ‖∂T/∂u × ∂T/∂v‖ = 2πρL, pointing outward; it vanishes at the cap
 *     centres (v = 0 and v = 1), never on the side.
 *
 * u wraps (seam along e1). Cell areas split at the cap/side seams: caps are
 * exact under any affine transform, the side is exact under similarities
 * and integrated numerically otherwise. */
#include <math.h>

#include "prim.h"

/* The cylinder's frame and meridian layout. */
struct cframe {
	struct vec3 a, w, e1, e2; /* base point, unit axis, radial axes */
	double h, r;              /* height and radius */
	double s1, s2, len;       /* meridian arc length at the seams, and in all */
};

static bool cy_frame(const struct object *o, struct cframe *f)
{
	struct vec3 ab = v_sub(o->g.cylinder.b, o->g.cylinder.a);
	f->h = v_len(ab);
	f->r = o->g.cylinder.r;
	if (!(f->h > 0) || !(f->r > 0))
		return false;
	f->a = o->g.cylinder.a;
	f->w = v_scale(ab, 1 / f->h);
	shape_basis(f->w, &f->e1, &f->e2);
	bool caps = !(o->flags & OF_OPEN);
	f->s1 = caps ? f->r : 0;
	f->s2 = f->s1 + f->h;
	f->len = f->s2 + (caps ? f->r : 0);
	return true;
}

/* T and its partials at angle φ and meridian arc length s. */
static void cy_eval(const struct cframe *f, double phi, double s, struct vec3 *p,
                    struct vec3 *dpdu, struct vec3 *dpdv)
{
	struct vec3 rad = v_add(v_scale(f->e1, cos(phi)), v_scale(f->e2, sin(phi)));
	struct vec3 tan = v_add(v_scale(f->e1, -sin(phi)), v_scale(f->e2, cos(phi)));
	double rho, z;
	struct vec3 dv;
	if (s < f->s1) {
		rho = s, z = 0, dv = rad;
	} else if (s <= f->s2) {
		rho = f->r, z = s - f->s1, dv = f->w;
	} else {
		rho = f->len - s, z = f->h, dv = v_neg(rad);
	}
	if (p)
		*p = v_madd(v_madd(f->a, rad, rho), f->w, z);
	if (dpdu)
		*dpdu = v_scale(tan, 2 * M_PI * rho);
	if (dpdv)
		*dpdv = v_scale(dv, f->len);
}

static bool cy_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	struct cframe f;
	if (!cy_frame(o, &f))
		return false;
	cy_eval(&f, 2 * M_PI * u, v * f.len, p, dpdu, dpdv);
	return true;
}

/* Candidate roots (in t) of the side: the quadratic in the plane across the
 * axis, with the accurate discriminant 4a·(r² − |f⊥ − ...|²). */
static int cy_side_roots(const struct cframe *f, const struct ray *r, double t[2])
{
	struct vec3 q = v_sub(r->o, f->a);
	struct vec3 qp = v_madd(q, f->w, -v_dot(q, f->w)), dp = v_madd(r->d, f->w, -v_dot(r->d, f->w));
	double a = v_dot(dp, dp), b = 2 * v_dot(qp, dp), c = v_dot(qp, qp) - f->r * f->r;
	if (!(a > 0))
		return 0;
	double lp = v_len(v_madd(qp, dp, -v_dot(qp, dp) / a));
	double disc = 4 * a * (f->r + lp) * (f->r - lp);
	return prim_quadratic(a, b, c, disc, &t[0], &t[1]) ? 2 : 0;
}

/* Collects every hit of the surface (side within its height, caps within
 * the radius) into c[], up to 4. */
static int cy_candidates(const struct object *o, const struct cframe *f, const struct ray *r,
                         struct cand c[4])
{
	int n = 0;
	double t[2];
	struct vec3 q = v_sub(r->o, f->a);
	double oz = v_dot(q, f->w), dz = v_dot(r->d, f->w);
	if (cy_side_roots(f, r, t) == 2)
		for (int i = 0; i < 2; i++) {
			double z = oz + t[i] * dz;
			if (z >= 0 && z <= f->h)
				c[n++] = (struct cand){t[i], 0};
		}
	if ((o->flags & OF_OPEN) || dz == 0)
		return n;
	for (int k = 0; k < 2; k++) {
		double tc = ((k ? f->h : 0) - oz) / dz;
		struct vec3 pr = v_madd(v_madd(q, r->d, tc), f->w, -(k ? f->h : 0));
		if (v_dot(pr, pr) <= f->r * f->r)
			c[n++] = (struct cand){tc, 1 + k};
	}
	return n;
}

/* Fills the hit for part `part` at parameter t. */
static void cy_fill(const struct cframe *f, const struct ray *r, double t, int part,
                    struct local_hit *lh)
{
	struct vec3 q = v_sub(ray_at(*r, t), f->a);
	double x = v_dot(q, f->e1), y = v_dot(q, f->e2), z = v_dot(q, f->w);
	double phi = atan2(y, x), rho = sqrt(x * x + y * y), s;
	if (part == 0)
		s = f->s1 + fmin(fmax(z, 0), f->h);
	else if (part == 1)
		s = fmin(rho, f->r);
	else
		s = f->len - fmin(rho, f->r);
	lh->t = t;
	lh->u = prim_turns(y, x);
	lh->v = s / f->len;
	cy_eval(f, phi, s, &lh->p, &lh->dpdu, &lh->dpdv);
	if (part == 0)
		lh->n = v_add(v_scale(f->e1, cos(phi)), v_scale(f->e2, sin(phi)));
	else
		lh->n = part == 1 ? v_neg(f->w) : f->w;
}

/* The nearest candidate in range. */
static bool cy_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	struct cframe f;
	struct cand c[4];
	if (!cy_frame(o, &f))
		return false;
	int best = prim_cand_nearest(c, cy_candidates(o, &f, r, c), tmin, tmax);
	if (best < 0)
		return false;
	cy_fill(&f, r, c[best].t, c[best].part, lh);
	return true;
}

/* cy_intersect's answer without the hit: a candidate in range. */
static bool cy_occluded(const struct object *o, const struct ray *r, double tmin, double tmax)
{
	struct cframe f;
	struct cand c[4];
	if (!cy_frame(o, &f))
		return false;
	return prim_cand_any(c, cy_candidates(o, &f, r, c), tmin, tmax);
}

static bool cy_inside(const struct object *o, struct vec3 p)
{
	struct cframe f;
	if (!cy_frame(o, &f))
		return false;
	struct vec3 q = v_sub(p, f.a);
	double z = v_dot(q, f.w);
	struct vec3 qp = v_madd(q, f.w, -z);
	return z > 0 && z < f.h && v_dot(qp, qp) < f.r * f.r;
}

/* Bounds of the two rim circles (see disc.c). */
static struct bbox cy_bounds(const struct object *o)
{
	struct vec3 a = o->g.cylinder.a, b = o->g.cylinder.b, w = v_norm(v_sub(b, a));
	double r = fabs(o->g.cylinder.r);
	struct vec3 e = v3(r * sqrt(fmax(0, 1 - w.x * w.x)), r * sqrt(fmax(0, 1 - w.y * w.y)),
	                   r * sqrt(fmax(0, 1 - w.z * w.z)));
	return (struct bbox){v_sub(v_min(a, b), e), v_add(v_max(a, b), e)};
}

static struct uv_range cy_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, true, false};
}

/* Area of the annular sector between radii ρ0 < ρ1 (object frame). */
static double sector(double du, double rho0, double rho1)
{
	return M_PI * du * (rho1 - rho0) * (rho1 + rho0);
}

/* Split at the seams: caps exact, side closed form or numeric. */
static double cy_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	struct cframe f;
	double s2;
	if (!cy_frame(o, &f))
		return 0;
	double s0 = fmax(v0, 0) * f.len, s1 = fmin(v1, 1) * f.len, sum = 0, du = u1 - u0;
	if (!(s1 > s0))
		return 0;
	double cap = shape_planar_scale(o, f.w);
	if (s0 < f.s1) /* cap a */
		sum += sector(du, s0, fmin(s1, f.s1)) * cap;
	if (s1 > f.s2) /* cap b */
		sum += sector(du, f.len - s1, f.len - fmax(s0, f.s2)) * cap;
	double z0 = fmax(s0, f.s1), z1 = fmin(s1, f.s2);
	if (z1 > z0) { /* side */
		if (shape_similarity(o, &s2))
			sum += s2 * 2 * M_PI * f.r * du * (z1 - z0);
		else
			sum += shape_integrate_area(o, u0, u1, z0 / f.len, z1 / f.len);
	}
	return sum;
}

static void cy_dump(const struct object *o, FILE *out)
{
	fputs("base ", out), prim_dump_vec(out, o->g.cylinder.a), fputs(" cap ", out), prim_dump_vec(out, o->g.cylinder.b);
	fprintf(out, " radius %.6g", o->g.cylinder.r);
}

const struct prim_ops shape_cylinder_ops = {
	cy_intersect, cy_inside, cy_bounds, cy_uv_point, cy_uv_range, cy_cell_area, cy_dump, cy_occluded,
};
