/* SPDX-License-Identifier: MIT */
/* lightrays.c: times arvo's light pass on the glass-sphere scene (refs scene
 * B) and measures its accuracy, as tests/unit/test_caustics.c does.
 *
 *   lightrays RAYS THREADS [SCENE [REF_CSV [METHOD]]]
 *
 * METHOD is point (default: bilinear point deposits) or shaft (light
 * shafts spread over their footprints). REF_CSV may instead be
 * exact:H,L,N,W,NB: the exact profile of a sphere of index N centred at
 * height H under a light at height L (both on the y axis), NB annuli of
 * width W (the fold-ring scene, bench/caustics/ring.scn: exact:1.5,10,1.5,0.02,150).
 * Runs lp_run once with `.rays = RAYS`, `.threads = THREADS` and
 * `.transmit_only = true` (the reference holds only twice-transmitted light),
 * bins the floor map's node energies into 0.05 annuli out to r = 3 and prints
 * one line of key=value pairs:
 *   rays, threads, time_s       (wall clock of lp_run alone, CLOCK_MONOTONIC)
 *   rays_shot, segments         (lp_stats)
 *   rays_per_s_per_core         rays_shot / time_s / threads
 *   segments_per_s_per_core     segments / time_s / threads
 *   l1, l1_noise                flux-weighted relative L1 against column 3
 *                               (flux_caustic_n1.50) and its photon-noise
 *                               expectation √(2/π)·Σ√(wΦ_k)/ΣΦ_k, w = Φ_s/N
 *   flux, flux_ref              binned flux on r ≤ 3, got and exact
 *   l1_lookup                   the same L1 of the irradiance the eye pass
 *                               reads (every map level; each node's tent
 *                               integrated over the annuli)
 *   map_bytes                   memory held by the maps
 * Exit status 0, or 1 when the scene cannot be evaluated or no map results. */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../../common/diag.h"
#include "../../common/srcloc.h"
#include "../../eval/eval.h"
#include "../../tracer/bvh.h"
#include "../../tracer/light/lightpass.h"
#include "../../tracer/shape.h"

enum { MAXBINS = 400 };
static int NBINS = 60;       /* annuli */
static double BIN_W = 0.05;  /* their width */

struct bins {
	const struct object *floor;
	double flux[MAXBINS];
};

static void bin_node(void *ctx, const struct illum_node *n)
{
	struct bins *B = ctx;
	struct vec3 p, du, dv;
	shape_uv_point(B->floor, n->u, n->v, &p, &du, &dv);
	int k = (int)(sqrt(p.x * p.x + p.z * p.z) / BIN_W);
	if (k < NBINS)
		B->flux[k] += n->energy[1];
}

/* Bins the irradiance a node's tent carries (what illum_lookup reads) by
 * where it lies. */
struct spread {
	const struct object *floor;
	double flux[MAXBINS];
	double du, dv;  /* the level's node spacing */
};

static void spread_node(void *ctx, const struct illum_node *n)
{
	struct spread *S = ctx;
	double share = n->irr[1] * n->area, wsum = 0, part[8][8];
	int bin[8][8];
	for (int i = 0; i < 8; i++)
		for (int j = 0; j < 8; j++) {
			double a = (i + 0.5) / 4 - 1, b = (j + 0.5) / 4 - 1; /* in (-1, 1) */
			struct vec3 p, du, dv;
			shape_uv_point(S->floor, n->u + a * S->du, n->v + b * S->dv, &p, &du, &dv);
			part[i][j] = (1 - fabs(a)) * (1 - fabs(b));
			wsum += part[i][j];
			bin[i][j] = (int)(sqrt(p.x * p.x + p.z * p.z) / BIN_W);
		}
	for (int i = 0; i < 8; i++)
		for (int j = 0; j < 8; j++)
			if (bin[i][j] < NBINS)
				S->flux[bin[i][j]] += share * part[i][j] / wsum;
}

/* Column `col` (0-based) of a CSV with one header line: n values or fewer. */
static int read_column(const char *path, int col, double *out, int n)
{
	FILE *f = fopen(path, "r");
	char line[1024];
	int k = 0;
	if (!f)
		return 0;
	if (fgets(line, sizeof line, f)) {
		while (k < n && fgets(line, sizeof line, f)) {
			char *p = line;
			for (int c = 0; c < col && p; c++)
				p = strchr(p, ',') ? strchr(p, ',') + 1 : NULL;
			if (!p)
				break;
			out[k++] = strtod(p, NULL);
		}
	}
	fclose(f);
	return k;
}

/* Refracts unit (dx, dy) at a surface of unit normal (nx, ny) facing against
 * it, with relative index eta; false on total internal reflection. */
static bool snell2(double *dx, double *dy, double nx, double ny, double eta)
{
	double ci = -(*dx * nx + *dy * ny), k = 1 - eta * eta * (1 - ci * ci);
	if (k < 0)
		return false;
	double f = eta * ci - sqrt(k);
	*dx = eta * *dx + f * nx;
	*dy = eta * *dy + f * ny;
	return true;
}

/* The exact binned flux on the floor y = 0 of the light twice transmitted
 * by a glass sphere (radius 1, index n, centre at height h on the axis)
 * under an isotropic point light of 1 W/sr at height l on the axis: each
 * meridional ray at angle θ from the axis carries 2π·sinθ·dθ (midpoint
 * rule, 4·10⁶ steps over the sphere's cone). */
static void exact_profile(double h, double l, double n, double *ref)
{
	enum { STEPS = 4000000 };
	double tmax = asin(1 / (l - h));
	for (int k = 0; k < NBINS; k++)
		ref[k] = 0;
	for (int i = 0; i < STEPS; i++) {
		double th = (i + 0.5) / STEPS * tmax, dth = tmax / STEPS;
		double dx = sin(th), dy = -cos(th), ox = 0, oy = l - h; /* from the centre */
		double b = ox * dx + oy * dy, c = ox * ox + oy * oy - 1, disc = b * b - c;
		if (disc < 0)
			continue;
		double t = -b - sqrt(disc), px = ox + t * dx, py = oy + t * dy;
		if (!snell2(&dx, &dy, px, py, 1 / n))
			continue;
		t = -2 * (px * dx + py * dy);
		px += t * dx, py += t * dy;
		if (!snell2(&dx, &dy, -px, -py, n) || dy >= 0)
			continue;
		double x = px + (-(h + py) / dy) * dx;
		int bin = (int)(fabs(x) / BIN_W);
		if (bin < NBINS)
			ref[bin] += 2 * M_PI * sin(th) * dth;
	}
}

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + ts.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
	if (argc < 3) {
		fprintf(stderr, "usage: lightrays RAYS THREADS [SCENE [REF_CSV [point|shaft]]]\n");
		return 2;
	}
	long rays = (long)strtod(argv[1], NULL);
	int threads = atoi(argv[2]);
	const char *scene = argc > 3 ? argv[3] : "tests/accuracy/sphere.scn";
	const char *csv = argc > 4 ? argv[4] : "tests/accuracy/B_profile_binned_0.05.csv";
	bool shafts = argc > 5 && !strcmp(argv[5], "shaft");

	struct diag dg;
	diag_init(&dg, stderr);
	struct eval_options eo;
	eval_default_options(&eo);
	struct scene s;
	if (eval_scene(scene, &eo, &dg, &s) != 0)
		return 1;
	struct bvh *b = bvh_build(s.objects, s.nobjects);
	struct mat_cache mc;
	memset(&mc, 0, sizeof mc);
	struct lp_opts o = {.rays = rays, .max_depth = 10, .min_weight = 1e-9, .threads = threads,
	                    .channel = -1, .transmit_only = true, .shafts = shafts};
	struct lp_stats st;
	memset(&st, 0, sizeof st);

	double t0 = now();
	struct lp_result *r = lp_run(&s, b, &mc, &o, &st);
	double t = now() - t0;

	struct bins B = {.floor = s.objects[s.nobjects - 1]};
	const struct illum_map *m = r ? lp_map(r, B.floor) : NULL;
	double ref[MAXBINS];
	double H, L, N;
	if (sscanf(csv, "exact:%lf,%lf,%lf,%lf,%d", &H, &L, &N, &BIN_W, &NBINS) == 5 && NBINS > 0 && NBINS <= MAXBINS) {
		exact_profile(H, L, N, ref);
	} else if (!m || read_column(csv, 3, ref, NBINS) != NBINS) {
		fprintf(stderr, "lightrays: no floor map, or %s unreadable\n", csv);
		return 1;
	}
	for (int l = 0; l < LP_LEVELS; l++)
		if (lp_map_level(r, B.floor, l))
			illum_each(lp_map_level(r, B.floor, l), bin_node, &B);
	/* the irradiance the eye pass reads, integrated over each annulus: each
	 * node's share (irradiance × node area, what the bilinear reading
	 * holds) spread over its tent's support, 8×8 points weighted by the tent */
	struct spread S = {B.floor, {0}, 0, 0};
	for (int l = 0; l < LP_LEVELS; l++) {
		const struct illum_map *ml = lp_map_level(r, B.floor, l);
		if (!ml)
			continue;
		long nu, nv;
		illum_grid(ml, &nu, &nv, &S.du, &S.dv);
		illum_each(ml, spread_node, &S);
	}
	const double *look = S.flux;
	double w = st.emitted[1] / (double)st.rays, d = 0, tot = 0, got = 0, sq = 0, dl = 0;
	for (int k = 0; k < NBINS; k++) {
		d += fabs(B.flux[k] - ref[k]);
		dl += fabs(look[k] - ref[k]);
		tot += ref[k];
		got += B.flux[k];
		sq += sqrt(w * ref[k]);
	}
	printf("rays=%ld threads=%d time_s=%.6f rays_shot=%lld segments=%lld "
	       "rays_per_s_per_core=%.0f segments_per_s_per_core=%.0f l1=%.6f l1_noise=%.6f "
	       "flux=%.7g flux_ref=%.7g l1_lookup=%.6f map_bytes=%zu\n",
	       rays, threads, t, st.rays, st.segments, st.rays / t / threads, st.segments / t / threads,
	       d / tot, sqrt(2 / M_PI) * sq / tot, got, tot, dl / tot, st.map_bytes);

	lp_free(r);
	bvh_free(b);
	scene_free(&s);
	srcfile_free_all();
	return 0;
}
