/* SPDX-License-Identifier: MIT */
/* merge.c: `arvo merge -o full.exr parts...`: assembles the EXRs of partial
 * renders (--region, --tile) into the whole frame. Each part's data window
 * says where it goes; the parts must share the frame (display window) and
 * the channels, and cover the frame exactly once. Pixels are copied, so
 * the result is bit-identical to a render of the whole frame (the first
 * part's header, compression and pixel types are kept). */
#include "tools.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../common/arena.h"
#include "../tracer/output/exrout.h"

/* The EXR reader and writer report to a diag; the tool prints their message
 * with its own prefix. QUIET(call) is NULL on success, else the message. */
static struct diag quiet;
#define QUIET(call) (diag_init(&quiet, NULL), (call) ? (const char *)quiet.last : (const char *)NULL)

enum { EX_OK = 0, EX_USAGE = 64, EX_DATAERR = 65, EX_NOINPUT = 66, EX_IOERR = 74 };

__attribute__((format(printf, 1, 2)))
static int merge_usage(const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	fprintf(stderr, "arvo merge: error: ");
	vfprintf(stderr, fmt, ap);
	va_end(ap);
	fprintf(stderr, "\nusage: arvo merge -o FULL.exr PART.exr...\n");
	return EX_USAGE;
}

/* Why part p (file path) does not fit the frame of the first part f, or NULL. */
static const char *misfit(const struct framebuffer *f, const struct framebuffer *p, char *buf, size_t n)
{
	if (p->full_w != f->full_w || p->full_h != f->full_h)
		snprintf(buf, n, "its frame is %dx%d, the first part's %dx%d", p->full_w, p->full_h,
		         f->full_w, f->full_h);
	else if (p->x0 < 0 || p->y0 < 0 || p->x0 + p->w > p->full_w || p->y0 + p->h > p->full_h)
		snprintf(buf, n, "its pixels lie outside the frame");
	else if (fb_count(p) != fb_count(f))
		snprintf(buf, n, "it has %d channels, the first part %d", fb_count(p), fb_count(f));
	else
		for (int c = 0; c < fb_count(p); c++)
			if (!fb_find(f, fb_name(p, c))) {
				snprintf(buf, n, "channel '%s' is not in the first part", fb_name(p, c));
				return buf;
			}
	return buf[0] ? buf : NULL;
}

/* Copies part p into the frame fb, marking covered pixels; returns the
 * first pixel already covered (index + 1), or 0. */
static size_t paste(struct framebuffer *fb, unsigned char *covered, const struct framebuffer *p)
{
	for (int y = 0; y < p->h; y++)
		for (int x = 0; x < p->w; x++) {
			size_t at = (size_t)(p->y0 + y) * (size_t)fb->w + (size_t)(p->x0 + x);
			if (covered[at])
				return at + 1;
			covered[at] = 1;
		}
	for (int c = 0; c < fb_count(p); c++) {
		const float *src = fb_data(p, c);
		float *dst = fb_plane(fb, fb_name(p, c));
		for (int y = 0; y < p->h; y++)
			memcpy(dst + (size_t)(p->y0 + y) * (size_t)fb->w + (size_t)p->x0,
			       src + (size_t)y * (size_t)p->w, sizeof(float) * (size_t)p->w);
	}
	return 0;
}

/* Reads the parts into one frame; returns -1 (done: *out set) or an exit code. */
static int assemble(char **parts, int n, struct framebuffer **out, struct out_exr_info *info)
{
	struct framebuffer *fb = NULL, *first = NULL;
	unsigned char *covered = NULL;
	int rc = -1;
	for (int i = 0; i < n && rc < 0; i++) {
		struct framebuffer *p;
		char why[256] = "";
		const char *err = QUIET(out_exr_read(parts[i], &p, i == 0 ? info : NULL, &quiet));
		if (err) {
			fprintf(stderr, "arvo merge: error: %s\n", err);
			rc = EX_NOINPUT;
			break;
		}
		if (!first) {
			first = p;
			fb = fb_new(p->full_w, p->full_h);
			covered = mem_calloc((size_t)fb->w * (size_t)fb->h, 1);
		}
		size_t dup = 0;
		if (misfit(first, p, why, sizeof why)) {
			fprintf(stderr, "arvo merge: error: '%s' does not fit: %s\n", parts[i], why);
			rc = EX_DATAERR;
		} else if ((dup = paste(fb, covered, p)) != 0) {
			fprintf(stderr, "arvo merge: error: '%s' overlaps an earlier part at pixel (%d, %d)\n",
			        parts[i], (int)((dup - 1) % (size_t)fb->w), (int)((dup - 1) / (size_t)fb->w));
			rc = EX_DATAERR;
		}
		if (p != first)
			fb_free(p);
	}
	for (size_t i = 0; rc < 0 && fb && i < (size_t)fb->w * (size_t)fb->h; i++)
		if (!covered[i]) {
			fprintf(stderr, "arvo merge: error: no part covers pixel (%d, %d)\n",
			        (int)(i % (size_t)fb->w), (int)(i / (size_t)fb->w));
			rc = EX_DATAERR;
		}
	fb_free(first);
	free(covered);
	if (rc >= 0)
		fb_free(fb);
	else
		*out = fb;
	return rc;
}

int tool_merge(int argc, char **argv)
{
	const char *output = NULL;
	char **parts = mem_calloc((size_t)argc, sizeof *parts);
	int n = 0, rc = -1;
	for (int i = 1; i < argc && rc < 0; i++) {
		if (!strcmp(argv[i], "-o")) {
			if (i + 1 >= argc)
				rc = merge_usage("option '%s' needs a value", "-o");
			else
				output = argv[++i];
		} else if (argv[i][0] == '-' && argv[i][1]) {
			rc = merge_usage("unknown option '%s'", argv[i]);
		} else {
			parts[n++] = argv[i];
		}
	}
	if (rc < 0 && !output)
		rc = merge_usage("%s", "no output given (-o FULL.exr)");
	if (rc < 0 && n == 0)
		rc = merge_usage("%s", "no parts given");
	struct framebuffer *fb = NULL;
	static struct out_exr_info info;
	if (rc < 0)
		rc = assemble(parts, n, &fb, &info);
	if (rc < 0) {
		struct out_exr_opts eo = {info.half_but_z, info.compression, info.scene[0] ? info.scene : NULL, &info.meta, 0};
		const char *err = QUIET(out_exr_write(fb, output, &eo, &quiet));
		if (err)
			fprintf(stderr, "arvo merge: error: %s\n", err);
		rc = err ? EX_IOERR : EX_OK;
	}
	fb_free(fb);
	free(parts);
	return rc;
}
