/* SPDX-License-Identifier: MIT */
/* povbin.c: the error of a POV-Ray caustic image (the .pov files of bench/accuracy,
 * bench/caustics/sphere.pov) against a reference (ref.h).
 *
 *   oiiotool --dumpdata IMAGE | povbin X0 X1 Z0 Z1 REF
 *
 * Reads `Pixel (i, j): r g b` lines (oiiotool --dumpdata) of a W×H image
 * whose pixels tile the floor rectangle x in [X0, X1] (columns, left to
 * right), z in [Z1, Z0] (rows, top to bottom), as the .pov files' orthographic
 * cameras set it: pixel (i, j) has its centre at x = X0 + (i + 0.5)·(X1 −
 * X0)/W, z = Z1 − (j + 0.5)·(Z1 − Z0)/H. The image holds the caustic alone in
 * POV-Ray's units, so:
 *  1. Ebar_k = the mean green value over the pixels whose centres fall in
 *     bin k, and Φ̂_k = Ebar_k · (the bin's exact area), so jagged annulus
 *     edges do not enter (grid cells align with pixels);
 *  2. Φ̂ is scaled so that ΣΦ̂_k = ΣΦ_k over the bins kept (POV-Ray's light
 *     units differ): only the shape is compared, never the absolute level;
 *  3. L1 = Σ|Φ̂_k − Φ_k| / ΣΦ_k over the bins kept (ref.h).
 * Prints: l1=… scale=… pixels=… */
#include "ref.h"

struct pixel {
	int i, j;
	double g;
};

/* Reads every pixel line from f into a growing array; returns the count. */
static long read_pixels(FILE *f, struct pixel **out, int *w, int *h)
{
	char line[512];
	long n = 0, cap = 0;
	struct pixel *px = NULL;
	*w = *h = 0;
	while (fgets(line, sizeof line, f)) {
		struct pixel p;
		double r, b;
		const char *s = strstr(line, "Pixel (");
		if (!s || sscanf(s, "Pixel (%d, %d): %lf %lf %lf", &p.i, &p.j, &r, &p.g, &b) != 5)
			continue;
		if (n == cap) {
			cap = cap ? 2 * cap : 1 << 16;
			struct pixel *q = realloc(px, (size_t)cap * sizeof *px);
			if (!q) {
				free(px);
				return -1;
			}
			px = q;
		}
		px[n++] = p;
		if (p.i + 1 > *w)
			*w = p.i + 1;
		if (p.j + 1 > *h)
			*h = p.j + 1;
	}
	*out = px;
	return n;
}

int main(int argc, char **argv)
{
	if (argc != 6) {
		fprintf(stderr, "usage: oiiotool --dumpdata IMG | povbin X0 X1 Z0 Z1 REF\n");
		return 2;
	}
	double x0 = strtod(argv[1], NULL), x1 = strtod(argv[2], NULL);
	double z0 = strtod(argv[3], NULL), z1 = strtod(argv[4], NULL);
	struct ref R;
	if (ref_load(argv[5], &R))
		return 1;
	struct pixel *px = NULL;
	int w, h;
	long n = read_pixels(stdin, &px, &w, &h);
	if (n <= 0) {
		fprintf(stderr, "povbin: no pixels on stdin\n");
		return 1;
	}
	double *sum = calloc((size_t)R.n, sizeof *sum), *est = calloc((size_t)R.n, sizeof *est);
	long *cnt = calloc((size_t)R.n, sizeof *cnt);
	if (!sum || !est || !cnt)
		return 1;
	for (long k = 0; k < n; k++) {
		double x = x0 + (px[k].i + 0.5) * (x1 - x0) / w;
		double z = z1 - (px[k].j + 0.5) * (z1 - z0) / h;
		int b = ref_bin(&R, x, z);
		if (b >= 0) {
			sum[b] += px[k].g;
			cnt[b]++;
		}
	}
	double got = 0, tot = ref_total(&R);
	for (int b = 0; b < R.n; b++) {
		est[b] = cnt[b] ? sum[b] / (double)cnt[b] * ref_area(&R, b) : 0;
		if (R.keep[b])
			got += est[b];
	}
	double s = got > 0 ? tot / got : 0;
	printf("l1=%.6f scale=%.6g pixels=%ld\n", got > 0 ? ref_l1(&R, est, s) : 1.0, s, n);
	free(px);
	free(sum);
	free(est);
	free(cnt);
	ref_free(&R);
	return 0;
}
