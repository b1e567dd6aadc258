/* SPDX-License-Identifier: MIT */
/* triangle.c: triangle { p0, p1, p2 }. Flat: nothing is inside it (POV-Ray),
 * unless OF_INVERSE makes everything inside.
 *
 * Parametrisation (object frame): barycentric, with e1 = p1 − p0,
 * e2 = p2 − p0:
 *
 *     T(u,v) = p0 + u·e1 + v·e2,   (u,v) ∈ [0,1]², on the surface for u + v ≤ 1
 *     ∂T/∂u = e1,  ∂T/∂v = e2,  ∂T/∂u × ∂T/∂v = e1 × e2   (constant, the normal)
 *
 * The "outward" normal is e1 × e2 (counter-clockwise p0 → p1 → p2). Half of
 * the unit square (u + v > 1) lies off the triangle: T extends the plane
 * there, and a cell's area counts only the part with u, v ≥ 0, u + v ≤ 1
 * (exact, under any affine transform). */
#include <math.h>

#include "prim.h"

#define TP(o, i) ((o)->g.triangle.p[i])

static bool tr_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	struct vec3 e1 = v_sub(TP(o, 1), TP(o, 0)), e2 = v_sub(TP(o, 2), TP(o, 0));
	if (p)
		*p = v_madd(v_madd(TP(o, 0), e1, u), e2, v);
	if (dpdu)
		*dpdu = e1;
	if (dpdv)
		*dpdv = e2;
	return true;
}

/* Möller–Trumbore in double precision; edges are inclusive. */
static bool tr_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	struct vec3 e1 = v_sub(TP(o, 1), TP(o, 0)), e2 = v_sub(TP(o, 2), TP(o, 0));
	double t, u, v;
	if (!prim_tri_hit(TP(o, 0), e1, e2, r, &t, &u, &v) || !(t > tmin && t < tmax))
		return false;
	lh->t = t;
	lh->u = u;
	lh->v = v;
	lh->p = v_madd(v_madd(TP(o, 0), e1, u), e2, v);
	lh->n = v_cross(e1, e2);
	lh->dpdu = e1;
	lh->dpdv = e2;
	return true;
}

static bool tr_inside(const struct object *o, struct vec3 p)
{
	(void)o;
	(void)p;
	return false;
}

static struct bbox tr_bounds(const struct object *o)
{
	struct bbox b = bbox_empty();
	for (int i = 0; i < 3; i++)
		b = bbox_add(b, TP(o, i));
	return b;
}

static struct uv_range tr_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, false, false};
}

static double tr_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	u0 = fmax(u0, 0);
	v0 = fmax(v0, 0);
	u1 = fmin(u1, 1);
	v1 = fmin(v1, 1);
	if (!(u1 > u0) || !(v1 > v0))
		return 0;
	struct vec3 e1 = v_sub(TP(o, 1), TP(o, 0)), e2 = v_sub(TP(o, 2), TP(o, 0));
	double jac = v_len(v_cross(xf_vector(obj_xf(o), e1), xf_vector(obj_xf(o), e2)));
	return prim_tri_clipped_area(u0, u1, v0, v1) * jac;
}

static void tr_dump(const struct object *o, FILE *out)
{
	for (int i = 0; i < 3; i++)
		fputs(i ? " " : "", out), prim_dump_vec(out, o->g.triangle.p[i]);
}

const struct prim_ops shape_triangle_ops = {
	tr_intersect, tr_inside, tr_bounds, tr_uv_point, tr_uv_range, tr_cell_area, tr_dump, NULL,
};
