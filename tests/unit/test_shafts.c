/* SPDX-License-Identifier: MIT */
/* test_shafts.c: light shafts (method shaft, docs/design.md §4) against the
 * analytic caustic references (tests/accuracy/: mirror A, glass sphere B,
 * glass slab C) and the exact fold-ring profile of a ball lens whose floor
 * lies between its foci. The metric is what the eye pass reads: every map
 * level's node irradiance × node area, spread over its bilinear tent (8×8
 * points) and binned, against the binned exact flux; flux-weighted relative
 * L1. Shafts have no point-sample noise, so the tolerances are the measured
 * errors at these budgets with a margin (docs/methods.md gives the
 * convergence), not a noise model. */
#include <stdlib.h>
#include <string.h>

#include "../../common/diag.h"
#include "../../eval/eval.h"
#include "../../tracer/bvh.h"
#include "../../tracer/light/lightpass.h"
#include "../../tracer/shape.h"
#include "test.h"

struct run {
	struct scene s;
	struct bvh *b;
	struct lp_result *r;
	struct lp_stats st;
	const struct object *floor; /* the last object: the plane */
};

static double tolerance; /* > 0: start() runs the light pass to this accuracy target */

static int start(struct run *R, const char *path, const char *define, long rays, bool shafts, int threads,
                 bool transmit_only)
{
	struct diag dg;
	diag_init(&dg, stderr);
	struct eval_options eo;
	eval_default_options(&eo);
	const char *defs[1] = {define};
	eo.defines = defs;
	eo.ndefines = define ? 1 : 0;
	if (eval_scene(path, &eo, &dg, &R->s) != 0)
		return 0;
	R->b = bvh_build(R->s.objects, R->s.nobjects);
	struct mat_cache mc;
	memset(&mc, 0, sizeof mc);
	struct lp_opts o = {.rays = rays, .max_depth = 10, .min_weight = 1e-9, .threads = threads,
	                    .discard_isolated = true, .channel = -1, .transmit_only = transmit_only, .shafts = shafts,
	                    .tolerance = tolerance};
	R->r = lp_run(&R->s, R->b, &mc, &o, &R->st);
	R->floor = R->s.objects[R->s.nobjects - 1];
	return R->r != NULL && lp_map(R->r, R->floor) != NULL;
}

static void stop(struct run *R)
{
	lp_free(R->r);
	bvh_free(R->b);
	scene_free(&R->s);
}

/* ---- what the eye pass reads, binned ------------------------------------- */

struct bins {
	const struct object *floor;
	int radial;       /* 1: annuli of width w around the y axis; 0: grid cells */
	double w;         /* bin width */
	double x0, z0;    /* grid origin */
	int nx, nz;       /* grid size (radial: nx annuli) */
	double *flux;     /* per bin, green */
	double du, dv;    /* the level's node spacing */
};

static int bin_of(const struct bins *B, struct vec3 p)
{
	if (B->radial) {
		int k = (int)(sqrt(p.x * p.x + p.z * p.z) / B->w);
		return k < B->nx ? k : -1;
	}
	int i = (int)floor((p.x - B->x0) / B->w), j = (int)floor((p.z - B->z0) / B->w);
	return i >= 0 && i < B->nx && j >= 0 && j < B->nz ? i * B->nz + j : -1;
}

static void spread_node(void *ctx, const struct illum_node *n)
{
	struct bins *B = ctx;
	double share = n->irr[1] * n->area, part[64], wsum = 0;
	int bin[64];
	for (int q = 0; q < 64; q++) {
		double a = (q / 8 + 0.5) / 4 - 1, b = (q % 8 + 0.5) / 4 - 1;
		struct vec3 p, du, dv;
		shape_uv_point(B->floor, n->u + a * B->du, n->v + b * B->dv, &p, &du, &dv);
		part[q] = (1 - fabs(a)) * (1 - fabs(b));
		wsum += part[q];
		bin[q] = bin_of(B, p);
	}
	for (int q = 0; q < 64; q++)
		if (bin[q] >= 0)
			B->flux[bin[q]] += share * part[q] / wsum;
}

static void read_maps(const struct run *R, struct bins *B)
{
	for (int l = 0; l < LP_LEVELS; l++) {
		const struct illum_map *m = lp_map_level(R->r, R->floor, l);
		if (!m)
			continue;
		long nu, nv;
		illum_grid(m, &nu, &nv, &B->du, &B->dv);
		illum_each(m, spread_node, B);
	}
}

static int read_column(const char *path, int col, double *out, int n)
{
	FILE *f = fopen(path, "r");
	char line[1024];
	int k = 0;
	if (!f || !fgets(line, sizeof line, f))
		return 0;
	while (k < n && fgets(line, sizeof line, f)) {
		char *p = line;
		for (int c = 0; c < col && p; c++)
			p = strchr(p, ',') ? strchr(p, ',') + 1 : NULL;
		if (!p)
			break;
		out[k++] = strtod(p, NULL);
	}
	fclose(f);
	return k;
}

static double l1_of(const double *got, const double *ref, int n, double *gt, double *rt)
{
	double d = 0;
	*gt = *rt = 0;
	for (int k = 0; k < n; k++)
		d += fabs(got[k] - ref[k]), *gt += got[k], *rt += ref[k];
	return d / *rt;
}

/* ---- the references ------------------------------------------------------ */

/* Scenes B and C: 60 annuli of 0.05 out to r = 3 (the CSV's flux column). */
static double radial_l1(const char *scene, const char *define, const char *csv, int col, long rays,
                        double *flux_ratio)
{
	struct run R;
	if (!start(&R, scene, define, rays, true, 2, true)) {
		CHECK(!"light pass ran");
		return 1;
	}
	double flux[60] = {0}, ref[60], g, t;
	struct bins B = {R.floor, 1, 0.05, 0, 0, 60, 1, flux, 0, 0};
	read_maps(&R, &B);
	CHECK(read_column(csv, col, ref, 60) == 60);
	double l1 = l1_of(flux, ref, 60, &g, &t);
	if (tolerance > 0)
		printf("# tolerance %g: estimate %.5f after %d rounds\n", tolerance, R.st.tol_estimate, R.st.tol_rounds);
	printf("# %s %s shafts, %ld rays (%lld traced): L1 %.5f, flux r<=3 %.7g (exact %.7g), maps %.1f MiB\n", scene,
	       define, rays, R.st.rays, l1, g, t, R.st.map_bytes / 1048576.0);
	*flux_ratio = g / t;
	stop(&R);
	return l1;
}

static void t_sphere(void)
{
	double fr, l1 = radial_l1("tests/accuracy/sphere.scn", "Fresnel=0", "tests/accuracy/B_profile_binned_0.05.csv", 3,
	                          300000, &fr);
	CHECK(l1 <= 0.005);
	CHECK_NEAR(fr, 1, 0.001);
}

/* Every ray that meets the ideal glass sphere lands on the floor, so what
 * lands is the light's intensity times the sphere's solid angle, exactly
 * (1 W/sr per channel; sin a = 1/7): no shaft at the sphere's outline
 * drops its missed corners' share (the target is grown past the outline,
 * lightpass.c widen), and none of the sphere's light is missed. By points
 * as well, at any ray count. */
static void t_sphere_energy(void)
{
	double want = 2 * M_PI * (1 - sqrt(48.0 / 49.0));
	for (int k = 0; k < 6; k++) {
		long rays = k % 3 == 0 ? 20000 : k % 3 == 1 ? 50000 : 200000;
		struct run R;
		CHECK(start(&R, "tests/accuracy/sphere.scn", "Fresnel=0", rays, k < 3, 2, true));
		printf("# %s, %ld rays: landed %.9g, I*omega %.9g, direct %.3g\n", k < 3 ? "shafts" : "points", rays,
		       R.st.landed[1], want, R.st.direct[1]);
		CHECK_NEAR(R.st.landed[1] / want, 1, 1e-8); /* (the cone pads the radius by 1e-9: 2e-9 more) */
		stop(&R);
	}
}

static void t_slab(void)
{
	double fr, l1 = radial_l1("tests/accuracy/slab.scn", "Fresnel=0", "tests/accuracy/C_profile_binned_0.05.csv", 6,
	                          100000, &fr);
	CHECK(l1 <= 0.005);
	CHECK_NEAR(fr, 1, 0.001);
	l1 = radial_l1("tests/accuracy/slab.scn", "Fresnel=1", "tests/accuracy/C_profile_binned_0.05.csv", 7, 100000, &fr);
	CHECK(l1 <= 0.005);
	CHECK_NEAR(fr, 1, 0.001);
}

/* Mirror A: 0.1 cells over x in [-3, 1], z in [-4, 4]; the L1, and the
 * flux in the grid over the exact one in *flux_ratio. */
static double mirror_l1(long rays, double *flux_ratio)
{
	struct run R;
	if (!start(&R, "tests/accuracy/mirror.scn", "Fresnel=0", rays, true, 2, false)) {
		CHECK(!"light pass ran");
		return 1;
	}
	enum { NX = 40, NZ = 80 };
	static double flux[NX * NZ], ref[NX * NZ];
	memset(flux, 0, sizeof flux);
	struct bins B = {R.floor, 0, 0.1, -3, -4, NX, NZ, flux, 0, 0};
	read_maps(&R, &B);
	CHECK(read_column("tests/accuracy/A_grid_cellavg_0.1.csv", 5, ref, NX * NZ) == NX * NZ);
	for (int k = 0; k < NX * NZ; k++)
		ref[k] *= 0.01; /* Ebar × cell area */
	/* the column at the mirror's foot (x in [0.9, 1]) is left out: the map's
	 * tents there reach under the mirror (x > 1), where the floor is dark,
	 * a loss of half a node of a bright edge that is the reading, not the
	 * light (the point method's t_mirror allows 0.5 % of flux for it) */
	double g, t, l1 = l1_of(flux, ref, (NX - 1) * NZ, &g, &t);
	printf("# mirror shafts, %ld rays (%lld traced%s): L1 %.5f, flux in the grid %.7g (exact %.7g)\n", rays,
	       R.st.rays, tolerance > 0 ? ", tolerance" : "", l1, g, t);
	*flux_ratio = g / t;
	stop(&R);
	return l1;
}

static void t_mirror(void)
{
	double fr, l1 = mirror_l1(300000, &fr);
	CHECK(l1 <= 0.004);
	CHECK_NEAR(fr, 1, 0.001);
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
 * under a point light of 1 W/sr at height l: each meridional ray at angle θ
 * carries 2π·sinθ·dθ (midpoint rule, 2·10⁶ steps). */
static void ring_profile(double h, double l, double n, double w, double *ref, int nbins)
{
	enum { STEPS = 2000000 };
	double tmax = asin(1 / (l - h));
	for (int k = 0; k < nbins; k++)
		ref[k] = 0;
	for (int i = 0; i < STEPS; i++) {
		double th = (i + 0.5) / STEPS * tmax, dth = tmax / STEPS;
		double dx = sin(th), dy = -cos(th), oy = l - h, b = oy * dy, disc = b * b - (oy * oy - 1);
		if (disc < 0)
			continue;
		double t = -b - sqrt(disc), px = t * dx, py = oy + t * dy;
		if (!snell2(&dx, &dy, px, py, 1 / n))
			continue;
		t = -2 * (px * dx + py * dy);
		px += t * dx, py += t * dy;
		if (!snell2(&dx, &dy, -px, -py, n) || dy >= 0)
			continue;
		int bin = (int)(fabs(px + (-(h + py) / dy) * dx) / w);
		if (bin < nbins)
			ref[bin] += 2 * M_PI * sin(th) * dth;
	}
}

/* The fold ring (bench/caustics/ring.scn, automatic map resolution): 150
 * annuli of 0.02; the error keeps falling with rays (no floor). */
static void t_ring(void)
{
	static double ref[150];
	ring_profile(1.5, 10, 1.5, 0.02, ref, 150);
	double l1s[2];
	long budget[2] = {250000, 1000000};
	for (int i = 0; i < 2; i++) {
		struct run R;
		if (!start(&R, "bench/caustics/ring.scn", NULL, budget[i], true, 2, true)) {
			CHECK(!"light pass ran");
			return;
		}
		double flux[150] = {0}, g, t;
		struct bins B = {R.floor, 1, 0.02, 0, 0, 150, 1, flux, 0, 0};
		read_maps(&R, &B);
		l1s[i] = l1_of(flux, ref, 150, &g, &t);
		printf("# ring shafts, %ld rays: L1 %.5f, flux %.7g (exact %.7g), maps %.1f MiB\n", budget[i], l1s[i], g, t,
		       R.st.map_bytes / 1048576.0);
		CHECK_NEAR(g / t, 1, 0.002);
		stop(&R);
	}
	CHECK(l1s[0] <= 0.02);
	CHECK(l1s[1] <= 0.009);
	CHECK(l1s[1] < 0.6 * l1s[0]);
}

/* The accuracy target is honest: with `tolerance T` the L1 measured
 * against the exact references does not exceed T (the estimate compares
 * each round's maps with the previous round's over the whole lit region,
 * in 2-D bins, so it is conservative for the references' bins; mirror A's
 * reflection reaches far beyond the reference's grid, and its sharp edges
 * there make it the slowest). */
static void t_tolerance(void)
{
	static const double tols[3] = {0.02, 0.01, 0.005};
	for (int i = 0; i < 3; i++) {
		double fr, l1;
		tolerance = tols[i];
		l1 = radial_l1("tests/accuracy/sphere.scn", "Fresnel=0", "tests/accuracy/B_profile_binned_0.05.csv", 3, 0, &fr);
		CHECK(l1 <= tols[i]);
		l1 = radial_l1("tests/accuracy/slab.scn", "Fresnel=0", "tests/accuracy/C_profile_binned_0.05.csv", 6, 0, &fr);
		CHECK(l1 <= tols[i]);
		l1 = mirror_l1(0, &fr);
		CHECK(l1 <= tols[i]);
	}
	tolerance = 0;
}

/* The maps are bit-identical for 1 and 3 threads. */
static void energies(void *ctx, const struct illum_node *n)
{
	double *acc = ctx;
	acc[0] = acc[0] * 1.000001 + n->energy[1] + n->i * 1e-3 + n->j * 1e-6;
}

static void t_threads(void)
{
	double sum[2] = {0, 0};
	for (int i = 0; i < 2; i++) {
		struct run R;
		if (!start(&R, "tests/accuracy/sphere.scn", "Fresnel=1", 30000, true, i ? 3 : 1, false)) {
			CHECK(!"light pass ran");
			return;
		}
		for (int l = 0; l < LP_LEVELS; l++)
			if (lp_map_level(R.r, R.floor, l))
				illum_each(lp_map_level(R.r, R.floor, l), energies, &sum[i]);
		stop(&R);
	}
	CHECK(sum[0] == sum[1] && sum[0] != 0);
}

int main(void)
{
	RUN(t_sphere);
	RUN(t_sphere_energy);
	RUN(t_slab);
	RUN(t_mirror);
	RUN(t_ring);
	RUN(t_threads);
	RUN(t_tolerance);
	return test_done();
}
