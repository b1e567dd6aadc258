/* SPDX-License-Identifier: MIT */
/* csg.c: union, merge, intersection and difference.
 *
 * Hits are found by walking the children's surface crossings along the ray
 * in order: take the nearest crossing of any child, keep it if it lies on
 * the boundary of the combined solid (inside() tests against the OTHER
 * children), else continue past it. The rules, for a crossing of child i at
 * point p:
 *
 *   union         always kept (POV-Ray keeps the inner surfaces; merge does not)
 *   merge         kept when p is inside no other child
 *   intersection  kept when p is inside every other child
 *   clip          child 0 (the object clipped_by the others): kept when p is
 *                 inside every other child; the others are never surfaces
 *   difference    child 0: kept when p is inside none of the others;
 *                 child i > 0: kept when p is inside child 0 and no other
 *                 subtracted child — its normal is flipped (it faces into
 *                 the removed part, which is outside the result)
 *
 * OF_INVERSE on a CSG node swaps inside and outside and flips its normals.
 * The node's own xf is unused: the evaluator composed it into the children. */
#include <math.h>

#include "shape.h"

/* Children whose next crossings are cached between steps (larger CSG nodes
 * recompute every child each step). */
#define CSG_CACHE 16

bool csg_is_csg(const struct object *o)
{
	return o->kind >= OBJ_FIRST_CSG && o->kind < OBJ_KIND_COUNT;
}

/* Is p inside child j for some j ≥ from, j ≠ skip? */
static bool inside_any(const struct object *o, int from, int skip, struct vec3 p)
{
	for (int j = from; j < o->g.csg.n; j++)
		if (j != skip && shape_inside(o->g.csg.kids[j], p))
			return true;
	return false;
}

/* Is p inside every child but skip? */
static bool inside_all(const struct object *o, int skip, struct vec3 p)
{
	for (int j = 0; j < o->g.csg.n; j++)
		if (j != skip && !shape_inside(o->g.csg.kids[j], p))
			return false;
	return true;
}

/* Does a crossing of child i at p lie on the combined surface? */
static bool keeps(const struct object *o, int i, struct vec3 p)
{
	switch (o->kind) {
	case OBJ_MERGE:
		return !inside_any(o, 0, i, p);
	case OBJ_INTERSECTION:
		return inside_all(o, i, p);
	case OBJ_CLIP:
		return i == 0 && inside_all(o, 0, p);
	case OBJ_DIFFERENCE:
		if (i == 0)
			return !inside_any(o, 1, -1, p);
		return shape_inside(o->g.csg.kids[0], p) && !inside_any(o, 1, i, p);
	default:
		return true;
	}
}

/* Orients a kept hit of child i for this node and the ray. */
static void finish(const struct object *o, int i, const struct ray *r, struct hit *h)
{
	bool flip = (o->kind == OBJ_DIFFERENCE && i > 0) != ((o->flags & OF_INVERSE) != 0);
	if (flip)
		h->n = v_neg(h->n);
	h->entering = v_dot(r->d, h->n) < 0;
}

/* Nearest crossing of child i in (t, tmax). */
static bool next_of(const struct object *o, int i, const struct ray *r, double t, double tmax,
                    struct hit *h)
{
	return shape_intersect(o->g.csg.kids[i], r, t, tmax, h);
}

/* The walk for nodes with at most CSG_CACHE children: each child's next
 * crossing is kept, and only the consumed child is advanced. */
static bool walk_cached(const struct object *o, const struct ray *r, double tmin, double tmax,
                        struct hit *h)
{
	struct hit next[CSG_CACHE];
	bool has[CSG_CACHE];
	int n = o->g.csg.n;
	for (int i = 0; i < n; i++)
		has[i] = next_of(o, i, r, tmin, tmax, &next[i]);
	for (int step = 0; step < 64 * n + 64; step++) {
		int b = -1;
		for (int i = 0; i < n; i++)
			if (has[i] && (b < 0 || next[i].t < next[b].t))
				b = i;
		if (b < 0)
			return false;
		if (keeps(o, b, next[b].p)) {
			*h = next[b];
			finish(o, b, r, h);
			return true;
		}
		has[b] = next_of(o, b, r, next[b].t, tmax, &next[b]);
	}
	return false;
}

/* The same walk for large nodes, recomputing every child at each step. */
static bool walk_plain(const struct object *o, const struct ray *r, double tmin, double tmax,
                       struct hit *h)
{
	double t = tmin;
	for (int step = 0; step < 64 * o->g.csg.n + 64; step++) {
		struct hit best, cur;
		int b = -1;
		for (int i = 0; i < o->g.csg.n; i++)
			if (next_of(o, i, r, t, b < 0 ? tmax : best.t, &cur))
				best = cur, b = i;
		if (b < 0)
			return false;
		if (keeps(o, b, best.p)) {
			*h = best;
			finish(o, b, r, h);
			return true;
		}
		t = best.t;
	}
	return false;
}

/* A union needs no walk: its nearest child crossing is the answer. */
static bool union_hit(const struct object *o, const struct ray *r, double tmin, double tmax,
                      struct hit *h)
{
	int b = -1;
	for (int i = 0; i < o->g.csg.n; i++)
		if (next_of(o, i, r, tmin, tmax, h))
			tmax = h->t, b = i;
	if (b >= 0)
		finish(o, b, r, h);
	return b >= 0;
}

bool csg_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                   struct hit *h)
{
	struct hit tmp;
	if (o->g.csg.n <= 0)
		return false;
	if (o->kind == OBJ_UNION) {
		if (!union_hit(o, r, tmin, tmax, &tmp))
			return false;
	} else if (o->g.csg.n <= CSG_CACHE) {
		if (!walk_cached(o, r, tmin, tmax, &tmp))
			return false;
	} else if (!walk_plain(o, r, tmin, tmax, &tmp)) {
		return false;
	}
	*h = tmp;
	return true;
}

bool csg_inside(const struct object *o, struct vec3 p)
{
	bool in;
	int n = o->g.csg.n;
	switch (o->kind) {
	case OBJ_INTERSECTION: case OBJ_CLIP:
		in = n > 0 && inside_all(o, -1, p);
		break;
	case OBJ_DIFFERENCE:
		in = n > 0 && shape_inside(o->g.csg.kids[0], p) && !inside_any(o, 1, -1, p);
		break;
	default:
		in = inside_any(o, 0, -1, p);
		break;
	}
	return (o->flags & OF_INVERSE) ? !in : in;
}

/* ==== bounds ============================================================= */

static struct bbox box_meet(struct bbox a, struct bbox b)
{
	struct bbox r = {v_max(a.lo, b.lo), v_min(a.hi, b.hi)};
	if (r.lo.x > r.hi.x || r.lo.y > r.hi.y || r.lo.z > r.hi.z)
		return bbox_empty();
	return r;
}

static struct bbox infinite(void)
{
	return (struct bbox){v3(-INFINITY, -INFINITY, -INFINITY), v3(INFINITY, INFINITY, INFINITY)};
}

/* Bounds of the node's solid, ignoring its own OF_INVERSE. */
static struct bbox solid_plain(const struct object *o)
{
	struct object *const *k = o->g.csg.kids;
	int n = o->g.csg.n;
	struct bbox b = bbox_empty();
	if (n <= 0)
		return b;
	if (o->kind == OBJ_DIFFERENCE)
		return shape_solid_bounds(k[0]);
	if (o->kind == OBJ_INTERSECTION || o->kind == OBJ_CLIP) {
		b = infinite();
		for (int i = 0; i < n; i++)
			b = box_meet(b, shape_solid_bounds(k[i]));
		return b;
	}
	for (int i = 0; i < n; i++)
		b = bbox_union(b, shape_solid_bounds(k[i]));
	return b;
}

struct bbox csg_solid_bounds(const struct object *o)
{
	return (o->flags & OF_INVERSE) ? infinite() : solid_plain(o);
}

/* The surface lies on the children's surfaces, and for intersection and
 * difference also within the (uninverted) solid. */
struct bbox csg_bounds(const struct object *o)
{
	struct bbox b = bbox_empty();
	for (int i = 0; i < (o->kind == OBJ_CLIP ? 1 : o->g.csg.n); i++)
		b = bbox_union(b, shape_bounds(o->g.csg.kids[i]));
	if (o->kind == OBJ_INTERSECTION || o->kind == OBJ_DIFFERENCE || o->kind == OBJ_CLIP)
		b = box_meet(b, solid_plain(o));
	return b;
}
