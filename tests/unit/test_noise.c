/* SPDX-License-Identifier: MIT */
/* test_noise.c: POV-Ray's noise (tracer/noise.c) and noise patterns
 * (tracer/noisepat.c) at fixed points, against values read from POV-Ray
 * 3.7's own renders: a 16x16 plane, orthographic, 16-bit PNG with file gamma
 * 1, pigment { P color_map {[0 rgb 0][1 rgb 1]} scale 0.125 translate
 * <0,0,-0.37> } with finish { ambient 1 diffuse 0 }, so pixel (i, j) shows
 * the pattern at ((i+0.5)/2, 8 - (j+0.5)/2, 2.96). The expected values are
 * POV-Ray's 16-bit pixels over 65535; the tolerance is one 16-bit step. */
#include <math.h>

#include "../../tracer/noise.h"
#include "../../tracer/pattern.h"
#include "test.h"

#define TOL (1.0 / 65535)

/* Pixel k (row-major) of the 16x16 reference renders. */
static struct vec3 at(int k)
{
	int i = k % 16, j = k / 16;
	return v3((i + 0.5) / 2, 8 - (j + 0.5) / 2, 2.96);
}

static const int pix[5] = {0, 37, 119, 200, 255};

/* POV-Ray's bozo pixels for noise_generator 1, 2, 3 */
static const double bozo[3][5] = {
	{20790, 8009, 49831, 15879, 32942},
	{27918, 21658, 42144, 25513, 33871},
	{38236, 44185, 41617, 45185, 25046},
};

static void t_noise_generators(void)
{
	for (int g = 0; g < 3; g++)
		for (int k = 0; k < 5; k++)
			CHECK_NEAR(noise_at(at(pix[k]), g + 1), bozo[g][k] / 65535, TOL);
}

static struct pigment pattern_pig(struct pattern *pt, enum pattern_kind kind)
{
	struct pigment g = scene_default_texture().pigment;
	*pt = *pig_pattern(&g);
	pt->pattern = kind;
	pt->noise_gen = 2;
	g.kind = PIG_PATTERN;
	g.pat = pt;
	return g;
}

/* crackle: MT19937's numbers place the cell points; form <-1,1,0> */
static void t_crackle(void)
{
	static const double want[5] = {10798, 12237, 7275, 8414, 7611};
	struct pattern pt;
	struct pigment g = pattern_pig(&pt, PAT_CRACKLE);
	for (int k = 0; k < 5; k++)
		CHECK_NEAR(pattern_value(&g, pattern_point(&g, at(pix[k]))), want[k] / 65535, TOL);
}

/* marble turbulence 0.6 ramp_wave frequency 0.25: x plus the turbulence
 * sum (octaves 6, omega 0.5, lambda 2), a quarter of it */
static void t_turbulence(void)
{
	static const double want[5] = {10883, 51712, 8771, 13386, 6511};
	struct pattern pt;
	struct pigment g = pattern_pig(&pt, PAT_MARBLE);
	struct warp w = {.kind = WARP_TURB, .classic = true, .turb = {0.6, 0.6, 0.6}, .octaves = 6, .omega = 0.5,
	                 .lambda = 2};
	pt.warps = &w;
	pt.nwarps = 1;
	pt.frequency = 0.25;
	for (int k = 0; k < 5; k++)
		CHECK_NEAR(pattern_value(&g, pattern_point(&g, at(pix[k]))), want[k] / 65535, TOL);
}

/* granite frequency 0.5: six octaves of folded noise */
static void t_granite(void)
{
	static const double want[5] = {14219, 18437, 15512, 18433, 21391};
	struct pattern pt;
	struct pigment g = pattern_pig(&pt, PAT_GRANITE);
	pt.frequency = 0.5;
	for (int k = 0; k < 5; k++)
		CHECK_NEAR(pattern_value(&g, pattern_point(&g, at(pix[k]))), want[k] / 65535, TOL);
}

/* The tables' invariants: the sine table, the triangle wave, the hash. */
static void t_helpers(void)
{
	CHECK_NEAR(noise_cycloidal(0.25), 1, 1e-12);
	CHECK_NEAR(noise_cycloidal(-0.25), -1, 1e-12);
	CHECK_NEAR(noise_cycloidal(1.1), sin(0.2 * M_PI), 1e-12);
	CHECK_NEAR(noise_triangle(0.25), 0.5, 1e-12);
	CHECK_NEAR(noise_triangle(-0.25), 0.5, 1e-12);
	CHECK_NEAR(noise_triangle(2.5), 1, 1e-12);
	CHECK(noise_hash3(0, 0, 0) >= 0 && noise_hash3(0, 0, 0) < 4096);
	CHECK(noise_hash3(1, 2, 3) == noise_hash3(1 + 4096, 2 - 4096, 3 + 8192)); /* 12-bit lattice */
	for (int k = 0; k < 100; k++)
		CHECK(noise_rand((unsigned long)k * 97) >= 0 && noise_rand((unsigned long)k * 97) < 1);
	CHECK_NEAR(v_len(noise_wave_source(3)), 1, 1e-12);
}

int main(void)
{
	RUN(t_noise_generators);
	RUN(t_crackle);
	RUN(t_turbulence);
	RUN(t_granite);
	RUN(t_helpers);
	return test_done();
}
