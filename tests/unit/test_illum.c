/* SPDX-License-Identifier: MIT */
/* test_illum.c: illumination maps (tracer/light/illum.h): exact energy
 * conservation on every primitive, the bilinear split, unbiased irradiance
 * for uniform flux (poles, apex, disc centre included), sparse tiles on the
 * unbounded plane, order-independent merges, energies far above 2^32 W,
 * grey (white-light) maps, the isolated-sample rule, the ray-density rule
 * and the EXR dump. Random numbers: geo_rand.h, fixed seeds. */
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "../../tracer/light/illum.h"
#include "../../tracer/output/exrout.h"
#include "geo_rand.h"
#include "test.h"

static const enum object_kind all_kinds[] = {OBJ_SPHERE,   OBJ_PLANE, OBJ_BOX,   OBJ_DISC,
                                             OBJ_CYLINDER, OBJ_CONE,  OBJ_TORUS, OBJ_TRIANGLE};
#define NKINDS(a) ((int)(sizeof(a) / sizeof(a[0])))

/* A fixed primitive of each kind (identity transform). */
static struct object prim(enum object_kind k)
{
	struct object o = mk_obj(k);
	switch (k) {
	case OBJ_SPHERE: o.g.sphere.c = v3(0.5, 1, -2); o.g.sphere.r = 1.5; break;
	case OBJ_PLANE: o.g.plane.n = v3(0, 1, 0); o.g.plane.d = 0; break;
	case OBJ_BOX: o.g.box.lo = v3(-1, -0.5, -2); o.g.box.hi = v3(1, 1, 1); break;
	case OBJ_DISC: o.g.disc.c = v3(0, 1, 0); o.g.disc.n = v3(0, 1, 0); o.g.disc.r = 2; break;
	case OBJ_CYLINDER: o.g.cylinder.a = v3(0, 0, 0); o.g.cylinder.b = v3(0, 2, 0); o.g.cylinder.r = 1; break;
	case OBJ_CONE:
		o.g.cone.a = v3(0, 0, 0); o.g.cone.ra = 1; o.g.cone.b = v3(0, 2, 0); o.g.cone.rb = 0;
		break;
	case OBJ_TORUS: o.g.torus.major = 2; o.g.torus.minor = 0.5; break;
	case OBJ_TRIANGLE:
		o.g.triangle.p[0] = v3(0, 0, 0); o.g.triangle.p[1] = v3(2, 0, 0); o.g.triangle.p[2] = v3(0, 0, 2);
		break;
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

/* ==== collecting nodes ==================================================== */

#define MAXN (1 << 17)
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

/* How many nodes of two maps differ, bit for bit (energies, Σw²,
 * irradiance, counts, place, isolated flag), counting a different number of
 * nodes as one. */
static int node_diffs(const struct nodes *s1, const struct nodes *s2)
{
	int diff = s1->n != s2->n;
	for (int q = 0; q < s1->n && q < s2->n; q++) {
		const struct illum_node *a = &s1->a[q], *b = &s2->a[q];
		diff += memcmp(a->energy, b->energy, sizeof a->energy) != 0;
		diff += memcmp(a->sumsq, b->sumsq, sizeof a->sumsq) != 0;
		diff += memcmp(a->irr, b->irr, sizeof a->irr) != 0;
		diff += a->count != b->count || a->i != b->i || a->j != b->j || a->isolated != b->isolated;
	}
	return diff;
}

/* Map m, its deposits made on `threads` threads, finished the same way,
 * is map one (nodes s1, energy removed by the isolated rule rem1) bit for
 * bit, with one deposit dropped; m is freed. */
static void check_same_map(const struct illum_map *one, const struct nodes *s1, const double rem1[3],
                           struct illum_map *m, int threads)
{
	double rem[3];
	illum_finish_mt(m, true, rem, threads);
	struct nodes *s2 = nodes_of(m);
	CHECK(node_diffs(s1, s2) == 0);
	CHECK(memcmp(rem, rem1, 3 * sizeof *rem) == 0);
	CHECK(illum_dropped(m) == 1 && illum_tiles(m) == illum_tiles(one));
	free(s2);
	illum_free(m);
}

/* Energy of node (i,j) in channel 0, 0 when absent. */
static double node_e(const struct nodes *s, long i, long j)
{
	for (int k = 0; k < s->n; k++)
		if (s->a[k].i == i && s->a[k].j == j)
			return s->a[k].energy[0];
	return 0;
}

/* ==== energy conservation ================================================= */

static void t_conservation(void)
{
	rng_seed(11);
	for (int k = 0; k < NKINDS(all_kinds); k++) {
		struct object o = prim(all_kinds[k]);
		struct uv_range r;
		CHECK(shape_uv_range(&o, &r));
		struct illum_map *m = o.kind == OBJ_PLANE ? map_cell(&o, 0.25) : map_res(&o, 12);
		CHECK(m != NULL);
		double want[3] = {0, 0, 0};
		for (int n = 0; n < 20000; n++) {
			double u = r.bounded ? rnd() : rndr(-3, 3), v = r.bounded ? rnd() : rndr(-3, 3);
			if (n % 4 == 0 && r.u_wraps)
				u = rnd() < 0.5 ? rndr(0.99, 1.0) : rndr(-0.3, 1.3); /* seam, out of period */
			if (n % 4 == 1 && r.v_wraps)
				v = rndr(-0.05, 0.05);
			double e[3] = {rnd(), 1e-6 * rnd(), 100 * rnd()};
			illum_deposit(m, u, v, e);
			for (int c = 0; c < 3; c++)
				want[c] += e[c];
		}
		double got[3];
		illum_total(m, got);
		struct nodes *s = nodes_of(m);
		double sum0 = 0;
		for (int q = 0; q < s->n; q++)
			sum0 += s->a[q].energy[0];
		for (int c = 0; c < 3; c++)
			CHECK_NEAR(got[c] / want[c], 1, 1e-12);
		CHECK_NEAR(sum0 / want[0], 1, 1e-12);
		free(s);
		illum_free(m);
	}
}

/* ==== bilinear split ====================================================== */

static void t_split(void)
{
	struct object o = prim(OBJ_SPHERE);
	struct illum_map *m = map_res(&o, 8);
	long nu, nv;
	double du, dv;
	illum_grid(m, &nu, &nv, &du, &dv);
	CHECK(nu == 8 && nv == 9); /* u wraps: no seam duplicate; v: both poles */
	CHECK_NEAR(du, 0.125, 0);
	double u, v, one[3] = {1, 1, 1};
	illum_node_uv(m, 3, 4, &u, &v);
	illum_deposit(m, u, v, one);                    /* on node (3,4): all of it */
	illum_deposit(m, 5.5 / 8, 2.5 / 8, one);        /* cell centre: ¼ each */
	illum_deposit(m, 1.0 / 8, 6.25 / 8, one);       /* on a u line: ¾ and ¼ */
	illum_deposit(m, 7.5 / 8, 1.0, one);            /* across the seam, at the north pole */
	illum_deposit(m, 0.5, 1.5, one);                /* beyond v = 1: clamped to the pole row */
	struct nodes *s = nodes_of(m);
	CHECK_NEAR(node_e(s, 3, 4), 1, 0);
	CHECK(node_e(s, 2, 4) == 0 && node_e(s, 3, 3) == 0 && node_e(s, 4, 5) == 0);
	CHECK_NEAR(node_e(s, 5, 2), 0.25, 1e-15);
	CHECK_NEAR(node_e(s, 6, 2), 0.25, 1e-15);
	CHECK_NEAR(node_e(s, 5, 3), 0.25, 1e-15);
	CHECK_NEAR(node_e(s, 6, 3), 0.25, 1e-15);
	CHECK_NEAR(node_e(s, 1, 6), 0.75, 1e-15);
	CHECK_NEAR(node_e(s, 1, 7), 0.25, 1e-15);
	CHECK_NEAR(node_e(s, 7, 8), 0.5, 1e-15);
	CHECK_NEAR(node_e(s, 0, 8), 0.5, 1e-15);
	CHECK_NEAR(node_e(s, 4, 8), 1, 0);
	CHECK(s->n == 10);
	free(s);
	illum_free(m);
}

/* ==== uniform irradiance ================================================== */

/* ‖∂T/∂u × ∂T/∂v‖ at (u,v). */
static double jac(const struct object *o, double u, double v)
{
	struct vec3 p, pu, pv;
	shape_uv_point(o, u, v, &p, &pu, &pv);
	return v_len(v_cross(pu, pv));
}

/* Deposits total flux phi as n samples uniform in AREA over the bounded
 * surface o (rejection on the Jacobian), finishes, and checks every node's
 * irradiance against phi/area within 5σ (σ from the node's Σw²), the mean
 * z² (χ²/dof), and the pooled edge rows v = 0 and v = 1 (poles, apex, disc
 * centre, cap centres) against a 5σ band: no spike. */
static void uniform_case(struct object *o, struct illum_map *m, long n, const char *name)
{
	double jmax = 0, phi = 3.0;
	for (int a = 0; a <= 200; a++)
		for (int b = 0; b <= 200; b++)
			jmax = fmax(jmax, jac(o, a / 200.0, b / 200.0));
	jmax *= 1.05;
	double e[3] = {phi / (double)n, 2 * phi / (double)n, 0.5 * phi / (double)n};
	for (long k = 0; k < n;) {
		double u = rnd(), v = rnd();
		if (o->kind == OBJ_TRIANGLE && u + v > 1)
			continue;
		if (rnd() * jmax < jac(o, u, v)) {
			illum_deposit(m, u, v, e);
			k++;
		}
	}
	double removed[3];
	illum_finish(m, true, removed);
	CHECK(removed[0] == 0);
	double e0 = phi / shape_area(o), chi = 0, edge[2][3] = {{0}}; /* energy, area, Σw² */
	long nv;
	illum_grid(m, NULL, &nv, NULL, NULL);
	struct nodes *s = nodes_of(m);
	int bad = 0;
	for (int q = 0; q < s->n; q++) {
		const struct illum_node *x = &s->a[q];
		double sig = sqrt(x->sumsq[0]) / x->area, z = (x->irr[0] - e0) / sig;
		chi += z * z;
		if (fabs(z) > 5 && bad++ < 3)
			printf("#   %s: node (%ld,%ld) E = %g, expected %g ± %g\n", name, x->i, x->j, x->irr[0], e0, sig);
		CHECK_NEAR(x->irr[1], 2 * x->irr[0], 1e-12 * x->irr[0]);
		for (int side = 0; side < 2; side++)
			if (x->j == (side ? nv - 1 : 0)) {
				edge[side][0] += x->energy[0];
				edge[side][1] += x->area;
				edge[side][2] += x->sumsq[0];
			}
	}
	CHECK(bad == 0);
	chi /= s->n;
	if (!(fabs(chi - 1) < 5 * sqrt(2.0 / s->n) + 0.05))
		printf("#   %s: chi2/dof = %g over %d nodes\n", name, chi, s->n);
	CHECK(fabs(chi - 1) < 5 * sqrt(2.0 / s->n) + 0.05);
	for (int side = 0; side < 2; side++) {
		double E = edge[side][0] / edge[side][1], sig = sqrt(edge[side][2]) / edge[side][1];
		if (!(fabs(E - e0) < 5 * sig))
			printf("#   %s: edge row %d E = %g, expected %g ± %g\n", name, side, E, e0, sig);
		CHECK(fabs(E - e0) < 5 * sig);
		CHECK(sig < 0.05 * e0);
	}
	double lk[3];
	illum_lookup(m, 0.37, 0.41, lk);
	CHECK_NEAR(lk[0], e0, 0.2 * e0);
	free(s);
}

static void t_uniform(void)
{
	static const enum object_kind kinds[] = {OBJ_SPHERE, OBJ_BOX,  OBJ_DISC,
	                                         OBJ_CYLINDER, OBJ_CONE, OBJ_TORUS};
	static const char *names[] = {"sphere", "box", "disc", "cylinder", "cone", "torus"};
	rng_seed(23);
	for (int k = 0; k < NKINDS(kinds); k++) {
		struct object o = prim(kinds[k]);
		struct illum_map *m = map_res(&o, 12);
		uniform_case(&o, m, 400000, names[k]);
		illum_free(m);
	}
	/* an ellipsoid (non-uniform scale): node areas by cubature, with cell */
	struct object o = prim(OBJ_SPHERE);
	o.xf = xf_keep(xf_scale(v3(1, 2, 0.7)));
	struct illum_map *m = map_cell(&o, 0.6);
	long nu, nv;
	illum_grid(m, &nu, &nv, NULL, NULL);
	CHECK(nu >= 10 && nu <= 24 && nv >= 8 && nv <= 24);
	uniform_case(&o, m, 400000, "ellipsoid");
	illum_free(m);
}

/* The plane with cell: uniform flux over [-1,1]², interior nodes at phi/4. */
static void t_uniform_plane(void)
{
	rng_seed(5);
	struct object o = prim(OBJ_PLANE);
	struct illum_map *m = map_cell(&o, 0.1);
	double phi = 2, e[3];
	long n = 400000;
	e[0] = e[1] = e[2] = phi / (double)n;
	for (long k = 0; k < n; k++)
		illum_deposit(m, rndr(-1, 1), rndr(-1, 1), e);
	illum_finish(m, true, NULL);
	struct nodes *s = nodes_of(m);
	int checked = 0, bad = 0;
	for (int q = 0; q < s->n; q++) {
		const struct illum_node *x = &s->a[q];
		CHECK_NEAR(x->area, 0.01, 1e-15);
		if (fabs(x->u) > 0.95 || fabs(x->v) > 0.95)
			continue;
		checked++;
		double sig = sqrt(x->sumsq[0]) / x->area;
		bad += fabs(x->irr[0] - phi / 4) > 5 * sig;
	}
	CHECK(checked == 19 * 19);
	CHECK(bad == 0);
	free(s);
	illum_free(m);
}

/* ==== sparse tiles ======================================================== */

static void t_plane_sparse(void)
{
	rng_seed(7);
	struct object o = prim(OBJ_PLANE);
	struct illum_map *m = map_cell(&o, 0.01);
	size_t empty = illum_memory(m);
	double e[3] = {1e-3, 1e-3, 1e-3}, out[3];
	for (int k = 0; k < 10000; k++) {
		double r = 0.05 * sqrt(rnd()), a = rndr(0, 2 * M_PI);
		illum_deposit(m, 1000 + r * cos(a), -500 + r * sin(a), e);
	}
	illum_finish(m, true, NULL);
	/* the deposits span at most 12 nodes a side: the tiles those touch, and
	 * memory for about that many nodes, never for the plane */
	long side = 12 / ILLUM_TILE + 2;
	CHECK(illum_tiles(m) >= 1 && illum_tiles(m) <= side * side);
	CHECK(illum_memory(m) - empty <= (size_t)(side * side * ILLUM_TILE * ILLUM_TILE) * 160 + 16384);
	illum_lookup(m, 0, 0, out);
	CHECK(out[0] == 0 && out[1] == 0 && out[2] == 0);
	illum_lookup(m, 1000.5, -500, out);
	CHECK(out[0] == 0);
	illum_lookup(m, 1000, -500, out);
	CHECK_NEAR(out[0], 10 / (M_PI * 0.0025), 0.25 * 10 / (M_PI * 0.0025));
	illum_free(m);
}

/* A lookup reads the two nodes around (u,v) on each axis, whichever tiles
 * they lie in: a map holding one node (one tile) gives its irradiance at
 * the node, half of it half a cell away on either side of either axis
 * (where the other node's tile lies outside the tiles held), and nothing a
 * cell and a half away. */
static void t_lookup_edges(void)
{
	struct object o = prim(OBJ_PLANE);
	struct illum_map *m = map_cell(&o, 0.1);
	double e[3] = {0.02, 0.04, 0.06}, out[3];
	illum_deposit(m, 0.2, -0.8, e);
	illum_finish(m, false, NULL); /* a lone node: kept */
	CHECK(illum_tiles(m) == 1);
	illum_lookup(m, 0.2, -0.8, out);
	CHECK_NEAR(out[0], 2, 1e-12);
	CHECK_NEAR(out[2], 6, 1e-12);
	static const double off[4][2] = {{0.05, 0}, {-0.05, 0}, {0, 0.05}, {0, -0.05}};
	for (int k = 0; k < 4; k++) {
		illum_lookup(m, 0.2 + off[k][0], -0.8 + off[k][1], out);
		CHECK_NEAR(out[0], 1, 1e-12);
		CHECK_NEAR(out[1], 2, 1e-12);
		illum_lookup(m, 0.2 + 3 * off[k][0], -0.8 + 3 * off[k][1], out);
		CHECK(out[0] == 0 && out[1] == 0 && out[2] == 0);
	}
	illum_free(m);
}

/* ==== merge =============================================================== */

/* illum_deposit_all and illum_finish_mt give the same map, bit for bit
 * (energies, counts, Σw², irradiance, isolated flags, removed energy), for
 * any thread count as one by one: on a plane with a dense core and sparse
 * far-flung splats (so the isolated rule bites) and on a wrapping torus. */
static void t_threads(void)
{
	enum { N = 100000 }; /* more than PREP_MAX: split where they are added (illum.c) */
	static struct illum_splat sp[N];
	for (int shape = 0; shape < 2; shape++) {
		rng_seed(5 + shape);
		struct object o = prim(shape ? OBJ_TORUS : OBJ_PLANE);
		for (int k = 0; k < N; k++) {
			double r = k % 10 ? 0.3 * rnd() : 40 * rnd(), a = rndr(0, 2 * M_PI);
			sp[k] = shape ? (struct illum_splat){rnd(), rnd(), {rnd(), 1e-9 * rnd(), 0}}
			              : (struct illum_splat){r * cos(a), r * sin(a), {rnd(), 1e-9 * rnd(), 0}};
		}
		sp[17].u = NAN; /* dropped once, whatever the thread count */
		struct illum_map *one = shape ? map_res(&o, 96) : map_cell(&o, 0.01);
		for (int k = 0; k < N; k++)
			illum_deposit(one, sp[k].u, sp[k].v, sp[k].e);
		double rem1[3];
		illum_finish(one, true, rem1);
		struct nodes *s1 = nodes_of(one);
		CHECK(s1->n > 1000 && s1->n < MAXN && (rem1[0] > 0) == !shape);
		printf("# %s: %d nodes, %ld tiles\n", shape ? "torus" : "plane", s1->n, illum_tiles(one));
		static const int threads[] = {1, 2, 3, 7};
		for (int t = 0; t < 4; t++) {
			/* a new map: grey until this first batch, coloured, is scanned
			 * (illum_new_like(one) would be colour already, and split the
			 * batch in step 1) */
			struct illum_map *m = shape ? map_res(&o, 96) : map_cell(&o, 0.01);
			illum_deposit_all(m, sp, N, threads[t]);
			check_same_map(one, s1, rem1, m, threads[t]);
		}
		free(s1);
		illum_free(one);
	}
}

/* The same for white light (a grey map, whose bands skip the splats of
 * the other bands' 32-row stripes before splitting them, illum.c
 * band_skips): on a plane (a dense core, far-flung splats, rows on and
 * half a row off the stripes' edges), on a cylinder (v bounded and not
 * wrapping: splats at and beyond its ends, clamped) and on a sphere (u
 * wrapping, v bounded), any thread count as one by one. */
static void t_threads_grey(void)
{
	enum { N = 100000 };
	static struct illum_splat sp[N];
	static const enum object_kind kinds[] = {OBJ_PLANE, OBJ_CYLINDER, OBJ_SPHERE};
	for (int shape = 0; shape < 3; shape++) {
		rng_seed(11 + shape);
		struct object o = prim(kinds[shape]);
		struct illum_map *one = shape ? map_res(&o, 200) : map_cell(&o, 0.01);
		for (int k = 0; k < N; k++) {
			double e = rnd(), u, v;
			if (shape == 0) {
				double r = k % 10 ? 0.3 * rnd() : 40 * rnd(), a = rndr(0, 2 * M_PI);
				u = r * cos(a), v = r * sin(a);
				if (k % 7 == 0) /* on a stripe's edge (32 rows of 0.01), or half a row off it */
					v = 0.32 * (double)((k / 7) % 9 - 4) + 0.005 * (double)((k / 63) % 3 - 1);
			} else {
				u = rnd(), v = k % 5 ? rnd() : rndr(-0.02, 0.02) + (k % 2 ? 1 : 0);
				if (k % 11 == 0) /* exactly on the ends */
					v = k % 2 ? 1 : 0;
			}
			sp[k] = (struct illum_splat){u, v, {e, e, e}};
		}
		sp[17].v = NAN; /* dropped once, whatever the thread count */
		for (int k = 0; k < N; k++)
			illum_deposit(one, sp[k].u, sp[k].v, sp[k].e);
		double rem1[3];
		illum_finish(one, true, rem1);
		struct nodes *s1 = nodes_of(one);
		CHECK(s1->n > 1000 && s1->n < MAXN);
		printf("# grey %s: %d nodes, %ld tiles\n", shape == 0 ? "plane" : shape == 1 ? "cylinder" : "sphere",
		       s1->n, illum_tiles(one));
		static const int threads[] = {1, 2, 3, 4};
		for (int t = 0; t < 4; t++) {
			/* a new map, grey (one, made colour by its single deposits, is
			 * not; illum_new_like(one) would not be either) */
			struct illum_map *m = shape ? map_res(&o, 200) : map_cell(&o, 0.01);
			illum_deposit_all(m, sp, N, threads[t]);
			CHECK(illum_memory(m) < illum_memory(one)); /* one channel a node */
			check_same_map(one, s1, rem1, m, threads[t]);
		}
		free(s1);
		illum_free(one);
	}
}

/* illum_deposit_runs reads the splats where they lie (a record whose first
 * member is the splat; runs of any length, empty ones too, across the prep
 * chunks, with other records between them) and gives the map illum_deposit_all gives the same splats in
 * one array, bit for bit, for any thread count. The far-flung tenth of the
 * splats lands outside the window, so the tiles' hash grows many times. */
struct rec_like {
	struct illum_splat s;
	const void *obj;
	double pad[4];
};

static void t_runs(void)
{
	enum { N = 60000, R = 9 };
	static struct illum_splat sp[N];
	static struct rec_like rec[N + 2 * R]; /* two others after each run */
	static const long len[R] = {0, 5, 16384, 0, 20000, 1, 3610, 20000, 0}; /* Σ = N */
	rng_seed(11);
	struct object o = prim(OBJ_PLANE);
	for (int k = 0; k < N; k++) {
		double r = k % 10 ? 0.3 * rnd() : 40 * rnd(), a = rndr(0, 2 * M_PI);
		sp[k] = (struct illum_splat){r * cos(a), r * sin(a), {rnd(), 0.5 * rnd(), 0}};
	}
	sp[20001].v = NAN; /* dropped once */
	struct illum_run runs[R];
	long at = 0, next = 0;
	for (int k = 0; k < R; k++) {
		runs[k] = (struct illum_run){rec + at, len[k], sizeof *rec, false};
		for (long i = 0; i < len[k]; i++)
			rec[at++] = (struct rec_like){sp[next++], &o, {(double)i, -1, 0, 0}};
		for (int i = 0; i < 2; i++) /* not splats of the map: they must not count */
			rec[at++] = (struct rec_like){{0.5, 0.5, {1e3, 1e3, 1e3}}, NULL, {0, 0, 0, 0}};
	}
	CHECK(next == N && at == N + 2 * R);
	struct illum_map *one = map_cell(&o, 0.01);
	illum_deposit_all(one, sp, N, 1);
	double rem1[3];
	illum_finish(one, true, rem1);
	struct nodes *s1 = nodes_of(one);
	CHECK(s1->n > 1000 && s1->n < MAXN && rem1[0] > 0);
	static const int threads[] = {1, 2, 3};
	for (int t = 0; t < 3; t++) {
		struct illum_map *m = illum_new_like(one);
		illum_deposit_runs(m, runs, R, threads[t]);
		check_same_map(one, s1, rem1, m, threads[t]);
	}
	/* grey runs (struct illum_gsplat first in each record): the map of the
	 * same splats given white as illum_splats, on 1, 2, 3 threads */
	static struct gsrec {
		struct illum_gsplat s;
		const void *obj;
	} gr[N + 2 * R];
	static struct illum_splat ws[N];
	struct illum_run gruns[R];
	for (int k = 0; k < N; k++)
		ws[k] = (struct illum_splat){sp[k].u, sp[k].v, {sp[k].e[0], sp[k].e[0], sp[k].e[0]}};
	at = next = 0;
	for (int k = 0; k < R; k++) {
		gruns[k] = (struct illum_run){gr + at, len[k], sizeof *gr, true};
		for (long i = 0; i < len[k]; i++, next++)
			gr[at++] = (struct gsrec){{ws[next].u, ws[next].v, ws[next].e[0]}, &o};
		for (int i = 0; i < 2; i++)
			gr[at++] = (struct gsrec){{0.5, 0.5, 1e3}, NULL};
	}
	struct illum_map *white = map_cell(&o, 0.01); /* grey, as the light pass's maps (one is colour) */
	illum_deposit_all(white, ws, N, 1);
	double remw[3];
	illum_finish(white, true, remw);
	struct nodes *sw = nodes_of(white);
	CHECK(sw->n > 1000 && sw->n < MAXN && remw[0] > 0 && remw[1] == remw[0]);
	for (int t = 0; t < 3; t++) {
		struct illum_map *m = map_cell(&o, 0.01);
		illum_deposit_runs(m, gruns, R, threads[t]);
		CHECK(illum_memory(m) < illum_memory(one)); /* grey: one channel a node */
		check_same_map(white, sw, remw, m, threads[t]);
	}
	free(sw);
	illum_free(white);
	/* no splats at all: nothing happens */
	struct illum_map *m = illum_new_like(one);
	illum_deposit_runs(m, runs, 1, 2);
	CHECK(illum_tiles(m) == 0 && illum_dropped(m) == 0);
	illum_free(m);
	free(s1);
	illum_free(one);
}

static void t_merge(void)
{
	rng_seed(99);
	struct object o = prim(OBJ_TORUS);
	struct illum_map *one = map_res(&o, 24);
	struct illum_map *pa = illum_new_like(one), *pb = illum_new_like(one);
	struct illum_map *ab = illum_new_like(one), *ba = illum_new_like(one);
	for (int k = 0; k < 20000; k++) {
		double u = rnd(), v = rnd(), e[3] = {rnd(), rnd() * 1e-9, rnd() * 1e3};
		illum_deposit(one, u, v, e);
		illum_deposit(k < 12000 ? pa : pb, u, v, e);
	}
	CHECK(illum_merge(ab, pa) && illum_merge(ab, pb));
	CHECK(illum_merge(ba, pb) && illum_merge(ba, pa));
	struct illum_map *other = map_res(&o, 12);
	CHECK(!illum_merge(other, pa));
	illum_finish(one, true, NULL);
	illum_finish(ab, true, NULL);
	illum_finish(ba, true, NULL);
	struct nodes *s1 = nodes_of(one), *s2 = nodes_of(ab), *s3 = nodes_of(ba);
	CHECK(s1->n == s2->n && s1->n == s3->n && s1->n == 24 * 24);
	int diff = 0;
	for (int q = 0; q < s1->n && q < s2->n && q < s3->n; q++) {
		const struct illum_node *a = &s1->a[q], *b = &s2->a[q], *c = &s3->a[q];
		diff += memcmp(a->energy, b->energy, sizeof a->energy) != 0;
		diff += memcmp(a->energy, c->energy, sizeof a->energy) != 0;
		diff += memcmp(a->irr, b->irr, sizeof a->irr) != 0;
		diff += memcmp(a->irr, c->irr, sizeof a->irr) != 0;
		diff += a->count != b->count || a->count != c->count || a->i != b->i || a->j != c->j;
		CHECK_NEAR(a->sumsq[2], b->sumsq[2], 1e-5 * a->sumsq[2]); /* float sums, merged in another order */
	}
	CHECK(diff == 0);
	free(s1);
	free(s2);
	free(s3);
	illum_free(one);
	illum_free(pa);
	illum_free(pb);
	illum_free(ab);
	illum_free(ba);
	illum_free(other);
}

/* ==== grey maps ============================================================ */

/* A map whose deposits have all been white holds one channel a node; the
 * first deposit that is not white (here a batch on two threads) makes it a
 * colour map. Either way the nodes, the isolated rule, the totals and the
 * lookups are bit for bit those of the same deposits made one by one into
 * a colour map; merges between grey and colour maps add the same energies. */
static void t_grey(void)
{
	enum { N = 160000, H = N / 2 }; /* halves of more than PREP_MAX (illum.c) */
	static struct illum_splat sp[N];
	rng_seed(5);
	struct object o = prim(OBJ_PLANE);
	for (int k = 0; k < N; k++) {
		double r = k % 10 ? 0.3 * rnd() : 40 * rnd(), a = rndr(0, 2 * M_PI), x = rnd();
		sp[k] = (struct illum_splat){r * cos(a), r * sin(a), {x, x, x}};
		if (k >= H && k % 3 == 0) /* some colour light in the second half */
			sp[k].e[1] = 0.5 * x;
	}
	struct illum_map *one = map_cell(&o, 0.01); /* one by one: colour from the first */
	for (int k = 0; k < N; k++)
		illum_deposit(one, sp[k].u, sp[k].v, sp[k].e);
	/* new maps, grey (a map made like one would be colour, as one is) */
	struct illum_map *g = map_cell(&o, 0.01), *w1 = map_cell(&o, 0.01), *w2 = map_cell(&o, 0.01);
	illum_deposit_all(g, sp, H, 2); /* grey */
	size_t grey_bytes = illum_memory(g);
	illum_deposit_all(g, sp + H, N - H, 2); /* made colour */
	for (int k = 0; k < H; k++)
		illum_deposit(w1, sp[k].u, sp[k].v, sp[k].e);
	illum_deposit_all(w2, sp, H, 1); /* grey throughout */
	CHECK(illum_memory(g) > grey_bytes && illum_memory(w2) < illum_memory(w1)); /* made colour; grey */
	double r1[3], rg[3], rw1[3], rw2[3], t1[3], tg[3], tw1[3], tw2[3];
	illum_finish(one, true, r1);
	illum_finish_mt(g, true, rg, 2);
	illum_finish(w1, true, rw1);
	illum_finish_mt(w2, true, rw2, 3);
	illum_total(one, t1), illum_total(g, tg), illum_total(w1, tw1), illum_total(w2, tw2);
	struct nodes *s1 = nodes_of(one), *sg = nodes_of(g), *sw1 = nodes_of(w1), *sw2 = nodes_of(w2);
	CHECK(s1->n > 1000 && s1->n < MAXN && r1[0] > 0 && r1[1] < r1[0]);
	CHECK(node_diffs(s1, sg) == 0 && memcmp(r1, rg, sizeof r1) == 0 && memcmp(t1, tg, sizeof t1) == 0);
	CHECK(sw1->n > 500 && rw1[0] > 0 && rw1[1] == rw1[0] && rw1[2] == rw1[0]);
	CHECK(node_diffs(sw1, sw2) == 0 && memcmp(rw1, rw2, sizeof rw1) == 0 && memcmp(tw1, tw2, sizeof tw1) == 0);
	int bad = 0;
	for (int k = 0; k < 2000; k++) {
		double u = rndr(-0.3, 0.3), v = rndr(-0.3, 0.3), a[3], b[3];
		illum_lookup(w1, u, v, a), illum_lookup(w2, u, v, b);
		bad += memcmp(a, b, sizeof a) != 0 || a[1] != a[0];
		illum_lookup(one, u, v, a), illum_lookup(g, u, v, b);
		bad += memcmp(a, b, sizeof a) != 0;
	}
	CHECK(bad == 0);
	/* merges: grey into grey, colour into grey, grey into colour */
	struct illum_map *c2 = map_cell(&o, 0.01), *m1 = map_cell(&o, 0.01), *m2 = map_cell(&o, 0.01);
	for (int k = H; k < N; k++)
		illum_deposit(c2, sp[k].u, sp[k].v, sp[k].e);
	struct illum_map *w3 = map_cell(&o, 0.01);
	illum_deposit_all(w3, sp, H, 2);
	CHECK(illum_merge(m1, w3) && illum_merge(m1, c2)); /* m1: grey, then colour */
	CHECK(illum_merge(m2, c2) && illum_merge(m2, w3)); /* m2: colour, then a grey one added */
	illum_finish(m1, true, NULL), illum_finish(m2, true, NULL);
	struct nodes *sm1 = nodes_of(m1), *sm2 = nodes_of(m2);
	int diff = sm1->n != s1->n || sm2->n != s1->n;
	for (int q = 0; q < s1->n && q < sm1->n && q < sm2->n; q++) {
		const struct illum_node *a = &s1->a[q], *b = &sm1->a[q], *c = &sm2->a[q];
		diff += memcmp(a->energy, b->energy, sizeof a->energy) != 0 || memcmp(a->energy, c->energy, sizeof a->energy) != 0;
		diff += memcmp(a->irr, b->irr, sizeof a->irr) != 0 || memcmp(a->irr, c->irr, sizeof a->irr) != 0;
		diff += a->count != b->count || a->count != c->count || a->i != c->i || a->j != c->j;
	}
	CHECK(diff == 0);
	free(s1), free(sg), free(sw1), free(sw2), free(sm1), free(sm2);
	illum_free(one), illum_free(g), illum_free(w1), illum_free(w2), illum_free(w3);
	illum_free(c2), illum_free(m1), illum_free(m2);
}

/* ==== range: energies far above 2^32 W ==================================== */

/* A scene at 1e6 scale carries ~1e9 W per ray. The same deposits at 1 W and
 * at 2^40 W (deposited one by one, on 1 and 3 threads, and merged with a
 * faint map) must give the same irradiances times 2^40: the fixed-point
 * unit follows the energy instead of saturating at 2^32 W per node. */
static void t_range(void)
{
	enum { N = 20000 };
	static struct illum_splat lo[N], hi[N];
	rng_seed(42);
	struct object o = prim(OBJ_SPHERE);
	for (int k = 0; k < N; k++) { /* most of it into a few nodes */
		double u = 0.5 + 0.01 * rnd(), v = 0.5 + 0.01 * rnd(), e = 0.5 + rnd();
		lo[k] = (struct illum_splat){u, v, {e, 0.25 * e, 0}};
		hi[k] = (struct illum_splat){u, v, {e * 0x1p40, 0.25 * e * 0x1p40, 0}};
	}
	struct illum_map *ref = map_res(&o, 48), *one = illum_new_like(ref), *three = illum_new_like(ref);
	for (int k = 0; k < N; k++)
		illum_deposit(one, hi[k].u, hi[k].v, hi[k].e);
	illum_deposit_all(ref, lo, N, 1);
	illum_deposit_all(three, hi, N, 3);
	struct illum_map *merged = illum_new_like(ref), *faint = illum_new_like(ref);
	illum_deposit(faint, 0.25, 0.25, (double[3]){1e-20, 0, 0}); /* on one node */
	CHECK(illum_merge(merged, faint) && illum_merge(merged, three));
	struct illum_map *ms[3] = {one, three, merged};
	double tref[3], t[3];
	illum_finish(ref, false, NULL);
	illum_total(ref, tref);
	struct nodes *sr = nodes_of(ref);
	CHECK(sr->n >= 4 && sr->n < 100);
	for (int i = 0; i < 3; i++) {
		illum_finish(ms[i], false, NULL);
		illum_total(ms[i], t);
		CHECK_NEAR(t[0], tref[0] * 0x1p40, 1e-12 * tref[0] * 0x1p40);
		CHECK_NEAR(t[1], tref[1] * 0x1p40, 1e-12 * tref[1] * 0x1p40);
		struct nodes *s = nodes_of(ms[i]);
		CHECK(s->n == sr->n + (i == 2));
		double irr[3];
		for (int q = 0; q < sr->n; q++) {
			illum_lookup(ms[i], sr->a[q].u, sr->a[q].v, irr);
			CHECK_NEAR(irr[0], sr->a[q].irr[0] * 0x1p40, 1e-12 * sr->a[q].irr[0] * 0x1p40);
		}
		free(s);
		illum_free(ms[i]);
	}
	free(sr);
	illum_free(ref);
	illum_free(faint);
}

/* A node that saturates (an infinite deposit: the largest fixed-point
 * value, 2^128 - 1 quanta, about 2^32 W) saturates the map's total too
 * (illum_finish sums the nodes in 192 bits, then saturates once), while
 * the other channels keep their exact sums. */
static void t_saturate(void)
{
	struct object o = prim(OBJ_SPHERE);
	struct illum_map *m = map_res(&o, 48);
	illum_deposit(m, 0.25, 0.25, (double[3]){INFINITY, 1, 0}); /* on node (12,12) */
	illum_deposit(m, 0.5, 0.5, (double[3]){1, 1, 1});          /* on node (24,24), another tile */
	illum_finish(m, false, NULL);
	double t[3];
	illum_total(m, t);
	CHECK(t[0] == 0x1p32); /* (2^128 - 1)·2^-96, rounded to a double; wrapping would give ~1 */
	CHECK(t[1] == 2 && t[2] == 1);
	illum_free(m);
}

/* ==== isolated samples ==================================================== */

static void t_isolated(void)
{
	rng_seed(3);
	struct object o = prim(OBJ_PLANE);
	struct illum_map *m = map_cell(&o, 0.1);
	double e[3] = {1e-4, 1e-4, 1e-4}, lone[3] = {0.5, 0.25, 0.125}, rem[3], out[3];
	for (int k = 0; k < 40000; k++)
		illum_deposit(m, rndr(0, 2), rndr(0, 2), e);
	illum_finish(m, false, rem);
	struct nodes *before = nodes_of(m);
	CHECK(rem[0] == 0);
	illum_finish(m, true, rem);
	CHECK(rem[0] == 0 && rem[1] == 0 && rem[2] == 0); /* dense: changed by exactly 0 */
	struct nodes *after = nodes_of(m);
	CHECK(before->n == after->n && memcmp(before->a, after->a, sizeof(struct illum_node) * (size_t)before->n) == 0);
	illum_deposit(m, 10.03, 10.07, lone); /* far away and alone */
	illum_finish(m, true, rem);
	CHECK_NEAR(rem[0], 0.5, 1e-15);
	CHECK_NEAR(rem[1], 0.25, 1e-15);
	CHECK_NEAR(rem[2], 0.125, 1e-15);
	illum_lookup(m, 10.03, 10.07, out);
	CHECK(out[0] == 0);
	illum_finish(m, false, rem); /* switched off: kept */
	illum_lookup(m, 10.03, 10.07, out);
	CHECK(out[0] > 0 && rem[0] == 0);
	free(before);
	free(after);
	illum_free(m);
}

/* The isolated-sample rule against a brute-force count: a node is isolated
 * exactly when the counts of the (2r+1)² nodes around it add up to at most
 * 4 (r = 2, or less on a short wrapping axis; wrapping across seams).
 * Sparse splats, so both kinds abound, on a plane (no wrap; nodes on both
 * sides of 0, whose negative neighbours count as much) and a torus
 * with 24 nodes a side (windows across both seams); on a torus with 4
 * (r = 1), five splats on node (0,0) and one on (2,2), which r = 2 would
 * see together. */
static void t_isolated_rule(void)
{
	enum { W = 64 };
	static const int res[3] = {0, 24, 4}, splats[3] = {150, 30, 6};
	for (int s = 0; s < 3; s++) {
		rng_seed(21 + s);
		struct object o = prim(s ? OBJ_TORUS : OBJ_PLANE);
		struct illum_map *m = s ? map_res(&o, res[s]) : map_cell(&o, 1);
		double e[3] = {1, 1, 1}, rem[3];
		for (int k = 0; k < splats[s]; k++)
			if (s == 2)
				illum_deposit(m, k < 5 ? 0 : 0.5, k < 5 ? 0 : 0.5, e);
			else
				illum_deposit(m, s ? rnd() : rndr(-28, 28), s ? rnd() : rndr(-28, 28), e);
		illum_finish(m, true, rem);
		struct nodes *ns = nodes_of(m);
		static uint64_t cnt[W][W];
		memset(cnt, 0, sizeof cnt);
		int n = s ? res[s] : W, r = s && (n - 1) / 2 < 2 ? (n - 1) / 2 : 2, bad = 0, iso = 0, neg = 0;
		long off = s ? 0 : W / 2; /* the plane's node i at cnt[.][i + off] */
		for (int k = 0; k < ns->n; k++)
			if (ns->a[k].i + off >= 0 && ns->a[k].i + off < W && ns->a[k].j + off >= 0 && ns->a[k].j + off < W)
				cnt[ns->a[k].j + off][ns->a[k].i + off] = ns->a[k].count;
			else
				bad++;
		for (int k = 0; k < ns->n; k++) {
			long i = ns->a[k].i, j = ns->a[k].j;
			uint64_t sum = 0;
			for (long dj = -r; dj <= r; dj++)
				for (long di = -r; di <= r; di++) {
					long a = s ? ((i + di) % n + n) % n : i + di, b = s ? ((j + dj) % n + n) % n : j + dj;
					a += off, b += off;
					sum += a >= 0 && a < W && b >= 0 && b < W ? cnt[b][a] : 0;
				}
			bad += ns->a[k].isolated != (sum <= 4);
			iso += ns->a[k].isolated;
			neg += i < 0 && !ns->a[k].isolated;
		}
		printf("# %s: %d nodes, %d isolated\n", s ? "torus" : "plane", ns->n, iso);
		CHECK(bad == 0);
		CHECK(iso > 0 && iso < ns->n); /* both kinds */
		CHECK(s || neg > 0);
		CHECK((rem[0] > 0) == (iso > 0));
		free(ns);
		illum_free(m);
	}
}

/* ==== ray density and EXR dump ============================================ */

static void t_auto_cell(void)
{
	CHECK_NEAR(illum_auto_cell(1.6e5, 1, 0), 0.01, 1e-15);
	CHECK_NEAR(illum_auto_cell(1e6, 4, 64), 0.016, 1e-15);
	CHECK(illum_auto_cell(0, 1, 0) == 0 && illum_auto_cell(10, INFINITY, 0) == 0);
	/* on a sphere: 200000 rays at the default density → ~16 rays per node */
	struct object o = prim(OBJ_SPHERE);
	double S = illum_auto_cell(2e5, shape_area(&o), 0);
	struct illum_map *m = map_cell(&o, S);
	long nu, nv;
	illum_grid(m, &nu, &nv, NULL, NULL);
	double per = 2e5 / (double)(nu * (nv - 1));
	CHECK(per >= 16 / 1.6 && per <= 16 * 1.1); /* cell S gives nodes at most ~S apart */
	illum_free(m);
}

static void t_exr(void)
{
	struct object o = prim(OBJ_SPHERE);
	struct illum_map *m = map_res(&o, 20);
	double e[3] = {1, 2, 3}, u, v;
	illum_node_uv(m, 5, 7, &u, &v);
	illum_deposit(m, u, v, e);
	illum_finish(m, false, NULL);
	char path[] = "/tmp/test_illum_XXXXXX.exr";
	int fd = mkstemps(path, 4);
	CHECK(fd >= 0);
	close(fd);
	CHECK(MSG(illum_write_exr(m, path, TDG)) == NULL);
	struct framebuffer *fb = NULL;
	CHECK(MSG(out_exr_read(path, &fb, NULL, TDG)) == NULL);
	if (fb) {
		CHECK(fb->w == ILLUM_TILE && fb->h == ILLUM_TILE); /* the one allocated tile */
		float *g = fb_find(fb, "G");
		double area = 0, want;
		struct nodes *s = nodes_of(m);
		area = s->a[0].area;
		want = 2 / area;
		/* node (5, 7) in its tile; the top image row is the largest v */
		int T = ILLUM_TILE, x = 5 % T, y = T - 1 - 7 % T;
		CHECK(g && fabs(g[y * T + x] - want) <= 1e-6 * want);
		free(s);
		fb_free(fb);
	}
	unlink(path);
	illum_free(m);
}

int main(void)
{
	RUN(t_conservation);
	RUN(t_split);
	RUN(t_uniform);
	RUN(t_uniform_plane);
	RUN(t_plane_sparse);
	RUN(t_lookup_edges);
	RUN(t_threads);
	RUN(t_threads_grey);
	RUN(t_runs);
	RUN(t_merge);
	RUN(t_grey);
	RUN(t_range);
	RUN(t_saturate);
	RUN(t_isolated);
	RUN(t_isolated_rule);
	RUN(t_auto_cell);
	RUN(t_exr);
	return test_done();
}
