/* SPDX-License-Identifier: MIT */
/* render.h: the render driver (docs/design.md §1): builds the BVH, loads the
 * images, runs the passes over a thread pool and fills the framebuffer.
 *
 * Layers written (struct eye_px says what each holds): R G B (beauty), A
 * (coverage), direct.R/G/B and caustic.R/G/B (irradiance, W/m²),
 * specular.R/G/B and emission.R/G/B (radiance), albedo.R/G/B, N.X/Y/Z,
 * P.X/Y/Z (world space) and Z (distance to the nearest hit, +inf where
 * nothing was hit). The result is bit-identical for any thread count and
 * for any region: every pixel depends only on (pixel, sample) keyed random
 * numbers, the pixel numbered in the full frame. */
#ifndef ARVO_RENDER_H
#define ARVO_RENDER_H

#include <stdbool.h>
#include <stdint.h>

#include "../common/diag.h"
#include "output/framebuffer.h"
#include "scene.h"

struct render_opts {
	int width, height;       /* image size in pixels */
	int spp;                 /* camera samples per pixel (>= 1) */
	int threads;             /* worker threads (0: one per online CPU) */
	int quiet;               /* no progress report (common/progress.h) */
	const char *ocio_config; /* config for image_map colour conversion, or NULL */
	long rays;               /* light-pass rays per light: > 0 this many; 0 the scene's
	                            (else 1e6); < 0 no light pass */
	const char *dump_maps;   /* write every illumination map as an EXR here, or NULL */
	const char *save_maps;   /* save the light pass's maps to this file, or NULL */
	const char *load_maps;   /* load the maps from this file instead of the light pass */
	int method;              /* 0: the scene's method, else enum illum_method + 1 */
	double tolerance;        /* > 0: the light pass's accuracy target (else the scene's) */
	int passes;              /* 0: the scene's passes, else enum illum_passes + 1 */
	int region[4];           /* x0 x1 y0 y1: render only columns [x0, x1) and rows
	                            [y0, y1) (the framebuffer is that region of the
	                            frame); x1 == 0: the whole frame */
	long seed;               /* --seed: 0, or another set of random numbers */
	bool beauty_only;        /* the outputs read R G B alone (PNG): the other
	                            layers are neither stored nor allocated */
};

/* The key a seed mixes into every random stream (0 for seed 0). */
uint64_t render_seed_key(long seed);

struct render_stats {
	long long rays;     /* camera, reflected, refracted and shadow rays */
	double t_setup;     /* seconds building the BVH and loading images */
	double t_light;     /* seconds in the light pass */
	long long light_rays; /* light rays shot (all passes) */
	long long light_segments; /* ray segments traced by the light pass */
	long maps;          /* surfaces with an illumination map */
	size_t map_bytes;   /* memory held by the maps */
	/* light-pass energy (W, summed over channels and passes): emitted toward
	 * the specular objects = deposited + direct + absorbed + escaped + cut
	 * (lightpass.h); held is what the maps hold */
	double e_emitted, e_deposited, e_direct, e_absorbed, e_escaped, e_cut, e_held;
	double finest_cell;   /* the finest map cell reached (world units; 0: none) */
	double tolerance;     /* the accuracy asked (0: none) */
	double tol_estimate;  /* the light pass's error estimate when it stopped */
	int tol_rounds;       /* rounds of rays it took */
	long tol_rays;        /* rays per light of the last round */
	double t_eye;       /* seconds in the eye pass */
	double cpu_eye;     /* CPU seconds of every thread in the eye pass */
	long peak_rss_kb;   /* peak resident memory (getrusage) */
	int threads;        /* threads used */
};

/* Renders s into a new framebuffer (*out, free with fb_free). stats may be
 * NULL. Errors and warnings go to dg. Returns 0, or an enum fail status:
 * FAIL_INPUT (an image_map or --load-maps file missing, broken or foreign;
 * an OCIO config that cannot be loaded), FAIL_CREATE or FAIL_WRITE
 * (--save-maps, --dump-maps). */
int render(const struct scene *s, const struct render_opts *o, struct diag *dg, struct framebuffer **out,
           struct render_stats *stats);
/* Prints the stats as --stats shows them. */
void render_print_stats(FILE *f, const struct render_stats *st);

#endif
