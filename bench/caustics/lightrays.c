/* SPDX-License-Identifier: MIT */
/* lightrays.c: times arvo's light pass on the glass-sphere scene (refs scene
 * B) and measures its accuracy, as tests/unit/test_caustics.c does.
 *
 *   lightrays RAYS THREADS [SCENE [REF_CSV]]
 *
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
 * Exit status 0, or 1 when the scene cannot be evaluated or no map results. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../../common/diag.h"
#include "../../common/srcloc.h"
#include "../../eval/eval.h"
#include "../../tracer/bvh.h"
#include "../../tracer/lightpass.h"
#include "../../tracer/shape.h"

enum { NBINS = 60 };
#define BIN_W 0.05

struct bins {
	const struct object *floor;
	double flux[NBINS];
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

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + ts.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
	if (argc < 3) {
		fprintf(stderr, "usage: lightrays RAYS THREADS [SCENE [REF_CSV]]\n");
		return 2;
	}
	long rays = (long)strtod(argv[1], NULL);
	int threads = atoi(argv[2]);
	const char *scene = argc > 3 ? argv[3] : "tests/accuracy/sphere.scn";
	const char *csv = argc > 4 ? argv[4] : "tests/accuracy/B_profile_binned_0.05.csv";

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
	                    .channel = -1, .transmit_only = true};
	struct lp_stats st;
	memset(&st, 0, sizeof st);

	double t0 = now();
	struct lp_result *r = lp_run(&s, b, &mc, &o, &st);
	double t = now() - t0;

	struct bins B = {.floor = s.objects[s.nobjects - 1]};
	const struct illum_map *m = r ? lp_map(r, B.floor) : NULL;
	double ref[NBINS];
	if (!m || read_column(csv, 3, ref, NBINS) != NBINS) {
		fprintf(stderr, "lightrays: no floor map, or %s unreadable\n", csv);
		return 1;
	}
	illum_each(m, bin_node, &B);

	double w = st.emitted[1] / (double)st.rays, d = 0, tot = 0, got = 0, sq = 0;
	for (int k = 0; k < NBINS; k++) {
		d += fabs(B.flux[k] - ref[k]);
		tot += ref[k];
		got += B.flux[k];
		sq += sqrt(w * ref[k]);
	}
	printf("rays=%ld threads=%d time_s=%.6f rays_shot=%lld segments=%lld "
	       "rays_per_s_per_core=%.0f segments_per_s_per_core=%.0f l1=%.6f l1_noise=%.6f "
	       "flux=%.7g flux_ref=%.7g\n",
	       rays, threads, t, st.rays, st.segments, st.rays / t / threads, st.segments / t / threads,
	       d / tot, sqrt(2 / M_PI) * sq / tot, got, tot);

	lp_free(r);
	bvh_free(b);
	scene_free(&s);
	srcfile_free_all();
	return 0;
}
