/* SPDX-License-Identifier: MIT */
/* test_png.c: PNG output through the OCIO views (8-bit values of known
 * pixels, read back with libpng), its failure modes, and image loading for
 * image_map (PNG through "sRGB - Texture", EXR as linear). */
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <png.h>

#include "../../tracer/output/exrout.h"
#include "../../tracer/output/framebuffer.h"
#include "../../tracer/output/imageio.h"
#include "../../tracer/output/pngout.h"
#include "test.h"

static char dir[64]; /* scratch directory of this run */

/* dir/name in one of two rotating static buffers. */
static const char *in_dir(const char *name)
{
	static char p[2][256];
	static int k;
	k ^= 1;
	snprintf(p[k], sizeof p[k], "%s/%s", dir, name);
	return p[k];
}

#define NPIX 8
static const float pix[NPIX][3] = {
    {0.18f, 0.18f, 0.18f}, {1, 1, 1},    {0.5f, 0.2f, 0.1f}, {50, 5, 1},
    {10, 0.5f, 0.05f},     {0, 0, 0},    {-1, -1, -1},       {0.25f, 0.75f, 0},
};
/* Expected bytes: docs/design.md §6's reference values * 255, rounded. */
static const int want_standard[NPIX][3] = {
    {118, 118, 118}, {255, 255, 255}, {188, 124, 89}, {255, 255, 255},
    {255, 188, 63},  {0, 0, 0},       {0, 0, 0},      {137, 225, 0},
};
static const int want_aces[NPIX][3] = {
    {91, 91, 91},    {207, 207, 207}, {159, 100, 64}, {255, 251, 237},
    {255, 213, 135}, {0, 0, 0},       {0, 0, 0},      {-1, -1, -1}, /* -1: not checked */
};
static const int want_raw[NPIX][3] = {
    {46, 46, 46}, {255, 255, 255}, {128, 51, 26}, {255, 255, 255},
    {255, 128, 13}, {0, 0, 0},     {0, 0, 0},     {64, 191, 0},
};

/* An 8x1 framebuffer of the pixels above. */
static struct framebuffer *make_fb(void)
{
	struct framebuffer *fb = fb_new(NPIX, 1);
	float *p[3] = {fb_plane(fb, "R"), fb_plane(fb, "G"), fb_plane(fb, "B")};
	for (int i = 0; i < NPIX; i++)
		for (int c = 0; c < 3; c++)
			p[c][i] = pix[i][c];
	fb_plane(fb, "Z")[0] = 5; /* extra planes are ignored */
	return fb;
}

/* Reads an 8-bit RGB PNG with libpng's simplified API into buf (w*h*3). */
static int read_png8(const char *path, unsigned char *buf, int w, int h)
{
	png_image im;
	memset(&im, 0, sizeof im);
	im.version = PNG_IMAGE_VERSION;
	if (!png_image_begin_read_from_file(&im, path))
		return -1;
	int ok = im.width == (unsigned)w && im.height == (unsigned)h && im.format == PNG_FORMAT_RGB;
	im.format = PNG_FORMAT_RGB;
	if (!ok) {
		png_image_free(&im);
		return -1;
	}
	return png_image_finish_read(&im, NULL, buf, 0, NULL) ? 0 : -1;
}

/* Writes with view (NULL = default), reads back, compares with want (±tol). */
static void check_png(const char *view, const int want[NPIX][3], int tol)
{
	struct framebuffer *fb = make_fb();
	struct out_png_opts o = {NULL, NULL, view, NULL, NULL, 8, 0};
	const char *path = in_dir("v.png");
	const char *err = MSG(out_png_write(fb, path, &o, TDG));
	CHECK(err == NULL);
	if (err)
		printf("# %s\n", err);
	unsigned char got[NPIX * 3], enc[NPIX * 3];
	CHECK(read_png8(path, got, NPIX, 1) == 0);
	CHECK(MSG(out_png_encode(fb, &o, enc, TDG)) == NULL);
	CHECK(memcmp(got, enc, sizeof got) == 0);
	for (int i = 0; i < NPIX; i++)
		for (int c = 0; c < 3; c++)
			if (want[i][c] >= 0)
				CHECK_NEAR(got[3 * i + c], want[i][c], tol);
	fb_free(fb);
}

static void t_standard(void) { check_png("Standard", want_standard, 0); }
static void t_aces_default(void) { check_png(NULL, want_aces, 1); }
static void t_raw(void) { check_png("Raw", want_raw, 0); }

/* The default view desaturates a bright orange; Standard keeps it saturated. */
static void t_highlight_desaturation(void)
{
	CHECK(want_aces[4][2] - want_standard[4][2] > 50);
}

/* Runs of equal pixels (a background) are transformed once and copied:
 * every pixel of an image of long and short runs, one across the boundary
 * of two chunks of the transform (16384 pixels), encodes as its colour
 * does in a row where no two neighbours are equal. Default (ACES) view. */
static void t_runs(void)
{
	enum { K = 7, W = 200, H = 100 };
	const float col[K][3] = {{0.05f, 0.06f, 0.08f}, {0.9f, 0.2f, 0.1f}, {4.0f, 3.0f, 0.5f}, {0, 0, 0},
	                         {0.18f, 0.18f, 0.18f}, {-0.0f, 0.0f, 0.0f}, {0.5f, 0.9f, 0.3f}};
	struct framebuffer *fb = fb_new(W, H), *row = fb_new(K, 1);
	float *pl[3] = {fb_plane(fb, "R"), fb_plane(fb, "G"), fb_plane(fb, "B")};
	float *rl[3] = {fb_plane(row, "R"), fb_plane(row, "G"), fb_plane(row, "B")};
	int which[W * H];
	for (int i = 0, k = 0; i < W * H; i++) {
		/* runs of 1, 2, 3 ... 40 pixels, then one of 2000 around pixel 16384 */
		bool early = i > 0 && i < 15400 && i % (1 + i % 41) == 0, late = i > 17400 && i % 37 == 0;
		if (early || late || i == 15400 || i == 17400)
			k = (k + 1) % K;
		which[i] = k;
		for (int c = 0; c < 3; c++)
			pl[c][i] = col[k][c];
	}
	for (int k = 0; k < K; k++)
		for (int c = 0; c < 3; c++)
			rl[c][k] = col[k][c];
	struct out_png_opts o = {NULL, NULL, NULL, NULL, NULL, 8, 0};
	static unsigned char enc[W * H * 3];
	unsigned char one[K * 3];
	CHECK(MSG(out_png_encode(fb, &o, enc, TDG)) == NULL);
	CHECK(MSG(out_png_encode(row, &o, one, TDG)) == NULL);
	int bad = 0;
	for (int i = 0; i < W * H; i++)
		bad += memcmp(enc + 3 * i, one + 3 * which[i], 3) != 0;
	CHECK(bad == 0);
	CHECK(one[3 * 1] != one[3 * 0] && one[3 * 2] != one[3 * 1]); /* the colours do differ */
	fb_free(fb);
	fb_free(row);
}

/* NaN and a missing R plane: no crash, clear results. */
static void t_odd_inputs(void)
{
	struct framebuffer *fb = fb_new(2, 1);
	float *r = fb_plane(fb, "R");
	r[0] = NAN, r[1] = 0.5f;
	unsigned char enc[6];
	struct out_png_opts o = {NULL, NULL, "Raw", NULL, NULL, 8, 0};
	CHECK(MSG(out_png_encode(fb, &o, enc, TDG)) == NULL);
	CHECK(enc[0] == 0 && enc[3] == 128 && enc[4] == 0 && enc[5] == 0);
	struct framebuffer *nob = fb_new(2, 1);
	fb_plane(nob, "Z");
	CHECK(MSG(out_png_encode(nob, &o, enc, TDG)) != NULL);
	fb_free(nob);
	fb_free(fb);
}

/* Failures leave the old file and no temp file; bad views list valid ones. */
static void t_failures(void)
{
	struct framebuffer *fb = make_fb();
	const char *path = in_dir("old.png");
	FILE *f = fopen(path, "wb");
	if (f) {
		fputs("old", f);
		fclose(f);
	}
	struct out_png_opts o = {NULL, NULL, "Filmic", NULL, NULL, 8, 0};
	const char *err = MSG(out_png_write(fb, path, &o, TDG));
	CHECK(err && strstr(err, "Filmic") && strstr(err, "\"Standard\""));
	o.view = NULL;
	o.display = "DCI-P3";
	CHECK(MSG(out_png_write(fb, path, &o, TDG)) != NULL);
	o.display = NULL;
	o.ocio_config = "/nonexistent/config.ocio";
	err = MSG(out_png_write(fb, path, &o, TDG));
	CHECK(err && strstr(err, "/nonexistent/config.ocio"));
	char buf[8] = "";
	f = fopen(path, "rb");
	CHECK(f && fread(buf, 1, 7, f) == 3 && strcmp(buf, "old") == 0);
	if (f)
		fclose(f);
	char bad[256];
	snprintf(bad, sizeof bad, "%s/missing/dir.png", dir);
	CHECK(MSG(out_png_write(fb, bad, NULL, TDG)) != NULL);
	char cmd[160];
	snprintf(cmd, sizeof cmd, "ls %s | grep -q '\\.tmp\\.'", dir);
	CHECK(system(cmd) != 0);
	fb_free(fb);
}

/* ---- image loading ---- */

/* Writes w*h pixels of format fmt (simplified API, 8-bit) to path. */
static int write_png8(const char *path, const unsigned char *buf, int w, int h, png_uint_32 fmt)
{
	png_image im;
	memset(&im, 0, sizeof im);
	im.version = PNG_IMAGE_VERSION;
	im.width = (png_uint_32)w, im.height = (png_uint_32)h, im.format = fmt;
	return png_image_write_to_file(&im, path, 0, buf, 0, NULL) ? 0 : -1;
}

static void t_load_png_rgb(void)
{
	static const unsigned char px[] = {128, 255, 0, 64, 10, 200};
	CHECK(write_png8(in_dir("tex.png"), px, 2, 1, PNG_FORMAT_RGB) == 0);
	struct img im;
	const char *err = MSG(img_load(in_dir("tex.png"), NULL, &im, TDG, srcloc_none(), NULL));
	CHECK(err == NULL);
	if (err)
		printf("# %s\n", err);
	CHECK(im.w == 2 && im.h == 1 && im.nch == 3);
	if (im.px) {
		CHECK_NEAR(im.px[0], 0.2158605, 1e-4); /* sRGB EOTF of 128/255 */
		CHECK_NEAR(im.px[1], 1.0, 1e-4);
		CHECK_NEAR(im.px[2], 0.0, 1e-5);
		CHECK_NEAR(im.px[3], 0.0512695, 1e-4);
		CHECK_NEAR(im.px[4], 0.0030353, 1e-4); /* linear toe */
		CHECK_NEAR(im.px[5], 0.5775804, 1e-4);
	}
	img_free(&im);
	struct img_opts raw = {NULL, NULL, 1, 0};
	CHECK(MSG(img_load(in_dir("tex.png"), &raw, &im, TDG, srcloc_none(), NULL)) == NULL);
	if (im.px)
		CHECK_NEAR(im.px[0], 128.0 / 255.0, 1e-6);
	img_free(&im);
}

/* Grey+alpha: grey expands to RGB and is decoded; alpha stays as stored. */
static void t_load_png_gray_alpha(void)
{
	static const unsigned char px[] = {128, 128, 255, 0};
	CHECK(write_png8(in_dir("ga.png"), px, 2, 1, PNG_FORMAT_GA) == 0);
	struct img im;
	CHECK(MSG(img_load(in_dir("ga.png"), NULL, &im, TDG, srcloc_none(), NULL)) == NULL);
	CHECK(im.nch == 4);
	if (im.px && im.nch == 4) {
		for (int c = 0; c < 3; c++)
			CHECK_NEAR(im.px[c], 0.2158605, 1e-4);
		CHECK_NEAR(im.px[3], 128.0 / 255.0, 1e-6);
		CHECK_NEAR(im.px[4], 1.0, 1e-4);
		CHECK_NEAR(im.px[7], 0.0, 0);
	}
	img_free(&im);
}

/* A 16-bit RGB PNG written with the classic API keeps 16-bit precision. */
static void t_load_png16(void)
{
	FILE *f = fopen(in_dir("p16.png"), "wb");
	png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
	png_infop info = png_create_info_struct(png);
	if (!f || !png || !info || setjmp(png_jmpbuf(png))) {
		CHECK(0);
		return;
	}
	png_init_io(png, f);
	png_set_IHDR(png, info, 1, 1, 16, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
	             PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	png_write_info(png, info);
	unsigned char row[6] = {0x80, 0x00, 0xff, 0xff, 0x00, 0x01}; /* big-endian */
	png_write_row(png, row);
	png_write_end(png, info);
	png_destroy_write_struct(&png, &info);
	fclose(f);
	struct img im;
	CHECK(MSG(img_load(in_dir("p16.png"), NULL, &im, TDG, srcloc_none(), NULL)) == NULL);
	if (im.px) {
		CHECK_NEAR(im.px[0], 0.2140609, 1e-4); /* EOTF(32768/65535) */
		CHECK_NEAR(im.px[1], 1.0, 1e-4);
		CHECK_NEAR(im.px[2], 1.0 / 65535 / 12.92, 1e-6);
	}
	img_free(&im);
}

static void t_load_exr(void)
{
	struct framebuffer *fb = fb_new(3, 2);
	const char *nm[4] = {"R", "G", "B", "A"};
	for (int c = 0; c < 4; c++)
		for (int i = 0; i < 6; i++)
			fb_plane(fb, nm[c])[i] = (float)(c * 10 + i) * 0.25f - 1.0f;
	CHECK(MSG(out_exr_write(fb, in_dir("m.exr"), NULL, TDG)) == NULL);
	struct img im;
	CHECK(MSG(img_load(in_dir("m.exr"), NULL, &im, TDG, srcloc_none(), NULL)) == NULL);
	CHECK(im.w == 3 && im.h == 2 && im.nch == 4);
	for (int i = 0; im.px && i < 6; i++)
		for (int c = 0; c < 4; c++)
			CHECK(im.px[4 * i + c] == fb_find(fb, nm[c])[i]);
	img_free(&im);
	fb_free(fb);
	fb = fb_new(2, 2);
	fb_plane(fb, "Y")[3] = 0.75f;
	CHECK(MSG(out_exr_write(fb, in_dir("y.exr"), NULL, TDG)) == NULL);
	CHECK(MSG(img_load(in_dir("y.exr"), NULL, &im, TDG, srcloc_none(), NULL)) == NULL);
	CHECK(im.nch == 3 && im.px && im.px[9] == 0.75f && im.px[11] == 0.75f && im.px[0] == 0);
	img_free(&im);
	fb_free(fb);
}

static void t_load_errors(void)
{
	struct img im;
	CHECK(MSG(img_load(in_dir("nope.png"), NULL, &im, TDG, srcloc_none(), NULL)) != NULL && im.px == NULL);
	FILE *f = fopen(in_dir("bad.png"), "wb");
	if (f) {
		fwrite("\x89PNG\r\n\x1a\n garbage", 1, 16, f);
		fclose(f);
	}
	const char *err = MSG(img_load(in_dir("bad.png"), NULL, &im, TDG, srcloc_none(), NULL));
	CHECK(err != NULL && im.px == NULL);
	if (err)
		printf("# expected error: %s\n", err);
	struct img_opts o = {NULL, "No Such Space", 0, 0};
	CHECK(MSG(img_load(in_dir("tex.png"), &o, &im, TDG, srcloc_none(), NULL)) != NULL && im.px == NULL);
	CHECK(MSG(img_load(in_dir("old.png"), NULL, &im, TDG, srcloc_none(), NULL)) != NULL);
}

/* What a PNG file says besides its pixels (libpng's low-level reader). */
struct png_facts {
	int depth, srgb, cicp;       /* bit depth; sRGB and cICP chunks present */
	unsigned char cicp_data[4];  /* the cICP chunk */
	char display[128], view[128];/* the "OCIO display" and "OCIO view" texts */
	unsigned px[3];              /* the first pixel's samples */
};

static int read_facts(const char *path, struct png_facts *f)
{
	memset(f, 0, sizeof *f);
	FILE *fp = fopen(path, "rb");
	if (!fp)
		return 0;
	png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
	png_infop info = png_create_info_struct(png);
	if (setjmp(png_jmpbuf(png))) {
		png_destroy_read_struct(&png, &info, NULL);
		fclose(fp);
		return 0;
	}
	png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_ALWAYS, (png_const_bytep) "cICP", 1);
	png_init_io(png, fp);
	png_read_info(png, info);
	f->depth = png_get_bit_depth(png, info);
	int intent;
	f->srgb = png_get_sRGB(png, info, &intent) != 0;
	png_unknown_chunkp unk;
	int nunk = png_get_unknown_chunks(png, info, &unk);
	for (int i = 0; i < nunk; i++)
		if (!memcmp(unk[i].name, "cICP", 4) && unk[i].size == 4)
			f->cicp = 1, memcpy(f->cicp_data, unk[i].data, 4);
	png_textp text;
	int ntext = 0;
	png_get_text(png, info, &text, &ntext);
	for (int i = 0; i < ntext; i++) {
		if (!strcmp(text[i].key, "OCIO display"))
			snprintf(f->display, sizeof f->display, "%s", text[i].text);
		if (!strcmp(text[i].key, "OCIO view"))
			snprintf(f->view, sizeof f->view, "%s", text[i].text);
	}
	unsigned char row[2 * 3 * 4];
	png_read_row(png, row, NULL);
	for (int c = 0; c < 3; c++)
		f->px[c] = f->depth == 16 ? (unsigned)(row[2 * c] << 8 | row[2 * c + 1]) : row[c];
	png_destroy_read_struct(&png, &info, NULL);
	fclose(fp);
	return 1;
}

/* --png-depth 16 through Raw: 0.5 → 32768, 0.25 → 16384, 2 → 65535; no
 * colour chunk for Raw, the display and view in the text chunks. */
static void t_png16(void)
{
	struct framebuffer *fb = fb_new(2, 1);
	float *p[3] = {fb_plane(fb, "R"), fb_plane(fb, "G"), fb_plane(fb, "B")};
	p[0][0] = 0.5f, p[1][0] = 0.25f, p[2][0] = 2;
	struct out_png_opts o = {NULL, NULL, "Raw", NULL, NULL, 16, 0};
	struct png_facts f;
	CHECK(MSG(out_png_write(fb, in_dir("d16.png"), &o, TDG)) == NULL);
	CHECK(read_facts(in_dir("d16.png"), &f));
	CHECK(f.depth == 16);
	CHECK(f.px[0] == 32768 && f.px[1] == 16384 && f.px[2] == 65535);
	CHECK(!f.srgb && !f.cicp);
	CHECK_STR(f.display, "sRGB - Display");
	CHECK_STR(f.view, "Raw");
	o.depth = 8;
	CHECK(MSG(out_png_write(fb, in_dir("d8.png"), &o, TDG)) == NULL);
	CHECK(read_facts(in_dir("d8.png"), &f));
	CHECK(f.depth == 8 && f.px[0] == 128 && f.px[1] == 64 && f.px[2] == 255);
	fb_free(fb);
}

/* The sRGB display gets an sRGB chunk; other displays map to cICP codes. */
static void t_colour_chunks(void)
{
	struct framebuffer *fb = make_fb();
	struct out_png_opts o = {NULL, NULL, NULL, NULL, NULL, 8, 0};
	struct png_facts f;
	CHECK(MSG(out_png_write(fb, in_dir("srgb.png"), &o, TDG)) == NULL);
	CHECK(read_facts(in_dir("srgb.png"), &f));
	CHECK(f.srgb && !f.cicp);
	CHECK_STR(f.display, "sRGB - Display");
	CHECK_STR(f.view, "ACES 1.0 - SDR Video");
	unsigned char c[4] = {0, 0, 0, 0};
	CHECK(out_png_signal("Display P3", "Standard", c) == OUT_PNG_CICP);
	CHECK(c[0] == 12 && c[1] == 13 && c[2] == 0 && c[3] == 1);
	CHECK(out_png_signal("Rec.2100-PQ - Display", "ACES 1.0 - HDR Video", c) == OUT_PNG_CICP);
	CHECK(c[0] == 9 && c[1] == 16);
	CHECK(out_png_signal("Rec.1886 Rec.709 - Display", "Standard", c) == OUT_PNG_CICP);
	CHECK(c[0] == 1 && c[1] == 1);
	CHECK(out_png_signal("sRGB - Display", "Standard", c) == OUT_PNG_SRGB);
	CHECK(out_png_signal("sRGB - Display", "Raw", c) == OUT_PNG_RAW);
	CHECK(out_png_signal("Projector", "Standard", c) == OUT_PNG_UNKNOWN);
	fb_free(fb);
}

int main(void)
{
	snprintf(dir, sizeof dir, "%s/arvo-png-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
	if (!mkdtemp(dir)) {
		perror("mkdtemp");
		return 1;
	}
	RUN(t_standard);
	RUN(t_aces_default);
	RUN(t_raw);
	RUN(t_highlight_desaturation);
	RUN(t_runs);
	RUN(t_odd_inputs);
	RUN(t_failures);
	RUN(t_png16);
	RUN(t_colour_chunks);
	RUN(t_load_png_rgb);
	RUN(t_load_png_gray_alpha);
	RUN(t_load_png16);
	RUN(t_load_exr);
	RUN(t_load_errors);
	if (getenv("ARVO_KEEP_TMP"))
		return test_done();
	char cmd[128];
	snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
	if (system(cmd) != 0)
		printf("# could not remove %s\n", dir);
	return test_done();
}
