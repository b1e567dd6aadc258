/* SPDX-License-Identifier: MIT */
/* test_layers.c: the EXR layers a compositor relies on (eyepass.h, render.h).
 *   - at --spp 1, R G B = albedo/π · (direct + caustic) + specular + emission
 *     to float precision, on scenes with glass and caustics, area lights,
 *     the legacy light model and a camera inside glass;
 *   - A is the share of samples that hit; Z is the nearest hit (+inf where
 *     none), never a mean with misses; N (unit), P and albedo are one
 *     surface's, never a blend;
 *   - P maps through the camera's worldToNDC to the pixel's centre, and
 *     through worldToCamera to z = distance along the view;
 *   - a region renders the same pixels as the whole frame. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../../common/diag.h"
#include "../../eval/eval.h"
#include "../../tracer/camera.h"
#include "../../tracer/render.h"
#include "test.h"

/* Renders tests/render/<name>.scn (or another path) at w×h, spp samples. */
static struct framebuffer *render_scene(const char *path, int w, int h, int spp, long rays,
                                        const int region[4], struct scene *keep)
{
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
	struct render_opts ro = {.width = w, .height = h, .spp = spp, .threads = 2, .quiet = 1,
	                         .rays = rays};
	if (region)
		memcpy(ro.region, region, sizeof ro.region);
	struct framebuffer *fb = NULL;
	const char *err = MSG(render(&s, &ro, TDG, &fb, NULL));
	if (err)
		printf("#   %s: %s\n", path, err);
	if (keep)
		*keep = s;
	else
		scene_free(&s);
	return fb;
}

/* The worst |beauty - composition| / scale over every pixel and channel,
 * scale = |beauty| + the sum of the terms' magnitudes (float rounding of
 * each term). */
static double composition_error(const struct framebuffer *fb, double *largest_spec)
{
	static const char *const ch[3] = {"R", "G", "B"};
	double worst = 0;
	size_t n = (size_t)fb->w * (size_t)fb->h;
	*largest_spec = 0;
	for (int c = 0; c < 3; c++) {
		char nm[5][16];
		const char *lay[5] = {"albedo", "direct", "caustic", "specular", "emission"};
		const float *p[5];
		for (int k = 0; k < 5; k++) {
			snprintf(nm[k], sizeof nm[k], "%s.%s", lay[k], ch[c]);
			p[k] = fb_find(fb, nm[k]);
			if (!p[k])
				return INFINITY;
		}
		const float *beauty = fb_find(fb, ch[c]);
		for (size_t i = 0; i < n; i++) {
			double lam = (double)p[0][i] / M_PI * ((double)p[1][i] + (double)p[2][i]);
			double sum = lam + p[3][i] + p[4][i];
			double scale = fabs(beauty[i]) + fabs(lam) + fabs(p[3][i]) + fabs(p[4][i]) + 1e-30;
			worst = fmax(worst, fabs(beauty[i] - sum) / scale);
			*largest_spec = fmax(*largest_spec, p[3][i]);
		}
	}
	return worst;
}

/* The composition holds to float precision (a few units of 2^-24) at spp 1. */
static void t_composition(void)
{
	static const struct { const char *path; long rays; } scenes[] = {
		{"tests/render/layers.scn", 0}, {"tests/render/g_glass.scn", 20000},
		{"tests/render/g_lights.scn", 0}, {"tests/render/g_legacy.scn", 0},
		{"tests/stability/camera_in_glass.scn", 0}, {"tests/render/plane_point.scn", 0}};
	for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; k++) {
		struct framebuffer *fb = render_scene(scenes[k].path, 48, 36, 1, scenes[k].rays, NULL, NULL);
		CHECK(fb != NULL);
		if (!fb)
			continue;
		double spec, e = composition_error(fb, &spec);
		if (!(e < 4e-7))
			printf("#   %s: composition off by %g relative\n", scenes[k].path, e);
		CHECK(e < 4e-7);
		fb_free(fb);
	}
}

/* layers.scn at spp 4: coverage, nearest depth, one surface per pixel. */
static void t_nearest(void)
{
	const int w = 64, h = 48;
	struct framebuffer *fb = render_scene("tests/render/layers.scn", w, h, 4, 0, NULL, NULL);
	CHECK(fb != NULL);
	if (!fb)
		return;
	const float *A = fb_find(fb, "A"), *Z = fb_find(fb, "Z"), *al = fb_find(fb, "albedo.R");
	const float *N[3] = {fb_find(fb, "N.X"), fb_find(fb, "N.Y"), fb_find(fb, "N.Z")};
	const float *P[3] = {fb_find(fb, "P.X"), fb_find(fb, "P.Y"), fb_find(fb, "P.Z")};
	int partial = 0, empty = 0, bad_a = 0, bad_z = 0, bad_albedo = 0, bad_n = 0, bad_p = 0, mixed_z = 0;
	for (int i = 0; i < w * h; i++) {
		float q = A[i] * 4;
		bad_a += q != floorf(q) || A[i] < 0 || A[i] > 1;
		partial += A[i] > 0 && A[i] < 1;
		if (A[i] == 0) {
			empty++;
			bad_z += !(isinf(Z[i]) && Z[i] > 0);
			bad_albedo += al[i] != 0;
			continue;
		}
		/* the sphere's front is 4 to 5 away, the card 7 */
		bad_z += !(Z[i] >= 4 - 1e-5 && (Z[i] <= 5 + 1e-5 || fabsf(Z[i] - 7) < 1e-5));
		mixed_z += Z[i] > 5 + 1e-5 && Z[i] < 7 - 1e-5;
		bad_albedo += al[i] != 0.8f && al[i] != 0.2f;
		bad_albedo += (Z[i] < 6) != (al[i] == 0.8f); /* albedo of the surface Z is from */
		double len = sqrt((double)N[0][i] * N[0][i] + (double)N[1][i] * N[1][i] + (double)N[2][i] * N[2][i]);
		bad_n += fabs(len - 1) > 1e-6;
		/* P is where the camera ray met the surface: 5 + P.z = Z for this camera */
		bad_p += fabs(5 + P[2][i] - Z[i]) > 1e-5;
	}
	CHECK(bad_a == 0);
	CHECK(partial > 20); /* the sphere's and the card's edges */
	CHECK(empty > 200);  /* the upper right */
	CHECK(bad_z == 0);
	CHECK(mixed_z == 0);
	CHECK(bad_albedo == 0);
	CHECK(bad_n == 0);
	CHECK(bad_p == 0);
	printf("#   %d partly covered pixels, %d empty\n", partial, empty);
	fb_free(fb);
}

/* Row vector p (w = 1) times the row-major 4×4 m. */
static void xform(const double m[16], const double p[3], double out[4])
{
	for (int j = 0; j < 4; j++)
		out[j] = p[0] * m[j] + p[1] * m[4 + j] + p[2] * m[8 + j] + m[12 + j];
}

/* P through worldToNDC lands on the pixel centre (spp 1 shoots through it);
 * through worldToCamera its z is the distance along the view direction, and
 * cameraToWorld undoes worldToCamera. Perspective (g_glass) and
 * orthographic (layers). */
static void t_matrices(void)
{
	const char *paths[2] = {"tests/render/g_glass.scn", "tests/render/layers.scn"};
	for (int k = 0; k < 2; k++) {
		const int w = 40, h = 30;
		struct scene s;
		struct framebuffer *fb = render_scene(paths[k], w, h, 1, -1, NULL, &s);
		CHECK(fb != NULL);
		if (!fb)
			continue;
		struct cam c;
		double c2w[16], w2c[16], ndc[16];
		cam_setup(&c, &s.camera);
		cam_matrices(&c, c2w, w2c, ndc);
		const float *P[3] = {fb_find(fb, "P.X"), fb_find(fb, "P.Y"), fb_find(fb, "P.Z")};
		const float *A = fb_find(fb, "A"), *Z = fb_find(fb, "Z");
		double worst_ndc = 0, worst_back = 0, worst_z = 0;
		for (int y = 0; y < h; y++)
			for (int x = 0; x < w; x++) {
				int i = y * w + x;
				if (A[i] == 0)
					continue;
				double p[3] = {P[0][i], P[1][i], P[2][i]}, q[4], cp[4], back[4];
				xform(ndc, p, q);
				worst_ndc = fmax(worst_ndc, fmax(fabs(q[0] / q[3] - (x + 0.5) / w), fabs(q[1] / q[3] - (y + 0.5) / h)));
				xform(w2c, p, cp);
				xform(c2w, cp, back);
				for (int j = 0; j < 3; j++)
					worst_back = fmax(worst_back, fabs(back[j] - p[j]));
				/* perspective: Z is the distance, |cp|; orthographic: cp.z + 0 (rays start on the film plane) */
				double want = k == 0 ? sqrt(cp[0] * cp[0] + cp[1] * cp[1] + cp[2] * cp[2]) : cp[2];
				worst_z = fmax(worst_z, fabs(want - Z[i]) / Z[i]);
			}
		printf("#   %s: ndc %.3g, inverse %.3g, depth %.3g\n", paths[k], worst_ndc, worst_back, worst_z);
		CHECK(worst_ndc < 1e-5);
		CHECK(worst_back < 1e-5);
		CHECK(worst_z < 1e-5);
		fb_free(fb);
		scene_free(&s);
	}
}

/* Every region of the frame holds the same bits as the whole render. */
static void t_region(void)
{
	const int w = 37, h = 29, region[4] = {5, 30, 7, 20};
	struct framebuffer *full = render_scene("tests/render/g_glass.scn", w, h, 2, 20000, NULL, NULL);
	struct framebuffer *part = render_scene("tests/render/g_glass.scn", w, h, 2, 20000, region, NULL);
	CHECK(full && part);
	if (!full || !part)
		return;
	CHECK(part->w == 25 && part->h == 13 && part->x0 == 5 && part->y0 == 7);
	CHECK(part->full_w == w && part->full_h == h);
	CHECK(fb_count(part) == fb_count(full) && fb_count(full) == 26);
	int differ = 0;
	for (int c = 0; c < fb_count(part); c++) {
		const float *a = fb_data(part, c), *b = fb_find(full, fb_name(part, c));
		for (int y = 0; y < part->h; y++)
			differ += memcmp(a + y * part->w, b + (y + 7) * w + 5, sizeof(float) * (size_t)part->w) != 0;
	}
	CHECK(differ == 0);
	fb_free(full);
	fb_free(part);
}

int main(void)
{
	RUN(t_composition);
	RUN(t_nearest);
	RUN(t_matrices);
	RUN(t_region);
	return test_done();
}
