/* SPDX-License-Identifier: MIT */
/* box.c: box { lo, hi } (corners in any order).
 *
 * Parametrisation (object frame): the six faces are packed into the unit
 * square as a 3×2 atlas. Face (k, side) — k the axis of its normal (0 x, 1 y,
 * 2 z), side 0 the face at lo[k] (normal −e_k), side 1 the one at hi[k] —
 * owns the block u ∈ [k/3, (k+1)/3], v ∈ [side/2, (side+1)/2]. Within it,
 * with a = (k+1) mod 3, b = (k+2) mod 3, E = hi − lo and local coordinates
 * s = 3u − k, w = 2v − side in [0,1]:
 *
 *     side 1:  T = (hi[k] on axis k, lo[a] + s·E[a] on a, lo[b] + w·E[b] on b)
 *     side 0:  T = (lo[k] on axis k, hi[a] − s·E[a] on a, lo[b] + w·E[b] on b)
 *
 *     ∂T/∂u = ±3E[a]·e_a (− on side 0),  ∂T/∂v = 2E[b]·e_b,
 *     ∂T/∂u × ∂T/∂v = 6E[a]E[b]·(outward normal)   (constant per face)
 *
 * Layout of the atlas (u →, v ↑):
 *     v∈[½,1]:  +x  +y  +z
 *     v∈[0,½]:  −x  −y  −z
 * Map resolutions that are multiples of 6 keep map cells inside one face.
 * Cell areas are exact under any affine transform (each face is planar). */
#include <math.h>

#include "prim.h"

/* Normalised corners (lo ≤ hi on every axis). */
static void bx_corners(const struct object *o, struct vec3 *lo, struct vec3 *hi)
{
	struct vec3 a = o->g.box.lo, b = o->g.box.hi;
	*lo = v3(d_min(a.x, b.x), d_min(a.y, b.y), d_min(a.z, b.z));
	*hi = v3(d_max(a.x, b.x), d_max(a.y, b.y), d_max(a.z, b.z));
}

static double *comp(struct vec3 *v, int i) { return i == 0 ? &v->x : i == 1 ? &v->y : &v->z; }

static struct vec3 axis(int i, double s)
{
	struct vec3 e = v3(0, 0, 0);
	*comp(&e, i) = s;
	return e;
}

/* T(u,v) for face (k, side) at local coordinates s, w. */
static void bx_face_point(const struct object *o, int k, int side, double s, double w,
                          struct vec3 *p, struct vec3 *dpdu, struct vec3 *dpdv)
{
	struct vec3 lo, hi, q = v3(0, 0, 0);
	bx_corners(o, &lo, &hi);
	struct vec3 e = v_sub(hi, lo);
	int a = (k + 1) % 3, b = (k + 2) % 3;
	double ea = v_comp(e, a), eb = v_comp(e, b);
	*comp(&q, k) = side ? v_comp(hi, k) : v_comp(lo, k);
	*comp(&q, a) = side ? v_comp(lo, a) + s * ea : v_comp(hi, a) - s * ea;
	*comp(&q, b) = v_comp(lo, b) + w * eb;
	if (p)
		*p = q;
	if (dpdu)
		*dpdu = axis(a, side ? 3 * ea : -3 * ea);
	if (dpdv)
		*dpdv = axis(b, 2 * eb);
}

static bool bx_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	int k = (int)fmin(fmax(floor(3 * u), 0), 2);
	int side = (int)fmin(fmax(floor(2 * v), 0), 1);
	bx_face_point(o, k, side, 3 * u - k, 2 * v - side, p, dpdu, dpdv);
	return true;
}

/* The box as arrays per axis, corners normalised (lo <= hi): what the
 * slab test and the fill index by axis, without a switch per access. */
struct bx_arr {
	double lo[3], hi[3];
};

static inline struct bx_arr bx_arrays(const struct object *o)
{
	struct vec3 lo, hi;
	bx_corners(o, &lo, &hi);
	return (struct bx_arr){{lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z}};
}

/* Slab test on one axis: narrows [*t0,*t1] and records which axis set each
 * end. Returns false when the ray misses the slab. */
static inline bool slab(double o, double d, double lo, double hi, int k, double *t0, double *t1,
                        int *k0, int *k1)
{
	if (d == 0)
		return o >= lo && o <= hi;
	double a = (lo - o) / d, b = (hi - o) / d;
	if (a > b) {
		double t = a;
		a = b;
		b = t;
	}
	if (a > *t0)
		*t0 = a, *k0 = k;
	if (b < *t1)
		*t1 = b, *k1 = k;
	return *t0 <= *t1;
}

/* Fills the local hit on face (k, side) at parameter t: as bx_face_point at
 * (s, w), with the same operations on the same numbers, done by axis. */
static void bx_fill(const struct bx_arr *B, const struct ray *r, double t, int k, int side,
                    struct local_hit *lh)
{
	struct vec3 pv = ray_at(*r, t);
	double p[3] = {pv.x, pv.y, pv.z}, e[3] = {B->hi[0] - B->lo[0], B->hi[1] - B->lo[1], B->hi[2] - B->lo[2]};
	int a = k == 2 ? 0 : k + 1, b = k == 0 ? 2 : k - 1; /* (k + 1) % 3, (k + 2) % 3 */
	double s = (p[a] - B->lo[a]) / e[a];
	double w = (p[b] - B->lo[b]) / e[b];
	s = d_min(d_max(s, 0), 1);
	w = d_min(d_max(w, 0), 1);
	if (!side)
		s = 1 - s;
	lh->t = t;
	lh->u = (k + s) / 3;
	lh->v = (side + w) / 2;
	double q[3], du[3] = {0, 0, 0}, dv[3] = {0, 0, 0}, n[3] = {0, 0, 0};
	q[k] = side ? B->hi[k] : B->lo[k];
	q[a] = side ? B->lo[a] + s * e[a] : B->hi[a] - s * e[a];
	q[b] = B->lo[b] + w * e[b];
	du[a] = side ? 3 * e[a] : -3 * e[a];
	dv[b] = 2 * e[b];
	n[k] = side ? 1 : -1;
	lh->p = v3(q[0], q[1], q[2]);
	lh->dpdu = v3(du[0], du[1], du[2]);
	lh->dpdv = v3(dv[0], dv[1], dv[2]);
	lh->n = v3(n[0], n[1], n[2]);
}

/* Slabs: the ray's entry (t0, through face axis k0) and exit (t1, k1), or
 * false when it misses the box. */
static inline bool bx_span(const struct bx_arr *B, const struct ray *r, double *t0, double *t1, int *k0,
                           int *k1)
{
	if (!(B->hi[0] > B->lo[0] && B->hi[1] > B->lo[1] && B->hi[2] > B->lo[2]))
		return false;
	*t0 = -INFINITY, *t1 = INFINITY;
	*k0 = -1, *k1 = -1;
	return slab(r->o.x, r->d.x, B->lo[0], B->hi[0], 0, t0, t1, k0, k1) &&
	       slab(r->o.y, r->d.y, B->lo[1], B->hi[1], 1, t0, t1, k0, k1) &&
	       slab(r->o.z, r->d.z, B->lo[2], B->hi[2], 2, t0, t1, k0, k1);
}

/* The entry face when the entry is in range, else the exit face. */
static bool bx_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	struct bx_arr B = bx_arrays(o);
	double t0, t1;
	int k0, k1;
	if (!bx_span(&B, r, &t0, &t1, &k0, &k1))
		return false;
	/* entering through the face looking at the ray, leaving through the other */
	if (t0 > tmin && t0 < tmax && k0 >= 0)
		bx_fill(&B, r, t0, k0, v_comp(r->d, k0) < 0, lh);
	else if (t1 > tmin && t1 < tmax && k1 >= 0)
		bx_fill(&B, r, t1, k1, v_comp(r->d, k1) > 0, lh);
	else
		return false;
	return true;
}

static bool bx_occluded(const struct object *o, const struct ray *r, double tmin, double tmax)
{
	struct bx_arr B = bx_arrays(o);
	double t0, t1;
	int k0, k1;
	return bx_span(&B, r, &t0, &t1, &k0, &k1) &&
	       ((t0 > tmin && t0 < tmax && k0 >= 0) || (t1 > tmin && t1 < tmax && k1 >= 0));
}

static bool bx_inside(const struct object *o, struct vec3 p)
{
	struct vec3 lo, hi;
	bx_corners(o, &lo, &hi);
	return p.x > lo.x && p.x < hi.x && p.y > lo.y && p.y < hi.y && p.z > lo.z && p.z < hi.z;
}

static struct bbox bx_bounds(const struct object *o)
{
	struct bbox b;
	bx_corners(o, &b.lo, &b.hi);
	return b;
}

static struct uv_range bx_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, false, false};
}

/* Sum over the faces of (overlap of the cell with the face's block) × the
 * face's world area per unit (u,v) area. */
static double bx_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	struct vec3 lo, hi;
	bx_corners(o, &lo, &hi);
	struct vec3 e = v_sub(hi, lo);
	double sum = 0;
	for (int k = 0; k < 3; k++) {
		double du = prim_overlap(u0, u1, k / 3.0, (k + 1) / 3.0);
		if (du == 0)
			continue;
		double dens = 6 * v_comp(e, (k + 1) % 3) * v_comp(e, (k + 2) % 3) *
		              shape_planar_scale(o, axis(k, 1));
		for (int side = 0; side < 2; side++)
			sum += du * prim_overlap(v0, v1, side / 2.0, (side + 1) / 2.0) * dens;
	}
	return sum;
}

static void bx_dump(const struct object *o, FILE *out)
{
	fputs("corner1 ", out), prim_dump_vec(out, o->g.box.lo), fputs(" corner2 ", out), prim_dump_vec(out, o->g.box.hi);
}

const struct prim_ops shape_box_ops = {
	bx_intersect, bx_inside, bx_bounds, bx_uv_point, bx_uv_range, bx_cell_area, bx_dump, bx_occluded,
};
