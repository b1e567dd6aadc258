/* SPDX-License-Identifier: MIT */
/* pattern.h: POV-Ray's patterns, in pattern space, as POV-Ray 3.7 computes
 * them (so that a stock scene's textures land where POV-Ray puts them). */
#ifndef ARVO_PATTERN_H
#define ARVO_PATTERN_H

#include "scene.h"

/* The value of a continuous pattern (gradient, PIG_PATTERN) at q, after
 * frequency, phase and the wave: in [0,1], for the colour_map. */
double pattern_value(const struct pigment *pg, struct vec3 q);
/* Which colour (0, 1, 2) of a block pattern (checker, hexagon, brick) q is in. */
int pattern_block(const struct pigment *pg, struct vec3 q);
/* The unit normal n at world point p perturbed as POV-Ray's normal { }
 * does: in pattern space, the pattern's values at the four corners of a
 * small tetrahedron around p, scaled by the bump size, tilt n. */
struct vec3 pattern_perturb(const struct tnormal *t, struct vec3 p, struct vec3 n);

#endif
