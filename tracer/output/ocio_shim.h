/* SPDX-License-Identifier: MIT */
/* ocio_shim.h: a small C interface over OpenColorIO 2.1 (C++ only).
 *
 * ocio_shim.cpp is the only C++ file of arvo. Every entry point catches all
 * exceptions; failures return NULL or -1 and write a message into err
 * (errlen bytes, always NUL-terminated when errlen > 0). */
#ifndef ARVO_OCIO_SHIM_H
#define ARVO_OCIO_SHIM_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

struct ocio_config; /* a loaded, validated config */
struct ocio_proc;   /* a CPU processor; apply is thread-safe */

/* Loads the config at path, or the one named by $OCIO when path is NULL or
 * empty (an error, not OCIO's "colour management disabled" raw config, when
 * $OCIO is unset). */
struct ocio_config *ocio_config_load(const char *path, char *err, size_t errlen);
void ocio_config_free(struct ocio_config *cfg);

/* Displays and views of the config. Returned strings live as long as cfg.
 * Out-of-range indices and unknown displays give NULL / 0. */
int ocio_display_count(const struct ocio_config *cfg);
const char *ocio_display_name(const struct ocio_config *cfg, int i);
const char *ocio_default_display(const struct ocio_config *cfg);
int ocio_view_count(const struct ocio_config *cfg, const char *display);
const char *ocio_view_name(const struct ocio_config *cfg, const char *display, int i);
const char *ocio_default_view(const struct ocio_config *cfg, const char *display);
/* 1 when name is a colour space or a role of the config. */
int ocio_has_colorspace(const struct ocio_config *cfg, const char *name);
/* Writes every display with its views into buf, one display per line:
 *   "sRGB - Display": "Standard", "ACES 1.0 - SDR Video", "Raw"
 * Returns the length it needed (like snprintf). */
size_t ocio_describe_views(const struct ocio_config *cfg, char *buf, size_t len);

/* A processor from colour space (or role) src to display/view; src NULL
 * means the "scene_linear" role. Unknown names fail with OCIO's message. */
struct ocio_proc *ocio_proc_display(const struct ocio_config *cfg, const char *src,
                                    const char *display, const char *view, char *err,
                                    size_t errlen);
/* A processor from colour space (or role) src to dst (e.g. "sRGB - Texture"
 * to "scene_linear", for image maps). */
struct ocio_proc *ocio_proc_convert(const struct ocio_config *cfg, const char *src,
                                    const char *dst, char *err, size_t errlen);
/* Applies the processor in place to npix packed RGB float triples.
 * Returns 0, or -1 with a message. */
int ocio_proc_apply_rgb(const struct ocio_proc *p, float *rgb, long npix, char *err,
                        size_t errlen);
void ocio_proc_free(struct ocio_proc *p);

/* The OpenColorIO library version, e.g. "2.1.2". */
const char *ocio_version(void);

#ifdef __cplusplus
}
#endif

#endif
