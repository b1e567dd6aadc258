/* SPDX-License-Identifier: MIT */
/* bvh.c: the acceleration structure and traversal, on Embree 3
 * (docs/design.md §5).
 *
 * Every bounded leaf is one primitive of a single Embree user geometry:
 * Embree builds the hierarchy over float boxes and walks it; the callbacks
 * run arvo's own double-precision intersectors, so (u,v), partials and the
 * accuracy of every hit are those of shape.h. A sphere candidate computes
 * its t alone (shape_hit_t); the point, normal, (u,v) and partials are
 * computed once, for the winner. Unbounded leaves are tested on every ray
 * first, as before.
 *
 * Native Embree spheres (RTC_GEOMETRY_TYPE_SPHERE_POINT) are no way round
 * the callbacks: bench/eye/kernel.sh times the same camera rays through
 * this kernel and through Embree alone, and Embree's own float spheres are
 * slower on the random cloud at 100k spheres (3.3 against 3.8 M rays/s on
 * one core) and faster on the grid (11.9 against 9.4); besides, Embree
 * proposes a sphere only where the float segment meets its surface with
 * tnear >= 0, which a ray starting in the margin's shell (every ray spawned
 * on a sphere) can miss. Neither RTC_SCENE_FLAG_ROBUST nor _COMPACT is set:
 * the margins below already cover the float error of the non-robust box
 * test, and the two flags cost 7 % and 10-20 % of the traversal in a
 * stand-alone Embree test (compact would save 13-18 MB at 1M leaves).
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
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "../common/arena.h"
#include "leafbox.h"
#include "shapes/prim.h"

struct bvh {
	RTCScene scene;                /* NULL when nothing is bounded */
	const struct object **prims;   /* bounded leaves, in collection order */
	int nprims;                    /* entries of prims */
	bool own_prims;                /* prims is ours to free, not the caller's list */
	const struct object **unbound; /* unbounded leaves, tested always */
	struct pl_prep *uplane;        /* per unbounded leaf: its frame, when a plane */
	int nunbound;                  /* entries of unbound */
	struct bbox bounds;            /* world bounds of the bounded leaves */
	double pad;                    /* float safety margin of every box */
	struct bbox padded;            /* bounds grown by pad (float_ray) */
	bool brute;                    /* few leaves: tested without Embree (brute) */
	struct bbox lbox[LEAFBOX_MAX]; /* with box: each leaf's box grown by pad */
	bool alone[LEAFBOX_MAX];       /* with box: no other leaf's grown box comes
	                                  within pad of this leaf's (bvh_intersect_in) */
	struct leafbox *box;           /* the leaves' boxes grown by pad, when brute
	                                  tests boxes first (NULL: it does not) */
	/* with Embree (spatial_order): leaf ids in Morton order, and what the
	 * callbacks read of each leaf side by side in that order */
	int32_t *rank;                 /* leaf id is prims[rank[id]] (leaf); NULL: prims[id] */
	struct sph *sph;               /* per leaf id: its centre and radius, when a sphere
	                                  without a transform */
	unsigned flags_any;            /* the object flags of any leaf, or'ed */
};

/* A leaf as the callbacks test it when it is a sphere without a transform:
 * the centre and radius of its object, copied; r NaN when it is not one. */
struct sph {
	double x, y, z, r;
};

/* The object of leaf id (a primitive index of the queries and of Embree). */
static inline const struct object *leaf(const struct bvh *b, int id)
{
	return b->prims[b->rank ? b->rank[id] : id];
}

/* One query: Embree's context first, so the callbacks can reach the rest;
 * lanes says whether the context is this query (1) or a packet's (16). */
struct query {
	struct RTCIntersectContext rc;
	int lanes;             /* 1 */
	const struct bvh *b;
	const struct ray *r;   /* the ray in double */
	double tmin, tmax;     /* open interval; tmax shrinks to the best hit */
	double t0;             /* where the float ray starts along r */
	unsigned skip;         /* leaves with these flags are ignored (and
	                          BVH_UV_UNREAD, which no object flag is) */
	struct hit *h;         /* best hit so far */
	bool uv;               /* the hit needs its (u,v) and partials */
	int best;              /* its primitive index, -1: an unbounded leaf */
	double best_t;         /* its t, when deferred */
	int ubest;             /* an unbounded winner found by its t alone, or -1 */
	double best_hi;        /* the interval's end its test used */
	bool found;
	bool deferred;         /* *h is still to be filled from primitive best */
	const struct object *from; /* a convex leaf the ray leaves outward: not tested */
};

/* The queries of a packet of rays, lane i in q[i] (rtcIntersect16), and,
 * with native 16-wide packets, their rays' doubles by rows (lanes16). */
struct packet {
	struct RTCIntersectContext rc;
	int lanes;             /* BVH_PACKET */
	int base;              /* the queries of Embree's lane i are q[base + i] */
	double tmin;           /* every lane's tmin */
	bool rows;             /* ox… are set (packet_rows) */
	struct query q[BVH_PACKET];
	_Alignas(64) double ox[BVH_PACKET], oy[BVH_PACKET], oz[BVH_PACKET]; /* q[i].r->o */
	_Alignas(64) double dx[BVH_PACKET], dy[BVH_PACKET], dz[BVH_PACKET]; /* q[i].r->d */
	_Alignas(64) double dd[BVH_PACKET];                                 /* q[i].r->d · itself */
};

/* ==== the device ========================================================= */

static RTCDevice device;
static pthread_once_t device_once = PTHREAD_ONCE_INIT;

static bool native16; /* the CPU walks packets of 16 natively (AVX-512) */

static void make_device(void)
{
	device = rtcNewDevice("verbose=0");
	/* Without AVX-512 Embree emulates rtcIntersect16 and, in the Debian
	 * build, asserts in it on a packet of ours; two packets of 8 give the
	 * same hits (the hits do not depend on how Embree walks). */
	native16 = device && rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED);
}

/* ==== collecting leaves ================================================== */

/* While every object so far is a bounded leaf, prims is the caller's list
 * itself (a million spheres need no second array of a million pointers);
 * the first union or unbounded object makes it a copy of its own. */
struct builder {
	struct bvh *t;
	struct object *const *objs; /* the caller's list */
	int next;                   /* objs[next] is the next to be collected */
	int cap, capu;
};

static void add_leaf(struct builder *B, const struct object *o, struct bbox b)
{
	struct bvh *t = B->t;
	t->bounds = bbox_union(t->bounds, b);
	if (!t->own_prims && t->nprims == B->next && B->objs[B->next] == o) {
		t->nprims++; /* still the caller's list */
		return;
	}
	if (!t->own_prims || t->nprims == B->cap) {
		B->cap = B->cap ? 2 * B->cap : t->nprims + 64;
		const struct object **p = mem_alloc(sizeof *p * (size_t)B->cap);
		for (int i = 0; i < t->nprims; i++)
			p[i] = t->prims[i];
		if (t->own_prims)
			free(t->prims);
		t->prims = p;
		t->own_prims = true;
	}
	t->prims[t->nprims++] = o;
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
	if (!bbox_finite(b)) /* shape_bounded(o), from the box in hand */
		add_unbound(B, o);
	else
		add_leaf(B, o, b);
}

/* Scenes with at most BRUTE_MAX bounded leaves, each of a kind whose exact
 * test is a closed form (cheap_kind), are traced without Embree (brute),
 * every leaf tested on every ray. Other scenes of at most LEAFBOX_MAX
 * leaves are traced without Embree too, the leaves' boxes tested first, in
 * double, two at a time (boxed). */
#define BRUTE_MAX 4

/* A leaf whose exact test costs about what Embree's box test would: without
 * Embree's culling every ray tests every leaf, and four tori or isosurfaces
 * tested on every ray cost more than Embree's walk (a fifth more on a test
 * scene of two tori and an isosurface). */
static bool cheap_kind(const struct object *o)
{
	switch (o->kind) {
	case OBJ_SPHERE: case OBJ_BOX: case OBJ_TRIANGLE: case OBJ_DISC: case OBJ_CYLINDER: case OBJ_CONE:
		return true;
	default:
		return false;
	}
}

/* ==== callbacks ========================================================== */

/* Inlined wherever it is called: the steps of a query (traverse and what
 * it calls), which GCC otherwise leaves as calls. On a small scene (two
 * leaves, no Embree) their entries and exits were a seventh of the query:
 * the light pass of tests/accuracy/sphere.scn at 1M rays spent 843 M
 * instructions in bvh_intersect_lazy before, 724 M after. */
#define HOT static inline __attribute__((always_inline))

/* The next float towards -inf (+inf) from a finite, non-zero float f:
 * nextafterf, without the call. */
static float step_float(float f, bool towards_up)
{
	uint32_t b;
	memcpy(&b, &f, sizeof b);
	b += (f > 0) == towards_up ? 1u : ~0u; /* away from or towards zero */
	memcpy(&f, &b, sizeof f);
	return f;
}

/* The next double above x (x not NaN): nextafter(x, INFINITY), without
 * the call. */
static inline double next_up(double x)
{
	if (x == INFINITY)
		return x;
	if (x == 0)
		return 0x1p-1074;
	uint64_t u;
	memcpy(&u, &x, sizeof u);
	u += x > 0 ? 1 : (uint64_t)-1;
	memcpy(&x, &u, sizeof x);
	return x;
}

/* x rounded to a float no greater (down) or no less (up) than it. */
static float down(double x)
{
	float f = (float)x;
	if (!((double)f > x))
		return f;
	return f == 0 ? -0x1p-149f : step_float(f, false);
}

static float up(double x)
{
	float f = (float)x;
	if (!((double)f < x))
		return f;
	return f == 0 ? 0x1p-149f : step_float(f, true);
}

static void bounds_cb(const struct RTCBoundsFunctionArguments *a)
{
	const struct bvh *t = a->geometryUserPtr;
	struct bbox b = shape_bounds(leaf(t, (int)a->primID)); /* as collect found it */
	double p = t->pad;
	*a->bounds_o = (struct RTCBounds){down(b.lo.x - p), down(b.lo.y - p), down(b.lo.z - p), 0,
	                                  up(b.hi.x + p), up(b.hi.y + p), up(b.hi.z + p), 0};
}

/* A sphere's t over (tmin, tmax), as shape_hit_t finds it: inline for the
 * common sphere without a transform. */
HOT bool sphere_t(const struct object *o, const struct ray *r, double tmin, double tmax, double *t)
{
	if (!o->xf)
		return prim_sphere_t(o->g.sphere.c, o->g.sphere.r, r, tmin, tmax, t);
	return shape_hit_t(o, r, tmin, tmax, t);
}

/* Whether leaf a comes before leaf b in collection order (prims may be in
 * spatial order: rank). */
HOT bool before(const struct bvh *t, int a, int b)
{
	return t->rank ? t->rank[a] < t->rank[b] : a < b;
}

/* The end of the interval primitive id is tested over for query q: a tie
 * with the best so far is looked at, and the leaf first in collection
 * order wins. */
HOT double upper_end(const struct query *q, int id)
{
	return q->found && q->best >= 0 && before(q->b, id, q->best) ? next_up(q->tmax) : q->tmax;
}

/* Query q's best hit so far becomes leaf id's at t, tested over
 * (q->tmin, hi); deferred: a sphere's found by its t alone (traverse fills
 * *h at the end), else *h holds it already. */
HOT void take(struct query *q, int id, double t, double hi, bool deferred)
{
	q->deferred = deferred;
	if (deferred)
		q->best_t = t;
	q->tmax = t;
	q->best = id;
	q->best_hi = hi;
	q->found = true;
}

/* Tests primitive id for query q over (q->tmin, hi): on a better hit,
 * records it (take) and returns true. */
HOT bool consider_to(struct query *q, int id, const struct object *o, double hi)
{
	if ((o->flags & q->skip) || o == q->from)
		return false;
	double t;
	if (o->kind == OBJ_SPHERE) {
		if (!sphere_t(o, q->r, q->tmin, hi, &t))
			return false;
		take(q, id, t, hi, true);
	} else {
		struct hit tmp;
		if (!(q->skip & BVH_UV_UNREAD ? shape_intersect_bare : shape_intersect)(o, q->r, q->tmin, hi, &tmp))
			return false;
		*q->h = tmp;
		take(q, id, tmp.t, hi, false);
	}
	return true;
}

HOT bool consider_obj(struct query *q, int id, const struct object *o)
{
	return consider_to(q, id, o, upper_end(q, id));
}

HOT bool consider(struct query *q, int id)
{
	return consider_obj(q, id, leaf(q->b, id));
}

/* Leaf id's compact record (struct sph) when the callbacks may test it by
 * that alone: a sphere without a transform, and no flag the query skips is
 * set on any leaf; else NULL (its object is read). */
HOT const struct sph *plain(const struct query *q, int id)
{
	const struct sph *s = q->b->sph ? &q->b->sph[id] : NULL;
	return s && !isnan(s->r) && !(q->skip & q->b->flags_any) ? s : NULL;
}

/* Whether query q's ray leaves leaf id outward (q->from): read only when
 * the leaf is hit, so a miss does not read its object. */
HOT bool is_from(const struct query *q, int id)
{
	return q->from && leaf(q->b, id) == q->from;
}

/* consider, the object read only when the leaf is hit where it is a plain
 * sphere (plain): the same test on the same doubles. */
HOT bool consider_id(struct query *q, int id)
{
	const struct sph *s = plain(q, id);
	if (!s)
		return consider(q, id);
	double hi = upper_end(q, id), t;
	if (!prim_sphere_t(v3(s->x, s->y, s->z), s->r, q->r, q->tmin, hi, &t) || is_from(q, id))
		return false;
	take(q, id, t, hi, true);
	return true;
}

/* consider, for leaves tested in index order from the first (brute's
 * loop): no leaf comes before the best so far, so upper_end is tmax. */
HOT bool consider_next(struct query *q, int id)
{
	return consider_to(q, id, q->b->prims[id], q->tmax);
}

/* Tests primitive id against lane i of a ray packet of N rays (N = 1: a
 * single ray) for query q: on a better hit, records it and shrinks the
 * lane's tfar just past it. */
static void lane_hit(const struct query *q, int id, struct RTCRayHitN *rayhit, unsigned N, unsigned i,
                     unsigned geom)
{
	/* RTCRayHitN is a structure of arrays: tfar is float row 8, the hit's
	 * primID and geomID are rows 12 + 5 and 12 + 6 */
	((float *)rayhit)[8 * N + i] = up((q->tmax - q->t0) * (1 + 1e-6));
	((unsigned *)rayhit)[17 * N + i] = (unsigned)id;
	((unsigned *)rayhit)[18 * N + i] = geom;
}

static void test_lane(struct query *q, int id, struct RTCRayHitN *rayhit, unsigned N, unsigned i, unsigned geom)
{
	if (consider_id(q, id))
		lane_hit(q, id, rayhit, N, i, geom);
}

#if defined(__x86_64__) && defined(__GNUC__)
#define LANES16 1
/* Sets the packet's rows, once, when a callback first needs them. */
static void packet_rows(struct packet *P)
{
	for (int i = 0; i < BVH_PACKET; i++) {
		const struct ray *r = P->q[i].r;
		P->ox[i] = r->o.x, P->oy[i] = r->o.y, P->oz[i] = r->o.z;
		P->dx[i] = r->d.x, P->dy[i] = r->d.y, P->dz[i] = r->d.z;
		P->dd[i] = v_dot(r->d, r->d);
	}
	P->rows = true;
}

/* Half h (lanes 8h to 8h + 7) of packet P against sphere o's centre and
 * radius: f = origin - centre and the ray's direction d by rows, a = d·d,
 * fd = f·d, ff = f·f, cc = ff - r², and in keep the lanes prim_sphere_t's
 * first two tests do not turn away (lanes16). */
struct half16 {
	__m512d fx, fy, fz, dx, dy, dz, a, fd, ff, cc;
	__mmask8 keep;
};

__attribute__((target("avx512f"), always_inline)) static inline void sphere_half(const struct packet *P,
                                                                                 const struct sph *o, int h,
                                                                                 struct half16 *s)
{
	const double r2 = o->r * o->r;
	const __m512d zero = _mm512_setzero_pd(), eps = _mm512_set1_pd(1e-12);
	s->fx = _mm512_sub_pd(_mm512_load_pd(P->ox + 8 * h), _mm512_set1_pd(o->x));
	s->fy = _mm512_sub_pd(_mm512_load_pd(P->oy + 8 * h), _mm512_set1_pd(o->y));
	s->fz = _mm512_sub_pd(_mm512_load_pd(P->oz + 8 * h), _mm512_set1_pd(o->z));
	s->dx = _mm512_load_pd(P->dx + 8 * h), s->dy = _mm512_load_pd(P->dy + 8 * h);
	s->dz = _mm512_load_pd(P->dz + 8 * h), s->a = _mm512_load_pd(P->dd + 8 * h);
	s->fd = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(s->fx, s->dx), _mm512_mul_pd(s->fy, s->dy)),
	                      _mm512_mul_pd(s->fz, s->dz));
	s->ff = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(s->fx, s->fx), _mm512_mul_pd(s->fy, s->fy)),
	                      _mm512_mul_pd(s->fz, s->fz));
	s->cc = _mm512_sub_pd(s->ff, _mm512_set1_pd(r2));
	__m512d lhs = _mm512_sub_pd(_mm512_mul_pd(s->a, s->ff), _mm512_mul_pd(s->fd, s->fd));
	__m512d rhs = _mm512_mul_pd(s->a, _mm512_add_pd(_mm512_set1_pd(r2 * (1 + 1e-9)), _mm512_mul_pd(s->ff, eps)));
	__mmask8 away = _mm512_cmp_pd_mask(lhs, rhs, _CMP_GT_OQ);
	__mmask8 behind = P->tmin >= 0 ? (__mmask8)(_mm512_cmp_pd_mask(s->fd, zero, _CMP_GT_OQ) &
	                                            _mm512_cmp_pd_mask(s->cc, zero, _CMP_GT_OQ))
	                               : 0;
	s->keep = (__mmask8)~(away | behind);
}

/* The lanes of a native 16-wide packet that sphere o (no transform) may
 * meet, as a bit mask: those prim_sphere_t does not turn away by its first
 * two tests (a clear miss, a sphere behind a ray from tmin >= 0), the same
 * operations on the same doubles (AVX-512 multiplies and adds, not fused,
 * and ordered comparisons, so a NaN turns no lane away), so the lanes left
 * are the ones it would go on with and every hit is still decided by
 * prim_sphere_t. Sixteen lanes in two halves instead of the scalar test
 * per valid lane: 12-16 % more camera rays a second at 100k spheres
 * (bench/eye/kernel.c). Called only where Embree has native 16-wide
 * packets, which is where the CPU has AVX-512. */
__attribute__((target("avx512f"))) static unsigned lanes16(const struct packet *P, const struct sph *o)
{
	unsigned m = 0;
	for (int h = 0; h < 2; h++) {
		struct half16 s;
		sphere_half(P, o, h, &s);
		m |= (unsigned)s.keep << (8 * h);
	}
	return m;
}

/* prim_sphere_t on all sixteen lanes of a native 16-wide packet at once,
 * for sphere o (no transform, radius > 0): the lanes (a bit mask) whose
 * two roots it would go on to compare with the interval, those roots in
 * t0[i] <= t1[i] (prim_quadratic's), and the lanes lanes16 turns away left
 * out. The same operations on the same doubles in the same order (AVX-512
 * multiplies, adds, divisions and square roots, each rounded as the scalar
 * one: -ffp-contract=off (Makefile) fuses no multiply-add; comparisons
 * that treat a NaN as the scalar ones do), so every root has the scalar
 * bits. The scalar test solved each lane that lanes16 let through in turn,
 * its square roots and divisions one after another: 60 % of intersect_cb's
 * samples on bench/eye/grid.scn (perf). */
__attribute__((target("avx512f"))) static unsigned roots16(const struct packet *P, const struct sph *o,
                                                          double *t0, double *t1)
{
	const double rad = o->r;
	const __m512d zero = _mm512_setzero_pd(), two = _mm512_set1_pd(2), four = _mm512_set1_pd(4);
	const __m512d half = _mm512_set1_pd(-0.5), vrad = _mm512_set1_pd(rad);
	const __m512i sign = _mm512_set1_epi64((long long)0x8000000000000000ull);
	unsigned m = 0;
	for (int h = 0; h < 2; h++) {
		struct half16 s;
		sphere_half(P, o, h, &s); /* lanes16's two rejections */
		__m512d fx = s.fx, fy = s.fy, fz = s.fz, dx = s.dx, dy = s.dy, dz = s.dz, a = s.a, fd = s.fd, cc = s.cc;
		/* !(a > 0), then prim_quadratic's disc < 0 || a == 0 */
		__mmask8 go = (__mmask8)(s.keep & _mm512_cmp_pd_mask(a, zero, _CMP_GT_OQ));
		if (!go)
			continue;
		__m512d b = _mm512_mul_pd(two, fd);
		__m512d k = _mm512_div_pd(_mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(fd), sign)), a);
		__m512d px = _mm512_add_pd(fx, _mm512_mul_pd(dx, k)), py = _mm512_add_pd(fy, _mm512_mul_pd(dy, k));
		__m512d pz = _mm512_add_pd(fz, _mm512_mul_pd(dz, k));
		__m512d lp = _mm512_sqrt_pd(_mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(px, px), _mm512_mul_pd(py, py)),
		                                          _mm512_mul_pd(pz, pz)));
		__m512d disc = _mm512_mul_pd(_mm512_mul_pd(_mm512_mul_pd(four, a), _mm512_add_pd(vrad, lp)),
		                             _mm512_sub_pd(vrad, lp));
		go &= (__mmask8)~_mm512_cmp_pd_mask(disc, zero, _CMP_LT_OQ);
		go &= (__mmask8)~_mm512_cmp_pd_mask(a, zero, _CMP_EQ_OQ);
		if (!go)
			continue;
		/* q = -0.5·(b + copysign(√disc, b)) */
		__m512i bs = _mm512_and_si512(_mm512_castpd_si512(b), sign);
		__m512i sq = _mm512_andnot_si512(sign, _mm512_castpd_si512(_mm512_sqrt_pd(disc)));
		__m512d q = _mm512_mul_pd(half, _mm512_add_pd(b, _mm512_castsi512_pd(_mm512_or_si512(sq, bs))));
		__m512d r0 = _mm512_div_pd(q, a);
		__m512d r1 = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(q, zero, _CMP_NEQ_UQ), r0, _mm512_div_pd(cc, q));
		/* d_min(r0, r1) = r0 < r1 ? r0 : r1; d_max = r0 > r1 ? r0 : r1 */
		_mm512_storeu_pd(t0 + 8 * h, _mm512_mask_blend_pd(_mm512_cmp_pd_mask(r0, r1, _CMP_LT_OQ), r1, r0));
		_mm512_storeu_pd(t1 + 8 * h, _mm512_mask_blend_pd(_mm512_cmp_pd_mask(r0, r1, _CMP_GT_OQ), r1, r0));
		m |= (unsigned)go << (8 * h);
	}
	return m;
}
#endif

/* The lanes of packet P (N rays; NULL: a single ray) that leaf o may
 * meet: lanes16's mask for a sphere without a transform in a native
 * 16-wide packet, else every lane. */
static inline unsigned may_meet(struct packet *P, unsigned N, const struct sph *o)
{
#ifdef LANES16
	if (native16 && P && N == BVH_PACKET && !isnan(o->r)) {
		if (!P->rows)
			packet_rows(P);
		return lanes16(P, o);
	}
#else
	(void)P, (void)N, (void)o;
#endif
	return ~0u;
}

static void intersect_cb(const struct RTCIntersectFunctionNArguments *a)
{
	struct query *q = (struct query *)a->context;
	struct packet *P = q->lanes == 1 ? NULL : (struct packet *)a->context;
	struct query *lane = P ? &P->q[P->base] : q; /* lane i's query: lane[i], or q alone */
	const struct bvh *b = lane->b;
	const struct sph *o = &b->sph[a->primID]; /* looked up once for every lane */
#ifdef LANES16
	if (native16 && P && a->N == BVH_PACKET && o->r > 0) { /* (a NaN r: not a plain sphere) */
		_Alignas(64) double t0[BVH_PACKET], t1[BVH_PACKET];
		if (!P->rows)
			packet_rows(P);
		unsigned m = roots16(P, o, t0, t1);
		for (; m; m &= m - 1) { /* consider_id with the roots in hand */
			unsigned i = (unsigned)__builtin_ctz(m);
			struct query *qi = &lane[i];
			if (!a->valid[i] || ((qi->skip & b->flags_any) && (leaf(b, (int)a->primID)->flags & qi->skip)))
				continue;
			double hi = upper_end(qi, (int)a->primID), t;
			if (t0[i] > qi->tmin && t0[i] < hi)
				t = t0[i];
			else if (t1[i] > qi->tmin && t1[i] < hi)
				t = t1[i];
			else
				continue;
			if (is_from(qi, (int)a->primID))
				continue;
			take(qi, (int)a->primID, t, hi, true);
			lane_hit(qi, (int)a->primID, a->rayhit, a->N, i, a->geomID);
		}
		return;
	}
#endif
	unsigned m = may_meet(P, a->N, o);
	for (unsigned i = 0; i < a->N; i++)
		if (a->valid[i] && (m >> (i & 31) & 1))
			test_lane(P ? &lane[i] : q, (int)a->primID, a->rayhit, a->N, i, a->geomID);
}

/* Whether primitive id blocks query q's ray over its interval. */
static bool blocks(const struct query *q, unsigned id)
{
	const struct sph *s = plain(q, (int)id);
	double t;
	if (s)
		return prim_sphere_t(v3(s->x, s->y, s->z), s->r, q->r, q->tmin, q->tmax, &t) && !is_from(q, (int)id);
	const struct object *o = leaf(q->b, (int)id);
	if ((o->flags & q->skip) || o == q->from)
		return false;
	return o->kind == OBJ_SPHERE ? sphere_t(o, q->r, q->tmin, q->tmax, &t)
	                             : shape_occluded(o, q->r, q->tmin, q->tmax);
}

/* A blocked lane's tfar (RTCRayN's float row 8) becomes -inf: Embree drops
 * it from the walk. */
static void occluded_cb(const struct RTCOccludedFunctionNArguments *a)
{
	struct query *q = (struct query *)a->context;
	struct packet *P = q->lanes == 1 ? NULL : (struct packet *)a->context;
	unsigned m = P ? may_meet(P, a->N, &P->q[0].b->sph[a->primID]) : ~0u; /* lanes that may be blocked */
	for (unsigned i = 0; i < a->N; i++) {
		struct query *qi = P ? &P->q[P->base + (int)i] : q;
		if (a->valid[i] && (m >> (i & 31) & 1) && !qi->found && blocks(qi, a->primID)) {
			qi->found = true;
			((float *)a->ray)[8 * a->N + i] = -INFINITY;
		}
	}
}

/* ==== building =========================================================== */

/* The low 10 bits of v spread out to every third bit: one axis of a
 * Morton code. */
static uint64_t spread3(uint64_t v)
{
	v &= 0x3ff;
	v = (v | v << 16) & 0x30000ffull;
	v = (v | v << 8) & 0x300f00full;
	v = (v | v << 4) & 0x30c30c3ull;
	v = (v | v << 2) & 0x9249249ull;
	return v;
}

/* x in [lo, lo + ext] as a 10-bit grid coordinate (0 for NaN and a flat
 * axis). */
static uint64_t grid10(double x, double lo, double ext)
{
	double f = ext > 0 ? (x - lo) / ext : 0;
	return f > 0 ? f < 1 ? (uint64_t)(f * 1024.0) : 1023 : 0;
}

#define RADIX_BITS 10 /* a Morton code's bits per axis, and a radix sort pass's */

/* Numbers the leaves in the Morton order of their boxes' centres (docs/
 * design.md §5), on a grid of 2^10 cells an axis: rank. Embree is given
 * the leaves by these ids. A stable sort (leaves in one cell keep their
 * collection order), and ties between hits still go by collection order
 * (upper_end), so every hit is the one collection order gives. In
 * collection order a random cloud's leaves lie scattered over memory, and
 * the callbacks' reads of a hierarchy node's leaves miss the cache one by
 * one; in this order they lie together (plain_fill). Keys hold the code
 * above the collection index, and a radix sort passes over the code's
 * digits alone. */
static void spatial_order(struct bvh *t)
{
	long n = t->nprims;
	uint64_t *a = mem_alloc_huge(sizeof *a * (size_t)n), *b = mem_alloc_huge(sizeof *b * (size_t)n);
	struct vec3 lo = t->bounds.lo, ext = v_sub(t->bounds.hi, t->bounds.lo);
	for (long i = 0; i < n; i++) {
		struct vec3 c = bbox_centre(shape_bounds(t->prims[i]));
		uint64_t code = spread3(grid10(c.x, lo.x, ext.x)) | spread3(grid10(c.y, lo.y, ext.y)) << 1 |
		                spread3(grid10(c.z, lo.z, ext.z)) << 2;
		a[i] = code << 32 | (uint64_t)i;
	}
	const unsigned digit = (1u << RADIX_BITS) - 1;
	for (int shift = 32; shift < 32 + 3 * RADIX_BITS; shift += RADIX_BITS) { /* lowest digit first */
		long count[(1 << RADIX_BITS) + 1] = {0};
		for (long i = 0; i < n; i++)
			count[(a[i] >> shift & digit) + 1]++;
		if (count[(a[0] >> shift & digit) + 1] == n)
			continue; /* one digit for all: the order stays */
		for (unsigned d = 0; d < digit + 1; d++)
			count[d + 1] += count[d];
		for (long i = 0; i < n; i++)
			b[count[a[i] >> shift & digit]++] = a[i];
		uint64_t *x = a;
		a = b, b = x;
	}
	free(b);
	t->rank = mem_alloc(sizeof *t->rank * (size_t)n);
	for (long k = 0; k < n; k++)
		t->rank[k] = (int32_t)(a[k] & 0xffffffffu);
	free(a);
}

/* sph and flags_any, once Embree has built its hierarchy (whose build
 * memory is then given back: a million spheres' 32 MB do not add to the
 * peak). */
static void plain_fill(struct bvh *t)
{
	t->sph = mem_alloc_huge(sizeof *t->sph * (size_t)t->nprims);
	t->flags_any = 0;
	for (int k = 0; k < t->nprims; k++) {
		const struct object *o = leaf(t, k);
		t->flags_any |= o->flags;
		t->sph[k] = o->kind == OBJ_SPHERE && !o->xf
		                ? (struct sph){o->g.sphere.c.x, o->g.sphere.c.y, o->g.sphere.c.z, o->g.sphere.r}
		                : (struct sph){0, 0, 0, NAN};
	}
}

/* Whether boxes a and b lie more than gap apart along some axis. */
static bool apart(struct bbox a, struct bbox b, double gap)
{
	return a.hi.x + gap < b.lo.x || b.hi.x + gap < a.lo.x || a.hi.y + gap < b.lo.y || b.hi.y + gap < a.lo.y ||
	       a.hi.z + gap < b.lo.z || b.hi.z + gap < a.lo.z;
}

/* t->lbox and t->alone from the leaves' grown boxes bx (bvh_intersect_in). */
static void set_alone(struct bvh *t, const struct bbox *bx)
{
	for (int i = 0; i < t->nprims; i++) {
		t->lbox[i] = bx[i];
		t->alone[i] = true;
		for (int j = 0; j < t->nprims && t->alone[i]; j++)
			t->alone[i] = j == i || apart(bx[i], bx[j], t->pad);
	}
}

struct bvh *bvh_build(struct object **objs, int n)
{
	struct bvh *t = mem_calloc(1, sizeof *t);
	struct builder B = {t, objs, 0, 0, 0};
	t->bounds = bbox_empty();
	t->prims = (const struct object **)objs;
	for (int i = 0; i < n; i++, B.next++)
		collect(&B, objs[i]);
	t->uplane = mem_calloc((size_t)(t->nunbound ? t->nunbound : 1), sizeof *t->uplane);
	for (int i = 0; i < t->nunbound; i++)
		if (t->unbound[i]->kind == OBJ_PLANE)
			pl_prep(t->unbound[i], &t->uplane[i]);
	if (t->nprims == 0)
		return t;
	/* rounding a ray that starts inside (or on) the box to float moves it
	 * by a few ulps of the box's magnitude and diagonal */
	struct vec3 m = v_max(v_neg(t->bounds.lo), t->bounds.hi);
	double mag = fmax(fmax(m.x, m.y), m.z) + v_len(v_sub(t->bounds.hi, t->bounds.lo));
	t->pad = ldexp(mag, -18) + 1e-30;
	t->padded = (struct bbox){v_sub(t->bounds.lo, v3(t->pad, t->pad, t->pad)),
	                          v_add(t->bounds.hi, v3(t->pad, t->pad, t->pad))};
	t->brute = t->nprims <= BRUTE_MAX;
	for (int i = 0; i < t->nprims && t->brute; i++)
		t->brute = cheap_kind(t->prims[i]);
	if (!t->brute && t->nprims <= LEAFBOX_MAX) {
		struct bbox bx[LEAFBOX_MAX];
		for (int i = 0; i < t->nprims; i++) {
			struct bbox b = shape_bounds(t->prims[i]); /* as collect found it */
			bx[i] = (struct bbox){v_sub(b.lo, v3(t->pad, t->pad, t->pad)),
			                      v_add(b.hi, v3(t->pad, t->pad, t->pad))};
		}
		t->box = mem_alloc(sizeof *t->box);
		leafbox_set(t->box, t->nprims, bx);
		set_alone(t, bx);
		t->brute = true;
	}
	if (t->brute)
		return t; /* tested without Embree (brute): no Embree scene */
	pthread_once(&device_once, make_device);
	if (!device)
		return t; /* no Embree: every leaf is tested (see traverse) */
	spatial_order(t);
	t->scene = rtcNewScene(device);
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
	plain_fill(t);
	return t;
}

void bvh_free(struct bvh *b)
{
	if (!b)
		return;
	if (b->scene)
		rtcReleaseScene(b->scene);
	if (b->own_prims)
		free(b->prims);
	free(b->unbound), free(b->uplane), free(b->box), free(b->rank), free(b->sph);
	free(b);
}

int bvh_count(const struct bvh *b, int *unbounded)
{
	if (unbounded)
		*unbounded = b->nunbound;
	return b->nprims;
}

bool bvh_walks(const struct bvh *b)
{
	return b->scene != NULL;
}

struct bbox bvh_bounds(const struct bvh *b)
{
	return b->bounds;
}

/* ==== traversal ========================================================== */

/* Narrows (*tmin, *tmax) to the slab lo..hi of one axis (ray origin o,
 * direction d along it): false when it becomes empty. */
static inline bool slab(double o, double d, double lo, double hi, double *tmin, double *tmax)
{
	double inv = 1 / d; /* ±inf for 0: the same bounds */
	double t0 = (lo - o) * inv, t1 = (hi - o) * inv;
	if (t0 > t1) {
		double s = t0;
		t0 = t1;
		t1 = s;
	}
	if (t0 > *tmin) /* NaN (0/0) leaves the bound as it is */
		*tmin = t0;
	if (t1 < *tmax)
		*tmax = t1;
	return !(*tmin > *tmax);
}

/* Where r enters box b over (tmin, tmax): false when it misses. */
HOT bool enter(struct bbox b, const struct ray *r, double tmin, double tmax, double *t)
{
	if (!slab(r->o.x, r->d.x, b.lo.x, b.hi.x, &tmin, &tmax) ||
	    !slab(r->o.y, r->d.y, b.lo.y, b.hi.y, &tmin, &tmax) ||
	    !slab(r->o.z, r->d.z, b.lo.z, b.hi.z, &tmin, &tmax))
		return false;
	*t = tmin;
	return true;
}

/* The float ray of query q, written as lane i of a packet of N rays (N = 1:
 * an RTCRayHit or RTCRay): the nine rows of an RTCRay (org xyz, tnear, dir
 * xyz, time, tfar), then mask, id, flags and the hit's geomID (words 9,
 * 10, 11 and 12 + 6, written for an RTCRayHit only: hit set). It starts
 * where q's ray enters the padded box of everything bounded, and its
 * interval is rounded outward. False (and no ray) when the ray misses
 * that box within q's interval. */
HOT bool float_ray_from(struct query *q, float *f, unsigned N, unsigned i, bool hit, double te);

static inline bool float_ray(struct query *q, float *f, unsigned N, unsigned i, bool hit)
{
	const struct bbox *bx = &q->b->padded;
	const struct ray *r = q->r;
	double te = 0; /* a ray starting inside the box enters it at t <= 0 */
	bool inside = r->o.x >= bx->lo.x && r->o.x <= bx->hi.x && r->o.y >= bx->lo.y && r->o.y <= bx->hi.y &&
	              r->o.z >= bx->lo.z && r->o.z <= bx->hi.z;
	if (!inside && !enter(*bx, r, -INFINITY, INFINITY, &te))
		return false;
	return float_ray_from(q, f, N, i, hit, te);
}

/* float_ray, where q's ray enters the padded box at te (float_ray's te). */
HOT bool float_ray_from(struct query *q, float *f, unsigned N, unsigned i, bool hit, double te)
{
	const struct ray *r = q->r;
	if (!(te < q->tmax))
		return false;
	double t0 = q->t0 = te > 0 ? te : 0; /* the float ray starts here along r */
	struct vec3 o = v_add(r->o, v_scale(r->d, t0));
	double lo = q->tmin - t0;
	f[0 * N + i] = (float)o.x, f[1 * N + i] = (float)o.y, f[2 * N + i] = (float)o.z;
	f[3 * N + i] = lo > 0 ? down(lo * (1 - 1e-6)) : 0;
	f[4 * N + i] = (float)r->d.x, f[5 * N + i] = (float)r->d.y, f[6 * N + i] = (float)r->d.z;
	f[7 * N + i] = 0;
	f[8 * N + i] = isinf(q->tmax) ? INFINITY : up((q->tmax - t0) * (1 + 1e-6));
	unsigned *u = (unsigned *)f;
	u[9 * N + i] = ~0u;
	u[10 * N + i] = 0;
	u[11 * N + i] = 0;
	if (hit)
		u[18 * N + i] = RTC_INVALID_GEOMETRY_ID;
	return true;
}

/* The bounded leaves through Embree; q holds the interval and the result. */
static void walk(struct query *q, bool any)
{
	const struct bvh *b = q->b;
	struct RTCRayHit rh;
	if (!float_ray(q, (float *)&rh, 1, 0, !any))
		return;
	rtcInitIntersectContext(&q->rc);
	q->lanes = 1;
	if (any) {
		rtcOccluded1(b->scene, &q->rc, &rh.ray);
		q->found = rh.ray.tfar < 0;
	} else {
		rtcIntersect1(b->scene, &q->rc, &rh);
	}
}

/* The bounded leaves of a scene of at most LEAFBOX_MAX for query q, by their
 * boxes first. The nearest hit tests the leaves whose boxes the ray meets in
 * the order it enters them, and stops at a box entered beyond the best hit
 * so far (a costly leaf behind a near one is never solved); the hit is that
 * of the loop in order all the same (consider). */
HOT void boxed(struct query *q, bool any)
{
	double at[LEAFBOX_MAX];
	int id[LEAFBOX_MAX], n = 0;
	unsigned m = leafbox_hits(q->b->box, q->r, q->tmin, any ? q->tmax : next_up(q->tmax), at);
	if (any) { /* the leaves met, by index (the lowest set bit first) */
		for (; m; m &= m - 1)
			if (blocks(q, (unsigned)__builtin_ctz(m))) {
				q->found = true;
				return;
			}
		return;
	}
	for (; m; m &= m - 1)
		id[n++] = __builtin_ctz(m);
	for (int j = 1; j < n; j++) { /* by entry (insertion: at most 8) */
		int k = j, i = id[j];
		for (; k > 0 && at[id[k - 1]] > at[i]; k--)
			id[k] = id[k - 1];
		id[k] = i;
	}
	for (int k = 0; k < n; k++) {
		if (at[id[k]] > next_up(q->tmax)) /* a tie is looked at */
			break; /* this box and the rest lie beyond the best hit */
		consider(q, id[k]);
	}
}

/* Every bounded leaf in order, as the callbacks test them: without a
 * device (Embree failed to start), and for a scene of at most BRUTE_MAX
 * cheap leaves, where setting up Embree's float ray and walk costs more
 * than testing them all (a sphere's t is ~80 instructions; Embree's query
 * ~500); by their boxes (boxed) for other scenes of at most LEAFBOX_MAX.
 * The hit is the same either way (see the top of this file). */
HOT void brute(struct query *q, bool any)
{
	if (q->b->box) {
		boxed(q, any);
		return;
	}
	for (int i = 0; i < q->b->nprims && !(any && q->found); i++) {
		if (!any) {
			consider_next(q, i);
			continue;
		}
		const struct object *o = q->b->prims[i];
		if (!(o->flags & q->skip) && o != q->from)
			q->found = shape_occluded(o, q->r, q->tmin, q->tmax);
	}
}

/* The unbounded leaves, tested on every ray first; true when, with any
 * set, one of them is hit. */
HOT bool unbounded(struct query *q, bool any)
{
	struct hit tmp;
	for (int i = 0; i < q->b->nunbound; i++) {
		const struct object *o = q->b->unbound[i];
		if ((o->flags & q->skip) || o == q->from)
			continue;
		double t;
		if (o->kind == OBJ_PLANE) { /* the t alone; finish fills *h */
			const struct pl_prep *pp = &q->b->uplane[i]; /* inline without a transform */
			if (!(o->xf ? shape_plane_hit_t(o, pp, q->r, q->tmin, q->tmax, &t)
			            : pp->ok && prim_plane_root(pp->n, pp->d, q->r, q->tmin, q->tmax, &t)))
				continue;
			if (any) /* as shape_occluded, without the plane's frame */
				return q->found = true;
			q->ubest = i, q->tmax = t, q->found = true;
		} else if (any && shape_occluded(o, q->r, q->tmin, q->tmax)) {
			return q->found = true;
		} else if (!any && shape_intersect(o, q->r, q->tmin, q->tmax, &tmp)) {
			*q->h = tmp, q->tmax = tmp.t, q->found = true, q->ubest = -1;
		}
	}
	return false;
}

/* The hit of a sphere that won with its t alone: the same test over the
 * same interval, in full. */
HOT void finish_hit(struct query *q);
static inline void finish(struct query *q)
{
	if (q->deferred || (q->best < 0 && q->ubest >= 0))
		finish_hit(q);
}

HOT void finish_hit(struct query *q)
{
	if (q->deferred)
		shape_hit_at(leaf(q->b, q->best), q->r, q->tmin, q->best_hi, q->best_t, q->uv, q->h);
	else if (q->best < 0 && q->ubest >= 0) /* an unbounded winner found by its t, still q->tmax; its
	                                          (u,v) come with its point (pl_prep_hit): kept, as a light
	                                          ray's deposit needs them */
		shape_plane_hit_at(q->b->unbound[q->ubest], &q->b->uplane[q->ubest], q->r, q->tmax, true, q->h);
}

/* Sets *q up as a query over (tmin, tmax) for ray r, its result into *h:
 * skip's object flags, and BVH_NO_UV as the uv flag. Embree's context is
 * left for walk to set (rtcInitIntersectContext): zeroing it on every query
 * cost a fifth of a query that never reaches Embree. */
static void new_query(struct query *q, const struct bvh *b, const struct ray *r, double tmin, double tmax,
                      unsigned skip, struct hit *h)
{
	q->lanes = 1, q->b = b, q->r = r, q->tmin = tmin, q->tmax = tmax, q->t0 = 0;
	q->skip = skip & ~BVH_NO_UV, q->h = h, q->uv = !(skip & BVH_NO_UV);
	q->best = -1, q->best_t = 0, q->ubest = -1, q->best_hi = 0;
	q->found = q->deferred = false;
	q->from = NULL;
}

/* finish(q), unless full (when given) says the winner found by its t
 * alone needs no more than its object and t (bvh_intersect_lazy). */
HOT void finish_if(struct query *q, bool (*full)(const void *ctx, const struct object *o),
               const void *ctx)
{
	const struct object *o = q->deferred                       ? leaf(q->b, q->best)
	                         : q->best < 0 && q->ubest >= 0 ? q->b->unbound[q->ubest]
	                                                         : NULL;
	if (!o || !full || full(ctx, o)) {
		finish(q);
		return;
	}
	q->h->obj = o;
	q->h->t = q->deferred ? q->best_t : q->tmax;
	q->h->u = q->h->v = NAN;
}

/* The query shared by both kinds: with any set, stops at the first hit. A
 * ray that leaves convex leaf from outward (NULL: none) does not test it
 * (bvh.h). */
HOT bool traverse(const struct bvh *b, const struct ray *r, double tmin, double tmax, unsigned skip, bool any,
                  const struct object *from, struct hit *h, bool (*full)(const void *ctx, const struct object *o),
                  const void *ctx)
{
	struct query q;
	new_query(&q, b, r, tmin, tmax, skip, h);
	q.from = from;
	if (b->nunbound && unbounded(&q, any))
		return q.found;
	if (b->nprims > 0 && b->scene)
		walk(&q, any);
	else if (b->nprims > 0)
		brute(&q, any);
	finish_if(&q, full, ctx);
	return q.found;
}

/* Lane i of a packet gets query q's float ray (into rh, or into rh8
 * without native 16-wide packets); valid[i] says whether it has one (false:
 * it misses the scene's box). With te (packet_enter), the ray enters the
 * box at te[i] if bit i of in is set, else misses it. */
HOT bool packet_lane(struct query *q, int i, int *valid, struct RTCRayHit16 *rh, struct RTCRayHit8 *rh8,
                     const double *te, unsigned in)
{
	bool ok = !te   ? native16 ? float_ray(q, (float *)rh, BVH_PACKET, (unsigned)i, true)
	                           : float_ray(q, (float *)&rh8[i / 8], 8, (unsigned)i % 8, true)
	          : in >> i & 1 ? float_ray_from(q, (float *)rh, BVH_PACKET, (unsigned)i, true, te[i])
	                        : false;
	valid[i] = ok ? -1 : 0;
	return ok;
}

#ifdef LANES16
/* float_ray's entry into box b of the n rays r (n <= 16) at once, as
 * float_ray finds them one by one: te[i], and the lanes whose ray
 * starts inside or enters the box as a bit mask. The same divisions,
 * subtractions, multiplies and comparisons on the same doubles (enter's
 * early exit aside: its bounds only narrow, so a lane once empty stays
 * empty), with AVX-512: the scalar slabs, one division after another, were
 * two fifths of bvh_intersect_packet's own samples (perf, grid 100k). */
__attribute__((target("avx512f"))) static unsigned enter16(const struct bbox *b, int n, const struct ray *r,
                                                          double *te)
{
	_Alignas(64) double ox[BVH_PACKET], oy[BVH_PACKET], oz[BVH_PACKET];
	_Alignas(64) double dx[BVH_PACKET], dy[BVH_PACKET], dz[BVH_PACKET];
	for (int i = 0; i < BVH_PACKET; i++) {
		const struct ray *ri = &r[i < n ? i : 0];
		ox[i] = ri->o.x, oy[i] = ri->o.y, oz[i] = ri->o.z;
		dx[i] = ri->d.x, dy[i] = ri->d.y, dz[i] = ri->d.z;
	}
	const double *o3[3] = {ox, oy, oz}, *d3[3] = {dx, dy, dz};
	const double lo3[3] = {b->lo.x, b->lo.y, b->lo.z}, hi3[3] = {b->hi.x, b->hi.y, b->hi.z};
	const __m512d one = _mm512_set1_pd(1), zero = _mm512_setzero_pd();
	unsigned m = 0;
	for (int h = 0; h < 2; h++) {
		__mmask8 inside = 0xff;
		__m512d tmin = _mm512_set1_pd(-INFINITY), tmax = _mm512_set1_pd(INFINITY);
		for (int k = 0; k < 3; k++) {
			__m512d o = _mm512_load_pd(o3[k] + 8 * h), d = _mm512_load_pd(d3[k] + 8 * h);
			__m512d lo = _mm512_set1_pd(lo3[k]), hi = _mm512_set1_pd(hi3[k]);
			inside &= _mm512_cmp_pd_mask(o, lo, _CMP_GE_OQ) & _mm512_cmp_pd_mask(o, hi, _CMP_LE_OQ);
			__m512d inv = _mm512_div_pd(one, d);
			__m512d t0 = _mm512_mul_pd(_mm512_sub_pd(lo, o), inv), t1 = _mm512_mul_pd(_mm512_sub_pd(hi, o), inv);
			__mmask8 sw = _mm512_cmp_pd_mask(t0, t1, _CMP_GT_OQ);
			__m512d near = _mm512_mask_blend_pd(sw, t0, t1), far = _mm512_mask_blend_pd(sw, t1, t0);
			tmin = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(near, tmin, _CMP_GT_OQ), tmin, near);
			tmax = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(far, tmax, _CMP_LT_OQ), tmax, far);
		}
		__mmask8 meets = (__mmask8)~_mm512_cmp_pd_mask(tmin, tmax, _CMP_GT_OQ);
		_mm512_store_pd(te + 8 * h, _mm512_mask_blend_pd(inside, tmin, zero));
		m |= (unsigned)(uint8_t)(inside | meets) << (8 * h);
	}
	return m;
}
#endif

/* The entry of every ray of a packet into the padded box at once (enter16)
 * where Embree takes native 16-wide packets: te is then set and *in holds
 * the lanes that meet it; NULL otherwise (float_ray finds each). */
static const double *packet_enter(const struct bvh *b, int n, const struct ray *r, double *te, unsigned *in)
{
#ifdef LANES16
	if (native16 && b->scene && b->nprims > 0) {
		*in = enter16(&b->padded, n, r, te);
		return te;
	}
#else
	(void)b, (void)n, (void)r, (void)in;
#endif
	return NULL;
}

/* Embree's context for a packet of camera or shadow rays (coherent). */
static void packet_start(struct packet *Q, double tmin)
{
	Q->rows = false;
	Q->tmin = tmin;
	rtcInitIntersectContext(&Q->rc);
	Q->rc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
	Q->lanes = BVH_PACKET;
	Q->base = 0;
}

#ifdef LANES16
/* finish_hit for the lanes of packet Q (bit i of m: lane i) whose winner
 * is a sphere without a transform found by its t alone, without (u,v):
 * shape_hit_at's point and normal (prim_sphere_at, then to_world's
 * v_norm) on all sixteen lanes at once, the same operations on the same
 * doubles; the lanes whose point lies at the centre (no normal) are left
 * to finish_hit, as are the flags and the record, per lane. Their two
 * square roots and divisions one lane after another were most of
 * shape_hit_at's samples (perf, grid 100k). Returns the lanes done. */
__attribute__((target("avx512f"))) static unsigned hits16(struct packet *Q, unsigned m)
{
	_Alignas(64) double t[BVH_PACKET], cx[BVH_PACKET], cy[BVH_PACKET], cz[BVH_PACKET], rad[BVH_PACKET];
	_Alignas(64) double out[6][BVH_PACKET]; /* p, then n */
	if (!Q->rows)
		packet_rows(Q);
	for (int i = 0; i < BVH_PACKET; i++) {
		const struct object *o = leaf(Q->q[i].b, Q->q[i].best < 0 ? 0 : Q->q[i].best);
		bool on = m >> i & 1;
		t[i] = on ? Q->q[i].best_t : 0;
		cx[i] = on ? o->g.sphere.c.x : 0, cy[i] = on ? o->g.sphere.c.y : 0, cz[i] = on ? o->g.sphere.c.z : 0;
		rad[i] = on ? o->g.sphere.r : 0;
	}
	const __m512d one = _mm512_set1_pd(1), zero = _mm512_setzero_pd();
	unsigned ok = 0;
	for (int h = 0; h < 2; h++) {
		__m512d tt = _mm512_load_pd(t + 8 * h);
		__m512d ccx = _mm512_load_pd(cx + 8 * h), ccy = _mm512_load_pd(cy + 8 * h);
		__m512d ccz = _mm512_load_pd(cz + 8 * h), rr = _mm512_load_pd(rad + 8 * h);
		/* prim_sphere_at: q = ray_at(r, t) - c, reprojected */
		__m512d qx = _mm512_sub_pd(_mm512_add_pd(_mm512_load_pd(Q->ox + 8 * h),
		                                         _mm512_mul_pd(_mm512_load_pd(Q->dx + 8 * h), tt)), ccx);
		__m512d qy = _mm512_sub_pd(_mm512_add_pd(_mm512_load_pd(Q->oy + 8 * h),
		                                         _mm512_mul_pd(_mm512_load_pd(Q->dy + 8 * h), tt)), ccy);
		__m512d qz = _mm512_sub_pd(_mm512_add_pd(_mm512_load_pd(Q->oz + 8 * h),
		                                         _mm512_mul_pd(_mm512_load_pd(Q->dz + 8 * h), tt)), ccz);
		__m512d l = _mm512_sqrt_pd(_mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(qx, qx), _mm512_mul_pd(qy, qy)),
		                                         _mm512_mul_pd(qz, qz)));
		__mmask8 good = _mm512_cmp_pd_mask(l, zero, _CMP_GT_OQ);
		__m512d k = _mm512_div_pd(one, l);
		qx = _mm512_mul_pd(qx, k), qy = _mm512_mul_pd(qy, k), qz = _mm512_mul_pd(qz, k);
		_mm512_store_pd(out[0] + 8 * h, _mm512_add_pd(ccx, _mm512_mul_pd(qx, rr)));
		_mm512_store_pd(out[1] + 8 * h, _mm512_add_pd(ccy, _mm512_mul_pd(qy, rr)));
		_mm512_store_pd(out[2] + 8 * h, _mm512_add_pd(ccz, _mm512_mul_pd(qz, rr)));
		/* to_world: n = v_norm(q) */
		__m512d l2 = _mm512_sqrt_pd(_mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(qx, qx), _mm512_mul_pd(qy, qy)),
		                                          _mm512_mul_pd(qz, qz)));
		__mmask8 pos = _mm512_cmp_pd_mask(l2, zero, _CMP_GT_OQ);
		__m512d k2 = _mm512_div_pd(one, l2);
		_mm512_store_pd(out[3] + 8 * h, _mm512_mask_blend_pd(pos, qx, _mm512_mul_pd(qx, k2)));
		_mm512_store_pd(out[4] + 8 * h, _mm512_mask_blend_pd(pos, qy, _mm512_mul_pd(qy, k2)));
		_mm512_store_pd(out[5] + 8 * h, _mm512_mask_blend_pd(pos, qz, _mm512_mul_pd(qz, k2)));
		ok |= (unsigned)(uint8_t)good << (8 * h);
	}
	ok &= m;
	for (unsigned mm = ok; mm; mm &= mm - 1) {
		int i = __builtin_ctz(mm);
		struct query *q = &Q->q[i];
		const struct object *o = leaf(q->b, q->best);
		struct hit *hh = q->h;
		struct vec3 n = v3(out[3][i], out[4][i], out[5][i]);
		if (o->flags & OF_INVERSE)
			n = v_neg(n);
		hh->t = t[i];
		hh->p = v3(out[0][i], out[1][i], out[2][i]);
		hh->n = n;
		hh->obj = o;
		hh->entering = v_dot(q->r->d, n) < 0;
		hh->u = hh->v = NAN;
		hh->dpdu = hh->dpdv = v3(0, 0, 0);
		q->deferred = false;
	}
	return ok;
}
#endif

/* The packet's hits, completed (finish), and whether each lane hit. */
static void done(struct packet *Q, int n, bool *found)
{
#ifdef LANES16
	if (native16) { /* the plain spheres' hits at once (hits16) */
		unsigned m = 0;
		for (int i = 0; i < n; i++) {
			const struct query *q = &Q->q[i];
			if (q->deferred && !q->uv && !leaf(q->b, q->best)->xf)
				m |= 1u << i;
		}
		if (m)
			hits16(Q, m);
	}
#endif
	for (int i = 0; i < n; i++) {
		finish(&Q->q[i]);
		found[i] = Q->q[i].found;
	}
}

void bvh_intersect_packet(const struct bvh *b, int n, const struct ray *r, double tmin, double tmax,
                          unsigned skip, struct hit *h, bool *found)
{
	struct packet Q;
	Q.rows = false; /* done may read them (hits16) when no lane reaches Embree */
	_Alignas(64) struct RTCRayHit16 rh;
	_Alignas(64) struct RTCRayHit8 rh8[2];
	_Alignas(64) int valid[BVH_PACKET];
	_Alignas(64) double te[BVH_PACKET];
	unsigned in = 0;
	const double *ten = packet_enter(b, n, r, te, &in);
	bool any = false;
	for (int i = 0; i < BVH_PACKET; i++) {
		struct query *q = &Q.q[i];
		new_query(q, b, &r[i < n ? i : 0], tmin, tmax, skip, &h[i < n ? i : 0]);
		valid[i] = 0;
		if (i >= n)
			continue;
		if (b->nunbound)
			unbounded(q, false);
		if (b->nprims == 0)
			continue;
		if (!b->scene) {
			brute(q, false);
			continue;
		}
		any |= packet_lane(q, i, valid, &rh, rh8, ten, in);
	}
	if (!any) {
		done(&Q, n, found);
		return;
	}
	packet_start(&Q, tmin);
	if (native16) {
		rtcIntersect16(valid, b->scene, &Q.rc, &rh);
	} else {
		rtcIntersect8(valid, b->scene, &Q.rc, &rh8[0]);
		Q.base = 8;
		rtcIntersect8(valid + 8, b->scene, &Q.rc, &rh8[1]);
	}
	done(&Q, n, found);
}

void bvh_occluded_packet(const struct bvh *b, int n, const struct ray *r, const double *tmax,
                         unsigned skip, bool *blocked)
{
	struct packet Q;
	_Alignas(64) struct RTCRayHit16 rh;
	_Alignas(64) struct RTCRayHit8 rh8[2];
	_Alignas(64) int valid[BVH_PACKET];
	_Alignas(64) double te[BVH_PACKET];
	unsigned in = 0;
	const double *ten = packet_enter(b, n, r, te, &in);
	bool any = false;
	for (int i = 0; i < BVH_PACKET; i++) {
		struct query *q = &Q.q[i];
		new_query(q, b, &r[i < n ? i : 0], 0, i < n ? tmax[i] : 0, skip | BVH_NO_UV, NULL);
		valid[i] = 0;
		if (i >= n || unbounded(q, true) || b->nprims == 0)
			continue;
		if (!b->scene) {
			brute(q, true);
			continue;
		}
		any |= packet_lane(q, i, valid, &rh, rh8, ten, in);
	}
	if (any) {
		packet_start(&Q, 0);
		if (native16) {
			rtcOccluded16(valid, b->scene, &Q.rc, &rh.ray);
		} else {
			rtcOccluded8(valid, b->scene, &Q.rc, &rh8[0].ray);
			Q.base = 8;
			rtcOccluded8(valid + 8, b->scene, &Q.rc, &rh8[1].ray);
		}
	}
	for (int i = 0; i < n; i++)
		blocked[i] = Q.q[i].found;
}

bool bvh_intersect_skip(const struct bvh *b, const struct ray *r, double tmin, double tmax,
                        unsigned skip, struct hit *h)
{
	return traverse(b, r, tmin, tmax, skip, false, NULL, h, NULL, NULL);
}

bool bvh_occluded_skip(const struct bvh *b, const struct ray *r, double tmin, double tmax,
                       unsigned skip)
{
	return traverse(b, r, tmin, tmax, skip, true, NULL, NULL, NULL, NULL);
}

bool bvh_intersect_from(const struct bvh *b, const struct ray *r, double tmin, double tmax, unsigned skip,
                        const struct object *from, struct hit *h)
{
	return traverse(b, r, tmin, tmax, skip, false, from, h, NULL, NULL);
}

/* A ray that starts in leaf in's grown box, where no other leaf's box comes
 * near (alone), reaches no other bounded leaf before it leaves that box
 * (whether or not it starts inside the leaf, which need not be convex):
 * when it meets that leaf (consider, after the unbounded leaves, as the
 * full query asks them), that hit is the nearest, and the leaves' boxes are
 * not walked. The segment up to the hit lies in the box (the hit is on the
 * leaf, the box is convex); another leaf's hit lies in its own box, more
 * than pad away, which no solver's rounding spans. Otherwise the full
 * query: the leaf tested again over the same interval answers the same. */
bool bvh_intersect_in(const struct bvh *b, const struct ray *r, double tmin, double tmax, unsigned skip,
                      const struct object *in, struct hit *h)
{
	int id = -1;
	for (int i = 0; b->box && in && i < b->nprims; i++)
		if (b->prims[i] == in)
			id = i;
	const struct bbox *x = id >= 0 && b->alone[id] ? &b->lbox[id] : NULL;
	if (!x || !(r->o.x > x->lo.x && r->o.x < x->hi.x && r->o.y > x->lo.y && r->o.y < x->hi.y &&
	            r->o.z > x->lo.z && r->o.z < x->hi.z))
		return traverse(b, r, tmin, tmax, skip, false, NULL, h, NULL, NULL);
	struct query q;
	new_query(&q, b, r, tmin, tmax, skip, h);
	if (b->nunbound)
		unbounded(&q, false);
	if (!consider(&q, id))
		brute(&q, false);
	finish_if(&q, NULL, NULL);
	return q.found;
}

bool bvh_occluded_from(const struct bvh *b, const struct ray *r, double tmin, double tmax, unsigned skip,
                       const struct object *from)
{
	return traverse(b, r, tmin, tmax, skip, true, from, NULL, NULL, NULL);
}

bool bvh_intersect(const struct bvh *b, const struct ray *r, double tmin, double tmax,
                   struct hit *h)
{
	return traverse(b, r, tmin, tmax, 0, false, NULL, h, NULL, NULL);
}

bool bvh_occluded(const struct bvh *b, const struct ray *r, double tmin, double tmax)
{
	return traverse(b, r, tmin, tmax, 0, true, NULL, NULL, NULL, NULL);
}

bool bvh_intersect_lazy(const struct bvh *b, const struct ray *r, double tmin, double tmax, unsigned skip,
                        struct hit *h, bool (*full)(const void *ctx, const struct object *o), const void *ctx)
{
	return traverse(b, r, tmin, tmax, skip, false, NULL, h, full, ctx);
}
