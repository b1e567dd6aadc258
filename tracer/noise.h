/* SPDX-License-Identifier: MIT */
/* noise.h: POV-Ray 3.7's solid noise, reproduced value for value so that
 * the noise patterns (bozo, granite, marble, wood, …) land where POV-Ray
 * puts them: the lattice noise of generators 1 (original) and 2 (range
 * corrected, POV-Ray's default), Perlin's gradient noise (generator 3),
 * the vector noise that turbulence displaces points by, and fractal sums
 * of both (docs/design.md §10). Tables are built once, on first use, from
 * POV-Ray's own pseudo-random sequences; everything is read-only after. */
#ifndef ARVO_NOISE_H
#define ARVO_NOISE_H

#include "../common/vec.h"

/* Turbulence parameters: POV-Ray's defaults are octaves 6, omega 0.5,
 * lambda 2. */
struct turb_params {
	int octaves;   /* terms of the fractal sum */
	double omega;  /* amplitude factor per octave */
	double lambda; /* frequency factor per octave */
};

/* Scalar noise at p in [0,1], for generator gen (1, 2 or 3). */
double noise_at(struct vec3 p, int gen);
/* Vector noise at p (each component roughly in [-1,1]): POV-Ray's DNoise. */
struct vec3 noise_vec(struct vec3 p);
/* The fractal sum of noise_at over t's octaves (POV-Ray's Turbulence). */
double noise_turb(struct vec3 p, const struct turb_params *t, int gen);
/* The fractal sum of noise_vec (POV-Ray's DTurbulence). */
struct vec3 noise_dturb(struct vec3 p, const struct turb_params *t);
/* The k-th of POV-Ray's 32768 pattern random numbers in [0,1) (crackle's
 * cell points, cells): Mersenne Twister MT19937, default seed. */
double noise_rand(unsigned long k);
/* POV-Ray's sine of a full turn, sin(2πv), from its 1000-entry table. */
double noise_cycloidal(double v);
/* POV-Ray's triangle wave: 0 at whole v, 1 at halves. */
double noise_triangle(double v);
/* POV-Ray's hash of an integer lattice point into 0..4095. */
int noise_hash3(int x, int y, int z);
/* The n-th wave source (unit vector) and frequency of ripples and waves
 * (n < 256, POV-Ray's sequence; it uses the first number_of_waves). */
struct vec3 noise_wave_source(int n);
double noise_wave_freq(int n);

#endif
