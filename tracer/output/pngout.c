/* SPDX-License-Identifier: MIT */
/* pngout.c: beauty → OCIO display/view → clamp → 8 bits → PNG (libpng). */
#include "pngout.h"

#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include <png.h>

#include "../../common/arena.h"
#include "../../common/pool.h"
#include "exrout.h"
#include "ocio_shim.h"
#include "tmpfile.h"

/* ================= config resolution ================= */

static char default_cfg[PATH_MAX]; /* found shipped config, or "" */
static pthread_once_t default_once = PTHREAD_ONCE_INIT;

/* True when dir/rel is a readable file; leaves the joined path in out. */
static int try_path(char *out, size_t n, const char *dir, const char *rel)
{
	int k = snprintf(out, n, "%s/%s", dir, rel);
	return k > 0 && (size_t)k < n && access(out, R_OK) == 0;
}

/* Looks beside the executable: <dir>/stdlib-scenes, <dir>/../share/arvo and
 * the stdlib-scenes of up to three parents of dir. */
static int find_near_exe(char *out, size_t n)
{
	char dir[PATH_MAX];
	ssize_t len = readlink("/proc/self/exe", dir, sizeof dir - 1);
	if (len <= 0)
		return 0;
	dir[len] = '\0';
	char *slash = strrchr(dir, '/');
	if (!slash)
		return 0;
	*slash = '\0';
	if (try_path(out, n, dir, "../share/arvo/ocio/config.ocio"))
		return 1;
	for (int up = 0; up < 4; up++) {
		if (try_path(out, n, dir, "stdlib-scenes/ocio/config.ocio"))
			return 1;
		if (!(slash = strrchr(dir, '/')) || slash == dir)
			break;
		*slash = '\0';
	}
	return 0;
}

/* Runs once: fills default_cfg following the documented search order. */
static void find_default(void)
{
	const char *env = getenv("ARVO_DATA_DIR");
	if (env && *env && try_path(default_cfg, sizeof default_cfg, env, "ocio/config.ocio"))
		return;
#ifdef ARVO_DATA_DIR
	if (try_path(default_cfg, sizeof default_cfg, ARVO_DATA_DIR, "ocio/config.ocio"))
		return;
#endif
	if (find_near_exe(default_cfg, sizeof default_cfg))
		return;
	default_cfg[0] = '\0';
}

/* Thread-safe: the search runs once per process. */
const char *out_default_ocio_config(void)
{
	pthread_once(&default_once, find_default);
	return default_cfg[0] ? default_cfg : NULL;
}

/* explicit > $OCIO > shipped. */
const char *out_ocio_config_path(const char *explicit_path)
{
	if (explicit_path && *explicit_path)
		return explicit_path;
	const char *env = getenv("OCIO");
	if (env && *env)
		return env;
	return out_default_ocio_config();
}

/* Resolves the path and loads it, naming the path in any error. */
int out_ocio_load(const char *explicit_path, struct ocio_config **cfg, struct diag *dg)
{
	char msg[512];
	const char *path = out_ocio_config_path(explicit_path);
	*cfg = NULL;
	if (!path)
		return diag_fail(dg, FAIL_INPUT, srcloc_none(), "no OCIO config: give --ocio-config, set $OCIO, "
		                 "or install ocio/config.ocio (set $ARVO_DATA_DIR to its directory)");
	*cfg = ocio_config_load(path, msg, sizeof msg);
	if (*cfg)
		return 0;
	return diag_fail(dg, FAIL_INPUT, srcloc_none(), "cannot load OCIO config '%s': %s", path, msg);
}

/* ================= display and view ================= */

/* An error naming the bad choice and listing every valid display/view. */
static int bad_choice(const struct ocio_config *cfg, const char *what, const char *name, struct diag *dg)
{
	char list[1400];
	ocio_describe_views(cfg, list, sizeof list);
	return diag_fail(dg, FAIL_USAGE, srcloc_none(), "unknown OCIO %s '%s'; valid displays and views:\n%s",
	                 what, name, list);
}

/* True when view is one of display's views. */
static int has_view(const struct ocio_config *cfg, const char *display, const char *view)
{
	for (int i = 0; i < ocio_view_count(cfg, display); i++)
		if (strcmp(ocio_view_name(cfg, display, i), view) == 0)
			return 1;
	return 0;
}

/* Defaults fall back to the config's own defaults when our names are absent. */
int out_ocio_pick_view(const struct ocio_config *cfg, const char *display, const char *view,
                       const char **disp_out, const char **view_out, struct diag *dg)
{
	if (!display)
		display = ocio_view_count(cfg, OUT_DEFAULT_DISPLAY) > 0 ? OUT_DEFAULT_DISPLAY
		                                                        : ocio_default_display(cfg);
	if (!display || ocio_view_count(cfg, display) == 0)
		return bad_choice(cfg, "display", display ? display : "(none)", dg);
	if (!view)
		view = has_view(cfg, display, OUT_DEFAULT_VIEW) ? OUT_DEFAULT_VIEW
		                                                : ocio_default_view(cfg, display);
	if (!view || !has_view(cfg, display, view))
		return bad_choice(cfg, "view", view ? view : "(none)", dg);
	*disp_out = display;
	*view_out = view;
	return 0;
}

/* For --help: load, describe, free. */
int out_ocio_list_views(const char *explicit_path, char *buf, size_t len, struct diag *dg)
{
	struct ocio_config *cfg;
	int err = out_ocio_load(explicit_path, &cfg, dg);
	if (err)
		return err;
	ocio_describe_views(cfg, buf, len);
	ocio_config_free(cfg);
	return 0;
}

/* ================= pixels ================= */

/* Display value → byte: NaN and negatives → 0, clamp at 1, round. */
static unsigned char quantise(float v)
{
	if (!(v > 0.0f))
		return 0;
	if (v >= 1.0f)
		return 255;
	return (unsigned char)(v * 255.0f + 0.5f);
}

/* Packs R,G,B planes into interleaved floats (missing G/B read as 0). */
static float *pack_rgb(const struct framebuffer *fb, size_t n)
{
	const float *pl[3] = {fb_find(fb, "R"), fb_find(fb, "G"), fb_find(fb, "B")};
	float *rgb = mem_alloc_huge(n * 3 * sizeof(float)); /* written whole: fewer page faults */
	for (size_t i = 0; i < n; i++)
		for (int c = 0; c < 3; c++)
			rgb[3 * i + (size_t)c] = pl[c] ? pl[c][i] : 0.0f;
	return rgb;
}

/* Builds the display processor for opts; *cfg must be freed by the caller.
 * The display and view used are stored in disp and view (the config's
 * strings, valid while *cfg lives). */
static int make_proc(const struct out_png_opts *o, struct ocio_config **cfg, struct ocio_proc **proc,
                     const char **disp, const char **view, struct diag *dg)
{
	char msg[512];
	int err = out_ocio_load(o->ocio_config, cfg, dg);
	if (!err)
		err = out_ocio_pick_view(*cfg, o->display, o->view, disp, view, dg);
	if (!err && !o->view && o->scene_view && has_view(*cfg, *disp, o->scene_view))
		*view = o->scene_view;
	if (err)
		return err;
	*proc = ocio_proc_display(*cfg, o->source, *disp, *view, msg, sizeof msg);
	return *proc ? 0 : diag_fail(dg, FAIL_INPUT, srcloc_none(), "OCIO: %s", msg);
}

/* What the PNG records of the display encoding (out_png_tags). */
struct png_tags {
	char display[128], view[128]; /* the OCIO display and view */
};

/* pack → OCIO display/view; rgb gets w*h*3 display values (free it). */
/* The OCIO transform over the image in chunks of pixels on several
 * threads: each pixel is transformed alone, so the result is the same for
 * any split. */
#define OCIO_CHUNK 16384
struct ocio_job {
	const struct ocio_proc *proc;
	float *rgb;
	long npix;
	atomic_int failed;
	char msg[512];
	pthread_mutex_t lock; /* guards msg */
};

/* Transforms px[0..n) in place, a run of equal pixels (a background, a
 * flat wall: bit for bit the same floats) once: the runs' first pixels are
 * transformed together, then copied over their runs. Each pixel is
 * transformed alone, so the result is the one of transforming them all. */
static int apply_runs(const struct ocio_proc *proc, float *px, long n, char *msg, size_t len)
{
	float *u = malloc(sizeof *u * 3 * (size_t)n);
	int32_t *run = malloc(sizeof *run * (size_t)n);
	if (!u || !run) { /* no room to collapse: every pixel */
		free(u), free(run);
		return ocio_proc_apply_rgb(proc, px, n, msg, len);
	}
	long m = 0;
	for (long k = 0; k < n; k++) {
		if (m > 0 && memcmp(px + 3 * k, u + 3 * (m - 1), 3 * sizeof *u) == 0) {
			run[m - 1]++;
			continue;
		}
		memcpy(u + 3 * m, px + 3 * k, 3 * sizeof *u);
		run[m++] = 1;
	}
	int rv = ocio_proc_apply_rgb(proc, u, m, msg, len);
	for (long r = 0, k = 0; rv == 0 && r < m; r++)
		for (int32_t c = 0; c < run[r]; c++, k++)
			memcpy(px + 3 * k, u + 3 * r, 3 * sizeof *u);
	free(u), free(run);
	return rv;
}

static void ocio_chunk(void *arg, long i, int worker)
{
	(void)worker;
	struct ocio_job *j = arg;
	long at = i * OCIO_CHUNK, n = j->npix - at < OCIO_CHUNK ? j->npix - at : OCIO_CHUNK;
	char msg[512];
	if (apply_runs(j->proc, j->rgb + 3 * at, n, msg, sizeof msg) != 0) {
		pthread_mutex_lock(&j->lock);
		if (!atomic_load(&j->failed))
			snprintf(j->msg, sizeof j->msg, "%s", msg);
		atomic_store(&j->failed, 1);
		pthread_mutex_unlock(&j->lock);
	}
}

static int apply_parallel(const struct ocio_proc *proc, float *rgb, long npix, int threads, char *err,
                          size_t errsz)
{
	struct ocio_job j = {.proc = proc, .rgb = rgb, .npix = npix};
	atomic_init(&j.failed, 0);
	pthread_mutex_init(&j.lock, NULL);
	parallel_for((npix + OCIO_CHUNK - 1) / OCIO_CHUNK, pool_threads(threads), ocio_chunk, &j);
	pthread_mutex_destroy(&j.lock);
	if (atomic_load(&j.failed)) {
		snprintf(err, errsz, "%s", j.msg);
		return -1;
	}
	return 0;
}

static int encode_float(const struct framebuffer *fb, const struct out_png_opts *o, float **rgb,
                        struct png_tags *tags, struct diag *dg)
{
	*rgb = NULL;
	if (!fb_find(fb, "R"))
		return diag_fail(dg, FAIL_INTERNAL, srcloc_none(), "the image has no beauty channels (R, G, B)");
	struct ocio_config *cfg = NULL;
	struct ocio_proc *proc = NULL;
	const char *disp = NULL, *view = NULL;
	int err = make_proc(o, &cfg, &proc, &disp, &view, dg);
	if (!err) {
		char msg[512];
		size_t n = (size_t)fb->w * (size_t)fb->h;
		*rgb = pack_rgb(fb, n);
		if (apply_parallel(proc, *rgb, (long)n, o->threads, msg, sizeof msg) != 0) {
			err = diag_fail(dg, FAIL_INPUT, srcloc_none(), "OCIO: %s", msg);
			free(*rgb);
			*rgb = NULL;
		}
		if (tags) {
			snprintf(tags->display, sizeof tags->display, "%s", disp);
			snprintf(tags->view, sizeof tags->view, "%s", view);
		}
	}
	ocio_proc_free(proc);
	ocio_config_free(cfg);
	return err;
}

/* pack → OCIO display/view → clamp → round to bytes (deterministic, no dither). */
int out_png_encode(const struct framebuffer *fb, const struct out_png_opts *opts, unsigned char *rgb8,
                   struct diag *dg)
{
	static const struct out_png_opts defaults = {NULL, NULL, NULL, NULL, NULL, 8, 0};
	float *rgb;
	int err = encode_float(fb, opts ? opts : &defaults, &rgb, NULL, dg);
	for (size_t i = 0; !err && i < 3 * (size_t)fb->w * (size_t)fb->h; i++)
		rgb8[i] = quantise(rgb[i]);
	free(rgb);
	return err;
}

/* Display value → 16 bits, stored big-endian as PNG wants. */
static void quantise16(float v, unsigned char *out)
{
	unsigned q = !(v > 0.0f) ? 0 : v >= 1.0f ? 65535 : (unsigned)(v * 65535.0f + 0.5f);
	out[0] = (unsigned char)(q >> 8);
	out[1] = (unsigned char)(q & 255);
}

int out_png_signal(const char *display, const char *view, unsigned char cicp[4])
{
	static const struct { const char *name; unsigned char prim, tf; } known[] = {
		{"P3", 12, 13}, {"Rec.1886", 1, 1}, {"BT.1886", 1, 1}, {"Rec.709", 1, 1},
		{"PQ", 9, 16}, {"ST2084", 9, 16}, {"HLG", 9, 18}};
	if (view && !strcasecmp(view, "Raw"))
		return OUT_PNG_RAW;
	if (!display)
		return OUT_PNG_UNKNOWN;
	for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
		if (strstr(display, known[i].name)) {
			cicp[0] = known[i].prim, cicp[1] = known[i].tf, cicp[2] = 0, cicp[3] = 1;
			return OUT_PNG_CICP;
		}
	return strstr(display, "sRGB") ? OUT_PNG_SRGB : OUT_PNG_UNKNOWN;
}

/* ================= libpng ================= */

struct png_err {
	jmp_buf jb;     /* where libpng errors return to */
	char msg[256];  /* libpng's message */
};

/* libpng error callback: records the message and unwinds to write_rows. */
static void on_png_error(png_structp png, png_const_charp msg)
{
	struct png_err *e = png_get_error_ptr(png);
	snprintf(e->msg, sizeof e->msg, "%s", msg);
	longjmp(e->jb, 1);
}

/* libpng warnings are not worth a message on a render's stderr. */
static void on_png_warning(png_structp png, png_const_charp msg)
{
	(void)png;
	(void)msg;
}

/* The colour chunks for the display: sRGB, or cICP (an unknown chunk to
 * libpng 1.6.39, written before PLTE/IDAT); none for the Raw view (scene
 * values in the config's scene-linear space, which no chunk names) or for
 * a display arvo does not recognise. */
static void set_colour_chunks(png_structp png, png_infop info, const struct png_tags *t,
                              png_unknown_chunk *cicp)
{
	switch (out_png_signal(t->display, t->view, cicp->data)) {
	case OUT_PNG_SRGB:
		png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
		break;
	case OUT_PNG_CICP:
		memcpy(cicp->name, "cICP", 5);
		cicp->size = 4;
		cicp->location = PNG_HAVE_IHDR;
		png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_ALWAYS, (png_const_bytep) "cICP", 1);
		png_set_unknown_chunks(png, info, cicp, 1);
		break;
	default:
		break;
	}
}

/* Writes w*h RGB pixels (depth 8 or 16 bits, rows packed) as a PNG to fp;
 * returns 0 or -1 with e->msg set. */
static int write_rows(FILE *fp, const unsigned char *px, int w, int h, int depth,
                      const struct png_tags *tags, struct png_err *e)
{
	png_structp png =
	    png_create_write_struct(PNG_LIBPNG_VER_STRING, e, on_png_error, on_png_warning);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	if (!info) {
		png_destroy_write_struct(&png, NULL);
		snprintf(e->msg, sizeof e->msg, "libpng: out of memory");
		return -1;
	}
	if (setjmp(e->jb)) {
		png_destroy_write_struct(&png, &info);
		return -1;
	}
	png_init_io(png, fp);
	png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, PNG_COLOR_TYPE_RGB,
	             PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	static unsigned char cicp_data[4];
	png_unknown_chunk cicp = {.data = cicp_data};
	set_colour_chunks(png, info, tags, &cicp);
	png_text text[3] = {
		{.compression = PNG_TEXT_COMPRESSION_NONE, .key = (png_charp) "Software",
		 .text = (png_charp) "arvo " ARVO_VERSION},
		{.compression = PNG_TEXT_COMPRESSION_NONE, .key = (png_charp) "OCIO display",
		 .text = (png_charp)tags->display},
		{.compression = PNG_TEXT_COMPRESSION_NONE, .key = (png_charp) "OCIO view",
		 .text = (png_charp)tags->view}};
	png_set_text(png, info, text, 3);
	png_write_info(png, info);
	size_t row = (size_t)w * 3 * (size_t)(depth / 8);
	for (int y = 0; y < h; y++)
		png_write_row(png, px + (size_t)y * row);
	png_write_end(png, info);
	png_destroy_write_struct(&png, &info);
	return 0;
}

/* Writes the PNG into the already-open temp file fd (which it closes). */
static int write_png_fd(int fd, const char *path, const unsigned char *px, int w, int h, int depth,
                        const struct png_tags *tags, struct diag *dg)
{
	struct png_err e = {.msg = ""};
	FILE *fp = fdopen(fd, "wb");
	if (!fp) {
		close(fd);
		return diag_fail(dg, FAIL_WRITE, srcloc_none(), "cannot write '%s': %s", path, strerror(errno));
	}
	int rc = write_rows(fp, px, w, h, depth, tags, &e);
	if (fflush(fp) != 0 || ferror(fp)) {
		if (rc == 0)
			snprintf(e.msg, sizeof e.msg, "%s", strerror(errno));
		rc = -1;
	}
	if (fclose(fp) != 0 && rc == 0) {
		snprintf(e.msg, sizeof e.msg, "%s", strerror(errno));
		rc = -1;
	}
	return rc ? diag_fail(dg, FAIL_WRITE, srcloc_none(), "cannot write '%s': %s", path, e.msg) : 0;
}

/* Encodes first (so OCIO errors never create a file), then temp file + rename. */
int out_png_write(const struct framebuffer *fb, const char *path, const struct out_png_opts *opts,
                  struct diag *dg)
{
	static const struct out_png_opts defaults = {NULL, NULL, NULL, NULL, NULL, 8, 0};
	const struct out_png_opts *o = opts ? opts : &defaults;
	int depth = o->depth == 16 ? 16 : 8;
	size_t n = (size_t)fb->w * (size_t)fb->h * 3;
	struct png_tags tags;
	float *rgb;
	int err = encode_float(fb, o, &rgb, &tags, dg);
	if (err)
		return err;
	unsigned char *px = mem_alloc_huge(n * (size_t)(depth / 8));
	for (size_t i = 0; i < n; i++) {
		if (depth == 16)
			quantise16(rgb[i], px + 2 * i);
		else
			px[i] = quantise(rgb[i]);
	}
	free(rgb);
	char tmp[4096];
	int fd = out_tmp_create(path, tmp, sizeof tmp);
	if (fd < 0) {
		err = diag_fail(dg, FAIL_CREATE, srcloc_none(), "cannot create '%s': %s", path, strerror(errno));
	} else {
		err = write_png_fd(fd, path, px, fb->w, fb->h, depth, &tags, dg);
		if (out_tmp_finish(tmp, path, err == 0) != 0)
			err = diag_fail(dg, FAIL_WRITE, srcloc_none(), "cannot write '%s': rename: %s", path,
			                strerror(errno));
	}
	free(px);
	return err;
}
