/* SPDX-License-Identifier: MIT */
/* noisepat.c: POV-Ray 3.7's noise patterns (bozo, spotted, bumps, dents,
 * granite, marble, wood, agate, wrinkles, ripples, waves, crackle, quilted,
 * spiral1, spiral2), its turbulence and warps, and the normals it computes
 * directly rather than from a pattern's slope (bumps, dents, ripples,
 * waves, wrinkles, quilted). Each follows POV-Ray's definition, including
 * its quirks, so a stock scene's textures match (docs/design.md §10):
 * - a pattern's own `turbulence` is a warp in the list like any other; the
 *   patterns marble and wood skip it as a warp and use it themselves, and
 *   marble, wood, agate and the spirals find it only when it is the last
 *   warp to act (the first one written);
 * - the sine is POV-Ray's 1000-step table. */
#include <math.h>
#include <stdlib.h>

#include "noise.h"
#include "pattern.h"

#define EPS 1.0e-10        /* POV-Ray's EPSILON */
#define COORD_LIMIT 1.0e17 /* warped points are clamped to this */

/* The noise generator of pt (0, not patched by the evaluator: POV-Ray's 2). */
static int gen(const struct pattern *pt) { return pt->noise_gen ? pt->noise_gen : 2; }

static struct turb_params params(const struct warp *w)
{
	return (struct turb_params){w->octaves, w->omega, w->lambda};
}

/* The pattern's own turbulence when it is the last warp to act, else NULL. */
static const struct warp *own_turb(const struct pattern *pt)
{
	if (pt->nwarps == 0)
		return NULL;
	const struct warp *w = &pt->warps[pt->nwarps - 1];
	return w->kind == WARP_TURB && w->classic ? w : NULL;
}

/* ==== warps =============================================================== */

/* repeat: every other block of width along the axis flips, and each block
 * shifts by offset (the block number is single precision, as in POV-Ray). */
static struct vec3 warp_repeat(const struct warp *w, struct vec3 q)
{
	double c[3] = {q.x, q.y, q.z}, f[3] = {w->flip.x, w->flip.y, w->flip.z};
	float blk = (float)floor(c[w->axis] / w->width);
	double r[3] = {c[0], c[1], c[2]};
	r[w->axis] = c[w->axis] - blk * w->width;
	if (fmod(fabs((double)blk), 2) >= 1) { /* an odd block (no int overflow for huge ones) */
		for (int i = 0; i < 3; i++)
			r[i] *= f[i];
		if (f[w->axis] < 0)
			r[w->axis] = w->width + r[w->axis];
	}
	return v_madd(v3(r[0], r[1], r[2]), w->offset, blk);
}

/* black_hole: points within radius are pulled toward the centre by
 * ((radius − d)/radius)^falloff · strength of their offset, at most all. */
static struct vec3 warp_black_hole(const struct warp *w, struct vec3 q)
{
	struct vec3 d = v_sub(q, w->center);
	double len = v_len(d);
	if (len >= w->radius)
		return q;
	double s = pow((w->radius - len) / w->radius, w->falloff) * w->strength;
	s = fmin(s, 1);
	return v_madd(q, d, w->inverse ? -s : s);
}

/* p through the identity, as xf_inv_point(&xf_ident, p) gives it: for
 * finite coordinates x·1 + (±0) + (±0) + 0 is x, and +0 for ±0 (the last
 * +0 turns -0 into +0), so x + 0 is the same number, without the call and
 * its nine products. */
static struct vec3 ident_point(struct vec3 p)
{
	if (isfinite(p.x) && isfinite(p.y) && isfinite(p.z))
		return v3(p.x + 0.0, p.y + 0.0, p.z + 0.0);
	return xf_inv_point(&xf_ident, p); /* an infinite coordinate: 0·inf */
}

struct vec3 pattern_point(const struct pigment *pg, struct vec3 p)
{
	struct vec3 q = pg->xf ? xf_inv_point(pg->xf, p) : ident_point(p);
	const struct pattern *pt = pig_pattern(pg);
	if (pt->nwarps == 0)
		return q;
	bool own = pg->kind == PIG_PATTERN && (pt->pattern == PAT_MARBLE || pt->pattern == PAT_WOOD);
	for (int i = 0; i < pt->nwarps; i++) {
		const struct warp *w = &pt->warps[i];
		switch (w->kind) {
		case WARP_TURB: {
			if (w->classic && own)
				break;
			struct turb_params tp = params(w);
			q = v_add(q, v_mul(noise_dturb(q, &tp), w->turb));
			break;
		}
		case WARP_REPEAT: q = warp_repeat(w, q); break;
		case WARP_BLACK_HOLE: q = warp_black_hole(w, q); break;
		case WARP_XF: q = xf_inv_point(w->xf, q); break;
		}
	}
	q.x = fmin(fmax(q.x, -COORD_LIMIT), COORD_LIMIT);
	q.y = fmin(fmax(q.y, -COORD_LIMIT), COORD_LIMIT);
	q.z = fmin(fmax(q.z, -COORD_LIMIT), COORD_LIMIT);
	return q;
}

/* ==== the patterns ======================================================== */

/* granite: six octaves of |noise| folded about its middle, from 4 q. */
static double granite(struct vec3 q, int g)
{
	double sum = 0, freq = 1;
	for (int i = 0; i < 6; i++, freq *= 2) {
		double n = noise_at(v_scale(q, 4 * freq), g), t;
		if (g == 1) {
			t = fabs(0.5 - n);
		} else {
			t = fabs(1 - 2 * n);
			t = fmin(t, 0.5);
		}
		sum += t / freq;
	}
	return sum;
}

/* wrinkles (as a pigment): ten octaves of noise, halved. */
static double wrinkles(struct vec3 q, int g)
{
	double v = g == 1 ? noise_at(q, g) : fmin(fmax(noise_at(q, g) * 2 - 0.5, 0), 1);
	double lambda = 2, omega = 0.5;
	for (int i = 1; i < 10; i++) {
		double n = noise_at(v_scale(q, lambda), g);
		v += omega * (g == 1 ? n : fmin(fmax(n * 2 - 0.5, 0), 1));
		lambda *= 2;
		omega *= 0.5;
	}
	return v / 2;
}

/* marble: x, displaced by the turbulence (POV-Ray's default wave for it is
 * the triangle). */
static double marble(const struct pattern *pt, struct vec3 q)
{
	const struct warp *t = own_turb(pt);
	if (!t)
		return q.x;
	struct turb_params tp = params(t);
	return q.x + t->turb.x * noise_turb(q, &tp, gen(pt));
}

/* wood: the distance from the z axis, its rings bent by the turbulence. */
static double wood(const struct pattern *pt, struct vec3 q)
{
	const struct warp *t = own_turb(pt);
	double px = 0, py = 0;
	if (t) {
		struct turb_params tp = params(t);
		struct vec3 d = noise_dturb(q, &tp);
		px = noise_cycloidal((q.x + d.x) * t->turb.x);
		py = noise_cycloidal((q.y + d.y) * t->turb.y);
	}
	px += q.x;
	py += q.y;
	return sqrt(px * px + py * py);
}

/* agate: bands along z bent by turbulence scaled by agate_turb. */
static double agate(const struct pattern *pt, struct vec3 q)
{
	static const struct warp none = {.kind = WARP_TURB, .octaves = 6, .omega = 0.5, .lambda = 2};
	const struct warp *t = own_turb(pt);
	struct turb_params tp = params(t ? t : &none);
	double tv = pt->agate_turb * noise_turb(q, &tp, gen(pt));
	double n = 0.5 * (noise_cycloidal(1.3 * tv + 1.1 * q.z) + 1);
	return n < 0 ? 0 : pow(fmin(1, n), 0.77);
}

/* spiral1, spiral2: arms about the z axis, the radius and z added. */
static double spiral(const struct pattern *pt, struct vec3 q, bool two)
{
	const struct warp *t = own_turb(pt);
	double tv = 0;
	if (t) {
		struct turb_params tp = params(t);
		tv = t->turb.x * noise_turb(q, &tp, gen(pt));
	}
	double rad = sqrt(q.x * q.x + q.y * q.y), phi = 0;
	if (rad != 0)
		phi = q.x < 0 ? 3 * M_PI_2 - asin(q.y / rad) : M_PI_2 + asin(q.y / rad);
	double v = q.z + rad + pt->arms * phi / (2 * M_PI) + tv;
	return two ? noise_triangle(rad) + noise_triangle(v) : v;
}

/* ripples and waves: point sources of circular waves (ten unless
 * number_of_waves says); waves gives each its own frequency and amplitude. */
/* The number of wave sources (global_settings' number_of_waves). */
static int nwaves(const struct pattern *pt) { return pt->nwaves > 0 ? pt->nwaves : 10; }

static double ripples(const struct pattern *pt, struct vec3 q, bool waves)
{
	double sum = 0;
	int n = nwaves(pt);
	for (int i = 0; i < n; i++) {
		double len = v_len(v_sub(q, noise_wave_source(i)));
		if (len == 0)
			len = 1;
		if (waves) {
			double f = noise_wave_freq(i);
			sum += noise_cycloidal(len * pt->frequency * f + pt->phase) / f;
		} else {
			sum += noise_cycloidal(len * pt->frequency + pt->phase);
		}
	}
	return waves ? 0.2 * (2.5 + sum / n) : 0.5 * (1 + sum / n);
}

/* quilted's cubic of the distance from the cell centre. */
static double quilt_cubic(double t, double p1, double p2)
{
	double it = 1 - t;
	return (t * t * t + 3 * t * it * it * p1 + 3 * t * t * it * p2) * 1.154700538;
}

/* POV-Ray's FLOOR: floor, but one lower at negative whole numbers. */
static double pov_floor(double x) { return x >= 0 ? floor(x) : -floor(-x) - 1; }

/* The offset of q from its cell centre, scaled by quilted's cubic. */
static struct vec3 quilt(const struct pattern *pt, struct vec3 q)
{
	struct vec3 v = v3(q.x - pov_floor(q.x) - 0.5, q.y - pov_floor(q.y) - 0.5, q.z - pov_floor(q.z) - 0.5);
	return v_scale(v, quilt_cubic(v_len(v), pt->control0, pt->control1));
}

/* The distance of d under crackle's metric, before the root. */
static double metric_sum(double m, struct vec3 d)
{
	if (m == 2)
		return d.x * d.x + d.y * d.y + d.z * d.z;
	if (m == 1)
		return fabs(d.x) + fabs(d.y) + fabs(d.z);
	return pow(fabs(d.x), m) + pow(fabs(d.y), m) + pow(fabs(d.z), m);
}

static double metric_root(double m, double s)
{
	return m == 2 ? sqrt(s) : m == 1 ? s : pow(s, 1 / m);
}

/* crackle: a random point in each unit cell; the value combines the
 * distances to the nearest three by form (or, solid, the noise at the
 * nearest), searching the 81 cells within a knight's move. */
static double crackle(const struct pattern *pt, struct vec3 q)
{
	q = v3(noise_tame(q.x), noise_tame(q.y), noise_tame(q.z));
	int fx = (int)floor(q.x - EPS), fy = (int)floor(q.y - EPS), fz = (int)floor(q.z - EPS);
	double m = pt->metric, d[3] = {INFINITY, INFINITY, INFINITY};
	struct vec3 nearest = v3(0, 0, 0);
	for (int ax = -2; ax <= 2; ax++)
		for (int ay = -2; ay <= 2; ay++)
			for (int az = -2; az <= 2; az++) {
				if ((abs(ax) == 2) + (abs(ay) == 2) + (abs(az) == 2) > 1)
					continue;
				int cx = fx + ax, cy = fy + ay, cz = fz + az;
				unsigned long seed = (unsigned long)noise_hash3(cx & 0xFFF, cy & 0xFFF, cz & 0xFFF);
				struct vec3 c = v3(cx + noise_rand(seed), cy + noise_rand(seed + 1), cz + noise_rand(seed + 2));
				double s = metric_sum(m, v_sub(c, q));
				if (s < d[0]) {
					d[2] = d[1], d[1] = d[0], d[0] = s;
					nearest = c;
				} else if (s < d[1]) {
					d[2] = d[1], d[1] = s;
				} else if (s < d[2]) {
					d[2] = s;
				}
			}
	if (pt->offset != 0) {
		double o = m == 2 ? pt->offset * pt->offset : m == 1 ? pt->offset : pow(pt->offset, m);
		for (int i = 0; i < 3; i++)
			d[i] += o;
	}
	double v = pt->solid ? noise_at(nearest, gen(pt))
	                     : pt->form.x * metric_root(m, d[0]) + pt->form.y * metric_root(m, d[1]) +
	                           pt->form.z * metric_root(m, d[2]);
	return fmax(fmin(v, 1), 0);
}

/* mandel: the escape time of z -> z^e + c, c = (x, y), over the iterations
 * (1 inside: POV-Ray's default exterior and interior types). */
static double mandel(const struct pattern *pt, struct vec3 q)
{
	double a = q.x, b = q.y, a2 = a * a, b2 = b * b;
	int max = pt->arms > 0 ? pt->arms : 1;
	for (int i = 0; i < max; i++) {
		double na, nb;
		if (pt->exponent_i == 3) {
			nb = 3 * a2 * b - b2 * b + q.y;
			na = a2 * a - 3 * a * b2 + q.x;
		} else if (pt->exponent_i == 4) {
			nb = 4 * (a2 * a * b - a * b2 * b) + q.y;
			na = a2 * a2 - 6 * a2 * b2 + b2 * b2 + q.x;
		} else {
			nb = 2 * a * b + q.y;
			na = a2 - b2 + q.x;
		}
		a = na, b = nb, a2 = a * a, b2 = b * b;
		if (a2 + b2 > 4)
			return (double)i / max;
	}
	return 1;
}

double pattern_noise_raw(const struct pattern *pt, struct vec3 q)
{
	switch (pt->pattern) {
	case PAT_BOZO: case PAT_SPOTTED: case PAT_BUMPS: return noise_at(q, gen(pt));
	case PAT_DENTS: {
		double n = noise_at(q, gen(pt));
		return n * n * n;
	}
	case PAT_GRANITE: return granite(q, gen(pt));
	case PAT_MARBLE: return marble(pt, q);
	case PAT_WOOD: return wood(pt, q);
	case PAT_AGATE: return agate(pt, q);
	case PAT_WRINKLES: return wrinkles(q, gen(pt));
	case PAT_RIPPLES: return ripples(pt, q, false);
	case PAT_WAVES: return ripples(pt, q, true);
	case PAT_CRACKLE: return crackle(pt, q);
	case PAT_QUILTED: {
		struct vec3 v = quilt(pt, q);
		return (fabs(v.x) + fabs(v.y) + fabs(v.z)) / 3;
	}
	case PAT_SPIRAL1: return spiral(pt, q, false);
	case PAT_SPIRAL2: return spiral(pt, q, true);
	case PAT_CELLS: { /* a random value for each unit cube */
		int h = noise_hash3((int)floor(noise_tame(q.x) + EPS), (int)floor(noise_tame(q.y) + EPS),
		                    (int)floor(noise_tame(q.z) + EPS));
		return fmin(noise_rand((unsigned long)h), 1);
	}
	case PAT_MANDEL: return mandel(pt, q);
	default: return 0;
	}
}

/* ==== normals ============================================================= */

bool pattern_normal_direct(const struct tnormal *t, struct vec3 q, struct vec3 *n)
{
	if (t->pat.kind != PIG_PATTERN)
		return false;
	const struct pattern *pt = pig_pattern(&t->pat);
	double a = t->amount;
	switch (pt->pattern) {
	case PAT_BUMPS: *n = v_madd(*n, noise_vec(q), a); return true;
	case PAT_DENTS: {
		double s = noise_at(q, gen(pt));
		*n = v_madd(*n, noise_vec(q), s * s * s * a);
		return true;
	}
	case PAT_RIPPLES: case PAT_WAVES:
		for (int i = 0, k = nwaves(pt); i < k; i++) {
			struct vec3 d = v_sub(q, noise_wave_source(i));
			double len = v_len(d), f = pt->pattern == PAT_WAVES ? noise_wave_freq(i) : 1;
			if (len == 0)
				len = 1;
			double s = noise_cycloidal(len * pt->frequency * f + pt->phase) * a / f;
			*n = v_madd(*n, d, s / (len * nwaves(pt)));
		}
		return true;
	case PAT_WRINKLES: {
		struct vec3 r = v3(0, 0, 0);
		double scale = 1;
		for (int i = 0; i < 10; i++, scale *= 2) {
			struct vec3 v = noise_vec(v_scale(q, scale));
			r = v_add(r, v3(fabs(v.x / scale), fabs(v.y / scale), fabs(v.z / scale)));
		}
		*n = v_madd(*n, r, a);
		return true;
	}
	case PAT_QUILTED: *n = v_madd(*n, quilt(pt, q), a); return true;
	default: return false;
	}
}
