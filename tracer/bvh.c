/* SPDX-License-Identifier: MIT */
/* bvh.c: the acceleration structure and traversal, on Embree 3
 * (docs/design.md §5).
 *
 * Every bounded leaf is one primitive of a single Embree user geometry:
 * Embree builds the hierarchy over float boxes and walks it; the callbacks
 * run arvo's own double-precision intersectors, so (u,v), partials and the
 * accuracy of every hit are those of shape.h. Unbounded leaves are tested on
 * every ray first, as before.
 *
 * Float culling must never drop the true nearest hit. Boxes are padded
 * outward by a margin that covers rounding the ray to float: a ray that
 * starts outside the scene's box is first moved (in double) to where it
 * enters it, so its float origin is within the box's magnitude, and the
 * margin is a few float ulps of that magnitude. The ray's float interval is
 * rounded outward too. Ties at the same t go to the lower primitive index,
 * and unbounded leaves win ties with bounded ones, so the hit is the one a
 * brute-force loop over the leaves in order returns, whatever order Embree
 * visits them in: images do not depend on the build or the thread count. */
#include "bvh.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>

#include "../common/arena.h"

struct bvh {
	RTCScene scene;                /* NULL when nothing is bounded */
	const struct object **prims;   /* bounded leaves, in collection order */
	int nprims;                    /* entries of prims */
	const struct object **unbound; /* unbounded leaves, tested always */
	int nunbound;                  /* entries of unbound */
	struct bbox bounds;            /* world bounds of the bounded leaves */
	double pad;                    /* float safety margin of every box */
};

/* One query: Embree's context first, so the callbacks can reach the rest. */
struct query {
	struct RTCIntersectContext rc;
	const struct bvh *b;
	const struct ray *r;   /* the ray in double */
	double tmin, tmax;     /* open interval; tmax shrinks to the best hit */
	double t0;             /* where the float ray starts along r */
	unsigned skip;         /* leaves with these flags are ignored */
	struct hit *h;         /* best hit so far */
	int best;              /* its primitive index, -1: an unbounded leaf */
	bool found;
};

/* ==== the device ========================================================= */

static RTCDevice device;
static pthread_once_t device_once = PTHREAD_ONCE_INIT;

static void make_device(void)
{
	device = rtcNewDevice("verbose=0");
}

/* ==== collecting leaves ================================================== */

struct builder {
	struct bvh *t;
	int cap, capu;
};

static void add_leaf(struct builder *B, const struct object *o, struct bbox b)
{
	struct bvh *t = B->t;
	if (t->nprims == B->cap) {
		B->cap = B->cap ? 2 * B->cap : 64;
		t->prims = mem_realloc(t->prims, sizeof *t->prims * (size_t)B->cap);
	}
	t->prims[t->nprims++] = o;
	t->bounds = bbox_union(t->bounds, b);
}

static void add_unbound(struct builder *B, const struct object *o)
{
	struct bvh *t = B->t;
	if (t->nunbound == B->capu) {
		B->capu = B->capu ? 2 * B->capu : 8;
		t->unbound = mem_realloc(t->unbound, sizeof *t->unbound * (size_t)B->capu);
	}
	t->unbound[t->nunbound++] = o;
}

/* Adds o, descending into unions that are not inverted. */
static void collect(struct builder *B, const struct object *o)
{
	if (o->kind == OBJ_UNION && !(o->flags & OF_INVERSE)) {
		for (int i = 0; i < o->g.csg.n; i++)
			collect(B, o->g.csg.kids[i]);
		return;
	}
	struct bbox b = shape_bounds(o);
	if (b.lo.x > b.hi.x || b.lo.y > b.hi.y || b.lo.z > b.hi.z)
		return; /* empty: nothing to hit */
	if (!shape_bounded(o))
		add_unbound(B, o);
	else
		add_leaf(B, o, b);
}

/* ==== callbacks ========================================================== */

static float down(double x) { float f = (float)x; return (double)f > x ? nextafterf(f, -INFINITY) : f; }
static float up(double x) { float f = (float)x; return (double)f < x ? nextafterf(f, INFINITY) : f; }

static void bounds_cb(const struct RTCBoundsFunctionArguments *a)
{
	const struct bvh *t = a->geometryUserPtr;
	struct bbox b = shape_bounds(t->prims[a->primID]); /* as collect found it */
	double p = t->pad;
	*a->bounds_o = (struct RTCBounds){down(b.lo.x - p), down(b.lo.y - p), down(b.lo.z - p), 0,
	                                  up(b.hi.x + p), up(b.hi.y + p), up(b.hi.z + p), 0};
}

static void intersect_cb(const struct RTCIntersectFunctionNArguments *a)
{
	if (!a->valid[0])
		return;
	struct query *q = (struct query *)a->context;
	int id = (int)a->primID;
	const struct object *o = q->b->prims[id];
	if (o->flags & q->skip)
		return;
	/* a tie with the best so far is looked at: the lower index wins */
	double hi = q->found && q->best >= 0 && id < q->best ? nextafter(q->tmax, INFINITY) : q->tmax;
	struct hit tmp;
	if (!shape_intersect(o, q->r, q->tmin, hi, &tmp))
		return;
	*q->h = tmp;
	q->tmax = tmp.t;
	q->best = id;
	q->found = true;
	struct RTCRayHit *rh = (struct RTCRayHit *)a->rayhit;
	rh->ray.tfar = up((tmp.t - q->t0) * (1 + 1e-6));
	rh->hit.geomID = a->geomID;
	rh->hit.primID = a->primID;
}

static void occluded_cb(const struct RTCOccludedFunctionNArguments *a)
{
	if (!a->valid[0])
		return;
	struct query *q = (struct query *)a->context;
	const struct object *o = q->b->prims[a->primID];
	if (o->flags & q->skip)
		return;
	if (shape_occluded(o, q->r, q->tmin, q->tmax))
		((struct RTCRay *)a->ray)->tfar = -INFINITY;
}

/* ==== building =========================================================== */

struct bvh *bvh_build(struct object **objs, int n)
{
	struct bvh *t = mem_calloc(1, sizeof *t);
	struct builder B = {t, 0, 0};
	t->bounds = bbox_empty();
	for (int i = 0; i < n; i++)
		collect(&B, objs[i]);
	if (t->nprims == 0)
		return t;
	/* rounding a ray that starts inside (or on) the box to float moves it
	 * by a few ulps of the box's magnitude and diagonal */
	struct vec3 m = v_max(v_neg(t->bounds.lo), t->bounds.hi);
	double mag = fmax(fmax(m.x, m.y), m.z) + v_len(v_sub(t->bounds.hi, t->bounds.lo));
	t->pad = ldexp(mag, -18) + 1e-30;
	pthread_once(&device_once, make_device);
	if (!device)
		return t; /* no Embree: every leaf is tested (see traverse) */
	t->scene = rtcNewScene(device);
	rtcSetSceneFlags(t->scene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT);
	rtcSetSceneBuildQuality(t->scene, RTC_BUILD_QUALITY_MEDIUM);
	RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
	rtcSetGeometryUserPrimitiveCount(g, (unsigned)t->nprims);
	rtcSetGeometryUserData(g, t);
	rtcSetGeometryBoundsFunction(g, bounds_cb, t);
	rtcSetGeometryIntersectFunction(g, intersect_cb);
	rtcSetGeometryOccludedFunction(g, occluded_cb);
	rtcCommitGeometry(g);
	rtcAttachGeometry(t->scene, g);
	rtcReleaseGeometry(g);
	rtcCommitScene(t->scene);
	return t;
}

void bvh_free(struct bvh *b)
{
	if (!b)
		return;
	if (b->scene)
		rtcReleaseScene(b->scene);
	free(b->prims);
	free(b->unbound);
	free(b);
}

int bvh_count(const struct bvh *b, int *unbounded)
{
	if (unbounded)
		*unbounded = b->nunbound;
	return b->nprims;
}

struct bbox bvh_bounds(const struct bvh *b)
{
	return b->bounds;
}

/* ==== traversal ========================================================== */

/* Where r enters box b over (tmin, tmax): false when it misses. */
static bool enter(struct bbox b, const struct ray *r, double tmin, double tmax, double *t)
{
	for (int k = 0; k < 3; k++) {
		double o = v_comp(r->o, k), d = v_comp(r->d, k);
		double t0 = (v_comp(b.lo, k) - o) / d, t1 = (v_comp(b.hi, k) - o) / d;
		if (t0 > t1) {
			double s = t0;
			t0 = t1;
			t1 = s;
		}
		if (t0 > tmin) /* NaN (0/0) leaves the bound as it is */
			tmin = t0;
		if (t1 < tmax)
			tmax = t1;
		if (tmin > tmax)
			return false;
	}
	*t = tmin;
	return true;
}

/* The bounded leaves through Embree; q holds the interval and the result. */
static void walk(struct query *q, bool any)
{
	const struct bvh *b = q->b;
	struct bbox bx = {v_sub(b->bounds.lo, v3(b->pad, b->pad, b->pad)),
	                  v_add(b->bounds.hi, v3(b->pad, b->pad, b->pad))};
	double te;
	if (!enter(bx, q->r, -INFINITY, INFINITY, &te) || !(te < q->tmax))
		return;
	q->t0 = te > 0 ? te : 0; /* the float ray starts here along r */
	struct vec3 o = v_add(q->r->o, v_scale(q->r->d, q->t0));
	struct RTCRayHit rh;
	rh.ray.org_x = (float)o.x, rh.ray.org_y = (float)o.y, rh.ray.org_z = (float)o.z;
	rh.ray.dir_x = (float)q->r->d.x, rh.ray.dir_y = (float)q->r->d.y, rh.ray.dir_z = (float)q->r->d.z;
	double lo = q->tmin - q->t0;
	rh.ray.tnear = lo > 0 ? down(lo * (1 - 1e-6)) : 0;
	rh.ray.tfar = isinf(q->tmax) ? INFINITY : up((q->tmax - q->t0) * (1 + 1e-6));
	rh.ray.time = 0;
	rh.ray.mask = ~0u;
	rh.ray.id = 0;
	rh.ray.flags = 0;
	rtcInitIntersectContext(&q->rc);
	if (any) {
		rtcOccluded1(b->scene, &q->rc, &rh.ray);
		q->found = rh.ray.tfar < 0;
	} else {
		rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
		rtcIntersect1(b->scene, &q->rc, &rh);
	}
}

/* Without a device (Embree failed to start): every bounded leaf in order. */
static void brute(struct query *q, bool any)
{
	struct hit tmp;
	for (int i = 0; i < q->b->nprims && !(any && q->found); i++) {
		const struct object *o = q->b->prims[i];
		if (o->flags & q->skip)
			continue;
		if (any)
			q->found = shape_occluded(o, q->r, q->tmin, q->tmax);
		else if (shape_intersect(o, q->r, q->tmin, q->tmax, &tmp))
			*q->h = tmp, q->tmax = tmp.t, q->best = i, q->found = true;
	}
}

/* The query shared by both kinds: with any set, stops at the first hit. */
static bool traverse(const struct bvh *b, const struct ray *r, double tmin, double tmax,
                     unsigned skip, bool any, struct hit *h)
{
	struct query q = {.b = b, .r = r, .tmin = tmin, .tmax = tmax, .skip = skip, .h = h, .best = -1};
	struct hit tmp;
	for (int i = 0; i < b->nunbound; i++) {
		const struct object *o = b->unbound[i];
		if (o->flags & skip)
			continue;
		if (any && shape_occluded(o, r, tmin, tmax))
			return true;
		if (!any && shape_intersect(o, r, q.tmin, q.tmax, &tmp))
			*h = tmp, q.tmax = tmp.t, q.found = true;
	}
	if (b->nprims == 0)
		return q.found;
	if (b->scene)
		walk(&q, any);
	else
		brute(&q, any);
	return q.found;
}

bool bvh_intersect_skip(const struct bvh *b, const struct ray *r, double tmin, double tmax,
                        unsigned skip, struct hit *h)
{
	return traverse(b, r, tmin, tmax, skip, false, h);
}

bool bvh_occluded_skip(const struct bvh *b, const struct ray *r, double tmin, double tmax,
                       unsigned skip)
{
	return traverse(b, r, tmin, tmax, skip, true, NULL);
}

bool bvh_intersect(const struct bvh *b, const struct ray *r, double tmin, double tmax,
                   struct hit *h)
{
	return traverse(b, r, tmin, tmax, 0, false, h);
}

bool bvh_occluded(const struct bvh *b, const struct ray *r, double tmin, double tmax)
{
	return traverse(b, r, tmin, tmax, 0, true, NULL);
}
