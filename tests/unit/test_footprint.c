/* SPDX-License-Identifier: MIT */
/* test_footprint.c: polygon (light-shaft footprint) deposits into
 * illumination maps (illum_deposit_poly, tracer/light/illum.h): exact conservation
 * on every kind of map, exact shares for cell-aligned and hand-integrated
 * polygons, agreement with point deposits in the small limit, a uniform
 * field from a tiling, seams, clamped edges, folds (bow-ties), huge
 * polygons, degenerate input, bookkeeping and the threaded variant.
 * Random numbers: geo_rand.h, fixed seeds. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../../tracer/light/illum.h"
#include "../../tracer/light/polygon.h"
#include "geo_rand.h"
#include "test.h"

/* A fixed primitive of each kind (identity transform). */
static struct object prim(enum object_kind k)
{
	struct object o = mk_obj(k);
	switch (k) {
	case OBJ_SPHERE: o.g.sphere.c = v3(0.5, 1, -2); o.g.sphere.r = 1.5; break;
	case OBJ_PLANE: o.g.plane.n = v3(0, 1, 0); o.g.plane.d = 0; break;
	case OBJ_BOX: o.g.box.lo = v3(-1, -0.5, -2); o.g.box.hi = v3(1, 1, 1); break;
	case OBJ_CONE:
		o.g.cone.a = v3(0, 0, 0); o.g.cone.ra = 1; o.g.cone.b = v3(0, 2, 0); o.g.cone.rb = 0;
		break;
	case OBJ_TORUS: o.g.torus.major = 2; o.g.torus.minor = 0.5; break;
	default: break;
	}
	return o;
}

static struct illum_map *map_res(const struct object *o, int r)
{
	struct illum_spec s = {r, 0};
	return illum_new(o, &s);
}

static struct illum_map *map_cell(const struct object *o, double c)
{
	struct illum_spec s = {0, c};
	return illum_new(o, &s);
}

/* ==== reading nodes back ================================================== */

#define MAXN (1 << 18)
struct nodes {
	int n;
	struct illum_node a[MAXN];
};

static void collect(void *ctx, const struct illum_node *n)
{
	struct nodes *s = ctx;
	if (s->n < MAXN)
		s->a[s->n++] = *n;
}

static struct nodes *nodes_of(const struct illum_map *m)
{
	struct nodes *s = calloc(1, sizeof *s);
	illum_each(m, collect, s);
	return s;
}

/* Node (i,j), or NULL when it holds nothing. */
static const struct illum_node *node(const struct nodes *s, long i, long j)
{
	for (int k = 0; k < s->n; k++)
		if (s->a[k].i == i && s->a[k].j == j)
			return &s->a[k];
	return NULL;
}

/* Energy of node (i,j) in channel c, 0 when absent. */
static double node_e(const struct nodes *s, long i, long j, int c)
{
	const struct illum_node *x = node(s, i, j);
	return x ? x->energy[c] : 0;
}

/* The (u,v) of grid point (x, y) in node units (fractions allowed). */
static void grid_uv(const struct illum_map *m, double x, double y, double uv[2])
{
	double u0, v0, du, dv;
	illum_node_uv(m, 0, 0, &u0, &v0);
	illum_grid(m, NULL, NULL, &du, &dv);
	uv[0] = u0 + x * du;
	uv[1] = v0 + y * dv;
}

/* ==== polygon geometry (polygon.h) ======================================== */

/* Moments of the unit square about two origins and in both windings;
 * clipping a non-convex L to a slab keeps its exact area and moments; a
 * bow-tie splits into two triangles of opposite winding, a pentagram into
 * simple loops whose signed areas add up to its own. */
static void t_geometry(void)
{
	struct pt2 sq[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, cw[4] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
	struct moments m = poly_moments(sq, 4, (struct pt2){0, 0});
	CHECK(m.a == 1 && m.x == 0.5 && m.y == 0.5 && m.xy == 0.25);
	m = poly_moments(sq, 4, (struct pt2){1, 2});
	CHECK(m.a == 1 && m.x == -0.5 && m.y == -1.5 && m.xy == 0.75);
	m = poly_moments(cw, 4, (struct pt2){0, 0});
	CHECK(m.a == -1 && m.x == -0.5 && m.xy == -0.25);
	/* the L: [0,3]×[0,1] ∪ [0,1]×[1,3], clipped to 0.5 ≤ y ≤ 2 → [0,3]×[0.5,1] ∪ [0,1]×[1,2] */
	struct pt2 ell[6] = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}}, out[24], tmp[12];
	int k = poly_clip_slab(ell, 6, 1, 0.5, 2, out, tmp);
	m = poly_moments(out, k, (struct pt2){0, 0});
	CHECK_NEAR(m.a, 2.5, 1e-15);
	CHECK_NEAR(m.x, 1.5 * 1.5 + 0.5 * 1, 1e-15);   /* ∫x: 1.5 area at x̄ 1.5, 1 at 0.5 */
	CHECK_NEAR(m.y, 1.5 * 0.75 + 1 * 1.5, 1e-15);  /* ∫y: ȳ 0.75 and 1.5 */
	CHECK(poly_clip_slab(ell, 6, 0, 4, 5, out, tmp) < 3);
	/* each axis cut on one side, the other or both (each its own inlined
	 * pass): the areas of the L's pieces, and ∫x of the first */
	static const struct {
		int axis;
		double lo, hi, area, mx;
	} cut[] = {
		{0, 0.5, 2, 1.5 + 0.5 * 2, 1.5 * 1.25 + 1 * 0.75}, /* [0.5,2]×[0,1] ∪ [0.5,1]×[1,3] */
		{0, 0.5, 10, 2.5 + 1, 2.5 * 1.75 + 1 * 0.75},      /* x ≥ 0.5 */
		{0, -10, 2, 2 + 2, 2 * 1 + 2 * 0.5},               /* x ≤ 2 */
		{1, 0.5, 10, 1.5 + 2, 1.5 * 1.5 + 2 * 0.5},        /* y ≥ 0.5 */
		{1, -10, 2, 3 + 1, 3 * 1.5 + 1 * 0.5},             /* y ≤ 2 */
		{1, -1, 4, 5, 3 * 1.5 + 2 * 0.5},                  /* inside: unchanged */
	};
	for (size_t c = 0; c < sizeof cut / sizeof cut[0]; c++) {
		k = poly_clip_slab(ell, 6, cut[c].axis, cut[c].lo, cut[c].hi, out, tmp);
		m = poly_moments(out, k, (struct pt2){0, 0});
		CHECK_NEAR(m.a, cut[c].area, 1e-15);
		CHECK_NEAR(m.x, cut[c].mx, 1e-14);
	}
	struct pt2 bow[4] = {{0, 0}, {2, 2}, {2, 0}, {0, 2}}, x;
	int a, b;
	CHECK(poly_crossing(bow, 4, &a, &b, &x) && a == 0 && b == 2 && x.x == 1 && x.y == 1);
	CHECK(!poly_crossing(ell, 6, &a, &b, &x));
	struct loops l = {0};
	poly_split(&l, bow, 4);
	CHECK(l.n == 2 && l.len[0] == 3 && l.len[1] == 3);
	CHECK_NEAR(poly_area(l.pt + l.start[0], 3), -poly_area(l.pt + l.start[1], 3), 1e-15);
	CHECK_NEAR(fabs(poly_area(l.pt + l.start[0], 3)), 1, 1e-15);
	struct pt2 star[5];
	for (int q = 0; q < 5; q++) /* every second corner of a pentagon */
		star[q] = (struct pt2){cos(q * 4 * M_PI / 5), sin(q * 4 * M_PI / 5)};
	poly_split(&l, star, 5);
	double sum = 0;
	int crossed = 0;
	for (int q = 0; q < l.n; q++) {
		crossed += poly_crossing(l.pt + l.start[q], l.len[q], &a, &b, &x);
		sum += poly_area(l.pt + l.start[q], l.len[q]);
	}
	CHECK(l.n >= 2 && crossed == 0);
	CHECK_NEAR(sum, poly_area(star, 5), 1e-14);
	loops_free(&l);
}

/* ==== exact shares ======================================================== */

/* A polygon covering exactly cell [i,i+1]×[j,j+1] gives each corner node ¼
 * of the energy, exactly, in either winding, on the plane, inside a sphere's
 * map and across its seam. */
/* poly_moments over every edge, as Green's theorem writes it (the two
 * edges at p[0], whose terms are ±0, included): the reference that
 * poly_moments, which leaves those two out, must match bit for bit. */
static struct moments moments_all_edges(const struct pt2 *p, int n, struct pt2 o)
{
	double a = 0, sx = 0, sy = 0, sxy = 0;
	for (int k = 0; k < n; k++) {
		const struct pt2 *q = &p[k + 1 < n ? k + 1 : 0];
		double x0 = p[k].x - p[0].x, y0 = p[k].y - p[0].y, x1 = q->x - p[0].x, y1 = q->y - p[0].y;
		double c = x0 * y1 - x1 * y0;
		a += c;
		sx += (x0 + x1) * c;
		sy += (y0 + y1) * c;
		sxy += (x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0) * c;
	}
	struct moments m = {a / 2, sx / 6, sy / 6, sxy / 24};
	double dx = p[0].x - o.x, dy = p[0].y - o.y;
	return (struct moments){m.a, m.x + dx * m.a, m.y + dy * m.a, m.xy + dx * m.y + dy * m.x + dx * dy * m.a};
}

static void t_moments_bits(void)
{
	rng_seed(11);
	long differ = 0, cases = 0, clips = 0;
	for (int t = 0; t < 20000; t++) {
		struct pt2 p[8], o = {rndr(-3, 3), rndr(-3, 3)};
		int n = 1 + (int)(rng_next() % 8), kind = (int)(rng_next() % 5);
		double scale = kind == 3 ? 1e-9 : kind == 4 ? 1e6 : 1;
		for (int k = 0; k < n; k++) {
			p[k] = (struct pt2){scale * rndr(-1, 1), scale * rndr(-1, 1)};
			if (kind == 1) /* collinear */
				p[k] = (struct pt2){p[0].x + (double)k * 0.25, p[0].y - (double)k * 0.5};
			if (kind == 2 && k % 2) /* signed zeros and exact repeats */
				p[k] = rng_next() % 2 ? p[0] : (struct pt2){-0.0, 0.0};
		}
		struct moments a = poly_moments(p, n, o), b = moments_all_edges(p, n, o);
		differ += memcmp(&a, &b, sizeof a) != 0;
		cases++;
		/* poly_clip_range given the corners' range: poly_clip_slab's corners */
		int axis = (int)(rng_next() % 2);
		double mn = axis ? p[0].y : p[0].x, mx = mn, lo = scale * rndr(-1.2, 1), hi = lo + scale * rndr(0, 1);
		for (int k = 1; k < n; k++)
			mn = fmin(mn, axis ? p[k].y : p[k].x), mx = fmax(mx, axis ? p[k].y : p[k].x);
		struct pt2 o1[32], o2[32], t1[16], t2[16];
		int k1 = poly_clip_slab(p, n, axis, lo, hi, o1, t1), k2 = poly_clip_range(p, n, axis, lo, hi, mn, mx, o2, t2);
		clips += k1 != k2 || memcmp(o1, o2, sizeof o1[0] * (size_t)(k1 > 0 ? k1 : 0)) != 0;
	}
	printf("# %ld polygons, %ld differ from the all-edges sum, %ld clipped otherwise\n", cases, differ, clips);
	CHECK(differ == 0);
	CHECK(clips == 0);
}

/* fmax_ and fmin_ (common/vec.h), which replaced libm's calls on the
 * light pass's path: libm's results, bit for bit, on signed zeros,
 * infinities, NaNs, denormals and ties (NaN against NaN: NaN both ways). */
static void t_fmax_inline(void)
{
	static volatile double v[] = {-INFINITY, -1, -0.0, 0.0, 5e-324, 1e-300, 1, 1, INFINITY, NAN, -NAN};
	int n = (int)(sizeof v / sizeof v[0]), differ = 0;
	for (int i = 0; i < n; i++)
		for (int j = 0; j < n; j++) {
			double a = v[i], b = v[j], r[4] = {fmax_(a, b), fmax(a, b), fmin_(a, b), fmin(a, b)};
			for (int k = 0; k < 4; k += 2)
				if (isnan(r[k]) || isnan(r[k + 1]) ? !(isnan(r[k]) && isnan(r[k + 1]))
				                                   : memcmp(&r[k], &r[k + 1], sizeof r[k]) != 0)
					differ++;
		}
	CHECK(differ == 0);
}

static void t_one_cell(void)
{
	static const enum object_kind kinds[] = {OBJ_PLANE, OBJ_SPHERE, OBJ_SPHERE};
	static const long ci[] = {-7, 3, 15}, cj[] = {4, 2, 5};
	for (int t = 0; t < 3; t++)
		for (int wind = 0; wind < 2; wind++) {
			struct object o = prim(kinds[t]);
			struct illum_map *m = t == 0 ? map_cell(&o, 0.25) : map_res(&o, 16);
			double uv[4][2], e[3] = {1, 0.375, 3e-6};
			static const int cx[4] = {0, 1, 1, 0}, cy[4] = {0, 0, 1, 1};
			for (int k = 0; k < 4; k++) {
				int q = wind ? 3 - k : k;
				grid_uv(m, (double)(ci[t] + cx[q]), (double)(cj[t] + cy[q]), uv[k]);
			}
			illum_deposit_poly(m, (const double (*)[2])uv, 4, e);
			struct nodes *s = nodes_of(m);
			CHECK(s->n == 4);
			long i1 = t == 2 ? 0 : ci[t] + 1; /* node 16 of 16 is node 0 */
			for (int c = 0; c < 3; c++) {
				CHECK(node_e(s, ci[t], cj[t], c) == e[c] / 4);
				CHECK(node_e(s, i1, cj[t], c) == e[c] / 4);
				CHECK(node_e(s, ci[t], cj[t] + 1, c) == e[c] / 4);
				CHECK(node_e(s, i1, cj[t] + 1, c) == e[c] / 4);
			}
			free(s);
			illum_free(m);
		}
}

/* Hand-integrated triangles on the plane, in node units about node (3,−5):
 * (0,0),(1,0),(0,1): ∫1 = 1/2, ∫x = ∫y = 1/6, ∫xy = 1/24 give shares 5/12,
 * 1/4, 1/4, 1/12; (0,0),(2,0),(0,2) (area 2) gives 1/8 at the origin node,
 * 11/48 at (1,0) and (0,1), 1/16 at (2,0) and (0,2), 1/4 at (1,1), 1/48 at
 * (2,1) and (1,2), and nothing at (2,2). */
static void t_triangles(void)
{
	struct object o = prim(OBJ_PLANE);
	static const double small[3][3] = {{0, 0, 5.0 / 12}, {1, 0, 0.25}, {0, 1, 0.25}};
	static const double big[9][3] = {{0, 0, 1.0 / 8},   {1, 0, 11.0 / 48}, {0, 1, 11.0 / 48},
	                                 {2, 0, 1.0 / 16},  {0, 2, 1.0 / 16},  {1, 1, 0.25},
	                                 {2, 1, 1.0 / 48},  {1, 2, 1.0 / 48},  {2, 2, 0}};
	for (int size = 1; size <= 2; size++) {
		struct illum_map *m = map_cell(&o, 0.1);
		double uv[3][2], e[3] = {2, 1, 0};
		grid_uv(m, 3, -5, uv[0]);
		grid_uv(m, 3 + size, -5, uv[1]);
		grid_uv(m, 3, -5 + size, uv[2]);
		illum_deposit_poly(m, (const double (*)[2])uv, 3, e);
		struct nodes *s = nodes_of(m);
		const double (*want)[3] = size == 1 ? small : big;
		int nw = size == 1 ? 3 : 9;
		for (int k = 0; k < nw; k++)
			CHECK_NEAR(node_e(s, 3 + (long)want[k][0], -5 + (long)want[k][1], 0), 2 * want[k][2], 1e-15);
		if (size == 1)
			CHECK_NEAR(node_e(s, 4, -4, 0), 2.0 / 12, 1e-15);
		CHECK(s->n == (size == 1 ? 4 : 8));
		CHECK(node_e(s, 3, -5, 2) == 0);
		free(s);
		illum_free(m);
	}
}

/* A tiny polygon (1e-5 of a spacing) gives the shares of a point deposit at
 * its centroid, to 1e-9 of the energy, on a sphere's map. */
static void t_tiny(void)
{
	rng_seed(31);
	struct object o = prim(OBJ_SPHERE);
	int bad = 0;
	for (int t = 0; t < 200; t++) {
		struct illum_map *mp = map_res(&o, 12), *mq = illum_new_like(mp);
		double cx = rndr(0.5, 11.5), cy = rndr(0.5, 11.5), h = 1e-5, uv[4][2], e[3] = {1, 2, 0.5};
		double px[4], py[4], a2 = 0, gx = 0, gy = 0;
		for (int k = 0; k < 4; k++) { /* a convex quad: corners at increasing angles */
			double ang = (k + rndr(0.1, 0.9)) * M_PI / 2, r = h * rndr(0.5, 1);
			px[k] = cx + r * cos(ang);
			py[k] = cy + r * sin(ang);
			grid_uv(mp, px[k], py[k], uv[k]);
		}
		for (int k = 0; k < 4; k++) { /* area centroid */
			int q = (k + 1) % 4;
			double c = (px[k] - cx) * (py[q] - cy) - (px[q] - cx) * (py[k] - cy);
			a2 += c;
			gx += (px[k] + px[q] - 2 * cx) * c;
			gy += (py[k] + py[q] - 2 * cy) * c;
		}
		double g[2];
		grid_uv(mp, cx + gx / (3 * a2), cy + gy / (3 * a2), g);
		illum_deposit_poly(mp, (const double (*)[2])uv, 4, e);
		illum_deposit(mq, g[0], g[1], e);
		struct nodes *sp = nodes_of(mp), *sq = nodes_of(mq);
		for (int k = 0; k < sq->n; k++)
			for (int c = 0; c < 3; c++)
				bad += fabs(node_e(sp, sq->a[k].i, sq->a[k].j, c) - sq->a[k].energy[c]) > 1e-9 * e[c];
		for (int k = 0; k < sp->n; k++)
			bad += !node(sq, sp->a[k].i, sp->a[k].j) && sp->a[k].energy[0] > 1e-9;
		free(sp);
		free(sq);
		illum_free(mp);
		illum_free(mq);
	}
	CHECK(bad == 0);
}

/* ==== conservation ======================================================== */

/* A random polygon in node units around (cx, cy) of size h: kind 0 a convex
 * quad, 1 a triangle, 2 a star-shaped (non-convex) hexagon, 3 a bow-tie, 4 a
 * zero-area (collinear) quad; either winding. Returns the corner count. */
static int random_poly(double cx, double cy, double h, int kind, double p[6][2])
{
	int n = kind == 1 ? 3 : kind == 2 ? 6 : 4;
	for (int k = 0; k < n; k++) {
		double ang = (k + rndr(0.1, 0.9)) * 2 * M_PI / n, r = h * (kind == 2 && k % 2 ? rndr(0.1, 0.4) : rndr(0.5, 1));
		p[k][0] = cx + r * cos(ang);
		p[k][1] = cy + r * sin(ang);
		if (kind == 4) {
			p[k][0] = cx + h * (k % 2 ? 0.3 : -0.7) * (k + 1);
			p[k][1] = cy + 0.5 * (p[k][0] - cx);
		}
	}
	if (kind == 3) { /* swap two corners: the edges 0→1 and 2→3 cross */
		double t[2] = {p[1][0], p[1][1]};
		p[1][0] = p[2][0], p[1][1] = p[2][1];
		p[2][0] = t[0], p[2][1] = t[1];
	}
	if (rnd() < 0.5)
		for (int k = 0; k < n / 2; k++)
			for (int d = 0; d < 2; d++) {
				double t = p[k][d];
				p[k][d] = p[n - 1 - k][d];
				p[n - 1 - k][d] = t;
			}
	return n;
}

/* Every polygon deposit adds exactly fx(energy), the same as a point deposit
 * on a node: the total equals that of a reference map, bit for bit, on a
 * plane, sphere, torus, box and cone map; polygons of every kind and size,
 * across seams, partly outside clamped domains, and some huge. A single
 * deposit into an empty map totals its energy exactly. */
static void t_conservation(void)
{
	static const enum object_kind kinds[] = {OBJ_PLANE, OBJ_SPHERE, OBJ_TORUS, OBJ_BOX, OBJ_CONE};
	rng_seed(17);
	for (int t = 0; t < 5; t++) {
		struct object o = prim(kinds[t]);
		struct illum_map *m = kinds[t] == OBJ_PLANE ? map_cell(&o, 0.05) : map_res(&o, 24);
		struct illum_map *ref = illum_new_like(m);
		long nu, nv;
		illum_grid(m, &nu, &nv, NULL, NULL);
		double span = nu ? (double)nu : 60, r0[2], one_bad = 0;
		illum_node_uv(m, 0, 0, &r0[0], &r0[1]);
		for (int k = 0; k < 3000; k++) {
			double p[6][2], uv[6][2], e[3] = {rnd(), 1e-7 * rnd(), 50 * rnd()};
			double h = span * exp(rndr(log(1e-4), log(0.4))) * (k % 97 == 0 ? 20 : 1);
			double cx = rndr(-0.1, 1.1) * span, cy = rndr(-0.1, 1.1) * (nv ? (double)nv : span);
			int n = random_poly(cx, cy, h, k % 5, p);
			for (int q = 0; q < n; q++)
				grid_uv(m, p[q][0], p[q][1], uv[q]);
			illum_deposit_poly(m, (const double (*)[2])uv, n, e);
			illum_deposit(ref, r0[0], r0[1], e);
			if (k % 50 == 0) { /* alone in a map: exactly e */
				struct illum_map *m1 = illum_new_like(m);
				double got[3];
				illum_deposit_poly(m1, (const double (*)[2])uv, n, e);
				illum_total(m1, got);
				for (int c = 0; c < 3; c++)
					one_bad += got[c] != e[c];
				illum_free(m1);
			}
		}
		double got[3], want[3];
		illum_total(m, got);
		illum_total(ref, want);
		CHECK(memcmp(got, want, sizeof got) == 0);
		CHECK(one_bad == 0);
		CHECK(illum_dropped(m) == 0);
		illum_free(m);
		illum_free(ref);
	}
}

/* ==== uniform fields ====================================================== */

/* The cells of a jittered lattice (quads, not aligned with the grid) tile
 * [−1,1]² on the plane; each carries energy D × its area. Interior nodes
 * then read irradiance D (the plane's node area is du·dv) to 1e-12. */
static void t_tiling_plane(void)
{
	enum { N = 54 };
	static double x[N + 1][N + 1][2];
	rng_seed(41);
	struct object o = prim(OBJ_PLANE);
	struct illum_map *m = map_cell(&o, 0.1);
	double h = 2.0 / N, D = 3.5;
	for (int a = 0; a <= N; a++)
		for (int b = 0; b <= N; b++) { /* edges of the square stay straight */
			bool eu = a == 0 || a == N, ev = b == 0 || b == N;
			x[a][b][0] = -1 + h * a + (eu ? 0 : rndr(-0.3, 0.3) * h);
			x[a][b][1] = -1 + h * b + (ev ? 0 : rndr(-0.3, 0.3) * h);
		}
	for (int a = 0; a < N; a++)
		for (int b = 0; b < N; b++) {
			double q[4][2];
			memcpy(q[0], x[a][b], sizeof q[0]);
			memcpy(q[1], x[a + 1][b], sizeof q[0]);
			memcpy(q[2], x[a + 1][b + 1], sizeof q[0]);
			memcpy(q[3], x[a][b + 1], sizeof q[0]);
			double area = 0.5 * ((q[2][0] - q[0][0]) * (q[3][1] - q[1][1]) - (q[3][0] - q[1][0]) * (q[2][1] - q[0][1]));
			double e[3] = {D * area, 2 * D * area, 0};
			illum_deposit_poly(m, (const double (*)[2])q, 4, e);
		}
	illum_finish(m, true, NULL);
	struct nodes *s = nodes_of(m);
	int inner = 0;
	double worst = 0;
	for (int k = 0; k < s->n; k++) {
		const struct illum_node *n = &s->a[k];
		if (fabs(n->u) > 0.95 || fabs(n->v) > 0.95)
			continue;
		inner++;
		worst = fmax(worst, fabs(n->irr[0] / D - 1));
		worst = fmax(worst, fabs(n->irr[1] / (2 * D) - 1));
	}
	CHECK(inner == 19 * 19);
	CHECK(worst <= 1e-12);
	double lk[3];
	illum_lookup(m, 0.337, -0.52, lk);
	CHECK_NEAR(lk[0], D, 1e-12 * D);
	printf("# plane tiling: %d interior nodes, worst relative error %.3g\n", inner, worst);
	free(s);
	illum_free(m);
}

/* The whole (u,v) domain of a torus (both axes wrap), tiled by quads of a
 * lattice that is jittered and offset so cells straddle both seams, each
 * with energy D × its (u,v) area: every node gets D·du·dv to 1e-12. */
static void t_tiling_torus(void)
{
	enum { N = 40 };
	static double x[N + 1][N + 1][2];
	rng_seed(43);
	struct object o = prim(OBJ_TORUS);
	struct illum_map *m = map_res(&o, 24);
	double h = 1.0 / N, D = 2.0, off = 0.013;
	for (int a = 0; a <= N; a++)
		for (int b = 0; b <= N; b++) { /* periodic jitter: the lattice closes on itself */
			int pa = a % N, pb = b % N;
			rng_seed(1000 + (uint64_t)(pa * N + pb));
			x[a][b][0] = off + h * a + rndr(-0.3, 0.3) * h;
			x[a][b][1] = -off + h * b + rndr(-0.3, 0.3) * h;
		}
	for (int a = 0; a < N; a++)
		for (int b = 0; b < N; b++) {
			double q[4][2];
			memcpy(q[0], x[a][b], sizeof q[0]);
			memcpy(q[1], x[a + 1][b], sizeof q[0]);
			memcpy(q[2], x[a + 1][b + 1], sizeof q[0]);
			memcpy(q[3], x[a][b + 1], sizeof q[0]);
			double area = 0.5 * ((q[2][0] - q[0][0]) * (q[3][1] - q[1][1]) - (q[3][0] - q[1][0]) * (q[2][1] - q[0][1]));
			for (int k = 0; k < 4; k++) /* corners given wrapped into [0,1) */
				for (int d = 0; d < 2; d++)
					q[k][d] -= floor(q[k][d]);
			double e[3] = {D * area, 0, 0};
			illum_deposit_poly(m, (const double (*)[2])q, 4, e);
		}
	struct nodes *s = nodes_of(m);
	double worst = 0, want = D / (24.0 * 24.0);
	for (int k = 0; k < s->n; k++)
		worst = fmax(worst, fabs(s->a[k].energy[0] / want - 1));
	CHECK(s->n == 24 * 24);
	CHECK(worst <= 1e-12);
	printf("# torus tiling: worst relative error %.3g\n", worst);
	free(s);
	illum_free(m);
}

/* ==== seams, edges, folds ================================================= */

/* A quad across a sphere's seam (u from 0.97 to 1.03, given as 0.97 and
 * 0.03) lands on both sides, symmetrically, conserves its energy, and is the
 * same deposit as the quad given unwrapped. */
static void t_seam(void)
{
	struct object o = prim(OBJ_SPHERE);
	struct illum_map *m = map_res(&o, 16), *m2 = illum_new_like(m);
	double q[4][2] = {{0.97, 0.40}, {0.03, 0.40}, {0.03, 0.45}, {0.97, 0.45}}, e[3] = {1, 1, 1}, got[3];
	double q2[4][2] = {{0.97, 0.40}, {1.03, 0.40}, {1.03, 0.45}, {0.97, 0.45}};
	illum_deposit_poly(m, (const double (*)[2])q, 4, e);
	illum_deposit_poly(m2, (const double (*)[2])q2, 4, e);
	illum_total(m, got);
	CHECK(got[0] == 1 && got[2] == 1);
	struct nodes *s = nodes_of(m), *s2 = nodes_of(m2);
	double west = 0, east = 0, mid = 0;
	for (int k = 0; k < s->n; k++) {
		const struct illum_node *n = &s->a[k];
		west += n->i == 15 ? n->energy[0] : 0;
		mid += n->i == 0 ? n->energy[0] : 0;
		east += n->i == 1 ? n->energy[0] : 0;
		CHECK(n->i == 15 || n->i == 0 || n->i == 1);
	}
	CHECK(west > 0.01 && east > 0.01 && mid > 0.5);
	CHECK_NEAR(west, east, 1e-14);
	CHECK(s->n == s2->n);
	for (int k = 0; k < s->n; k++)
		CHECK_NEAR(s->a[k].energy[0], node_e(s2, s->a[k].i, s->a[k].j, 0), 1e-15);
	free(s);
	free(s2);
	illum_free(m);
	illum_free(m2);
}

/* A clamped edge: a cell-sized square half beyond a sphere's north pole row
 * (node units: x in [3,4], y in [15.5,16.5], the pole row is 16). The half
 * inside, y in [15.5,16] of cell row 15, gives row 15 ∫(1−y') = 1/8 and row
 * 16 ∫y' = 3/8; the half outside clamps onto row 16, which gets 7/8 in all.
 * Each row splits evenly between columns 3 and 4. */
static void t_clamp(void)
{
	struct object o = prim(OBJ_SPHERE);
	struct illum_map *m = map_res(&o, 16);
	double q[4][2], e[3] = {1, 0, 0};
	static const double c[4][2] = {{3, 15.5}, {4, 15.5}, {4, 16.5}, {3, 16.5}};
	for (int k = 0; k < 4; k++)
		grid_uv(m, c[k][0], c[k][1], q[k]);
	illum_deposit_poly(m, (const double (*)[2])q, 4, e);
	struct nodes *s = nodes_of(m);
	CHECK(s->n == 4);
	CHECK_NEAR(node_e(s, 3, 15, 0), 1.0 / 16, 1e-15);
	CHECK_NEAR(node_e(s, 4, 15, 0), 1.0 / 16, 1e-15);
	CHECK_NEAR(node_e(s, 3, 16, 0), 7.0 / 16, 1e-15);
	CHECK_NEAR(node_e(s, 4, 16, 0), 7.0 / 16, 1e-15);
	free(s);
	illum_free(m);
}

/* A non-convex polygon: an L-shaped hexagon is its two rectangles, with
 * the energy split by area. */
static void t_nonconvex(void)
{
	struct object o = prim(OBJ_PLANE);
	struct illum_map *m = map_cell(&o, 0.1), *r = illum_new_like(m);
	double e[3] = {3, 0, 0}, e1[3] = {2.4, 0, 0}, e2[3] = {0.6, 0, 0};
	static const double ell[6][2] = {{0, 0}, {0.4, 0}, {0.4, 0.1}, {0.1, 0.1}, {0.1, 0.2}, {0, 0.2}};
	static const double ra[4][2] = {{0, 0}, {0.4, 0}, {0.4, 0.1}, {0, 0.1}}, rb[4][2] = {{0, 0.1}, {0.1, 0.1}, {0.1, 0.2}, {0, 0.2}};
	double d[6][2];
	for (int k = 0; k < 6; k++) /* off the grid lines */
		d[k][0] = ell[k][0] + 0.0137, d[k][1] = ell[k][1] - 0.0291;
	illum_deposit_poly(m, (const double (*)[2])d, 6, e);
	for (int k = 0; k < 4; k++)
		d[k][0] = ra[k][0] + 0.0137, d[k][1] = ra[k][1] - 0.0291;
	illum_deposit_poly(r, (const double (*)[2])d, 4, e1); /* area 0.04 of 0.05 */
	for (int k = 0; k < 4; k++)
		d[k][0] = rb[k][0] + 0.0137, d[k][1] = rb[k][1] - 0.0291;
	illum_deposit_poly(r, (const double (*)[2])d, 4, e2);
	struct nodes *s = nodes_of(m), *sr = nodes_of(r);
	CHECK(s->n == sr->n);
	for (int k = 0; k < sr->n; k++)
		CHECK_NEAR(node_e(s, sr->a[k].i, sr->a[k].j, 0), sr->a[k].energy[0], 1e-14);
	free(s);
	free(sr);
	illum_free(m);
	illum_free(r);
}

/* A fold: a bow-tie quad is split at its crossing into two triangles, here
 * of equal area, so it is those triangles with half the energy each; every
 * node gets a share in [0, e], mirror-symmetric. */
static void t_bowtie(void)
{
	struct object o = prim(OBJ_PLANE);
	struct illum_map *m = map_cell(&o, 0.1), *r = illum_new_like(m);
	double e[3] = {3, 0, 0};
	/* edges 0→1 and 2→3 cross at (0.15, 0.12): node column 1.5, the mirror line */
	double bow[4][2] = {{0.05, 0.02}, {0.25, 0.22}, {0.25, 0.02}, {0.05, 0.22}};
	double t1[3][2] = {{0.15, 0.12}, {0.25, 0.22}, {0.25, 0.02}}, t2[3][2] = {{0.15, 0.12}, {0.05, 0.22}, {0.05, 0.02}};
	double half[3] = {1.5, 0, 0}, got[3];
	struct nodes *s, *sr;
	illum_deposit_poly(m, (const double (*)[2])bow, 4, e);
	illum_deposit_poly(r, (const double (*)[2])t1, 3, half);
	illum_deposit_poly(r, (const double (*)[2])t2, 3, half);
	illum_total(m, got);
	CHECK(got[0] == 3);
	s = nodes_of(m);
	sr = nodes_of(r);
	CHECK(s->n == sr->n);
	for (int k = 0; k < sr->n; k++)
		CHECK_NEAR(node_e(s, sr->a[k].i, sr->a[k].j, 0), sr->a[k].energy[0], 1e-14);
	for (int k = 0; k < s->n; k++) /* a negative share would wrap around to ~2^32 W */
		CHECK(s->a[k].energy[0] <= 3);
	CHECK(node_e(s, 1, 1, 0) > 0.1);
	CHECK_NEAR(node_e(s, 1, 1, 0), node_e(s, 2, 1, 0), 1e-14); /* mirror-symmetric lobes */
	CHECK_NEAR(node_e(s, 0, 2, 0), node_e(s, 3, 2, 0), 1e-14);
	free(s);
	free(sr);
	illum_free(m);
	illum_free(r);
}

/* A pentagram (5 crossings) and a 100-corner circle (crossings not looked
 * for; simple anyway): exact totals, shares in [0, e], and the circle about
 * node (2,3) symmetric under quarter turns. */
static void t_many_corners(void)
{
	struct object o = prim(OBJ_PLANE);
	struct illum_map *m = map_cell(&o, 0.1);
	double star[5][2], circ[100][2], e[3] = {3, 0, 0}, got[3];
	for (int q = 0; q < 5; q++)
		star[q][0] = 0.5 + 0.3 * cos(q * 4 * M_PI / 5), star[q][1] = 0.5 + 0.3 * sin(q * 4 * M_PI / 5);
	for (int q = 0; q < 100; q++)
		circ[q][0] = 0.2 + 0.25 * cos(q * M_PI / 50), circ[q][1] = 0.3 + 0.25 * sin(q * M_PI / 50);
	illum_deposit_poly(m, (const double (*)[2])star, 5, e);
	illum_total(m, got);
	CHECK(got[0] == 3);
	struct nodes *s = nodes_of(m);
	CHECK(s->n >= 16);
	for (int k = 0; k < s->n; k++)
		CHECK(s->a[k].energy[0] <= 3);
	free(s);
	illum_free(m);
	m = map_cell(&o, 0.1);
	illum_deposit_poly(m, (const double (*)[2])circ, 100, e);
	illum_total(m, got);
	CHECK(got[0] == 3);
	s = nodes_of(m);
	CHECK(s->n == 45); /* radius 2.5 spacings: the 7×7 around (2,3) less its corners */
	for (int k = 0; k < s->n; k++) {
		long di = s->a[k].i - 2, dj = s->a[k].j - 3;
		CHECK_NEAR(s->a[k].energy[0], node_e(s, 2 - dj, 3 + di, 0), 1e-13);
	}
	free(s);
	illum_free(m);
}

/* ==== huge and degenerate polygons ======================================== */

static long gcd(long a, long b) { return b ? gcd(b, a % b) : labs(a); }

/* A square of 50 units on a plane of cell 0.001 (2.5e9 cells) is rasterised
 * on every s-th node: bounded time and memory, exact total, nodes only on
 * multiples of s, and an even spread (interior nodes equal to 1e-9: a share
 * is exact to ~2^-53 of the whole energy, here 38,000 nodes' worth). */
static void t_huge(void)
{
	struct object o = prim(OBJ_PLANE);
	struct illum_map *m = map_cell(&o, 0.001);
	double q[4][2] = {{-20.0003, -30.0007}, {30.0002, -30.0007}, {30.0002, 20.0001}, {-20.0003, 20.0001}};
	double e[3] = {7, 1, 0}, got[3];
	clock_t t0 = clock();
	illum_deposit_poly(m, (const double (*)[2])q, 4, e);
	double sec = (double)(clock() - t0) / CLOCKS_PER_SEC;
	illum_total(m, got);
	CHECK(got[0] == 7 && got[1] == 1);
	struct nodes *s = nodes_of(m);
	long stride = 0;
	for (int k = 0; k < s->n; k++)
		stride = gcd(gcd(stride, s->a[k].i), s->a[k].j);
	double lo = INFINITY, hi = 0;
	for (int k = 0; k < s->n; k++)
		if (fabs(s->a[k].u) < 15 && fabs(s->a[k].v + 5) < 15) {
			lo = fmin(lo, s->a[k].energy[0]);
			hi = fmax(hi, s->a[k].energy[0]);
		}
	printf("# huge: %d nodes, stride %ld, %.3f s, %zu bytes\n", s->n, stride, sec, illum_memory(m));
	CHECK(s->n > 10000 && s->n <= ILLUM_POLY_MAX_CELLS + 1000);
	CHECK(stride >= 128 && (stride & (stride - 1)) == 0);
	CHECK(hi > 0 && (hi - lo) <= 1e-9 * hi);
	CHECK(sec < 2);
	CHECK(illum_memory(m) < ((size_t)40 << 20));
	free(s);
	illum_free(m);
}

/* Zero area falls back to a point deposit at the corners' mean (the same
 * nodes and shares); n < 3 likewise; a non-finite corner is dropped and
 * counted; NaN and negative energies count as 0. */
static void t_degenerate(void)
{
	struct object o = prim(OBJ_TORUS);
	struct illum_map *m = map_res(&o, 20), *r = illum_new_like(m);
	double line[4][2] = {{0.11, 0.21}, {0.31, 0.26}, {0.51, 0.31}, {0.31, 0.26}}, e[3] = {1, -1, NAN}, got[3];
	illum_deposit_poly(m, (const double (*)[2])line, 4, e);
	illum_deposit(r, 0.31, 0.26, e);
	double two[2][2] = {{0.61, 0.7}, {0.65, 0.74}};
	illum_deposit_poly(m, (const double (*)[2])two, 2, e);
	illum_deposit(r, 0.63, 0.72, e);
	struct nodes *s = nodes_of(m), *sr = nodes_of(r);
	CHECK(s->n == sr->n && s->n == 8);
	for (int k = 0; k < sr->n && k < s->n; k++) {
		CHECK(s->a[k].i == sr->a[k].i && s->a[k].j == sr->a[k].j && s->a[k].count == 1);
		CHECK_NEAR(s->a[k].energy[0], sr->a[k].energy[0], 1e-15);
		CHECK(s->a[k].energy[1] == 0 && s->a[k].energy[2] == 0);
	}
	illum_total(m, got);
	CHECK(got[0] == 2 && got[1] == 0 && got[2] == 0);
	double bad[3][2] = {{0.1, 0.1}, {INFINITY, 0.2}, {0.2, 0.3}};
	illum_deposit_poly(m, (const double (*)[2])bad, 3, e);
	bad[1][0] = 0.15, bad[2][1] = NAN;
	illum_deposit_poly(m, (const double (*)[2])bad, 3, e);
	CHECK(illum_dropped(m) == 2);
	illum_total(m, got);
	CHECK(got[0] == 2);
	free(s);
	free(sr);
	illum_free(m);
	illum_free(r);
}

/* A polygon deposit is one sample: the nodes with a share get count 1 and
 * Σw² = (share·e)². */
static void t_bookkeeping(void)
{
	struct object o = prim(OBJ_PLANE);
	struct illum_map *m = map_cell(&o, 0.1);
	double uv[3][2], e[3] = {2, 4, 1};
	grid_uv(m, 3, -5, uv[0]);
	grid_uv(m, 5, -5, uv[1]);
	grid_uv(m, 3, -3, uv[2]);
	illum_deposit_poly(m, (const double (*)[2])uv, 3, e);
	struct nodes *s = nodes_of(m);
	CHECK(s->n == 8);
	for (int k = 0; k < s->n; k++) {
		CHECK(s->a[k].count == 1);
		for (int c = 0; c < 3; c++)
			CHECK_NEAR(s->a[k].sumsq[c], s->a[k].energy[c] * s->a[k].energy[c], 1e-6 * s->a[k].sumsq[c]);
	}
	CHECK_NEAR(node(s, 4, -4)->sumsq[1], (4 * 0.25) * (4 * 0.25), 1e-7); /* share ¼ */
	free(s);
	illum_free(m);
}

/* ==== threads ============================================================= */

/* illum_deposit_poly_all gives the same map, bit for bit (energies, Σw²,
 * counts, drops), for 1, 2, 3 and 7 threads as one by one, over more than
 * one of its rounds: on a plane with polygons spanning several bands and a
 * few huge ones, on a torus with seam crossings, and on a sphere with some
 * beyond its poles (clamped onto the edge rows). In coloured light and
 * in white light, where its map stays grey (a tile of a third the size)
 * while one by one makes it colour: the same numbers all the same. Spread
 * over the bands (written band by band) and, on the plane, in a strip of
 * one band (integrated on all threads first, then written). */
static void threads_case(bool white, bool narrow);

static void t_threads(void)
{
	for (int white = 0; white < 2; white++)
		threads_case(white, false);
	threads_case(false, true);
}

static void threads_case(bool white, bool narrow)
{
	enum { N = 17000 }; /* more than one round of illum_deposit_poly_all (POLY_ROUND) */
	static double corners[N][6][2];
	static struct illum_poly p[N];
	static const struct illum_poly *pp[N]; /* (illum_deposit_poly_all reads them by pointer) */
	static const enum object_kind kinds[] = {OBJ_PLANE, OBJ_TORUS, OBJ_SPHERE};
	for (int shape = 0; shape < (narrow ? 1 : 3); shape++) {
		rng_seed(61 + shape);
		struct object o = prim(kinds[shape]);
		struct illum_map *one = shape ? map_res(&o, 96) : map_cell(&o, 0.01);
		for (int k = 0; k < N; k++) {
			double h = narrow ? rndr(0.1, 5)
			                  : exp(rndr(log(0.1), log(shape ? 20 : 80))) * (k % 500 == 7 ? 100 : 1);
			double cx = rndr(-100, 100), cy = narrow ? rndr(2, 25) : shape == 2 ? rndr(-10, 105) : rndr(-100, 100);
			int n = random_poly(cx, cy, h, k % 5, corners[k]);
			for (int q = 0; q < n; q++)
				grid_uv(one, corners[k][q][0], corners[k][q][1], corners[k][q]);
			double x = rnd();
			p[k] = (struct illum_poly){(const double (*)[2])corners[k], n,
			                           {x, white ? x : 1e-9 * rnd(), white ? x : 0}};
			pp[k] = &p[k];
		}
		corners[17][1][0] = NAN;
		for (int k = 0; k < N; k++)
			illum_deposit_poly(one, p[k].uv, p[k].n, p[k].e);
		struct nodes *s1 = nodes_of(one);
		printf("# %s, %s light%s: %d nodes, %ld tiles\n", shape == 2 ? "sphere" : shape ? "torus" : "plane",
		       white ? "white" : "coloured", narrow ? ", one band" : "", s1->n, illum_tiles(one));
		CHECK(s1->n > 1000 && s1->n < MAXN);
		static const int threads[] = {1, 2, 3, 7};
		for (int t = 0; t < 4; t++) {
			struct illum_map *m = shape ? map_res(&o, 96) : map_cell(&o, 0.01);
			illum_deposit_poly_all(m, pp, N, threads[t]);
			/* a grey map's tiles: 120 bytes for four nodes, a colour one's 280 */
			CHECK(white == (illum_memory(m) < 0.6 * illum_memory(one)));
			struct nodes *s2 = nodes_of(m);
			int diff = s1->n != s2->n;
			for (int q = 0; q < s1->n && q < s2->n; q++) {
				const struct illum_node *a = &s1->a[q], *b = &s2->a[q];
				diff += memcmp(a->energy, b->energy, sizeof a->energy) != 0;
				diff += memcmp(a->sumsq, b->sumsq, sizeof a->sumsq) != 0;
				diff += a->count != b->count || a->i != b->i || a->j != b->j;
			}
			CHECK(diff == 0);
			CHECK(illum_dropped(m) == 1 && illum_tiles(m) == illum_tiles(one));
			free(s2);
			illum_free(m);
		}
		free(s1);
		illum_free(one);
	}
}

int main(void)
{
	RUN(t_geometry);
	RUN(t_moments_bits);
	RUN(t_fmax_inline);
	RUN(t_one_cell);
	RUN(t_triangles);
	RUN(t_tiny);
	RUN(t_conservation);
	RUN(t_tiling_plane);
	RUN(t_tiling_torus);
	RUN(t_seam);
	RUN(t_clamp);
	RUN(t_nonconvex);
	RUN(t_bowtie);
	RUN(t_many_corners);
	RUN(t_huge);
	RUN(t_degenerate);
	RUN(t_bookkeeping);
	RUN(t_threads);
	return test_done();
}
