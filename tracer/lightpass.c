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
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "optics.h"
#include "sampler.h"
#include "shape.h"
#include "spectrum.h"
#include "surface.h"

#define CHUNK 4096 /* rays per work item */

/* A diffuse landing, kept until the maps exist. */
struct rec {
	const struct object *obj; /* primitive hit */
	double u, v;              /* where on it */
	double e[3];              /* energy per channel (W) */
	struct vec3 p;            /* world point (for the automatic cell size) */
};

struct recbuf {
	struct rec *r;
	long n, cap;
};

/* What one light aims at one specular object: from a point or spot light,
 * the cone of directions that holds the object's bounds; from a parallel
 * light, the beam of parallel rays whose cross-section (a disc) covers them. */
struct target {
	struct vec3 axis;  /* unit direction to the bounds' centre; parallel: of travel */
	struct vec3 t1, t2;/* frame around axis */
	double cosmax;     /* cosine of the half-angle (-1: every direction) */
	double omega;      /* solid angle, sr; parallel: the disc's area, m² */
	struct vec3 origin;/* parallel: the disc's centre, upstream of the scene */
	double radius;     /* parallel: the disc's radius */
	long side;         /* rays per side of the stratified grid (side² rays) */
};

/* One work item: rays [first, first+count) of target k of light l. */
struct item {
	int light, target;
	long first, count;
};

struct lp_result {
	const struct object **objs; /* primitives with a map, deterministic order */
	struct illum_map **maps;
	struct illum_spec *specs;   /* the grid each map was made with */
	int n;
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
	atomic_long next;           /* next item to take */
	const struct object *clipped; /* see lp_stats */
	struct band band;           /* the light this pass carries */
};

struct worker {
	struct job *job;
	bool refract, reflect;      /* the current light's photons { } switches */
	struct band band;           /* the light the current ray carries */
	struct recbuf recs;
	long long segments;
	double emitted[3];
	double deposited[3], direct[3], absorbed[3], escaped[3], cut[3]; /* lp_stats */
};

static double maxc(struct vec3 a) { return fmax(a.x, fmax(a.y, a.z)); }

/* ==== which objects can form caustics ==================================== */

/* True when o (or a part of it) reflects light specularly or transmits it
 * bent (a straight transmitter's light is the shadow rays', surface.h). */
static bool is_specular(const struct scene *s, const struct object *o)
{
	if (o->kind >= OBJ_UNION) {
		for (int i = 0; i < o->g.csg.n; i++)
			if (is_specular(s, o->g.csg.kids[i]))
				return true;
		return false;
	}
	const struct texture *t = mat_texture(o);
	const struct finish *f = &t->finish;
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
			if (o->interior && o->interior->dispersion != 1)
				return true;
			if (o->kind >= OBJ_UNION)
				for (int k = 0; k < o->g.csg.n && n < 64; k++)
					stack[n++] = o->g.csg.kids[k];
		}
	}
	return false;
}

/* The cone from light position L that holds bounds bb. */
static struct target cone_to(struct vec3 L, struct bbox bb)
{
	struct target t;
	memset(&t, 0, sizeof t);
	t.cosmax = -1;
	t.axis = v3(0, -1, 0);
	if (bbox_finite(bb)) {
		struct vec3 c = v_scale(v_add(bb.lo, bb.hi), 0.5);
		double r = 0.5 * v_len(v_sub(bb.hi, bb.lo)) * (1 + 1e-9), d = v_len(v_sub(c, L));
		if (d > r) {
			t.axis = v_scale(v_sub(c, L), 1 / d);
			t.cosmax = sqrt(1 - (r / d) * (r / d));
		}
	}
	t.omega = 2 * M_PI * (1 - t.cosmax);
	struct vec3 a = fabs(t.axis.x) < 0.9 ? v3(1, 0, 0) : v3(0, 1, 0);
	t.t1 = v_norm(v_cross(a, t.axis));
	t.t2 = v_cross(t.axis, t.t1);
	return t;
}

static bool in_cone(const struct target *t, struct vec3 d) { return v_dot(d, t->axis) >= t->cosmax; }

/* The beam of parallel light travelling along unit D that covers bounds bb
 * (finite), its disc placed upstream of everything in the scene: past the
 * finite objects' bounds and past any unbounded object (a plane) that the
 * beam crosses before it reaches bb, so what shadows the object in the eye
 * pass (whose shadow rays toward a parallel light never end) shadows the
 * beam too. */
static struct target beam_to(const struct scene *s, struct vec3 D, struct bbox bb)
{
	struct target t;
	memset(&t, 0, sizeof t);
	struct vec3 c = v_scale(v_add(bb.lo, bb.hi), 0.5);
	t.axis = D;
	t.cosmax = 1;
	t.radius = 0.5 * v_len(v_sub(bb.hi, bb.lo)) * (1 + 1e-9);
	t.omega = M_PI * t.radius * t.radius;
	double back = t.radius;
	for (int i = 0; i < s->nobjects; i++) {
		struct bbox ob = shape_bounds(s->objects[i]);
		struct hit h;
		if (bbox_finite(ob)) {
			struct vec3 oc = v_scale(v_add(ob.lo, ob.hi), 0.5);
			back = fmax(back, v_len(v_sub(oc, c)) + 0.5 * v_len(v_sub(ob.hi, ob.lo)));
		} else if (shape_intersect(s->objects[i], &(struct ray){c, v_neg(D)}, 0, INFINITY, &h)) {
			back = fmax(back, h.t);
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

static void record(struct worker *w, const struct hit *h, const double e[3])
{
	struct recbuf *rb = &w->recs;
	if (rb->n == rb->cap) {
		rb->cap = rb->cap ? rb->cap * 2 : 4096;
		rb->r = mem_realloc(rb->r, sizeof *rb->r * (size_t)rb->cap);
	}
	rb->r[rb->n++] = (struct rec){h->obj, h->u, h->v, {e[0], e[1], e[2]}, h->p};
}

static void add3(double acc[3], const double e[3], double k)
{
	for (int c = 0; c < 3; c++)
		acc[c] += e[c] * k;
}

/* Follows one light ray; nspec counts its specular bounces so far (a
 * straight transmitter, whose light the eye pass's shadow rays carry, is no
 * bounce). Every joule that arrives is accounted for once (lp_stats):
 * followed on, deposited, direct, absorbed, escaped or cut. */
static void trace(struct worker *w, struct ray r, const double e[3], double cutoff, int depth, int nspec)
{
	const struct job *J = w->job;
	struct hit h;
	w->segments++;
	if (!bvh_intersect(J->b, &r, 0, INFINITY, &h)) {
		add3(w->escaped, e, 1);
		return;
	}
	/* POV-Ray's photons { } on the object: pass_through lets light by
	 * untouched, collect off keeps it off the maps, and a target with
	 * refraction or reflection off does not bend light that way */
	const struct photon_spec *ph = h.obj->has_photons ? &h.obj->photons : NULL;
	if (ph && ph->pass_through) {
		if (depth < J->o->max_depth)
			trace(w, (struct ray){v_madd(h.p, r.d, surf_eps(h.p) / v_len(r.d)), r.d}, e, cutoff, depth + 1, nspec);
		else
			add3(w->cut, e, 1);
		return;
	}
	double ea[3] = {e[0], e[1], e[2]};
	if (!h.entering) { /* leaving a medium: its absorption over the path inside */
		struct vec3 k = opt_fade(mat_interior(h.obj), h.t * v_len(r.d));
		ea[0] *= k.x, ea[1] *= k.y, ea[2] *= k.z;
		for (int c = 0; c < 3; c++)
			w->absorbed[c] += e[c] - ea[c];
		e = ea;
	}
	struct surf_in si;
	struct surf_out so;
	surf_prepare(J->s, J->mc, &h, v_norm(r.d), &si);
	surf_scatter(&si, w->band, &so);
	double opacity = 1 - si.pc.f - si.pc.t;
	/* what neither reflects nor transmits stays at the surface: a diffuse
	 * surface reached after a specular bounce keeps it in its map */
	double rest[3];
	for (int c = 0; c < 3; c++)
		rest[c] = e[c] * (1 - v_comp(so.R, c) - v_comp(so.T, c));
	if (si.f->diffuse > 0 && opacity > 0 && (nspec > 0 || J->o->deposit_direct) && (!ph || ph->collect)) {
		record(w, &h, e);
		add3(w->deposited, rest, 1);
	} else if (si.f->diffuse > 0 && opacity > 0 && nspec == 0) {
		add3(w->direct, rest, 1);
	} else {
		add3(w->absorbed, rest, 1);
	}
	bool more = depth < J->o->max_depth;
	bool refract = w->refract && (!ph || !ph->target || ph->refraction) && more;
	bool reflect = w->reflect && (!ph || !ph->target || ph->reflection) && !J->o->transmit_only && more;
	double te[3] = {e[0] * so.T.x, e[1] * so.T.y, e[2] * so.T.z};
	double re[3] = {e[0] * so.R.x, e[1] * so.R.y, e[2] * so.R.z};
	if (maxc(so.T) > 0) {
		if (refract && fmax(te[0], fmax(te[1], te[2])) > cutoff)
			trace(w, so.trans, te, cutoff, depth + 1, si.straight ? nspec : nspec + 1);
		else
			add3(w->cut, te, 1);
	}
	if (maxc(so.R) > 0) {
		if (reflect && fmax(re[0], fmax(re[1], re[2])) > cutoff)
			trace(w, so.refl, re, cutoff, depth + 1, nspec + 1);
		else
			add3(w->cut, re, 1);
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

/* Shoots the rays of one work item. */
static void run_item(struct worker *w, const struct item *it)
{
	const struct job *J = w->job;
	const struct light *l = &J->s->lights[it->light];
	const struct target *tg = J->targets[it->light];
	const struct target *t = &tg[it->target];
	long n = t->side * t->side;
	double scale = t->omega / (double)n;
	double e0[3] = {l->colour.r * scale, l->colour.g * scale, l->colour.b * scale};
	if (J->o->channel >= 0)
		for (int c = 0; c < 3; c++)
			if (c != J->o->channel)
				e0[c] = 0;
	double cutoff = J->o->min_weight * fmax(e0[0], fmax(e0[1], e0[2]));
	uint64_t key = ((uint64_t)it->light << 40) ^ ((uint64_t)it->target << 20) ^ 0x5A17u;
	bool beam = l->kind == LIGHT_PARALLEL;
	w->refract = l->photons_refraction;
	w->reflect = l->photons_reflection;
	for (long i = it->first; i < it->first + it->count; i++) {
		/* stratified in (cos θ, φ) over the cone, or in (r², φ) over the disc */
		double sx = ((double)(i % t->side) + smp_get(key, (uint32_t)i, 0)) / (double)t->side;
		double sy = ((double)(i / t->side) + smp_get(key, (uint32_t)i, 1)) / (double)t->side;
		double ph = 2 * M_PI * sy;
		struct vec3 o = l->pos, d = t->axis;
		if (beam) {
			double rr = t->radius * sqrt(sx);
			o = v_add(t->origin, v_add(v_scale(t->t1, rr * cos(ph)), v_scale(t->t2, rr * sin(ph))));
		} else {
			double ct = 1 - sx * (1 - t->cosmax), st = sqrt(fmax(0, 1 - ct * ct));
			d = v_add(v_scale(t->axis, ct), v_add(v_scale(t->t1, st * cos(ph)), v_scale(t->t2, st * sin(ph))));
		}
		bool covered = false;
		for (int k = 0; k < it->target && !covered; k++)
			covered = beam ? in_beam(&tg[k], o) : in_cone(&tg[k], d);
		if (covered)
			continue;
		double e[3] = {e0[0], e0[1], e0[2]};
		if (l->kind == LIGHT_SPOT) {
			double k = opt_spot(l, d);
			if (k <= 0)
				continue;
			e[0] *= k, e[1] *= k, e[2] *= k;
		}
		w->band = J->band;
		if (J->o->spectral)
			w->band.lambda = ray_wavelength(key, (uint64_t)i, (uint64_t)t->side, e);
		for (int c = 0; c < 3; c++)
			w->emitted[c] += e[c];
		trace(w, (struct ray){o, d}, e, cutoff, 0, 0);
	}
}

static void *work(void *arg)
{
	struct worker *w = arg;
	struct job *J = w->job;
	for (;;) {
		long k = atomic_fetch_add_explicit(&J->next, 1, memory_order_relaxed);
		if (k >= J->nitems)
			return NULL;
		run_item(w, &J->items[k]);
	}
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
		slot_put(r, k);
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

/* The grid for a surface: its illum_map { }, else a cell size chosen from
 * the rays that reached it (pitfall 1): per_node rays per node (0: the
 * default ILLUM_RAYS_PER_NODE) over the region where most of them landed. The region is the 5th to 95th
 * percentile of the landing points on each axis, so a few grazing rays that
 * land far away do not inflate it. */
static struct illum_spec choose_spec(const struct object *o, const struct vec3 *pts, long k, double per_node)
{
	if (o->illum.resolution > 0 || o->illum.cell > 0)
		return o->illum;
	double *c = mem_alloc(sizeof *c * (size_t)(k ? k : 1)), ex[3];
	for (int axis = 0; axis < 3; axis++) {
		for (long i = 0; i < k; i++)
			c[i] = v_comp(pts[i], axis);
		qsort(c, (size_t)k, sizeof *c, cmp_double);
		ex[axis] = k ? c[(long)(0.95 * (double)(k - 1))] - c[(long)(0.05 * (double)(k - 1))] : 0;
	}
	free(c);
	for (int i = 0; i < 2; i++) /* two largest extents first */
		for (int j = i + 1; j < 3; j++)
			if (ex[j] > ex[i]) {
				double t = ex[i];
				ex[i] = ex[j];
				ex[j] = t;
			}
	double area = ex[0] * fmax(ex[1], ex[0] * 1e-3);
	double cell = illum_auto_cell(0.9 * (double)k, area, per_node);
	struct illum_spec sp = {0, cell > 0 ? cell : 0.01};
	return sp;
}

/* Gives every surface reached a map and deposits the records into it: the
 * distinct surfaces through a hash, then the records grouped per surface
 * (a counting sort, keeping their order), so the work is O(records) whatever
 * the number of surfaces. Deposits and finishing run on o->threads threads. */
static struct lp_result *build_maps(const struct recbuf *bufs, int nbuf, const struct lp_opts *o)
{
	struct lp_result *r = mem_calloc(1, sizeof *r);
	long total = 0, t = 0;
	for (int b = 0; b < nbuf; b++)
		total += bufs[b].n;
	/* the distinct surfaces (through the hash as it grows), then in source order */
	r->objs = mem_alloc(sizeof *r->objs * 16);
	int cap = 16;
	const struct object *prev = NULL;
	for (int b = 0; b < nbuf; b++)
		for (long i = 0; i < bufs[b].n; i++) {
			const struct object *ob = bufs[b].r[i].obj;
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
	/* group the records per surface (counting sort by map index) */
	int *ki = mem_alloc(sizeof *ki * (size_t)(total ? total : 1));
	long *start = mem_calloc((size_t)n + 1, sizeof *start), *fill = mem_calloc((size_t)n + 1, sizeof *fill);
	struct vec3 *pts = mem_alloc(sizeof *pts * (size_t)(total ? total : 1));
	struct illum_splat *sp = mem_alloc(sizeof *sp * (size_t)(total ? total : 1));
	t = 0;
	for (int b = 0; b < nbuf; b++)
		for (long i = 0; i < bufs[b].n; i++, t++)
			start[(ki[t] = find_map(r, bufs[b].r[i].obj)) + 1]++;
	for (int k = 0; k < n; k++)
		start[k + 1] += start[k];
	t = 0;
	for (int b = 0; b < nbuf; b++)
		for (long i = 0; i < bufs[b].n; i++, t++) {
			const struct rec *rc = &bufs[b].r[i];
			long at = start[ki[t]] + fill[ki[t]]++;
			pts[at] = rc->p;
			sp[at] = (struct illum_splat){rc->u, rc->v, {rc->e[0], rc->e[1], rc->e[2]}};
		}
	r->maps = mem_calloc((size_t)(n ? n : 1), sizeof *r->maps);
	r->specs = mem_calloc((size_t)(n ? n : 1), sizeof *r->specs);
	for (int k = 0; k < n; k++) {
		r->specs[k] = choose_spec(objs[k], pts + start[k], start[k + 1] - start[k],
		                          o->spectral ? 3 * ILLUM_RAYS_PER_NODE : 0);
		r->maps[k] = illum_new(objs[k], &r->specs[k]);
		if (r->maps[k]) {
			illum_deposit_all(r->maps[k], sp + start[k], start[k + 1] - start[k], o->threads);
			illum_finish_mt(r->maps[k], o->discard_isolated, NULL, o->threads);
		}
	}
	free(ki), free(start), free(fill), free(pts), free(sp);
	return r;
}

/* ==== driver ============================================================= */

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
			struct bbox bb = shape_bounds(s->objects[i]);
			if (l->kind != LIGHT_PARALLEL)
				tg[nt] = cone_to(l->pos, bb);
			else if (bbox_finite(bb))
				tg[nt] = beam_to(s, D, bb);
			else {
				tg[nt] = beam_to(s, D, scene_extent(s));
				if (!J->clipped)
					J->clipped = s->objects[i];
			}
			total += tg[nt++].omega;
		}
		J->targets[li] = tg;
		J->ntargets[li] = nt;
		for (int k = 0; k < nt; k++) {
			double share = (double)J->o->rays * tg[k].omega / total;
			tg[k].side = (long)fmax(1, floor(sqrt(share) + 0.5));
			long nr = tg[k].side * tg[k].side;
			for (long f = 0; f < nr; f += CHUNK) {
				if (nitems == capitems)
					J->items = mem_realloc(J->items, sizeof *J->items * (size_t)(capitems = capitems ? capitems * 2 : 64));
				J->items[nitems++] = (struct item){li, k, f, nr - f < CHUNK ? nr - f : CHUNK};
			}
		}
	}
	return nitems;
}

struct lp_result *lp_run(const struct scene *s, const struct bvh *b, const struct mat_cache *mc,
                         const struct lp_opts *o, struct lp_stats *st)
{
	struct job J;
	memset(&J, 0, sizeof J);
	J.s = s, J.b = b, J.mc = mc, J.o = o;
	J.band = (struct band){o->channel, 0};
	J.targets = mem_calloc((size_t)(s->nlights ? s->nlights : 1), sizeof *J.targets);
	J.ntargets = mem_calloc((size_t)(s->nlights ? s->nlights : 1), sizeof *J.ntargets);
	J.nitems = plan(&J);
	atomic_init(&J.next, 0);
	int nt = o->threads > 0 ? o->threads : 1;
	struct worker *ws = mem_calloc((size_t)nt, sizeof *ws);
	pthread_t *tids = mem_calloc((size_t)nt, sizeof *tids);
	for (int i = 0; i < nt; i++) {
		ws[i].job = &J;
		if (i > 0 && pthread_create(&tids[i], NULL, work, &ws[i]) != 0)
			ws[i].job = NULL; /* fewer threads: the others take its share */
	}
	work(&ws[0]);
	for (int i = 1; i < nt; i++)
		if (ws[i].job)
			pthread_join(tids[i], NULL);
	struct recbuf *bufs = mem_calloc((size_t)nt, sizeof *bufs);
	struct lp_stats acc;
	memset(&acc, 0, sizeof acc);
	for (int i = 0; i < nt; i++) {
		bufs[i] = ws[i].recs;
		acc.segments += ws[i].segments;
		for (int c = 0; c < 3; c++) {
			acc.emitted[c] += ws[i].emitted[c];
			acc.landed[c] += ws[i].deposited[c];
			acc.direct[c] += ws[i].direct[c];
			acc.absorbed[c] += ws[i].absorbed[c];
			acc.escaped[c] += ws[i].escaped[c];
			acc.cut[c] += ws[i].cut[c];
		}
	}
	struct lp_result *r = J.nitems > 0 ? build_maps(bufs, nt, o) : NULL;
	for (long k = 0; k < J.nitems; k++)
		acc.rays += J.items[k].count;
	for (int k = 0; r && k < r->n; k++) {
		double tot[3];
		if (!r->maps[k])
			continue;
		illum_total(r->maps[k], tot);
		for (int c = 0; c < 3; c++)
			acc.deposited[c] += tot[c];
		acc.maps++;
		acc.map_bytes += illum_memory(r->maps[k]);
	}
	acc.clipped = J.clipped;
	if (st)
		*st = acc;
	for (int i = 0; i < nt; i++)
		free(bufs[i].r);
	for (int li = 0; li < s->nlights; li++)
		free(J.targets[li]);
	free(bufs), free(ws), free(tids), free(J.items), free(J.targets), free(J.ntargets);
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

const struct illum_map *lp_map(const struct lp_result *r, const struct object *o)
{
	int k = r ? find_map(r, o) : -1;
	return k >= 0 ? r->maps[k] : NULL;
}

void lp_lookup(const struct lp_result *r, const struct object *o, double u, double v, double out[3])
{
	const struct illum_map *m = lp_map(r, o);
	out[0] = out[1] = out[2] = 0;
	if (m)
		illum_lookup(m, u, v, out);
}

void lp_each_map(const struct lp_result *r, void (*fn)(void *ctx, const struct object *o,
                 const struct illum_map *m), void *ctx)
{
	for (int k = 0; r && k < r->n; k++)
		if (r->maps[k])
			fn(ctx, r->objs[k], r->maps[k]);
}

void lp_free(struct lp_result *r)
{
	if (!r)
		return;
	for (int k = 0; k < r->n; k++)
		illum_free(r->maps[k]);
	free(r->maps);
	free(r->specs);
	free(r->slots);
	free(r->objs);
	free(r);
}

/* ==== --save-maps / --load-maps ========================================== */

/* File layout (native byte order, for reuse on the same machine): the magic
 * "ARVOMAP1", int32 passes, int32 primitives in the scene; per pass int32
 * maps; per map int32 primitive index (depth-first over the scene's object
 * tree), int32 resolution, double cell, int64 nodes, then per node int64 i,
 * int64 j, double energy[3]. Loading deposits each energy exactly on its node
 * (a deposit on a node gives it all) and finishes the maps again. */

struct prims {
	const struct object **o; /* primitives in depth-first order */
	int n, cap;
};

static void collect(struct prims *p, const struct object *o)
{
	if (o->kind >= OBJ_UNION) {
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
	int64_t ij[2] = {n->i, n->j};
	fwrite(ij, sizeof ij, 1, sv->f);
	fwrite(n->energy, sizeof n->energy, 1, sv->f);
	sv->nodes++;
}

static void count_node(void *ctx, const struct illum_node *n)
{
	if (!n->isolated)
		(*(long long *)ctx)++;
}

const char *lp_save(struct lp_result *const *r, int npasses, const struct scene *s, const char *path, int *failed_io)
{
	static _Thread_local char err[512];
	struct prims P = scene_prims(s);
	char tmp[4096];
	snprintf(tmp, sizeof tmp, "%s.tmp", path);
	FILE *f = fopen(tmp, "wb");
	*failed_io = 1;
	if (!f) {
		free(P.o);
		snprintf(err, sizeof err, "cannot create '%s': %s", path, strerror(errno));
		return err;
	}
	int32_t hdr[2] = {npasses, P.n};
	fwrite("ARVOMAP1", 8, 1, f);
	fwrite(hdr, sizeof hdr, 1, f);
	for (int p = 0; p < npasses; p++) {
		int32_t nm = r[p] ? r[p]->n : 0;
		fwrite(&nm, sizeof nm, 1, f);
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
			fwrite(&idx, sizeof idx, 1, f);
			fwrite(&res, sizeof res, 1, f);
			fwrite(&cell, sizeof cell, 1, f);
			fwrite(&nodes, sizeof nodes, 1, f);
			struct saver sv = {f, 0};
			if (r[p]->maps[k])
				illum_each(r[p]->maps[k], save_node, &sv);
		}
	}
	free(P.o);
	if (ferror(f) | (fclose(f) != 0) || rename(tmp, path) != 0) {
		remove(tmp);
		snprintf(err, sizeof err, "cannot write '%s': %s", path, strerror(errno));
		return err;
	}
	*failed_io = 0;
	return NULL;
}

int lp_load(struct lp_result **out, const struct scene *s, const char *path, bool discard_isolated,
            const char **errmsg)
{
	static _Thread_local char err[512];
	struct prims P = scene_prims(s);
	FILE *f = fopen(path, "rb");
	int n = 0;
	*errmsg = NULL;
	if (!f) {
		snprintf(err, sizeof err, "cannot open '%s': %s", path, strerror(errno));
		*errmsg = err;
		free(P.o);
		return -1;
	}
	char magic[8];
	int32_t hdr[2];
	if (fread(magic, 8, 1, f) != 1 || memcmp(magic, "ARVOMAP1", 8) != 0 || fread(hdr, sizeof hdr, 1, f) != 1 ||
	    hdr[0] < 0 || hdr[0] > 3 || hdr[1] != P.n)
		goto bad;
	for (int p = 0; p < hdr[0]; p++) {
		int32_t nm;
		if (fread(&nm, sizeof nm, 1, f) != 1 || nm < 0 || nm > P.n)
			goto bad;
		struct lp_result *r = mem_calloc(1, sizeof *r);
		out[n++] = r;
		r->objs = mem_calloc((size_t)(nm ? nm : 1), sizeof *r->objs);
		r->maps = mem_calloc((size_t)(nm ? nm : 1), sizeof *r->maps);
		r->specs = mem_calloc((size_t)(nm ? nm : 1), sizeof *r->specs);
		for (int k = 0; k < nm; k++) {
			int32_t idx, res;
			double cell;
			int64_t nodes;
			if (fread(&idx, sizeof idx, 1, f) != 1 || fread(&res, sizeof res, 1, f) != 1 ||
			    fread(&cell, sizeof cell, 1, f) != 1 || fread(&nodes, sizeof nodes, 1, f) != 1 ||
			    idx < 0 || idx >= P.n || nodes < 0)
				goto bad;
			r->n = k + 1;
			r->objs[k] = P.o[idx];
			r->specs[k] = (struct illum_spec){res, cell};
			r->maps[k] = illum_new(P.o[idx], &r->specs[k]);
			if (!r->maps[k])
				goto bad;
			for (int64_t q = 0; q < nodes; q++) {
				int64_t ij[2];
				double e[3], u, v;
				if (fread(ij, sizeof ij, 1, f) != 1 || fread(e, sizeof e, 1, f) != 1)
					goto bad;
				illum_node_uv(r->maps[k], (long)ij[0], (long)ij[1], &u, &v);
				illum_deposit(r->maps[k], u, v, e);
			}
			illum_finish(r->maps[k], discard_isolated, NULL);
		}
		index_maps(r);
	}
	if (fgetc(f) != EOF)
		goto bad;
	fclose(f);
	free(P.o);
	return n;
bad:
	fclose(f);
	free(P.o);
	for (int i = 0; i < n; i++)
		lp_free(out[i]);
	snprintf(err, sizeof err, "'%s' is not a map file saved for this scene", path);
	*errmsg = err;
	return -1;
}
