/* SPDX-License-Identifier: MIT */
/* povl1.c: the L1 of POV-Ray's caustic image of sphere.pov against refs
 * scene B (bench/caustics).
 *
 *   oiiotool --dumpdata IMAGE | povl1 HALF REF_CSV [PHOTONS]
 *
 * Reads `Pixel (i, j): r g b` lines (oiiotool --dumpdata) of a W×H image
 * whose pixels tile the floor square x, z in [-HALF, HALF] (sphere.pov's
 * orthographic camera), pixel centre x = (i + 0.5)·2·HALF/W − HALF. The image
 * holds the caustic alone in POV-Ray's units, so:
 *  1. Ebar_k = the mean green value over the pixels whose centres fall in the
 *     0.05 annulus k (r ≤ 3), and Φ̂_k = Ebar_k · (exact annulus area), so the
 *     pixel grid's jagged annulus edges do not enter;
 *  2. Φ̂ is scaled so that ΣΦ̂_k = ΣΦ_k (POV-Ray's light units differ): only
 *     the shape of the profile is compared, never its absolute level;
 *  3. L1 = Σ|Φ̂_k − Φ_k| / ΣΦ_k against column 3 (flux_caustic_n1.50).
 * With PHOTONS (photons shot), l1_noise is the photon-noise L1 that N
 * box-binned photons of w = Φ_s/N (Φ_s = 0.0644446 W, the flux entering the
 * sphere) would give: √(2/π)·Σ√(wΦ_k)/ΣΦ_k. POV-Ray's gather smooths over a
 * radius, so it can be below that (at the price of bias).
 * Prints: l1=… l1_noise=… scale=… centre=… (Ebar at r < 0.05, normalised). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { NBINS = 60, MAXPIX = 4096 };
#define BIN_W 0.05
#define PHI_S 0.0644446

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
			px = realloc(px, cap * sizeof *px);
			if (!px)
				return -1;
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

/* Column `col` (0-based) of a CSV with one header line: n values or fewer. */
static int read_column(const char *path, int col, double *out, int n)
{
	FILE *f = fopen(path, "r");
	char line[1024];
	int k = 0;
	if (!f)
		return 0;
	if (fgets(line, sizeof line, f)) {
		while (k < n && fgets(line, sizeof line, f)) {
			char *p = line;
			for (int c = 0; c < col && p; c++)
				p = strchr(p, ',') ? strchr(p, ',') + 1 : NULL;
			if (!p)
				break;
			out[k++] = strtod(p, NULL);
		}
	}
	fclose(f);
	return k;
}

int main(int argc, char **argv)
{
	if (argc < 3) {
		fprintf(stderr, "usage: oiiotool --dumpdata IMG | povl1 HALF REF_CSV [PHOTONS]\n");
		return 2;
	}
	double half = strtod(argv[1], NULL), photons = argc > 3 ? strtod(argv[3], NULL) : 0;
	double ref[NBINS], sum[NBINS] = {0};
	long cnt[NBINS] = {0};
	if (read_column(argv[2], 3, ref, NBINS) != NBINS) {
		fprintf(stderr, "povl1: cannot read %s\n", argv[2]);
		return 1;
	}
	struct pixel *px;
	int w, h;
	long n = read_pixels(stdin, &px, &w, &h);
	if (n <= 0 || w > MAXPIX || h > MAXPIX) {
		fprintf(stderr, "povl1: no pixels on stdin\n");
		return 1;
	}
	for (long k = 0; k < n; k++) {
		double x = (px[k].i + 0.5) * 2 * half / w - half;
		double z = half - (px[k].j + 0.5) * 2 * half / h;
		int b = (int)(sqrt(x * x + z * z) / BIN_W);
		if (b < NBINS) {
			sum[b] += px[k].g;
			cnt[b]++;
		}
	}
	double est[NBINS], tot = 0, got = 0;
	for (int b = 0; b < NBINS; b++) {
		double lo = b * BIN_W, hi = lo + BIN_W;
		est[b] = cnt[b] ? sum[b] / cnt[b] * M_PI * (hi * hi - lo * lo) : 0;
		tot += ref[b];
		got += est[b];
	}
	if (got <= 0) {
		printf("l1=1 l1_noise= scale=0 centre=0\n");
		return 0;
	}
	double s = tot / got, d = 0, sq = 0;
	for (int b = 0; b < NBINS; b++) {
		d += fabs(s * est[b] - ref[b]);
		sq += photons > 0 ? sqrt(PHI_S / photons * ref[b]) : 0;
	}
	printf("l1=%.6f l1_noise=", d / tot);
	if (photons > 0)
		printf("%.6f", sqrt(2 / M_PI) * sq / tot);
	printf(" scale=%.6g centre=%.6g\n", s, s * est[0] / (M_PI * BIN_W * BIN_W));
	free(px);
	return 0;
}
