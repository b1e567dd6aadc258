/* SPDX-License-Identifier: MIT */
/* renderl1.c: the L1 of a rendered caustic layer of the fold-ring scene
 * (bench/caustics/ring.scn -D View=HALF) against its exact profile, the
 * metric a user sees: flux-weighted L1 in annuli of an orthographic render.
 *
 *   oiiotool IMAGE.exr --ch caustic.G -o G.exr; oiiotool --dumpdata G.exr | renderl1 HALF [W NB]
 *
 * Reads `Pixel (i, j): g` lines of a square image tiling x, z in
 * [-HALF, HALF] (ring.scn -D View=HALF);
 * Ebar_k = the mean of the pixels whose centres fall in annulus k (width W,
 * default 0.02, NB annuli, default 150), Φ̂_k = Ebar_k × the annulus's exact
 * area; L1 = Σ|Φ̂_k − Φ_k| / ΣΦ_k against the exact twice-transmitted flux
 * (sphere r 1, ior 1.5, centre 1.5 above the floor, light 10 above it,
 * 1 W/sr; midpoint rule over 4·10⁶ meridional rays). Prints l1=… */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>

enum { MAXBINS = 1000 };

static bool snell2(double *dx, double *dy, double nx, double ny, double eta)
{
	double ci = -(*dx * nx + *dy * ny), k = 1 - eta * eta * (1 - ci * ci);
	if (k < 0)
		return false;
	double f = eta * ci - sqrt(k);
	*dx = eta * *dx + f * nx;
	*dy = eta * *dy + f * ny;
	return true;
}

static void exact(double h, double l, double n, double w, int nb, double *ref)
{
	enum { STEPS = 4000000 };
	double tmax = asin(1 / (l - h));
	for (int i = 0; i < STEPS; i++) {
		double th = (i + 0.5) / STEPS * tmax, dth = tmax / STEPS;
		double dx = sin(th), dy = -cos(th), oy = l - h, b = oy * dy, disc = b * b - (oy * oy - 1);
		if (disc < 0)
			continue;
		double t = -b - sqrt(disc), px = t * dx, py = oy + t * dy;
		if (!snell2(&dx, &dy, px, py, 1 / n))
			continue;
		t = -2 * (px * dx + py * dy);
		px += t * dx, py += t * dy;
		if (!snell2(&dx, &dy, -px, -py, n) || dy >= 0)
			continue;
		int bin = (int)(fabs(px + (-(h + py) / dy) * dx) / w);
		if (bin < nb)
			ref[bin] += 2 * M_PI * sin(th) * dth;
	}
}

int main(int argc, char **argv)
{
	double half = argc > 1 ? atof(argv[1]) : 0, w = argc > 2 ? atof(argv[2]) : 0.02;
	int nb = argc > 3 ? atoi(argv[3]) : (int)(half / w + 1e-9);
	if (!(half > 0) || !(w > 0) || nb < 1 || nb > MAXBINS || nb * w > half * (1 + 1e-9)) {
		fprintf(stderr, "usage: renderl1 HALF [W NB] (NB·W <= HALF)\n");
		return 2;
	}
	static double sum[MAXBINS], cnt[MAXBINS], ref[MAXBINS];
	static int ii[1 << 22], jj[1 << 22];
	static double gg[1 << 22];
	long n = 0;
	int size = 0;
	char line[512];
	while (fgets(line, sizeof line, stdin) && n < (1 << 22)) {
		int i, j;
		double g;
		if (sscanf(line, " Pixel (%d, %d): %lf", &i, &j, &g) == 3) {
			ii[n] = i, jj[n] = j, gg[n++] = g;
			size = i + 1 > size ? i + 1 : size;
		}
	}
	if (n == 0 || (long)size * size != n) {
		fprintf(stderr, "renderl1: expected a square image's pixels on stdin\n");
		return 1;
	}
	for (long k = 0; k < n; k++) {
		double x = (ii[k] + 0.5) * 2 * half / size - half, z = (jj[k] + 0.5) * 2 * half / size - half;
		int b = (int)(sqrt(x * x + z * z) / w);
		if (b < nb)
			sum[b] += gg[k], cnt[b]++;
	}
	exact(1.5, 10, 1.5, w, nb, ref);
	double d = 0, t = 0;
	for (int b = 0; b < nb; b++) {
		double got = cnt[b] > 0 ? sum[b] / cnt[b] * M_PI * w * w * (2 * b + 1) : 0;
		d += fabs(got - ref[b]);
		t += ref[b];
	}
	printf("l1=%.6f\n", d / t);
	return 0;
}
