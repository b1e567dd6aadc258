/* SPDX-License-Identifier: MIT */
/* shape.h: the primitive interface: ray hits, inside tests, bounds and the
 * (u,v) parametrisations the illumination maps are indexed by.
 *
 * Every function takes an object of the scene model (tracer/scene.h) whose xf
 * maps its own frame to the world; rays, points, bounds and areas here are in
 * WORLD space. CSG nodes (union, intersection, difference, merge) go through
 * the same entry points (csg.c); their own xf is ignored, since the evaluator
 * has already composed it into every child.
 *
 * Conventions (docs/parametrisations.md has the per-primitive details):
 *   - hit.n is the unit outward normal of the solid the object stands for
 *     (OF_INVERSE and CSG difference flip it); hit.entering says the ray
 *     crosses the surface from outside to inside (d·n < 0).
 *   - In the primitive's own frame dpdu × dpdv points along the primitive's
 *     outward normal (before OF_INVERSE); a transform with det < 0 flips it.
 *   - Bounded surfaces use (u,v) ∈ [0,1]²; the plane uses world-unit
 *     coordinates along two orthonormal in-plane axes, unbounded. */
#ifndef ARVO_SHAPE_H
#define ARVO_SHAPE_H

#include <stdbool.h>

#include "../common/vec.h"
#include "scene.h"

/* A ray-surface intersection. */
struct hit {
	double t;                 /* ray parameter: p = r.o + t·r.d */
	struct vec3 p;            /* world point on the surface */
	struct vec3 n;            /* unit outward geometric normal (world) */
	double u, v;              /* surface parameters of p */
	struct vec3 dpdu, dpdv;   /* world-space partials of T(u,v) */
	const struct object *obj; /* the primitive hit (never a CSG node) */
	bool entering;            /* the ray enters the solid here */
};

/* The (u,v) domain of a surface. */
struct uv_range {
	double u0, u1; /* u interval ([0,1], or ±INFINITY for the plane) */
	double v0, v1; /* v interval */
	bool bounded;  /* false for the plane: u,v are unbounded world units */
	bool u_wraps;  /* u is periodic with period 1 (a sweep around an axis) */
	bool v_wraps;  /* v is periodic with period 1 (torus) */
};

/* Nearest hit with tmin < t < tmax; fills *h and returns true, else false. */
bool shape_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                     struct hit *h);
/* shape_intersect for a caller that reads no (u,v) or partials (the eye
 * pass without illumination maps): the same t, point and normal, with
 * (u,v) NaN and the partials zero, which the torus does not work out. */
bool shape_intersect_bare(const struct object *o, const struct ray *r, double tmin, double tmax,
                          struct hit *h);
/* The t of that nearest hit alone: the same t shape_intersect finds over the
 * same interval, cheaper where the primitive can skip the rest (spheres,
 * planes). */
bool shape_hit_t(const struct object *o, const struct ray *r, double tmin, double tmax, double *t);
/* The hit shape_intersect finds over (tmin, tmax), given the t shape_hit_t
 * found there; without uv, (u,v) may be NaN and the partials zero (the eye
 * pass needs them only on a surface with an illumination map). */
bool shape_hit_at(const struct object *o, const struct ray *r, double tmin, double tmax, double t,
                  bool uv, struct hit *h);
/* shape_hit_t and shape_hit_at for plane o, with its frame p made once by
 * pl_prep (shapes/prim.h): the same results; the hit is filled at the t
 * shape_plane_hit_t found, without solving for it again. */
struct pl_prep;
bool shape_plane_hit_t(const struct object *o, const struct pl_prep *p, const struct ray *r, double tmin,
                       double tmax, double *t);
void shape_plane_hit_at(const struct object *o, const struct pl_prep *p, const struct ray *r, double t, bool uv,
                        struct hit *h);
/* Any hit with tmin < t < tmax (shadow rays). */
bool shape_occluded(const struct object *o, const struct ray *r, double tmin, double tmax);
/* Is o's solid convex (a sphere, a box, a plane's half-space, a closed
 * cylinder or cone; never OF_INVERSE)? Then a ray from a point of its
 * surface, offset along the
 * outward normal n, with direction d·n >= 0, stays in the half-space
 * beyond the tangent plane, which holds none of the solid: it cannot hit o
 * again (bvh_intersect_from). Inline: the eye pass asks at every hit. */
static inline bool shape_convex(const struct object *o)
{
	if (o->flags & OF_INVERSE)
		return false;
	switch (o->kind) {
	case OBJ_SPHERE:
	case OBJ_BOX:
	case OBJ_PLANE: /* a half-space */
		return true;
	case OBJ_CYLINDER:
		return !(o->flags & OF_OPEN);
	case OBJ_CONE: /* the solid between the caps; an apex where a radius is 0 */
		return !(o->flags & OF_OPEN) && o->g.cone.ra >= 0 && o->g.cone.rb >= 0;
	default:
		return false;
	}
}
/* Is the world point strictly inside the solid (OF_INVERSE honoured)? */
bool shape_inside(const struct object *o, struct vec3 world_p);
/* World bounds of the object's SURFACE; ±INFINITY components when unbounded. */
struct bbox shape_bounds(const struct object *o);
/* World bounds of the SOLID (everything inside); infinite when OF_INVERSE. */
struct bbox shape_solid_bounds(const struct object *o);
/* Are all of shape_bounds(o)'s components finite? */
bool shape_bounded(const struct object *o);
/* A sphere that holds the object's surface (centre *c, radius *r in world
 * units; false when unbounded): a sphere's own, else the smaller of the
 * world bounds' sphere and the transformed object-frame bounds' sphere.
 * The light pass aims at it (docs/design.md §4). */
bool shape_bsphere(const struct object *o, struct vec3 *c, double *r);
/* Writes a primitive's geometry for --dump-scene; false for CSG kinds. */
bool shape_dump(const struct object *o, FILE *out);

/* T(u,v): the world point and world partials at (u,v). Outside the domain the
 * same formulas extend the surface (periodic parameters wrap). Returns false
 * for CSG nodes and degenerate primitives. dpdu/dpdv may be NULL. */
bool shape_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                    struct vec3 *dpdu, struct vec3 *dpdv);
/* The (u,v) domain; false for CSG nodes. */
bool shape_uv_range(const struct object *o, struct uv_range *out);
/* World area of the surface over [u0,u1]×[v0,v1] (u0 ≤ u1, v0 ≤ v1), i.e. the
 * integral of ‖∂T/∂u × ∂T/∂v‖. Non-periodic parameters are clipped to the
 * domain, periodic ones are not (a cell straddling a seam is fine). Exact in
 * closed form for planar pieces and similarity transforms, adaptive Gauss–
 * Legendre otherwise; finite at poles and apexes. 0 for CSG nodes. */
double shape_cell_area(const struct object *o, double u0, double u1, double v0, double v1);
/* Total world surface area (INFINITY for the plane, 0 for CSG nodes). */
double shape_area(const struct object *o);

/* ---- meshes (shapes/mesh.c) ---------------------------------------------- */

/* Builds m's hierarchy in the arena and its (u,v) atlas; false when a
 * triangle's indices are out of range (*bad: which) or it has no triangle. */
bool mesh_finish(struct mesh *m, struct arena *a, int *bad);

/* ---- CSG (csg.c): called by the shape_ entry points for CSG kinds -------- */

bool csg_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                   struct hit *h);
bool csg_inside(const struct object *o, struct vec3 world_p);
/* Surface bounds (as shape_bounds) and solid bounds (bounds of the inside). */
struct bbox csg_bounds(const struct object *o);
struct bbox csg_solid_bounds(const struct object *o);
/* Is o one of the CSG kinds? */
bool csg_is_csg(const struct object *o);

#endif
