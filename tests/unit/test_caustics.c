/* SPDX-License-Identifier: MIT */
/* test_caustics.c: the light pass against the analytic caustic references
 * (tests/accuracy/, from the project's refs: mirror A, glass sphere B, glass
 * slab C). Metric as the references prescribe: flux-weighted relative L1 of
 * binned flux, L1 <= 1.5·L1_noise + 0.5 %, and total flux to 0.5 %. The map's
 * node energies are binned by the node's position (bilinear splats conserve
 * energy; the ±h smear at bin edges is what the 0.5 % allows for). */
#include <stdlib.h>
#include <string.h>

#include "../../common/diag.h"
#include "../../eval/eval.h"
#include "../../tracer/bvh.h"
#include "../../tracer/light/lightpass.h"
#include "../../tracer/render.h"
#include "../../tracer/shape.h"
#include "test.h"

#define RAYS 1000000L

struct run {
	struct scene s;
	struct bvh *b;
	struct lp_result *r;
	struct lp_stats st;
	const struct object *floor; /* the last object: the plane */
};

/* Evaluates a scene (with one -D) and runs the light pass on it. */
static int start(struct run *R, const char *path, const char *define, int channel, bool transmit_only)
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
	/* the isolated-sample rule is on: it must not bias a converged result */
	struct lp_opts o = {.rays = RAYS, .max_depth = 10, .min_weight = 1e-9, .threads = 2,
	                    .discard_isolated = true, .channel = channel, .transmit_only = transmit_only};
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

/* ---- binning ------------------------------------------------------------ */

struct bins {
	const struct object *floor;
	int radial;       /* 1: annuli of width w from the y axis; 0: grid cells */
	double w;         /* bin width */
	double x0, z0;    /* grid origin */
	int nx, nz;       /* grid size (radial: nx annuli) */
	double *flux;     /* per bin, green channel */
	int channel;
	double h;         /* grid cells: the map's node spacing in x and z (a plane's cell) */
};

/* The share of a tent of half-width h centred at c (area 1) over [a, b]. */
static double tent_share(double c, double h, double a, double b)
{
	double lo = fmax(a, c - h), hi = fmin(b, c + h);
	if (!(hi > lo))
		return 0;
	/* ∫ (1 − |x − c|/h) dx / h over [lo, hi], split at c */
	double s = 0, l = fmin(hi, c), r = fmax(lo, c);
	if (l > lo) /* left half: rises from lo to l */
		s += ((l - lo) - ((c - lo) * (c - lo) - (c - l) * (c - l)) / (2 * h)) / h;
	if (hi > r) /* right half */
		s += ((hi - r) - ((hi - c) * (hi - c) - (r - c) * (r - c)) / (2 * h)) / h;
	return s;
}

static void bin_node(void *ctx, const struct illum_node *n)
{
	struct bins *B = ctx;
	struct vec3 p, du, dv;
	shape_uv_point(B->floor, n->u, n->v, &p, &du, &dv);
	if (B->radial) {
		int k = (int)(sqrt(p.x * p.x + p.z * p.z) / B->w);
		if (k < B->nx)
			B->flux[k] += n->energy[B->channel];
	} else { /* the node's tent (its bilinear weight), spread exactly over the cells it reaches */
		int i0 = (int)floor((p.x - B->h - B->x0) / B->w), k0 = (int)floor((p.z - B->h - B->z0) / B->w);
		for (int i = i0; i <= i0 + 1; i++)
			for (int k = k0; k <= k0 + 1; k++) {
				if (i < 0 || k < 0 || i >= B->nx || k >= B->nz)
					continue;
				double x = B->x0 + i * B->w, z = B->z0 + k * B->w;
				B->flux[i * B->nz + k] += n->energy[B->channel] * tent_share(p.x, B->h, x, x + B->w) *
				                          tent_share(p.z, B->h, z, z + B->w);
			}
	}
}

/* Reads column `col` (0-based) of a reference CSV, at most n rows. */
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

/* Flux-weighted relative L1 and its noise-only expectation. */
static void compare(const double *got, const double *ref, int n, double w, double *l1, double *noise,
                    double *got_total, double *ref_total)
{
	double d = 0, t = 0, g = 0, s = 0;
	for (int k = 0; k < n; k++) {
		d += fabs(got[k] - ref[k]);
		t += ref[k];
		g += got[k];
		s += sqrt(w * ref[k]);
	}
	*l1 = d / t;
	*noise = sqrt(2 / M_PI) * s / t;
	*got_total = g;
	*ref_total = t;
}

/* Radial scenes B and C: 60 annuli of 0.05 out to r = 3. */
static void radial_case(const char *scene, const char *define, const char *csv, int col, double exact_total)
{
	struct run R;
	CHECK(start(&R, scene, define, -1, true));
	if (!R.r)
		return;
	double flux[60] = {0}, ref[60];
	struct bins B = {R.floor, 1, 0.05, 0, 0, 60, 1, flux, 1, 0};
	illum_each(lp_map(R.r, R.floor), bin_node, &B);
	CHECK(read_column(csv, col, ref, 60) == 60);
	double l1, noise, g, t;
	compare(flux, ref, 60, R.st.emitted[1] / (double)R.st.rays, &l1, &noise, &g, &t);
	printf("# %s %s: L1 %.5f (noise %.5f), flux r<=3 %.6g (ref %.6g), deposited %.7g\n", scene,
	       define, l1, noise, g, t, R.st.deposited[1]);
	CHECK(l1 <= 1.5 * noise + 0.005);
	CHECK_NEAR(g / t, 1, 0.005);
	CHECK(R.st.deposited[1] <= R.st.emitted[1]);
	if (exact_total > 0)
		CHECK_NEAR(R.st.deposited[1] / exact_total, 1, 0.005);
	stop(&R);
}

static void t_sphere_ideal(void)
{
	radial_case("tests/accuracy/sphere.scn", "Fresnel=0", "tests/accuracy/B_profile_binned_0.05.csv", 3,
	            0.0644446);
}

static void t_sphere_fresnel(void)
{
	radial_case("tests/accuracy/sphere.scn", "Fresnel=1", "tests/accuracy/B_profile_binned_0.05.csv", 5,
	            0.0538253);
}

static void t_slab_ideal(void)
{
	radial_case("tests/accuracy/slab.scn", "Fresnel=0", "tests/accuracy/C_profile_binned_0.05.csv", 6, 0);
}

static void t_slab_fresnel(void)
{
	radial_case("tests/accuracy/slab.scn", "Fresnel=1", "tests/accuracy/C_profile_binned_0.05.csv", 7, 0);
}

/* Aim: the light of C sits 1 above the slab, inside the sphere round its
 * box but outside the box, so it shoots into the cone round the box's
 * corners (axis -y, cos = 1/sqrt(51) at the top corners), not in every
 * direction (half of those rays went up and escaped): what it emits is
 * that cone's solid angle, nothing escapes, and what lands is the light
 * through the top face, the square of side 10 one below the light
 * (4 atan(25/sqrt(51)) sr; the lossless slab lets all of it reach the
 * floor), to the sampling of the face's outline. */
static void t_slab_aim(void)
{
	struct run R;
	CHECK(start(&R, "tests/accuracy/slab.scn", "Fresnel=0", -1, false));
	double cone = 2 * M_PI * (1 - 1 / sqrt(51.0)), face = 4 * atan(25 / sqrt(51.0));
	printf("# slab: emitted %.9g (cone %.9g), escaped %g, landed %.7g (top face %.7g)\n", R.st.emitted[1], cone,
	       R.st.escaped[1], R.st.landed[1], face);
	CHECK_NEAR(R.st.emitted[1] / cone, 1, 1e-8);
	CHECK(R.st.escaped[1] == 0);
	CHECK_NEAR(R.st.landed[1] / face, 1, 0.001);
	stop(&R);
}

/* Energy: for the lossless sphere, the maps hold exactly what entered it
 * (2π(1 − cos θmax), θmax = asin(1/7)) to 0.1 %. */
static void t_energy_lossless(void)
{
	struct run R;
	CHECK(start(&R, "tests/accuracy/sphere.scn", "Fresnel=0", -1, false));
	double entering = 2 * M_PI * (1 - cos(asin(1.0 / 7)));
	CHECK_NEAR(R.st.deposited[1] / entering, 1, 0.001);
	CHECK(R.st.deposited[0] <= R.st.emitted[0] && R.st.deposited[2] <= R.st.emitted[2]);
	stop(&R);
}

/* Absorption along light rays inside glass (POV-Ray's exponential fade):
 * paraxial rays cross the sphere along its diameter, 2, so the centre of the
 * caustic is dimmed by exp(-0.5 · 2). */
static void t_absorption(void)
{
	double centre[2];
	for (int f = 0; f < 2; f++) {
		struct run R;
		CHECK(start(&R, "tests/accuracy/sphere.scn", f ? "Fade=1" : "Fade=0", -1, true));
		double e[3];
		lp_lookup(R.r, R.floor, 0, 0, e);
		centre[f] = e[1];
		stop(&R);
	}
	printf("# absorption: centre %.5g clear, %.5g absorbing (ratio %.4f, exp(-1) = %.4f)\n", centre[0],
	       centre[1], centre[1] / centre[0], exp(-1));
	CHECK_NEAR(centre[1] / centre[0], exp(-1), 0.01);
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

/* Under a parallel light of irradiance E straight down, a ray at distance b
 * from the axis crosses the sphere (centre height h, radius 1, index n) in
 * its meridional plane: refraction at entry and exit, then on to the floor.
 * Integrating E·2πb·db over b (midpoint rule, 2·10⁶ steps) into annuli of
 * width w gives the exact binned flux of the twice-transmitted light. */
static void sun_profile(double E, double h, double n, double w, double *ref, int nbins)
{
	enum { STEPS = 2000000 };
	for (int k = 0; k < nbins; k++)
		ref[k] = 0;
	for (int i = 0; i < STEPS; i++) {
		double b = (i + 0.5) / STEPS, db = 1.0 / STEPS;
		double px = b, py = sqrt(1 - b * b), dx = 0, dy = -1, ox, oy; /* entry, relative to the centre */
		if (!snell2(&dx, &dy, px, py, 1 / n))
			continue;
		double t = -2 * (px * dx + py * dy); /* the second hit of the unit circle */
		px += t * dx, py += t * dy;
		ox = dx, oy = dy;
		if (!snell2(&ox, &oy, -px, -py, n))
			continue; /* (never: a sphere has no internal reflection for these) */
		if (oy >= 0)
			continue; /* leaves upward: never reaches the floor */
		double x = px + (-(h + py) / oy) * ox;
		int bin = (int)(fabs(x) / w);
		if (bin < nbins)
			ref[bin] += E * 2 * M_PI * b * db;
	}
}

/* Parallel lights: the beam covers the sphere, each ray carries
 * E·A/N, and the floor's binned flux matches sun_profile like the
 * point-light references. An opaque plane upstream casts the beam's shadow. */
static void t_parallel(void)
{
	struct run R;
	CHECK(start(&R, "tests/accuracy/sun.scn", "Roof=0", -1, true));
	if (!R.r)
		return;
	double flux[60] = {0}, ref[60];
	struct bins B = {R.floor, 1, 0.05, 0, 0, 60, 1, flux, 1, 0};
	illum_each(lp_map(R.r, R.floor), bin_node, &B);
	sun_profile(1, 3, 1.5, 0.05, ref, 60);
	double l1, noise, g, t;
	compare(flux, ref, 60, R.st.emitted[1] / (double)R.st.rays, &l1, &noise, &g, &t);
	printf("# parallel light: L1 %.5f (noise %.5f), flux r<=3 %.6g (ref %.6g), emitted %.7g (π = %.7g)\n",
	       l1, noise, g, t, R.st.emitted[1], M_PI);
	CHECK(l1 <= 1.5 * noise + 0.005);
	CHECK_NEAR(g / t, 1, 0.005);
	CHECK_NEAR(R.st.emitted[1] / M_PI, 1, 1e-6); /* the disc of radius 1 around the sphere (not √3, the box's) */
	stop(&R);

	struct run Q;
	CHECK(start(&Q, "tests/accuracy/sun.scn", "Roof=1", -1, true) == 0); /* no map at all */
	CHECK(Q.st.rays > 0 && Q.st.deposited[1] == 0);
	stop(&Q);
}

/* POV-Ray's photons { } switches (tests/accuracy/photons.scn): each case
 * either leaves the caustic as it is, bit for bit, or removes it. */
static void t_photons_switches(void)
{
	static const bool lit[] = {true, false, false, true, false, false, false};
	double base = 0;
	for (int c = 0; c < 7; c++) {
		char def[16];
		snprintf(def, sizeof def, "Case=%d", c);
		struct run R;
		bool map = start(&R, "tests/accuracy/photons.scn", def, -1, false);
		printf("# photons case %d: deposited %.7g\n", c, R.st.deposited[1]);
		CHECK(map == lit[c]);
		CHECK(R.st.rays > 0);
		if (c == 0)
			base = R.st.deposited[1];
		CHECK(lit[c] ? R.st.deposited[1] == base && base > 0 : R.st.deposited[1] == 0);
		stop(&R);
	}
}

/* A spotlight weights the light rays by its cone, as the eye pass does. */
static void t_spotlight(void)
{
	struct run R;
	CHECK(start(&R, "tests/accuracy/spot.scn", NULL, -1, false));
	double want = 2 * M_PI * (1 - cos(5 * M_PI / 180));
	printf("# spotlight: deposited %.7g, expected %.7g\n", R.st.deposited[1], want);
	CHECK_NEAR(R.st.deposited[1] / want, 1, 0.005);
	stop(&R);
}

/* Mirror A: 0.1 cells over x in [-3, 1], z in [-4, 4] (each node's tent
 * spread over the cells it reaches: a node binned whole at its point put
 * the light of the nodes at x = 1, under the mirror's face, out of the grid,
 * 0.5 % of it, and shifted light across every cell edge); reflectance 1, or
 * Fresnel for n = 1.5 (then the total on the floor is 0.0707892 W). */
static void mirror_case(const char *define, int col, double exact_total)
{
	struct run R;
	CHECK(start(&R, "tests/accuracy/mirror.scn", define, -1, false));
	if (!R.r)
		return;
	enum { NX = 40, NZ = 80 };
	static double flux[NX * NZ], ref[NX * NZ];
	memset(flux, 0, sizeof flux);
	struct bins B = {R.floor, 0, 0.1, -3, -4, NX, NZ, flux, 1, 0.01}; /* mirror.scn's cell */
	illum_each(lp_map(R.r, R.floor), bin_node, &B);
	CHECK(read_column("tests/accuracy/A_grid_cellavg_0.1.csv", col, ref, NX * NZ) == NX * NZ);
	for (int k = 0; k < NX * NZ; k++)
		ref[k] *= 0.01; /* Ebar × cell area */
	double l1, noise, g, t;
	compare(flux, ref, NX * NZ, R.st.emitted[1] / (double)R.st.rays, &l1, &noise, &g, &t);
	printf("# mirror %s: L1 %.5f (noise %.5f), flux in the grid %.6g (ref %.6g), on the floor %.7g (exact %.7g)\n",
	       define, l1, noise, g, t, R.st.deposited[1], exact_total);
	CHECK(l1 <= 1.5 * noise + 0.005);
	CHECK_NEAR(g / t, 1, 0.005);
	/* all reflected light from the mirror's lower half reaches the floor */
	CHECK_NEAR(R.st.deposited[1] / exact_total, 1, 0.005);
	stop(&R);
}

static void t_mirror(void) { mirror_case("Fresnel=0", 5, 1.3694384); }
static void t_mirror_fresnel(void) { mirror_case("Fresnel=1", 6, 0.0707892); }

/* Chromatic aberration: with dispersion the red pass (lower index) focuses
 * farther from the sphere, nearer the floor, than the blue one: red is
 * brighter at the centre. */
static void t_dispersion(void)
{
	double centre[3];
	for (int c = 0; c < 3; c += 2) {
		struct run R;
		CHECK(start(&R, "tests/accuracy/dispersion.scn", NULL, c, false));
		double e[3];
		lp_lookup(R.r, R.floor, 0, 0, e);
		centre[c] = e[c];
		CHECK(e[1] == 0 && e[2 - c] == 0); /* a channel pass carries its channel only */
		stop(&R);
	}
	printf("# dispersion: centre irradiance red %.5g blue %.5g\n", centre[0], centre[2]);
	CHECK(centre[0] > 1.05 * centre[2]);
}

/* End to end: the eye pass reads the map. Under the sphere the floor gets no
 * direct light, the caustic layer holds E(0) = 0.0625 W/m² (paraxial, the
 * reference's point value), and the beauty is diffuse · E / π exactly. */
static void t_render_caustic_layer(void)
{
	struct scene s;
	struct diag dg;
	diag_init(&dg, stderr);
	struct eval_options eo;
	eval_default_options(&eo);
	CHECK(eval_scene("tests/accuracy/sphere_view.scn", &eo, &dg, &s) == 0);
	struct render_opts ro = {.width = 21, .height = 21, .spp = 1, .threads = 2, .quiet = 1, .rays = 2000000};
	struct framebuffer *fb = NULL;
	struct render_stats st;
	CHECK(MSG(render(&s, &ro, TDG, &fb, &st)) == NULL);
	if (fb) {
		float *c = fb_find(fb, "caustic.G"), *d = fb_find(fb, "direct.G"), *g = fb_find(fb, "G");
		CHECK(c && d && g);
		if (c && d && g) {
			int i = 10 * 21 + 10;
			printf("# centre: caustic %.5f W/m2, direct %.5f, beauty %.6f\n", c[i], d[i], g[i]);
			CHECK_NEAR(c[i], 0.0625, 0.0625 * 0.08);
			CHECK(d[i] == 0);
			CHECK_NEAR(g[i], 0.6 * c[i] / M_PI, 1e-6);
		}
		fb_free(fb);
	}
	CHECK(st.light_rays > 0 && st.maps == 1);
	scene_free(&s);
}

/* The largest |R − B| of a render of dispersion_view.scn with dispersion D. */
static double fringe(const char *define)
{
	struct scene s;
	struct diag dg;
	diag_init(&dg, stderr);
	struct eval_options eo;
	eval_default_options(&eo);
	const char *defs[1] = {define};
	eo.defines = defs;
	eo.ndefines = 1;
	double worst = -1;
	if (eval_scene("tests/accuracy/dispersion_view.scn", &eo, &dg, &s) != 0)
		return worst;
	struct render_opts ro = {.width = 48, .height = 36, .spp = 1, .threads = 2, .quiet = 1, .rays = -1};
	struct framebuffer *fb = NULL;
	if (MSG(render(&s, &ro, TDG, &fb, NULL)) == NULL && fb) {
		const float *r = fb_find(fb, "R"), *b = fb_find(fb, "B");
		worst = 0;
		for (int i = 0; i < 48 * 36; i++)
			worst = fmax(worst, fabs((double)r[i] - b[i]));
		fb_free(fb);
	}
	scene_free(&s);
	return worst;
}

/* Chromatic aberration in the eye pass: each channel refracts with its own
 * index, so a neutral scene seen through dispersive glass gets colour
 * fringes, and none without dispersion. */
static void t_eye_dispersion(void)
{
	double none = fringe("D=1"), some = fringe("D=1.2");
	printf("# eye-pass dispersion: max |R-B| %.4f without, %.4f with\n", none, some);
	CHECK(none == 0);
	CHECK(some > 0.1);
}

/* ---- eq. (1) on every primitive ---------------------------------------- */

struct eq1 {
	const struct object *o;
	const struct bvh *b;
	struct vec3 L;          /* the light */
	struct uv_range rg;     /* the object's (u,v) domain */
	double du, dv;          /* node spacing */
	double diff, ref, var;  /* Σ|Ê−E|·A, Σ E·A, Σ σ_E·A (noise) */
};

/* I·|cosθ|/d² at T(u,v) if the light sees the point, else 0 (I = 1). */
static double irradiance_at(const struct eq1 *q, double u, double v, double *jac)
{
	struct vec3 p, a, b;
	*jac = 0;
	if (!shape_uv_point(q->o, u, v, &p, &a, &b))
		return 0;
	struct vec3 n = v_cross(a, b), d = v_sub(q->L, p);
	*jac = v_len(n);
	double dist = v_len(d);
	if (*jac <= 0)
		return 0;
	struct ray r = {v_madd(p, d, 1e-7), d};
	if (bvh_occluded(q->b, &r, 0, 1 - 2e-7))
		return 0;
	return fabs(v_dot(n, d)) / (*jac * dist * dist * dist);
}

/* The node's expected value: the tent-weighted average of the irradiance over
 * its support (what energy / tent-weighted area estimates), by a 16×16
 * midpoint rule, clipped to the domain on non-wrapping axes. */
static double tent_average(const struct eq1 *q, double u, double v)
{
	double num = 0, den = 0;
	for (int i = 0; i < 16; i++) {
		double s = (i + 0.5) / 8 - 1, uu = u + s * q->du;
		if (q->rg.bounded && !q->rg.u_wraps && (uu < q->rg.u0 || uu > q->rg.u1))
			continue;
		for (int k = 0; k < 16; k++) {
			double t = (k + 0.5) / 8 - 1, vv = v + t * q->dv, jac;
			if (q->rg.bounded && !q->rg.v_wraps && (vv < q->rg.v0 || vv > q->rg.v1))
				continue;
			double w = (1 - fabs(s)) * (1 - fabs(t)), e = irradiance_at(q, uu, vv, &jac);
			num += w * jac * e;
			den += w * jac;
		}
	}
	return den > 0 ? num / den : 0;
}

static void eq1_node(void *ctx, const struct illum_node *n)
{
	struct eq1 *q = ctx;
	struct vec3 p, a, b;
	if (n->area <= 0 || !shape_uv_point(q->o, n->u, n->v, &p, &a, &b))
		return;
	/* the unbounded plane: the region under the light where the rays are dense */
	if (!q->rg.bounded && hypot(p.x - q->L.x, p.z - q->L.z) > 3)
		return;
	double e = tent_average(q, n->u, n->v);
	q->diff += fabs(n->irr[1] - e) * n->area;
	q->ref += e * n->area;
	q->var += sqrt(n->sumsq[1]); /* σ of the node's energy */
}

/* With first-generation deposits, the map's irradiance equals the shadow-ray
 * irradiance (the paper's eq. 1 with integrated node areas), poles, apex and
 * disc centre included: flux-weighted L1 within 2 % beyond the noise. */
static void t_eq1_every_primitive(void)
{
	static const char *const names[] = {"plane", "sphere", "cylinder", "cone", "torus", "box", "disc"};
	for (int k = 0; k < 7; k++) {
		char def[32];
		snprintf(def, sizeof def, "Shape=%d", k);
		struct diag dg;
		diag_init(&dg, stderr);
		struct eval_options eo;
		eval_default_options(&eo);
		const char *defs[1] = {def};
		eo.defines = defs;
		eo.ndefines = 1;
		struct scene s;
		CHECK(eval_scene("tests/accuracy/eq1.scn", &eo, &dg, &s) == 0);
		struct bvh *b = bvh_build(s.objects, s.nobjects);
		struct mat_cache mc;
		memset(&mc, 0, sizeof mc);
		struct lp_opts o = {.rays = 2000000, .max_depth = 1, .min_weight = 0, .threads = 2,
		                    .deposit_direct = true, .discard_isolated = true, .channel = -1, .aim_all = true};
		struct lp_stats st;
		struct lp_result *r = lp_run(&s, b, &mc, &o, &st);
		const struct illum_map *m = lp_map(r, s.objects[0]);
		CHECK(m != NULL);
		if (m) {
			struct eq1 q = {.o = s.objects[0], .b = b, .L = s.lights[0].pos};
			long nu, nv;
			shape_uv_range(q.o, &q.rg);
			illum_grid(m, &nu, &nv, &q.du, &q.dv);
			illum_each(m, eq1_node, &q);
			double l1 = q.diff / q.ref, noise = sqrt(2 / M_PI) * q.var / q.ref;
			printf("# eq. 1 on the %s: L1 %.4f (noise %.4f)\n", names[k], l1, noise);
			CHECK(l1 <= 1.5 * noise + 0.02);
		}
		lp_free(r);
		bvh_free(b);
		scene_free(&s);
	}
}

/* ---- thread counts -------------------------------------------------------- */

struct nodelist {
	struct illum_node *a;
	long n, cap;
};

static void keep_node(void *ctx, const struct illum_node *n)
{
	struct nodelist *L = ctx;
	if (L->n == L->cap)
		L->a = realloc(L->a, sizeof *L->a * (size_t)(L->cap = L->cap ? 2 * L->cap : 4096));
	L->a[L->n++] = *n;
}

/* Every map of scene B (Fresnel on: reflected and refracted light on the
 * floor) is the same, bit for bit, on 1, 2 and 3 threads: energies, counts,
 * areas, irradiances and even the float Σw², whose sums depend on the order
 * of the deposits (they are taken in work-item order, whichever thread
 * traced the item). Both methods. */
static void t_threads_identical(void)
{
	struct diag dg;
	diag_init(&dg, stderr);
	struct eval_options eo;
	eval_default_options(&eo);
	const char *defs[1] = {"Fresnel=1"};
	eo.defines = defs;
	eo.ndefines = 1;
	struct scene s;
	if (eval_scene("tests/accuracy/sphere.scn", &eo, &dg, &s) != 0) {
		CHECK(0);
		return;
	}
	struct bvh *b = bvh_build(s.objects, s.nobjects);
	struct mat_cache mc;
	memset(&mc, 0, sizeof mc);
	const struct object *floor = s.objects[s.nobjects - 1];
	for (int shafts = 0; shafts < 2; shafts++) {
		struct nodelist one = {NULL, 0, 0};
		for (int t = 1; t <= 3; t++) {
			struct lp_opts o = {.rays = shafts ? 20000 : 100000, .max_depth = 10, .min_weight = 1e-9, .threads = t,
			                    .discard_isolated = true, .channel = -1, .shafts = shafts};
			struct lp_stats st;
			struct lp_result *r = lp_run(&s, b, &mc, &o, &st);
			struct nodelist L = {NULL, 0, 0};
			for (int l = 0; r && l < LP_LEVELS; l++)
				if (lp_map_level(r, floor, l))
					illum_each(lp_map_level(r, floor, l), keep_node, &L);
			CHECK(L.n > 1000);
			if (t == 1) {
				one = L;
			} else {
				CHECK(L.n == one.n);
				long diff = 0, dsq = 0;
				for (long k = 0; k < L.n && k < one.n; k++) {
					const struct illum_node *x = &L.a[k], *y = &one.a[k];
					diff += x->i != y->i || x->j != y->j || x->count != y->count || x->isolated != y->isolated;
					diff += memcmp(x->energy, y->energy, sizeof x->energy) != 0 || memcmp(&x->area, &y->area, sizeof x->area);
					diff += memcmp(x->irr, y->irr, sizeof x->irr) != 0;
					dsq += memcmp(x->sumsq, y->sumsq, sizeof x->sumsq) != 0;
				}
				printf("# %s, %d threads: %ld nodes, %ld differ, %ld differ in sumsq\n", shafts ? "shafts" : "points", t,
				       L.n, diff, dsq);
				CHECK(diff == 0 && dsq == 0);
				free(L.a);
			}
			lp_free(r);
		}
		free(one.a);
	}
	bvh_free(b);
	scene_free(&s);
}

int main(void)
{
	RUN(t_sphere_ideal);
	RUN(t_sphere_fresnel);
	RUN(t_slab_ideal);
	RUN(t_slab_fresnel);
	RUN(t_slab_aim);
	RUN(t_energy_lossless);
	RUN(t_spotlight);
	RUN(t_parallel);
	RUN(t_photons_switches);
	RUN(t_absorption);
	RUN(t_mirror);
	RUN(t_mirror_fresnel);
	RUN(t_dispersion);
	RUN(t_render_caustic_layer);
	RUN(t_eye_dispersion);
	RUN(t_eq1_every_primitive);
	RUN(t_threads_identical);
	srcfile_free_all();
	return test_done();
}
