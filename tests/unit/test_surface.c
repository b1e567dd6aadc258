/* SPDX-License-Identifier: MIT */
/* test_surface.c: surf_any_straight (tracer/surface.h), which decides
 * whether the eye pass's shadow rays look for straight transmitters or only
 * ask whether anything blocks them: a pattern of opaque colours (a checker
 * floor) is no transmitter, a pattern with one filtering or transmitting
 * colour anywhere (its colours, colour_map, pigment_map) is, and so is a
 * texture_map or layered texture; a clear object that bends light (ior 1.5)
 * is not (the light pass carries what passes it). */
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "../../common/diag.h"
#include "../../eval/eval.h"
#include "../../tracer/scatter.h"
#include "../../tracer/surface.h"
#include "geo_rand.h"
#include "test.h"

/* Evaluates SDL text (written to a temporary file) into *s: 0, or -1 when
 * it does not evaluate. */
static int load_scene(const char *text, struct scene *s)
{
	char path[64];
	snprintf(path, sizeof path, "/tmp/arvo-test-surface-%ld.scn", (long)getpid());
	FILE *f = fopen(path, "w");
	if (!f)
		return -1;
	fputs(text, f);
	fclose(f);
	struct eval_options eo;
	eval_default_options(&eo);
	struct diag dg;
	diag_init(&dg, stdout);
	int rc = eval_scene(path, &eo, &dg, s);
	remove(path);
	return rc != 0 ? -1 : 0;
}

/* surf_any_straight of a scene of one plane under a light with the given
 * texture and interior (SDL text); -1 when it does not evaluate. */
static int straight_of(const char *texture, const char *interior)
{
	char text[1024];
	snprintf(text, sizeof text, "camera { location <0, 1, -4> look_at 0 }\nlight_source { <0, 5, -5>, rgb 1 }\n"
	                            "plane { y, 0 texture { %s } interior { %s } }\n", texture, interior);
	struct scene s;
	if (load_scene(text, &s) != 0)
		return -1;
	int got = surf_any_straight(&s);
	scene_free(&s);
	return got;
}

static void t_opaque_patterns(void)
{
	CHECK(straight_of("pigment { rgb 0.5 }", "ior 1") == 0);
	CHECK(straight_of("pigment { checker rgb 1 rgb 0.2 }", "ior 1") == 0);
	CHECK(straight_of("pigment { hexagon rgb 1 rgb 0.2 rgb 0.4 }", "ior 1") == 0);
	CHECK(straight_of("pigment { brick rgb 1 rgb 0.2 }", "ior 1") == 0);
	CHECK(straight_of("pigment { bozo }", "ior 1") == 0); /* its default colour map */
	CHECK(straight_of("pigment { gradient y color_map { [0 rgb 0] [1 rgb <1, 0, 0>] } }", "ior 1") == 0);
	CHECK(straight_of("pigment { checker pigment { rgb 1 } pigment { granite } }", "ior 1") == 0);
	CHECK(straight_of("pigment { gradient x pigment_map { [0 rgb 1] [1 checker rgb 0 rgb 1] } }", "ior 1") == 0);
}

static void t_clear_patterns(void)
{
	CHECK(straight_of("pigment { rgbf <1, 1, 1, 0.5> }", "ior 1") == 1);
	CHECK(straight_of("pigment { checker rgb 1 rgbt <1, 1, 1, 0.5> }", "ior 1") == 1);
	CHECK(straight_of("pigment { checker rgbf <1, 1, 1, 0.5> rgb 1 }", "ior 1") == 1);
	CHECK(straight_of("pigment { hexagon rgb 1 rgb 0.2 rgbf 0.4 }", "ior 1") == 1);
	CHECK(straight_of("pigment { gradient y color_map { [0 rgb 0] [1 rgbt 1] } }", "ior 1") == 1);
	CHECK(straight_of("pigment { checker pigment { rgb 1 } pigment { bozo color_map { [0 rgbf 1] [1 rgb 0] } } }",
	                  "ior 1") == 1);
	CHECK(straight_of("pigment { gradient x pigment_map { [0 rgb 1] [1 rgbt <0, 0, 0, 0.1>] } }", "ior 1") == 1);
	/* where the colours come from a map of textures, or a layer below */
	CHECK(straight_of("checker texture { pigment { rgb 1 } } texture { pigment { rgb 0 } }", "ior 1") == 1);
	/* clear, but bending light: a caustic of the light pass, not a shadow's */
	CHECK(straight_of("pigment { checker rgb 1 rgbf 0.9 }", "ior 1.5") == 0);
	CHECK(straight_of("pigment { rgbf 0.9 }", "ior 1.5") == 0);
}

/* The light pass's surface step in parts (lightpass.c's oinfo cache:
 * surf_prepare_obj made once per object, surf_prepare_hit per hit, and
 * under sc_refl_fixed surf_weights made once, then sc_sides and
 * surf_scatter_rt) against the one step both passes take (surf_prepare,
 * surf_scatter): the same R, T, spawned rays and total internal reflection,
 * bit for bit, for hits from outside and inside a sphere in every band
 * (each RGB channel, all three, wavelengths). Returns the hits compared, -1
 * when the scene does not evaluate; *plain is surf_prepare_obj's answer,
 * *fixed sc_refl_fixed's, *differ the hits whose parts differ. */
static long split_matches(const char *version, const char *texture, const char *interior, bool *plain, bool *fixed,
                          long *differ)
{
	char text[1024];
	snprintf(text, sizeof text, "%s\ncamera { location <0, 1, -4> look_at 0 }\nlight_source { <0, 5, -5>, rgb 1 }\n"
	                            "sphere { 0, 1 texture { %s } interior { %s } }\n", version, texture, interior);
	struct scene s;
	if (load_scene(text, &s) != 0)
		return -1;
	if (s.nobjects != 1) {
		scene_free(&s);
		return -1;
	}
	const struct object *o = s.objects[0];
	struct mat_cache mc;
	memset(&mc, 0, sizeof mc);
	struct surf_in obj;
	*plain = surf_prepare_obj(&s, o, &obj);
	*fixed = *plain && sc_refl_fixed(obj.f);
	struct sc_weights w = {{0, 0, 0}, {0, 0, 0}};
	if (*fixed)
		w = surf_weights(&obj, 1, 1, 1);
	const struct band bands[] = {BAND_ALL, {0, 0}, {1, 0}, {2, 0}, {-1, 420}, {-1, 555}, {-1, 690}};
	long n = 0;
	*differ = 0;
	rng_seed(17);
	for (int k = 0; k < 4000; k++) {
		/* from outside toward a point near the sphere, or from inside */
		struct vec3 a = v3(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5), b = v3(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5);
		struct ray r = k % 2 ? (struct ray){v_scale(v_norm(a), 3), v_sub(v_scale(b, 1.8), v_scale(v_norm(a), 3))}
		                     : (struct ray){v_scale(a, 1.2), b};
		struct hit h;
		if (!shape_intersect(o, &r, 0, INFINITY, &h))
			continue;
		struct vec3 d = v_norm(r.d);
		for (size_t bi = 0; bi < sizeof bands / sizeof *bands; bi++) {
			struct surf_in ref, part = obj;
			struct surf_out want, got;
			memset(&want, 0, sizeof want), memset(&got, 0, sizeof got);
			surf_prepare(&s, &mc, &h, d, &ref);
			surf_scatter(&ref, bands[bi], &want);
			if (!*plain) {
				n++;
				continue;
			}
			surf_prepare_hit(&h, d, &part);
			if (*fixed) {
				double n1, n2;
				sc_sides(&part, bands[bi], &n1, &n2);
				surf_scatter_rt(&part, n1, n2, w, &got);
			} else {
				surf_scatter(&part, bands[bi], &got);
			}
			bool same = part.f == ref.f && part.in == ref.in && part.legacy == ref.legacy &&
			            part.straight == ref.straight && !memcmp(&part.pc, &ref.pc, sizeof part.pc) &&
			            !memcmp(&part.nf, &ref.nf, sizeof part.nf) && !memcmp(&part.d, &ref.d, sizeof part.d) &&
			            !memcmp(&got.R, &want.R, sizeof got.R) && !memcmp(&got.T, &want.T, sizeof got.T) &&
			            got.tir == want.tir;
			if (same && (want.T.x > 0 || want.T.y > 0 || want.T.z > 0))
				same = !memcmp(&got.trans, &want.trans, sizeof got.trans);
			if (same && (want.R.x > 0 || want.R.y > 0 || want.R.z > 0))
				same = !memcmp(&got.refl, &want.refl, sizeof got.refl);
			*differ += !same;
			n++;
		}
	}
	scene_free(&s);
	return n;
}

static void t_light_pass_parts(void)
{
	static const struct {
		const char *version, *texture, *interior;
		bool plain, fixed;
	} c[] = {
		{"", "pigment { rgbf <1, 1, 1, 0.9> } finish { reflection 0.1 }", "ior 1.5", true, true},
		{"", "pigment { rgbt <0.9, 0.8, 1, 0.6> } finish { reflection rgb <0.1, 0.2, 0.3> conserve_energy }",
		 "ior 1.7 dispersion 1.1", true, true},
		{"", "pigment { rgbf 0.9 } finish { reflection { 0.1, 0.9 fresnel } }", "ior 1.5 dispersion 1.05", true,
		 false},
		{"", "pigment { rgbf <1, 0.5, 0.2, 0.7> } finish { reflection { 0.3 metallic } conserve_energy }",
		 "ior 1.33 fade_distance 1 fade_power 2", true, false},
		{"", "pigment { rgbf <1, 1, 1, 0.9> } finish { reflection { 0.05, 0.6 falloff 2 } }", "ior 2.4", true, false},
		{"#version 3.7;", "pigment { rgbf <1, 1, 1, 0.9> } finish { reflection 0.2 }", "ior 1.5", true, true},
		{"#version 3.7;", "pigment { rgbf <0.9, 0.9, 1, 0.5> } finish { reflection { 0.1, 0.5 fresnel } }",
		 "ior 1.45 dispersion 1.02", true, false},
		/* a pigment or texture that varies over the surface: no part made once */
		{"", "pigment { checker rgbf 1 rgbf <1, 0.2, 0.2, 0.5> } finish { reflection 0.1 }", "ior 1.5", false,
		 false},
		{"", "checker texture { pigment { rgbf 1 } } texture { pigment { rgbf 0.5 } finish { reflection 0.3 } }",
		 "ior 1.5", false, false},
	};
	for (size_t i = 0; i < sizeof c / sizeof *c; i++) {
		bool plain = !c[i].plain, fixed = !c[i].fixed;
		long differ = -1, n = split_matches(c[i].version, c[i].texture, c[i].interior, &plain, &fixed, &differ);
		printf("# case %zu: %ld hits x bands, plain %d, fixed %d, %ld differ\n", i, n, plain, fixed, differ);
		CHECK(n > 5000);
		CHECK(plain == c[i].plain && fixed == c[i].fixed);
		CHECK(differ == 0);
	}
}

int main(void)
{
	RUN(t_opaque_patterns);
	RUN(t_clear_patterns);
	RUN(t_light_pass_parts);
	return test_done();
}
