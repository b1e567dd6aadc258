/* SPDX-License-Identifier: MIT */
/* disc.c: disc { c, n, r [, hole] }: the annulus hole ≤ |p − c| ≤ r in the
 * plane through c with normal n. Like POV-Ray, its inside is the half-space
 * behind the normal, (p − c)·n < 0.
 *
 * Parametrisation (object frame), φ = 2πu, ρ = hole + v·(r − hole),
 * (u,v) ∈ [0,1]², with n̂ = n/|n| and e1, e2 = shape_basis(n̂):
 *
 *     T(u,v) = c + ρ·(cosφ·e1 − sinφ·e2)
 *     ∂T/∂u = 2πρ·(−sinφ·e1 − cosφ·e2),   ∂T/∂v = (r − hole)·(cosφ·e1 − sinφ·e2)
 *     ∂T/∂u × ∂T/∂v = 2πρ(r − hole)·n̂
 *
 * u wraps (seam along e1); v = 0 is the hole's rim (the centre when there is
 * no hole: the Jacobian vanishes there), v = 1 the outer rim. Cell area:
 * π(u1−u0)(ρ1² − ρ0²), exact under any affine transform (the disc is planar). */
#include <math.h>

#include "prim.h"

/* The disc's frame: unit normal, in-plane axes, radii. */
struct dframe {
	struct vec3 n, e1, e2; /* n̂ and the in-plane axes */
	double r0, r1;         /* hole radius and outer radius */
};

static bool dc_frame(const struct object *o, struct dframe *f)
{
	double l = v_len(o->g.disc.n);
	f->r0 = fmax(o->g.disc.hole, 0);
	f->r1 = o->g.disc.r;
	if (!(l > 0) || !(f->r1 > f->r0))
		return false;
	f->n = v_scale(o->g.disc.n, 1 / l);
	shape_basis(f->n, &f->e1, &f->e2);
	return true;
}

/* T and its partials at angle φ and radius ρ. */
static void dc_eval(const struct object *o, const struct dframe *f, double phi, double rho,
                    struct vec3 *p, struct vec3 *dpdu, struct vec3 *dpdv)
{
	double c = cos(phi), s = sin(phi);
	struct vec3 radial = v_madd(v_scale(f->e1, c), f->e2, -s);
	if (p)
		*p = v_madd(o->g.disc.c, radial, rho);
	if (dpdu)
		*dpdu = v_scale(v_madd(v_scale(f->e1, -s), f->e2, -c), 2 * M_PI * rho);
	if (dpdv)
		*dpdv = v_scale(radial, f->r1 - f->r0);
}

static bool dc_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	struct dframe f;
	if (!dc_frame(o, &f))
		return false;
	dc_eval(o, &f, 2 * M_PI * u, f.r0 + v * (f.r1 - f.r0), p, dpdu, dpdv);
	return true;
}

/* The plane's root, kept when its radius lies in [hole, r]. */
static bool dc_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	struct dframe f;
	if (!dc_frame(o, &f))
		return false;
	double den = v_dot(f.n, r->d);
	if (den == 0)
		return false;
	double t = v_dot(f.n, v_sub(o->g.disc.c, r->o)) / den;
	if (!(t > tmin && t < tmax))
		return false;
	struct vec3 q = v_sub(ray_at(*r, t), o->g.disc.c);
	double x = v_dot(q, f.e1), y = -v_dot(q, f.e2), rho = sqrt(x * x + y * y);
	if (rho > f.r1 || rho < f.r0)
		return false;
	lh->t = t;
	lh->u = prim_turns(y, x);
	lh->v = (rho - f.r0) / (f.r1 - f.r0);
	lh->n = f.n;
	dc_eval(o, &f, 2 * M_PI * lh->u, rho, NULL, &lh->dpdu, &lh->dpdv);
	/* the point itself, snapped into the disc's plane */
	lh->p = v_add(o->g.disc.c, v_madd(v_scale(f.e1, x), f.e2, -y));
	return true;
}

static bool dc_inside(const struct object *o, struct vec3 p)
{
	return v_dot(v_sub(p, o->g.disc.c), o->g.disc.n) < 0;
}

/* Bounds of the rim circle: along each axis i, the circle spans
 * r·sqrt(1 − n̂_i²) either side of c. */
static struct bbox dc_bounds(const struct object *o)
{
	struct vec3 n = v_norm(o->g.disc.n), c = o->g.disc.c;
	double r = fabs(o->g.disc.r);
	struct vec3 e = v3(r * sqrt(fmax(0, 1 - n.x * n.x)), r * sqrt(fmax(0, 1 - n.y * n.y)),
	                   r * sqrt(fmax(0, 1 - n.z * n.z)));
	return (struct bbox){v_sub(c, e), v_add(c, e)};
}

static struct uv_range dc_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, true, false};
}

/* An annular sector, scaled by the transform's area factor for the plane. */
static double dc_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	struct dframe f;
	if (!dc_frame(o, &f))
		return 0;
	v0 = fmax(v0, 0);
	v1 = fmin(v1, 1);
	if (!(v1 > v0))
		return 0;
	double w = f.r1 - f.r0, rho0 = f.r0 + v0 * w, rho1 = f.r0 + v1 * w;
	double local = M_PI * (u1 - u0) * (rho1 - rho0) * (rho1 + rho0);
	return local * shape_planar_scale(o, f.n);
}

static void dc_dump(const struct object *o, FILE *out)
{
	fputs("center ", out), prim_dump_vec(out, o->g.disc.c), fputs(" normal ", out), prim_dump_vec(out, o->g.disc.n);
	fprintf(out, " radius %.6g hole %.6g", o->g.disc.r, o->g.disc.hole);
}

const struct prim_ops shape_disc_ops = {
	dc_intersect, dc_inside, dc_bounds, dc_uv_point, dc_uv_range, dc_cell_area, dc_dump, NULL,
};
