/* SPDX-License-Identifier: MIT */
/* test_tools.c: the figures of `arvo compare` (tools/compare.c) on pairs
 * with known answers, and its matching rules. */
#include <math.h>
#include <stdio.h>

#include "../../tools/tools.h"
#include "test.h"

/* a: R = 0, 0.5, 1, 1 and N.X = 1 (4 pixels); b differs by 0.1, 0, 0.5, 0. */
static void make_pair(struct framebuffer **a, struct framebuffer **b)
{
	static const float ra[4] = {0, 0.5f, 1, 1}, rb[4] = {0.1f, 0.5f, 0.5f, 1};
	*a = fb_new(2, 2);
	*b = fb_new(2, 2);
	float *pa = fb_plane(*a, "R"), *pb = fb_plane(*b, "R");
	float *na = fb_plane(*a, "N.X"), *nb = fb_plane(*b, "N.X");
	for (int i = 0; i < 4; i++)
		pa[i] = ra[i], pb[i] = rb[i], na[i] = nb[i] = 1;
	fb_plane(*a, "Z")[3] = INFINITY;
	fb_plane(*b, "Z")[3] = INFINITY;
}

static void t_figures(void)
{
	struct framebuffer *a, *b;
	make_pair(&a, &b);
	struct cmp_figures f;
	cmp_layer(a, b, "", CMP_MAX, 0, &f); /* R (the beauty layer) */
	double d0 = fabs(0.1f - 0.0), d2 = 0.5;
	CHECK_NEAR(f.mean, (d0 + d2) / 4, 1e-12);
	CHECK_NEAR(f.rmse, sqrt((d0 * d0 + d2 * d2) / 4), 1e-12);
	CHECK_NEAR(f.psnr, 20 * log10(1 / sqrt((d0 * d0 + d2 * d2) / 4)), 1e-9);
	CHECK(f.max == 0.5 && f.max_x == 0 && f.max_y == 1 && f.max_ch[0] == 'R');
	CHECK(f.rel == 1); /* 0 against 0.1 */
	CHECK(f.over == 2 && f.pixels == 4);
	cmp_layer(a, b, "N", CMP_MAX, 0, &f);
	CHECK(f.max == 0 && f.over == 0 && isinf(f.psnr));
	cmp_layer(a, b, "Z", CMP_MAX, 0, &f); /* +inf against +inf is equal */
	CHECK(f.max == 0 && f.mean == 0);
	cmp_layer(a, b, NULL, CMP_MAX, 0, &f); /* all 12 values */
	CHECK_NEAR(f.mean, (d0 + d2) / 12, 1e-12);
	fb_free(a);
	fb_free(b);
}

static void t_rules(void)
{
	struct framebuffer *a, *b;
	make_pair(&a, &b);
	struct cmp_figures f;
	cmp_layer(a, b, "", CMP_MAX, 0.2, &f);
	CHECK(f.over == 1);
	CHECK(!cmp_match(&f, CMP_MAX, 0.2, 0));
	CHECK(cmp_match(&f, CMP_MAX, 0.2, 25));  /* 1 of 4 pixels */
	CHECK(!cmp_match(&f, CMP_MAX, 0.2, 24.9));
	CHECK(cmp_match(&f, CMP_MEAN, 0.151, 0) && !cmp_match(&f, CMP_MEAN, 0.149, 0)); /* mean 0.15 */
	cmp_layer(a, b, "", CMP_REL, 0.6, &f); /* relative: 1 at pixel 0, 0.5 at pixel 2 */
	CHECK(f.over == 1);
	CHECK(cmp_match(&f, CMP_PSNR, 10, 0) && !cmp_match(&f, CMP_PSNR, 20, 0)); /* 14.9 dB */
	fb_free(a);
	fb_free(b);
}

int main(void)
{
	RUN(t_figures);
	RUN(t_rules);
	return test_done();
}
