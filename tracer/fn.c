/* SPDX-License-Identifier: MIT */
/* fn.c: the stack machine that runs compiled functions, and POV-Ray's
 * internal(N) functions (docs/design.md §2, "Functions"). */
#include "fn.h"

#include <math.h>

#include "material.h"
#include "noise.h"
#include "pattern.h"

/* ==== internal(N) ========================================================= */

/* POV-Ray's built-in functions take x, y, z and then their own parameters
 * p[0] …; each is defined by its documentation (functions.inc). */
typedef double (*internal_fn)(const double *a);
typedef double (*noise_fn)(const double *a, int gen); /* gen: the scene's noise generator */

#define X a[0]
#define Y a[1]
#define Z a[2]
#define P(i) a[3 + (i)]

static double clamp10(double v) { return fmin(10.0, fmax(v, -10.0)); }

/* f_r: distance from the origin. */
static double i_r(const double *a) { return sqrt(X * X + Y * Y + Z * Z); }
/* f_th: the angle about y, from +z towards +x. */
static double i_th(const double *a) { return atan2(X, Z); }
/* f_ph: the angle from +y. */
static double i_ph(const double *a) { return atan2(sqrt(X * X + Z * Z), Y); }
/* f_sphere(x, y, z, radius): signed distance to the sphere. */
static double i_sphere(const double *a) { return sqrt(X * X + Y * Y + Z * Z) - P(0); }

/* f_torus(x, y, z, major, minor): signed distance to a torus about y. */
static double i_torus(const double *a)
{
	double d = sqrt(X * X + Z * Z) - P(0);
	return sqrt(d * d + Y * Y) - P(1);
}

/* f_rounded_box(x, y, z, radius, sx, sy, sz): a box of half sizes s with
 * its edges rounded by radius; negative inside. */
static double i_rounded_box(const double *a)
{
	double r = P(0), d[3];
	for (int k = 0; k < 3; k++) {
		double q = fabs(a[k]) - (P(1 + k) - r);
		d[k] = q > 0 ? q : 0;
	}
	return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - r - 1e-6;
}

/* f_superellipsoid(x, y, z, e, n): 1 − the superquadric's inside-outside
 * value, so positive inside (as POV-Ray's). */
static double i_superellipsoid(const double *a)
{
	double e = P(0), n = P(1);
	double xy = pow(pow(fabs(X), 2 / e) + pow(fabs(Y), 2 / e), e / n);
	return 1 - pow(xy + pow(fabs(Z), 2 / n), n * 0.5);
}

/* f_paraboloid(x, y, z, strength). */
static double i_paraboloid(const double *a) { return clamp10(-P(0) * (X * X - Y + Z * Z)); }

/* f_torus2(x, y, z, strength, major, minor): the torus's quartic. */
static double i_torus2(const double *a)
{
	double x2 = X * X, y2 = Y * Y, z2 = Z * Z, R = P(1) * P(1), r = P(2) * P(2);
	double q = x2 * x2 + y2 * y2 + z2 * z2 + 2 * x2 * y2 + 2 * x2 * z2 + 2 * y2 * z2 -
	           2 * (R + r) * x2 + 2 * (R - r) * y2 - 2 * (R + r) * z2 + (R - r) * (R - r);
	return clamp10(-P(0) * q);
}

/* f_spikes_2d(x, y, z, height, freq x, freq z, falloff): a height field. */
static double i_spikes_2d(const double *a)
{
	return -(P(0) * cos(P(1) * X) * cos(P(2) * Z) * exp(-P(3) * (X * X + Z * Z)) - Y);
}

/* f_noise3d: the scene's noise, in [0, 1]. */
static double i_noise3d(const double *a, int gen) { return noise_at(v3(X, Y, Z), gen); }

/* f_noise_generator(x, y, z, generator): generator 1-3's noise (0 reads as 2, POV-Ray's default). */
static double i_noise_generator(const double *a, int gen)
{
	int g = (int)fmod(fabs(P(0)), 4);
	(void)gen;
	return noise_at(v3(X, Y, Z), g ? g : 2);
}

/* f_ridged_mf(x, y, z, H, lacunarity, octaves, offset, gain, generator):
 * Musgrave's ridged multifractal over the scene's noise: each octave's
 * ridge (offset − |2·noise − 1|)², weighted by the previous octave's
 * signal times gain (clamped to [0, 1]) and by frequency^−H. */
static double i_ridged_mf(const double *a, int gen)
{
	int g = (int)fmod(fabs(P(5)), 4);
	struct vec3 p = v3(X, Y, Z);
	double sig = P(3) - fabs(noise_at(p, g ? g : gen) * 2 - 1);
	sig *= sig;
	double sum = sig, freq = 1;
	int octaves = P(2) > 64 ? 64 : (int)P(2);
	for (int i = 1; i < octaves; i++) {
		p = v_scale(p, P(1));
		freq *= P(1);
		double w = fmin(1, fmax(0, sig * P(4)));
		sig = P(3) - fabs(noise_at(p, g ? g : gen) * 2 - 1);
		sig = sig * sig * w;
		sum += sig * pow(freq, -P(0));
	}
	return sum;
}

static const struct {
	const char *name;
	int extra;       /* parameters after x, y, z */
	internal_fn fn;  /* NULL (and noise NULL): not built */
	noise_fn noise;  /* the functions of the noise */
} internals[FN_INTERNAL_COUNT] = {
	[45] = {"f_paraboloid", 1, i_paraboloid},
	[47] = {"f_ph", 0, i_ph},
	[57] = {"f_r", 0, i_r},
	[60] = {"f_rounded_box", 4, i_rounded_box},
	[61] = {"f_sphere", 1, i_sphere},
	[63] = {"f_spikes_2d", 4, i_spikes_2d},
	[68] = {"f_superellipsoid", 2, i_superellipsoid},
	[69] = {"f_th", 0, i_th},
	[70] = {"f_torus", 2, i_torus},
	[71] = {"f_torus2", 3, i_torus2},
	[59] = {"f_ridged_mf", 6, NULL, i_ridged_mf},
	[76] = {"f_noise3d", 0, NULL, i_noise3d},
	[78] = {"f_noise_generator", 1, NULL, i_noise_generator},
};

#undef X
#undef Y
#undef Z
#undef P

struct fn_internal_info fn_internal(int n)
{
	struct fn_internal_info r = {NULL, 0};
	if (n >= 0 && n < FN_INTERNAL_COUNT && (internals[n].fn || internals[n].noise))
		r = (struct fn_internal_info){internals[n].name, 3 + internals[n].extra};
	return r;
}

/* ==== the machine ========================================================= */

static double math1(int which, double v)
{
	switch (which) {
	case FM_ABS: return fabs(v);
	case FM_ACOS: return acos(v);
	case FM_ACOSH: return acosh(v);
	case FM_ASIN: return asin(v);
	case FM_ASINH: return asinh(v);
	case FM_ATAN: return atan(v);
	case FM_ATANH: return atanh(v);
	case FM_CEIL: return ceil(v);
	case FM_COS: return cos(v);
	case FM_COSH: return cosh(v);
	case FM_DEGREES: return v * (180 / M_PI);
	case FM_EXP: return exp(v);
	case FM_FLOOR: return floor(v);
	case FM_INT: return trunc(v) + 0.0;
	case FM_LN: return log(v);
	case FM_LOG: return log10(v);
	case FM_RADIANS: return v * (M_PI / 180);
	case FM_SIN: return sin(v);
	case FM_SINH: return sinh(v);
	case FM_SQRT: return sqrt(v);
	case FM_TAN: return tan(v);
	default: return tanh(v);
	}
}

static double math2(int which, double a, double b)
{
	switch (which) {
	case FM_ATAN2: return atan2(a, b);
	case FM_DIV: return trunc(a / b) + 0.0;
	case FM_MAX: return fmax(a, b);
	case FM_MIN: return fmin(a, b);
	case FM_MOD: return fmod(a, b);
	default: return pow(a, b);
	}
}

/* The pattern's value at q (in the function's space): a continuous
 * pattern's after its wave, a block pattern's colour index. */
static double pattern_at(const struct pigment *pg, struct vec3 p)
{
	struct vec3 q = xf_inv_point(pg->xf ? pg->xf : &xf_ident, p);
	switch (pg->kind) {
	case PIG_CHECKER: case PIG_HEXAGON: case PIG_BRICK: return pattern_block(pg, q);
	case PIG_GRADIENT: case PIG_PATTERN: return pattern_value(pg, q);
	default: return 0;
	}
}

static double run(const struct fn *f, const double *args)
{
	double st[FN_MAX_STACK];
	int sp = 0;
	for (const struct fn_op *o = f->code, *end = f->code + f->ncode; o < end; o++) {
		switch ((enum fn_opcode)o->op) {
		case FO_CONST: st[sp++] = o->u.k; break;
		case FO_ARG: st[sp++] = args[o->i]; break;
		case FO_ADD: sp--; st[sp - 1] += st[sp]; break;
		case FO_SUB: sp--; st[sp - 1] -= st[sp]; break;
		case FO_MUL: sp--; st[sp - 1] *= st[sp]; break;
		case FO_DIV: sp--; st[sp - 1] /= st[sp]; break;
		case FO_POW: sp--; st[sp - 1] = pow(st[sp - 1], st[sp]); break;
		case FO_LT: sp--; st[sp - 1] = st[sp - 1] < st[sp]; break;
		case FO_LE: sp--; st[sp - 1] = st[sp - 1] <= st[sp]; break;
		case FO_GT: sp--; st[sp - 1] = st[sp - 1] > st[sp]; break;
		case FO_GE: sp--; st[sp - 1] = st[sp - 1] >= st[sp]; break;
		case FO_EQ: sp--; st[sp - 1] = st[sp - 1] == st[sp]; break;
		case FO_NE: sp--; st[sp - 1] = st[sp - 1] != st[sp]; break;
		case FO_AND: sp--; st[sp - 1] = st[sp - 1] != 0 && st[sp] != 0; break;
		case FO_OR: sp--; st[sp - 1] = st[sp - 1] != 0 || st[sp] != 0; break;
		case FO_NEG: st[sp - 1] = -st[sp - 1]; break;
		case FO_NOT: st[sp - 1] = st[sp - 1] == 0; break;
		case FO_MATH1: st[sp - 1] = math1(o->i, st[sp - 1]); break;
		case FO_MATH2: sp--; st[sp - 1] = math2(o->i, st[sp - 1], st[sp]); break;
		case FO_SELECT3: /* select(a, b, c): b when a < 0, else c */
			sp -= 2;
			st[sp - 1] = st[sp - 1] < 0 ? st[sp] : st[sp + 1];
			break;
		case FO_SELECT4: /* select(a, b, c, d): a < 0, a = 0, a > 0 */
			sp -= 3;
			st[sp - 1] = st[sp - 1] < 0 ? st[sp] : st[sp - 1] == 0 ? st[sp + 1] : st[sp + 2];
			break;
		case FO_CALL:
			sp -= o->i;
			st[sp] = fn_eval(o->u.f, st + sp);
			sp++;
			break;
		case FO_CALLC: {
			sp -= o->i;
			struct colour c = fn_eval_colour(o->u.f, st + sp);
			double comp[5] = {c.r, c.g, c.b, c.f, c.t};
			st[sp++] = o->j < 5 ? comp[o->j] : 0.297 * c.r + 0.589 * c.g + 0.114 * c.b;
			break;
		}
		}
	}
	return sp > 0 ? st[sp - 1] : 0;
}

double fn_eval(const struct fn *f, const double *args)
{
	switch (f->kind) {
	case FN_CODE: return run(f, args);
	case FN_INTERNAL: {
		int gen = pig_pattern(&f->pig)->noise_gen;
		if (internals[f->internal].noise)
			return internals[f->internal].noise(args, gen ? gen : 2);
		return internals[f->internal].fn(args);
	}
	case FN_PATTERN: return pattern_at(&f->pig, v3(args[0], args[1], args[2]));
	default: {
		struct colour c = fn_eval_colour(f, args);
		return 0.297 * c.r + 0.589 * c.g + 0.114 * c.b;
	}
	}
}

struct colour fn_eval_colour(const struct fn *f, const double *args)
{
	if (f->kind != FN_PIGMENT) {
		double v = fn_eval(f, args);
		return (struct colour){v, v, v, 0, 0};
	}
	/* the compiler refuses image_map here, so no image cache is needed */
	return mat_pigment(NULL, &f->pig, v3(args[0], args[1], args[2]));
}
