/* SPDX-License-Identifier: MIT */
/* imageio.c: PNG (libpng) and EXR (OpenEXRCore) image loading to linear floats. */
#include "imageio.h"

#include <errno.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <png.h>

#include "../../common/arena.h"
#include "exrout.h"
#include "ocio_shim.h"
#include "pngout.h"

/* ================= PNG ================= */

struct png_rd {
	jmp_buf jb;        /* where libpng errors return to */
	char msg[256];     /* libpng's message */
	png_bytep *rows;   /* row pointers into data */
	unsigned char *data; /* decoded 8- or 16-bit samples */
};

/* libpng error callback: records the message and unwinds to read_png. */
static void on_error(png_structp png, png_const_charp msg)
{
	struct png_rd *r = png_get_error_ptr(png);
	snprintf(r->msg, sizeof r->msg, "%s", msg);
	longjmp(r->jb, 1);
}

/* Ignores libpng warnings (e.g. about unknown chunks). */
static void on_warning(png_structp png, png_const_charp msg)
{
	(void)png;
	(void)msg;
}

/* libpng read callback: says "truncated" where libpng's own says "Read Error". */
static void read_data(png_structp png, png_bytep data, size_t len)
{
	FILE *fp = png_get_io_ptr(png);
	if (fread(data, 1, len, fp) != len)
		png_error(png, feof(fp) ? "the file ends early (truncated)" : "read error");
}

/* Sets up transforms so every PNG decodes to RGB or RGBA, 8 or 16 bits;
 * with indices, a palette image to one 8-bit index a pixel. */
static void set_transforms(png_structp png, png_infop info, int indices)
{
	int ct = png_get_color_type(png, info);
	if (ct == PNG_COLOR_TYPE_PALETTE && indices) {
		png_set_packing(png);
		png_set_interlace_handling(png);
		png_read_update_info(png, info);
		return;
	}
	if (ct == PNG_COLOR_TYPE_PALETTE)
		png_set_palette_to_rgb(png);
	if (ct == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8)
		png_set_expand_gray_1_2_4_to_8(png);
	if (png_get_valid(png, info, PNG_INFO_tRNS))
		png_set_tRNS_to_alpha(png);
	if (ct == PNG_COLOR_TYPE_GRAY || ct == PNG_COLOR_TYPE_GRAY_ALPHA)
		png_set_gray_to_rgb(png);
	png_set_interlace_handling(png);
	png_read_update_info(png, info);
}

/* Converts the decoded samples into im->px (values in [0,1], still encoded);
 * one index a pixel becomes three equal channels. */
static void samples_to_float(const struct png_rd *r, int depth, struct img *im)
{
	size_t n = (size_t)im->w * (size_t)im->h * (size_t)im->nch;
	if (im->indexed) {
		im->nch = 3;
		im->px = mem_alloc(n * 3 * sizeof(float));
		for (size_t i = 0; i < n; i++)
			im->px[3 * i] = im->px[3 * i + 1] = im->px[3 * i + 2] = (float)r->data[i] / 255.0f;
		return;
	}
	im->px = mem_alloc(n * sizeof(float));
	for (size_t i = 0; i < n; i++)
		im->px[i] = depth == 16
		                ? (float)((r->data[2 * i] << 8) | r->data[2 * i + 1]) / 65535.0f
		                : (float)r->data[i] / 255.0f;
}

/* Decodes the PNG on fp into im. Returns 0, or -1 with r->msg set. */
static int read_png(FILE *fp, struct png_rd *r, struct img *im, int indices)
{
	png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, r, on_error, on_warning);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	if (!info) {
		png_destroy_read_struct(&png, NULL, NULL);
		snprintf(r->msg, sizeof r->msg, "libpng: out of memory");
		return -1;
	}
	if (setjmp(r->jb)) {
		png_destroy_read_struct(&png, &info, NULL);
		return -1;
	}
	png_set_user_limits(png, 1u << 15, 1u << 15);
	/* a chunk may not declare more than 16 MiB, and that is an error, not a
	 * warning libpng reads past (a 350-byte file whose tEXt chunk declared
	 * 800 MB made libpng allocate and clear it: 2.5 s, 800 MB; make fuzz) */
	png_set_chunk_malloc_max(png, (png_alloc_size_t)16 << 20);
	png_set_chunk_cache_max(png, 1000);
	png_set_benign_errors(png, 0);
	png_set_read_fn(png, fp, read_data);
	png_read_info(png, info);
	im->indexed = indices && png_get_color_type(png, info) == PNG_COLOR_TYPE_PALETTE;
	set_transforms(png, info, indices);
	int depth = png_get_bit_depth(png, info);
	im->depth = depth;
	im->w = (int)png_get_image_width(png, info);
	im->h = (int)png_get_image_height(png, info);
	im->nch = png_get_channels(png, info);
	if ((size_t)im->w * (size_t)im->h * (size_t)im->nch > ((size_t)1 << 28)) /* 1 GiB of floats, as EXR */
		png_error(png, "image too large (more than 2^28 samples)");
	size_t stride = png_get_rowbytes(png, info);
	r->data = mem_alloc(stride * (size_t)im->h);
	r->rows = mem_alloc((size_t)im->h * sizeof *r->rows);
	for (int y = 0; y < im->h; y++)
		r->rows[y] = r->data + (size_t)y * stride;
	png_read_image(png, r->rows);
	png_read_end(png, NULL);
	png_destroy_read_struct(&png, &info, NULL);
	samples_to_float(r, depth, im);
	return 0;
}

/* Loads a PNG file into im (encoded values; no colour conversion yet).
 * Returns 0, or -1 with the reason in why. */
static int load_png(const char *path, struct img *im, int indices, char *why, size_t n)
{
	FILE *fp = fopen(path, "rb");
	if (!fp) {
		snprintf(why, n, "%s", strerror(errno));
		return -1;
	}
	struct png_rd r = {.msg = ""};
	int rc = read_png(fp, &r, im, indices);
	fclose(fp);
	free(r.rows);
	free(r.data);
	if (rc)
		snprintf(why, n, "%s", r.msg);
	return rc;
}

/* ================= EXR ================= */

/* Picks the colour planes of an EXR: R,G,B (A), else Y, else the first. */
static void pick_planes(const struct framebuffer *fb, const float *pl[4], int *nch)
{
	pl[0] = fb_find(fb, "R"), pl[1] = fb_find(fb, "G"), pl[2] = fb_find(fb, "B");
	pl[3] = fb_find(fb, "A");
	if (!pl[0] && !pl[1] && !pl[2]) {
		const float *y = fb_find(fb, "Y");
		pl[0] = pl[1] = pl[2] = y ? y : fb->planes[0].data;
	}
	*nch = pl[3] ? 4 : 3;
}

/* Loads an EXR file into im (interleaving its planes; missing ones are 0).
 * Returns 0, or -1 with the reader's message in why. */
static int load_exr(const char *path, struct img *im, char *why, size_t whylen)
{
	struct framebuffer *fb;
	struct diag quiet;
	diag_init(&quiet, NULL);
	if (out_exr_read(path, &fb, NULL, &quiet) != 0) {
		/* the reader says "cannot read 'PATH': reason"; keep the reason */
		const char *r = strstr(quiet.last, "': ");
		r = r ? r + 3 : quiet.last;
		size_t l = strlen(r) < whylen ? strlen(r) : whylen - 1;
		memcpy(why, r, l);
		why[l] = '\0';
		return -1;
	}
	const float *pl[4];
	pick_planes(fb, pl, &im->nch);
	im->w = fb->w, im->h = fb->h;
	size_t n = (size_t)fb->w * (size_t)fb->h;
	im->px = mem_alloc(n * (size_t)im->nch * sizeof(float));
	for (size_t i = 0; i < n; i++)
		for (int c = 0; c < im->nch; c++)
			im->px[i * (size_t)im->nch + (size_t)c] = pl[c] ? pl[c][i] : 0.0f;
	fb_free(fb);
	return 0;
}

/* ================= colour ================= */

/* Converts the colour of im in place from space src to scene_linear.
 * Returns 0 or an enum fail status (reported at at). */
static int to_linear(struct img *im, const char *config, const char *src, struct diag *dg, struct srcloc at)
{
	struct ocio_config *cfg;
	char msg[512];
	int err = out_ocio_load(config, &cfg, dg);
	if (err)
		return err;
	struct ocio_proc *p = ocio_proc_convert(cfg, src, "scene_linear", msg, sizeof msg);
	size_t n = (size_t)im->w * (size_t)im->h;
	float *rgb = p ? mem_alloc(n * 3 * sizeof(float)) : NULL;
	for (size_t i = 0; p && i < n; i++)
		memcpy(rgb + 3 * i, im->px + i * (size_t)im->nch, 3 * sizeof(float));
	if (!p || ocio_proc_apply_rgb(p, rgb, (long)n, msg, sizeof msg) != 0)
		err = diag_fail(dg, FAIL_INPUT, at, "cannot convert colours from '%s': %s", src, msg);
	for (size_t i = 0; !err && i < n; i++)
		memcpy(im->px + i * (size_t)im->nch, rgb + 3 * i, 3 * sizeof(float));
	free(rgb);
	ocio_proc_free(p);
	ocio_config_free(cfg);
	return err;
}

/* The first bytes of path, to tell the format; returns how many were read. */
static size_t read_magic(const char *path, unsigned char *buf, size_t n)
{
	FILE *fp = fopen(path, "rb");
	if (!fp)
		return 0;
	size_t k = fread(buf, 1, n, fp);
	fclose(fp);
	return k;
}

/* Sniffs the format, decodes, then converts colour unless raw (alpha untouched). */
int img_load(const char *path, const struct img_opts *opts, struct img *out, struct diag *dg, struct srcloc at,
             const char *name)
{
	static const struct img_opts defaults = {NULL, NULL, 0, 0};
	const struct img_opts *o = opts ? opts : &defaults;
	unsigned char m[8];
	char why[400] = "";
	memset(out, 0, sizeof *out);
	errno = 0;
	size_t k = read_magic(path, m, sizeof m);
	int is_png = k == 8 && png_sig_cmp(m, 0, 8) == 0;
	int is_exr = k >= 4 && m[0] == 0x76 && m[1] == 0x2f && m[2] == 0x31 && m[3] == 0x01;
	int err = 0;
	if (is_png)
		err = load_png(path, out, o->indices, why, sizeof why);
	else if (is_exr)
		err = load_exr(path, out, why, sizeof why);
	else
		err = -1, snprintf(why, sizeof why, "%s", k == 0 ? (errno ? strerror(errno) : "empty file")
		                                                  : "not a PNG or OpenEXR image");
	if (err)
		err = diag_fail(dg, FAIL_INPUT, at, "cannot read image file '%s': %s", name ? name : path, why);
	const char *src = o->colorspace ? o->colorspace : is_png ? IMG_TEXTURE_SPACE : NULL;
	if (!err && !o->raw && !out->indexed && src)
		err = to_linear(out, o->ocio_config, src, dg, at);
	if (err)
		img_free(out);
	return err;
}

void img_free(struct img *im)
{
	free(im->px);
	memset(im, 0, sizeof *im);
}
