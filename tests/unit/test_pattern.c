/* SPDX-License-Identifier: MIT */
/* test_pattern.c: POV-Ray's patterns (tracer/pattern.c) at points where
 * their values are known in closed form, the waves, and the plain
 * checker's inline path. */
#include <math.h>
#include <string.h>

#include "../../tracer/material.h"
#include "../../tracer/pattern.h"
#include "test.h"

/* g's pattern settings made its own, to be set (pigments share them). */
static struct pattern *own(struct pigment *g)
{
	static struct pattern ring[64];
	static unsigned next;
	struct pattern *p = &ring[next++ % 64];
	*p = *pig_pattern(g);
	g->pat = p;
	return p;
}

static struct pigment pig(enum pigment_kind k, enum pattern_kind p)
{
	struct pigment g = scene_default_texture().pigment;
	g.kind = k;
	own(&g)->pattern = p;
	return g;
}

static void t_continuous(void)
{
	struct pigment g = pig(PIG_PATTERN, PAT_ONION);
	CHECK_NEAR(pattern_value(&g, v3(0, 0.3, 0.4)), 0.5, 1e-12);
	CHECK_NEAR(pattern_value(&g, v3(0, 0, 1.75)), 1.75 - 1.00001, 1e-12); /* POV-Ray's modulus */
	own(&g)->pattern = PAT_RADIAL; /* 0.25 at -z (less POV-Ray's 1.00001), 0.5 at -x, 1 at +x */
	CHECK_NEAR(pattern_value(&g, v3(0, 0, -1)), 1.25 - 1.00001, 1e-12);
	CHECK_NEAR(pattern_value(&g, v3(-1, 0, 0)), 0.5, 1e-12);
	CHECK_NEAR(pattern_value(&g, v3(1, 0, 0)), 1.0, 1e-12);
	CHECK_NEAR(pattern_value(&g, v3(0, 5, 0)), 0.25, 1e-12); /* on the axis */
	own(&g)->pattern = PAT_SPHERICAL;
	CHECK_NEAR(pattern_value(&g, v3(0.6, 0, 0)), 0.4, 1e-12);
	CHECK_NEAR(pattern_value(&g, v3(2, 0, 0)), 0, 1e-12);
	own(&g)->pattern = PAT_CYLINDRICAL;
	CHECK_NEAR(pattern_value(&g, v3(0.3, 9, 0.4)), 0.5, 1e-12);
	own(&g)->pattern = PAT_BOXED;
	CHECK_NEAR(pattern_value(&g, v3(0.2, -0.7, 0.1)), 0.3, 1e-12);
	own(&g)->pattern = PAT_PLANAR;
	CHECK_NEAR(pattern_value(&g, v3(5, -0.25, 5)), 0.75, 1e-12);
	own(&g)->pattern = PAT_LEOPARD;
	CHECK_NEAR(pattern_value(&g, v3(M_PI / 2, M_PI / 2, M_PI / 2)), 1, 1e-12);
}

static void t_waves(void)
{
	struct pigment g = scene_default_texture().pigment;
	g.kind = PIG_GRADIENT;
	own(&g)->axis = v3(1, 0, 0);
	CHECK_NEAR(pattern_value(&g, v3(0.25, 0, 0)), 0.25, 1e-12);
	CHECK_NEAR(pattern_value(&g, v3(-0.25, 0, 0)), 0.75, 1e-12); /* negative wraps */
	own(&g)->frequency = 2, own(&g)->phase = 0.1;
	CHECK_NEAR(pattern_value(&g, v3(0.2, 0, 0)), 0.5, 1e-12);
	own(&g)->frequency = 1, own(&g)->phase = 0;
	own(&g)->wave = WAVE_TRIANGLE;
	CHECK_NEAR(pattern_value(&g, v3(0.25, 0, 0)), 0.5, 1e-12);
	CHECK_NEAR(pattern_value(&g, v3(0.75, 0, 0)), 0.5, 1e-12);
	own(&g)->wave = WAVE_SINE;
	CHECK_NEAR(pattern_value(&g, v3(0.25, 0, 0)), 1, 1e-12);
	own(&g)->wave = WAVE_SCALLOP;
	CHECK_NEAR(pattern_value(&g, v3(0.25, 0, 0)), sqrt(0.5), 1e-12);
	own(&g)->wave = WAVE_CUBIC;
	CHECK_NEAR(pattern_value(&g, v3(0.25, 0, 0)), 0.15625, 1e-12);
	own(&g)->wave = WAVE_POLY, own(&g)->exponent = 3;
	CHECK_NEAR(pattern_value(&g, v3(0.5, 0, 0)), 0.125, 1e-12);
}

static void t_blocks(void)
{
	struct pigment g = pig(PIG_CHECKER, PAT_RADIAL);
	CHECK(pattern_block(&g, v3(0.5, 0.5, 0.5)) == 0);
	CHECK(pattern_block(&g, v3(1.5, 0.5, 0.5)) == 1);
	CHECK(pattern_block(&g, v3(-0.5, 0.5, 0.5)) == 1);
	g.kind = PIG_HEXAGON; /* cells of 0.5 × √3/2: rows of colours 0 1 1 2 2 0 */
	CHECK(pattern_block(&g, v3(0.1, 0, 0.1)) == 0);
	CHECK(pattern_block(&g, v3(0.1, 0, 1.0)) == 1);
	CHECK(pattern_block(&g, v3(0.1, 0, 2.7)) == 2);
	CHECK(pattern_block(&g, v3(1.1, 0, 0.1)) == 2);
	CHECK(pattern_block(&g, v3(-1.1, 0, 0.1)) == 2); /* mirrored in x */
	g.kind = PIG_BRICK; /* <8, 3, 4.5>, mortar 0.5 */
	CHECK(pattern_block(&g, v3(0.2, 0.1, 0.2)) == 1);
	CHECK(pattern_block(&g, v3(0.2, -0.3, 0.2)) == 0); /* the bed joint */
	CHECK(pattern_block(&g, v3(-0.3, 1, 2)) == 0);      /* a head joint (x) */
	CHECK(pattern_block(&g, v3(-0.3, 4, 2)) == 1);      /* next course: offset by half a brick */
}

/* A linear pattern tilts the normal by −5·amount·0.02·(4/3) times its
 * slope: gradient x with bump size 0.75 on a floor gives (−0.1, 1, 0). */
static void t_perturb(void)
{
	struct tnormal t = {.pat = scene_default_texture().pigment, .amount = 0.75};
	t.pat.kind = PIG_GRADIENT;
	own(&t.pat)->axis = v3(1, 0, 0);
	struct vec3 n = pattern_perturb(&t, v3(0.4, 0, 0.3), v3(0, 1, 0));
	CHECK_NEAR(n.x / n.y, -0.1, 1e-7); /* POV-Ray's corners have 9 digits */
	CHECK_NEAR(n.z, 0, 1e-12);
	CHECK_NEAR(v_len(n), 1, 1e-12);
	t.pat.kind = PIG_PATTERN; /* a bump size of 0 leaves n as it is */
	own(&t.pat)->pattern = PAT_SPHERICAL;
	t.amount = 0;
	n = pattern_perturb(&t, v3(0, 0.5, 0), v3(0, 1, 0));
	CHECK_NEAR(n.y, 1, 1e-12);
}

/* pattern_lfloor is (long)floor: on whole numbers, either side of them by an
 * ulp, ±0, tiny values, at and past 2⁵², and on a sweep of values. A plain
 * checker read in place (mat_pigment) gives the colour of pigment_at's
 * steps: pattern_point, pattern_block, pig_colour, near cell edges too. */
static void t_checker_floor(void)
{
	const double edge[] = {0.0, -0.0, 0.5, -0.5, 1, -1, 3, -3, 1e-300, -1e-300, 0x1p52, -0x1p52,
	                       0x1p52 + 1, -0x1p52 - 1, 0x1p62, -0x1p62, 4503599627370495.5,
	                       -4503599627370495.5, 1e15 + 0.25, -1e15 - 0.25};
	int bad = 0, n = 0;
	for (int i = 0; i < (int)(sizeof edge / sizeof edge[0]); i++)
		for (int s = -1; s <= 1; s++) {
			double x = s < 0 ? nextafter(edge[i], -INFINITY) : s > 0 ? nextafter(edge[i], INFINITY) : edge[i];
			bad += pattern_lfloor(x) != (long)floor(x), n++;
		}
	for (int i = 0; i < 20000; i++) {
		double x = (i - 10000) * 0.37 + (i % 7) * 1e-7;
		bad += pattern_lfloor(x) != (long)floor(x), n++;
	}
	CHECK(bad == 0 && n == 20060);
	struct pigment g = pig(PIG_CHECKER, PAT_RADIAL);
	g.c[0] = c_rgb(1, 0.5, 0.25);
	own(&g)->more[0] = c_rgb(0.2, 0.3, 0.4);
	int differ = 0, ones = 0;
	for (int i = 0; i < 4000; i++) {
		double a = (i % 41 - 20) * 0.5, b = (i % 23 - 11) * 0.25;
		struct vec3 p = v3(a - 1e-6 + (i % 3 - 1) * 1e-12, b * 0.7, (i % 5 - 2) * (1 - 1e-6));
		struct colour want = pig_colour(&g, pattern_block(&g, pattern_point(&g, p)));
		struct colour got = mat_pigment(NULL, &g, p);
		differ += memcmp(&want, &got, sizeof want) != 0;
		ones += got.r == 0.2;
	}
	CHECK(differ == 0);
	CHECK(ones > 1000 && ones < 3000);
}

int main(void)
{
	RUN(t_continuous);
	RUN(t_waves);
	RUN(t_blocks);
	RUN(t_checker_floor);
	RUN(t_perturb);
	return test_done();
}
