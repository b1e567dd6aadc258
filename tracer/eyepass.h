/* SPDX-License-Identifier: MIT */
/* eyepass.h: the eye pass (docs/design.md §5): Whitted recursion from the camera.
 *
 * One call shades one pixel: its camera samples are traced to the visible
 * surface, lit by shadow rays to every light (point, spot, parallel, area),
 * and followed through mirror reflection and refraction up to
 * max_trace_level or until a branch's weight drops below adc_bailout. Beside
 * the beauty, the first visible point gives the pixel's AOVs: irradiance
 * from shadow rays (before albedo), albedo, normal and distance.
 *
 * Light models (docs/design.md §3): by default a point light's colour is its
 * intensity I (W/sr) and a diffuse surface of albedo ρ = pigment × diffuse
 * has radiance ρ·E/π with E = I·cosθ/d². A parallel light's colour is the
 * irradiance it gives a surface facing it (W/m²). When the scene declared
 * #version 3.x (legacy_lights), POV-Ray's model applies: no falloff unless
 * fade_distance/fade_power, and diffuse = ρ·I·cosθ^brilliance with no 1/π.
 * Shadow rays are blocked by every object without no_shadow, transparent or
 * not: light through glass is the light pass's job (no transparent-shadow
 * hack). */
#ifndef ARVO_EYEPASS_H
#define ARVO_EYEPASS_H

#include "bvh.h"
#include "camera.h"
#include "material.h"
#include "light/lightpass.h"
#include "scene.h"

/* What every render thread shares, read-only. */
struct eye_ctx {
	const struct scene *scene;     /* the scene being rendered */
	const struct bvh *bvh;         /* its objects */
	const struct mat_cache *mats;  /* image_map pixels */
	struct cam cam;                /* the prepared camera */
	int w, h;                      /* image size */
	int spp;                       /* camera samples per pixel */
	struct lp_result *const *caustics; /* light-pass results (one, or one per channel) */
	int ncaustics;                 /* entries in caustics (0: no light pass) */
	bool beauty_only;              /* only R G B are kept: the AOV layers are
	                                  not computed (eye_px holds R G B alone:
	                                  the rest is left unset) */
	bool see_through;              /* some object is a straight transmitter: shadow
	                                  rays look through such objects (surface.h) */
	bool spectral;                 /* passes spectral: dispersive glass splits a path
	                                  into wavelengths, not into channels */
	uint64_t seed_key;             /* --seed, mixed into every pixel's key (0: seed 0) */
	bool simd16;                   /* the CPU has AVX-512: a packet's camera hits
	                                  get their directions at once (eyepass.c) */
};

/* One pixel's result. The beauty splits into layers the way Cycles' colour ×
 * light passes do: per camera sample,
 *   rgb = albedo/π · (direct + caustic) + specular + emission
 * exactly (to float rounding; with several samples per pixel albedo is the
 * nearest sample's, so the sum holds only where they all saw one surface).
 * specular holds highlights, reflected and refracted radiance, and whatever
 * of the diffuse radiance is not albedo/π · irradiance (brilliance ≠ 1,
 * the legacy light model's missing 1/π); emission holds ambient, emission,
 * and the background where the camera ray escaped. */
struct eye_px {
	float rgb[3];     /* beauty radiance: the mean of the samples */
	float direct[3];  /* irradiance from shadow rays at the first hit, W/m² (mean) */
	float caustic[3]; /* irradiance from the illumination maps at the first hit, W/m² (mean) */
	float specular[3];/* highlights, reflected and refracted radiance (mean) */
	float emission[3];/* ambient, emission and background radiance (mean) */
	float albedo[3];  /* pigment × diffuse × opacity at the nearest sample's hit */
	float n[3];       /* world normal there (facing the camera; 0 on a miss) */
	float p[3];       /* world position there (0 on a miss) */
	float z;          /* distance from the camera to the nearest hit (+inf: none) */
	float a;          /* coverage: the share of samples that hit an object */
};

/* Sets up ctx for scene s rendered at w×h with spp samples per pixel. */
void eye_setup(struct eye_ctx *ctx, const struct scene *s, const struct bvh *b,
               const struct mat_cache *m, int w, int h, int spp);
/* Shades pixel (x, y) (row 0 at the top) into *out; adds the rays it traced
 * to *rays. Depends only on ctx and (x, y): any thread gets the same bits. */
void eye_pixel(const struct eye_ctx *ctx, int x, int y, struct eye_px *out, long long *rays);
/* The same for n <= BVH_PACKET pixels (x[i], y[i]), neighbours best: their first
 * camera rays are traced together as one packet (bvh_intersect_packet), then
 * each pixel is shaded as eye_pixel shades it, to the same bits. */
void eye_pixels(const struct eye_ctx *ctx, int n, const int *x, const int *y, struct eye_px *out,
                long long *rays);

#endif
