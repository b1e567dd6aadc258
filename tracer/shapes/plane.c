/* SPDX-License-Identifier: MIT */
/* plane.c: plane { n, d }, the set n·p = d; inside is n·p < d (POV-Ray).
 *
 * Parametrisation (object frame), unbounded, in object-frame length units:
 * with n̂ = n/|n|, the origin o = (d/|n|)·n̂ and the orthonormal in-plane axes
 * e1, e2 of shape_basis(n̂) (e1 = x made perpendicular to n̂, or z when n̂ is
 * near x; e2 = n̂ × e1):
 *
 *     T(u,v) = o + u·e1 + v·e2,   ∂T/∂u = e1,  ∂T/∂v = e2,
 *     ∂T/∂u × ∂T/∂v = n̂            (‖·‖ = 1, never vanishes)
 *
 * For plane { y, 0 }: e1 = x, e2 = −z, so u = x and v = −z. In the world the
 * partials are scaled by the object's transform; a cell's area is
 * (u1−u0)(v1−v0) times the transform's area factor for the plane. */
#include <math.h>

#include "prim.h"

/* Unit normal, offset along it, and the in-plane axes. */
struct pframe {
	struct vec3 n, e1, e2; /* n̂ and the in-plane axes */
	double d;              /* n̂·p = d on the plane */
};

/* |n|, without the square root for the common unit normal (the same
 * numbers: sqrt(1) is 1). */
static double pl_norm(const struct object *o)
{
	double l2 = v_dot(o->g.plane.n, o->g.plane.n);
	return l2 == 1 ? 1 : sqrt(l2);
}

static bool pl_frame(const struct object *o, struct pframe *f)
{
	double l = pl_norm(o);
	if (!(l > 0))
		return false;
	f->n = l == 1 ? o->g.plane.n : v_scale(o->g.plane.n, 1 / l);
	f->d = l == 1 ? o->g.plane.d : o->g.plane.d / l;
	shape_basis(f->n, &f->e1, &f->e2);
	return true;
}

static bool pl_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	struct pframe f;
	if (!pl_frame(o, &f))
		return false;
	if (p)
		*p = v_madd(v_madd(v_scale(f.n, f.d), f.e1, u), f.e2, v);
	if (dpdu)
		*dpdu = f.e1;
	if (dpdv)
		*dpdv = f.e2;
	return true;
}

static bool pl_root(struct vec3 n, double d, const struct ray *r, double tmin, double tmax, double *t)
{
	return prim_plane_root(n, d, r, tmin, tmax, t);
}

bool pl_hit_t(const struct object *o, const struct ray *r, double tmin, double tmax, double *t)
{
	double l = pl_norm(o); /* as pl_frame, without the in-plane axes */
	if (!(l > 0))
		return false;
	if (l == 1)
		return pl_root(o->g.plane.n, o->g.plane.d, r, tmin, tmax, t);
	return pl_root(v_scale(o->g.plane.n, 1 / l), o->g.plane.d / l, r, tmin, tmax, t);
}

/* One root. */
static bool pl_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	struct pframe f;
	double t;
	if (!pl_frame(o, &f) || !pl_root(f.n, f.d, r, tmin, tmax, &t))
		return false;
	prim_plane_hit(&f.n, &f.e1, &f.e2, f.d, r, t, lh);
	return true;
}

void pl_prep(const struct object *o, struct pl_prep *p)
{
	struct pframe f = {.d = 0};
	p->ok = pl_frame(o, &f);
	p->n = f.n, p->e1 = f.e1, p->e2 = f.e2, p->d = f.d;
	p->nw = v_norm(f.n);
}

bool pl_prep_hit_t(const struct pl_prep *p, const struct ray *r, double tmin, double tmax, double *t)
{
	return p->ok && pl_root(p->n, p->d, r, tmin, tmax, t);
}

static bool pl_inside(const struct object *o, struct vec3 p)
{
	return v_dot(o->g.plane.n, p) < o->g.plane.d;
}

static struct bbox pl_bounds(const struct object *o)
{
	(void)o;
	return prim_infinite_box();
}

static struct uv_range pl_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){-INFINITY, INFINITY, -INFINITY, INFINITY, false, false, false};
}

static double pl_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	return (u1 - u0) * (v1 - v0) * shape_planar_scale(o, o->g.plane.n);
}

static void pl_dump(const struct object *o, FILE *out)
{
	fputs("normal ", out), prim_dump_vec(out, o->g.plane.n), fprintf(out, " distance %.6g", o->g.plane.d);
}

const struct prim_ops shape_plane_ops = {
	pl_intersect, pl_inside, pl_bounds, pl_uv_point, pl_uv_range, pl_cell_area, pl_dump, NULL,
};
