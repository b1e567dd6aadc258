/* SPDX-License-Identifier: MIT */
/* test_transport.c: the one surface step (tracer/surface.h) and the light
 * transport both passes build on it: no surface returns more light than it
 * receives, for every finish/interior combination the language allows, in
 * the surface step itself, in the light pass (whose energy balance must
 * close) and in the eye pass (a white furnace); total internal reflection in
 * a tilted glass cube creates no energy; transparent objects cast
 * see-through shadows exactly once. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../../common/diag.h"
#include "../../eval/eval.h"
#include "../../tracer/bvh.h"
#include "../../tracer/light/lightpass.h"
#include "../../tracer/render.h"
#include "../../tracer/spectrum.h"
#include "../../tracer/surface.h"
#include "geo_rand.h"
#include "test.h"

/* The materials of the language, as finish/pigment/interior text. */
static const struct mat {
	const char *name, *text;
	bool lossless; /* R + T = 1 everywhere */
} mats[] = {
	{"ideal", "pigment { rgbf 1 } interior { ior 1.5 }", true},
	{"fresnel", "pigment { rgbf 1 } finish { reflection { 0, 1 fresnel on } } interior { ior 1.5 }", true},
	{"conserve_energy", "pigment { rgbf 1 } finish { reflection 0.3 conserve_energy } interior { ior 1.5 }", true},
	{"reflection+filter", "pigment { rgbf 1 } finish { reflection 0.3 } interior { ior 1.5 }", true},
	{"metallic", "pigment { rgbf <1, 0.5, 0.2, 0.5> } finish { reflection { 0.5 metallic } } interior { ior 1.3 }", false},
	{"filter", "pigment { rgbf <1, 0.5, 0.2, 0.9> } interior { ior 1.5 }", false},
	{"transmit", "pigment { rgbt <0.2, 0.5, 1, 0.7> } interior { ior 1.5 }", false},
	{"absorbing", "pigment { rgbf 1 } finish { reflection { 0, 1 fresnel on } } interior { ior 1.5 "
	              "fade_distance 1 fade_power 1001 fade_color rgb <0.5, 0.7, 0.9> }", false},
	{"mirror", "pigment { rgb 0.8 } finish { reflection 1 }", true},
	{"ior 1", "pigment { rgbt <1, 1, 1, 0.9> } interior { ior 1 }", false},
	{"dispersive", "pigment { rgbf 1 } finish { reflection { 0, 1 fresnel on } } interior { ior 1.5 dispersion 1.1 }", true},
};
#define NMATS ((int)(sizeof mats / sizeof mats[0]))

/* Writes text to a new temporary .scn file; returns its path (static). */
static const char *scene_file(const char *text)
{
	static char path[64];
	strcpy(path, "/tmp/arvo-transport-XXXXXX.scn");
	int fd = mkstemps(path, 4);
	if (fd < 0)
		return NULL;
	size_t n = strlen(text);
	bool ok = write(fd, text, n) == (ssize_t)n;
	close(fd);
	return ok ? path : NULL;
}

static int load(const char *text, struct scene *s)
{
	const char *path = scene_file(text);
	struct diag dg;
	diag_init(&dg, stderr);
	struct eval_options eo;
	eval_default_options(&eo);
	static char cwd[4096];
	const char *dirs[1] = {getcwd(cwd, sizeof cwd)};
	eo.include_dirs = dirs;
	eo.ninclude = 1;
	int rc = path ? eval_scene(path, &eo, &dg, s) : 1;
	if (path)
		unlink(path);
	return rc == 0;
}

/* ---- the surface step ---------------------------------------------------- */

/* Every material, legacy or physical, every band, entering and leaving, at
 * random incidence (TIR included): 0 <= R, T and R + T <= 1 per channel;
 * lossless materials keep exactly 1. */
static void t_scatter_never_creates(void)
{
	rng_seed(0x7A11u);
	for (int m = 0; m < NMATS; m++)
		for (int legacy = 0; legacy < 2; legacy++) {
			char text[512];
			snprintf(text, sizeof text, "%s sphere { 0, 1 %s }\n", legacy ? "#version 3.7;" : "", mats[m].text);
			struct scene s;
			if (!load(text, &s)) {
				CHECK(!"scene loads");
				continue;
			}
			const struct object *o = s.objects[0];
			struct mat_cache mc;
			memset(&mc, 0, sizeof mc);
			double worst = 0, lossless = 0;
			for (int i = 0; i < 4000; i++) {
				struct hit h;
				struct vec3 d = rnd_dir(), p = v_neg(v_scale(d, 3));
				if (i & 1) /* from inside: leaving the glass */
					p = v_scale(rnd_dir(), 0.3);
				if (!shape_intersect(o, &(struct ray){p, d}, 0, INFINITY, &h))
					continue;
				struct surf_in si;
				struct surf_out so;
				surf_prepare(&s, &mc, &h, d, &si);
				struct band b = {(i / 2) % 4 - 1, i % 5 == 0 ? 400 + 300 * rnd() : 0};
				surf_scatter(&si, b, &so);
				for (int c = 0; c < 3; c++) {
					double R = v_comp(so.R, c), T = v_comp(so.T, c);
					CHECK(R >= 0 && T >= 0);
					worst = fmax(worst, R + T);
					if (mats[m].lossless)
						lossless = fmax(lossless, fabs(R + T - 1));
				}
			}
			if (!(worst <= 1 + 1e-12) || !(lossless <= 1e-12))
				printf("#   %s%s: max R+T %.17g, lossless error %.3g\n", mats[m].name, legacy ? " (legacy)" : "",
				       worst, lossless);
			CHECK(worst <= 1 + 1e-12);
			CHECK(lossless <= 1e-12);
			scene_free(&s);
		}
}

/* Dispersion: red bends least, blue most; Cauchy wavelengths span them. */
static void t_ior_bands(void)
{
	struct interior in = scene_default_interior();
	in.ior = 1.5;
	in.dispersion = 1.1;
	double r = surf_ior(&in, (struct band){0, 0}), gg = surf_ior(&in, (struct band){1, 0});
	double bl = surf_ior(&in, (struct band){2, 0});
	CHECK_NEAR(gg, 1.5, 1e-15);
	CHECK_NEAR(bl / r, 1.1, 1e-12);
	/* a wavelength (Cauchy, spectrum.h): at the channels' centroids the
	 * light of each channel refracts as the channel does, on average:
	 * green at ior, blue/red = D */
	double lr = spec_centroid(0), lg = spec_centroid(1), lb = spec_centroid(2);
	CHECK_NEAR(surf_ior(&in, (struct band){-1, lg}), 1.5, 1e-12);
	CHECK_NEAR(surf_ior(&in, (struct band){-1, lb}) / surf_ior(&in, (struct band){-1, lr}), 1.1, 1e-12);
	CHECK(surf_ior(&in, (struct band){-1, 400}) > surf_ior(&in, (struct band){-1, 700}));
	in.dispersion = 1;
	CHECK(surf_ior(&in, (struct band){2, 450}) == 1.5);
}

/* ---- the light pass -------------------------------------------------------- */

static void light_run(struct scene *s, long rays, int max_depth, struct lp_stats *st, struct lp_result **out)
{
	struct bvh *b = bvh_build(s->objects, s->nobjects);
	struct mat_cache mc;
	memset(&mc, 0, sizeof mc);
	struct lp_opts o = {.rays = rays, .max_depth = max_depth, .min_weight = 1e-12, .threads = 2,
	                    .discard_isolated = false, .channel = -1};
	struct lp_result *r = lp_run(s, b, &mc, &o, st);
	if (out)
		*out = r;
	else
		lp_free(r);
	bvh_free(b);
}

/* The solid angle of triangle (a, b, c) seen from the origin (Van Oosterom
 * and Strackee). */
static double tri_omega(struct vec3 a, struct vec3 b, struct vec3 c)
{
	double la = v_len(a), lb = v_len(b), lc = v_len(c);
	double num = v_dot(a, v_cross(b, c));
	double den = la * lb * lc + v_dot(a, b) * lc + v_dot(a, c) * lb + v_dot(b, c) * la;
	return fabs(2 * atan2(num, den));
}

/* The solid angle of the tilted cube of tests/accuracy/cube.scn seen from
 * its light: its three faces turned toward the light, each two triangles. */
static double cube_omega(void)
{
	struct xform xf = xf_then(xf_rotate(v3(30, 0, 40)), xf_translate(v3(0, 4, 0)));
	struct vec3 L = v3(0, 14, 0);
	double om = 0;
	for (int axis = 0; axis < 3; axis++)
		for (int sgn = -1; sgn <= 1; sgn += 2) {
			struct vec3 n = v3(axis == 0 ? sgn : 0, axis == 1 ? sgn : 0, axis == 2 ? sgn : 0), q[4];
			struct vec3 t1 = v3(axis == 1, axis == 2, axis == 0), t2 = v_cross(n, t1);
			for (int k = 0; k < 4; k++) {
				double a = k == 0 || k == 3 ? -1 : 1, bb = k < 2 ? -1 : 1;
				q[k] = v_sub(xf_point(&xf, v_add(n, v_add(v_scale(t1, a), v_scale(t2, bb)))), L);
			}
			struct vec3 c = v_sub(xf_point(&xf, n), L), nw = xf_normal(&xf, n);
			if (v_dot(nw, c) >= 0)
				continue; /* faces away from the light */
			om += tri_omega(q[0], q[1], q[2]) + tri_omega(q[0], q[2], q[3]);
		}
	return om;
}

/* A glass cube tilted over a floor, light above, inside a closed room (a
 * ceiling over the light), so whatever leaves the cube lands somewhere:
 * Fresnel glass can only lose light to reflection, so its caustic on the
 * floor holds less than lossless ideal glass's, and ideal glass deposits
 * exactly the flux that
 * enters the cube, I·Ω (Ω its exact solid angle), to 0.1 %; so do the
 * Fresnel and conserve_energy cubes, whose reflections land too, while
 * their floor caustic is dimmer. */
static void t_tilted_cube(void)
{
	double dep[3], floor_e[3];
	double omega = cube_omega();
	for (int f = 0; f < 3; f++) {
		char text[1024];
		snprintf(text, sizeof text,
		         "#declare Fresnel = %d;\n#include \"tests/accuracy/cube.scn\"\n"
		         "plane { y, 20 pigment { rgb 1 } illum_map { cell 1 } }\n", f);
		struct scene s;
		if (!load(text, &s)) {
			CHECK(!"scene loads");
			return;
		}
		struct lp_stats st;
		struct lp_result *r;
		light_run(&s, 1000000, 40, &st, &r);
		double tot[3] = {0, 0, 0};
		const struct illum_map *m = lp_map(r, s.objects[1]);
		if (m)
			illum_total(m, tot);
		floor_e[f] = tot[1];
		dep[f] = st.landed[1];
		double sum = st.landed[1] + st.direct[1] + st.absorbed[1] + st.escaped[1] + st.cut[1];
		printf("# cube %d: emitted %.6f, floor %.6f, deposited %.6f, escaped %.3g, cut %.3g, I*omega %.6f\n", f,
		       st.emitted[1], floor_e[f], dep[f], st.escaped[1], st.cut[1], omega);
		CHECK_NEAR(sum / st.emitted[1], 1, 1e-9);
		lp_free(r);
		scene_free(&s);
	}
	CHECK(floor_e[1] < floor_e[0]);
	CHECK(floor_e[2] < floor_e[0]);
	for (int f = 0; f < 3; f++) /* all three are lossless: all that enters lands */
		CHECK_NEAR(dep[f] / omega, 1, 0.001);
}

/* The energy balance closes for every material, and the maps never hold
 * more than was emitted (a sphere of each material over an opaque floor):
 * the floor's map, where every ray ends at most once, for every material;
 * all maps for a sphere that takes no map itself. A partly opaque sphere's
 * map holds the light incident on its inside, which then goes on in part
 * to the floor, so its map and the floor's together may hold more than was
 * emitted (every ray aimed at the sphere reaches it: the light pass aims at
 * the sphere, not at the box around it). */
static void t_balance(void)
{
	for (int m = 0; m < NMATS; m++) {
		char text[1024];
		snprintf(text, sizeof text, "light_source { <1, 8, 0.5>, rgb 1 }\n"
		         "sphere { <0, 2, 0>, 1 %s }\nplane { y, 0 pigment { rgb 1 } illum_map { cell 0.05 } }\n",
		         mats[m].text);
		struct scene s;
		if (!load(text, &s)) {
			CHECK(!"scene loads");
			continue;
		}
		struct lp_stats st;
		struct lp_result *r;
		light_run(&s, 200000, 12, &st, &r);
		if (!strcmp(mats[m].name, "ior 1")) { /* its light is the shadow rays': not a target */
			CHECK(st.emitted[0] == 0 && st.rays == 0);
			lp_free(r);
			scene_free(&s);
			continue;
		}
		double floor_e[3] = {0, 0, 0};
		const struct illum_map *fm = lp_map(r, s.objects[1]);
		CHECK(fm != NULL);
		if (fm)
			illum_total(fm, floor_e);
		bool sphere_map = lp_map(r, s.objects[0]) != NULL;
		lp_free(r);
		for (int c = 0; c < 3; c++) {
			double sum = st.landed[c] + st.direct[c] + st.absorbed[c] + st.escaped[c] + st.cut[c];
			CHECK_NEAR(sum / st.emitted[c], 1, 1e-9);
			CHECK(floor_e[c] > 0 && floor_e[c] <= st.emitted[c]);
			CHECK(sphere_map || st.deposited[c] <= st.emitted[c]);
			if (mats[m].lossless && m != 3)
				CHECK(st.absorbed[c] == 0);
		}
		scene_free(&s);
	}
}

/* ---- the eye pass -------------------------------------------------------- */

/* A white furnace: each material as a sphere filling the view of a camera
 * in a uniform background of radiance 1, no lights: every pixel is at most
 * 1, and exactly 1 (to the depth limit) for lossless materials. */
static void t_furnace(void)
{
	for (int m = 0; m < NMATS; m++)
		for (int legacy = 0; legacy < 2; legacy++) {
			char text[1024];
			snprintf(text, sizeof text, "%s global_settings { max_trace_level 60 adc_bailout 1e-9 }\n"
			         "camera { location <0, 0, -3> look_at 0 angle 40 }\nbackground { rgb 1 }\n"
			         "sphere { 0, 1 %s finish { ambient 0 diffuse 0 } }\n", legacy ? "#version 3.7;" : "",
			         mats[m].text);
			struct scene s;
			if (!load(text, &s)) {
				CHECK(!"scene loads");
				continue;
			}
			struct render_opts ro = {.width = 9, .height = 9, .spp = 4, .threads = 2, .quiet = 1, .rays = -1};
			struct framebuffer *fb = NULL;
			CHECK(MSG(render(&s, &ro, TDG, &fb, NULL)) == NULL);
			double hi = 0, err = 0;
			for (int c = 0; fb && c < 3; c++) {
				const float *p = fb_find(fb, c == 0 ? "R" : c == 1 ? "G" : "B");
				for (int i = 0; i < 81; i++) {
					hi = fmax(hi, p[i]);
					err = fmax(err, fabs(p[i] - 1));
				}
			}
			if (!(hi <= 1 + 1e-5) || (mats[m].lossless && !(err <= 1e-3)))
				printf("#   %s%s: brightest %.9g, lossless error %.3g\n", mats[m].name,
				       legacy ? " (legacy)" : "", hi, err);
			CHECK(hi <= 1 + 1e-5);
			if (mats[m].lossless)
				CHECK(err <= 1e-3);
			fb_free(fb);
			scene_free(&s);
		}
}

int main(void)
{
	RUN(t_scatter_never_creates);
	RUN(t_ior_bands);
	RUN(t_tilted_cube);
	RUN(t_balance);
	RUN(t_furnace);
	return test_done();
}
