/* SPDX-License-Identifier: MIT */
/* pattern.c: POV-Ray's patterns. Each raw function follows the definition
 * of POV-Ray 3.7 (its documentation and pattern.cpp): the value before the
 * wave, then pattern_value applies frequency, phase and the wave exactly as
 * POV-Ray does, including its modulus of 1.00001 (docs/design.md §10). */
#include "pattern.h"

#include <math.h>

#include "material.h"
#include "noise.h"
#include "fn.h"

/* 1 − v for v in [0,1], 0 beyond, 1 below 0 (POV-Ray's CLIP_DENSITY). */
static double clip_density(double v) { return v < 0 ? 1 : v > 1 ? 0 : 1 - v; }

/* Raw gradient: q·axis, reduced modulo 1 above 1 (negative values are
 * wrapped by the wave step). */
static double gradient_raw(const struct pigment *pg, struct vec3 q)
{
	double v = v_dot(q, pig_pattern(pg)->axis);
	return v > 1 ? fmod(v, 1) : v;
}

/* The angle about y, starting a quarter turn from -z, in turns. */
static double radial_raw(struct vec3 q)
{
	if (fabs(q.x) < 0.001 && fabs(q.z) < 0.001)
		return 0.25;
	return 0.25 + (atan2(q.x, q.z) + M_PI) / (2 * M_PI);
}

static double leopard_raw(struct vec3 q)
{
	double s = (sin(q.x) + sin(q.y) + sin(q.z)) / 3;
	return s * s;
}

/* A function's value at q, reduced modulo 1 above 1 as POV-Ray's function
 * pattern does (the wave step wraps negative values); 0 where the function
 * is not finite. */
static double function_raw(const struct fn *f, struct vec3 q)
{
	double a[FN_MAX_PARAMS] = {q.x, q.y, q.z};
	double v = fn_eval(f, a);
	if (!isfinite(v))
		return 0;
	return v > 1 ? fmod(v, 1) : v;
}

static double raw(const struct pigment *pg, struct vec3 q)
{
	if (pg->kind == PIG_GRADIENT)
		return gradient_raw(pg, q);
	if (pg->kind == PIG_CHECKER || pg->kind == PIG_HEXAGON || pg->kind == PIG_BRICK)
		return pattern_block(pg, q); /* in a normal: the index, through the wave */
	switch (pig_pattern(pg)->pattern) {
	case PAT_RADIAL: return radial_raw(q);
	case PAT_ONION: return sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
	case PAT_SPHERICAL: return clip_density(sqrt(q.x * q.x + q.y * q.y + q.z * q.z));
	case PAT_CYLINDRICAL: return clip_density(sqrt(q.x * q.x + q.z * q.z));
	case PAT_BOXED: return clip_density(fmax(fabs(q.x), fmax(fabs(q.y), fabs(q.z))));
	case PAT_PLANAR: return clip_density(fabs(q.y));
	case PAT_LEOPARD: return leopard_raw(q);
	case PAT_PIGMENT: /* in a normal: the grey of the pigment (without image maps) */
		return pig_pattern(pg)->sub ? pattern_grey(mat_pigment(NULL, pig_pattern(pg)->sub, q)) : 0;
	case PAT_AVERAGE: return 0;
	case PAT_FUNCTION: return function_raw(pig_pattern(pg)->fn, q);
	default: return pattern_noise_raw(pig_pattern(pg), q);
	}
}

double pattern_wave(const struct pigment *pg, double v)
{
	const struct pattern *pt = pig_pattern(pg);
	if (pt->frequency != 0)
		v = fmod(v * pt->frequency + pt->phase, 1.00001);
	if (v < 0)
		v -= floor(v);
	switch (pt->wave) {
	case WAVE_TRIANGLE: return noise_triangle(v);
	case WAVE_SINE: return (1 + noise_cycloidal(v)) * 0.5;
	case WAVE_SCALLOP: return fabs(noise_cycloidal(v * 0.5));
	case WAVE_CUBIC: return v * v * (3 - 2 * v);
	case WAVE_POLY: return pow(v, pt->exponent);
	default: return v;
	}
}

double pattern_value(const struct pigment *pg, struct vec3 q)
{
	return pattern_wave(pg, raw(pg, q));
}

/* POV-Ray's hexagon: the x-z plane tiled by hexagons of unit side, three
 * colours, none touching another of its own. The plane is cut into a 6×6
 * grid of half-triangle cells (0.5 × √3/2); most cells are one colour,
 * the rest are split by a hexagon edge at 45° in grid units. */
static int hexagon(struct vec3 q)
{
	const double xf = 0.5, zf = 0.866025404, zrep = 5.196152424; /* √3/2, 6·√3/2 */
	double x = fabs(q.x), z = q.z < 0 ? zrep - fabs(q.z) : q.z;
	double xs = x / xf, zs = z / zf;
	xs -= floor(xs / 6) * 6;
	zs -= floor(zs / 6) * 6;
	int xm = (int)floor(xs) % 6, zm = (int)floor(zs) % 6;
	/* colour of each row zm for columns 0/5 and 2/3 */
	static const int even[6] = {0, 1, 1, 2, 2, 0}, odd[6] = {2, 2, 0, 0, 1, 1};
	/* split columns 1/4: below and above the edge */
	static const int below[6] = {0, 2, 1, 0, 2, 1}, above[6] = {2, 1, 0, 2, 1, 0};
	switch (xm) {
	case 0: case 5: return even[zm];
	case 2: case 3: return odd[zm];
	default: {
		double xl = xs - xm, zl = zs - zm;
		if ((xm + zm) % 2 == 1)
			xl = 1 - xl;
		if (xl == 0)
			xl = 0.0001;
		return zl / xl < 1 ? below[zm] : above[zm];
	}
	}
}

/* The fractional part as POV-Ray's brick takes it: truncation, then +1
 * below zero. */
static double frac_trunc(double v)
{
	double f = v - (double)(long)v;
	return f < 0 ? f + 1 : f;
}

/* POV-Ray's brick: 0 in the mortar, 1 in a brick. Courses alternate every
 * brick height, each offset by half a brick along x (ends) and z (faces). */
static int brick(const struct pigment *pg, struct vec3 q)
{
	const double small = 1e-6; /* POV-Ray's Small_Tolerance */
	double m = pig_pattern(pg)->mortar, fudge = small + m;
	double x = q.x + fudge, y = q.y + fudge, z = q.z + fudge;
	struct vec3 sz = pig_pattern(pg)->brick_size;
	double mw = m / sz.x, mh = m / sz.y, md = m / sz.z;
	if (frac_trunc(y / sz.y) <= mh)
		return 0;
	bool odd = frac_trunc(y / sz.y * 0.5) <= 0.5;
	if (frac_trunc(x / sz.x + (odd ? 0 : 0.5)) <= mw)
		return 0;
	if (frac_trunc(z / sz.z + (odd ? 0.5 : 0)) <= md)
		return 0;
	return 1;
}

int pattern_block(const struct pigment *pg, struct vec3 q)
{
	switch (pg->kind) {
	case PIG_HEXAGON: return hexagon(q);
	case PIG_BRICK: return brick(pg, q);
	default: return pattern_checker(q);
	}
}

double pattern_grey(struct colour c) { return 0.297 * c.r + 0.589 * c.g + 0.114 * c.b; }

/* A world normal into the frame of X (the transpose of its linear part). */
static struct vec3 xf_inv_normal(const struct xform *X, struct vec3 n)
{
	const double (*m)[4] = X->m;
	return v3(m[0][0] * n.x + m[1][0] * n.y + m[2][0] * n.z, m[0][1] * n.x + m[1][1] * n.y + m[2][1] * n.z,
	          m[0][2] * n.x + m[1][2] * n.y + m[2][2] * n.z);
}

/* The unit normal n into the pattern's space: through its transform, then
 * the transforms among its warps (turbulence leaves normals alone). */
static struct vec3 normal_in(const struct pigment *pg, struct vec3 n)
{
	n = v_norm(xf_inv_normal(pg->xf ? pg->xf : &xf_ident, n));
	const struct pattern *pt = pig_pattern(pg);
	for (int i = 0; i < pt->nwarps; i++)
		if (pt->warps[i].kind == WARP_XF)
			n = xf_inv_normal(pt->warps[i].xf, n);
	return v_norm(n);
}

/* The pattern-space normal n back to the world, the reverse of normal_in. */
static struct vec3 normal_out(const struct pigment *pg, struct vec3 n)
{
	const struct pattern *pt = pig_pattern(pg);
	n = v_norm(n);
	for (int i = pt->nwarps - 1; i >= 0; i--)
		if (pt->warps[i].kind == WARP_XF)
			n = xf_normal(pt->warps[i].xf, n);
	return v_norm(xf_normal(pg->xf ? pg->xf : &xf_ident, n));
}

/* An entry of a normal_map at pattern-space point q (none: n unchanged). */
static struct vec3 entry_normal(const struct tnormal *e, struct vec3 q, struct vec3 n)
{
	return e ? pattern_perturb(e, q, n) : n;
}

/* normal_map at value v: the entries around v perturb the pattern-space
 * normal n at q (their own transforms relative to the map's), blended. */
static struct vec3 normal_map(const struct tnormal *t, double v, struct vec3 q, struct vec3 n)
{
	const struct nrm_entry *m = t->map;
	int k = t->nmap, i = 0;
	if (v >= m[k - 1].pos)
		return entry_normal(m[k - 1].n, q, n);
	while (v > m[i].pos)
		i++;
	if (i == 0 || v == m[i].pos)
		return entry_normal(m[i].n, q, n);
	double w = (v - m[i - 1].pos) / (m[i].pos - m[i - 1].pos);
	return v_add(v_scale(entry_normal(m[i - 1].n, q, n), 1 - w), v_scale(entry_normal(m[i].n, q, n), w));
}

struct vec3 pattern_perturb(const struct tnormal *t, struct vec3 p, struct vec3 n)
{
	/* POV-Ray's tetrahedron, its spacing 0.02 and its gain −5 per unit of
	 * bump size (the sum of the corners is zero, so a flat pattern tilts
	 * nothing) */
	static const struct vec3 corner[4] = {
		{0.942809041, -0.333333333, 0}, {-0.471404521, -0.333333333, 0.816496581},
		{-0.471404521, -0.333333333, -0.816496581}, {0, 1, 0}};
	const double delta = 0.02;
	struct vec3 np = normal_in(&t->pat, n), q = pattern_point(&t->pat, p);
	if (t->map && t->nmap > 0 && t->pat.kind == PIG_PATTERN && pig_pattern(&t->pat)->pattern == PAT_AVERAGE) {
		struct vec3 sum = v3(0, 0, 0); /* average: the entries' normals by weight */
		double total = 0;
		for (int i = 0; i < t->nmap; i++) {
			sum = v_madd(sum, entry_normal(t->map[i].n, q, np), t->map[i].pos);
			total += t->map[i].pos;
		}
		return normal_out(&t->pat, total != 0 ? v_scale(sum, 1 / total) : np);
	}
	if (t->map && t->nmap > 0) { /* normal_map: the two entries' normals blended */
		enum pigment_kind k = t->pat.kind;
		double v = k == PIG_CHECKER || k == PIG_HEXAGON || k == PIG_BRICK ? pattern_block(&t->pat, q)
		                                                                 : pattern_value(&t->pat, q);
		return normal_out(&t->pat, normal_map(t, v, q, np));
	}
	if (!pattern_normal_direct(t, q, &np)) {
		double gain = -5 * t->amount;
		for (int i = 0; i < 4; i++)
			np = v_madd(np, corner[i], gain * pattern_value(&t->pat, v_madd(q, corner[i], delta)));
	}
	return normal_out(&t->pat, np);
}
