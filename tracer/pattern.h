/* SPDX-License-Identifier: MIT */
/* pattern.h: POV-Ray's patterns, in pattern space, as POV-Ray 3.7 computes
 * them (so that a stock scene's textures land where POV-Ray puts them). */
#ifndef ARVO_PATTERN_H
#define ARVO_PATTERN_H

#include "scene.h"

/* The pattern-space point of world point p: the pigment's transform, then
 * its turbulence and warps in order (tracer/noisepat.c). */
struct vec3 pattern_point(const struct pigment *pg, struct vec3 p);
/* The value of a continuous pattern (gradient, PIG_PATTERN) at the
 * pattern-space point q, after frequency, phase and the wave: in [0,1],
 * for the colour_map. */
double pattern_value(const struct pigment *pg, struct vec3 q);
/* Frequency, phase and the wave applied to a raw value v. */
double pattern_wave(const struct pigment *pg, double v);
/* The raw value of a noise pattern (bozo … spiral2) at q (tracer/noisepat.c). */
double pattern_noise_raw(const struct pattern *pt, struct vec3 q);
/* For the patterns POV-Ray perturbs normals with directly (bumps, dents,
 * ripples, waves, wrinkles, quilted): adds the perturbation at
 * pattern-space point q to the pattern-space normal *n; false for the
 * others, which tilt by their slope (tracer/noisepat.c). */
bool pattern_normal_direct(const struct tnormal *t, struct vec3 q, struct vec3 *n);
/* POV-Ray's greyscale of a colour (pigment_pattern). */
double pattern_grey(struct colour c);
/* Which colour (0, 1, 2) of a block pattern (checker, hexagon, brick) q is in. */
int pattern_block(const struct pigment *pg, struct vec3 q);

/* (long)floor(x), inline (floor is a libm call without SSE4.1). Truncation
 * rounds towards zero, so one step down for x below it gives the floor;
 * x <= -2⁵² is a whole number already, and NaN, infinities and values past
 * the range of long convert as (long)floor(x) converts them. */
static inline long pattern_lfloor(double x)
{
	long i = (long)x;
	if (x > -0x1p52 && (double)i > x)
		i--;
	return i;
}

/* The checker's colour (0 or 1) at pattern-space point q: pattern_block's
 * for a checker, inline. */
static inline int pattern_checker(struct vec3 q)
{
	const double small = 1e-6;
	long s = pattern_lfloor(q.x + small) + pattern_lfloor(q.y + small) + pattern_lfloor(q.z + small);
	return (int)(s & 1);
}
/* The unit normal n at world point p perturbed as POV-Ray's normal { }
 * does: in pattern space, the pattern's values at the four corners of a
 * small tetrahedron around p, scaled by the bump size, tilt n. */
struct vec3 pattern_perturb(const struct tnormal *t, struct vec3 p, struct vec3 n);

#endif
