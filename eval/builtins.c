/* SPDX-License-Identifier: MIT */
/* builtins.c: POV-Ray's built-in constants and functions, one table. */
#include <ctype.h>
#include <errno.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "../tracer/noise.h"
#include "../tracer/shape.h"

/* ==== constants =========================================================== */

bool builtin_constant(struct eval *E, const char *name, struct value *out)
{
	static const struct { const char *name; double v[3]; int n; } consts[] = {
		{"pi", {M_PI}, 1}, {"tau", {2 * M_PI}, 1}, {"true", {1}, 1}, {"yes", {1}, 1},
		{"on", {1}, 1}, {"false", {0}, 1}, {"no", {0}, 1}, {"off", {0}, 1},
		{"x", {1, 0, 0}, 3}, {"y", {0, 1, 0}, 3}, {"z", {0, 0, 1}, 3},
		{"u", {1, 0}, 2}, {"v", {0, 1}, 2},
	};
	for (size_t i = 0; i < sizeof consts / sizeof consts[0]; i++) {
		if (strcmp(consts[i].name, name) == 0) {
			*out = consts[i].n == 1 ? val_float(consts[i].v[0]) : val_vector(consts[i].n, consts[i].v);
			return true;
		}
	}
	if (strcmp(name, "t") == 0) {
		double t4[4] = {0, 0, 0, 1};
		*out = val_vector(4, t4);
	} else if (strcmp(name, "clock") == 0) {
		*out = val_float(E->opt->clock);
	} else if (strcmp(name, "clock_on") == 0) {
		*out = val_float(E->opt->clock_on);
	} else if (strcmp(name, "frame_number") == 0) {
		*out = val_float(E->opt->frame);
	} else if (strcmp(name, "clock_delta") == 0) {
		*out = val_float(E->opt->clock_delta);
	} else if (strcmp(name, "initial_clock") == 0) {
		*out = val_float(E->opt->initial_clock);
	} else if (strcmp(name, "final_clock") == 0) {
		*out = val_float(E->opt->final_clock);
	} else if (strcmp(name, "initial_frame") == 0) {
		*out = val_float(E->opt->initial_frame);
	} else if (strcmp(name, "final_frame") == 0) {
		*out = val_float(E->opt->final_frame);
	} else if (strcmp(name, "image_width") == 0) {
		*out = val_float(E->opt->width);
	} else if (strcmp(name, "image_height") == 0) {
		*out = val_float(E->opt->height);
	} else if (strcmp(name, "version") == 0) {
		*out = val_float(E->scene->version);
	} else {
		return false;
	}
	return true;
}

/* ==== function helpers ==================================================== */

struct call {
	struct eval *E;
	const struct node *n;  /* the call node */
	struct value a[16];    /* evaluated arguments */
	int argc;
};

static double F(struct call *c, int i) { return val_want_float(c->E, &c->a[i], c->n->kids[i]->loc); }
static struct vec3 V(struct call *c, int i) { return val_want_vec3(c->E, &c->a[i], c->n->kids[i]->loc); }

static const char *S(struct call *c, int i, int *len)
{
	if (c->a[i].kind != V_STRING)
		eval_fail(c->E, c->n->kids[i]->loc, "argument %d of %s() must be a string, found %s", i + 1, c->n->str,
		          val_type_name(&c->a[i]));
	*len = c->a[i].n;
	return c->a[i].p.s;
}

static _Noreturn void domain(struct call *c, int i, const char *what)
{
	eval_fail(c->E, c->n->kids[i]->loc, "%s(): %s", c->n->str, what);
}

static struct value str_value(struct eval *E, const char *s, size_t n, struct srcloc loc)
{
	if (n > MAX_STRING)
		eval_fail(E, loc, "string too long (%zu bytes; the limit is %d)", n, MAX_STRING);
	return val_string(eval_strdup(E, s, (int)n), (int)n);
}

/* ==== maths =============================================================== */

static struct value f_abs(struct call *c) { return val_float(fabs(F(c, 0))); }
static struct value f_ceil(struct call *c) { return val_float(ceil(F(c, 0))); }
static struct value f_floor(struct call *c) { return val_float(floor(F(c, 0))); }
static struct value f_int(struct call *c) { return val_float(trunc(F(c, 0)) + 0.0); /* never -0 */ }
static struct value f_sin(struct call *c) { return val_float(sin(F(c, 0))); }
static struct value f_cos(struct call *c) { return val_float(cos(F(c, 0))); }
static struct value f_tan(struct call *c) { return val_float(tan(F(c, 0))); }
static struct value f_atan(struct call *c) { return val_float(atan(F(c, 0))); }
static struct value f_sinh(struct call *c) { return val_float(sinh(F(c, 0))); }
static struct value f_cosh(struct call *c) { return val_float(cosh(F(c, 0))); }
static struct value f_tanh(struct call *c) { return val_float(tanh(F(c, 0))); }
static struct value f_asinh(struct call *c) { return val_float(asinh(F(c, 0))); }
static struct value f_exp(struct call *c) { return val_float(exp(F(c, 0))); }
static struct value f_radians(struct call *c) { return val_float(F(c, 0) * M_PI / 180); }
static struct value f_degrees(struct call *c) { return val_float(F(c, 0) * 180 / M_PI); }

static struct value f_asin(struct call *c)
{
	double x = F(c, 0);
	if (x < -1 || x > 1)
		domain(c, 0, "argument outside [-1, 1]");
	return val_float(asin(x));
}

static struct value f_acos(struct call *c)
{
	double x = F(c, 0);
	if (x < -1 || x > 1)
		domain(c, 0, "argument outside [-1, 1]");
	return val_float(acos(x));
}

static struct value f_acosh(struct call *c)
{
	double x = F(c, 0);
	if (x < 1)
		domain(c, 0, "argument below 1");
	return val_float(acosh(x));
}

static struct value f_atanh(struct call *c)
{
	double x = F(c, 0);
	if (x <= -1 || x >= 1)
		domain(c, 0, "argument outside (-1, 1)");
	return val_float(atanh(x));
}

static struct value f_sqrt(struct call *c)
{
	double x = F(c, 0);
	if (x < 0)
		domain(c, 0, "square root of a negative number");
	return val_float(sqrt(x));
}

static struct value f_ln(struct call *c)
{
	double x = F(c, 0);
	if (x <= 0)
		domain(c, 0, "logarithm of a number that is not positive");
	return val_float(log(x));
}

static struct value f_log(struct call *c)
{
	double x = F(c, 0);
	if (x <= 0)
		domain(c, 0, "logarithm of a number that is not positive");
	return val_float(log10(x));
}

static struct value f_atan2(struct call *c) { return val_float(atan2(F(c, 0), F(c, 1))); }

static struct value f_pow(struct call *c)
{
	double a = F(c, 0), b = F(c, 1);
	if (a == 0 && b < 0)
		domain(c, 1, "zero to a negative power");
	if (a < 0 && b != floor(b))
		domain(c, 0, "negative base with a fractional exponent");
	return val_float(pow(a, b));
}

static struct value f_mod(struct call *c)
{
	double b = F(c, 1);
	if (b == 0)
		eval_fail(c->E, c->n->kids[1]->loc, "division by zero");
	return val_float(fmod(F(c, 0), b));
}

static struct value f_div(struct call *c)
{
	double b = F(c, 1);
	if (b == 0)
		eval_fail(c->E, c->n->kids[1]->loc, "division by zero");
	return val_float(trunc(F(c, 0) / b));
}

static struct value f_max(struct call *c)
{
	double m = F(c, 0);
	for (int i = 1; i < c->argc; i++)
		m = fmax(m, F(c, i));
	return val_float(m);
}

static struct value f_min(struct call *c)
{
	double m = F(c, 0);
	for (int i = 1; i < c->argc; i++)
		m = fmin(m, F(c, i));
	return val_float(m);
}

/* select(A, B, C): A < 0 ? B : C;  select(A, B, C, D): A <0, =0, >0. */
static struct value f_select(struct call *c)
{
	double a = F(c, 0);
	if (c->argc == 3)
		return a < 0 ? c->a[1] : c->a[2];
	return a < 0 ? c->a[1] : a == 0 ? c->a[2] : c->a[3];
}

/* ==== vectors ============================================================= */

static struct value f_vlength(struct call *c) { return val_float(v_len(V(c, 0))); }
static struct value f_vdot(struct call *c) { return val_float(v_dot(V(c, 0), V(c, 1))); }
static struct value f_vcross(struct call *c) { return val_vec3(v_cross(V(c, 0), V(c, 1))); }

static struct value f_vnormalize(struct call *c)
{
	struct vec3 a = V(c, 0);
	if (v_len(a) == 0)
		domain(c, 0, "cannot normalise a zero-length vector");
	return val_vec3(v_norm(a));
}

static struct value f_vrotate(struct call *c)
{
	struct xform r = xf_rotate(V(c, 1));
	return val_vec3(xf_vector(&r, V(c, 0)));
}

/* vturbulence(lambda, omega, octaves, p): POV-Ray's turbulence vector. */
static struct value f_vturbulence(struct call *c)
{
	double oct = F(c, 2);
	if (!(oct >= 1 && oct <= 64))
		domain(c, 2, "octaves must be 1 to 64");
	struct turb_params t = {(int)oct, F(c, 1), F(c, 0)};
	return val_vec3(noise_dturb(V(c, 3), &t));
}

static struct value f_vaxis_rotate(struct call *c)
{
	struct vec3 axis = V(c, 1);
	if (v_len(axis) == 0)
		domain(c, 1, "rotation axis has zero length");
	struct xform r = xf_axis_rotate(axis, F(c, 2));
	return val_vec3(xf_vector(&r, V(c, 0)));
}

/* ==== strings ============================================================= */

static struct value f_concat(struct call *c)
{
	size_t n = 0;
	for (int i = 0; i < c->argc; i++) {
		int len;
		S(c, i, &len);
		n += (size_t)len;
	}
	if (n > MAX_STRING)
		eval_fail(c->E, c->n->loc, "string too long (%zu bytes; the limit is %d)", n, MAX_STRING);
	char *buf = ARENA_ARRAY(&c->E->arena, char, n + 1);
	size_t at = 0;
	for (int i = 0; i < c->argc; i++) {
		int len;
		const char *s = S(c, i, &len);
		memcpy(buf + at, s, (size_t)len);
		at += (size_t)len;
	}
	return val_string(buf, (int)n);
}

/* Formats a float as POV-Ray's str(): width |L| (zero padded when L < 0),
 * P digits after the point (P < 0: six). The caller has checked L and P
 * (str_format_args), so the text fits STR_FLOAT_MAX bytes: 309 integer
 * digits at most for a finite double, a sign, a point and 60 decimals, or
 * 255 of padding. */
#define STR_FLOAT_MAX 400
static int format_float(char *buf, size_t size, double f, double L, double P)
{
	int w = (int)fabs(L), p = P < 0 ? 6 : (int)P;
	return snprintf(buf, size, L < 0 ? "%0*.*f" : "%*.*f", w, p, f);
}

/* Checks str()'s and vstr()'s width and precision: out of range or NaN is an
 * error at the argument, never a conversion out of range. */
static void str_format_args(struct call *c, int li, int pi)
{
	double L = F(c, li), P = F(c, pi);
	if (!(L >= -255 && L <= 255))
		domain(c, li, "the width must be -255 to 255");
	if (!(P >= -1 && P <= 60))
		domain(c, pi, "the precision must be -1 to 60");
}

static struct value f_str(struct call *c)
{
	char buf[STR_FLOAT_MAX];
	str_format_args(c, 1, 2);
	int n = format_float(buf, sizeof buf, F(c, 0), F(c, 1), F(c, 2));
	return str_value(c->E, buf, (size_t)n, c->n->loc);
}

/* vstr(N, V, Sep, L, P): the first N components of V, each formatted into
 * its own buffer and joined in one sized for them (never truncated). */
static struct value f_vstr(struct call *c)
{
	double fn = F(c, 0);
	int seplen;
	const char *sep = S(c, 2, &seplen);
	const struct value *v = &c->a[1];
	if (v->kind != V_VECTOR && v->kind != V_COLOUR && v->kind != V_FLOAT)
		eval_fail(c->E, c->n->kids[1]->loc, "argument 2 of vstr() must be a vector, found %s", val_type_name(v));
	if (!(fn >= 2 && fn < 6))
		domain(c, 0, "the component count must be 2 to 5");
	str_format_args(c, 3, 4);
	int n = (int)fn;
	char part[5][STR_FLOAT_MAX];
	int plen[5];
	size_t total = (size_t)(n - 1) * (size_t)seplen;
	for (int i = 0; i < n; i++) {
		double x = v->kind == V_FLOAT ? v->v[0] : v->v[i];
		plen[i] = format_float(part[i], sizeof part[i], x, F(c, 3), F(c, 4));
		total += (size_t)plen[i];
	}
	if (total > MAX_STRING)
		eval_fail(c->E, c->n->loc, "string too long (%zu bytes; the limit is %d)", total, MAX_STRING);
	char *buf = ARENA_ARRAY(&c->E->arena, char, total + 1);
	size_t at = 0;
	for (int i = 0; i < n; i++) {
		if (i) {
			memcpy(buf + at, sep, (size_t)seplen);
			at += (size_t)seplen;
		}
		memcpy(buf + at, part[i], (size_t)plen[i]);
		at += (size_t)plen[i];
	}
	return val_string(buf, (int)at);
}

static struct value f_chr(struct call *c)
{
	double f = F(c, 0);
	if (f < 1 || f > 0xFFFF)
		domain(c, 0, "character code out of range");
	unsigned cp = (unsigned)f;
	char b[4];
	int n;
	if (cp < 0x80)
		b[0] = (char)cp, n = 1;
	else if (cp < 0x800)
		b[0] = (char)(0xC0 | cp >> 6), b[1] = (char)(0x80 | (cp & 0x3F)), n = 2;
	else
		b[0] = (char)(0xE0 | cp >> 12), b[1] = (char)(0x80 | ((cp >> 6) & 0x3F)), b[2] = (char)(0x80 | (cp & 0x3F)), n = 3;
	return str_value(c->E, b, (size_t)n, c->n->loc);
}

static struct value f_strlen(struct call *c)
{
	int len;
	S(c, 0, &len);
	return val_float(len);
}

static struct value f_substr(struct call *c)
{
	int len;
	const char *s = S(c, 0, &len);
	double pos = F(c, 1), n = F(c, 2);
	if (pos < 1 || n < 0 || pos - 1 + n > len)
		eval_fail(c->E, c->n->loc, "substr(): range %g+%g is outside the string (length %d)", pos, n, len);
	return str_value(c->E, s + (int)pos - 1, (size_t)n, c->n->loc);
}

static struct value change_case(struct call *c, int upper)
{
	int len;
	const char *s = S(c, 0, &len);
	char *b = eval_strdup(c->E, s, len);
	for (int i = 0; i < len; i++)
		b[i] = (char)(upper ? toupper((unsigned char)b[i]) : tolower((unsigned char)b[i]));
	return val_string(b, len);
}

static struct value f_strupr(struct call *c) { return change_case(c, 1); }
static struct value f_strlwr(struct call *c) { return change_case(c, 0); }

static struct value f_val(struct call *c)
{
	int len;
	const char *s = S(c, 0, &len);
	char *z = eval_strdup(c->E, s, len);
	return val_float(strtod(z, NULL));
}

static struct value f_asc(struct call *c)
{
	int len;
	const char *s = S(c, 0, &len);
	return val_float(len ? (unsigned char)s[0] : 0);
}

static struct value f_strcmp(struct call *c)
{
	int la, lb;
	const char *a = S(c, 0, &la), *b = S(c, 1, &lb);
	int r = memcmp(a, b, (size_t)(la < lb ? la : lb));
	if (r == 0)
		r = la - lb;
	return val_float(r < 0 ? -1 : r > 0);
}

/* ==== arrays and random numbers =========================================== */

static struct array *A(struct call *c, int i)
{
	if (c->a[i].kind != V_ARRAY)
		eval_fail(c->E, c->n->kids[i]->loc, "argument %d of %s() must be an array, found %s", i + 1, c->n->str,
		          val_type_name(&c->a[i]));
	return c->a[i].p.arr;
}

static struct value f_dimensions(struct call *c) { return val_float(A(c, 0)->ndims); }

static struct value f_dimension_size(struct call *c)
{
	struct array *a = A(c, 0);
	double d = F(c, 1);
	if (d < 1 || d > a->ndims)
		domain(c, 1, "no such dimension");
	return val_float(a->dims[(int)d - 1]);
}

/* splitmix64: a small, well-mixed generator; one state per seed() stream. */
static uint64_t splitmix(uint64_t *s)
{
	uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	return z ^ (z >> 31);
}

static struct value f_seed(struct call *c)
{
	struct eval *E = c->E;
	if (E->nrng >= 1 << 20)
		eval_fail(E, c->n->loc, "too many random streams (seed() called more than %d times)", 1 << 20);
	if ((E->nrng & (E->nrng - 1)) == 0)
		E->rng = mem_realloc(E->rng, sizeof *E->rng * (size_t)(E->nrng ? E->nrng * 2 : 1));
	double v = F(c, 0);
	uint64_t k = (uint64_t)(int64_t)v;
	if (!(fabs(v) < 9.2e18)) /* beyond int64: the double's bits, not a conversion out of range */
		memcpy(&k, &v, sizeof k);
	E->rng[E->nrng] = k * 0x2545F4914F6CDD1Dull;
	return val_float(E->nrng++);
}

static struct value f_rand(struct call *c)
{
	double s = F(c, 0);
	if (s < 0 || s >= c->E->nrng || s != floor(s))
		domain(c, 0, "not a stream made by seed()");
	return val_float((double)(splitmix(&c->E->rng[(int)s]) >> 11) * 0x1.0p-53);
}

/* ==== the table =========================================================== */

struct builtin {
	const char *name;
	int min, max; /* argument counts */
	struct value (*fn)(struct call *);
	double (*f1)(double); /* the same as a plain function of one float (sin, exp …), for
	                       * eval_num (builtin_float_fn); NULL for the others */
};

/* min_extent(O), max_extent(O): the corners of an object's bounding box
 * (its solid's, as POV-Ray's bounding); an unbounded axis gives +-1e10. */
static struct value extent(struct call *c, int hi)
{
	if (c->a[0].kind != V_OBJECT)
		eval_fail(c->E, c->n->kids[0]->loc, "%s needs an object", hi ? "max_extent" : "min_extent");
	struct bbox b = shape_solid_bounds(c->a[0].p.obj);
	struct vec3 p = hi ? b.hi : b.lo;
	double q[3] = {p.x, p.y, p.z};
	for (int i = 0; i < 3; i++)
		if (!isfinite(q[i]))
			q[i] = q[i] < 0 ? -1e10 : 1e10;
	return val_vec3(v3(q[0], q[1], q[2]));
}
static struct value f_min_extent(struct call *c) { return extent(c, 0); }

/* inside(O, P): 1 when the point is inside the object's solid. */
static struct value f_inside(struct call *c)
{
	if (c->a[0].kind != V_OBJECT)
		eval_fail(c->E, c->n->kids[0]->loc, "inside() needs an object");
	return val_float(shape_inside(c->a[0].p.obj, V(c, 1)));
}

/* trace(O, A, D [, N]): where the ray from A along D first meets the
 * object, and in the variable N the unit normal there, facing the ray's
 * origin; both <0, 0, 0> when it misses (POV-Ray's). */
static struct value f_trace(struct call *c)
{
	if (c->a[0].kind != V_OBJECT)
		eval_fail(c->E, c->n->kids[0]->loc, "trace() needs an object");
	struct vec3 o = V(c, 1), d = V(c, 2), p = v3(0, 0, 0), nrm = v3(0, 0, 0);
	struct hit h;
	if (v_len(d) > 0 && shape_intersect(c->a[0].p.obj, &(struct ray){o, d}, 1e-9, INFINITY, &h)) {
		p = h.p;
		nrm = v_dot(h.n, d) > 0 ? v_neg(h.n) : h.n;
	}
	if (c->argc == 4) {
		struct value *slot = env_lookup(c->E, c->n->kids[3]->str);
		if (!slot)
			slot = env_declare(c->E, c->n->kids[3]->str, false);
		*slot = val_vec3(nrm);
	}
	return val_vec3(p);
}
static struct value f_max_extent(struct call *c) { return extent(c, 1); }

static const struct builtin table[] = {
	{"abs", 1, 1, f_abs, fabs}, {"acos", 1, 1, f_acos, NULL}, {"acosh", 1, 1, f_acosh, NULL},
	{"asc", 1, 1, f_asc, NULL}, {"asin", 1, 1, f_asin, NULL}, {"asinh", 1, 1, f_asinh, asinh},
	{"atan", 1, 1, f_atan, atan}, {"atan2", 2, 2, f_atan2, NULL}, {"atanh", 1, 1, f_atanh, NULL},
	{"ceil", 1, 1, f_ceil, ceil}, {"chr", 1, 1, f_chr, NULL}, {"concat", 1, 16, f_concat, NULL},
	{"cos", 1, 1, f_cos, cos}, {"cosh", 1, 1, f_cosh, cosh}, {"degrees", 1, 1, f_degrees, NULL},
	{"dimension_size", 2, 2, f_dimension_size, NULL}, {"dimensions", 1, 1, f_dimensions, NULL},
	{"div", 2, 2, f_div, NULL}, {"exp", 1, 1, f_exp, exp}, {"floor", 1, 1, f_floor, floor},
	{"int", 1, 1, f_int, NULL}, {"ln", 1, 1, f_ln, NULL}, {"log", 1, 1, f_log, NULL},
	{"max", 2, 16, f_max, NULL}, {"max_extent", 1, 1, f_max_extent, NULL}, {"min", 2, 16, f_min, NULL},
	{"min_extent", 1, 1, f_min_extent, NULL}, {"inside", 2, 2, f_inside, NULL}, {"trace", 3, 4, f_trace, NULL}, {"mod", 2, 2, f_mod, NULL},
	{"pow", 2, 2, f_pow, NULL}, {"radians", 1, 1, f_radians, NULL}, {"rand", 1, 1, f_rand, NULL},
	{"seed", 1, 1, f_seed, NULL}, {"select", 3, 4, f_select, NULL}, {"sin", 1, 1, f_sin, sin},
	{"sinh", 1, 1, f_sinh, sinh}, {"sqrt", 1, 1, f_sqrt, NULL}, {"str", 3, 3, f_str, NULL},
	{"strcmp", 2, 2, f_strcmp, NULL}, {"strlen", 1, 1, f_strlen, NULL}, {"strlwr", 1, 1, f_strlwr, NULL},
	{"strupr", 1, 1, f_strupr, NULL}, {"substr", 3, 3, f_substr, NULL}, {"tan", 1, 1, f_tan, tan},
	{"tanh", 1, 1, f_tanh, tanh}, {"val", 1, 1, f_val, NULL}, {"vaxis_rotate", 3, 3, f_vaxis_rotate, NULL},
	{"vcross", 2, 2, f_vcross, NULL}, {"vdot", 2, 2, f_vdot, NULL}, {"vlength", 1, 1, f_vlength, NULL},
	{"vnormalize", 1, 1, f_vnormalize, NULL}, {"vrotate", 2, 2, f_vrotate, NULL}, {"vturbulence", 4, 4, f_vturbulence, NULL}, {"vstr", 5, 5, f_vstr, NULL},
};

/* Every built-in name (the functions above and the constants below) in one
 * open-addressing hash table, made on first use: name lookups run on every
 * #declare and every call, in the innermost loops of a scene. */
static const char *const consts[] = {"pi", "tau", "true", "false", "yes", "no", "on", "off",
	"x", "y", "z", "t", "u", "v", "clock", "clock_delta", "clock_on", "frame_number",
	"initial_clock", "final_clock", "initial_frame", "final_frame", "image_width",
	"image_height", "version", "defined"};

#define NSLOTS 256 /* a power of two, well above the names' count */

struct slot {
	const char *name;        /* NULL: empty */
	const struct builtin *b; /* NULL for a constant */
};

static struct slot slots[NSLOTS];
static pthread_once_t slots_once = PTHREAD_ONCE_INIT;

static uint32_t name_hash(const char *s)
{
	uint32_t h = 2166136261u;
	for (; *s; s++)
		h = (h ^ (unsigned char)*s) * 16777619u;
	return h;
}

static void slot_put(const char *name, const struct builtin *b)
{
	uint32_t h = name_hash(name);
	while (slots[h & (NSLOTS - 1)].name)
		h++;
	slots[h & (NSLOTS - 1)] = (struct slot){name, b};
}

static void make_slots(void)
{
	for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
		slot_put(table[i].name, &table[i]);
	for (size_t i = 0; i < sizeof consts / sizeof consts[0]; i++)
		slot_put(consts[i], NULL);
}

/* The slot holding name, or NULL when it is not a built-in name. */
static const struct slot *lookup(const char *name)
{
	pthread_once(&slots_once, make_slots);
	for (uint32_t h = name_hash(name);; h++) {
		const struct slot *sl = &slots[h & (NSLOTS - 1)];
		if (!sl->name)
			return NULL;
		if (strcmp(sl->name, name) == 0)
			return sl;
	}
}

const struct builtin *builtin_find(const char *name)
{
	const struct slot *sl = lookup(name);
	return sl ? sl->b : NULL;
}

double (*builtin_float_fn(const struct builtin *b))(double)
{
	return b ? b->f1 : NULL;
}

bool builtin_is_name(const char *name)
{
	return lookup(name) != NULL;
}

bool builtin_call(struct eval *E, const struct node *n, struct value *out)
{
	if (n->str[0] == 'd' && strcmp(n->str, "defined") == 0) {
		if (n->nkids != 1 || !n->kids[0] || n->kids[0]->kind != N_IDENT)
			eval_fail(E, n->loc, "defined() needs one identifier");
		*out = val_float(env_lookup(E, n->kids[0]->str) != NULL || env_macro(E, n->kids[0]->str) != NULL);
		return true;
	}
	const struct builtin *b = env_call_builtin(E, n);
	if (!b)
		return false;
	if (n->nkids < b->min || n->nkids > b->max) {
		if (b->min == b->max)
			eval_fail(E, n->loc, "%s() takes %d argument%s, %d given", b->name, b->min, b->min == 1 ? "" : "s", n->nkids);
		eval_fail(E, n->loc, "%s() takes %d to %d arguments, %d given", b->name, b->min, b->max, n->nkids);
	}
	struct call c; /* the arguments not given are V_NONE (not the whole array: a call per sin()) */
	c.E = E, c.n = n, c.argc = n->nkids;
	for (int i = n->nkids; i < b->max && i < (int)(sizeof c.a / sizeof c.a[0]); i++)
		c.a[i] = val_none();
	for (int i = 0; i < n->nkids; i++) {
		if (!n->kids[i])
			eval_fail(E, n->loc, "argument %d of %s() is empty", i + 1, b->name);
		if (b->fn == f_trace && i == 3) { /* trace's normal: a variable it sets */
			c.a[i] = val_none();
			if (n->kids[3]->kind != N_IDENT)
				eval_fail(E, n->kids[3]->loc, "trace()'s fourth argument is a variable to set to the normal");
			continue;
		}
		c.a[i] = eval_expr(E, n->kids[i]);
	}
	*out = b->fn(&c);
	return true;
}
