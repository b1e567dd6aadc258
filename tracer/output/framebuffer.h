/* SPDX-License-Identifier: MIT */
/* framebuffer.h: named float planes of one image (the renderer's film).
 *
 * A plane is w*h floats, row-major, row 0 at the top. Plane names follow the
 * EXR channel convention: "R" "G" "B" (beauty), "direct.R", "albedo.G",
 * "caustic.B", "N.X", "Z", ... Planes are created on first use and zeroed.
 * Iteration (fb_count/fb_name/fb_data) is in a stable order that does not
 * depend on the order of creation: beauty R G B A first, then the layers in
 * alphabetical order, each layer's channels as R G B A X Y Z then others. */
#ifndef ARVO_FRAMEBUFFER_H
#define ARVO_FRAMEBUFFER_H

struct fb_plane {
	char *name;  /* channel name, e.g. "caustic.R" */
	float *data; /* w*h floats, row-major, top row first */
};

struct framebuffer {
	int w, h;                /* size in pixels (the EXR data window) */
	int x0, y0;              /* where pixel (0,0) sits in the full frame (0, 0) */
	int full_w, full_h;      /* the full frame (the EXR display window): w, h
	                            unless this is a region of it (--region, --tile) */
	int count;               /* planes in use */
	int cap;                 /* allocated entries of planes[] */
	struct fb_plane *planes; /* sorted in the stable iteration order */
	float *block;            /* fb_reserve's planes, one after another (NULL: none) */
	int spare;               /* planes of block not given out yet */
	int given;               /* planes given out from block */
};

/* A framebuffer with no planes, the whole of a w×h frame; w and h must be
 * >= 1. Never returns NULL. */
struct framebuffer *fb_new(int w, int h);
/* Makes room for n more planes at once, zeroed, in one block backed by
 * huge pages where the system gives them (common/arena.h): the next n
 * planes fb_plane creates take it. A megapixel image's 26 planes in 4 KiB
 * pages took 0.36 s of page faults to set up. Call it once, before those
 * planes exist. */
void fb_reserve(struct framebuffer *fb, int n);
/* The plane called name, created (zeroed) if absent. The pointer stays valid
 * until fb_free, even when more planes are added. */
float *fb_plane(struct framebuffer *fb, const char *name);
/* The plane called name, or NULL when there is none (never creates). */
float *fb_find(const struct framebuffer *fb, const char *name);
/* Number of planes, and the i-th name/data in the stable order. */
int fb_count(const struct framebuffer *fb);
const char *fb_name(const struct framebuffer *fb, int i);
float *fb_data(const struct framebuffer *fb, int i);
void fb_free(struct framebuffer *fb);

#endif
