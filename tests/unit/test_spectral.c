/* SPDX-License-Identifier: MIT */
/* test_spectral.c: passes spectral (tracer/spectrum.h). The observer fit
 * against the CIE table's integrals, the colour conversion (a flat spectrum
 * is white), the weights and the wavelength sampler (unit area, unbiased),
 * the dispersion law (each channel's light refracts on average as the RGB
 * convention has it), the light pass (the same energy as the RGB passes,
 * conserved with dispersion, a continuous spectrum where the RGB passes
 * leave gaps), the eye pass (white stays white through dispersive glass),
 * and bit-identical results for 1 and 2 threads. */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "../../common/diag.h"
#include "../../eval/eval.h"
#include "../../tracer/bvh.h"
#include "../../tracer/light/illum.h"
#include "../../tracer/light/lightpass.h"
#include "../../tracer/render.h"
#include "../../tracer/sampler.h"
#include "../../tracer/shape.h"
#include "../../tracer/spectrum.h"
#include "../../tracer/surface.h"
#include "test.h"

/* ---- the observer and the colour conversion ------------------------------ */

/* Summed at 1 nm over 360–830 nm, the CIE 1931 2° table gives 106.8654,
 * 106.8569 (the ∫ȳ every photometric normalisation uses) and 106.8922. The
 * fit is within 0.1 % of each (it gives 106.766, 106.922, 106.875); the
 * tolerance is 0.15 %. Its peak, ȳ(555 nm) = 1 in the table, to 0.5 %. */
static void t_observer(void)
{
	const double cie[3] = {106.8654, 106.8569, 106.8922};
	double s[3] = {0, 0, 0}, xyz[3];
	for (int l = 360; l <= 830; l++) {
		spec_cie(l, xyz);
		for (int c = 0; c < 3; c++)
			s[c] += xyz[c];
	}
	for (int c = 0; c < 3; c++)
		CHECK_NEAR(s[c] / cie[c], 1, 1.5e-3);
	CHECK_NEAR(s[1], 106.86, 0.16);
	spec_cie(555, xyz);
	CHECK_NEAR(xyz[1], 1, 5e-3);
}

/* A flat spectrum is white: its XYZ converts to r = g = b, within 1 %
 * (the adaptation maps X = Y = Z to r = g = b exactly; the fit's 0.1 %
 * errors in X, Y and Z come out as 0.6 % through the Rec.709 matrix, whose
 * coefficients reach 3.2). The colour of light k(λ) then has unit area per
 * channel to the same tolerance. */
static void t_flat_is_white(void)
{
	double xyz[3] = {0, 0, 0}, v[3], rgb[3];
	for (int l = 360; l <= 830; l++) {
		spec_cie(l, v);
		for (int c = 0; c < 3; c++)
			xyz[c] += v[c];
	}
	spec_xyz_to_rgb(xyz, rgb);
	CHECK_NEAR(rgb[0] / rgb[1], 1, 1e-2);
	CHECK_NEAR(rgb[2] / rgb[1], 1, 1e-2);
	spec_xyz_to_rgb((double[3]){1, 1, 1}, rgb);
	for (int c = 0; c < 3; c++)
		CHECK_NEAR(rgb[c], 1, 1e-12);
	double area[3] = {0, 0, 0}, k[3];
	for (double l = 360.005; l < 830; l += 0.01) {
		spec_colour(l, k);
		for (int c = 0; c < 3; c++)
			area[c] += k[c] * 0.01;
	}
	for (int c = 0; c < 3; c++)
		CHECK_NEAR(area[c], 1, 1e-2);
}

/* The RGB hue angle, unwrapped to (-60°, 300°]: red 0, green 120, blue 240. */
static double hue(const double c[3])
{
	double h = atan2(sqrt(3) * (c[1] - c[2]), 2 * c[0] - c[1] - c[2]) * 180 / M_PI;
	return h <= -60 ? h + 360 : h;
}

/* The weights: non-negative, unit area per channel (midpoint rule at
 * 0.01 nm against the table's Simpson at 0.05 nm: 1e-6), and the hue of
 * every wavelength kept (adding white changes no channel difference; only
 * the channels' areas, equal to 0.5 %, rescale them: within 1°). */
static void t_weights(void)
{
	double area[3] = {0, 0, 0}, w[3], k[3], worst = 0;
	int negative = 0;
	for (double l = 360.005; l < 830; l += 0.01) {
		spec_weights(l, w);
		for (int c = 0; c < 3; c++) {
			area[c] += w[c] * 0.01;
			negative += w[c] < 0;
		}
		spec_colour(l, k);
		double chroma = fmax(k[0], fmax(k[1], k[2])) - fmin(k[0], fmin(k[1], k[2]));
		if (l > 400 && l < 700 && chroma > 1e-3) {
			double d = fabs(hue(w) - hue(k));
			worst = fmax(worst, fmin(d, 360 - d));
		}
	}
	CHECK(negative == 0);
	for (int c = 0; c < 3; c++)
		CHECK_NEAR(area[c], 1, 1e-6);
	CHECK(worst < 1);
	spec_weights(300, w);
	CHECK(w[0] == 0 && w[1] == 0 && w[2] == 0);
}

/* The sampler: λ(u) is monotonic; f = w/p; the mean of f_c over u is 1
 * (∫ w_c = 1: a stratified midpoint sum of 10^6 points, to 1e-5); and a
 * ray's f_R + f_G + f_B stays near 3 (p ∝ the channels' sum), so only its
 * colour varies: within 3 ± 10 % over 380–780 nm, since p is constant over
 * each 1 nm bin while w is not (most near 396 nm, where w rises steeply). */
static void t_sampler(void)
{
	const int n = 1000000;
	double mean[3] = {0, 0, 0}, prev = 0, lo = 10, hi = 0;
	int backwards = 0, mismatch = 0;
	for (int i = 0; i < n; i++) {
		double f[3], w[3];
		double l = spec_sample((i + 0.5) / n, f);
		backwards += l < prev;
		prev = l;
		spec_weights(l, w);
		for (int c = 0; c < 3; c++) {
			mean[c] += f[c] / n;
			mismatch += fabs(f[c] - w[c] / spec_pdf(l)) > 1e-9 * (1 + f[c]);
		}
		if (l > 380 && l < 780) {
			lo = fmin(lo, f[0] + f[1] + f[2]);
			hi = fmax(hi, f[0] + f[1] + f[2]);
		}
	}
	CHECK(backwards == 0 && mismatch == 0);
	for (int c = 0; c < 3; c++)
		CHECK_NEAR(mean[c], 1, 1e-5);
	CHECK(lo > 2.7 && hi < 3.3);
	double f[3];
	CHECK(spec_sample(0, f) >= SPEC_MIN && spec_sample(1, f) <= SPEC_MAX);
}

/* The dispersion law: the mean index of each channel's light, ∫ w_c n dλ,
 * is the RGB convention's: ior for green, and blue's is D times red's
 * (Cauchy is linear in 1/λ², so exactly, to the quadrature's 1e-9); the
 * index falls with λ; D = 1 leaves ior. */
static void t_dispersion_law(void)
{
	double ior = 1.5, D = 1.1, m[3] = {0, 0, 0}, w[3], prev = 10;
	int rising = 0;
	for (double l = 360.0025; l < 830; l += 0.005) {
		double n = spec_ior(ior, D, l);
		spec_weights(l, w);
		for (int c = 0; c < 3; c++)
			m[c] += w[c] * n * 0.005;
		rising += n > prev;
		prev = n;
	}
	CHECK_NEAR(m[1], ior, 1e-7);
	CHECK_NEAR(m[2] / m[0], D, 1e-7);
	CHECK(rising == 0);
	CHECK(spec_ior(ior, 1, 450) == ior);
	CHECK(spec_centroid(2) < spec_centroid(1) && spec_centroid(1) < spec_centroid(0));
}

/* The wavelength strata of a light-ray grid: smp_permute is a bijection of
 * 0..n−1 for every n (cycle-walking included) and keyed (another key,
 * another order); smp_latin gives every row and every column of a
 * side×side grid each of the side strata once (a Latin square), and is
 * unrelated to the ray's place: over a 64×64 grid the correlation of the
 * stratum with the row and with the column is ~1/64 (tolerance 0.05). */
static void t_strata(void)
{
	int bad = 0, same = 0;
	for (uint64_t n = 1; n <= 300; n++) {
		char *seen = calloc(n, 1);
		for (uint64_t i = 0; i < n; i++) {
			uint64_t k = smp_permute(i, n, 0x5A17u + n);
			bad += k >= n || seen[k];
			if (k < n)
				seen[k] = 1;
		}
		free(seen);
	}
	for (uint64_t i = 0; i < 4096; i++)
		same += smp_permute(i, 4096, 1) == smp_permute(i, 4096, 2);
	CHECK(bad == 0 && same < 16);
	for (uint64_t side = 1; side <= 70; side += 3) {
		char *row = calloc(side * side, 1), *col = calloc(side * side, 1);
		for (uint64_t y = 0; y < side; y++)
			for (uint64_t x = 0; x < side; x++) {
				double u = smp_latin(x, y, side, 7, 0.5);
				uint64_t k = (uint64_t)(u * (double)side);
				bad += !(u >= 0 && u < 1) || row[y * side + k]++ || col[x * side + k]++;
			}
		free(row);
		free(col);
	}
	CHECK(bad == 0);
	double s = 0, ss = 0, sr = 0, sc = 0;
	for (uint64_t y = 0; y < 64; y++)
		for (uint64_t x = 0; x < 64; x++) {
			double u = smp_latin(x, y, 64, 7, 0.5) - 0.5;
			s += u;
			ss += u * u;
			sr += u * ((double)y - 31.5);
			sc += u * ((double)x - 31.5);
		}
	double sd_u = sqrt(ss / 4096 - (s / 4096) * (s / 4096)), sd_i = sqrt((64.0 * 64 - 1) / 12);
	CHECK(fabs(sr / 4096 / (sd_u * sd_i)) < 0.05);
	CHECK(fabs(sc / 4096 / (sd_u * sd_i)) < 0.05);
}

/* ---- the light pass -------------------------------------------------------- */

struct run {
	struct scene s;
	struct bvh *b;
	struct lp_result *r[3];
	int n;
	struct lp_stats st[3];
};

static int load(struct scene *s, const char *path, const char *define)
{
	struct diag dg;
	diag_init(&dg, stderr);
	struct eval_options eo;
	eval_default_options(&eo);
	const char *defs[1] = {define};
	eo.defines = defs;
	eo.ndefines = define ? 1 : 0;
	return eval_scene(path, &eo, &dg, s) == 0;
}

/* The light pass of a scene: rgb (three channel passes when it disperses,
 * else one) or one spectral pass, on `threads` threads. */
static int run_m(struct run *R, const char *path, const char *define, bool spectral, long rays, int threads,
                 bool shafts)
{
	memset(R, 0, sizeof *R);
	if (!load(&R->s, path, define))
		return 0;
	R->b = bvh_build(R->s.objects, R->s.nobjects);
	struct mat_cache mc;
	memset(&mc, 0, sizeof mc);
	int passes = !spectral && lp_dispersive(&R->s) ? 3 : 1;
	for (int c = 0; c < passes; c++) {
		struct lp_opts o = {.rays = rays, .max_depth = 10, .min_weight = 1e-9, .threads = threads,
		                    .discard_isolated = false, .channel = passes == 3 ? c : -1,
		                    .spectral = spectral, .shafts = shafts};
		R->r[R->n] = lp_run(&R->s, R->b, &mc, &o, &R->st[R->n]);
		if (!R->r[R->n])
			return 0;
		R->n++;
	}
	return 1;
}

static int run(struct run *R, const char *path, const char *define, bool spectral, long rays, int threads)
{
	return run_m(R, path, define, spectral, rays, threads, false);
}

static void stop(struct run *R)
{
	for (int i = 0; i < R->n; i++)
		lp_free(R->r[i]);
	bvh_free(R->b);
	scene_free(&R->s);
}

/* Sums a stats field over the passes of a run, per channel. */
static void total(const struct run *R, size_t field, double out[3])
{
	out[0] = out[1] = out[2] = 0;
	for (int i = 0; i < R->n; i++) {
		const double *v = (const double *)((const char *)&R->st[i] + field);
		for (int c = 0; c < 3; c++)
			out[c] += v[c];
	}
}

/* With dispersion 1 a wavelength changes nothing but the colour a ray
 * carries, so the spectral pass must deposit what the RGB pass does, per
 * channel, up to the noise of the colour weights: stratified (one ray per
 * stratum of the spectrum in each ring and spoke of the cone), the
 * difference stays within 0.08 % for 1.5 to 4.5·10^5 spectral rays
 * (σ ≈ 0.03 %); the tolerance is 0.2 %. */
static void t_same_energy(void)
{
	struct run a, b;
	if (!run(&a, "tests/accuracy/sphere.scn", NULL, false, 100000, 2) ||
	    !run(&b, "tests/accuracy/sphere.scn", NULL, true, 300000, 2)) {
		CHECK(!"sphere.scn did not run");
		return;
	}
	double ea[3], eb[3];
	total(&a, offsetof(struct lp_stats, deposited), ea);
	total(&b, offsetof(struct lp_stats, deposited), eb);
	printf("# D = 1: rgb %.6f %.6f %.6f, spectral %.6f %.6f %.6f\n", ea[0], ea[1], ea[2], eb[0], eb[1], eb[2]);
	for (int c = 0; c < 3; c++)
		CHECK_NEAR(eb[c] / ea[c], 1, 2e-3);
	stop(&a);
	stop(&b);
}

/* With dispersion (dispersion.scn: the glass sphere, D = 1.05) every joule
 * is still accounted for (emitted = landed + direct + absorbed + escaped +
 * cut, per channel, to 1e-9), and ideal glass sends on all it receives, so
 * the spectral pass lands what the three channel passes land, per channel,
 * within the 0.2 % of the colour weights' noise (measured as above: within
 * 0.07 % for 1.5 to 4.5·10^5 rays). */
static void t_conserved(void)
{
	struct run a, b;
	if (!run(&a, "tests/accuracy/dispersion.scn", NULL, false, 100000, 2) ||
	    !run(&b, "tests/accuracy/dispersion.scn", NULL, true, 300000, 2)) {
		CHECK(!"dispersion.scn did not run");
		return;
	}
	CHECK(a.n == 3 && b.n == 1);
	double em[3], la[3], di[3], ab[3], es[3], cu[3], ref[3];
	total(&b, offsetof(struct lp_stats, emitted), em);
	total(&b, offsetof(struct lp_stats, landed), la);
	total(&b, offsetof(struct lp_stats, direct), di);
	total(&b, offsetof(struct lp_stats, absorbed), ab);
	total(&b, offsetof(struct lp_stats, escaped), es);
	total(&b, offsetof(struct lp_stats, cut), cu);
	total(&a, offsetof(struct lp_stats, landed), ref);
	printf("# D = 1.05: rgb landed %.6f %.6f %.6f, spectral %.6f %.6f %.6f\n", ref[0], ref[1], ref[2],
	       la[0], la[1], la[2]);
	for (int c = 0; c < 3; c++) {
		CHECK_NEAR(la[c] + di[c] + ab[c] + es[c] + cu[c], em[c], 1e-9 * em[c]);
		CHECK_NEAR(la[c] / ref[c], 1, 2e-3);
	}
	stop(&a);
	stop(&b);
}

/* ---- a prism's spectrum ---------------------------------------------------- */

#define NBIN 240
#define BIN 0.05

struct profile {
	const struct object *wall;
	double e[NBIN][3]; /* energy per bin along the wall's vertical, from t = -5 */
};

static void bin_node(void *ctx, const struct illum_node *n)
{
	struct profile *P = ctx;
	struct vec3 p, du, dv;
	shape_uv_point(P->wall, n->u, n->v, &p, &du, &dv);
	double s = sin(18.6 * M_PI / 180), c = cos(18.6 * M_PI / 180);
	int k = (int)floor((p.x * s + p.y * c + 7) / BIN); /* up the wall */
	if (k >= 0 && k < NBIN)
		for (int ch = 0; ch < 3; ch++)
			P->e[k][ch] += n->energy[ch];
}

static void profile(const struct run *R, struct profile *P)
{
	memset(P, 0, sizeof *P);
	P->wall = R->s.objects[R->s.nobjects - 1];
	for (int i = 0; i < R->n; i++)
		illum_each(lp_map(R->r[i], P->wall), bin_node, P);
}

static double sum3(const double e[3]) { return e[0] + e[1] + e[2]; }

/* tests/accuracy/prism.scn (dispersion 1.1): the RGB passes cast three
 * bands with gaps between them (bins below 1 % of the peak), while the
 * spectral pass lights every bin from the red band's peak to the blue
 * band's (each above 5 % of its peak) with a hue that turns monotonically
 * from red to blue: no bin more than 2° back from the largest hue before it
 * (a bin holds ~10^3 rays; the hue steps by 1–10° a bin). */
static void t_prism_spectrum(void)
{
	struct run a, b;
	static struct profile pa, pb;
	if (!run(&a, "tests/accuracy/prism.scn", NULL, false, 60000, 2) ||
	    !run(&b, "tests/accuracy/prism.scn", NULL, true, 180000, 2)) {
		CHECK(!"prism.scn did not run");
		return;
	}
	profile(&a, &pa);
	profile(&b, &pb);
	int peak[3] = {0, 0, 0}; /* each channel's peak bin in the RGB passes */
	double top = 0, topb = 0;
	for (int k = 0; k < NBIN; k++) {
		for (int c = 0; c < 3; c++)
			if (pa.e[k][c] > pa.e[peak[c]][c])
				peak[c] = k;
		top = fmax(top, sum3(pa.e[k]));
		topb = fmax(topb, sum3(pb.e[k]));
	}
	CHECK(peak[2] < peak[1] && peak[1] < peak[0]); /* blue lowest */
	int gaps = 0, dark = 0, back = 0;
	double prev = -1e9;
	for (int k = peak[0]; k >= peak[2]; k--) {
		gaps += sum3(pa.e[k]) < 0.01 * top;
		dark += sum3(pb.e[k]) < 0.05 * topb;
		double h = hue(pb.e[k]);
		back += h < prev - 2;
		prev = fmax(prev, h);
	}
	printf("# prism: RGB peaks at bins %d %d %d, %d gap bins between; spectral: %d dark, %d backwards\n",
	       peak[0], peak[1], peak[2], gaps, dark, back);
	CHECK(gaps >= 4);
	CHECK(dark == 0);
	CHECK(back == 0);
	CHECK(hue(pb.e[peak[0]]) < 60 && hue(pb.e[peak[2]]) > 180);
	stop(&a);
	stop(&b);
}

/* Light shafts carry the band of their pass too: under method shaft the
 * three channel passes cast their bands where the point method does, blue
 * lowest. Each channel's centroid is within a quarter of a bin of the point
 * method's (measured: 0.14 bin, the same shift in all three, footprints
 * against bilinear splats); a shaft refracting with another channel's index
 * would land 24 or more bins away. */
static void t_shaft_bands(void)
{
	struct run a, b;
	static struct profile pa, pb;
	if (!run(&a, "tests/accuracy/prism.scn", NULL, false, 60000, 2) ||
	    !run_m(&b, "tests/accuracy/prism.scn", NULL, false, 20000, 2, true)) {
		CHECK(!"prism.scn did not run");
		return;
	}
	profile(&a, &pa);
	profile(&b, &pb);
	double m[2][3] = {{0, 0, 0}, {0, 0, 0}}, w[2][3] = {{0, 0, 0}, {0, 0, 0}};
	for (int k = 0; k < NBIN; k++)
		for (int c = 0; c < 3; c++) {
			m[0][c] += k * pa.e[k][c], w[0][c] += pa.e[k][c];
			m[1][c] += k * pb.e[k][c], w[1][c] += pb.e[k][c];
		}
	for (int i = 0; i < 2; i++)
		for (int c = 0; c < 3; c++)
			m[i][c] /= w[i][c];
	printf("# shafts: centroids at bins %.2f %.2f %.2f (points %.2f %.2f %.2f)\n", m[1][0], m[1][1], m[1][2],
	       m[0][0], m[0][1], m[0][2]);
	CHECK(m[1][2] < m[1][1] - 10 && m[1][1] < m[1][0] - 10);
	for (int c = 0; c < 3; c++)
		CHECK_NEAR(m[1][c], m[0][c], 0.25);
	stop(&a);
	stop(&b);
}

/* ---- threads --------------------------------------------------------------- */

struct nodes {
	double *v;
	long n, cap;
};

static void keep_node(void *ctx, const struct illum_node *n)
{
	struct nodes *N = ctx;
	if (N->n + 5 > N->cap)
		N->v = realloc(N->v, sizeof *N->v * (size_t)(N->cap = N->cap * 2 + 64));
	double row[5] = {(double)n->i, (double)n->j, n->energy[0], n->energy[1], n->energy[2]};
	memcpy(N->v + N->n, row, sizeof row);
	N->n += 5;
}

/* The spectral light pass and the eye pass that splits by wavelength give
 * the same bits on 1 and 2 threads: the maps node by node, the image pixel
 * by pixel. */
static void t_threads(void)
{
	struct run r1, r2;
	if (!run(&r1, "tests/accuracy/prism.scn", "D=1.1", true, 20000, 1) ||
	    !run(&r2, "tests/accuracy/prism.scn", "D=1.1", true, 20000, 2)) {
		CHECK(!"prism.scn did not run");
		return;
	}
	struct nodes n1 = {NULL, 0, 0}, n2 = {NULL, 0, 0};
	const struct object *wall = r1.s.objects[r1.s.nobjects - 1];
	illum_each(lp_map(r1.r[0], wall), keep_node, &n1);
	illum_each(lp_map(r2.r[0], r2.s.objects[r2.s.nobjects - 1]), keep_node, &n2);
	CHECK(n1.n > 0 && n1.n == n2.n && memcmp(n1.v, n2.v, sizeof *n1.v * (size_t)n1.n) == 0);
	free(n1.v);
	free(n2.v);
	stop(&r1);
	stop(&r2);

	struct framebuffer *fb[2];
	for (int t = 0; t < 2; t++) {
		struct scene s;
		CHECK(load(&s, "tests/accuracy/dispersion_view.scn", NULL));
		s.gs.illum.passes = PASSES_SPECTRAL;
		struct render_opts ro = {.width = 24, .height = 18, .spp = 2, .threads = t + 1, .quiet = 1, .rays = 20000};
		CHECK(MSG(render(&s, &ro, TDG, &fb[t], NULL)) == NULL);
		scene_free(&s);
	}
	const char *planes[] = {"R", "G", "B", "caustic.R", "caustic.B"};
	for (int k = 0; k < 5; k++)
		CHECK(memcmp(fb_plane(fb[0], planes[k]), fb_plane(fb[1], planes[k]), sizeof(float) * 24 * 18) == 0);
	fb_free(fb[0]);
	fb_free(fb[1]);
}

/* ---- the eye pass ---------------------------------------------------------- */

/* White seen through dispersive glass stays white (glass_white.scn): each
 * wavelength returns 1, so the split's weighted mean is white up to the
 * noise of 7 jittered strata: averaged over the middle of the ball, each
 * channel is 1 within 2 %. */
static void t_white_through_glass(void)
{
	struct scene s;
	if (!load(&s, "tests/accuracy/glass_white.scn", NULL)) {
		CHECK(!"glass_white.scn did not run");
		return;
	}
	s.gs.illum.passes = PASSES_SPECTRAL;
	struct render_opts ro = {.width = 32, .height = 32, .spp = 4, .threads = 2, .quiet = 1, .rays = -1};
	struct framebuffer *fb;
	CHECK(MSG(render(&s, &ro, TDG, &fb, NULL)) == NULL);
	double m[3] = {0, 0, 0};
	int n = 0;
	const float *pl[3] = {fb_plane(fb, "R"), fb_plane(fb, "G"), fb_plane(fb, "B")};
	for (int y = 8; y < 24; y++) /* the ball spans ±11 pixels around the centre */
		for (int x = 8; x < 24; x++, n++)
			for (int c = 0; c < 3; c++)
				m[c] += pl[c][y * 32 + x];
	printf("# white through glass: %.4f %.4f %.4f\n", m[0] / n, m[1] / n, m[2] / n);
	for (int c = 0; c < 3; c++)
		CHECK_NEAR(m[c] / n, 1, 0.02);
	fb_free(fb);
	scene_free(&s);
}

int main(void)
{
	RUN(t_observer);
	RUN(t_flat_is_white);
	RUN(t_weights);
	RUN(t_sampler);
	RUN(t_dispersion_law);
	RUN(t_strata);
	RUN(t_same_energy);
	RUN(t_conserved);
	RUN(t_prism_spectrum);
	RUN(t_shaft_bands);
	RUN(t_threads);
	RUN(t_white_through_glass);
	return test_done();
}
