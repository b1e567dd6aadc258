/* SPDX-License-Identifier: MIT */
/* bvh.c: binned-SAH bounding volume hierarchy with iterative traversal.
 *
 * Nodes live in one array in depth-first order: an inner node's left child
 * follows it, its right child's index is stored. Leaves hold a run of the
 * primitive array. Boxes are padded by a small relative margin so rounding
 * in the slab test can never cull the true nearest hit: the tree returns
 * exactly the hit a brute-force loop over shape_intersect would. */
#include "bvh.h"

#include <math.h>
#include <stdlib.h>

#include "../common/arena.h"

#define BINS 16      /* SAH bins per split */
#define MAX_DEPTH 60 /* leaves are forced below this; the stack holds 64 */
#define LEAF_MAX 4   /* leaves never hold more unless the split fails */

struct bvh_node {
	struct bbox b; /* padded bounds of everything below */
	int first;     /* leaf: first primitive; inner: right child's index */
	int count;     /* leaf: number of primitives; inner: 0 */
};

struct bvh {
	struct bvh_node *nodes;        /* depth-first; nodes[0] is the root */
	int nnodes;                    /* used entries of nodes */
	const struct object **prims;   /* bounded leaves, in tree order */
	int nprims;                    /* entries of prims */
	const struct object **unbound; /* unbounded leaves, tested always */
	int nunbound;                  /* entries of unbound */
};

/* One primitive while building. */
struct item {
	const struct object *o; /* the leaf object */
	struct bbox b;          /* its padded world bounds */
	struct vec3 c;          /* centre of b */
};

/* Growable arrays used during the build. */
struct builder {
	struct item *items;    /* bounded leaves */
	int nitems, capitems;  /* count and capacity of items */
	struct bvh *t;         /* the tree being filled */
	int capnodes;          /* capacity of t->nodes */
};

/* ==== collecting leaves ================================================== */

static double box_area(struct bbox b)
{
	struct vec3 e = v_sub(b.hi, b.lo);
	if (e.x < 0 || e.y < 0 || e.z < 0)
		return 0;
	return 2 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

/* b grown by a margin relative to its size and distance from the origin. */
static struct bbox pad(struct bbox b)
{
	struct vec3 m = v_max(v_max(v_neg(b.lo), b.hi), v_sub(b.hi, b.lo));
	double e = 1e-9 * fmax(fmax(m.x, m.y), m.z) + 1e-300;
	return (struct bbox){v_sub(b.lo, v3(e, e, e)), v_add(b.hi, v3(e, e, e))};
}

static void add_unbound(struct builder *B, const struct object *o)
{
	struct bvh *t = B->t;
	t->unbound = mem_realloc(t->unbound, sizeof *t->unbound * (size_t)(t->nunbound + 1));
	t->unbound[t->nunbound++] = o;
}

static void add_item(struct builder *B, const struct object *o, struct bbox b)
{
	if (B->nitems == B->capitems) {
		B->capitems = B->capitems ? 2 * B->capitems : 64;
		B->items = mem_realloc(B->items, sizeof *B->items * (size_t)B->capitems);
	}
	b = pad(b);
	B->items[B->nitems++] = (struct item){o, b, v_scale(v_add(b.lo, b.hi), 0.5)};
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
		add_item(B, o, b);
}

/* ==== building =========================================================== */

static int new_node(struct builder *B)
{
	struct bvh *t = B->t;
	if (t->nnodes == B->capnodes) {
		B->capnodes = B->capnodes ? 2 * B->capnodes : 64;
		t->nodes = mem_realloc(t->nodes, sizeof *t->nodes * (size_t)B->capnodes);
	}
	return t->nnodes++;
}

/* The SAH split of items[lo,hi) along axis over centroid range [c0,c1]:
 * returns the best bin boundary (1..BINS-1) and its cost in *cost. */
static int best_bin(const struct builder *B, int lo, int hi, int axis, double c0, double c1,
                    double *cost)
{
	struct bbox bb[BINS];
	int cnt[BINS] = {0};
	double scale = BINS / (c1 - c0), right_area[BINS];
	int right_cnt[BINS];
	for (int i = 0; i < BINS; i++)
		bb[i] = bbox_empty();
	for (int i = lo; i < hi; i++) {
		int k = (int)((v_comp(B->items[i].c, axis) - c0) * scale);
		k = k < 0 ? 0 : k >= BINS ? BINS - 1 : k;
		cnt[k]++;
		bb[k] = bbox_union(bb[k], B->items[i].b);
	}
	struct bbox acc = bbox_empty();
	int n = 0;
	for (int k = BINS - 1; k > 0; k--) {
		acc = bbox_union(acc, bb[k]);
		n += cnt[k];
		right_area[k] = box_area(acc);
		right_cnt[k] = n;
	}
	acc = bbox_empty();
	n = 0;
	int best = -1;
	for (int k = 1; k < BINS; k++) {
		acc = bbox_union(acc, bb[k - 1]);
		n += cnt[k - 1];
		double c = n * box_area(acc) + right_cnt[k] * right_area[k];
		if (n > 0 && right_cnt[k] > 0 && (best < 0 || c < *cost))
			best = k, *cost = c;
	}
	return best;
}

/* Moves items whose centroid bin is below `bin` to the front; returns the split. */
static int partition(struct builder *B, int lo, int hi, int axis, double c0, double c1, int bin)
{
	double scale = BINS / (c1 - c0);
	int i = lo, j = hi - 1;
	while (i <= j) {
		int k = (int)((v_comp(B->items[i].c, axis) - c0) * scale);
		k = k < 0 ? 0 : k >= BINS ? BINS - 1 : k;
		if (k < bin) {
			i++;
		} else {
			struct item tmp = B->items[i];
			B->items[i] = B->items[j];
			B->items[j--] = tmp;
		}
	}
	return i;
}

/* Makes node ni a leaf over items[lo,hi). */
static void make_leaf(struct builder *B, int ni, int lo, int hi)
{
	B->t->nodes[ni].first = lo;
	B->t->nodes[ni].count = hi - lo;
}

/* Builds the subtree over items[lo,hi); returns its node index. */
static int build(struct builder *B, int lo, int hi, int depth)
{
	int ni = new_node(B);
	struct bbox b = bbox_empty(), cb = bbox_empty();
	for (int i = lo; i < hi; i++) {
		b = bbox_union(b, B->items[i].b);
		cb = bbox_add(cb, B->items[i].c);
	}
	B->t->nodes[ni].b = b;
	struct vec3 e = v_sub(cb.hi, cb.lo);
	int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
	double c0 = v_comp(cb.lo, axis), c1 = v_comp(cb.hi, axis), cost = 0;
	if (hi - lo <= 1 || depth >= MAX_DEPTH || !(c1 > c0)) {
		make_leaf(B, ni, lo, hi);
		return ni;
	}
	int bin = best_bin(B, lo, hi, axis, c0, c1, &cost);
	/* leaf cost n·A against 1/8 traversal + the split's cost (both per A) */
	if (bin < 0 || (hi - lo <= LEAF_MAX && cost >= (hi - lo - 0.125) * box_area(b))) {
		make_leaf(B, ni, lo, hi);
		return ni;
	}
	int mid = partition(B, lo, hi, axis, c0, c1, bin);
	if (mid == lo || mid == hi)
		mid = (lo + hi) / 2;
	build(B, lo, mid, depth + 1);
	int right = build(B, mid, hi, depth + 1);
	B->t->nodes[ni].first = right;
	B->t->nodes[ni].count = 0;
	return ni;
}

struct bvh *bvh_build(struct object **objs, int n)
{
	struct bvh *t = mem_calloc(1, sizeof *t);
	struct builder B = {NULL, 0, 0, t, 0};
	for (int i = 0; i < n; i++)
		collect(&B, objs[i]);
	if (B.nitems > 0)
		build(&B, 0, B.nitems, 0);
	t->prims = mem_alloc(sizeof *t->prims * (size_t)(B.nitems ? B.nitems : 1));
	for (int i = 0; i < B.nitems; i++)
		t->prims[i] = B.items[i].o;
	t->nprims = B.nitems;
	free(B.items);
	return t;
}

void bvh_free(struct bvh *b)
{
	if (!b)
		return;
	free(b->nodes);
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
	return b->nnodes > 0 ? b->nodes[0].b : bbox_empty();
}

/* ==== traversal ========================================================== */

/* Slab test of box b against the ray (inv = 1/d) over [tmin,tmax]; the entry
 * distance goes to *t. NaN from 0·∞ leaves the bound unchanged. */
static bool box_hit(const struct bbox *b, struct vec3 o, struct vec3 inv, double tmin,
                    double tmax, double *t)
{
	for (int k = 0; k < 3; k++) {
		double oi = v_comp(o, k), iv = v_comp(inv, k);
		double t0 = (v_comp(b->lo, k) - oi) * iv, t1 = (v_comp(b->hi, k) - oi) * iv;
		if (t0 > t1) {
			double s = t0;
			t0 = t1;
			t1 = s;
		}
		t1 *= 1 + 1e-12;
		if (t0 > tmin)
			tmin = t0;
		if (t1 < tmax)
			tmax = t1;
		if (tmin > tmax)
			return false;
	}
	*t = tmin;
	return true;
}

/* The walk shared by both queries: with any set, stops at the first hit. */
static bool traverse(const struct bvh *b, const struct ray *r, double tmin, double tmax,
                     unsigned skip, bool any, struct hit *h)
{
	bool found = false;
	struct hit tmp;
	for (int i = 0; i < b->nunbound; i++) {
		if (b->unbound[i]->flags & skip)
			continue;
		if (any && shape_occluded(b->unbound[i], r, tmin, tmax))
			return true;
		if (!any && shape_intersect(b->unbound[i], r, tmin, tmax, &tmp))
			*h = tmp, tmax = tmp.t, found = true;
	}
	if (b->nnodes == 0)
		return found;
	struct vec3 inv = v3(1 / r->d.x, 1 / r->d.y, 1 / r->d.z);
	struct { int n; double t; } stack[64];
	int sp = 0;
	double te;
	if (!box_hit(&b->nodes[0].b, r->o, inv, tmin, tmax, &te))
		return found;
	stack[sp].n = 0, stack[sp++].t = te;
	while (sp > 0) {
		sp--;
		if (stack[sp].t > tmax)
			continue;
		const struct bvh_node *nd = &b->nodes[stack[sp].n];
		if (nd->count > 0) {
			for (int i = nd->first; i < nd->first + nd->count; i++) {
				const struct object *o = b->prims[i];
				if (o->flags & skip)
					continue;
				if (any && shape_occluded(o, r, tmin, tmax))
					return true;
				if (!any && shape_intersect(o, r, tmin, tmax, &tmp))
					*h = tmp, tmax = tmp.t, found = true;
			}
			continue;
		}
		int l = (int)(nd - b->nodes) + 1, rt = nd->first;
		double tl, tr;
		bool hl = box_hit(&b->nodes[l].b, r->o, inv, tmin, tmax, &tl);
		bool hr = box_hit(&b->nodes[rt].b, r->o, inv, tmin, tmax, &tr);
		if (hl && hr && tr < tl) { /* push the far one first */
			stack[sp].n = l, stack[sp++].t = tl;
			stack[sp].n = rt, stack[sp++].t = tr;
		} else {
			if (hr)
				stack[sp].n = rt, stack[sp++].t = tr;
			if (hl)
				stack[sp].n = l, stack[sp++].t = tl;
		}
	}
	return found;
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
