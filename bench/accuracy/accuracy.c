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
 *             bilinear tent, 8×8 points), binned like the reference
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

static void spread_node(void *ctx, const struct illum_node *n)
{
	struct spread *S = ctx;
	struct vec3 p, du, dv;
	shape_uv_point(S->floor, n->u, n->v, &p, &du, &dv);
	int k = ref_bin(S->R, p.x, p.z);
	if (k >= 0)
		S->nodes[k] += n->energy[1];
	if (S->level == 0 && S->cell == 0) {
		struct vec3 q;
		shape_uv_point(S->floor, n->u + S->du, n->v, &q, &du, &dv);
		S->cell = sqrt((q.x - p.x) * (q.x - p.x) + (q.y - p.y) * (q.y - p.y) + (q.z - p.z) * (q.z - p.z));
	}
	double share = n->irr[1] * n->area, part[64], wsum = 0;
	int bin[64];
	for (int q = 0; q < 64; q++) {
		double a = (q / 8 + 0.5) / 4 - 1, b = (q % 8 + 0.5) / 4 - 1; /* in (-1, 1) */
		shape_uv_point(S->floor, n->u + a * S->du, n->v + b * S->dv, &p, &du, &dv);
		part[q] = (1 - fabs(a)) * (1 - fabs(b));
		wsum += part[q];
		bin[q] = ref_bin(S->R, p.x, p.z);
	}
	for (int q = 0; q < 64; q++)
		if (bin[q] >= 0)
			S->look[bin[q]] += share * part[q] / wsum;
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
	                "[--all-paths] [--keep-isolated] [--tolerance T]\n");
	return 2;
}

int main(int argc, char **argv)
{
	const char *defs[MAXDEF];
	int ndefs = 0;
	bool all_paths = false, keep_isolated = false;
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
