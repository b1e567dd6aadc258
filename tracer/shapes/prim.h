/* SPDX-License-Identifier: MIT */
/* prim.h: what each primitive file under tracer/shapes/ supplies to shape.c.
 *
 * A primitive works in its own frame: shape.c turns the world ray into that
 * frame (t is unchanged, the direction is not normalised), calls the table
 * below, and turns the local hit back into a world hit. Only cell_area sees
 * the transform, because area does not transform by a single factor. */
#ifndef ARVO_PRIM_H
#define ARVO_PRIM_H

#include <math.h>
#include <stdbool.h>
#include <stdio.h>

#include "../shape.h"

/* A hit in the primitive's own frame. */
struct local_hit {
	double t;               /* ray parameter (same as in the world) */
	struct vec3 p;          /* point on the surface */
	struct vec3 n;          /* outward normal, any non-zero length */
	double u, v;            /* surface parameters */
	struct vec3 dpdu, dpdv; /* partials of T(u,v) in the object frame */
};

/* The operations of one primitive kind, all in the object frame. */
struct prim_ops {
	/* Nearest hit with tmin < t < tmax. */
	bool (*intersect)(const struct object *o, const struct ray *r, double tmin, double tmax,
	                  struct local_hit *lh);
	/* Strictly inside the solid (no OF_INVERSE handling). */
	bool (*inside)(const struct object *o, struct vec3 p);
	/* Object-frame bounds; ±INFINITY when unbounded. */
	struct bbox (*bounds)(const struct object *o);
	/* T(u,v) and its partials (any of the outputs may be NULL). NULL, with
	 * uv_range and cell_area, for a surface without a parametrisation
	 * (the isosurface): it gets no illumination map. */
	bool (*uv_point)(const struct object *o, double u, double v, struct vec3 *p,
	                 struct vec3 *dpdu, struct vec3 *dpdv);
	/* The (u,v) domain. */
	struct uv_range (*uv_range)(const struct object *o);
	/* World area over the cell (see shape_cell_area). */
	double (*cell_area)(const struct object *o, double u0, double u1, double v0, double v1);
	/* The geometry on one line of --dump-scene, without the newline. */
	void (*dump)(const struct object *o, FILE *out);
	/* Whether intersect finds a hit, without filling it in (shadow rays);
	 * NULL: intersect is asked. */
	bool (*occluded)(const struct object *o, const struct ray *r, double tmin, double tmax);
};

#define PRIM(n, w) extern const struct prim_ops shape_##w##_ops;
#include "../objects.def"


/* The sphere's nearest root in (tmin, tmax), in its own frame: the t its
 * intersect finds, without the point, normal and (u,v) (shape_hit_t). */
bool sph_hit_t(const struct object *o, const struct ray *r, double tmin, double tmax, double *t);
/* The plane's root in (tmin, tmax), in its own frame: the t its intersect
 * finds, without its frame, point and (u,v) (shape_hit_t). */
bool pl_hit_t(const struct object *o, const struct ray *r, double tmin, double tmax, double *t);
/* A plane's unit normal, offset and in-plane axes, which pl_hit_t and the
 * plane's intersect work out on every call, worked out once (pl_prep) for
 * a leaf every ray tests: pl_prep_hit_t and pl_prep_hit then give
 * the same numbers, bit for bit. ok: the normal is not zero (else neither
 * hits). */
struct pl_prep {
	struct vec3 n, e1, e2;
	struct vec3 nw; /* v_norm(n): the world normal of a plane without a
	                   transform, as to_world finds it (shape_plane_hit_at) */
	double d;
	bool ok;
};
void pl_prep(const struct object *o, struct pl_prep *p);
bool pl_prep_hit_t(const struct pl_prep *p, const struct ray *r, double tmin, double tmax, double *t);
/* The hit of the plane n̂·p = d with in-plane axes e1, e2 at root t:
 * rebuilt from its (u,v) so it lies in the plane. Inline: the plane's
 * intersect and pl_prep_hit share it. */
static inline void prim_plane_hit(const struct vec3 *n, const struct vec3 *e1, const struct vec3 *e2, double d,
                                  const struct ray *r, double t, struct local_hit *lh)
{
	struct vec3 p = ray_at(*r, t);
	lh->t = t;
	lh->u = v_dot(p, *e1);
	lh->v = v_dot(p, *e2);
	lh->p = v_madd(v_madd(v_scale(*n, d), *e1, lh->u), *e2, lh->v);
	lh->n = *n;
	lh->dpdu = *e1;
	lh->dpdv = *e2;
}

/* The hit at the root t that pl_prep_hit_t found, as the plane's intersect
 * fills it there (inline: a light ray's every landing on a floor). */
static inline void pl_prep_hit(const struct pl_prep *p, const struct ray *r, double t, struct local_hit *lh)
{
	prim_plane_hit(&p->n, &p->e1, &p->e2, p->d, r, t, lh);
}
/* The torus's intersect without (u,v) and the partials (left unset):
 * the same t, point and normal (shape_intersect_bare). */
bool to_hit(const struct object *o, const struct ray *r, double tmin, double tmax, struct local_hit *lh);
/* The hit at a root t that sph_hit_t returned, as sph_intersect fills it;
 * without uv, (u,v) and the partials are left unset (shape_hit_at). */
bool sph_hit_at(const struct object *o, const struct ray *r, double t, bool uv, struct local_hit *lh);

/* ---- helpers shared by the primitives (shape.c) ------------------------- */

/* When o->xf's linear part is a rotation times a uniform scale s (possibly
 * mirrored), stores s² (the area factor) and returns true. */
bool shape_similarity(const struct object *o, double *area_scale);
/* World area of one unit of object-frame area on a plane with normal n. */
double shape_planar_scale(const struct object *o, struct vec3 n);
/* ∬ ‖∂T/∂u × ∂T/∂v‖ (world) over the cell by adaptive Gauss–Legendre; the
 * integrand must be smooth on the cell (callers split at seams). */
double shape_integrate_area(const struct object *o, double u0, double u1, double v0, double v1);
/* An orthonormal basis e1, e2 with e1 × e2 = w (w unit): e1 is the x axis
 * (or z when w is near x) made perpendicular to w. */
void shape_basis(struct vec3 w, struct vec3 *e1, struct vec3 *e2);

/* ---- the radial parametrisation of implicit surfaces (shape.c) ----------
 * Surfaces with no natural (u,v) (poly, blob, superellipsoid) are indexed
 * by the direction from a centre c, with the sphere's angles (φ = 2πu about
 * y from +x towards −z, θ = πv from −y): T(u,v) is the FIRST surface point
 * along the ray from c in that direction (docs/parametrisations.md,
 * "Implicit surfaces"). */

/* Fills lh->u, v, dpdu, dpdv for a hit at lh->p with normal lh->n. */
void prim_radial_hit(struct vec3 c, struct local_hit *lh);
/* T(u,v) and its partials, by intersecting the ray from c (through
 * intersect, in the object frame); false when that ray meets nothing or
 * grazes the surface. */
bool prim_radial_point(const struct object *o, struct vec3 c,
                       bool (*intersect)(const struct object *, const struct ray *, double,
                                         double, struct local_hit *),
                       double u, double v, struct vec3 *p, struct vec3 *dpdu, struct vec3 *dpdv);

/* Real roots of a·t² + b·t + c = 0 (a ≠ 0), t0 ≤ t1, without cancellation.
 * disc is b² − 4ac, passed in so callers may compute it more accurately. */
static inline bool prim_quadratic(double a, double b, double c, double disc, double *t0,
                                  double *t1)
{
	if (disc < 0 || a == 0)
		return false;
	double q = -0.5 * (b + copysign(sqrt(disc), b));
	double r0 = q / a, r1 = q != 0 ? c / q : r0;
	*t0 = d_min(r0, r1);
	*t1 = d_max(r0, r1);
	return true;
}

/* The nearer root in (tmin, tmax) of the ray and the sphere of centre c and
 * radius rad (> 0), in the sphere's frame. The discriminant is computed as
 * 4a·(r² − |f⊥|²), f⊥ the part of f = o − c perpendicular to d, which keeps
 * precision for distant rays (pbrt-v4's formulation). Inline: the sphere
 * primitive and the hierarchy's sphere leaves (bvh.c) share it; always
 * inlined, as the candidate test of every sphere leaf (GCC at -O2 would
 * call it, passing c through the stack). */
__attribute__((always_inline)) static inline bool prim_sphere_t(struct vec3 c, double rad,
                                                                 const struct ray *r, double tmin,
                                                                 double tmax, double *t)
{
	if (!(rad > 0))
		return false;
	struct vec3 f = v_sub(r->o, c), d = r->d;
	double a = v_dot(d, d), fd = v_dot(f, d), ff = v_dot(f, f), rr = rad * rad;
	/* a clear miss without a square root or a division: a·|f⊥|² = a·|f|² −
	 * (f·d)², rounded within 5e-16·a·|f|², exceeds a·r² by more than any
	 * error of the exact test below, which decides everything else */
	if (a * ff - fd * fd > a * (rr * (1 + 1e-9) + ff * 1e-12))
		return false;
	double b = 2 * fd, cc = ff - rr, t0, t1;
	/* from outside, moving away: b > 0 and c > 0 make both roots below
	 * (q = -(b + √disc)/2 < 0, q/a < 0 and c/q < 0), so none is past a
	 * tmin >= 0 (rays spawned on a sphere, towards lights or reflected) */
	if (fd > 0 && cc > 0 && tmin >= 0)
		return false;
	if (!(a > 0))
		return false;
	struct vec3 perp = v_madd(f, d, -fd / a);
	double lp = v_len(perp);
	double disc = 4 * a * (rad + lp) * (rad - lp);
	if (!prim_quadratic(a, b, cc, disc, &t0, &t1))
		return false;
	if (t0 > tmin && t0 < tmax)
		*t = t0;
	else if (t1 > tmin && t1 < tmax)
		*t = t1;
	else
		return false;
	return true;
}

/* The point and normal of the sphere of centre c and radius rad at root t
 * (as prim_sphere_t found it): the point on the ray projected back onto the
 * sphere. Inline: sph_hit_at (sphere.c) and the winner of a query that
 * needs no (u,v) (shape_hit_at) share it. */
__attribute__((always_inline)) static inline bool prim_sphere_at(struct vec3 c, double rad, const struct ray *r,
                                                                  double t, struct local_hit *lh)
{
	struct vec3 q = v_sub(ray_at(*r, t), c);
	double l = v_len(q);
	if (!(l > 0))
		return false;
	q = v_scale(q, 1 / l); /* reproject onto the surface */
	lh->t = t;
	lh->p = v_madd(c, q, rad);
	lh->n = q;
	return true;
}

/* The root t in (tmin, tmax) of the ray and the plane n̂·p = d. Inline: the
 * plane primitive and the hierarchy's plane leaves (bvh.c) share it. */
static inline bool prim_plane_root(struct vec3 n, double d, const struct ray *r, double tmin, double tmax,
                                   double *t)
{
	double den = v_dot(n, r->d);
	if (den == 0)
		return false;
	*t = (d - v_dot(n, r->o)) / den;
	return *t > tmin && *t < tmax;
}

/* Möller–Trumbore in double precision, edges inclusive: the ray meets the
 * triangle p0 + a·e1 + b·e2 at *t, with barycentric (a, b) in *a, *b (no
 * interval test on t). The triangle primitive and the mesh share it. */
static inline bool prim_tri_hit(struct vec3 p0, struct vec3 e1, struct vec3 e2, const struct ray *r,
                                double *t, double *a, double *b)
{
	struct vec3 pv = v_cross(r->d, e2);
	double det = v_dot(e1, pv);
	if (det == 0 || !isfinite(det))
		return false;
	double inv = 1 / det;
	struct vec3 s = v_sub(r->o, p0);
	double u = v_dot(s, pv) * inv;
	if (u < 0 || u > 1)
		return false;
	struct vec3 qv = v_cross(s, e1);
	double v = v_dot(r->d, qv) * inv;
	if (v < 0 || u + v > 1)
		return false;
	*t = v_dot(e2, qv) * inv;
	*a = u;
	*b = v;
	return true;
}

/* Area of {u0≤u≤u1, v0≤v≤v1, u+v≤1} for a rectangle already inside the
 * positive quadrant: the rectangle minus the corner cut off by u + v = 1. */
static inline double prim_tri_clipped_area(double u0, double u1, double v0, double v1)
{
	double full = (u1 - u0) * (v1 - v0);
	double over = u1 + v1 - 1; /* how far the top-right corner is past the line */
	if (over <= 0)
		return full;
	if (u0 + v0 >= 1)
		return 0;
	/* the cut corner is a right triangle of leg "over", minus what sticks
	 * out past the rectangle's left and bottom edges */
	double cut = 0.5 * over * over;
	double lx = over - (u1 - u0), ly = over - (v1 - v0);
	if (lx > 0)
		cut -= 0.5 * lx * lx;
	if (ly > 0)
		cut -= 0.5 * ly * ly;
	return full - cut;
}

/* Length of the overlap of [a0,a1] and [b0,b1] (0 when disjoint). */
static inline double prim_overlap(double a0, double a1, double b0, double b1)
{
	double lo = fmax(a0, b0), hi = fmin(a1, b1);
	return hi > lo ? hi - lo : 0;
}

/* x wrapped into [0,1). */
static inline double prim_wrap01(double x)
{
	x -= floor(x);
	return x >= 1 ? 0 : x;
}

/* atan2(y,x)/2π in [0,1). */
static inline double prim_turns(double y, double x)
{
	double a = atan2(y, x) / (2 * M_PI);
	return a < 0 ? (a + 1 < 1 ? a + 1 : 0) : a;
}

/* A vector as --dump-scene writes it. */
static inline void prim_dump_vec(FILE *out, struct vec3 v)
{
	fprintf(out, "<%.6g, %.6g, %.6g>", v.x + 0.0, v.y + 0.0, v.z + 0.0);
}

/* An infinite box. */
static inline struct bbox prim_infinite_box(void)
{
	return (struct bbox){v3(-INFINITY, -INFINITY, -INFINITY), v3(INFINITY, INFINITY, INFINITY)};
}

/* A hit of a solid of revolution's side or caps (cylinder, cone): its ray
 * parameter and its part (0 side, 1 cap a, 2 cap b). */
struct cand {
	double t;
	int part;
};

/* The nearest of c[0..n) with tmin < t < tmax (the first of equals), or -1. */
static inline int prim_cand_nearest(const struct cand *c, int n, double tmin, double tmax)
{
	int best = -1;
	for (int i = 0; i < n; i++)
		if (c[i].t > tmin && c[i].t < tmax && (best < 0 || c[i].t < c[best].t))
			best = i;
	return best;
}

/* Whether any of c[0..n) has tmin < t < tmax. */
static inline bool prim_cand_any(const struct cand *c, int n, double tmin, double tmax)
{
	for (int i = 0; i < n; i++)
		if (c[i].t > tmin && c[i].t < tmax)
			return true;
	return false;
}

#endif
