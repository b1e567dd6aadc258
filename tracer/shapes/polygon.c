/* SPDX-License-Identifier: MIT */
/* polygon.c: polygon { n, <p0>, <p1>, … }: flat sub-polygons, each closed by
 * repeating its first point, filled by the even-odd rule (POV-Ray). The
 * evaluator finds the plane (Newell's normal n, origin o, e1 × e2 = n) and
 * stores the points as a 2D outline in (e1, e2) coordinates. Flat: nothing
 * is inside it, unless OF_INVERSE makes everything inside.
 *
 * Parametrisation (object frame), [A0,A1]×[B0,B1] the outline's bounding
 * rectangle:
 *
 *     T(u,v) = o + (A0 + u·ΔA)·e1 + (B0 + v·ΔB)·e2,   (u,v) ∈ [0,1]²
 *     ∂T/∂u = ΔA·e1,  ∂T/∂v = ΔB·e2,  ∂T/∂u × ∂T/∂v = ΔA·ΔB·n
 *
 * Points of the rectangle outside the outline are off the surface; a cell's
 * area counts only the part inside (exact when no edge crosses the cell,
 * sampled on a 16×16 grid when one does). */
#include "outline.h"
#include "prim.h"

#define PF(o) ((o)->g.polygon.f)

static struct vec3 V(const double *a) { return v3(a[0], a[1], a[2]); }

static bool pg_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	const struct flat_outline *f = PF(o);
	double da = f->ol.hi[0] - f->ol.lo[0], db = f->ol.hi[1] - f->ol.lo[1];
	if (p)
		*p = v_madd(v_madd(V(f->o), V(f->e1), f->ol.lo[0] + u * da), V(f->e2), f->ol.lo[1] + v * db);
	if (dpdu)
		*dpdu = v_scale(V(f->e1), da);
	if (dpdv)
		*dpdv = v_scale(V(f->e2), db);
	return true;
}

static bool pg_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	const struct flat_outline *f = PF(o);
	struct vec3 n = V(f->n), org = V(f->o);
	double dn = v_dot(r->d, n);
	if (dn == 0)
		return false;
	double t = v_dot(v_sub(org, r->o), n) / dn;
	if (!(t > tmin && t < tmax))
		return false;
	struct vec3 q = v_sub(v_madd(r->o, r->d, t), org);
	double a = v_dot(q, V(f->e1)), b = v_dot(q, V(f->e2));
	if (!outline_inside(&f->ol, a, b))
		return false;
	double da = f->ol.hi[0] - f->ol.lo[0], db = f->ol.hi[1] - f->ol.lo[1];
	lh->t = t;
	lh->u = (a - f->ol.lo[0]) / da;
	lh->v = (b - f->ol.lo[1]) / db;
	lh->p = v_add(org, q);
	lh->n = n;
	return pg_uv_point(o, lh->u, lh->v, NULL, &lh->dpdu, &lh->dpdv);
}

static bool pg_inside(const struct object *o, struct vec3 p)
{
	(void)o;
	(void)p;
	return false;
}

static struct bbox pg_bounds(const struct object *o)
{
	struct bbox b = bbox_empty();
	struct vec3 p;
	for (int i = 0; i < 4; i++) {
		pg_uv_point(o, i & 1, i >> 1, &p, NULL, NULL);
		b = bbox_add(b, p);
	}
	return b;
}

static struct uv_range pg_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, false, false};
}

static double pg_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	const struct flat_outline *f = PF(o);
	double da = f->ol.hi[0] - f->ol.lo[0], db = f->ol.hi[1] - f->ol.lo[1];
	double a = outline_rect_area(&f->ol, f->ol.lo[0] + u0 * da, f->ol.lo[0] + u1 * da,
	                             f->ol.lo[1] + v0 * db, f->ol.lo[1] + v1 * db);
	return a * shape_planar_scale(o, V(f->n));
}

static void pg_dump(const struct object *o, FILE *out)
{
	const struct flat_outline *f = PF(o);
	fprintf(out, "edges %d normal ", f->ol.n);
	prim_dump_vec(out, V(f->n));
}

const struct prim_ops shape_polygon_ops = {
	pg_intersect, pg_inside, pg_bounds, pg_uv_point, pg_uv_range, pg_cell_area, pg_dump, NULL,
};
