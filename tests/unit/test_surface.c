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
#include "../../tracer/surface.h"
#include "test.h"

/* surf_any_straight of a scene of one plane under a light with the given
 * texture and interior (SDL text); -1 when it does not evaluate. */
static int straight_of(const char *texture, const char *interior)
{
	char path[64];
	snprintf(path, sizeof path, "/tmp/arvo-test-surface-%ld.scn", (long)getpid());
	FILE *f = fopen(path, "w");
	if (!f)
		return -1;
	fprintf(f, "camera { location <0, 1, -4> look_at 0 }\nlight_source { <0, 5, -5>, rgb 1 }\n"
	           "plane { y, 0 texture { %s } interior { %s } }\n", texture, interior);
	fclose(f);
	struct eval_options eo;
	eval_default_options(&eo);
	struct diag dg;
	diag_init(&dg, stdout);
	struct scene s;
	int rc = eval_scene(path, &eo, &dg, &s);
	remove(path);
	if (rc != 0)
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

int main(void)
{
	RUN(t_opaque_patterns);
	RUN(t_clear_patterns);
	return test_done();
}
