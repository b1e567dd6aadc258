/* SPDX-License-Identifier: MIT */
/* test_render.c: analytic renders with known answers (docs/design.md §11).
 * Each scene under tests/render/ is evaluated and rendered in-process,
 * written as a float EXR, read back, and checked pixel by pixel:
 *   - plane_point: the direct layer is I·cosθ/d² at every pixel to 0.1 %;
 *   - sphere_inside: the radiance is ρ·I/(π·r²) everywhere;
 *   - mirror_a/b: a mirror shows exactly the reflected scene;
 *   - slab_a/b: a clear glass slab shifts the image by t·(tanθ - tanθt);
 *   - flags: no_image objects still cast shadows, no_shadow ones do not;
 *   - fn_pattern: a function pattern shows the function's value;
 *   - iso_sphere_a/b: the isosurface of x² + y² + z² = 1 renders as the
 *     sphere does, its caustic included;
 *   - g_glass, flags: a beauty-only render has the R G B of a full one;
 *   - bench/eye grid and spheres, g_lights: a block of pixels shaded from
 *     one packet (eye_pixels) has the bits of each pixel shaded alone
 *     (eye_pixel). */
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "../../common/diag.h"
#include "../../eval/eval.h"
#include "../../tracer/output/exrout.h"
#include "../../tracer/bvh.h"
#include "../../tracer/eyepass.h"
#include "../../tracer/material.h"
#include "../../tracer/render.h"
#include "test.h"

/* Renders tests/render/<name>.scn at w×h with spp samples on nthreads
 * threads, in-process (no file), R G B alone when beauty_only is set. */
static struct framebuffer *render_mem(const char *name, int w, int h, int spp, int nthreads, bool beauty_only)
{
	char path[256];
	snprintf(path, sizeof path, "tests/render/%s.scn", name);
	struct eval_options eo;
	eval_default_options(&eo);
	eo.width = w;
	eo.height = h;
	struct diag dg;
	diag_init(&dg, stdout);
	struct scene s;
	if (eval_scene(path, &eo, &dg, &s) != 0) {
		printf("#   cannot evaluate %s\n", path);
		return NULL;
	}
	struct render_opts ro = {.width = w, .height = h, .spp = spp, .threads = nthreads, .quiet = 1,
	                         .beauty_only = beauty_only};
	struct framebuffer *fb = NULL;
	const char *err = MSG(render(&s, &ro, TDG, &fb, NULL));
	if (err)
		printf("#   %s: %s\n", name, err);
	scene_free(&s);
	return fb;
}

/* render_mem, all layers, round-tripped through an EXR: the planes read
 * back. */
static struct framebuffer *render_file(const char *name, int w, int h, int spp, int nthreads)
{
	char out[64];
	snprintf(out, sizeof out, "/tmp/arvo-test-render-%ld.exr", (long)getpid());
	struct framebuffer *fb = render_mem(name, w, h, spp, nthreads, false), *back = NULL;
	if (!fb)
		return NULL;
	const char *err = MSG(out_exr_write(fb, out, NULL, TDG));
	if (!err)
		err = MSG(out_exr_read(out, &back, NULL, TDG));
	if (err)
		printf("#   %s: %s\n", name, err);
	remove(out);
	fb_free(fb);
	return back;
}

/* The worst relative error of plane a against expected values. */
static double worst(const float *a, const double *want, int n)
{
	double m = 0;
	for (int i = 0; i < n; i++) {
		double e = fabs(a[i] - want[i]) / fmax(fabs(want[i]), 1e-12);
		m = e > m ? e : m;
	}
	return m;
}

/* Floor under a point light: E = I·h/d³ at the floor point of each pixel. */
static void t_plane_direct(void)
{
	const int w = 64, h = 48;
	struct framebuffer *fb = render_file("plane_point", w, h, 1, 3);
	CHECK(fb != NULL);
	if (!fb)
		return;
	const double I[3] = {10, 5, 2.5}, lx = 0.3, ly = 2, lz = 0.2;
	const char *names[3] = {"direct.R", "direct.G", "direct.B"};
	double *want = malloc(sizeof *want * (size_t)(w * h));
	for (int c = 0; c < 3; c++) {
		for (int y = 0; y < h; y++)
			for (int x = 0; x < w; x++) {
				double X = ((x + 0.5) / w - 0.5) * 4, Z = (0.5 - (y + 0.5) / h) * 3;
				double d = sqrt((X - lx) * (X - lx) + ly * ly + (Z - lz) * (Z - lz));
				want[y * w + x] = I[c] * ly / (d * d * d);
			}
		float *p = fb_find(fb, names[c]);
		CHECK(p != NULL);
		if (p)
			CHECK(worst(p, want, w * h) < 1e-3);
	}
	float *r = fb_find(fb, "R");
	CHECK(r && fabs(r[(h / 2) * w + w / 2] - fb_find(fb, "direct.R")[(h / 2) * w + w / 2] / M_PI) < 1e-4);
	free(want);
	fb_free(fb);
}

/* Inside a diffuse sphere around a point light: L = ρ·I/(π·r²). */
static void t_sphere_inside(void)
{
	const int w = 40, h = 30;
	struct framebuffer *fb = render_file("sphere_inside", w, h, 2, 2);
	CHECK(fb != NULL);
	if (!fb)
		return;
	double L = 0.5 * 8 / (M_PI * 4), *want = malloc(sizeof *want * (size_t)(w * h));
	for (int i = 0; i < w * h; i++)
		want[i] = L;
	const char *names[3] = {"R", "G", "B"};
	for (int c = 0; c < 3; c++) {
		float *p = fb_find(fb, names[c]);
		CHECK(p && worst(p, want, w * h) < 1e-4);
	}
	free(want);
	fb_free(fb);
}

/* A perfect mirror reproduces the mirrored scene pixel for pixel. */
static void t_mirror(void)
{
	const int w = 48, h = 36;
	struct framebuffer *a = render_file("mirror_a", w, h, 1, 2);
	struct framebuffer *b = render_file("mirror_b", w, h, 1, 2);
	CHECK(a && b);
	if (!a || !b)
		return;
	const char *names[3] = {"R", "G", "B"};
	int lit = 0;
	double m = 0;
	for (int c = 0; c < 3; c++) {
		float *pa = fb_find(a, names[c]), *pb = fb_find(b, names[c]);
		for (int i = 0; i < w * h; i++) {
			m = fmax(m, fabs(pa[i] - pb[i]));
			lit += pb[i] > 0.05f;
		}
	}
	CHECK(m < 1e-5);
	CHECK(lit > w * h / 4); /* the sphere is really in view */
	fb_free(a);
	fb_free(b);
}

/* The largest difference of R, G, B between two renders, and how many
 * samples of b are lit. */
static double max_diff(struct framebuffer *a, struct framebuffer *b, int *lit)
{
	const char *names[3] = {"R", "G", "B"};
	double m = 0;
	*lit = 0;
	for (int c = 0; c < 3; c++) {
		float *pa = fb_find(a, names[c]), *pb = fb_find(b, names[c]);
		for (int i = 0; i < a->w * a->h; i++) {
			m = fmax(m, fabs(pa[i] - pb[i]));
			*lit += pb[i] > 0.05f;
		}
	}
	return m;
}

/* A glass slab displaces the image it is looked through. */
static void t_slab(void)
{
	const int w = 48, h = 36;
	struct framebuffer *a = render_file("slab_a", w, h, 1, 2);
	struct framebuffer *b = render_file("slab_b", w, h, 1, 2);
	CHECK(a && b);
	if (!a || !b)
		return;
	int lit;
	CHECK(max_diff(a, b, &lit) < 1e-4);
	CHECK(lit > w * h);
	fb_free(a);
	fb_free(b);
}

/* no_image: invisible to the camera but shadowing; no_shadow: the reverse. */
static void t_flags(void)
{
	const int w = 64, h = 48, row = 24 * w;
	struct framebuffer *fb = render_file("flags", w, h, 1, 2);
	CHECK(fb != NULL);
	if (!fb)
		return;
	float *z = fb_find(fb, "Z"), *d = fb_find(fb, "direct.R"), *g = fb_find(fb, "G");
	int under_hidden = row + 16, hidden_shadow = row + 10, seen = row + 48, no_shadow = row + 53;
	CHECK_NEAR(z[under_hidden], 5, 1e-3); /* the floor, through the no_image sphere */
	CHECK(fb_find(fb, "R")[under_hidden] == g[under_hidden]); /* white floor, not red */
	CHECK(d[hidden_shadow] == 0); /* its shadow */
	CHECK(z[seen] < 4.8f && g[seen] > 0.9f); /* the no_shadow sphere is seen */
	CHECK(d[no_shadow] > 0.1f);             /* and casts nothing */
	fb_free(fb);
}

/* pigment { function { … } } on a self-lit plane: each pixel is the
 * function at the pixel's centre, 0.4·(x+1) + 0.15·y². */
static void t_function_pattern(void)
{
	const int w = 16, h = 12;
	struct framebuffer *fb = render_file("fn_pattern", w, h, 1, 2);
	CHECK(fb != NULL);
	if (!fb)
		return;
	double *want = malloc(sizeof *want * (size_t)(w * h));
	for (int y = 0; y < h; y++)
		for (int x = 0; x < w; x++) {
			double X = (x + 0.5) / w * 2 - 1, Y = 1 - (y + 0.5) / h * 2;
			want[y * w + x] = 0.4 * (X + 1) + 0.15 * Y * Y;
		}
	float *p = fb_find(fb, "G");
	CHECK(p && worst(p, want, w * h) < 1e-4);
	free(want);
	fb_free(fb);
}

/* The unit sphere as a sphere and as an isosurface, lit directly and by
 * the caustic of a glass sphere above it: the same image and caustic. */
static void t_isosurface_sphere(void)
{
	const int w = 48, h = 36;
	struct framebuffer *a = render_file("iso_sphere_a", w, h, 1, 2), *b = render_file("iso_sphere_b", w, h, 1, 2);
	CHECK(a && b);
	if (a && b) {
		const char *names[4] = {"R", "G", "B", "caustic.R"};
		double peak = 0;
		for (int c = 0; c < 4; c++) {
			const float *pa = fb_find(a, names[c]), *pb = fb_find(b, names[c]);
			CHECK(pa && pb);
			for (int i = 0; pa && pb && i < w * h; i++) {
				CHECK_NEAR(pb[i], pa[i], 1e-4 * (1 + fabs(pa[i])));
				if (c == 3)
					peak = fmax(peak, pa[i]);
			}
		}
		CHECK(peak > 1); /* there is a caustic to compare */
	}
	if (a)
		fb_free(a);
	if (b)
		fb_free(b);
}

/* A beauty-only render (PNG output: no AOV layers, misses written as the
 * background without shading) has exactly the R G B of a full render, with
 * one sample per pixel and with several: background, diffuse, glass and
 * mirror pixels alike. */
static void t_beauty_only(void)
{
	const char *names[] = {"g_glass", "flags"};
	for (int k = 0; k < 2; k++)
		for (int spp = 1; spp <= 4; spp += 3) {
			struct framebuffer *full = render_mem(names[k], 48, 36, spp, 2, false);
			struct framebuffer *rgb = render_mem(names[k], 48, 36, spp, 2, true);
			CHECK(full && rgb);
			if (!full || !rgb)
				continue;
			CHECK(fb_find(rgb, "A") == NULL && fb_find(full, "A") != NULL);
			int differ = 0, bg = 0, bg_off = 0;
			const double sky[3] = {0.05, 0.07, 0.1}; /* g_glass's background */
			for (int c = 0; c < 3; c++) {
				const char *ch[] = {"R", "G", "B"};
				const float *a = fb_find(full, ch[c]), *b = fb_find(rgb, ch[c]);
				const float *alpha = fb_find(full, "A");
				for (int i = 0; i < 48 * 36; i++) {
					differ += memcmp(&a[i], &b[i], sizeof a[i]) != 0;
					bg += c == 0 && alpha[i] == 0;
					bg_off += k == 0 && spp == 1 && alpha[i] == 0 && b[i] != (float)sky[c];
				}
			}
			CHECK(differ == 0);
			if (k == 0) /* g_glass shows the background above the horizon: 144 pixels */
				CHECK(bg == 144);
			CHECK(bg_off == 0);
			fb_free(full);
			fb_free(rgb);
		}
}

/* The pixels of 4×4 blocks shaded as the eye pass shades them, from one
 * packet of camera rays (eye_pixels: with AVX-512 the rays' entry into the
 * scene, the spheres' roots, points and normals, the view vector and the
 * first light's direction are worked out sixteen lanes at a time), have
 * the bits of each pixel shaded alone (eye_pixel: every step scalar), with
 * all layers and with R G B alone: a few hundred small spheres, on a grid
 * (bench/eye/grid.scn) and at random (spheres.scn), enough for Embree, and
 * g_lights.scn, whose jittered area light draws from each pixel's random
 * numbers (the path's key, which camera16 sets for each lane)
 * and whose few leaves skip Embree: its packets never reach Embree while
 * the process has native 16-wide packets (from the two scenes before). */
static void t_packet_as_one(void)
{
	const char *files[] = {"bench/eye/grid.scn", "bench/eye/spheres.scn", "tests/render/g_lights.scn"};
	const char *defs[] = {"N=400"};
	enum { W = 64, H = 48 };
	for (int f = 0; f < 3; f++) {
		struct eval_options eo;
		eval_default_options(&eo);
		eo.width = W, eo.height = H, eo.defines = defs, eo.ndefines = 1;
		struct diag dg;
		diag_init(&dg, stdout);
		struct scene s;
		CHECK(eval_scene(files[f], &eo, &dg, &s) == 0);
		struct mat_cache mats = {0};
		CHECK(mat_cache_load(&mats, &s, NULL, TDG) == 0);
		struct bvh *b = bvh_build(s.objects, s.nobjects);
		CHECK(bvh_walks(b) == (f < 2));
		for (int beauty = 0; beauty < 2; beauty++) {
			struct eye_ctx ctx;
			eye_setup(&ctx, &s, b, &mats, W, H, 1);
			ctx.beauty_only = beauty;
			int differ = 0, lit = 0;
			long long rays = 0;
			for (int by = 0; by < H; by += 4)
				for (int bx = 0; bx < W; bx += 4) {
					int xs[BVH_PACKET], ys[BVH_PACKET];
					for (int i = 0; i < BVH_PACKET; i++)
						xs[i] = bx + i % 4, ys[i] = by + i / 4;
					struct eye_px pk[BVH_PACKET], one;
					eye_pixels(&ctx, BVH_PACKET, xs, ys, pk, &rays);
					for (int i = 0; i < BVH_PACKET; i++) {
						eye_pixel(&ctx, xs[i], ys[i], &one, &rays);
						size_t n = beauty ? sizeof one.rgb : sizeof one;
						differ += memcmp(&one, &pk[i], n) != 0;
						lit += one.rgb[0] > 0.1f;
					}
				}
			printf("# %s, %s: %d of %d pixels differ, %d lit\n", files[f], beauty ? "R G B" : "all layers",
			       differ, W * H, lit);
			CHECK(differ == 0);
			CHECK(lit > W * H / 20);
		}
		bvh_free(b);
		mat_cache_free(&mats);
		scene_free(&s);
	}
}

int main(void)
{
	RUN(t_plane_direct);
	RUN(t_sphere_inside);
	RUN(t_mirror);
	RUN(t_slab);
	RUN(t_flags);
	RUN(t_function_pattern);
	RUN(t_isosurface_sphere);
	RUN(t_beauty_only);
	RUN(t_packet_as_one);
	return test_done();
}
