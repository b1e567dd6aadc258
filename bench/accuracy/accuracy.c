/* SPDX-License-Identifier: MIT */
/* accuracy.c: one light pass of arvo on a reference scene (tests/accuracy:
 * mirror A, glass sphere B, glass slab C), timed, and its error against the
 * exact binned caustic (bench/accuracy/ref.h).
 *
 *   accuracy SCENE REF point|shaft RAYS THREADS [options]
 *     -D NAME=VALUE    a scene define (as arvo -D), repeatable
 *     --all-paths      follow reflection too (mirror A); by default only
 *                      refraction is followed (.transmit_only: the references
 *                      of B and C hold only twice-transmitted light)
 *     --keep-isolated  keep isolated samples (the renderer discards them)
 *     --time-only      skip the metric (repeat runs: the maps, so the L1,
 *                      are bit-identical from run to run)
 *     --tolerance T    the light pass's own accuracy target T (lp_opts
 *                      .tolerance, arvo --tolerance: rounds of 4x more rays
 *                      until its error estimate is at most T; RAYS unused)
 *
 * Runs lp_run once with the renderer's settings (render.c: min_weight 1e-4,
 * the isolated-sample rule, max_depth 5, which these scenes never reach) and
 * prints one line of key=value pairs:
 *   method, rays, threads, time_s  lp_run alone (CLOCK_MONOTONIC wall)
 *   rays_shot, segments            lp_stats
 *   l1        THE metric: the irradiance the eye pass reads (every map
 *             level's node irradiance × node area, spread over the node's
 *             bilinear tent), binned like the reference: grid cells get the
 *             tent's exact integral (a product of 1-D tents); annuli its
 *             exact integral along x on rows of z 1/128 of an annulus apart
 *             (converged to 1e-5 in L1).
 *             The 8×8 points of lightrays.c and tests/unit/test_shafts.c
 *             alias with the bins where the map's nodes are coarse: ±5 %
 *             stripes on A's 0.1 cells at 3e5 automatic shaft rays
 *   l1_nodes  node energies binned by node position (smeared by a cell)
 *   l1_noise  what photon noise alone would give with rays_shot box-binned
 *             rays: √(2/π)·Σ√(wΦ_k)/ΣΦ_k, w = emitted/rays_shot
 *   flux_ratio  Σ read flux / Σ exact flux over the bins kept
 *   map_bytes   memory the maps hold
 *   cell, levels  the floor map's finest cell (world units) and its levels
 *   tol_estimate, tol_rounds, tol_rays   with --tolerance: the pass's own
 *             error estimate when it stopped, its rounds, and the rays of
 *             its last round
 * Exit status 0; 1 when the scene fails or no floor map results (the floor
 * is the scene's last object). */
#include <stdbool.h>
#include <time.h>

#include "../../common/diag.h"
#include "../../common/srcloc.h"
#include "../../eval/eval.h"
#include "../../tracer/bvh.h"
#include "../../tracer/light/lightpass.h"
#include "../../tracer/shape.h"
#include "ref.h"

enum { MAXDEF = 16 };

struct spread {
	const struct object *floor;
	const struct ref *R;
	double *look;  /* per bin: what the eye pass reads */
	double *nodes; /* per bin: node energies by node position */
	double du, dv; /* the level's node spacing (u, v) */
	double cell;   /* world spacing of level 0 (set on its first node) */
	int level;
};

/* The share of a unit tent of half-width h centred at c that lies below x
 * (its CDF). */
static double tent_cdf(double x, double c, double h)
{
	double t = (x - c) / h;
	if (t <= -1)
		return 0;
	if (t >= 1)
		return 1;
	return t <= 0 ? 0.5 * (1 + t) * (1 + t) : 1 - 0.5 * (1 - t) * (1 - t);
}

/* The shares of that tent in the cells [x0 + i·w, x0 + (i+1)·w] it meets:
 * first cell index in *i0, shares in out[0 .. returned count). */
static int tent_cells(double c, double h, double x0, double w, int *i0, double *out, int max)
{
	int lo = (int)floor((c - h - x0) / w), hi = (int)floor((c + h - x0) / w), k = 0;
	*i0 = lo;
	for (int i = lo; i <= hi && k < max; i++, k++)
		out[k] = tent_cdf(x0 + (i + 1) * w, c, h) - tent_cdf(x0 + i * w, c, h);
	return k;
}

enum { MAXTENT = 512 };

static void spread_node(void *ctx, const struct illum_node *n)
{
	struct spread *S = ctx;
	const struct ref *R = S->R;
	struct vec3 p, q, r, du, dv;
	shape_uv_point(S->floor, n->u, n->v, &p, &du, &dv);
	int k = ref_bin(R, p.x, p.z);
	if (k >= 0)
		S->nodes[k] += n->energy[1];
	shape_uv_point(S->floor, n->u + S->du, n->v, &q, &du, &dv);
	shape_uv_point(S->floor, n->u, n->v + S->dv, &r, &du, &dv);
	struct vec3 eu = {q.x - p.x, q.y - p.y, q.z - p.z}, ev = {r.x - p.x, r.y - p.y, r.z - p.z};
	if (S->level == 0 && S->cell == 0)
		S->cell = sqrt(eu.x * eu.x + eu.y * eu.y + eu.z * eu.z);
	double share = n->irr[1] * n->area;
	if (share == 0)
		return;
	/* a floor whose (u, v) run along x and z (the plane: u = x, v = -z):
	 * the tent is a product of 1-D tents of half-widths hx, hz */
	double tiny = 1e-12 * (fabs(eu.x) + fabs(eu.z) + fabs(ev.x) + fabs(ev.z));
	if (fabs(eu.y) <= tiny && fabs(ev.y) <= tiny &&
	    ((fabs(eu.z) <= tiny && fabs(ev.x) <= tiny) || (fabs(eu.x) <= tiny && fabs(ev.z) <= tiny))) {
		double hx = fabs(eu.x) + fabs(ev.x), hz = fabs(eu.z) + fabs(ev.z);
		if (!R->radial) { /* grid cells: the exact integral */
			double sx[MAXTENT], sz[MAXTENT];
			int ix, iz, nx = tent_cells(p.x, hx, R->x0, R->w, &ix, sx, MAXTENT),
			            nz = tent_cells(p.z, hz, R->z0, R->w, &iz, sz, MAXTENT);
			for (int a = 0; a < nx; a++)
				for (int b = 0; b < nz; b++)
					if (ix + a >= 0 && ix + a < R->nx && iz + b >= 0 && iz + b < R->nz)
						S->look[(ix + a) * R->nz + iz + b] += share * sx[a] * sz[b];
			return;
		}
		/* annuli: a tent inside one annulus is all in it */
		double dx = fmax(0, fabs(p.x) - hx), dz = fmax(0, fabs(p.z) - hz);
		double ex = fabs(p.x) + hx, ez = fabs(p.z) + hz;
		int k0 = (int)(sqrt(dx * dx + dz * dz) / R->w), k1 = (int)(sqrt(ex * ex + ez * ez) / R->w);
		if (k0 >= R->nx)
			return; /* reaches no annulus */
		if (k0 == k1) {
			S->look[k0] += share;
			return;
		}
		/* else exact along x, row by row: the rows (midpoints of an even
		 * number of strips, 1/128 of an annulus apart or closer, weighted
		 * by the z tent, which the midpoint rule integrates exactly) sample
		 * a function continuous in z. Measured: L1 within 1e-5 of 4 times
		 * as many rows; 1/8 of an annulus was off by up to 5e-4 */
		int m = 2 * (int)fmin(16384, fmax(32, ceil(128 * hz / R->w)));
		for (int j = 0; j < m; j++) {
			double b = 2 * (j + 0.5) / m - 1, z = p.z + b * hz, wz = (1 - fabs(b)) * 2 / m;
			double z2 = z * z;
			int r0 = (int)(fabs(z) / R->w), r1 = (int)fmin(R->nx - 1, sqrt(ex * ex + z2) / R->w);
			for (int kk = r0; kk <= r1; kk++) {
				double lo = kk * R->w, hi = lo + R->w;
				if (hi * hi <= z2)
					continue;
				double x1 = lo * lo > z2 ? sqrt(lo * lo - z2) : 0, x2 = sqrt(hi * hi - z2);
				double f = tent_cdf(x2, p.x, hx) - tent_cdf(x1, p.x, hx) + tent_cdf(-x1, p.x, hx) -
				           tent_cdf(-x2, p.x, hx);
				S->look[kk] += share * wz * f;
			}
		}
		return;
	}
	/* otherwise the tent sampled at m×m points, m such that their spacing is
	 * at most 1/16 of a bin (8 at least: fine maps) */
	double span = 2 * fmax(sqrt(eu.x * eu.x + eu.z * eu.z), sqrt(ev.x * ev.x + ev.z * ev.z));
	if (R->radial && sqrt(p.x * p.x + p.z * p.z) - span > R->nx * R->w)
		return; /* reaches no annulus */
	int m = (int)fmin(256, fmax(8, ceil(16 * span / R->w)));
	double wsum = 0;
	for (int i = 0; i < m; i++)
		for (int j = 0; j < m; j++) {
			double a = 2 * (i + 0.5) / m - 1, b = 2 * (j + 0.5) / m - 1; /* in (-1, 1) */
			wsum += (1 - fabs(a)) * (1 - fabs(b));
		}
	for (int i = 0; i < m; i++)
		for (int j = 0; j < m; j++) {
			double a = 2 * (i + 0.5) / m - 1, b = 2 * (j + 0.5) / m - 1;
			shape_uv_point(S->floor, n->u + a * S->du, n->v + b * S->dv, &q, &du, &dv);
			int bin = ref_bin(R, q.x, q.z);
			if (bin >= 0)
				S->look[bin] += share * (1 - fabs(a)) * (1 - fabs(b)) / wsum;
		}
}

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int usage(void)
{
	fprintf(stderr, "usage: accuracy SCENE REF point|shaft RAYS THREADS [-D NAME=VALUE]... "
	                "[--all-paths] [--keep-isolated] [--time-only] [--tolerance T]\n");
	return 2;
}

int main(int argc, char **argv)
{
	const char *defs[MAXDEF];
	int ndefs = 0;
	bool all_paths = false, keep_isolated = false, time_only = false;
	double tolerance = 0;
	const char *pos[5];
	int npos = 0;
	for (int i = 1; i < argc; i++) {
		if (!strcmp(argv[i], "-D") && i + 1 < argc && ndefs < MAXDEF)
			defs[ndefs++] = argv[++i];
		else if (!strcmp(argv[i], "--all-paths"))
			all_paths = true;
		else if (!strcmp(argv[i], "--keep-isolated"))
			keep_isolated = true;
		else if (!strcmp(argv[i], "--time-only"))
			time_only = true;
		else if (!strcmp(argv[i], "--tolerance") && i + 1 < argc)
			tolerance = strtod(argv[++i], NULL);
		else if (argv[i][0] == '-' && argv[i][1])
			return usage();
		else if (npos < 5)
			pos[npos++] = argv[i];
		else
			return usage();
	}
	if (npos != 5)
		return usage();
	const char *scene = pos[0], *refspec = pos[1], *method = pos[2];
	long rays = (long)strtod(pos[3], NULL);
	int threads = atoi(pos[4]);
	bool shafts = !strcmp(method, "shaft");
	if ((!shafts && strcmp(method, "point")) || rays <= 0 || threads <= 0)
		return usage();

	struct ref R;
	if (ref_load(refspec, &R))
		return 1;
	struct diag dg;
	diag_init(&dg, stderr);
	struct eval_options eo;
	eval_default_options(&eo);
	eo.defines = defs;
	eo.ndefines = ndefs;
	struct scene s;
	if (eval_scene(scene, &eo, &dg, &s) != 0)
		return 1;
	struct bvh *b = bvh_build(s.objects, s.nobjects);
	struct mat_cache mc;
	memset(&mc, 0, sizeof mc);
	struct lp_opts o = {.rays = rays, .max_depth = 5, .min_weight = 1e-4, .threads = threads,
	                    .discard_isolated = !keep_isolated, .channel = -1, .transmit_only = !all_paths,
	                    .shafts = shafts, .tolerance = tolerance};
	struct lp_stats st;
	memset(&st, 0, sizeof st);

	double t0 = now();
	struct lp_result *r = lp_run(&s, b, &mc, &o, &st);
	double t = now() - t0;

	const struct object *floor_obj = s.objects[s.nobjects - 1];
	if (!r || !lp_map(r, floor_obj)) {
		fprintf(stderr, "accuracy: %s: no floor map\n", scene);
		return 1;
	}
	if (time_only) {
		printf("method=%s rays=%ld threads=%d time_s=%.6f rays_shot=%lld segments=%lld map_bytes=%zu\n", method,
		       rays, threads, t, st.rays, st.segments, st.map_bytes);
		ref_free(&R);
		lp_free(r);
		bvh_free(b);
		scene_free(&s);
		srcfile_free_all();
		return 0;
	}
	double *look = calloc((size_t)R.n, sizeof *look), *nodes = calloc((size_t)R.n, sizeof *nodes);
	if (!look || !nodes)
		return 1;
	struct spread S = {floor_obj, &R, look, nodes, 0, 0, 0, 0};
	int levels = 0;
	for (int l = 0; l < LP_LEVELS; l++) {
		const struct illum_map *m = lp_map_level(r, floor_obj, l);
		if (!m)
			continue;
		long nu, nv;
		illum_grid(m, &nu, &nv, &S.du, &S.dv);
		S.level = l;
		illum_each(m, spread_node, &S);
		levels++;
	}
	double tot = ref_total(&R), got = 0;
	for (int k = 0; k < R.n; k++)
		if (R.keep[k])
			got += look[k];
	double w = st.rays > 0 ? st.emitted[1] / (double)st.rays : 0;
	printf("method=%s rays=%ld threads=%d time_s=%.6f rays_shot=%lld segments=%lld l1=%.6f l1_nodes=%.6f "
	       "l1_noise=%.6f flux_ratio=%.6f map_bytes=%zu cell=%.6g levels=%d",
	       method, rays, threads, t, st.rays, st.segments, ref_l1(&R, look, 1), ref_l1(&R, nodes, 1),
	       ref_l1_noise(&R, w), got / tot, st.map_bytes, S.cell, levels);
	if (tolerance > 0)
		printf(" tol_estimate=%.6f tol_rounds=%d tol_rays=%ld", st.tol_estimate, st.tol_rounds, st.tol_rays);
	printf("\n");

	free(look);
	free(nodes);
	ref_free(&R);
	lp_free(r);
	bvh_free(b);
	scene_free(&s);
	srcfile_free_all();
	return 0;
}
