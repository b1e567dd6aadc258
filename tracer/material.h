/* SPDX-License-Identifier: MIT */
/* material.h: pigment evaluation (solid, checker, gradient with colour_map,
 * image_map) in pattern space, and the texture/interior an object shades with.
 *
 * Images for image_map are loaded once, before rendering, into a cache that
 * the render threads then only read. */
#ifndef ARVO_MATERIAL_H
#define ARVO_MATERIAL_H

#include "../common/vec.h"
#include "output/imageio.h"
#include "scene.h"

/* Loaded image_map files, keyed by their resolved path. */
struct mat_cache {
	const char **paths; /* resolved path of each image */
	struct img *imgs;   /* the pixels, linear */
	int n;              /* images loaded */
	int cap;            /* allocated entries */
};

/* Loads every image_map of the scene's objects into c (zeroed by the caller).
 * Returns 0, or FAIL_INPUT after reporting, at the image_map, why a file
 * cannot be read. */
int mat_cache_load(struct mat_cache *c, const struct scene *s, const char *ocio_config, struct diag *dg);
void mat_cache_free(struct mat_cache *c);

/* The texture and interior an object shades with (scene defaults if unset). */
const struct texture *mat_texture(const struct object *o);
const struct interior *mat_interior(const struct object *o);

/* A texture_map texture t at world point p: the one or two textures of
 * its map there (out) and their weights (w), which sum to 1; returns how
 * many. The textures may be texture maps themselves. */
int mat_texture_pick(const struct mat_cache *c, const struct texture *t, struct vec3 p,
                     const struct texture *out[2], double w[2]);
/* The texture that weighs most at p, down through nested texture maps
 * (t itself when it has no map): what the light pass sees there. */
const struct texture *mat_texture_leaf(const struct mat_cache *c, const struct texture *t, struct vec3 p);

/* The pigment's colour (with filter and transmit) at world point p (c NULL:
 * image maps are magenta). */
struct colour mat_pigment(const struct mat_cache *c, const struct pigment *pg, struct vec3 p);

#endif
