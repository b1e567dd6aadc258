/* SPDX-License-Identifier: MIT */
/* imageio.h: reading images for image_map, as linear floats.
 *
 * PNG (8/16-bit; gray, gray+alpha, RGB, RGBA, palette) is decoded with
 * libpng and its colour converted from the config's "sRGB - Texture" space
 * to the scene_linear working space through OCIO. EXR (via out_exr_read) is
 * taken as already scene-linear: R,G,B[,A], or Y replicated to grey, or the
 * first channel. Alpha is never colour-converted. Errors follow exrout.h. */
#ifndef ARVO_IMAGEIO_H
#define ARVO_IMAGEIO_H

#include <stdbool.h>

#include "../../common/diag.h"

#define IMG_TEXTURE_SPACE "sRGB - Texture" /* what 8/16-bit PNGs are taken to be */

struct img {
	int w, h;  /* size in pixels */
	int nch;   /* 3 (RGB) or 4 (RGBA, straight alpha) */
	float *px; /* w*h*nch floats, row-major, top row first */
	int depth; /* PNG: 8 or 16 bits per sample as decoded; EXR: 32 */
	bool indexed; /* the samples are a palette PNG's indices (img_opts.indices) */
};

struct img_opts {
	const char *ocio_config; /* explicit config path, or NULL ($OCIO, then shipped) */
	const char *colorspace;  /* source space override; NULL: IMG_TEXTURE_SPACE for PNG, none for EXR */
	int raw;                 /* 1: no colour conversion at all (data maps: bump, normal) */
	int indices;             /* 1: a palette PNG gives its indices, index/255 in R, G and B
	                          * (height_field); implies raw for such a file */
};

/* Loads path (format from its magic bytes) into *out; opts may be NULL.
 * Returns 0, or FAIL_INPUT (missing, empty, truncated, corrupt or foreign
 * file; an OCIO config that cannot be loaded) after reporting at `at`,
 * naming the file `name` (NULL: path). On failure *out is zeroed. Free
 * with img_free. */
int img_load(const char *path, const struct img_opts *opts, struct img *out, struct diag *dg, struct srcloc at,
             const char *name);
void img_free(struct img *im);

#endif
