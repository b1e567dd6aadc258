/* SPDX-License-Identifier: MIT */
/* mesh.c: mesh { triangle { … } smooth_triangle { … } … [inside_vector v] },
 * mesh2 { vertex_vectors normal_vectors face_indices normal_indices } and a
 * lone smooth_triangle: many triangles as ONE object, with a bounding volume
 * hierarchy of its own (docs/design.md §5): the scene's Embree hierarchy
 * holds the mesh as one box, and this file's walks its triangles.
 *
 * The hierarchy splits the triangles at the median of their centroids along
 * the longest axis of the centroids' box, down to leaves of 4 or fewer;
 * boxes are padded by 1e-9 of the mesh's size. Traversal is in double and
 * visits the nearer child first; a triangle is Möller–Trumbore with
 * inclusive edges (as triangle.c), so a ray through a shared edge cannot
 * slip between two triangles. Ties in t go to the lower triangle index, so
 * the hit does not depend on the traversal order.
 *
 * Normals: the geometric normal e1 × e2 (counter-clockwise p0 → p1 → p2 is
 * outward, as for triangle); a smooth triangle's shading normal is its
 * corners' unit normals interpolated by the barycentric coordinates, turned
 * to the geometric normal's side.
 *
 * Inside: with inside_vector, a point is inside when a ray from it along
 * that vector crosses the mesh an odd number of times (POV-Ray's rule);
 * without, nothing is inside.
 *
 * A height_field is such a mesh too (eval/geometry.c makes its grid of
 * triangles, inside_vector up); its water_level hides the surface below
 * that height (clip_y).
 *
 * Parametrisation: an atlas. With k = ⌈√nt⌉, triangle i has the cell
 * column i mod k, row ⌊i/k⌋ of a k × k grid over [0,1]², and inside the
 * cell its own barycentric (a, b) as triangle.c's (u,v):
 *
 *     T(u,v) = p0 + a·e1 + b·e2,   a = k·u − col, b = k·v − row
 *     ∂T/∂u = k·e1,   ∂T/∂v = k·e2
 *
 * Half of each cell (a + b > 1) and the cells past the last triangle lie
 * off the surface; cell areas count only the triangles' halves, exactly. */
#include <math.h>
#include <stdlib.h>

#include "prim.h"

#define MS(o) ((o)->g.mesh.m)
#define LEAF_MAX 4
#define STACK_MAX 128

static struct vec3 corner(const struct mesh *m, int t, int k) { return m->vert[m->tri[t].v[k]]; }

/* ==== building ============================================================ */

struct build {
	const struct mesh *m;
	struct vec3 *cen;   /* centroid of each triangle */
	struct mesh_node *node;
	int nnode;
	int *order;
	double pad;
};

static double cen_axis(const struct build *B, int t, int axis) { return v_comp(B->cen[t], axis); }

/* Partially sorts order[lo, hi) so the median along axis is at mid
 * (quickselect, ties by index so the build is deterministic). */
static void select_median(const struct build *B, int *ord, int lo, int hi, int mid, int axis)
{
	while (hi - lo > 1) {
		int pv = ord[lo + (hi - lo) / 2];
		double pc = cen_axis(B, pv, axis);
		int i = lo, j = hi - 1;
		while (i <= j) {
			while (cen_axis(B, ord[i], axis) < pc || (cen_axis(B, ord[i], axis) == pc && ord[i] < pv))
				i++;
			while (cen_axis(B, ord[j], axis) > pc || (cen_axis(B, ord[j], axis) == pc && ord[j] > pv))
				j--;
			if (i <= j) {
				int tmp = ord[i];
				ord[i++] = ord[j];
				ord[j--] = tmp;
			}
		}
		if (mid <= j)
			hi = j + 1;
		else if (mid >= i)
			lo = i;
		else
			return;
	}
}

/* Builds the node for order[first, first+count) at slot id; a split
 * takes two consecutive new slots for its children. */
static void build_node(struct build *B, int id, int first, int count, int depth)
{
	struct mesh_node *nd = &B->node[id];
	struct bbox b = bbox_empty(), cb = bbox_empty();
	for (int i = first; i < first + count; i++) {
		int t = B->order[i];
		for (int k = 0; k < 3; k++)
			b = bbox_add(b, corner(B->m, t, k));
		cb = bbox_add(cb, B->cen[t]);
	}
	struct vec3 pad = v3(B->pad, B->pad, B->pad);
	nd->b = (struct bbox){v_sub(b.lo, pad), v_add(b.hi, pad)};
	if (count <= LEAF_MAX || depth >= STACK_MAX / 2 - 2) {
		nd->first = first;
		nd->count = count;
		return;
	}
	struct vec3 ext = v_sub(cb.hi, cb.lo);
	int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
	int half = count / 2;
	select_median(B, B->order, first, first + count, first + half, axis);
	int kids = B->nnode;
	B->nnode += 2;
	nd->first = kids;
	nd->count = 0;
	build_node(B, kids, first, half, depth + 1);
	build_node(B, kids + 1, first + half, count - half, depth + 1);
}

bool mesh_finish(struct mesh *m, struct arena *a, int *bad)
{
	if (m->nt <= 0)
		return false;
	for (int t = 0; t < m->nt; t++)
		for (int k = 0; k < 3; k++)
			if (m->tri[t].v[k] < 0 || m->tri[t].v[k] >= m->nv || m->tri[t].n[k] >= m->nn) {
				*bad = t;
				return false;
			}
	for (int i = 0; i < m->nn; i++) /* corners' normals weigh alike (POV-Ray) */
		m->norm[i] = v_norm(m->norm[i]);
	struct build B = {.m = m};
	B.cen = mem_alloc(sizeof *B.cen * (size_t)m->nt);
	struct bbox all = bbox_empty();
	for (int t = 0; t < m->nt; t++) {
		struct vec3 p0 = corner(m, t, 0), p1 = corner(m, t, 1), p2 = corner(m, t, 2);
		B.cen[t] = v_scale(v_add(v_add(p0, p1), p2), 1.0 / 3);
		all = bbox_add(bbox_add(bbox_add(all, p0), p1), p2);
	}
	B.pad = 1e-9 * fmax(v_len(v_sub(all.hi, all.lo)), 1e-300);
	/* a binary tree over ≤ nt leaves has fewer than 2·nt nodes */
	B.node = ARENA_ARRAY(a, struct mesh_node, 2 * (size_t)m->nt + 2);
	B.order = ARENA_ARRAY(a, int, m->nt);
	for (int t = 0; t < m->nt; t++)
		B.order[t] = t;
	B.nnode = 1;
	build_node(&B, 0, 0, m->nt, 0);
	free(B.cen);
	m->node = B.node;
	m->nnode = B.nnode;
	m->order = B.order;
	m->side = (int)ceil(sqrt((double)m->nt));
	while ((long)m->side * m->side < m->nt)
		m->side++;
	return true;
}

/* ==== intersection ======================================================= */

/* Möller–Trumbore, edges inclusive: t and the barycentric (a, b). */
static bool tri_hit(const struct mesh *m, int t, const struct ray *r, double *tt, double *ua,
                    double *vb)
{
	struct vec3 p0 = corner(m, t, 0);
	return prim_tri_hit(p0, v_sub(corner(m, t, 1), p0), v_sub(corner(m, t, 2), p0), r, tt, ua, vb);
}

/* The ray's parameter interval inside box b, clipped to (lo, hi). */
static bool box_hit(struct bbox b, const struct ray *r, double lo, double hi, double *enter)
{
	for (int k = 0; k < 3; k++) {
		double o = v_comp(r->o, k), d = v_comp(r->d, k), bl = v_comp(b.lo, k), bh = v_comp(b.hi, k);
		if (d == 0) {
			if (o < bl || o > bh)
				return false;
			continue;
		}
		double t0 = (bl - o) / d, t1 = (bh - o) / d;
		if (t0 > t1) {
			double tmp = t0;
			t0 = t1;
			t1 = tmp;
		}
		lo = fmax(lo, t0);
		hi = fmin(hi, t1);
		if (lo > hi)
			return false;
	}
	*enter = lo;
	return true;
}

/* Calls visit(t) for each triangle whose leaf box the ray meets in (lo, hi),
 * nearer boxes first; visit returns the new hi. */
struct walk {
	const struct mesh *m;
	const struct ray *r;
	double lo, hi;
	/* nearest-hit state */
	int best;
	double ta, tb;
	/* crossing count (inside) */
	bool count_all;
	int crossings;
};

static void walk(struct walk *W)
{
	const struct mesh *m = W->m;
	int stack[STACK_MAX], sp = 0;
	double e;
	if (!box_hit(m->node[0].b, W->r, W->lo, W->hi, &e))
		return;
	stack[sp++] = 0;
	while (sp > 0) {
		const struct mesh_node *nd = &m->node[stack[--sp]];
		if (!box_hit(nd->b, W->r, W->lo, W->hi, &e))
			continue;
		if (nd->count == 0) {
			double e0, e1;
			bool h0 = box_hit(m->node[nd->first].b, W->r, W->lo, W->hi, &e0);
			bool h1 = box_hit(m->node[nd->first + 1].b, W->r, W->lo, W->hi, &e1);
			if (h0 && h1 && sp + 2 <= STACK_MAX) {
				/* push the farther first, so the nearer is visited next */
				stack[sp++] = e0 <= e1 ? nd->first + 1 : nd->first;
				stack[sp++] = e0 <= e1 ? nd->first : nd->first + 1;
			} else if (h0 && sp < STACK_MAX) {
				stack[sp++] = nd->first;
			} else if (h1 && sp < STACK_MAX) {
				stack[sp++] = nd->first + 1;
			}
			continue;
		}
		for (int i = nd->first; i < nd->first + nd->count; i++) {
			int t = m->order[i];
			double tt, a, b;
			if (!tri_hit(m, t, W->r, &tt, &a, &b) || !(tt > W->lo))
				continue;
			if (m->clipped && !W->count_all && W->r->o.y + tt * W->r->d.y < m->clip_y)
				continue; /* under a height field's water level */
			if (W->count_all) {
				W->crossings++;
				continue;
			}
			if (tt < W->hi || (tt == W->hi && t < W->best)) {
				W->hi = tt;
				W->best = t;
				W->ta = a;
				W->tb = b;
			}
		}
	}
}

static bool me_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	const struct mesh *m = MS(o);
	struct walk W = {.m = m, .r = r, .lo = tmin, .hi = tmax, .best = -1};
	walk(&W);
	if (W.best < 0 || !(W.hi < tmax))
		return false;
	int t = W.best, k = m->side;
	double a = W.ta, b = W.tb;
	struct vec3 p0 = corner(m, t, 0), e1 = v_sub(corner(m, t, 1), p0), e2 = v_sub(corner(m, t, 2), p0);
	struct vec3 g = v_cross(e1, e2);
	lh->t = W.hi;
	lh->p = v_madd(v_madd(p0, e1, a), e2, b);
	lh->n = g;
	const struct mesh_tri *tr = &m->tri[t];
	if (tr->n[0] >= 0) {
		struct vec3 s = v_add(v_add(v_scale(m->norm[tr->n[0]], 1 - a - b), v_scale(m->norm[tr->n[1]], a)),
		                      v_scale(m->norm[tr->n[2]], b));
		if (v_dot(s, s) > 0)
			lh->n = v_dot(s, g) < 0 ? v_neg(s) : s;
	}
	lh->u = ((t % k) + a) / k;
	lh->v = ((t / k) + b) / k;
	lh->dpdu = v_scale(e1, k);
	lh->dpdv = v_scale(e2, k);
	return true;
}

static bool me_inside(const struct object *o, struct vec3 p)
{
	const struct mesh *m = MS(o);
	if (!m->has_inside)
		return false;
	struct ray r = {p, m->inside_dir};
	struct walk W = {.m = m, .r = &r, .lo = 0, .hi = INFINITY, .best = -1, .count_all = true};
	walk(&W);
	return W.crossings & 1;
}

static struct bbox me_bounds(const struct object *o)
{
	return MS(o)->node[0].b;
}

/* The triangle of atlas cell (col, row), or -1. */
static int cell_tri(const struct mesh *m, long col, long row)
{
	if (col < 0 || row < 0 || col >= m->side || row >= m->side)
		return -1;
	long t = row * m->side + col;
	return t < m->nt ? (int)t : -1;
}

static bool me_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	const struct mesh *m = MS(o);
	int k = m->side;
	long col = (long)floor(u * k), row = (long)floor(v * k);
	col = col < 0 ? 0 : col >= k ? k - 1 : col;
	row = row < 0 ? 0 : row >= k ? k - 1 : row;
	int t = cell_tri(m, col, row);
	if (t < 0)
		return false;
	struct vec3 p0 = corner(m, t, 0), e1 = v_sub(corner(m, t, 1), p0), e2 = v_sub(corner(m, t, 2), p0);
	if (p)
		*p = v_madd(v_madd(p0, e1, u * k - col), e2, v * k - row);
	if (dpdu)
		*dpdu = v_scale(e1, k);
	if (dpdv)
		*dpdv = v_scale(e2, k);
	return true;
}

static struct uv_range me_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, false, false};
}

static double me_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	const struct mesh *m = MS(o);
	int k = m->side;
	u0 = fmax(u0, 0), v0 = fmax(v0, 0), u1 = fmin(u1, 1), v1 = fmin(v1, 1);
	if (!(u1 > u0) || !(v1 > v0))
		return 0;
	double sum = 0;
	long c0 = (long)floor(u0 * k), c1 = (long)ceil(u1 * k), r0 = (long)floor(v0 * k), r1 = (long)ceil(v1 * k);
	for (long row = r0; row < r1; row++)
		for (long col = c0; col < c1; col++) {
			int t = cell_tri(m, col, row);
			if (t < 0)
				continue;
			double a0 = fmax(u0 * k - col, 0), a1 = fmin(u1 * k - col, 1);
			double b0 = fmax(v0 * k - row, 0), b1 = fmin(v1 * k - row, 1);
			if (!(a1 > a0) || !(b1 > b0))
				continue;
			struct vec3 p0 = corner(m, t, 0), e1 = v_sub(corner(m, t, 1), p0), e2 = v_sub(corner(m, t, 2), p0);
			double jac = v_len(v_cross(xf_vector(obj_xf(o), e1), xf_vector(obj_xf(o), e2)));
			sum += prim_tri_clipped_area(a0, a1, b0, b1) * jac;
		}
	return sum;
}

static void me_dump(const struct object *o, FILE *out)
{
	const struct mesh *m = MS(o);
	fprintf(out, "triangles %d vertices %d normals %d", m->nt, m->nv, m->nn);
	if (m->has_inside)
		fputs(" inside_vector ", out), prim_dump_vec(out, m->inside_dir);
	if (m->hf_w)
		fprintf(out, " height_field %dx%d", m->hf_w, m->hf_h);
	if (m->clipped)
		fprintf(out, " water_level %.6g", m->clip_y);
}

const struct prim_ops shape_mesh_ops = {
	me_intersect, me_inside, me_bounds, me_uv_point, me_uv_range, me_cell_area, me_dump, NULL,
};
