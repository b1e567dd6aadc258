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

#endif
