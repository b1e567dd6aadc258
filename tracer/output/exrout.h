/* SPDX-License-Identifier: MIT */
/* exrout.h: OpenEXR output and input through the OpenEXR C API (OpenEXRCore).
 *
 * Errors: functions returning int return 0 on success, else an enum fail
 * status (diag.h) after reporting the reason ("cannot write 'a.exr': ...")
 * to the diag they were given. They never exit. Names avoid the exr_
 * prefix, which OpenEXRCore owns. */
#ifndef ARVO_EXROUT_H
#define ARVO_EXROUT_H

#include <stddef.h>

#include "../../common/diag.h"
#include "framebuffer.h"

#ifndef ARVO_VERSION
#define ARVO_VERSION "0.1.0" /* the Makefile may pass -DARVO_VERSION="..." */
#endif

enum out_exr_compression {
	OUT_EXR_ZIP = 0, /* zlib, 16 scanlines per block (the default) */
	OUT_EXR_NONE,    /* uncompressed */
	OUT_EXR_ZIPS,    /* zlib, one scanline per block */
	OUT_EXR_PIZ,     /* wavelet, 32 scanlines per block */
	OUT_EXR_RLE      /* run-length */
};

#define OUT_META_MAX 16 /* string attributes in a struct out_exr_meta */

/* Header attributes describing how an image was made. Matrices are for row
 * vectors (p' = p·M), row-major, as OpenEXR's m44f and Imath's M44f. */
struct out_exr_meta {
	int has_camera;            /* the three matrices are set */
	float world_to_camera[16]; /* "worldToCamera" (OpenEXR standard attribute) */
	float world_to_ndc[16];    /* "worldToNDC" (OpenEXR standard attribute) */
	float camera_to_world[16]; /* "arvo:cameraToWorld" (worldToCamera's inverse) */
	int n;                     /* string attributes in key/val */
	char key[OUT_META_MAX][64];
	char val[OUT_META_MAX][256];
};

struct out_exr_opts {
	int half;                             /* 1: 16-bit half pixels ("Z" stays float); 0: float */
	enum out_exr_compression compression; /* OUT_EXR_ZIP when zero-initialised */
	const char *scene;                    /* "arvo:scene" string attribute, or NULL for none */
	const struct out_exr_meta *meta;      /* more attributes, or NULL */
	int threads;                          /* threads compressing (0: the machine's) */
};

/* What out_exr_read found in the header besides the pixels. */
struct out_exr_info {
	int has_chroma;   /* 1 when a chromaticities attribute was present */
	float chroma[8];  /* red x,y  green x,y  blue x,y  white x,y */
	int half;         /* 1 when every channel is stored as half */
	int half_but_z;   /* 1 when every channel but Z is (as --half writes them) */
	enum out_exr_compression compression; /* the file's (OUT_EXR_ZIP when not one of ours) */
	char software[128]; /* the "software" attribute, or "" */
	char scene[256];  /* the "arvo:scene" attribute, or "" */
	struct out_exr_meta meta; /* the matrices, and every string attribute named "arvo:…" */
};

/* Adds the string attribute key = printf(fmt, ...) to m (ignored when full). */
void out_meta_add(struct out_exr_meta *m, const char *key, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* The zlib level of ZIP and ZIPS files (exrout.c). */
#define EXR_ZIP_LEVEL 1

/* Parses "none" "zip" "zips" "piz" "rle" into *out; returns 0, or -1 when the
 * name is unknown (out untouched). */
int out_exr_compression_parse(const char *name, enum out_exr_compression *out);

/* Writes every plane of fb as one channel of a scanline EXR at path (with
 * Rec.709/D65 chromaticities and software "arvo <version>"). The data window
 * is fb's region of the frame (x0, y0, w, h), the display window the whole
 * frame (full_w × full_h). opts NULL means float + zip. Writes to
 * "<path>.tmp.XXXXXX" and renames it into place only on success; on failure
 * the temp file is removed and path is untouched. Returns 0, FAIL_CREATE (no
 * temp file) or FAIL_WRITE. */
int out_exr_write(const struct framebuffer *fb, const char *path, const struct out_exr_opts *opts,
                  struct diag *dg);

/* Reads a single-part scanline EXR: every channel becomes a float plane of a
 * new framebuffer (*out, free with fb_free) named as in the file. info may be
 * NULL. Pixel (0,0) is the data window's corner; fb->x0, y0 say where that
 * is in the display window (whose size is full_w × full_h; a display window
 * not at the origin moves x0, y0 by its corner). Returns 0, or FAIL_INPUT
 * (missing, truncated, foreign or unsupported). */
int out_exr_read(const char *path, struct framebuffer **out, struct out_exr_info *info, struct diag *dg);

#endif
