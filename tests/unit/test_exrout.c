/* SPDX-License-Identifier: MIT */
/* test_exrout.c: framebuffer planes, EXR write/read round trips (float and
 * half, every compression), header attributes, and failed writes that must
 * leave an existing file untouched with no temp file behind. */
#include <dirent.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../../tracer/output/exrout.h"
#include "../../tracer/output/framebuffer.h"
#include "test.h"

static char dir[64]; /* scratch directory of this run */

/* dir/name in a static buffer (one at a time). */
static const char *in_dir(const char *name)
{
	static char p[256];
	snprintf(p, sizeof p, "%s/%s", dir, name);
	return p;
}

/* Number of entries of dir whose name contains ".tmp.". */
static int count_tmp(void)
{
	DIR *d = opendir(dir);
	int n = 0;
	for (struct dirent *e; d && (e = readdir(d));)
		n += strstr(e->d_name, ".tmp.") != NULL;
	if (d)
		closedir(d);
	return n;
}

static const char *const names[] = {"caustic.B", "Z", "N.Y", "B", "albedo.R", "direct.G",
                                    "G", "N.X", "caustic.R", "R", "direct.R", "albedo.G",
                                    "direct.B", "N.Z", "caustic.G", "albedo.B"};
#define NNAMES ((int)(sizeof names / sizeof names[0]))

/* A 37x23 framebuffer (odd sizes: partial last chunks) with distinct values
 * per plane, including negatives, large values and small ones. */
static struct framebuffer *make_fb(void)
{
	struct framebuffer *fb = fb_new(37, 23);
	for (int k = 0; k < NNAMES; k++) {
		float *p = fb_plane(fb, names[k]);
		for (int i = 0; i < fb->w * fb->h; i++)
			p[i] = (float)((i * 7919 + k * 104729) % 1000 - 200) * 0.0137f * (float)(k + 1);
	}
	return fb;
}

static void t_fb_order(void)
{
	struct framebuffer *fb = make_fb();
	static const char *const want[] = {"R", "G", "B", "Z", "N.X", "N.Y", "N.Z", "albedo.R",
	                                   "albedo.G", "albedo.B", "caustic.R", "caustic.G",
	                                   "caustic.B", "direct.R", "direct.G", "direct.B"};
	CHECK(fb_count(fb) == NNAMES);
	for (int i = 0; i < NNAMES && i < fb_count(fb); i++)
		CHECK_STR(fb_name(fb, i), want[i]);
	float *r = fb_find(fb, "R");
	CHECK(fb_plane(fb, "R") == r);
	CHECK(fb_find(fb, "nope") == NULL);
	float *x = fb_plane(fb, "x.A");
	CHECK(x && x[0] == 0.0f && x[fb->w * fb->h - 1] == 0.0f);
	CHECK(fb_find(fb, "R") == r); /* pointers survive growth */
	CHECK(fb_name(fb, NNAMES + 5) == NULL);
	fb_free(fb);
}

/* fb_reserve: the next planes made come from one zeroed block, in the
 * order they are made, each its own w*h floats; planes past the reserve,
 * and a second reserve, work as before; fb_free frees each once (the
 * sanitized build checks). 1024x1024: a block of 16 MiB, on huge pages. */
static void t_fb_reserve(void)
{
	struct framebuffer *fb = fb_new(1024, 1024);
	size_t n = (size_t)fb->w * (size_t)fb->h;
	fb_reserve(fb, 4);
	float *p[6];
	for (int k = 0; k < 6; k++) {
		p[k] = fb_plane(fb, names[k]);
		if (k == 2)
			fb_reserve(fb, 8); /* ignored: the block is there */
	}
	for (int k = 1; k < 4; k++)
		CHECK(p[k] == p[0] + n * (size_t)k); /* one block, in order made */
	CHECK(p[4] != p[3] + n && p[5] != p[4] + n);
	int nonzero = 0;
	for (int k = 0; k < 6; k++)
		for (size_t i = 0; i < n; i++)
			nonzero += p[k][i] != 0.0f;
	CHECK(nonzero == 0);
	for (int k = 0; k < 6; k++) /* each plane written whole: none overlaps another */
		for (size_t i = 0; i < n; i++)
			p[k][i] = (float)k;
	int wrong = 0;
	for (int k = 0; k < 6; k++) {
		CHECK(fb_find(fb, names[k]) == p[k]);
		for (size_t i = 0; i < n; i++)
			wrong += p[k][i] != (float)k;
	}
	CHECK(wrong == 0);
	CHECK(fb_count(fb) == 6);
	fb_free(fb);
}

/* Writes fb with opts, reads it back and compares every plane: exact for
 * float (and for Z), within half precision otherwise. */
static void roundtrip(const struct out_exr_opts *o, const char *file)
{
	struct framebuffer *fb = make_fb(), *rd = NULL;
	struct out_exr_info info;
	const char *path = in_dir(file);
	const char *err = MSG(out_exr_write(fb, path, o, TDG));
	CHECK(err == NULL);
	if (err)
		printf("# %s\n", err);
	err = MSG(out_exr_read(path, &rd, &info, TDG));
	CHECK(err == NULL);
	if (!rd) {
		fb_free(fb);
		return;
	}
	CHECK(rd->w == 37 && rd->h == 23 && fb_count(rd) == NNAMES);
	double maxerr = 0;
	for (int k = 0; k < fb_count(fb); k++) {
		const float *a = fb_data(fb, k), *b = fb_find(rd, fb_name(fb, k));
		CHECK_STR(fb_name(rd, k), fb_name(fb, k));
		int exact = !o->half || strcmp(fb_name(fb, k), "Z") == 0;
		for (int i = 0; b && i < fb->w * fb->h; i++) {
			double e = fabs((double)a[i] - (double)b[i]);
			double tol = exact ? 0.0 : fabs(a[i]) * (1.0 / 2048) + 6e-8;
			if (e > tol)
				maxerr = e > maxerr ? e : maxerr;
		}
	}
	CHECK(maxerr == 0.0);
	CHECK(info.half == 0); /* Z is float even in half files */
	CHECK(info.has_chroma);
	CHECK_NEAR(info.chroma[0], 0.64, 1e-6);
	CHECK_NEAR(info.chroma[1], 0.33, 1e-6);
	CHECK_NEAR(info.chroma[2], 0.30, 1e-6);
	CHECK_NEAR(info.chroma[3], 0.60, 1e-6);
	CHECK_NEAR(info.chroma[4], 0.15, 1e-6);
	CHECK_NEAR(info.chroma[5], 0.06, 1e-6);
	CHECK_NEAR(info.chroma[6], 0.3127, 1e-6);
	CHECK_NEAR(info.chroma[7], 0.3290, 1e-6);
	CHECK_STR(info.software, "arvo " ARVO_VERSION);
	CHECK_STR(info.scene, o->scene ? o->scene : "");
	CHECK(count_tmp() == 0);
	fb_free(fb);
	fb_free(rd);
}

static void t_float_all_compressions(void)
{
	static const char *const comp[] = {"zip", "none", "zips", "piz", "rle"};
	for (int c = 0; c < 5; c++) {
		struct out_exr_opts o = {0, OUT_EXR_ZIP, "float test", NULL, 0};
		char file[32];
		CHECK(out_exr_compression_parse(comp[c], &o.compression) == 0);
		CHECK((int)o.compression == c);
		snprintf(file, sizeof file, "f_%s.exr", comp[c]);
		roundtrip(&o, file);
	}
	enum out_exr_compression dummy = OUT_EXR_PIZ;
	CHECK(out_exr_compression_parse("b44", &dummy) == -1 && dummy == OUT_EXR_PIZ);
}

static void t_half(void)
{
	struct out_exr_opts o = {1, OUT_EXR_PIZ, NULL, NULL, 0};
	roundtrip(&o, "h_piz.exr");
	o.compression = OUT_EXR_ZIP;
	roundtrip(&o, "h_zip.exr");
}

/* A 3-channel half file (the case that crashed a partial decode) read back
 * with known values; the RGB-only half file must report half storage. */
static void t_half_rgb(void)
{
	struct framebuffer *fb = fb_new(5, 3), *rd = NULL;
	float *p[3] = {fb_plane(fb, "R"), fb_plane(fb, "G"), fb_plane(fb, "B")};
	for (int i = 0; i < 15; i++)
		p[0][i] = 0.5f * (float)i, p[1][i] = 0.1f, p[2][i] = -1.0f / 3.0f;
	struct out_exr_opts o = {1, OUT_EXR_ZIP, NULL, NULL, 0};
	struct out_exr_info info;
	CHECK(MSG(out_exr_write(fb, in_dir("rgb_half.exr"), &o, TDG)) == NULL);
	CHECK(MSG(out_exr_read(in_dir("rgb_half.exr"), &rd, &info, TDG)) == NULL);
	if (rd) {
		CHECK(info.half == 1);
		CHECK(fb_find(rd, "R")[14] == 7.0f);
		CHECK_NEAR(fb_find(rd, "G")[3], 0.0999755859375, 0); /* nearest half to 0.1 */
		CHECK_NEAR(fb_find(rd, "B")[7], -0.333251953125, 0);
	}
	fb_free(rd);
	fb_free(fb);
}

/* Small images of every size, 1 or 3 channels, every compression, float and
 * half: OpenEXRCore 3.1.5 corrupted chunks whose ZIP output was exactly as
 * long as the raw data (2x4 float, one channel); exrout works around it. */
static void t_small_sizes(void)
{
	int bad = 0, runs = 0;
	for (int half = 0; half < 2; half++)
		for (int c = 0; c < 5; c++)
			for (int nch = 1; nch <= 3; nch += 2)
				for (int w = 1; w <= 9; w++)
					for (int h = 1; h <= 4; h++) {
						static const char *const nm[3] = {"Y", "R", "G"};
						struct framebuffer *fb = fb_new(w, h), *rd = NULL;
						for (int k = 0; k < nch; k++) {
							float *p = fb_plane(fb, nm[k]);
							for (int i = 0; i < w * h; i++)
								p[i] = (float)((i * 37 + k * 11 + w) % 17) * 0.125f - 0.5f;
						}
						struct out_exr_opts o = {half, (enum out_exr_compression)c, NULL, NULL, 0};
						runs++;
						if (out_exr_write(fb, in_dir("s.exr"), &o, TDG) ||
						    out_exr_read(in_dir("s.exr"), &rd, NULL, TDG)) {
							bad++;
						} else {
							for (int k = 0; k < nch; k++)
								if (memcmp(fb_find(fb, nm[k]), fb_find(rd, nm[k]),
								           sizeof(float) * (size_t)(w * h)) != 0) {
									printf("# %dx%d nch %d comp %d half %d differs\n", w, h,
									       nch, c, half);
									bad++;
								}
						}
						fb_free(rd);
						fb_free(fb);
					}
	CHECK(runs == 720 && bad == 0);
}

/* ZIP compresses what it can: a smooth 256x256 float gradient (256 KiB
 * raw) takes well under half its raw size, at zlib level EXR_ZIP_LEVEL,
 * and reads back exactly; a file that stored its chunks raw would fail. */
static void t_zip_compresses(void)
{
	struct framebuffer *fb = fb_new(256, 256), *rd = NULL;
	float *p = fb_plane(fb, "Y");
	for (int i = 0; i < 256 * 256; i++)
		p[i] = (float)(i % 256) / 256.0f + (float)(i / 256) / 65536.0f;
	struct out_exr_opts o = {0, OUT_EXR_ZIP, NULL, NULL, 0};
	struct stat st;
	CHECK(out_exr_write(fb, in_dir("grad.exr"), &o, TDG) == 0);
	CHECK(stat(in_dir("grad.exr"), &st) == 0 && st.st_size > 0 && st.st_size < 256 * 256 * 4 / 2);
	CHECK(out_exr_read(in_dir("grad.exr"), &rd, NULL, TDG) == 0);
	CHECK(rd && memcmp(fb_find(rd, "Y"), p, sizeof(float) * 256 * 256) == 0);
	CHECK(EXR_ZIP_LEVEL == 1);
	fb_free(rd);
	fb_free(fb);
}

/* OIIO's idiff accepts our files and sees float == half for exact values. */
static void t_idiff(void)
{
	if (system("command -v idiff >/dev/null 2>&1") != 0) {
		printf("# skip: idiff not installed\n");
		return;
	}
	char cmd[512];
	snprintf(cmd, sizeof cmd, "cd %s && idiff -q f_zip.exr f_zip.exr >/dev/null 2>&1", dir);
	CHECK(system(cmd) == 0);
	snprintf(cmd, sizeof cmd, "cd %s && idiff -q f_piz.exr f_rle.exr >/dev/null 2>&1", dir);
	CHECK(system(cmd) == 0);
	snprintf(cmd, sizeof cmd, "cd %s && exrheader f_zip.exr 2>&1 | grep -q 'software.*arvo'", dir);
	CHECK(system(cmd) == 0);
}

/* Writes "old" bytes to path. */
static void put_old(const char *path)
{
	FILE *f = fopen(path, "wb");
	if (f) {
		fputs("old contents", f);
		fclose(f);
	}
}

/* True when path still holds exactly "old contents". */
static int is_old(const char *path)
{
	char buf[64] = "";
	FILE *f = fopen(path, "rb");
	size_t n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
	if (f)
		fclose(f);
	buf[n] = '\0';
	return strcmp(buf, "old contents") == 0;
}

/* A write that fails half-way (file size limit) must not touch the old file. */
static void t_failed_write_midway(void)
{
	char path[256];
	snprintf(path, sizeof path, "%s", in_dir("keep.exr"));
	put_old(path);
	struct framebuffer *fb = fb_new(256, 256);
	float *r = fb_plane(fb, "R");
	for (int i = 0; i < 256 * 256; i++)
		r[i] = (float)i;
	struct rlimit old, lim;
	getrlimit(RLIMIT_FSIZE, &old);
	lim = old;
	lim.rlim_cur = 4096;
	signal(SIGXFSZ, SIG_IGN);
	setrlimit(RLIMIT_FSIZE, &lim);
	struct out_exr_opts o = {0, OUT_EXR_NONE, NULL, NULL, 0};
	const char *err = MSG(out_exr_write(fb, path, &o, TDG));
	setrlimit(RLIMIT_FSIZE, &old);
	CHECK(err != NULL);
	if (err) {
		printf("# expected error: %s\n", err);
		CHECK(strstr(err, "keep.exr") != NULL);
	}
	CHECK(is_old(path));
	CHECK(count_tmp() == 0);
	fb_free(fb);
}

/* Unwritable or missing directories give an error, never a crash. */
static void t_failed_write_dir(void)
{
	struct framebuffer *fb = fb_new(4, 4);
	fb_plane(fb, "R");
	char path[256];
	snprintf(path, sizeof path, "%s/no/such/dir/x.exr", dir);
	const char *err = MSG(out_exr_write(fb, path, NULL, TDG));
	CHECK(err != NULL && strstr(err, "no/such/dir/x.exr") != NULL);
	if (geteuid() != 0) { /* root can write anywhere: skip the chmod case */
		char sub[256];
		snprintf(sub, sizeof sub, "%s/ro", dir);
		mkdir(sub, 0755);
		snprintf(path, sizeof path, "%s/ro/keep.exr", dir);
		put_old(path);
		chmod(sub, 0555);
		CHECK(MSG(out_exr_write(fb, path, NULL, TDG)) != NULL);
		CHECK(is_old(path));
		chmod(sub, 0755);
		unlink(path);
		rmdir(sub);
	}
	struct framebuffer *empty = fb_new(2, 2);
	CHECK(MSG(out_exr_write(empty, in_dir("empty.exr"), NULL, TDG)) != NULL);
	CHECK(access(in_dir("empty.exr"), F_OK) != 0);
	fb_free(empty);
	fb_free(fb);
}

static void t_read_errors(void)
{
	struct framebuffer *rd = (struct framebuffer *)&rd;
	const char *err = MSG(out_exr_read(in_dir("missing.exr"), &rd, NULL, TDG));
	CHECK(err != NULL && rd == NULL);
	put_old(in_dir("junk.exr"));
	err = MSG(out_exr_read(in_dir("junk.exr"), &rd, NULL, TDG));
	CHECK(err != NULL && rd == NULL);
	if (err)
		printf("# expected error: %s\n", err);
}

/* A region of a frame keeps its place (data window) and the frame (display
 * window) through a write and a read, with every header attribute. */
static void t_region_and_meta(void)
{
	struct framebuffer *fb = fb_new(3, 2);
	fb->x0 = 5, fb->y0 = 7, fb->full_w = 20, fb->full_h = 10;
	float *r = fb_plane(fb, "R");
	for (int i = 0; i < 6; i++)
		r[i] = (float)i + 0.5f;
	static struct out_exr_meta m;
	m.has_camera = 1;
	for (int i = 0; i < 16; i++)
		m.world_to_camera[i] = (float)i, m.world_to_ndc[i] = (float)(i * 2), m.camera_to_world[i] = (float)-i;
	out_meta_add(&m, "arvo:spp", "%d", 4);
	out_meta_add(&m, "arvo:method", "%s", "shaft");
	struct out_exr_opts o = {0, OUT_EXR_ZIP, "s.scn", &m, 0};
	struct framebuffer *rd = NULL;
	static struct out_exr_info info;
	CHECK(MSG(out_exr_write(fb, in_dir("region.exr"), &o, TDG)) == NULL);
	CHECK(MSG(out_exr_read(in_dir("region.exr"), &rd, &info, TDG)) == NULL);
	if (rd) {
		CHECK(rd->w == 3 && rd->h == 2 && rd->x0 == 5 && rd->y0 == 7);
		CHECK(rd->full_w == 20 && rd->full_h == 10);
		CHECK(memcmp(fb_find(rd, "R"), r, 6 * sizeof(float)) == 0);
	}
	CHECK(info.meta.has_camera);
	CHECK(info.meta.world_to_camera[7] == 7 && info.meta.world_to_ndc[15] == 30 &&
	      info.meta.camera_to_world[3] == -3);
	CHECK(info.meta.n == 3); /* arvo:spp, arvo:method and arvo:scene, in file order */
	CHECK_STR(info.meta.key[0], "arvo:scene");
	CHECK_STR(info.meta.val[0], "s.scn");
	CHECK_STR(info.meta.key[1], "arvo:spp");
	CHECK_STR(info.meta.val[1], "4");
	CHECK_STR(info.meta.val[2], "shaft");
	fb_free(rd);
	fb_free(fb);
}

int main(void)
{
	snprintf(dir, sizeof dir, "%s/arvo-exr-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
	if (!mkdtemp(dir)) {
		perror("mkdtemp");
		return 1;
	}
	RUN(t_fb_order);
	RUN(t_fb_reserve);
	RUN(t_float_all_compressions);
	RUN(t_half);
	RUN(t_half_rgb);
	RUN(t_small_sizes);
	RUN(t_zip_compresses);
	RUN(t_idiff);
	RUN(t_failed_write_midway);
	RUN(t_failed_write_dir);
	RUN(t_read_errors);
	RUN(t_region_and_meta);
	if (getenv("ARVO_KEEP_TMP"))
		return test_done();
	char cmd[128];
	snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
	if (system(cmd) != 0)
		printf("# could not remove %s\n", dir);
	return test_done();
}
