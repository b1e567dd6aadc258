/* SPDX-License-Identifier: MIT */
/* lightpass.c: Arvo's light pass (see lightpass.h).
 *
 * Steps: find the specular objects and the cone of directions each subtends
 * from each light; shoot a stratified set of rays into each cone (a direction
 * already covered by an earlier cone is skipped, so overlapping cones count
 * light once); follow every ray through reflection and refraction; record
 * each diffuse landing (after at least one specular bounce) as a hit record;
 * then give each surface that was reached a map (its illum_map { } or a cell
 * size chosen from the ray count: pitfall 1) and deposit the records.
 * Map sums are exact (illum.h), so the result is the same for any thread
 * count. */
#include "lightpass.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../../common/order.h"
#include "../../common/pool.h"
#include "../../common/progress.h"
#include "../optics.h"
#include "../output/tmpfile.h"
#include "../sampler.h"
#include "../scatter.h"
#include "../shape.h"
#include "../spectrum.h"
#include "../surface.h"

#define CHUNK 4096 /* rays per work item */

/* A diffuse landing, kept until the maps exist: 48 bytes (24 in a grey
 * item: see work). */
struct rec {
	struct illum_splat s;     /* where on the primitive (u,v) and the energy per
	                             channel (W): first, so the maps read it in place
	                             (illum_deposit_runs) */
	const struct object *obj; /* primitive hit */
};

/* What a record needs besides, only where it is read (rec_has_x): for the
 * automatic cell size (a surface without illum_map { cell } or {
 * resolution }) and for shafts. Kept apart, so that a surface with its own
 * grid (the usual caustic receiver) writes 48 bytes a record, not 80. */
struct recx {
	struct vec3 p;            /* world point */
	double size;              /* shafts: the spread of the corners around it (m), else 0 */
};

/* A worker's records (or their recx): r[item0 .. n) are the current work
 * item's; the earlier items' records stay where they were written (in r,
 * or in a block before it, kept in old), since their spans point at them:
 * a full buffer moves on to one twice its size, copying only the current
 * item's (realloc would copy them all, into pages faulted in once more).
 * Elements of sz bytes. */
struct recbuf {
	char *r;
	long n, cap, item0;
	char **old; /* the earlier blocks (freed with r) */
	long nold;
	size_t sz;
};

/* What one light aims at one specular object: from a point or spot light,
 * the cone of directions that holds the sphere round the object
 * (shape_bsphere); from a parallel light, the beam of parallel rays whose
 * cross-section (a disc) covers it. */
struct target {
	struct vec3 axis;  /* unit direction to the sphere's centre; parallel: of travel */
	struct vec3 t1, t2;/* frame around axis */
	double cosmax;     /* cosine of the half-angle (-1: every direction) */
	double omega;      /* solid angle, sr; parallel: the disc's area, m² */
	struct vec3 origin;/* parallel: the disc's centre, upstream of the scene */
	double radius;     /* parallel: the disc's radius */
	long side;         /* rays per side of the stratified grid (side² rays) */
	double gain;       /* the light's intensity factor for this target: 1, or
	                    * under legacy lights d²·fade(d) (docs/design.md §3) */
};

/* One work item: rays [first, first+count) of target k of light l. */
struct item {
	int light, target;
	long first, count;
};

/* The maps of a pass. A surface may have several levels (shafts: map
 * resolution that follows the light), entries objs[k..k+L) of one object,
 * level 0 the finest, each level's cell twice the one before; the
 * irradiance is the sum of the levels' lookups. */
struct lp_result {
	const struct object **objs; /* primitives with a map, deterministic order */
	struct illum_map **maps;
	struct illum_spec *specs;   /* the grid each map was made with */
	int *level;                 /* level of each entry (0: finest) */
	int n;
	const struct object *nomap; /* a surface reached whose map could not be made */
	int *slots;                 /* hash of objs: index + 1, 0 = empty */
	int nslots;                 /* power of two, > 2n */
};

struct job {
	const struct scene *s;
	const struct bvh *b;
	const struct mat_cache *mc;
	const struct lp_opts *o;
	struct target **targets;    /* per light */
	int *ntargets;              /* per light */
	struct item *items;
	long nitems;
	const struct object *clipped; /* see lp_stats */
	struct band band;           /* the light this pass carries */
	struct span *spans;         /* per item: where its records went */
};

#define DISTINCT_MAX 4 /* surfaces an item lists (more: the maps step reads its records) */

/* The records of one work item: r[0 .. nr) and p[0 .. np), in the buffers
 * of the worker that traced it. Taken in item order, the records are in the
 * same order for any thread count, and so is every map's sum (even its float
 * Σw²). The distinct surfaces they reach, in order of first appearance,
 * are listed while they are in cache (nd of them; -1: more than
 * DISTINCT_MAX), so the serial step that numbers the surfaces reads a few
 * per item instead of every record. */
struct span {
	const struct rec *r;        /* NULL when grey */
	const struct illum_gsplat *g; /* a grey item's records: one surface, white light */
	const struct object *obj;   /* and their surface */
	long nr;
	const struct prec *p;       /* NULL when np = 0 */
	long np;
	const struct recx *x;       /* the recx of those records that have one (rec_has_x) */
	int nd;
	const struct object *d[DISTINCT_MAX];
};

/* The same, resolved to memory once the workers are done. */
struct seg {
	const struct rec *r;
	const struct illum_gsplat *g;
	const struct object *obj;
	long nr;
	const struct recx *x;
	const struct prec *p;
	long np;
	int nd;
	const struct object *const *d;
};

/* Light shafts (docs/design.md §4): where one specular path of a corner ray
 * of a shaft ends on a diffuse surface. */
struct landing {
	uint64_t sig;             /* the path: surfaces, branches, receiver and chart */
	const struct object *obj; /* the receiver */
	double u, v;              /* where on it */
	struct vec3 p;            /* world point */
	double e[3];              /* the energy the corner's ray brought there */
};

struct landbuf {
	struct landing *l;
	long n, cap;
};

/* A shaft's footprint on a receiver, kept until the maps exist. */
struct prec {
	struct illum_poly poly;   /* the deposit: its corners (uv below, pointed at once the work item is
	                             done: work), their number (4, or 3 for a fold's hull) and the
	                             shaft's energy along this path (W); the maps read it in place */
	double uv[4][2];          /* corners in (u,v), unwrapped across seams */
	const struct object *obj;
	double px;                /* a pixel's width where corner 0 lands (lp_opts' view; 0 without
	                             one), for shaft_spec */
	double size;              /* world diameter of the footprint */
};

struct worker {
	struct job *job;
	bool refract, reflect;      /* the current light's photons { } switches */
	struct band band;           /* the light the current ray carries */
	struct recbuf stage;        /* struct rec: the current item's, until it ends (work) */
	struct recbuf recs;         /* struct rec: earlier items' */
	struct recbuf grecs;        /* struct illum_gsplat: earlier grey items' */
	struct recbuf recx;         /* struct recx, of the records that have one */
	const struct object *xo;    /* rec_has_x for xo is xneed (a cache) */
	bool xneed;
	bool corners;               /* tracing shaft corners: landings go to lands */
	struct landbuf lands;
	struct recbuf precs;        /* struct prec */
	long long primaries;        /* shaft corner rays traced */
	long long segments;
	double emitted[3];
	double deposited[3], direct[3], absorbed[3], escaped[3], cut[3]; /* lp_stats */
	struct oinfo {              /* what trace asks of a surface, kept for a few (oinfo_of) */
		const struct object *o;
		const struct finish *dull; /* dull(o) */
		bool quiet;                /* no pass_through, no fade (inert) */
		bool still;                /* dull and quiet: inert before any bounce */
		bool convex;               /* shape_convex(o) */
		bool fades;                /* its interior absorbs light (opt_fade) */
		bool plain;                /* surf_prepare_obj filled si: */
		struct surf_in si;         /* surf_prepare's fields that depend on o alone */
		bool fixed;                /* plain, and its reflection is constant: */
		struct sc_weights rt;      /* surf_weights, the same for any hit */
	} oi[8];
	char pad[128];              /* keeps the next worker's fields off these cache lines */
};

static double maxc(struct vec3 a) { return fmax_(a.x, fmax_(a.y, a.z)); }

/* ==== which objects can form caustics ==================================== */

/* True when o (or a part of it) reflects light specularly or transmits it
 * bent (a straight transmitter's light is the shadow rays', surface.h). */
static bool is_specular(const struct scene *s, const struct object *o)
{
	if (o->kind >= OBJ_FIRST_CSG) {
		for (int i = 0; i < o->g.csg.n; i++)
			if (is_specular(s, o->g.csg.kids[i]))
				return true;
		return false;
	}
	const struct texture *t = mat_texture(o);
	const struct finish *f = tex_finish(t);
	const struct pigment *p = &t->pigment;
	bool refl = maxc(opt_rgb(f->refl_min)) > 0 || maxc(opt_rgb(f->refl_max)) > 0;
	bool trans = p->kind == PIG_SOLID ? p->c[0].f + p->c[0].t > 0 : true;
	return refl || (trans && !surf_straight(s, o));
}

bool lp_dispersive(const struct scene *s)
{
	for (int i = 0; i < s->nobjects; i++) {
		const struct object *stack[64];
		int n = 0;
		stack[n++] = s->objects[i];
		while (n > 0) {
			const struct object *o = stack[--n];
			const struct interior *in = obj_interior(o);
			if (in && in->dispersion != 1)
				return true;
			if (o->kind >= OBJ_FIRST_CSG)
				for (int k = 0; k < o->g.csg.n && n < 64; k++)
					stack[n++] = o->g.csg.kids[k];
		}
	}
	return false;
}

/* The cone from light position L round the box bb: its axis towards the
 * box's centre, wide enough for the eight corners, when the light is
 * outside the box and the cone narrower than a half-space (then it is
 * convex and holds the whole box, the corners' hull); else cosmax -1. */
static void cone_box(struct vec3 L, struct bbox bb, struct vec3 *axis, double *cosmax)
{
	*cosmax = -1;
	struct vec3 c = v_sub(bbox_centre(bb), L);
	if (!(v_len(c) > 0))
		return;
	struct vec3 a = v_norm(c);
	double m = 1;
	for (int k = 0; k < 8; k++) {
		struct vec3 q = v_sub(v3(k & 1 ? bb.hi.x : bb.lo.x, k & 2 ? bb.hi.y : bb.lo.y, k & 4 ? bb.hi.z : bb.lo.z), L);
		double l = v_len(q);
		m = l > 0 ? fmin_(m, v_dot(q, a) / l) : -1;
	}
	if (m > 1e-6)
		*axis = a, *cosmax = m - 1e-9; /* the rounding of the corners' cosines */
}

/* The cone from light position L that holds the sphere (c, r) round the
 * object (bounded; every direction when not), or with corners, the
 * narrower of that and the cone round the corners of its box bb (a light
 * beside a wide slab or a tall mirror is inside their sphere, not their
 * box). Shafts keep the sphere's: on tests/accuracy's mirror the corner
 * cone left them 4x the L1 at 10^6 rays, as its grid's pole points at the
 * mirror, not down along the caustic's axis of symmetry (docs/design.md §4). */
static struct target cone_to(struct vec3 L, bool bounded, struct vec3 c, double r, struct bbox bb, bool corners)
{
	struct target t;
	memset(&t, 0, sizeof t);
	t.cosmax = -1;
	t.axis = v3(0, -1, 0);
	if (bounded) {
		double d = v_len(v_sub(c, L));
		r *= 1 + 1e-9;
		if (d > r) {
			t.axis = v_scale(v_sub(c, L), 1 / d);
			t.cosmax = sqrt(1 - (r / d) * (r / d));
		}
		struct vec3 ba;
		double bc = -1;
		if (corners)
			cone_box(L, bb, &ba, &bc);
		if (bc > t.cosmax)
			t.axis = ba, t.cosmax = bc;
	}
	t.omega = 2 * M_PI * (1 - t.cosmax);
	struct vec3 a = fabs(t.axis.x) < 0.9 ? v3(1, 0, 0) : v3(0, 1, 0);
	t.t1 = v_norm(v_cross(a, t.axis));
	t.t2 = v_cross(t.axis, t.t1);
	return t;
}

static bool in_cone(const struct target *t, struct vec3 d) { return v_dot(d, t->axis) >= t->cosmax; }

/* The beam of parallel light travelling along unit D that covers the
 * sphere (c, r), its disc placed upstream of everything in the scene: past the
 * finite objects' bounds and past any unbounded object (a plane) that the
 * beam crosses before it reaches the sphere, so what shadows the object in the eye
 * pass (whose shadow rays toward a parallel light never end) shadows the
 * beam too. */
static struct target beam_to(const struct scene *s, struct vec3 D, struct vec3 c, double r)
{
	struct target t;
	memset(&t, 0, sizeof t);
	t.axis = D;
	t.cosmax = 1;
	t.radius = r * (1 + 1e-9);
	t.omega = M_PI * t.radius * t.radius;
	double back = t.radius;
	for (int i = 0; i < s->nobjects; i++) {
		struct bbox ob = shape_bounds(s->objects[i]);
		struct hit h;
		if (bbox_finite(ob)) {
			struct vec3 oc = bbox_centre(ob);
			back = fmax_(back, v_len(v_sub(oc, c)) + bbox_radius(ob));
		} else if (shape_intersect(s->objects[i], &(struct ray){c, v_neg(D)}, 0, INFINITY, &h)) {
			back = fmax_(back, h.t);
		}
	}
	back = 2 * back + 1;
	t.origin = v_madd(c, D, -back);
	struct vec3 a = fabs(D.x) < 0.9 ? v3(1, 0, 0) : v3(0, 1, 0);
	t.t1 = v_norm(v_cross(a, D));
	t.t2 = v_cross(D, t.t1);
	return t;
}

/* Where light under a parallel source matters when a specular object is
 * unbounded (a mirror or glass plane under the sun): the bounds of every
 * finite object and the camera, at least 1 across. Receivers outside get no
 * caustic from that object. */
static struct bbox scene_extent(const struct scene *s)
{
	struct bbox e = bbox_add(bbox_empty(), s->camera.location);
	for (int i = 0; i < s->nobjects; i++)
		if (shape_bounded(s->objects[i]))
			e = bbox_union(e, shape_bounds(s->objects[i]));
	e.lo = v_sub(e.lo, v3(0.5, 0.5, 0.5));
	e.hi = v_add(e.hi, v3(0.5, 0.5, 0.5));
	return e;
}

/* Does the line through p along the beam's direction pass through the
 * beam's disc? */
static bool in_beam(const struct target *t, struct vec3 p)
{
	struct vec3 q = v_sub(p, t->origin);
	struct vec3 r = v_madd(q, t->axis, -v_dot(q, t->axis));
	return v_dot(r, r) <= t->radius * t->radius;
}

/* ==== tracing ============================================================ */

/* Mixes one step of a path (the object met and what happened there) into a
 * path signature. */
static uint64_t sig_mix(uint64_t sig, const void *obj, unsigned what)
{
	uint64_t x = sig ^ ((uint64_t)(uintptr_t)obj * 0x9E3779B97F4A7C15ull) ^ ((uint64_t)what << 56);
	x ^= x >> 31;
	x *= 0xBF58476D1CE4E5B9ull;
	x ^= x >> 29;
	return x;
}

/* The chart of a hit: the box's (u,v) atlas has six faces whose (u,v) do
 * not join, so a footprint may not span two of them. */
static unsigned chart(const struct hit *h)
{
	if (h->obj->kind != OBJ_BOX)
		return 0;
	int a = (int)(h->u * 3), b = (int)(h->v * 2);
	return (unsigned)(1 + (a < 0 ? 0 : a > 2 ? 2 : a) + 3 * (b < 0 ? 0 : b > 1 ? 1 : b));
}

static void land(struct worker *w, const struct hit *h, const double e[3], uint64_t sig);

/* Moves rb on to a block twice the size (see struct recbuf), or room for
 * `more` elements after the current item's. */
static __attribute__((noinline)) void recbuf_grow(struct recbuf *rb, long more)
{
	long cap = rb->cap ? rb->cap * 2 : 4096, keep = rb->n - rb->item0;
	if (cap < keep + more)
		cap = keep + more;
	if (rb->cap && (size_t)cap * rb->sz < MEM_HUGE_MIN) /* past the first block, MEM_HUGE_MIN at
	                                                        least (huge pages: fewer page faults;
	                                                        only the pages written are zeroed) */
		cap = (long)((MEM_HUGE_MIN + rb->sz - 1) / rb->sz);
	char *r = mem_alloc_huge(rb->sz * (size_t)cap);
	if (keep)
		memcpy(r, rb->r + rb->sz * (size_t)rb->item0, rb->sz * (size_t)keep);
	if (rb->item0 > 0) { /* earlier items' records are in it */
		rb->old = mem_realloc(rb->old, sizeof *rb->old * (size_t)(rb->nold + 1));
		rb->old[rb->nold++] = rb->r;
	} else {
		free(rb->r);
	}
	rb->r = r, rb->cap = cap, rb->n = keep, rb->item0 = 0;
}

/* The next element of rb, to fill. */
static inline void *recbuf_push(struct recbuf *rb)
{
	if (rb->n == rb->cap)
		recbuf_grow(rb, 1);
	return rb->r + rb->sz * (size_t)rb->n++;
}

/* Room for n elements, the current item's from now on (rb->n grows by n). */
static void *recbuf_take(struct recbuf *rb, long n)
{
	rb->item0 = rb->n;
	if (rb->cap - rb->n < n)
		recbuf_grow(rb, n);
	rb->n += n;
	return rb->r + rb->sz * (size_t)rb->item0;
}

/* The current item's elements (NULL when there are none). */
static void *recbuf_item(const struct recbuf *rb)
{
	return rb->n > rb->item0 ? rb->r + rb->sz * (size_t)rb->item0 : NULL;
}

static void recbuf_free(struct recbuf *rb)
{
	for (long i = 0; i < rb->nold; i++)
		free(rb->old[i]);
	free(rb->old), free(rb->r);
}

/* Whether a record on ob keeps its struct recx: with shafts (sizes, and
 * shaft_spec's points), and on a surface whose grid is chosen from where
 * the records landed (no illum_map { cell } or { resolution }, as
 * choose_spec asks). */
static bool rec_has_x(const struct lp_opts *o, const struct object *ob)
{
	struct illum_spec own = obj_illum(ob);
	return o->shafts || !(own.resolution > 0 || own.cell > 0);
}

/* Appends a record (and its recx where it keeps one). */
static inline void push_rec(struct worker *w, const struct illum_splat *s, const struct object *ob, struct vec3 p,
                            double size)
{
	*(struct rec *)recbuf_push(&w->stage) = (struct rec){*s, ob};
	if (ob != w->xo)
		w->xo = ob, w->xneed = rec_has_x(w->job->o, ob);
	if (w->xneed)
		*(struct recx *)recbuf_push(&w->recx) = (struct recx){p, size};
}

static void record(struct worker *w, struct hit *h, const struct ray *r, const double e[3], uint64_t sig)
{
	if (isnan(h->u)) /* traced without its (u,v) (BVH_NO_UV): a deposit needs them */
		shape_hit_at(h->obj, r, 0, INFINITY, h->t, true, h);
	if (w->corners) {
		land(w, h, e, sig_mix(sig, h->obj, 16 + chart(h)));
		return;
	}
	push_rec(w, &(struct illum_splat){h->u, h->v, {e[0], e[1], e[2]}}, h->obj, h->p, 0);
}

/* acc += e (written out: GCC does not unroll the loop at -O2, and every
 * segment counts its energy somewhere). */
static inline void add3(double acc[3], const double e[3])
{
	acc[0] += e[0];
	acc[1] += e[1];
	acc[2] += e[2];
}

/* The largest of three numbers that are not NaN, inline (fmax is a libm
 * call on the hot path). */
static double max3(double a, double b, double c)
{
	double m = b > c ? b : c;
	return a > m ? a : m;
}

/* The finish of o when light can neither reflect from nor pass through it
 * anywhere (one solid pigment without filter or transmit, a constant zero
 * reflection): surf_scatter would give R = T = 0 and the opacity is 1, so
 * trace needs neither it nor surf_prepare (most rays end on such a floor).
 * NULL otherwise. */
static const struct finish *dull(const struct object *o)
{
	const struct texture *t = mat_texture(o);
	const struct colour *c = &t->pigment.c[0];
	if (tex_map(t) || t->pigment.kind != PIG_SOLID || c->f != 0 || c->t != 0 || !isfinite(c->r) ||
	    !isfinite(c->g) || !isfinite(c->b)) /* (an infinite colour times f = 0 is NaN) */
		return NULL;
	const struct finish *f = tex_finish(t);
	if (f->refl_fresnel || f->refl_metallic || f->refl_min.r != 0 || f->refl_min.g != 0 || f->refl_min.b != 0 ||
	    f->refl_max.r != 0 || f->refl_max.g != 0 || f->refl_max.b != 0)
		return NULL;
	return f;
}

/* dull(o) and whether o lets nothing pass (photons { pass_through }) and
 * fades nothing, from the worker's small cache of them (a ray meets the
 * same few surfaces over and over). */
static __attribute__((noinline)) void oinfo_fill(const struct worker *w, struct oinfo *x, const struct object *o)
{
	const struct photon_spec *ph = obj_photons(o);
	bool fades = mat_interior(o)->fade_distance > 0;
	*x = (struct oinfo){.o = o, .dull = dull(o), .quiet = !(ph && ph->pass_through) && !fades,
	                    .convex = shape_convex(o), .fades = fades};
	x->still = x->dull && x->quiet;
	x->plain = surf_prepare_obj(w->job->s, o, &x->si);
	x->fixed = x->plain && sc_refl_fixed(x->si.f);
	if (x->fixed) /* (neither the angle nor the indices matter: any will do) */
		x->rt = surf_weights(&x->si, 1, 1, 1);
}

static inline struct oinfo *oinfo_of(struct worker *w, const struct object *o)
{
	struct oinfo *x = &w->oi[((uintptr_t)o >> 6) & 7];
	if (x->o != o)
		oinfo_fill(w, x, o);
	return x;
}

/* What trace needs of a hit on o by a ray with nspec specular bounces.
 * Inert: a dull surface the ray reaches before any bounce (it is not
 * recorded, unless the pass deposits direct light) that is quiet: all of
 * the ray's light is direct or absorbed there, whatever the point, normal
 * or side, so the query need not work them out (bvh_intersect_lazy). */
struct need {
	struct worker *w;
	bool direct; /* no bounce yet, and direct light is not deposited */
};

static bool inert(const struct need *n, const struct oinfo *x)
{
	return n->direct && x->still;
}

/* (Asked only before the first bounce, where n->direct holds: after it,
 * every hit is needed whole and trace passes no callback.) */
static __attribute__((noinline)) bool full_fill(struct worker *w, struct oinfo *x, const struct object *o)
{
	oinfo_fill(w, x, o);
	return !x->still;
}

static bool full_hit(const void *ctx, const struct object *o)
{
	struct worker *w = ((const struct need *)ctx)->w;
	struct oinfo *x = &w->oi[((uintptr_t)o >> 6) & 7]; /* oinfo_of, its fill a tail call */
	return x->o == o ? !x->still : full_fill(w, x, o);
}

/* Follows one light ray; nspec counts its specular bounces so far (a
 * straight transmitter, whose light the eye pass's shadow rays carry, is no
 * bounce). Every joule that arrives is accounted for once (lp_stats):
 * followed on, deposited, direct, absorbed, escaped or cut. from: a convex
 * object the ray leaves outward (it cannot hit it again: bvh_intersect_from),
 * or NULL. The last ray a hit spawns is followed in the same loop, not by a
 * call (the order of everything recorded and counted is the recursion's:
 * a transmitted ray before a reflected one). */
static void trace(struct worker *w, struct ray r, const double e_in[3], double cutoff, int depth, int nspec,
                  uint64_t sig, const struct object *from)
{
	const struct job *J = w->job;
	double en[3] = {e_in[0], e_in[1], e_in[2]}; /* the light this ray carries */
	for (;;) {
		const double *e = en;
		struct hit h;
		w->segments++;
		struct need nd = {w, nspec == 0 && !J->o->deposit_direct};
		if (!(nd.direct ? bvh_intersect_lazy(J->b, &r, 0, INFINITY, BVH_NO_UV, &h, full_hit, &nd)
		                : bvh_intersect_from(J->b, &r, 0, INFINITY, BVH_NO_UV, from, &h))) {
			add3(w->escaped, e);
			return;
		}
		struct oinfo *hx = oinfo_of(w, h.obj);
		if (inert(&nd, hx)) { /* h holds only obj and t */
			add3(hx->dull->diffuse > 0 ? w->direct : w->absorbed, e);
			return;
		}
		/* POV-Ray's photons { } on the object: pass_through lets light by
		 * untouched, collect off keeps it off the maps, and a target with
		 * refraction or reflection off does not bend light that way */
		const struct photon_spec *ph = obj_photons(h.obj);
		if (ph && ph->pass_through) {
			if (depth >= J->o->max_depth) {
				add3(w->cut, e);
				return;
			}
			r = (struct ray){v_madd(h.p, r.d, surf_eps(h.p) / v_len(r.d)), r.d};
			depth++, from = NULL;
			continue;
		}
		if (!h.entering && hx->fades) { /* leaving a medium: its absorption over the path inside
		                                   (none, k = 1, unless it fades) */
			struct vec3 k = opt_fade(mat_interior(h.obj), h.t * v_len(r.d));
			double ea[3] = {en[0] * k.x, en[1] * k.y, en[2] * k.z};
			for (int c = 0; c < 3; c++)
				w->absorbed[c] += en[c] - ea[c], en[c] = ea[c];
		}
		const struct finish *df = hx->dull;
		if (df) { /* all of it stays here (rest = e); nothing goes on */
			if (df->diffuse > 0 && (nspec > 0 || J->o->deposit_direct) && (!ph || ph->collect)) {
				record(w, &h, &r, e, sig);
				add3(w->deposited, e);
			} else {
				add3(df->diffuse > 0 && nspec == 0 ? w->direct : w->absorbed, e);
			}
			return;
		}
		struct surf_in own, *si = &own;
		struct surf_out so;
		if (hx->plain) { /* the object's part made once (oinfo_fill), the hit's in place */
			si = &hx->si;
			surf_prepare_hit(&h, v_norm(r.d), si);
		} else {
			surf_prepare(J->s, J->mc, &h, v_norm(r.d), si);
		}
		if (hx->fixed) {
			double n1, n2;
			sc_sides(si, w->band, &n1, &n2);
			surf_scatter_rt(si, n1, n2, hx->rt, &so);
		} else {
			surf_scatter(si, w->band, &so);
		}
		double opacity = 1 - si->pc.f - si->pc.t;
		/* what neither reflects nor transmits stays at the surface: a diffuse
		 * surface reached after a specular bounce keeps it in its map */
		double rest[3];
		for (int c = 0; c < 3; c++)
			rest[c] = e[c] * (1 - v_comp(so.R, c) - v_comp(so.T, c));
		bool diffuse = si->f->diffuse > 0 && opacity > 0;
		if (diffuse && (nspec > 0 || J->o->deposit_direct) && (!ph || ph->collect)) {
			record(w, &h, &r, e, sig);
			add3(w->deposited, rest);
		} else if (diffuse && nspec == 0) {
			add3(w->direct, rest);
		} else {
			add3(w->absorbed, rest);
		}
		double tmax = max3(so.T.x, so.T.y, so.T.z), rmax = max3(so.R.x, so.R.y, so.R.z);
		if (!(tmax > 0) && !(rmax > 0))
			return;
		bool more = depth < J->o->max_depth;
		/* the spawned rays start off the surface on the side of si.nf (the
		 * reflected one) or of -si.nf (the transmitted one): the outside of a
		 * convex object when that is the side of its outward normal */
		const struct object *out = hx->convex ? h.obj : NULL;
		bool outside = v_dot(si->nf, h.n) > 0; /* the incoming ray came from outside */
		uint64_t sig0 = sig;
		depth++;
		if (tmax > 0) {
			bool refract = w->refract && (!ph || !ph->target || ph->refraction) && more;
			double te[3] = {e[0] * so.T.x, e[1] * so.T.y, e[2] * so.T.z};
			if (!(refract && max3(te[0], te[1], te[2]) > cutoff)) {
				add3(w->cut, te);
			} else if (rmax > 0) { /* both: the transmitted ray first, by a call */
				trace(w, so.trans, te, cutoff, depth, si->straight ? nspec : nspec + 1,
				      sig_mix(sig0, h.obj, 1), outside ? NULL : out);
			} else { /* the transmitted ray alone: on in this loop */
				r = so.trans, en[0] = te[0], en[1] = te[1], en[2] = te[2];
				nspec = si->straight ? nspec : nspec + 1, sig = sig_mix(sig0, h.obj, 1);
				from = outside ? NULL : out;
				continue;
			}
		}
		if (!(rmax > 0))
			return;
		bool reflect = w->reflect && (!ph || !ph->target || ph->reflection) && !J->o->transmit_only && more;
		double re[3] = {e[0] * so.R.x, e[1] * so.R.y, e[2] * so.R.z};
		if (!(reflect && max3(re[0], re[1], re[2]) > cutoff)) {
			add3(w->cut, re);
			return;
		}
		r = so.refl, en[0] = re[0], en[1] = re[1], en[2] = re[2];
		nspec = nspec + 1, sig = sig_mix(sig0, h.obj, 2), from = outside ? out : NULL;
	}
}

/* The wavelength of ray i of a side×side grid (spectral passes), and its
 * energy per channel: e_c times f_c(λ) (spectrum.h). Stratified with the
 * grid (smp_latin): each row and each column of the grid, a ring or a
 * spoke of the cone, takes one wavelength from each 1/side of the
 * spectrum, in a scrambled order (a regular lattice aliases into stripes on
 * the maps, and a nesting in squares fails a narrow spotlight's strip).
 * It depends only on the ray's index: the same for any thread count. */
static double ray_wavelength(uint64_t key, uint64_t i, uint64_t side, double e[3])
{
	double f[3];
	double u = smp_latin(i % side, i / side, side, key, smp_get(key, (uint32_t)i, 2));
	double lambda = spec_sample(u, f);
	for (int c = 0; c < 3; c++)
		e[c] *= f[c];
	return lambda;
}

static void land(struct worker *w, const struct hit *h, const double e[3], uint64_t sig)
{
	struct landbuf *b = &w->lands;
	if (b->n == b->cap)
		b->l = mem_realloc(b->l, sizeof *b->l * (size_t)(b->cap = b->cap ? b->cap * 2 : 1024));
	b->l[b->n++] = (struct landing){sig, h->obj, h->u, h->v, h->p, {e[0], e[1], e[2]}};
}

/* ==== light shafts ======================================================= */

#define SHAFT_LEVELS 3 /* subdivisions of a shaft before it deposits as it is */

/* The origin and direction of the ray at (sx, sy) of target t's stratified
 * grid: (cos θ, φ) over a cone, (r², φ) over a beam's disc; both are
 * equal-area, so every grid cell carries the same share of the light. */
static void aim(const struct light *l, const struct target *t, double sx, double sy, struct vec3 *o,
                struct vec3 *d)
{
	double ph = 2 * M_PI * sy;
	*o = l->pos, *d = t->axis;
	if (l->kind == LIGHT_PARALLEL) {
		double rr = t->radius * sqrt(sx);
		*o = v_add(t->origin, v_add(v_scale(t->t1, rr * cos(ph)), v_scale(t->t2, rr * sin(ph))));
	} else {
		double ct = 1 - sx * (1 - t->cosmax), st = sqrt(fmax_(0, 1 - ct * ct));
		*d = v_add(v_scale(t->axis, ct), v_add(v_scale(t->t1, st * cos(ph)), v_scale(t->t2, st * sin(ph))));
	}
}

/* The light's weight along a ray of target k: 0 where an earlier target
 * already covers it (overlapping cones count light once) or outside a
 * spotlight's cone, else the spotlight factor (1 for other lights). */
static double emit_weight(const struct light *l, const struct target *tg, int k, struct vec3 o, struct vec3 d)
{
	bool beam = l->kind == LIGHT_PARALLEL;
	for (int j = 0; j < k; j++)
		if (beam ? in_beam(&tg[j], o) : in_cone(&tg[j], d))
			return 0;
	return l->kind == LIGHT_SPOT ? opt_spot(l, d) : 1;
}

/* What a shaft needs to know about its light and target. */
struct shaft_ctx {
	const struct light *l;
	const struct target *tg; /* the light's targets */
	int k;                   /* this one */
	double e0[3];            /* energy of a top-level grid cell (W) */
	double cutoff;           /* branch cutoff */
};

/* A corner ray: its landings are lands.l[first .. first+n). */
struct corner {
	long first, n;
};

/* Traces the corner ray at (sx, sy) with the cell energy e0 (the landings
 * then hold e0 × the path's weight). */
static struct corner corner_at(struct worker *w, const struct shaft_ctx *S, double sx, double sy)
{
	struct vec3 o, d;
	aim(S->l, &S->tg[S->k], sx, sy, &o, &d);
	struct corner c = {w->lands.n, 0};
	w->primaries++;
	double k = emit_weight(S->l, S->tg, S->k, o, d);
	if (k > 0) {
		double e[3] = {S->e0[0] * k, S->e0[1] * k, S->e0[2] * k};
		trace(w, (struct ray){o, d}, e, S->cutoff, 0, 0, 0, NULL);
	}
	c.n = w->lands.n - c.first;
	return c;
}

static const struct landing *find_sig(const struct worker *w, struct corner c, uint64_t sig)
{
	for (long i = c.first; i < c.first + c.n; i++)
		if (w->lands.l[i].sig == sig)
			return &w->lands.l[i];
	return NULL;
}

/* The four landings of one path as a footprint in (u,v): corners unwrapped
 * across a periodic seam, in shaft order. False when the quadrilateral is
 * not convex (a fold of the caustic turns it inside out) or has no area. */
static bool footprint(const struct landing *q[4], double uv[4][2]);

/* The convex hull of the unwrapped corners uv[0..4) in place (a fold turns
 * a footprint into a bow-tie: the hull is the region its light covers);
 * returns its vertex count, 3 or 4, or 0 when it has no area. */
static int hull4(double uv[4][2])
{
	double cx = 0.25 * (uv[0][0] + uv[1][0] + uv[2][0] + uv[3][0]);
	double cy = 0.25 * (uv[0][1] + uv[1][1] + uv[2][1] + uv[3][1]);
	double ang[4], p[4][2];
	int idx[4] = {0, 1, 2, 3};
	for (int i = 0; i < 4; i++)
		ang[i] = atan2(uv[i][1] - cy, uv[i][0] - cx);
	for (int i = 1; i < 4; i++) /* sort by angle around the centroid */
		for (int j = i; j > 0 && ang[idx[j]] < ang[idx[j - 1]]; j--) {
			int t = idx[j];
			idx[j] = idx[j - 1], idx[j - 1] = t;
		}
	for (int i = 0; i < 4; i++)
		p[i][0] = uv[idx[i]][0], p[i][1] = uv[idx[i]][1];
	/* drop a vertex inside the triangle of the others (a reflex corner) */
	int n = 4;
	for (int i = 0; i < n && n == 4; i++) {
		const double *a = p[(i + 3) & 3], *b = p[i], *c = p[(i + 1) & 3];
		double cr = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
		if (cr <= 0) {
			for (int j = i; j < 3; j++)
				p[j][0] = p[j + 1][0], p[j][1] = p[j + 1][1];
			n = 3;
		}
	}
	double area = 0;
	for (int i = 0; i < n; i++)
		area += p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1];
	if (!(fabs(area) > 0) || !isfinite(area))
		return 0;
	memcpy(uv, p, sizeof p);
	return n;
}

static bool footprint(const struct landing *q[4], double uv[4][2])
{
	struct uv_range rg;
	bool wu = false, wv = false;
	if (shape_uv_range(q[0]->obj, &rg))
		wu = rg.u_wraps, wv = rg.v_wraps;
	for (int i = 0; i < 4; i++) {
		uv[i][0] = q[i]->u, uv[i][1] = q[i]->v;
		if (wu)
			uv[i][0] -= floor(uv[i][0] - uv[0][0] + 0.5);
		if (wv)
			uv[i][1] -= floor(uv[i][1] - uv[0][1] + 0.5);
	}
	double sgn = 0, area = 0;
	for (int i = 0; i < 4; i++) {
		const double *a = uv[i], *b = uv[(i + 1) & 3], *c = uv[(i + 2) & 3];
		double cr = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
		area += a[0] * b[1] - b[0] * a[1];
		if (cr * sgn < 0)
			return false;
		if (cr != 0)
			sgn = cr;
	}
	return area != 0 && isfinite(area);
}

#define SHAFT_MEMO 8 /* the first landings of a shaft's corner 0 whose footprints it keeps */

/* The footprints of the paths of a shaft's corner 0, each worked out once
 * (footprint() depends on the four landings alone): the test for a whole
 * shaft, linear_enough and the deposits read the same ones. Entry k is the
 * path of corner 0's landing k, with its first landing of that signature
 * in each other corner (find_sig), when all four have one. */
struct fp_memo {
	bool known[SHAFT_MEMO];
	bool convex[SHAFT_MEMO];     /* footprint()'s answer */
	double uv[SHAFT_MEMO][4][2]; /* and its corners */
};

/* footprint(q, uv) for the path of corner 0's landing k (q[0] is it),
 * from the memo or worked out and kept. */
static bool footprint_kept(struct fp_memo *fm, long k, const struct landing *q[4], double uv[4][2])
{
	if (k < 0 || k >= SHAFT_MEMO)
		return footprint(q, uv);
	if (!fm->known[k]) {
		fm->convex[k] = footprint(q, fm->uv[k]);
		fm->known[k] = true;
	}
	memcpy(uv, fm->uv[k], sizeof fm->uv[k]);
	return fm->convex[k];
}

/* Does the centre ray of a shaft land, for every path, where the corners'
 * bilinear middle says (within a fifth of the footprint's size in (u,v))?
 * If not, the path bends the shaft too much to spread its flux evenly. */
static bool linear_enough(struct worker *w, const struct shaft_ctx *S, double sx, double sy, const struct corner c[4],
                          struct fp_memo *fm)
{
	long mark = w->lands.n;
	struct corner m = corner_at(w, S, sx, sy);
	bool ok = m.n == c[0].n;
	for (long i = c[0].first; ok && i < c[0].first + c[0].n; i++) {
		const struct landing *q[4] = {&w->lands.l[i], find_sig(w, c[1], w->lands.l[i].sig),
		                              find_sig(w, c[2], w->lands.l[i].sig), find_sig(w, c[3], w->lands.l[i].sig)};
		const struct landing *mid = find_sig(w, m, q[0]->sig);
		double uv[4][2];
		if (!mid || !footprint_kept(fm, i - c[0].first, q, uv)) {
			ok = false;
			break;
		}
		double cu = 0.25 * (uv[0][0] + uv[1][0] + uv[2][0] + uv[3][0]);
		double cv = 0.25 * (uv[0][1] + uv[1][1] + uv[2][1] + uv[3][1]);
		double du = mid->u - cu, dv = mid->v - cv;
		struct uv_range rg;
		bool ranged = shape_uv_range(mid->obj, &rg);
		if (ranged && rg.u_wraps)
			du -= floor(du + 0.5);
		if (ranged && rg.v_wraps)
			dv -= floor(dv + 0.5);
		double sz = fmax_(fabs(uv[2][0] - uv[0][0]), fabs(uv[3][0] - uv[1][0])) +
		            fmax_(fabs(uv[2][1] - uv[0][1]), fabs(uv[3][1] - uv[1][1]));
		ok = du * du + dv * dv <= 0.04 * sz * sz;
	}
	w->lands.n = mark;
	return ok;
}

static void push_prec(struct worker *w, const struct prec *p)
{
	*(struct prec *)recbuf_push(&w->precs) = *p;
}

/* One shaft: the grid cell [sx0,sx1]×[sy0,sy1] at subdivision level lv,
 * with corner rays c (in the order (sx0,sy0) (sx0,sy1) (sx1,sy1) (sx1,sy0)).
 * A path all four corners follow spreads the shaft's share of it, the mean
 * of their energies over 4^lv, over its footprint; where they diverge the
 * shaft splits in four, and at the last level each corner's landing is a
 * point deposit of a quarter of that. */
static void shaft(struct worker *w, const struct shaft_ctx *S, int lv, double sx0, double sx1, double sy0,
                  double sy1, const struct corner c[4])
{
	bool whole = true;
	struct fp_memo fm;
	memset(fm.known, 0, sizeof fm.known);
	const struct landing *l = w->lands.l; /* (for the test alone: tracing a corner may move it) */
	if (c[0].n == 1 && c[1].n == 1 && c[2].n == 1 && c[3].n == 1) /* one path each (the usual case) */
		whole = l[c[0].first].sig == l[c[1].first].sig && l[c[0].first].sig == l[c[2].first].sig &&
		        l[c[0].first].sig == l[c[3].first].sig;
	else
		for (int k = 0; k < 4 && whole; k++)
			for (long i = c[k].first; whole && i < c[k].first + c[k].n; i++)
				for (int j = 0; j < 4 && whole; j++)
					whole = find_sig(w, c[j], l[i].sig) != NULL;
	for (long i = c[0].first; whole && i < c[0].first + c[0].n; i++) {
		const struct landing *q[4] = {&w->lands.l[i], find_sig(w, c[1], w->lands.l[i].sig),
		                              find_sig(w, c[2], w->lands.l[i].sig), find_sig(w, c[3], w->lands.l[i].sig)};
		double uv[4][2];
		whole = footprint_kept(&fm, i - c[0].first, q, uv);
	}
	double sxm = 0.5 * (sx0 + sx1), sym = 0.5 * (sy0 + sy1);
	if (lv < SHAFT_LEVELS && c[0].n + c[1].n + c[2].n + c[3].n > 0 &&
	    (!whole || !linear_enough(w, S, sxm, sym, c, &fm))) {
		long mark = w->lands.n;
		struct corner a = corner_at(w, S, sxm, sy0), b = corner_at(w, S, sx0, sym), m = corner_at(w, S, sxm, sym);
		struct corner d = corner_at(w, S, sx1, sym), e = corner_at(w, S, sxm, sy1);
		shaft(w, S, lv + 1, sx0, sxm, sy0, sym, (struct corner[4]){c[0], b, m, a});
		shaft(w, S, lv + 1, sx0, sxm, sym, sy1, (struct corner[4]){b, c[1], e, m});
		shaft(w, S, lv + 1, sxm, sx1, sym, sy1, (struct corner[4]){m, e, c[2], d});
		shaft(w, S, lv + 1, sxm, sx1, sy0, sym, (struct corner[4]){a, m, d, c[3]});
		w->lands.n = mark;
		return;
	}
	double share = 0.25 / (double)(1L << (2 * lv));
	/* a whole shaft's paths are all corner 0's, each with a convex
	 * footprint: the other corners' landings would find theirs and add
	 * nothing */
	for (int k = 0; k < (whole ? 1 : 4); k++)
		for (long i = c[k].first; i < c[k].first + c[k].n; i++) {
			const struct landing *L = &w->lands.l[i];
			const struct landing *q[4] = {find_sig(w, c[0], L->sig), find_sig(w, c[1], L->sig),
			                              find_sig(w, c[2], L->sig), find_sig(w, c[3], L->sig)};
			double uv[4][2];
			bool all = q[0] && q[1] && q[2] && q[3];
			/* (q[0] is corner 0's first landing of this path: the memo's entry) */
			bool convex = all && footprint_kept(&fm, q[0] - &w->lands.l[c[0].first], q, uv);
			int nv = convex ? 4 : all ? hull4(uv) : 0;
			if (!nv) { /* a point deposit of this corner's quarter, as wide as the
			               other corners' landings on the same surface are far */
				double size = 0;
				for (int j = 0; j < 4; j++)
					for (long m = c[j].first; m < c[j].first + c[j].n; m++)
						if (w->lands.l[m].obj == L->obj) {
							double x = v_len(v_sub(w->lands.l[m].p, L->p));
							size = x > size ? x : size; /* fmax: size is never NaN */
						}
				push_rec(w, &(struct illum_splat){L->u, L->v, {L->e[0] * share, L->e[1] * share, L->e[2] * share}},
				         L->obj, L->p, size);
				continue;
			}
			if (k > 0)
				continue; /* the whole path was spread from corner 0 */
			const struct lp_opts *o = w->job->o;
			double px = o->pixel_width > 0   ? o->pixel_width
			            : o->pixel_angle > 0 ? v_len(v_sub(L->p, o->eye)) * o->pixel_angle
			                                 : 0;
			struct prec pr = {{NULL, nv, {0, 0, 0}}, {{0}}, L->obj, px, 0};
			memcpy(pr.uv, uv, sizeof uv);
			for (int j = 0; j < 4; j++) {
				for (int ch = 0; ch < 3; ch++)
					pr.poly.e[ch] += q[j]->e[ch] * share;
				for (int m = j + 1; m < 4; m++) {
					double x = v_len(v_sub(q[j]->p, q[m]->p));
					pr.size = x > pr.size ? x : pr.size; /* fmax: pr.size is never NaN */
				}
			}
			push_prec(w, &pr);
		}
}

/* Shoots the shafts of rows [first, first+count) of a target's grid,
 * tracing its corner rows first .. first+count once each. The energy
 * balance is estimated from the corner rays, as trapezoids: a corner row
 * counts half for each row of shafts it bounds, so a row on the boundary
 * of two items (traced by both) counts once in all. */
static void run_shafts(struct worker *w, const struct item *it)
{
	const struct job *J = w->job;
	const struct light *l = &J->s->lights[it->light];
	struct shaft_ctx S = {l, J->targets[it->light], it->target, {0, 0, 0}, 0};
	const struct target *t = &S.tg[S.k];
	long n = t->side, side = t->side;
	double scale = t->gain * t->omega / (double)(n * n);
	S.e0[0] = l->colour.r * scale, S.e0[1] = l->colour.g * scale, S.e0[2] = l->colour.b * scale;
	if (J->o->channel >= 0)
		for (int c = 0; c < 3; c++)
			if (c != J->o->channel)
				S.e0[c] = 0;
	S.cutoff = J->o->min_weight * fmax_(S.e0[0], fmax_(S.e0[1], S.e0[2]));
	w->refract = l->photons_refraction;
	w->reflect = l->photons_reflection;
	w->band = J->band;
	w->corners = true;
	w->lands.n = 0;
	/* rows of corner rays: lo (at sx0) and hi (at sx1); hi becomes the next
	 * shaft row's lo */
	struct corner *lo = mem_alloc(sizeof *lo * (size_t)side), *hi = mem_alloc(sizeof *hi * (size_t)side);
	double *now[6] = {w->emitted, w->deposited, w->direct, w->absorbed, w->escaped, w->cut};
	long first = it->first, last = it->first + it->count; /* corner rows first .. last */
	for (long r = first; r <= last; r++) {
		/* trace corner row r; it bounds (r > first) + (r < last) of this
		 * item's shaft rows, and counts that many halves */
		double sx = (double)r / (double)side, wr = 0.5 * ((r > first) + (r < last)), acc[6][3];
		for (int q = 0; q < 6; q++)
			memcpy(acc[q], now[q], sizeof acc[q]);
		for (long j = 0; j < side; j++) {
			double sy = (double)j / (double)side;
			struct vec3 o, d;
			aim(l, t, sx, sy, &o, &d);
			double k = emit_weight(l, S.tg, S.k, o, d);
			hi[j] = corner_at(w, &S, sx, sy);
			for (int c = 0; c < 3; c++)
				w->emitted[c] += S.e0[c] * k;
		}
		for (int q = 0; q < 6; q++)
			for (int c = 0; c < 3; c++)
				now[q][c] = acc[q][c] + wr * (now[q][c] - acc[q][c]);
		if (r > first) {
			/* the shafts between rows r-1 and r; subdivision rays only refine
			 * where the light goes, not how much */
			for (int q = 0; q < 6; q++)
				memcpy(acc[q], now[q], sizeof acc[q]);
			double sx0 = (double)(r - 1) / (double)side;
			for (long j = 0; j < side; j++) {
				long j1 = (j + 1) % side;
				struct corner c[4] = {lo[j], lo[j1], hi[j1], hi[j]};
				shaft(w, &S, 0, sx0, sx, (double)j / (double)side, (double)(j + 1) / (double)side, c);
			}
			for (int q = 0; q < 6; q++)
				memcpy(now[q], acc[q], sizeof acc[q]);
			/* keep only row r's landings, at the front */
			long from = hi[0].first, cnt = w->lands.n - from;
			if (cnt > 0)
				memmove(w->lands.l, w->lands.l + from, sizeof *w->lands.l * (size_t)cnt);
			w->lands.n = cnt;
			for (long j = 0; j < side; j++)
				hi[j].first -= from;
		}
		struct corner *tmp = lo;
		lo = hi, hi = tmp;
	}
	w->corners = false;
	free(lo), free(hi);
}

/* Shoots the rays of one work item. */
static void run_item(struct worker *w, const struct item *it)
{
	const struct job *J = w->job;
	const struct light *l = &J->s->lights[it->light];
	const struct target *tg = J->targets[it->light];
	const struct target *t = &tg[it->target];
	long n = t->side * t->side;
	double scale = t->gain * t->omega / (double)n;
	double e0[3] = {l->colour.r * scale, l->colour.g * scale, l->colour.b * scale};
	if (J->o->channel >= 0)
		for (int c = 0; c < 3; c++)
			if (c != J->o->channel)
				e0[c] = 0;
	double cutoff = J->o->min_weight * fmax_(e0[0], fmax_(e0[1], e0[2]));
	uint64_t key = ((uint64_t)it->light << 40) ^ ((uint64_t)it->target << 20) ^ 0x5A17u ^ J->o->seed_key;
	bool beam = l->kind == LIGHT_PARALLEL;
	w->refract = l->photons_refraction;
	w->reflect = l->photons_reflection;
	w->band = J->band; /* a spectral pass sets each ray's wavelength */
	long col = it->first % t->side, row = it->first / t->side; /* of ray i, kept without dividing */
	/* what every ray of the item reads, in locals: trace writes memory the
	 * compiler cannot tell apart from these, and would read them again */
	const struct target T = *t;
	const struct vec3 pos = l->pos;
	const double side = (double)T.side;
	const bool spot = l->kind == LIGHT_SPOT, spectral = J->o->spectral;
	const long end = it->first + it->count;
	double em[3] = {w->emitted[0], w->emitted[1], w->emitted[2]}; /* the same sums in the same order */
	for (long i = it->first; i < end; i++, col = col + 1 == T.side ? (row++, 0) : col + 1) {
		/* stratified in (cos θ, φ) over the cone, or in (r², φ) over the disc */
		struct smp_stream ss = smp_start(key, (uint32_t)i); /* smp_get's dimensions 0 and 1, one key */
		double sx = ((double)col + smp_next(&ss)) / side;
		double sy = ((double)row + smp_next(&ss)) / side;
		double ph = 2 * M_PI * sy;
		struct vec3 o = pos, d;
		if (beam) {
			d = T.axis;
			double rr = T.radius * sqrt(sx);
			o = v_add(T.origin, v_add(v_scale(T.t1, rr * cos(ph)), v_scale(T.t2, rr * sin(ph))));
		} else {
			double ct = 1 - sx * (1 - T.cosmax), s2 = 1 - ct * ct;
			double st = sqrt(s2 > 0 ? s2 : 0); /* fmax(0, s2), inline (s2 is never -0) */
			d = v_add(v_scale(T.axis, ct), v_add(v_scale(T.t1, st * cos(ph)), v_scale(T.t2, st * sin(ph))));
		}
		bool covered = false;
		for (int k = 0; k < it->target && !covered; k++)
			covered = beam ? in_beam(&tg[k], o) : in_cone(&tg[k], d);
		if (covered)
			continue;
		double e[3] = {e0[0], e0[1], e0[2]};
		if (spot) {
			double k = opt_spot(l, d);
			if (k <= 0)
				continue;
			e[0] *= k, e[1] *= k, e[2] *= k;
		}
		if (spectral)
			w->band.lambda = ray_wavelength(key, (uint64_t)i, (uint64_t)T.side, e);
		for (int c = 0; c < 3; c++)
			em[c] += e[c];
		trace(w, (struct ray){o, d}, e, cutoff, 0, 0, 0, NULL);
	}
	for (int c = 0; c < 3; c++)
		w->emitted[c] = em[c];
}

/* The distinct surfaces of records r[0..nr) and footprints p[0..np) (see
 * struct span). */
static void list_distinct(struct span *sp, const struct rec *r, long nr, const struct prec *p, long np)
{
	const struct object *prev = NULL;
	sp->nd = 0;
	for (long i = 0; i < nr + np && sp->nd >= 0; i++) {
		const struct object *ob = i < nr ? r[i].obj : p[i - nr].obj;
		if (ob == prev)
			continue;
		prev = ob;
		int k = 0;
		while (k < sp->nd && sp->d[k] != ob)
			k++;
		if (k < sp->nd)
			continue;
		if (sp->nd == DISTINCT_MAX)
			sp->nd = -1;
		else
			sp->d[sp->nd++] = ob;
	}
}

/* Moves the current item's records from the stage to where they are
 * kept: when they all landed on one surface in white light (the usual
 * case) as 24-byte illum_gsplats, the surface once in the span, else
 * whole. The stage is written while tracing and read back here while in
 * cache; only what is kept reaches fresh memory (the kernel zeroes every
 * page of it first). */
static void keep_item(struct worker *w, struct span *sp)
{
	const struct rec *r = (const struct rec *)(const void *)w->stage.r;
	long n = w->stage.n;
	bool grey = n > 0;
	for (long i = 0; i < n && grey; i++)
		grey = r[i].obj == r[0].obj && r[i].s.e[0] == r[i].s.e[1] && r[i].s.e[1] == r[i].s.e[2];
	if (grey) {
		struct illum_gsplat *g = recbuf_take(&w->grecs, n);
		for (long i = 0; i < n; i++)
			g[i] = (struct illum_gsplat){r[i].s.u, r[i].s.v, r[i].s.e[0]};
		sp->g = g, sp->obj = r[0].obj;
	} else if (n > 0) {
		sp->r = memcpy(recbuf_take(&w->recs, n), r, sizeof *r * (size_t)n);
	}
	sp->nr = n;
	w->stage.n = 0;
}

/* Work item k on the worker's own buffers (a parallel_for item; ctx is the
 * workers' array). */
static void work(void *ctx, long k, int worker)
{
	struct worker *w = (struct worker *)ctx + worker;
	struct job *J = w->job;
	w->stage.n = w->stage.item0 = 0;
	w->precs.item0 = w->precs.n;
	w->recx.item0 = w->recx.n;
	if (J->o->shafts)
		run_shafts(w, &J->items[k]);
	else
		run_item(w, &J->items[k]);
	struct span *sp = &J->spans[k];
	struct prec *pc = recbuf_item(&w->precs); /* where they stay from now on */
	for (long i = 0; i < w->precs.n - w->precs.item0; i++)
		pc[i].poly.uv = (const double(*)[2])pc[i].uv;
	*sp = (struct span){NULL, NULL, NULL, 0, pc, w->precs.n - w->precs.item0,
	                    recbuf_item(&w->recx), 0, {NULL}};
	list_distinct(sp, (const struct rec *)(const void *)w->stage.r, w->stage.n, sp->p, sp->np);
	keep_item(w, sp);
	progress_step(J->o->progress, 1);
}

/* ==== maps =============================================================== */

static int by_source(const void *a, const void *b)
{
	const struct object *x = *(const struct object *const *)a, *y = *(const struct object *const *)b;
	if (x->loc.file != y->loc.file)
		return x->loc.file < y->loc.file ? -1 : 1;
	if (x->loc.line != y->loc.line)
		return x->loc.line < y->loc.line ? -1 : 1;
	if (x->loc.col != y->loc.col)
		return x->loc.col < y->loc.col ? -1 : 1;
	return x < y ? -1 : x > y;
}

static unsigned ptr_hash(const void *p)
{
	uint64_t x = (uint64_t)(uintptr_t)p;
	x ^= x >> 33;
	x *= 0xff51afd7ed558ccdull;
	x ^= x >> 33;
	return (unsigned)x;
}

/* The map of primitive o: a hash lookup (the eye pass asks at every hit). */
static int find_map(const struct lp_result *r, const struct object *o)
{
	if (!r->nslots)
		return -1;
	for (unsigned h = ptr_hash(o) & (unsigned)(r->nslots - 1);; h = (h + 1) & (unsigned)(r->nslots - 1)) {
		int k = r->slots[h];
		if (k == 0)
			return -1;
		if (r->objs[k - 1] == o)
			return k - 1;
	}
}

/* Enters r->objs[k] into the hash (which has a free slot). */
static void slot_put(struct lp_result *r, int k)
{
	unsigned h = ptr_hash(r->objs[k]) & (unsigned)(r->nslots - 1);
	while (r->slots[h])
		h = (h + 1) & (unsigned)(r->nslots - 1);
	r->slots[h] = k + 1;
}

/* Builds the hash over r->objs[0..n) (freeing any older one). */
static void index_maps(struct lp_result *r)
{
	free(r->slots);
	r->nslots = 8;
	while (r->nslots <= 2 * r->n)
		r->nslots *= 2;
	r->slots = mem_calloc((size_t)r->nslots, sizeof *r->slots);
	for (int k = 0; k < r->n; k++)
		if (k == 0 || r->objs[k - 1] != r->objs[k]) /* an object's first level */
			slot_put(r, k);
}

/* The grid for a surface: its illum_map { }, else a cell size chosen from
 * the rays that reached it (pitfall 1): per_node rays per node (0: the
 * default ILLUM_RAYS_PER_NODE) over the region where most of them landed. The region is the 5th to 95th
 * percentile of the landing points on each axis, so a few grazing rays that
 * land far away do not inflate it. */
static struct illum_spec choose_spec(const struct object *o, const struct vec3 *pts, long k, double per_node)
{
	struct illum_spec own = obj_illum(o);
	if (own.resolution > 0 || own.cell > 0)
		return own;
	double *c = mem_alloc(sizeof *c * (size_t)(k ? k : 1)), ex[3];
	for (int axis = 0; axis < 3; axis++) {
		for (long i = 0; i < k; i++)
			c[i] = v_comp(pts[i], axis);
		/* the 95th percentile, then the 5th among what lies below it */
		long i95 = (long)(0.95 * (double)(k - 1)), i05 = (long)(0.05 * (double)(k - 1));
		ex[axis] = k ? order_nth(c, k, i95) - order_nth(c, i95 + 1, i05) : 0;
	}
	free(c);
	for (int i = 0; i < 2; i++) /* two largest extents first */
		for (int j = i + 1; j < 3; j++)
			if (ex[j] > ex[i]) {
				double t = ex[i];
				ex[i] = ex[j];
				ex[j] = t;
			}
	double area = ex[0] * fmax_(ex[1], ex[0] * 1e-3);
	double cell = illum_auto_cell(0.9 * (double)k, area, per_node);
	struct illum_spec sp = {0, cell > 0 ? cell : 0.01};
	return sp;
}

/* The finest grid for a surface reached by shafts: its illum_map { }, else
 * nodes half as far apart as the narrowest tenth of the footprints are wide
 * (the densest light; coarser levels take the wider footprints), but no
 * closer than the image's pixels are there (opt:
 * finer nodes alias in the eye pass's point reads), or, when
 * most of its deposits are points (folds, silhouettes), their rule
 * (choose_spec). */
static struct illum_spec shaft_spec(const struct object *o, const struct prec *const *p, long np,
                                    const struct vec3 *pts, long k, const struct lp_opts *opt)
{
	struct illum_spec own = obj_illum(o);
	if (own.resolution > 0 || own.cell > 0)
		return own;
	double *sz = mem_alloc(sizeof *sz * (size_t)(np ? np : 1)), px = 0;
	for (long i = 0; i < np; i++)
		sz[i] = p[i]->size;
	double cell = np ? 0.5 * order_nth(sz, np, np / 10) : 0;
	/* no finer than a pixel of the image where the light lands (the eye
	 * pass reads one point per sample: a finer map only adds noise) */
	for (long i = 0; i < np && (opt->pixel_width > 0 || opt->pixel_angle > 0); i++)
		sz[i] = p[i]->px;
	if (np && (opt->pixel_width > 0 || opt->pixel_angle > 0)) {
		px = order_nth(sz, np, np / 2);
	}
	cell = fmax_(cell, px);
	free(sz);
	if (k > 16 * np) /* mostly point deposits (folds, silhouettes): their rule */
		return choose_spec(o, pts, k, 0);
	struct illum_spec sp = {0, cell > 0 && isfinite(cell) ? cell : 0.01};
	return sp;
}

/* The map level for a deposit of world size `size`: the first whose cell
 * (cell × 2^level) is more than an eighth of it, so a footprint covers at
 * most about eight cells a side and the tents blur it by at most an eighth
 * of its size (four cells a side blur smooth caustics 2-3 times more, for
 * half the cost). */
static int level_of(double size, double cell, int nl)
{
	int l = 0;
	while (l + 1 < nl && size >= 8 * cell * (double)(1L << l))
		l++;
	return l;
}

#define FOOTPRINT_MAX_CELLS 1024 /* larger footprints are deposited at their corners
                                     (deposit_levels) */

/* Deposits a surface's shaft footprints p[0..np) and point records
 * s[0..ns) (of spread sz) into the levels lv[0..nl) (lv[0] exists; cell the
 * finest level's), each at the level of its size (level_of), making levels
 * as needed: per level, all its footprints at once, then all its points
 * (illum_deposit_poly_all and illum_deposit_all fix the map's fixed-point
 * unit before any deposit, so the result is the same for any order and
 * thread count). A footprint under a quarter of a cell a side is a point
 * deposit at its centre; one touching more than FOOTPRINT_MAX_CELLS of its
 * level's cells (illum_footprint_cells: by area and edges, not bounding box; nl =
 * 1: a fixed grid) gives its energy to its corners. */
static void deposit_levels(struct illum_map **lv, const struct object *o, double cell, int nl,
                           const struct prec *const *p, long np, const struct illum_splat *s, const double *sz,
                           long ns, int threads)
{
	const struct illum_poly **pp = mem_alloc_huge(sizeof *pp * (size_t)(np ? np : 1)); /* in place (prec) */
	struct illum_splat *ps = mem_alloc_huge(sizeof *ps * (size_t)(ns + 4 * np + 1)); /* (what is written
	                                                                                    is touched) */
	/* each one's level, found once (not once a level) */
	unsigned char *lp = mem_alloc((size_t)(np + ns + 1)), *ls = lp + np;
	for (long i = 0; i < np; i++)
		lp[i] = (unsigned char)level_of(p[i]->size, cell, nl);
	for (long i = 0; i < ns; i++)
		ls[i] = (unsigned char)level_of(sz[i], cell, nl);
	for (int l = 0; l < nl; l++) {
		long n = 0, m = 0;
		for (long i = 0; i < np; i++)
			if (lp[i] == l)
				pp[n++] = &p[i]->poly;
		for (long i = 0; i < ns; i++)
			if (ls[i] == l)
				ps[m++] = s[i];
		if (n + m == 0)
			continue;
		if (!lv[l])
			lv[l] = illum_new(o, &(struct illum_spec){0, cell * (double)(1L << l)});
		if (!lv[l])
			continue;
		long nu, nv, keep = 0;
		double du, dv;
		illum_grid(lv[l], &nu, &nv, &du, &dv);
		for (long i = 0; i < n; i++) {
			const struct illum_poly *q = pp[i];
			double u0 = q->uv[0][0], u1 = u0, v0 = q->uv[0][1], v1 = v0;
			for (int c = 1; c < q->n; c++) {
				u0 = fmin_(u0, q->uv[c][0]), u1 = fmax_(u1, q->uv[c][0]);
				v0 = fmin_(v0, q->uv[c][1]), v1 = fmax_(v1, q->uv[c][1]);
			}
			if ((u1 - u0) < 0.25 * du && (v1 - v0) < 0.25 * dv) {
				/* much smaller than a cell: its tent integrals are the tents
				 * at its centre to second order, so a point deposit there */
				double cu = 0, cv = 0;
				for (int c = 0; c < q->n; c++)
					cu += q->uv[c][0] / q->n, cv += q->uv[c][1] / q->n;
				ps[m++] = (struct illum_splat){cu, cv, {q->e[0], q->e[1], q->e[2]}};
				continue;
			}
			if (illum_footprint_cells(q->uv, q->n, du, dv) <= FOOTPRINT_MAX_CELLS) {
				pp[keep++] = q;
				continue;
			}
			for (int c = 0; c < q->n; c++)
				ps[m++] = (struct illum_splat){q->uv[c][0], q->uv[c][1], {q->e[0] / q->n, q->e[1] / q->n, q->e[2] / q->n}};
		}
		illum_deposit_poly_all(lv[l], pp, keep, threads);
		illum_deposit_all(lv[l], ps, m, threads);
	}
	free(pp), free(ps), free(lp);
}

/* Record i of segment s: its surface, and its splat. */
static const struct object *seg_obj(const struct seg *s, long i)
{
	return s->g ? s->obj : s->r[i].obj;
}

static struct illum_splat seg_splat(const struct seg *s, long i)
{
	return s->g ? illum_gsplat_splat(&s->g[i]) : s->r[i].s;
}

/* One surface's records gathered for its map: segment g's records go to
 * [off[g], off[g+1]) of the arrays that are not NULL (a parallel_for item).
 * pts and psz are filled from the records' recx (all of one surface's
 * records have one, or none do: rec_has_x). */
struct gather {
	const struct seg *sg;
	const long *off;
	struct vec3 *pts;
	double *psz;
	struct illum_splat *sp;
};

static void gather_work(void *ctx, long g, int worker)
{
	(void)worker;
	const struct gather *G = ctx;
	const struct recx *x = G->sg[g].x;
	for (long i = 0, at = G->off[g]; i < G->sg[g].nr; i++, at++) {
		if (G->pts)
			G->pts[at] = x[i].p;
		if (G->psz)
			G->psz[at] = x[i].size;
		if (G->sp)
			G->sp[at] = seg_splat(&G->sg[g], i);
	}
}

/* Gives every surface reached a map and deposits the records into it: the
 * distinct surfaces through a hash, then the records grouped per surface
 * (a counting sort, keeping their order), so the work is O(records) whatever
 * the number of surfaces. Point deposits and finishing run on o->threads
 * threads; shaft footprints (precs) are spread over their cells. */
static struct lp_result *build_maps(const struct seg *sg, long nseg, const struct lp_opts *o)
{
	struct lp_result *r = mem_calloc(1, sizeof *r);
	long total = 0, ptotal = 0, t = 0;
	for (long g = 0; g < nseg; g++)
		total += sg[g].nr, ptotal += sg[g].np;
	/* the distinct surfaces (through the hash as it grows), then in source order */
	r->objs = mem_alloc(sizeof *r->objs * 16);
	int cap = 16;
	const struct object *prev = NULL;
	for (long g = 0; g < nseg; g++)
		for (long i = 0; i < (sg[g].nd >= 0 ? sg[g].nd : sg[g].nr + sg[g].np); i++) {
			const struct object *ob = sg[g].nd >= 0 ? sg[g].d[i]
			                        : i < sg[g].nr ? seg_obj(&sg[g], i) : sg[g].p[i - sg[g].nr].obj;
			bool seen = ob == prev || find_map(r, ob) >= 0;
			prev = ob;
			if (seen)
				continue;
			if (r->n == cap)
				r->objs = mem_realloc(r->objs, sizeof *r->objs * (size_t)(cap *= 2));
			r->objs[r->n++] = ob;
			if (2 * r->n >= r->nslots)
				index_maps(r);
			else
				slot_put(r, r->n - 1);
		}
	const struct object **objs = r->objs;
	int n = r->n;
	if (n > 1)
		qsort(objs, (size_t)n, sizeof *objs, by_source);
	index_maps(r);
	/* group the records per surface (counting sort by map index; one
	 * surface, the usual case, needs no index per record) */
	int *ki = n > 1 ? mem_alloc(sizeof *ki * (size_t)(total ? total : 1)) : NULL;
	long *start = mem_calloc((size_t)n + 1, sizeof *start), *fill = mem_calloc((size_t)n + 1, sizeof *fill);
	long *pstart = mem_calloc((size_t)n + 1, sizeof *pstart);
	/* one surface and point deposits only (the usual case): its map reads
	 * the records where they are, and their points are copied only when
	 * they choose its cell */
	bool inplace = n == 1 && ptotal == 0;
	struct illum_spec own = n ? obj_illum(objs[0]) : (struct illum_spec){0, 0};
	bool need_pts = !inplace || !(own.resolution > 0 || own.cell > 0);
	struct vec3 *pts = need_pts ? mem_alloc(sizeof *pts * (size_t)(total ? total : 1)) : NULL;
	struct illum_splat *sp = inplace ? NULL : mem_alloc(sizeof *sp * (size_t)(total ? total : 1));
	double *psz = inplace ? NULL : mem_alloc(sizeof *psz * (size_t)(total ? total : 1));
	const struct prec **pr = mem_alloc(sizeof *pr * (size_t)(ptotal ? ptotal : 1)); /* by surface, in order */
	t = 0;
	for (long g = 0; g < nseg && ki; g++) {
		if (sg[g].g) { /* one surface */
			int k = sg[g].nr ? find_map(r, sg[g].obj) : 0;
			for (long i = 0; i < sg[g].nr; i++)
				ki[t++] = k;
			start[k + 1] += sg[g].nr;
			continue;
		}
		for (long i = 0; i < sg[g].nr; i++, t++)
			start[(ki[t] = find_map(r, sg[g].r[i].obj)) + 1]++;
	}
	if (!ki && n)
		start[1] = total;
	for (long g = 0; g < nseg && n > 1; g++) /* (one surface: every record is its) */
		for (long i = 0; i < sg[g].np; i++)
			pstart[find_map(r, sg[g].p[i].obj) + 1]++;
	if (n == 1)
		pstart[1] = ptotal;
	for (int k = 0; k < n; k++)
		start[k + 1] += start[k], pstart[k + 1] += pstart[k];
	t = 0;
	struct illum_run *runs = NULL;
	if (inplace) {
		runs = mem_alloc(sizeof *runs * (size_t)nseg);
		for (long g = 0; g < nseg; g++)
			runs[g] = sg[g].g ? (struct illum_run){sg[g].g, sg[g].nr, sizeof *sg[g].g, true}
			                  : (struct illum_run){sg[g].r, sg[g].nr, sizeof *sg[g].r, false};
	}
	/* which surfaces' records have their recx (rec_has_x): pts and psz are
	 * read only for those (choose_spec and shaft_spec return a surface's own
	 * grid at once; sizes are read only with shafts, where all have one) */
	bool *hasx = mem_alloc(sizeof *hasx * (size_t)(n ? n : 1));
	for (int k = 0; k < n; k++)
		hasx[k] = rec_has_x(o, objs[k]);
	if (!ki && (pts || sp)) { /* one surface: the segments' records in order, on the threads */
		long *off = mem_alloc(sizeof *off * (size_t)(nseg + 1));
		off[0] = 0;
		for (long g = 0; g < nseg; g++)
			off[g + 1] = off[g] + sg[g].nr;
		bool x = n && hasx[0];
		parallel_for(nseg, o->threads, gather_work, &(struct gather){sg, off, x ? pts : NULL, x ? psz : NULL, sp});
		if (!x && psz)
			memset(psz, 0, sizeof *psz * (size_t)total);
		free(off);
	}
	for (long g = 0; g < nseg && ki; g++) {
		const struct recx *x = sg[g].x;
		for (long i = 0; i < sg[g].nr; i++, t++) {
			int k = ki[t];
			long at = start[k] + fill[k]++;
			if (hasx[k])
				pts[at] = x->p, psz[at] = x->size, x++;
			else
				pts[at] = v3(0, 0, 0), psz[at] = 0;
			sp[at] = seg_splat(&sg[g], i);
		}
	}
	free(hasx);
	memset(fill, 0, sizeof *fill * ((size_t)n + 1));
	for (long g = 0; g < nseg; g++)
		for (long i = 0; i < sg[g].np; i++) {
			int k = n > 1 ? find_map(r, sg[g].p[i].obj) : 0;
			pr[pstart[k] + fill[k]++] = &sg[g].p[i];
		}
	struct lp_result *out = mem_calloc(1, sizeof *out);
	int cap2 = n ? n : 1;
	out->objs = mem_alloc(sizeof *out->objs * (size_t)cap2);
	out->maps = mem_alloc(sizeof *out->maps * (size_t)cap2);
	out->specs = mem_alloc(sizeof *out->specs * (size_t)cap2);
	out->level = mem_alloc(sizeof *out->level * (size_t)cap2);
	double per_node = o->spectral ? 3 * ILLUM_RAYS_PER_NODE : 0; /* see lp_opts.spectral */
	for (int k = 0; k < n; k++) {
		long np = pstart[k + 1] - pstart[k], nr = start[k + 1] - start[k];
		struct illum_map *lv[LP_LEVELS] = {NULL};
		struct illum_spec spec = np ? shaft_spec(objs[k], pr + pstart[k], np, pts + start[k], nr, o)
		                            : choose_spec(objs[k], pts ? pts + start[k] : NULL, nr, per_node);
		int nl = np && spec.resolution == 0 ? LP_LEVELS : 1;
		lv[0] = illum_new(objs[k], &spec);
		if (!lv[0] && !out->nomap)
			out->nomap = objs[k];
		if (lv[0] && inplace)
			illum_deposit_runs(lv[0], runs, nseg, o->threads);
		else if (lv[0] && nl == 1 && np == 0)
			illum_deposit_all(lv[0], sp + start[k], nr, o->threads);
		else if (lv[0])
			deposit_levels(lv, objs[k], spec.cell, nl, pr + pstart[k], np, sp + start[k], psz + start[k], nr,
			               o->threads);
		for (int l = 0; l < nl; l++) {
			if (l > 0 && !lv[l])
				continue;
			if (lv[l])
				illum_finish_mt(lv[l], o->discard_isolated && !o->shafts, NULL, o->threads);
			if (out->n == cap2) {
				cap2 *= 2;
				out->objs = mem_realloc(out->objs, sizeof *out->objs * (size_t)cap2);
				out->maps = mem_realloc(out->maps, sizeof *out->maps * (size_t)cap2);
				out->specs = mem_realloc(out->specs, sizeof *out->specs * (size_t)cap2);
				out->level = mem_realloc(out->level, sizeof *out->level * (size_t)cap2);
			}
			out->objs[out->n] = objs[k];
			out->maps[out->n] = lv[l];
			out->specs[out->n] = l ? (struct illum_spec){0, spec.cell * (double)(1L << l)} : spec;
			out->level[out->n++] = l;
		}
	}
	free(r->objs), free(r->slots), free(r);
	r = out;
	index_maps(r);
	free(ki), free(start), free(fill), free(pstart), free(pts), free(sp), free(psz), free(pr), free(runs);
	return r;
}

/* ==== driver ============================================================= */

/* POV-Ray's lights (legacy model) do not fall off with distance: the eye
 * pass takes irradiance I·cosθ (times the fade) at any distance, and
 * POV-Ray's photons are given the energy that reproduces it at the target.
 * So for a point or spot light the light pass, which spreads flux
 * physically (I·cosθ/d²), shoots at a target with I·d²·fade(d), d the
 * distance to the target's centre: its caustics then match the direct
 * light there. Physical lights, parallel lights and unbounded targets: 1. */
static double legacy_gain(const struct scene *s, const struct light *l, struct bbox bb)
{
	if (!s->legacy_lights || l->kind == LIGHT_PARALLEL || !bbox_finite(bb))
		return 1;
	double d = v_len(v_sub(bbox_centre(bb), l->pos));
	double g = d * d;
	if (l->fade_distance > 0) {
		double fp = l->fade_power > 0 ? l->fade_power : 1;
		g *= 2 / (1 + pow(d / l->fade_distance, fp));
	}
	return fmax_(g, 1e-12);
}

/* Shafts: target t grown by 1.5 rows of its grid (in sx, the grid's
 * equal-area coordinate), so the object's outline lies inside the grid,
 * not on its last corner row. A cone or beam fitted to a sphere touches it
 * along that row, whose corner rays then all just miss, and a shaft split
 * at the outline deposits its corners' quarters: the ones that missed
 * would lose light that reached the sphere, always in the same direction.
 * Inside the grid, a split shaft's corners err both ways. */
static void widen(struct target *t)
{
	double f = (double)t->side / ((double)t->side - 1.5);
	if (t->cosmax == 1) { /* a beam: sx is r² */
		t->radius *= sqrt(f);
		t->omega = M_PI * t->radius * t->radius;
	} else if (t->cosmax > -1) { /* a cone: sx is 1 − cos θ */
		t->cosmax = fmax_(-1, 1 - (1 - t->cosmax) * f);
		t->omega = 2 * M_PI * (1 - t->cosmax);
	}
}

/* Cones and ray counts for every light; returns the number of work items. */
static long plan(struct job *J)
{
	const struct scene *s = J->s;
	long nitems = 0, capitems = 0;
	for (int li = 0; li < s->nlights; li++) {
		const struct light *l = &s->lights[li];
		struct target *tg = mem_calloc((size_t)(s->nobjects ? s->nobjects : 1), sizeof *tg);
		int nt = 0;
		double total = 0;
		struct vec3 D = v_sub(l->point_at, l->pos);
		D = v_len(D) > 0 ? v_norm(D) : v3(0, -1, 0);
		for (int i = 0; i < s->nobjects; i++) {
			if (!J->o->aim_all && !is_specular(s, s->objects[i]))
				continue;
			/* aimed at a sphere round the object (a sphere's own: the box's
			 * would send two rays in three past it) */
			struct bbox bb = shape_bounds(s->objects[i]);
			struct vec3 c;
			double r;
			bool bounded = shape_bsphere(s->objects[i], &c, &r);
			if (l->kind != LIGHT_PARALLEL)
				tg[nt] = cone_to(l->pos, bounded, c, r, bb, !J->o->shafts);
			else if (bounded)
				tg[nt] = beam_to(s, D, c, r);
			else {
				struct bbox e = scene_extent(s);
				tg[nt] = beam_to(s, D, bbox_centre(e), bbox_radius(e));
				if (!J->clipped)
					J->clipped = s->objects[i];
			}
			tg[nt].gain = legacy_gain(s, l, bb);
			total += tg[nt++].omega;
		}
		J->targets[li] = tg;
		J->ntargets[li] = nt;
		for (int k = 0; k < nt; k++) {
			double share = (double)J->o->rays * tg[k].omega / total;
			/* shafts: a grid cell costs about two rays (a corner, its
			 * centre) before any subdivision */
			tg[k].side = (long)fmax_(J->o->shafts ? 2 : 1, floor(sqrt(J->o->shafts ? share / 2 : share) + 0.5));
			if (J->o->shafts)
				widen(&tg[k]);
			long nr = J->o->shafts ? tg[k].side : tg[k].side * tg[k].side;
			long chunk = J->o->shafts ? (4 * CHUNK + tg[k].side - 1) / tg[k].side : CHUNK; /* rows */
			for (long f = 0; f < nr; f += chunk) {
				if (nitems == capitems)
					J->items = mem_realloc(J->items, sizeof *J->items * (size_t)(capitems = capitems ? capitems * 2 : 64));
				J->items[nitems++] = (struct item){li, k, f, nr - f < chunk ? nr - f : chunk};
			}
		}
	}
	return nitems;
}

static struct lp_result *run_once(const struct scene *s, const struct bvh *b, const struct mat_cache *mc,
                                  const struct lp_opts *o, struct lp_stats *st)
{
	struct job J;
	memset(&J, 0, sizeof J);
	J.s = s, J.b = b, J.mc = mc, J.o = o;
	J.band = (struct band){o->channel, 0};
	J.targets = mem_calloc((size_t)(s->nlights ? s->nlights : 1), sizeof *J.targets);
	J.ntargets = mem_calloc((size_t)(s->nlights ? s->nlights : 1), sizeof *J.ntargets);
	J.nitems = plan(&J);
	J.spans = mem_calloc((size_t)(J.nitems ? J.nitems : 1), sizeof *J.spans);
	char what[64], round[32] = "";
	if (o->tolerance > 0) /* a round of the progressive pass */
		snprintf(round, sizeof round, ", %ld rays", o->rays);
	snprintf(what, sizeof what, "light pass%s%s", o->channel < 0 ? "" : o->channel == 0 ? " R"
	         : o->channel == 1 ? " G" : " B", round);
	progress_begin(o->progress, what, J.nitems);
	int nt = o->threads > 0 ? o->threads : 1;
	struct worker *ws = mem_calloc((size_t)nt, sizeof *ws);
	for (int i = 0; i < nt; i++)
		ws[i].job = &J, ws[i].stage.sz = ws[i].recs.sz = sizeof(struct rec), ws[i].recx.sz = sizeof(struct recx),
		ws[i].grecs.sz = sizeof(struct illum_gsplat), ws[i].precs.sz = sizeof(struct prec);
	parallel_for(J.nitems, nt, work, ws);
	progress_end(o->progress);
	struct recbuf *bufs = mem_calloc(4 * (size_t)nt, sizeof *bufs); /* recs, grecs, recx, precs */
	struct lp_stats acc;
	memset(&acc, 0, sizeof acc);
	for (int i = 0; i < nt; i++) {
		bufs[i] = ws[i].recs, bufs[nt + i] = ws[i].grecs, bufs[2 * nt + i] = ws[i].recx,
		bufs[3 * nt + i] = ws[i].precs;
		recbuf_free(&ws[i].stage);
		free(ws[i].lands.l);
		acc.segments += ws[i].segments;
		acc.rays += ws[i].primaries;
		for (int c = 0; c < 3; c++) {
			acc.emitted[c] += ws[i].emitted[c];
			acc.landed[c] += ws[i].deposited[c];
			acc.direct[c] += ws[i].direct[c];
			acc.absorbed[c] += ws[i].absorbed[c];
			acc.escaped[c] += ws[i].escaped[c];
			acc.cut[c] += ws[i].cut[c];
		}
	}
	struct seg *sg = mem_alloc(sizeof *sg * (size_t)(J.nitems ? J.nitems : 1));
	for (long k = 0; k < J.nitems; k++) {
		const struct span *p = &J.spans[k];
		sg[k] = (struct seg){p->r, p->g, p->obj, p->nr, p->x, p->p, p->np, p->nd, p->d};
	}
	struct lp_result *r = J.nitems > 0 ? build_maps(sg, J.nitems, o) : NULL;
	free(sg), free(J.spans);
	for (long k = 0; k < J.nitems && !o->shafts; k++)
		acc.rays += J.items[k].count;
	for (int k = 0; r && k < r->n; k++) {
		double tot[3];
		if (!r->maps[k])
			continue;
		illum_total(r->maps[k], tot);
		for (int c = 0; c < 3; c++)
			acc.deposited[c] += tot[c];
		acc.maps += r->level[k] == 0; /* surfaces, not their levels */
		acc.map_bytes += illum_memory(r->maps[k]);
	}
	acc.clipped = J.clipped;
	acc.nomap = r ? r->nomap : NULL;
	if (st)
		*st = acc;
	for (int i = 0; i < nt; i++)
		for (int k = 0; k < 4; k++)
			recbuf_free(&bufs[k * nt + i]);
	for (int li = 0; li < s->nlights; li++)
		free(J.targets[li]);
	free(bufs), free(ws), free(J.items), free(J.targets), free(J.ntargets);
	return r;
}

#define TOL_START 16384L    /* rays per light of a tolerance's first round */
#define TOL_MAX 67108864L   /* and the most it goes to */

struct lp_result *lp_run(const struct scene *s, const struct bvh *b, const struct mat_cache *mc,
                         const struct lp_opts *o, struct lp_stats *st)
{
	if (!(o->tolerance > 0))
		return run_once(s, b, mc, o, st);
	/* progressive: rounds of 4× more rays until this round's error,
	 * estimated from the difference between its maps and the previous
	 * round's, is at most the tolerance */
	struct lp_opts oo = *o;
	struct lp_stats ls;
	oo.rays = TOL_START;
	struct lp_result *prev = run_once(s, b, mc, &oo, &ls), *r = NULL;
	long long shot = ls.rays;
	int rounds = 1;
	double d = 1;
	for (;;) {
		oo.rays *= 4;
		r = run_once(s, b, mc, &oo, &ls);
		shot += ls.rays;
		rounds++;
		/* if a round cuts the error r-fold, the difference d ≥ (r − 1)·error:
		 * shafts' error falls at least 2.5-fold a round (refs A, B, C and the
		 * fold ring, docs/methods.md), point deposits' noise 2-fold */
		d = lp_difference(r, prev) / (o->shafts ? 1.5 : 1);
		lp_free(prev);
		if (d <= o->tolerance || oo.rays >= TOL_MAX)
			break;
		prev = r;
	}
	ls.rays = shot;
	ls.tol_estimate = d;
	ls.tol_rounds = rounds;
	ls.tol_rays = oo.rays;
	if (st)
		*st = ls;
	return r;
}

void lp_merge(struct lp_result *dst, const struct lp_result *src, bool discard_isolated)
{
	for (int k = 0; k < src->n; k++) {
		int i = find_map(dst, src->objs[k]);
		if (i >= 0 && dst->maps[i] && src->maps[k]) {
			illum_merge(dst->maps[i], src->maps[k]);
			illum_finish(dst->maps[i], discard_isolated, NULL);
		}
	}
}

/* ==== the error estimate (tolerance) ====================================== */

/* Sums of energy over bins of bu × bv in (u,v): a hash of (i, j) → sum. */
struct binsum {
	int64_t *key;
	double *val;
	long n, cap;     /* used, allocated (power of two) */
	double bu, bv;   /* bin size */
	double u0, u1, v0, v1; /* the region compared */
	double du, dv;   /* the current level's node spacing */
	double sign;     /* +1 for the first result, −1 for the second */
};

static void bin_add(struct binsum *B, double u, double v, double e)
{
	if (!(u >= B->u0 && u < B->u1 && v >= B->v0 && v < B->v1))
		return; /* the faint far field is left out, as the references leave it */
	double fi = floor(u / B->bu), fj = floor(v / B->bv);
	if (!(fabs(fi) < 1e9 && fabs(fj) < 1e9))
		return;
	if (2 * (B->n + 1) > B->cap) {
		struct binsum old = *B;
		B->cap = B->cap ? B->cap * 2 : 1024;
		B->key = mem_alloc(sizeof *B->key * (size_t)B->cap);
		B->val = mem_calloc((size_t)B->cap, sizeof *B->val);
		for (long i = 0; i < B->cap; i++)
			B->key[i] = INT64_MIN;
		B->n = 0;
		for (long i = 0; i < old.cap; i++)
			if (old.key[i] != INT64_MIN) {
				uint64_t h = (uint64_t)old.key[i] * 0x9E3779B97F4A7C15ull;
				long k = (long)(h >> 20) & (B->cap - 1);
				while (B->key[k] != INT64_MIN)
					k = (k + 1) & (B->cap - 1);
				B->key[k] = old.key[i], B->val[k] = old.val[i], B->n++;
			}
		free(old.key), free(old.val);
	}
	int64_t key = (int64_t)fi * 2000000000LL + (int64_t)fj;
	uint64_t h = (uint64_t)key * 0x9E3779B97F4A7C15ull;
	long k = (long)(h >> 20) & (B->cap - 1);
	while (B->key[k] != INT64_MIN && B->key[k] != key)
		k = (k + 1) & (B->cap - 1);
	if (B->key[k] == INT64_MIN)
		B->key[k] = key, B->n++;
	B->val[k] += B->sign * e;
}

/* A node's energy (all channels) spread over its bilinear tent, 4×4
 * points, into the bins. */
static void bin_node(void *ctx, const struct illum_node *n)
{
	struct binsum *B = ctx;
	double e = (n->irr[0] + n->irr[1] + n->irr[2]) * n->area;
	static const double at[4] = {-0.75, -0.25, 0.25, 0.75}, w[4] = {0.25, 0.75, 0.75, 0.25};
	for (int i = 0; i < 4; i++)
		for (int j = 0; j < 4; j++)
			bin_add(B, n->u + at[i] * B->du, n->v + at[j] * B->dv, e * w[i] * w[j] / 4);
}

struct wpt {
	double x, w;
};

static int cmp_wpt(const void *a, const void *b)
{
	double x = ((const struct wpt *)a)->x, y = ((const struct wpt *)b)->x;
	return x < y ? -1 : x > y;
}

struct extent {
	struct wpt *p[2];
	long n, cap;
};

static void extent_node(void *ctx, const struct illum_node *n)
{
	struct extent *X = ctx;
	if (X->n == X->cap) {
		X->cap = X->cap ? X->cap * 2 : 1024;
		for (int a = 0; a < 2; a++)
			X->p[a] = mem_realloc(X->p[a], sizeof *X->p[a] * (size_t)X->cap);
	}
	double e = n->energy[0] + n->energy[1] + n->energy[2];
	X->p[0][X->n] = (struct wpt){n->u, e};
	X->p[1][X->n++] = (struct wpt){n->v, e};
}

/* The energy-weighted 2 %–98 % range [*lo, *hi] of p[0..n). */
static void wrange(struct wpt *p, long n, double *lo, double *hi)
{
	double tot = 0, acc = 0;
	qsort(p, (size_t)n, sizeof *p, cmp_wpt);
	for (long i = 0; i < n; i++)
		tot += p[i].w;
	*lo = *hi = n ? p[0].x : 0;
	bool have_lo = false;
	for (long i = 0; i < n; i++) {
		acc += p[i].w;
		if (!have_lo && acc >= 0.05 * tot)
			*lo = p[i].x, have_lo = true;
		if (acc <= 0.95 * tot)
			*hi = p[i].x;
	}
}

/* Adds every level of o in r into B with sign. */
static void bin_levels(struct binsum *B, const struct lp_result *r, const struct object *o, double sign)
{
	int k = find_map(r, o);
	B->sign = sign;
	for (; k >= 0 && k < r->n && r->objs[k] == o; k++) {
		if (!r->maps[k])
			continue;
		long nu, nv;
		illum_grid(r->maps[k], &nu, &nv, &B->du, &B->dv);
		illum_each(r->maps[k], bin_node, B);
	}
}

double lp_finest_cell(const struct lp_result *r)
{
	double c = 0;
	for (int k = 0; r && k < r->n; k++)
		if (r->maps[k] && r->specs[k].cell > 0 && (c == 0 || r->specs[k].cell < c))
			c = r->specs[k].cell;
	return c;
}

double lp_difference(const struct lp_result *a, const struct lp_result *b)
{
	double num = 0, den = 0;
	for (int k = 0; a && k < a->n; k++) {
		if (k > 0 && a->objs[k - 1] == a->objs[k])
			continue; /* one object at a time, all its levels */
		const struct object *o = a->objs[k];
		struct extent X = {{NULL, NULL}, 0, 0};
		for (int j = k; j < a->n && a->objs[j] == o; j++)
			if (a->maps[j])
				illum_each(a->maps[j], extent_node, &X);
		struct binsum B;
		memset(&B, 0, sizeof B);
		wrange(X.p[0], X.n, &B.u0, &B.u1);
		wrange(X.p[1], X.n, &B.v0, &B.v1);
		free(X.p[0]), free(X.p[1]);
		double eu = B.u1 - B.u0, ev = B.v1 - B.v0;
		B.u0 -= 0.02 * eu, B.u1 += 0.02 * eu, B.v0 -= 0.02 * ev, B.v1 += 0.02 * ev;
		long nu, nv;
		double du = 1, dv = 1;
		if (a->maps[k])
			illum_grid(a->maps[k], &nu, &nv, &du, &dv);
		B.bu = fmax_(eu / 48, du), B.bv = fmax_(ev / 48, dv);
		bin_levels(&B, a, o, 1);
		for (long i = 0; i < B.cap; i++)
			if (B.key[i] != INT64_MIN)
				den += B.val[i];
		bin_levels(&B, b, o, -1);
		for (long i = 0; i < B.cap; i++)
			if (B.key[i] != INT64_MIN)
				num += fabs(B.val[i]);
		free(B.key), free(B.val);
	}
	for (int k = 0; b && k < b->n; k++) /* what b lit and a did not */
		if (b->maps[k] && (!a || find_map(a, b->objs[k]) < 0)) {
			double t[3];
			illum_total(b->maps[k], t);
			num += t[0] + t[1] + t[2];
		}
	return den > 0 ? num / den : num > 0 ? 1 : 0;
}

const struct illum_map *lp_map(const struct lp_result *r, const struct object *o)
{
	return lp_map_level(r, o, 0);
}

const struct illum_map *lp_map_level(const struct lp_result *r, const struct object *o, int level)
{
	int k = r ? find_map(r, o) : -1;
	for (; k >= 0 && k < r->n && r->objs[k] == o; k++)
		if (r->level[k] == level)
			return r->maps[k];
	return NULL;
}

void lp_lookup(const struct lp_result *r, const struct object *o, double u, double v, double out[3])
{
	out[0] = out[1] = out[2] = 0;
	int k = r ? find_map(r, o) : -1;
	for (; k >= 0 && k < r->n && r->objs[k] == o; k++) {
		double e[3] = {0, 0, 0};
		if (r->maps[k])
			illum_lookup(r->maps[k], u, v, e);
		out[0] += e[0], out[1] += e[1], out[2] += e[2];
	}
}

void lp_each_map(const struct lp_result *r, void (*fn)(void *ctx, const struct object *o, int level,
                 const struct illum_map *m), void *ctx)
{
	for (int k = 0; r && k < r->n; k++)
		if (r->maps[k])
			fn(ctx, r->objs[k], r->level[k], r->maps[k]);
}

void lp_free(struct lp_result *r)
{
	if (!r)
		return;
	for (int k = 0; k < r->n; k++)
		illum_free(r->maps[k]);
	free(r->maps);
	free(r->specs);
	free(r->level);
	free(r->slots);
	free(r->objs);
	free(r);
}

/* ==== --save-maps / --load-maps ========================================== */

/* File layout (docs/design.md §4, "Map files"): little-endian whatever
 * the machine, no padding. A header: the magic "ARVOMAPS", uint32 format
 * version (MAP_FORMAT), 16 bytes of the arvo version that wrote it (NUL
 * padded), uint64 hash of the scene (lp_scene_hash), int32 passes, int32
 * primitives in the scene; per pass int32 maps; per map int32 primitive
 * index (depth-first over the scene's object tree), int32 resolution,
 * double cell, int64 nodes, then per node int64 i, int64 j, double
 * energy[3]. A surface's levels (shafts) are consecutive maps of the same
 * primitive, finest first. Loading deposits each energy exactly on its node
 * (a deposit on a node gives it all) and finishes the maps again. Format 1
 * ("ARVOMAP1", native byte order, no version or hash) is refused. */

#define MAP_FORMAT 2u

/* ---- little-endian fields ---- */

static void put_u32(FILE *f, uint32_t v)
{
	unsigned char b[4];
	for (int i = 0; i < 4; i++)
		b[i] = (unsigned char)(v >> (8 * i));
	fwrite(b, 4, 1, f);
}

static void put_u64(FILE *f, uint64_t v)
{
	unsigned char b[8];
	for (int i = 0; i < 8; i++)
		b[i] = (unsigned char)(v >> (8 * i));
	fwrite(b, 8, 1, f);
}

static void put_f64(FILE *f, double d)
{
	uint64_t v;
	memcpy(&v, &d, 8);
	put_u64(f, v);
}

static int get_u32(FILE *f, uint32_t *v)
{
	unsigned char b[4];
	if (fread(b, 4, 1, f) != 1)
		return 0;
	*v = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
	return 1;
}

static int get_i32(FILE *f, int32_t *v)
{
	uint32_t u;
	if (!get_u32(f, &u))
		return 0;
	memcpy(v, &u, 4);
	return 1;
}

static int get_u64(FILE *f, uint64_t *v)
{
	uint32_t lo, hi;
	if (!get_u32(f, &lo) || !get_u32(f, &hi))
		return 0;
	*v = (uint64_t)hi << 32 | lo;
	return 1;
}

static int get_i64(FILE *f, int64_t *v)
{
	uint64_t u;
	if (!get_u64(f, &u))
		return 0;
	memcpy(v, &u, 8);
	return 1;
}

static int get_f64(FILE *f, double *d)
{
	uint64_t u;
	if (!get_u64(f, &u))
		return 0;
	memcpy(d, &u, 8);
	return 1;
}

/* ---- what the maps belong to ---- */

/* FNV-1a over the scene as --dump-scene prints it, without what the light
 * pass does not read: the scene's name, the camera block and source
 * positions ("@line:col"), so moving a comment or the camera keeps the
 * maps. What it covers: objects, their transforms, textures and interiors,
 * lights, global settings (illumination included) and the background. */
uint64_t lp_scene_hash(const struct scene *s)
{
	char *text = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&text, &len);
	if (!f)
		return 0;
	scene_dump(f, s);
	fclose(f);
	uint64_t h = 0xcbf29ce484222325ull;
	bool camera = false;
	for (char *line = text; line && *line;) {
		char *end = strchr(line, '\n');
		size_t n = end ? (size_t)(end - line) : strlen(line);
		bool skip = line == text; /* scene "name" version ... */
		if (!strncmp(line, "camera ", 7))
			camera = true;
		else if (strncmp(line, "  ", 2) != 0)
			camera = false;
		skip |= camera;
		for (size_t i = 0; i < n && !skip; i++) {
			if (line[i] == '@') /* @line:col */
				while (i + 1 < n && line[i + 1] != ' ')
					i++;
			else
				h = (h ^ (unsigned char)line[i]) * 0x100000001b3ull;
		}
		line = end ? end + 1 : NULL;
	}
	free(text);
	return h;
}

struct prims {
	const struct object **o; /* primitives in depth-first order */
	int n, cap;
};

static void collect(struct prims *p, const struct object *o)
{
	if (o->kind >= OBJ_FIRST_CSG) {
		for (int i = 0; i < o->g.csg.n; i++)
			collect(p, o->g.csg.kids[i]);
		return;
	}
	if (p->n == p->cap)
		p->o = mem_realloc(p->o, sizeof *p->o * (size_t)(p->cap = p->cap ? p->cap * 2 : 64));
	p->o[p->n++] = o;
}

static struct prims scene_prims(const struct scene *s)
{
	struct prims p = {NULL, 0, 0};
	for (int i = 0; i < s->nobjects; i++)
		collect(&p, s->objects[i]);
	return p;
}

struct saver {
	FILE *f;
	long long nodes; /* written */
};

static void save_node(void *ctx, const struct illum_node *n)
{
	struct saver *sv = ctx;
	if (n->isolated)
		return;
	put_u64(sv->f, (uint64_t)(int64_t)n->i);
	put_u64(sv->f, (uint64_t)(int64_t)n->j);
	for (int c = 0; c < 3; c++)
		put_f64(sv->f, n->energy[c]);
	sv->nodes++;
}

static void count_node(void *ctx, const struct illum_node *n)
{
	if (!n->isolated)
		(*(long long *)ctx)++;
}

int lp_save(struct lp_result *const *r, int npasses, const struct scene *s, const char *path, struct diag *dg)
{
	struct prims P = scene_prims(s);
	char tmp[4096];
	int fd = out_tmp_create(path, tmp, sizeof tmp);
	FILE *f = fd < 0 ? NULL : fdopen(fd, "wb");
	if (!f) {
		int e = errno;
		if (fd >= 0) {
			close(fd);
			out_tmp_finish(tmp, path, 0);
		}
		free(P.o);
		return diag_fail(dg, FAIL_CREATE, srcloc_none(), "cannot create '%s': %s", path, strerror(e));
	}
	char version[16] = {0};
	strncpy(version, ARVO_VERSION, sizeof version - 1);
	fwrite("ARVOMAPS", 8, 1, f);
	put_u32(f, MAP_FORMAT);
	fwrite(version, sizeof version, 1, f);
	put_u64(f, lp_scene_hash(s));
	put_u32(f, (uint32_t)npasses);
	put_u32(f, (uint32_t)P.n);
	for (int p = 0; p < npasses; p++) {
		int32_t nm = r[p] ? r[p]->n : 0;
		put_u32(f, (uint32_t)nm);
		for (int k = 0; k < nm; k++) {
			int32_t idx = -1;
			for (int i = 0; i < P.n; i++)
				if (P.o[i] == r[p]->objs[k])
					idx = i;
			long long cnt = 0;
			if (r[p]->maps[k])
				illum_each(r[p]->maps[k], count_node, &cnt);
			int32_t res = r[p]->specs[k].resolution;
			double cell = r[p]->specs[k].cell;
			int64_t nodes = cnt;
			put_u32(f, (uint32_t)idx);
			put_u32(f, (uint32_t)res);
			put_f64(f, cell);
			put_u64(f, (uint64_t)nodes);
			struct saver sv = {f, 0};
			if (r[p]->maps[k])
				illum_each(r[p]->maps[k], save_node, &sv);
		}
	}
	free(P.o);
	int bad = fflush(f) != 0 || ferror(f);
	int e = errno;
	if (fclose(f) != 0 && !bad)
		bad = 1, e = errno;
	if (out_tmp_finish(tmp, path, !bad) != 0)
		bad = 1, e = errno;
	if (bad)
		return diag_fail(dg, FAIL_WRITE, srcloc_none(), "cannot write '%s': %s", path,
		                 e ? strerror(e) : "write error");
	return 0;
}

/* Reads and checks the header: NULL, or why the file is refused (in err). */
static const char *check_header(FILE *f, const struct scene *s, int nprims, const char *path,
                                int32_t *passes, char *err, size_t n)
{
	char magic[8], version[17] = {0};
	uint32_t format = 1; /* ARVOMAP1's, which does not say it */
	uint64_t hash;
	int32_t prims;
	if (fread(magic, 8, 1, f) != 1 || (memcmp(magic, "ARVOMAPS", 8) && memcmp(magic, "ARVOMAP1", 8)))
		snprintf(err, n, "'%s' is not an arvo map file", path);
	else if (memcmp(magic, "ARVOMAP1", 8) && !get_u32(f, &format))
		snprintf(err, n, "'%s' is damaged (cut short or corrupt)", path);
	else if (format != MAP_FORMAT)
		snprintf(err, n, "'%s' is a map file of format %u; this arvo reads format %u "
		         "(save the maps again with --save-maps)", path, format, MAP_FORMAT);
	else if (fread(version, 16, 1, f) != 1 || strcmp(version, ARVO_VERSION) != 0)
		snprintf(err, n, "'%s' was saved by arvo %.16s; this is arvo %s (save the maps again "
		         "with --save-maps)", path, version, ARVO_VERSION);
	else if (!get_u64(f, &hash) || hash != lp_scene_hash(s) || !get_i32(f, passes) ||
	         !get_i32(f, &prims) || prims != nprims)
		snprintf(err, n, "'%s' was saved for another scene: the objects, lights or settings "
		         "differ (save the maps again with --save-maps)", path);
	else if (*passes < 0 || *passes > 3)
		snprintf(err, n, "'%s' is damaged", path);
	else
		return NULL;
	return err;
}

/* Is a node saved in a map file one the map can hold? Bounded axes have
 * nodes 0..n-1; unbounded ones stay within the reach of int tile indices;
 * energies are finite and not negative. */
static bool node_ok(const struct illum_map *m, int64_t i, int64_t j, const double e[3])
{
	long nu, nv;
	illum_grid(m, &nu, &nv, NULL, NULL);
	const int64_t reach = (int64_t)1 << 30;
	if (nu > 0 ? (i < 0 || i >= nu) : (i < -reach || i > reach))
		return false;
	if (nv > 0 ? (j < 0 || j >= nv) : (j < -reach || j > reach))
		return false;
	for (int c = 0; c < 3; c++)
		if (!(e[c] >= 0 && e[c] <= 1e30))
			return false;
	return true;
}

/* Reads the nodes of map k of r (header fields already past); 0 when the
 * file is damaged. */
static int load_map(FILE *f, struct lp_result *r, int k, const struct prims *P, bool discard_isolated)
{
	int32_t idx, res;
	double cell;
	int64_t nodes;
	if (!get_i32(f, &idx) || !get_i32(f, &res) || !get_f64(f, &cell) || !get_i64(f, &nodes) ||
	    idx < 0 || idx >= P->n || nodes < 0 || !(cell >= 0 && cell < 1e30))
		return 0;
	r->n = k + 1;
	r->objs[k] = P->o[idx];
	r->level[k] = k > 0 && r->objs[k - 1] == r->objs[k] ? r->level[k - 1] + 1 : 0;
	r->specs[k] = (struct illum_spec){res, cell};
	r->maps[k] = illum_new(P->o[idx], &r->specs[k]);
	if (!r->maps[k])
		return 0;
	for (int64_t q = 0; q < nodes; q++) {
		int64_t i, j;
		double e[3], u, v;
		if (!get_i64(f, &i) || !get_i64(f, &j) || !get_f64(f, &e[0]) || !get_f64(f, &e[1]) ||
		    !get_f64(f, &e[2]) || !node_ok(r->maps[k], i, j, e))
			return 0;
		illum_node_uv(r->maps[k], (long)i, (long)j, &u, &v);
		illum_deposit(r->maps[k], u, v, e);
	}
	illum_finish(r->maps[k], discard_isolated, NULL);
	return 1;
}

int lp_load(struct lp_result **out, const struct scene *s, const char *path, bool discard_isolated,
            struct diag *dg)
{
	char err[768];
	struct prims P = scene_prims(s);
	FILE *f = fopen(path, "rb");
	int n = 0;
	int32_t passes = 0;
	if (!f) {
		int e = errno;
		free(P.o);
		return -diag_fail(dg, FAIL_INPUT, srcloc_none(), "cannot open '%s': %s", path, strerror(e));
	}
	if (check_header(f, s, P.n, path, &passes, err, sizeof err))
		goto refused;
	for (int p = 0; p < passes; p++) {
		int32_t nm;
		if (!get_i32(f, &nm) || nm < 0 || nm > P.n * LP_LEVELS)
			goto bad;
		struct lp_result *r = mem_calloc(1, sizeof *r);
		out[n++] = r;
		r->objs = mem_calloc((size_t)(nm ? nm : 1), sizeof *r->objs);
		r->maps = mem_calloc((size_t)(nm ? nm : 1), sizeof *r->maps);
		r->specs = mem_calloc((size_t)(nm ? nm : 1), sizeof *r->specs);
		r->level = mem_calloc((size_t)(nm ? nm : 1), sizeof *r->level);
		for (int k = 0; k < nm; k++)
			if (!load_map(f, r, k, &P, discard_isolated))
				goto bad;
		index_maps(r);
	}
	if (fgetc(f) != EOF)
		goto bad;
	fclose(f);
	free(P.o);
	return n;
bad:
	snprintf(err, sizeof err, "'%s' is damaged (cut short or corrupt)", path);
refused:
	fclose(f);
	free(P.o);
	for (int i = 0; i < n; i++)
		lp_free(out[i]);
	return -diag_fail(dg, FAIL_INPUT, srcloc_none(), "%s", err);
}
