/* SPDX-License-Identifier: MIT */
/* pngout.h: 8- or 16-bit PNG output of the beauty (R,G,B) through an OCIO display
 * and view, and the resolution of which OCIO config to use.
 *
 * Config resolution: an explicit path (the CLI's --ocio-config) > $OCIO >
 * the shipped config (out_default_ocio_config). Errors follow exrout.h:
 * 0 on success, else an enum fail status after a report to the diag. */
#ifndef ARVO_PNGOUT_H
#define ARVO_PNGOUT_H

#include <stddef.h>

#include "../../common/diag.h"
#include "framebuffer.h"

struct ocio_config;

#define OUT_DEFAULT_DISPLAY "sRGB - Display"
#define OUT_DEFAULT_VIEW "ACES 1.0 - SDR Video" /* desaturates bright highlights */

struct out_png_opts {
	const char *ocio_config; /* explicit config path (--ocio-config), or NULL */
	const char *display;     /* NULL: OUT_DEFAULT_DISPLAY, or the config's default if absent */
	const char *view;        /* NULL: OUT_DEFAULT_VIEW, or the display's default if absent */
	const char *source;      /* colour space of the pixels; NULL: the scene_linear role */
	const char *scene_view;  /* the scene's view when view is NULL, if the display has it */
	int depth;               /* bits per channel: 16, else 8 */
	int threads;             /* threads for the OCIO transform (0: the machine's) */
};

/* How a PNG says what its values mean, from the OCIO display and view. */
enum out_png_signal {
	OUT_PNG_UNKNOWN, /* a display arvo does not recognise: no colour chunk */
	OUT_PNG_SRGB,    /* a display named "sRGB…": sRGB chunk (with gAMA and cHRM) */
	OUT_PNG_CICP,    /* P3, Rec.1886/Rec.709, PQ, HLG displays: a cICP chunk */
	OUT_PNG_RAW      /* the Raw view (scene-linear values unchanged): no chunk */
};
/* The signal for display/view; for OUT_PNG_CICP fills cicp (colour
 * primaries, transfer, matrix 0, full range 1; ITU-T H.273 codes). */
int out_png_signal(const char *display, const char *view, unsigned char cicp[4]);

/* The shipped config "ocio/config.ocio", searched in $ARVO_DATA_DIR, then the
 * compile-time ARVO_DATA_DIR (installed share/arvo), then beside the
 * executable: <exe dir>/stdlib-scenes, <exe dir>/../share/arvo, and the
 * stdlib-scenes of up to three parent directories (build trees). NULL when
 * none is readable. The string is static. */
const char *out_default_ocio_config(void);

/* The config path to use: explicit_path if non-empty, else $OCIO if set and
 * non-empty, else out_default_ocio_config() (may be NULL). */
const char *out_ocio_config_path(const char *explicit_path);

/* Loads the resolved config into *cfg (free with ocio_config_free); FAIL_INPUT
 * when there is none or it cannot be loaded. */
int out_ocio_load(const char *explicit_path, struct ocio_config **cfg, struct diag *dg);

/* Resolves display and view against cfg (NULL means the defaults above) and
 * stores the names to use; an unknown name gives FAIL_USAGE and an error
 * listing the valid displays and views. */
int out_ocio_pick_view(const struct ocio_config *cfg, const char *display, const char *view,
                       const char **disp_out, const char **view_out, struct diag *dg);

/* Writes into buf (len bytes) the displays and views of the resolved config,
 * one display per line, for --help. */
int out_ocio_list_views(const char *explicit_path, char *buf, size_t len, struct diag *dg);

/* Converts R,G,B of fb through the display/view, clamps to [0,1], and
 * quantises with rounding into rgb8 (w*h*3 bytes, top row first). Missing
 * G/B planes are read as zero; a missing R plane is an error. */
int out_png_encode(const struct framebuffer *fb, const struct out_png_opts *opts, unsigned char *rgb8,
                   struct diag *dg);

/* Encodes as out_png_encode (to opts->depth bits), then writes an RGB PNG
 * to "<path>.tmp.XXXXXX" and renames it to path only on success (path
 * untouched on failure). The PNG carries the colour chunk out_png_signal
 * picks and text chunks "Software", "OCIO display" and "OCIO view".
 * Returns 0, or the encoder's status, FAIL_CREATE or FAIL_WRITE. */
int out_png_write(const struct framebuffer *fb, const char *path, const struct out_png_opts *opts,
                  struct diag *dg);

#endif
