/* SPDX-License-Identifier: MIT */
/* bvh.h: a bounding volume hierarchy over the scene's objects.
 *
 * Top-level unions (not inverted) are flattened into their children, which
 * can be traced independently; intersection, difference, merge and inverted
 * unions stay whole as leaves. Unbounded objects (planes, CSG containing
 * them, inverted primitives) are kept apart and tested on every ray. Embree 3
 * builds and walks the hierarchy (bvh.c); the hit is exactly the one a loop
 * over every leaf in order would return. Queries are thread-safe. */
#ifndef ARVO_BVH_H
#define ARVO_BVH_H

#include <stdbool.h>

#include "shape.h"

struct bvh;

/* A bit of a query's skip mask that is no object flag: the nearest hit may
 * come without its (u,v) and partials (NaN and zero; shape_hit_at). */
#define BVH_NO_UV (1u << 31)
/* Another: no hit's (u,v) or partials are read at all (the eye pass without
 * illumination maps), so no leaf works them out (shape_intersect_bare). */
#define BVH_UV_UNREAD (1u << 30)

/* Builds the hierarchy over objs[0..n); the objects, and the array objs
 * itself (the hierarchy may use it as its list of leaves), must outlive it. */
struct bvh *bvh_build(struct object **objs, int n);
/* Nearest hit with tmin < t < tmax over every object (as shape_intersect). */
bool bvh_intersect(const struct bvh *b, const struct ray *r, double tmin, double tmax,
                   struct hit *h);
/* Any hit with tmin < t < tmax (shadow rays). */
bool bvh_occluded(const struct bvh *b, const struct ray *r, double tmin, double tmax);
/* The same, ignoring leaves whose flags share a bit with skip (e.g.
 * OF_NO_SHADOW for shadow rays, OF_NO_IMAGE for camera rays). */
bool bvh_intersect_skip(const struct bvh *b, const struct ray *r, double tmin, double tmax,
                        unsigned skip, struct hit *h);
bool bvh_occluded_skip(const struct bvh *b, const struct ray *r, double tmin, double tmax,
                       unsigned skip);
/* bvh_intersect_skip and bvh_occluded_skip for a ray that leaves convex
 * leaf from outward (shape_convex): from, which it cannot hit, is not
 * tested; NULL: every leaf is. */
bool bvh_intersect_from(const struct bvh *b, const struct ray *r, double tmin, double tmax, unsigned skip,
                        const struct object *from, struct hit *h);
bool bvh_occluded_from(const struct bvh *b, const struct ray *r, double tmin, double tmax, unsigned skip,
                       const struct object *from);
/* bvh_intersect_skip for a ray that starts next to leaf in and most likely
 * meets it first (refracted into it, or reflected inside it): the same hit,
 * found without walking the other leaves when the ray starts in that leaf's
 * box, no other leaf lies near it (a scene of a few leaves, bvh.c) and the
 * ray meets it; else, or with in NULL, every leaf is walked. */
bool bvh_intersect_in(const struct bvh *b, const struct ray *r, double tmin, double tmax, unsigned skip,
                      const struct object *in, struct hit *h);
/* bvh_intersect_skip, where the caller may not need the whole hit: when
 * full(ctx, object hit) returns false, *h may hold only obj and t, with
 * (u,v) NaN (the rest unset), which spares working out the point, normal
 * and (u,v) of a hit found by its t alone. full NULL: the whole hit. */
bool bvh_intersect_lazy(const struct bvh *b, const struct ray *r, double tmin, double tmax, unsigned skip,
                        struct hit *h, bool (*full)(const void *ctx, const struct object *o), const void *ctx);
/* The nearest hits of n <= BVH_PACKET rays at once, as bvh_intersect_skip
 * finds them one by one, bit for bit: Embree walks them as one packet
 * (camera rays of a 4×4 block of pixels, which stay together). found[i]
 * says whether ray i hit. */
#define BVH_PACKET 16
void bvh_intersect_packet(const struct bvh *b, int n, const struct ray *r, double tmin, double tmax,
                          unsigned skip, struct hit *h, bool *found);
/* Whether each of n <= BVH_PACKET shadow rays r[i] is blocked over
 * (0, tmax[i]), as bvh_occluded_skip answers one by one: Embree walks them
 * as one packet (the shadow rays of a 4×4 block's camera hits towards one
 * light, which stay together). */
void bvh_occluded_packet(const struct bvh *b, int n, const struct ray *r, const double *tmax,
                         unsigned skip, bool *blocked);
/* Whether Embree walks b's queries: false for a scene traced leaf by leaf
 * (a few leaves, bvh.c), where a packet costs what its rays cost one by
 * one, plus the packet's set-up. */
bool bvh_walks(const struct bvh *b);
/* Leaves after flattening: bounded ones in the tree, and unbounded ones. */
int bvh_count(const struct bvh *b, int *unbounded);
/* World bounds of everything bounded in the tree (empty when none). */
struct bbox bvh_bounds(const struct bvh *b);
void bvh_free(struct bvh *b);

#endif
