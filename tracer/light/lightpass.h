/* SPDX-License-Identifier: MIT */
/* lightpass.h: Arvo's light pass (docs/design.md §4). Rays leave every light
 * toward the bounds of the objects that reflect or refract (only where a
 * caustic can form), carry Φ = I·Ω/N each, recurse through Fresnel-weighted
 * reflection and refraction, and deposit their energy into the illumination
 * map of each diffuse surface they reach after at least one specular bounce. */
#ifndef ARVO_LIGHTPASS_H
#define ARVO_LIGHTPASS_H

#include <stdbool.h>

#include "../../common/diag.h"
#include "../bvh.h"
#include "illum.h"
#include "../material.h"
#include "../scene.h"

struct progress;

struct lp_opts {
	long rays;            /* light-ray budget per light (> 0) */
	int max_depth;        /* specular bounces followed (> 0) */
	double min_weight;    /* stop a branch below this fraction of its ray's energy */
	int threads;          /* worker threads (>= 1) */
	bool deposit_direct;  /* debug: deposit first-generation light too (eq. 1 checks) */
	bool discard_isolated;/* apply the isolated-sample rule (illum.h) */
	bool transmit_only;   /* debug: follow refraction only (the references'
	                         twice-transmitted light) */
	bool aim_all;         /* debug: aim at every object, not only specular ones
	                         (with deposit_direct: the eq. 1 consistency checks) */
	bool shafts;          /* method shaft: light shafts spread over their footprints */
	struct vec3 eye;      /* the camera, for the automatic finest cell of shafts: */
	double pixel_angle;   /* a pixel's angle (perspective; 0: unknown) */
	double pixel_width;   /* or its width (orthographic; 0: unknown) */
	double tolerance;     /* > 0: ignore rays; shoot rounds of 4× more rays (from 16384)
	                         until lp_difference between rounds is at most this */
	int channel;          /* -1: one pass for all channels; 0, 1, 2: only that channel,
	                         refracting with its dispersed index */
	struct progress *progress; /* reports the work items shot (common/progress.h;
	                         NULL: none) */
	bool spectral;        /* each ray at its own wavelength (spectrum.h), stratified
	                         over the spectrum, carrying f_c(λ) of the light's energy
	                         per channel (channel must be -1). A ray then carries one
	                         wavelength where a channel pass's ray carries a whole
	                         channel, so the automatic cell size asks for three times
	                         the rays per node: 3N spectral rays get the grid of a
	                         channel pass of N. Not with shafts: a shaft needs its
	                         corners on one path, which other wavelengths leave */
	uint64_t seed_key;    /* --seed, mixed into every ray's key (0: seed 0) */
};

struct lp_stats {
	long long rays;       /* light rays shot (primary) */
	long long segments;   /* ray segments traced (primary and secondary) */
	double emitted[3];    /* energy sent toward the specular objects (W) */
	double deposited[3];  /* energy held by the maps (W): the irradiance of light that
	                         landed, including what a partly specular surface sent on */
	/* Where the emitted energy went; the five add up to emitted: */
	double landed[3];     /* ended on a diffuse surface with a map (neither
	                         reflected nor transmitted there) */
	double direct[3];     /* ended on a diffuse surface before any specular bounce
	                         (direct light: the eye pass's shadow rays carry it) */
	double absorbed[3];   /* ended in a medium or on a surface that keeps no map */
	double escaped[3];    /* left the scene */
	double cut[3];        /* stopped by the depth and weight limits or photons { } */
	double removed[3];    /* energy the isolated-sample rule discarded (W) */
	long maps;            /* surfaces that received a map */
	size_t map_bytes;     /* memory held by the maps */
	const struct object *clipped; /* an unbounded specular object under a parallel
	                         light, whose beam covers only the scene's extent */
	double tol_estimate;  /* tolerance: the error estimate when it stopped */
	int tol_rounds;       /* rounds shot */
	long tol_rays;        /* rays per light of the last round (the maps kept) */
	const struct object *nomap; /* a surface light reached whose map has too many
	                         nodes (its illum_map is too fine): it gets no caustic */
};

struct lp_result;

/* Runs the light pass; NULL when the scene has no light or no specular object
 * (nothing to do). The maps are finished and ready for lp_lookup. */
struct lp_result *lp_run(const struct scene *s, const struct bvh *b, const struct mat_cache *mc,
                         const struct lp_opts *o, struct lp_stats *st);
/* Adds another pass's energies (for the per-channel passes) and refinishes. */
void lp_merge(struct lp_result *dst, const struct lp_result *src, bool discard_isolated);
#define LP_LEVELS 12/* map levels of a surface (shafts), cells 1, 2, 4, … × the finest */

/* The finished map of primitive o (its finest level), or NULL when no light
 * reached it. */
const struct illum_map *lp_map(const struct lp_result *r, const struct object *o);
/* The map of o at level 0 .. LP_LEVELS-1 (cell 2^level × the finest), or
 * NULL; lp_lookup sums the levels. */
const struct illum_map *lp_map_level(const struct lp_result *r, const struct object *o, int level);
/* Irradiance from the maps at a hit on o (W/m²); zero where there is none. */
void lp_lookup(const struct lp_result *r, const struct object *o, double u, double v, double out[3]);
/* Calls fn for each map (deterministic order). */
void lp_each_map(const struct lp_result *r, void (*fn)(void *ctx, const struct object *o, int level,
                 const struct illum_map *m), void *ctx);
/* The relative L1 difference between two passes' maps (a the reference,
 * e.g. the one with more rays): on each surface a lit, every level's
 * irradiance, each node's tent spread over bins of 1/48 of the
 * energy-weighted 5–95 % extent of its light (at least a node), summed over
 * channels; Σ|a − b| / Σ a. The tolerance's error estimate. */
double lp_difference(const struct lp_result *a, const struct lp_result *b);
/* The finest cell (world units) of r's maps made with a cell; 0 if none. */
double lp_finest_cell(const struct lp_result *r);
/* True when some interior has dispersion != 1 (three channel passes needed). */
bool lp_dispersive(const struct scene *s);
void lp_free(struct lp_result *r);
/* The hash a map file stores of what the light pass depends on: the scene
 * as --dump-scene prints it without its name, camera and source positions. */
uint64_t lp_scene_hash(const struct scene *s);
/* --save-maps: writes the passes' maps to path (temp file + rename). Returns
 * 0, FAIL_CREATE or FAIL_WRITE (reported to dg). */
int lp_save(struct lp_result *const *r, int npasses, const struct scene *s, const char *path, struct diag *dg);
/* --load-maps: reads maps saved for the same scene into out[0..2]; returns the
 * number of passes, or -FAIL_INPUT after reporting why: a missing file, not a
 * map file, an older format, another arvo version, another scene
 * (lp_scene_hash), or a damaged file. */
int lp_load(struct lp_result **out, const struct scene *s, const char *path, bool discard_isolated,
            struct diag *dg);

#endif
