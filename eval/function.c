/* SPDX-License-Identifier: MIT */
/* function.c: compiles `function { … }` into the stack program of
 * tracer/fn.h, and calls functions from expressions (docs/design.md §2,
 * "Functions").
 *
 * A subexpression that mentions no parameter is a constant: it is evaluated
 * once, here, by the ordinary evaluator (so it may use anything the language
 * has: declared values, vectors and their members, macros). The rest is the
 * function language: the parameters, + - * / ^, comparisons, & |, !, ?:,
 * select, the maths built-ins, and calls of functions declared before. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../tracer/fn.h"
#include "internal.h"

/* What a compiled function carries beside its program: a use that must
 * fail (internal(N) that arvo lacks, a pattern { } with what arvo lacks),
 * kept apart from the tracer's struct fn. */
struct fn_info {
	struct fn fn;
	const char *unsupported; /* NULL: usable; else why not, and where */
	const struct xform *xf;  /* function { transform { … } }: a vector
	                          * function of x, y, z, callable from the scene */
};

/* Records why the function cannot be used: "'warp' is not supported
 * (file.inc:12:5)". */
static void unsupported(struct eval *E, struct fn_info *fi, struct srcloc at, const char *what, const char *name)
{
	const struct srcfile *sf = srcfile_get(at.file);
	const char *file = sf ? strrchr(sf->name, '/') : NULL;
	file = file ? file + 1 : sf ? sf->name : "?";
	char *msg = ARENA_ARRAY(&SC(E)->arena, char, 256);
	snprintf(msg, 256, "'%.40s' is not supported (%.120s:%d:%d)", name ? name : what, file, at.line, at.col);
	fi->unsupported = msg;
}

struct fcomp {
	struct eval *E;
	const char *names[FN_MAX_PARAMS]; /* parameter names */
	int nparams;
	bool defaults;        /* no parameter list: x y z, with u and v for x and y */
	struct fn_op *code;   /* growing in the evaluator's arena; copied into the scene's at the end */
	int n, cap;
	int sp, maxsp;        /* operand stack, now and at most */
	int depth;            /* deepest callee */
	long cost;            /* callees' costs */
};

static const struct fn_info *info(const struct fn *f) { return (const struct fn_info *)f; }

/* ==== emitting ============================================================ */

static void emit(struct fcomp *c, struct srcloc loc, enum fn_opcode op, int i, int push)
{
	if (c->n == c->cap) { /* the arena, not malloc: a failure unwinds past this */
		c->cap = c->cap ? c->cap * 2 : 32;
		struct fn_op *code = ARENA_ARRAY(&c->E->arena, struct fn_op, c->cap);
		if (c->n)
			memcpy(code, c->code, sizeof *code * (size_t)c->n);
		c->code = code;
	}
	c->code[c->n++] = (struct fn_op){.op = (unsigned char)op, .i = (unsigned short)i};
	c->sp += push;
	if (c->sp > c->maxsp)
		c->maxsp = c->sp;
	if (c->maxsp > FN_MAX_STACK)
		eval_fail(c->E, loc, "function too deeply nested (its operands need more than %d places)", FN_MAX_STACK);
}

static void emit_const(struct fcomp *c, struct srcloc loc, double k)
{
	emit(c, loc, FO_CONST, 0, 1);
	c->code[c->n - 1].u.k = k;
}

/* ==== what is constant ==================================================== */

/* The parameter a name stands for, or -1. */
static int param_of(const struct fcomp *c, const char *name)
{
	for (int i = 0; i < c->nparams; i++)
		if (strcmp(c->names[i], name) == 0)
			return i;
	if (c->defaults && name[0] && !name[1] && (name[0] == 'u' || name[0] == 'v'))
		return name[0] == 'u' ? 0 : 1;
	return -1;
}

/* Does the expression mention a parameter? */
static bool varies(const struct fcomp *c, const struct node *n)
{
	if (!n)
		return false;
	switch (n->kind) {
	case N_IDENT: return param_of(c, n->str) >= 0;
	case N_UNARY: case N_BINARY: case N_COND: case N_MEMBER: case N_INDEX: case N_VEC: case N_CALL:
	case N_COLOUR:
		if (varies(c, n->a) || varies(c, n->b) || varies(c, n->c))
			return true;
		for (int i = 0; i < n->nkids; i++)
			if (varies(c, n->kids[i]))
				return true;
		return false;
	default: return false;
	}
}

/* ==== the language ======================================================== */

static const struct { const char *name; int math; } math1s[] = {
	{"abs", FM_ABS}, {"acos", FM_ACOS}, {"acosh", FM_ACOSH}, {"asin", FM_ASIN}, {"asinh", FM_ASINH},
	{"atan", FM_ATAN}, {"atanh", FM_ATANH}, {"ceil", FM_CEIL}, {"cos", FM_COS}, {"cosh", FM_COSH},
	{"degrees", FM_DEGREES}, {"exp", FM_EXP}, {"floor", FM_FLOOR}, {"int", FM_INT}, {"ln", FM_LN},
	{"log", FM_LOG}, {"radians", FM_RADIANS}, {"sin", FM_SIN}, {"sinh", FM_SINH}, {"sqrt", FM_SQRT},
	{"tan", FM_TAN}, {"tanh", FM_TANH},
};

static const struct { const char *name; int math; } math2s[] = {
	{"atan2", FM_ATAN2}, {"div", FM_DIV}, {"mod", FM_MOD}, {"pow", FM_POW2},
};

static void compile(struct fcomp *c, const struct node *n);

/* "function 'F' takes 3 arguments, 2 given" */
static void check_arity(struct eval *E, const struct node *call, const char *what, int want)
{
	if (call->nkids != want)
		eval_fail(E, call->loc, "%s takes %d argument%s, %d given", what, want, want == 1 ? "" : "s", call->nkids);
	for (int i = 0; i < call->nkids; i++)
		if (!call->kids[i])
			eval_fail(E, call->loc, "argument %d of %s is empty", i + 1, what);
}

/* A declared function that may be used, or a failure at the use. */
static const struct fn *usable(struct eval *E, const struct node *call)
{
	struct value *v = env_lookup(E, call->str);
	if (!v || v->kind != V_FUNCTION)
		return NULL;
	const struct fn_info *fi = info(v->p.fn);
	if (fi->unsupported)
		eval_fail(E, call->loc, "'%s' cannot be used: %s", call->str, fi->unsupported);
	return v->p.fn;
}

/* A call of a declared function; component >= 0 selects from a pigment
 * function's colour (5: its grey). */
static void compile_call(struct fcomp *c, const struct node *n, const struct fn *f, int component)
{
	char what[96];
	snprintf(what, sizeof what, "function '%.60s'", n->str);
	check_arity(c->E, n, what, f->nparams);
	if (f->kind == FN_PIGMENT && component < 0)
		eval_fail(c->E, n->loc, "'%s' is a pigment function: select a component (.red, .green, .blue, .filter, .transmit, .gray)",
		          n->str);
	for (int i = 0; i < n->nkids; i++)
		compile(c, n->kids[i]);
	emit(c, n->loc, component >= 0 ? FO_CALLC : FO_CALL, n->nkids, 1 - n->nkids);
	c->code[c->n - 1].u.f = f;
	c->code[c->n - 1].j = (unsigned char)(component >= 0 ? component : 0);
	if (f->depth > c->depth)
		c->depth = f->depth;
	c->cost += f->cost;
	if (c->cost > FN_MAX_COST)
		eval_fail(c->E, n->loc, "function too costly: one evaluation would take more than %ld operations", FN_MAX_COST);
}

static void compile_builtin(struct fcomp *c, const struct node *n)
{
	struct eval *E = c->E;
	char what[64];
	snprintf(what, sizeof what, "%.40s()", n->str);
	for (size_t i = 0; i < sizeof math1s / sizeof math1s[0]; i++)
		if (strcmp(math1s[i].name, n->str) == 0) {
			check_arity(E, n, what, 1);
			compile(c, n->kids[0]);
			emit(c, n->loc, FO_MATH1, math1s[i].math, 0);
			return;
		}
	for (size_t i = 0; i < sizeof math2s / sizeof math2s[0]; i++)
		if (strcmp(math2s[i].name, n->str) == 0) {
			check_arity(E, n, what, 2);
			compile(c, n->kids[0]);
			compile(c, n->kids[1]);
			emit(c, n->loc, FO_MATH2, math2s[i].math, -1);
			return;
		}
	if (strcmp(n->str, "min") == 0 || strcmp(n->str, "max") == 0) {
		if (n->nkids < 1)
			eval_fail(E, n->loc, "%s takes at least 1 argument, 0 given", what);
		for (int i = 0; i < n->nkids; i++) {
			if (!n->kids[i])
				eval_fail(E, n->loc, "argument %d of %s is empty", i + 1, what);
			compile(c, n->kids[i]);
			if (i > 0)
				emit(c, n->loc, FO_MATH2, n->str[1] == 'i' ? FM_MIN : FM_MAX, -1);
		}
		return;
	}
	if (strcmp(n->str, "select") == 0) {
		if (n->nkids != 3 && n->nkids != 4)
			eval_fail(E, n->loc, "select() takes 3 or 4 arguments, %d given", n->nkids);
		check_arity(E, n, what, n->nkids);
		for (int i = 0; i < n->nkids; i++)
			compile(c, n->kids[i]);
		emit(c, n->loc, n->nkids == 3 ? FO_SELECT3 : FO_SELECT4, 0, 1 - n->nkids);
		return;
	}
	const struct fn *f = usable(E, n);
	if (f) {
		compile_call(c, n, f, -1);
		return;
	}
	if (strcmp(n->str, "internal") == 0)
		eval_fail(E, n->loc, "internal() must be the whole body of a function");
	if (env_macro(E, n->str))
		eval_fail(E, n->loc, "macro '%s' cannot take the parameters of a function", n->str);
	if (builtin_is_name(n->str))
		eval_fail(E, n->loc, "%s is not available in a function", what);
	eval_fail(E, n->loc, "undeclared function '%s'", n->str);
}

/* The component a member selects from a colour: 0-4, 5 for grey, or -1. */
static int component_of(const char *m)
{
	static const char *const names[][2] = {{"red", "x"}, {"green", "y"}, {"blue", "z"}, {"filter", "t"},
	                                       {"transmit", ""}, {"gray", "grey"}};
	for (int i = 0; i < 6; i++)
		if (strcmp(m, names[i][0]) == 0 || (names[i][1][0] && strcmp(m, names[i][1]) == 0))
			return i;
	if (strcmp(m, "u") == 0 || strcmp(m, "v") == 0)
		return m[0] == 'u' ? 0 : 1;
	return -1;
}

static void compile(struct fcomp *c, const struct node *n)
{
	struct eval *E = c->E;
	if (!varies(c, n)) { /* a constant: the evaluator's value */
		struct value v = eval_expr(E, n);
		if (v.kind != V_FLOAT)
			eval_fail(E, n->loc, "a function computes with floats, found %s", val_type_name(&v));
		emit_const(c, n->loc, v.v[0]);
		return;
	}
	switch (n->kind) {
	case N_IDENT: emit(c, n->loc, FO_ARG, param_of(c, n->str), 1); return;
	case N_UNARY:
		compile(c, n->a);
		if (n->op == TK_MINUS)
			emit(c, n->loc, FO_NEG, 0, 0);
		else if (n->op == TK_BANG)
			emit(c, n->loc, FO_NOT, 0, 0);
		return;
	case N_BINARY: {
		static const struct { enum tok t; enum fn_opcode op; } ops[] = {
			{TK_PLUS, FO_ADD}, {TK_MINUS, FO_SUB}, {TK_STAR, FO_MUL}, {TK_SLASH, FO_DIV},
			{TK_CARET, FO_POW}, {TK_LT, FO_LT}, {TK_LE, FO_LE}, {TK_GT, FO_GT}, {TK_GE, FO_GE},
			{TK_EQ, FO_EQ}, {TK_NE, FO_NE}, {TK_AMP, FO_AND}, {TK_PIPE, FO_OR},
		};
		compile(c, n->a);
		compile(c, n->b);
		for (size_t i = 0; i < sizeof ops / sizeof ops[0]; i++)
			if (ops[i].t == n->op) {
				emit(c, n->loc, ops[i].op, 0, -1);
				return;
			}
		eval_fail(E, n->loc, "operator %s is not available in a function", tok_name(n->op));
	}
	case N_COND: /* a ? b : c is select(-(a != 0), b, c) */
		compile(c, n->a);
		emit_const(c, n->loc, 0);
		emit(c, n->loc, FO_NE, 0, -1);
		emit(c, n->loc, FO_NEG, 0, 0);
		compile(c, n->b);
		compile(c, n->c);
		emit(c, n->loc, FO_SELECT3, 0, -2);
		return;
	case N_CALL: compile_builtin(c, n); return;
	case N_MEMBER: {
		int k = component_of(n->str);
		const struct fn *f = n->a->kind == N_CALL ? usable(E, n->a) : NULL;
		if (!f)
			eval_fail(E, n->loc, "'.%s' in a function needs a call of a pigment function before it", n->str);
		if (k < 0)
			eval_fail(E, n->loc, "unknown member '.%s'", n->str);
		compile_call(c, n->a, f, f->kind == FN_PIGMENT ? k : -1);
		return;
	}
	default:
		eval_fail(E, n->loc, "a function computes with floats, found %s",
		          n->kind == N_VEC ? "a vector" : n->kind == N_COLOUR ? "a colour" : n->kind == N_INDEX ? "an array element" : ast_kind_name(n->kind));
	}
}

/* ==== bodies ============================================================== */

/* The first item of a pattern { } or pigment { } body that names something
 * arvo does not have (a word POV-Ray knows, undeclared here), or NULL. */
static const struct node *lacking(struct eval *E, const struct node *blk)
{
	for (int i = 0; i < blk->nkids; i++) {
		const struct node *k = blk->kids[i];
		struct value v;
		if (k && k->kind == N_IDENT && tok_is_pov_word(k->str) && !env_lookup(E, k->str) &&
		    !builtin_constant(E, k->str, &v))
			return k;
	}
	return NULL;
}

/* pattern { … } and pigment { … }: a pattern's value or a pigment's colour. */
static void pattern_body(struct eval *E, struct fn_info *fi, const struct node *blk)
{
	bool pattern = blk->str != NULL;
	fi->fn.kind = pattern ? FN_PATTERN : FN_PIGMENT;
	fi->fn.nparams = 3;
	fi->fn.depth = 1;
	fi->fn.cost = 50;
	const struct node *k = lacking(E, blk);
	if (k) {
		unsupported(E, fi, k->loc, NULL, k->str);
		return;
	}
	struct sink s;
	fi->fn.pig = scene_default_texture().pigment;
	if (pattern)
		fi->fn.pig.kind = PIG_SOLID, fi->fn.pig.c[0] = c_rgb(0, 0, 0);
	run_block(E, blk, SK_PIGMENT, &fi->fn.pig, &s);
	if (fi->fn.pig.kind == PIG_IMAGE)
		eval_fail(E, blk->loc, "an image_map cannot be used in a function");
	const struct fn *inner = pig_pattern(&fi->fn.pig)->fn; /* pattern { function { … } } */
	if (fi->fn.pig.kind == PIG_PATTERN && pig_pattern(&fi->fn.pig)->pattern == PAT_FUNCTION && inner) {
		fi->fn.depth = inner->depth + 1;
		fi->fn.cost = inner->cost + 50;
		if (fi->fn.depth > FN_MAX_DEPTH)
			eval_fail(E, blk->loc, "functions nested too deeply (more than %d calls within calls)", FN_MAX_DEPTH);
	}
}

struct value function_value(struct eval *E, const struct node *n)
{
	struct fn_info *fi = NEW(E, struct fn_info);
	fi->fn.loc = n->loc;
	struct value r = {.kind = V_FUNCTION};
	r.p.fn = &fi->fn;
	const struct node *body = n->a;
	if (!body)
		eval_fail(E, n->loc, "function { } needs a body");
	if (body->kind == N_BLOCK && body->op == TK_TRANSFORM) {
		/* POV-Ray's transform function (transforms.inc's vtransform):
		 * F(x, y, z) is the transformed point, a vector; the function
		 * machine computes floats, so it cannot be called inside
		 * another function */
		if (n->nkids)
			eval_fail(E, n->loc, "a transform function takes x, y, z: it has no parameter list");
		struct value t = eval_block(E, body);
		fi->xf = t.p.xf;
		fi->fn.nparams = 3;
		unsupported(E, fi, body->loc, "a transform inside a function", NULL);
		return r;
	}
	if (body->kind == N_BLOCK) {
		if (n->nkids)
			eval_fail(E, n->loc, "a %s function takes x, y, z: it has no parameter list", body->str ? "pattern" : "pigment");
		pattern_body(E, fi, body);
		return r;
	}
	if (body->kind == N_CALL && strcmp(body->str, "internal") == 0) { /* functions.inc */
		if (body->nkids != 1 || !body->kids[0])
			eval_fail(E, body->loc, "internal() takes 1 argument, %d given", body->nkids);
		double k = eval_float(E, body->kids[0]);
		struct fn_internal_info ii = fn_internal(k >= 0 && k < FN_INTERNAL_COUNT ? (int)k : -1);
		fi->fn.kind = FN_INTERNAL;
		fi->fn.internal = (int)k;
		fi->fn.pig = scene_default_texture().pigment;
		pat_w(E, &fi->fn.pig); /* its noise_gen becomes the scene's when the scene ends */
		fi->fn.nparams = ii.nparams;
		fi->fn.depth = 1;
		fi->fn.cost = 50;
		if (!ii.name) {
			char what[40];
			snprintf(what, sizeof what, "internal(%g)", k);
			unsupported(E, fi, body->loc, what, NULL);
		}
		return r;
	}
	struct fcomp c = {.E = E};
	if (n->nkids > FN_MAX_PARAMS)
		eval_fail(E, n->kids[FN_MAX_PARAMS]->loc, "a function has at most %d parameters", FN_MAX_PARAMS);
	for (int i = 0; i < n->nkids; i++) {
		for (int j = 0; j < i; j++)
			if (strcmp(c.names[j], n->kids[i]->str) == 0)
				eval_fail(E, n->kids[i]->loc, "parameter '%s' given twice", n->kids[i]->str);
		c.names[c.nparams++] = n->kids[i]->str;
	}
	if (n->nkids == 0) {
		c.defaults = true;
		c.names[0] = "x", c.names[1] = "y", c.names[2] = "z";
		c.nparams = 3;
	}
	compile(&c, body);
	if (c.depth + 1 > FN_MAX_DEPTH)
		eval_fail(E, n->loc, "functions nested too deeply (more than %d calls within calls)", FN_MAX_DEPTH);
	struct fn_op *code = ARENA_ARRAY(&SC(E)->arena, struct fn_op, c.n);
	memcpy(code, c.code, sizeof *code * (size_t)c.n);
	fi->fn.kind = FN_CODE;
	fi->fn.code = code;
	fi->fn.ncode = c.n;
	fi->fn.nparams = c.nparams;
	fi->fn.depth = c.depth + 1;
	fi->fn.cost = c.cost + c.n;
	return r;
}

struct value function_call(struct eval *E, const struct node *call, const struct fn *f)
{
	const struct fn_info *fi = info(f);
	if (fi->xf) {
		check_arity(E, call, "a transform function", 3);
		struct vec3 p = v3(eval_float(E, call->kids[0]), eval_float(E, call->kids[1]), eval_float(E, call->kids[2]));
		return val_vec3(xf_point(fi->xf, p));
	}
	if (fi->unsupported)
		eval_fail(E, call->loc, "'%s' cannot be used: %s", call->str, fi->unsupported);
	char what[96];
	snprintf(what, sizeof what, "function '%.60s'", call->str);
	check_arity(E, call, what, f->nparams);
	double args[FN_MAX_PARAMS];
	for (int i = 0; i < call->nkids; i++)
		args[i] = eval_float(E, call->kids[i]);
	if (f->kind == FN_PIGMENT)
		return val_colour(fn_eval_colour(f, args));
	return val_float(fn_eval(f, args));
}

const struct fn *function_usable(struct eval *E, const struct value *v, struct srcloc loc)
{
	const struct fn_info *fi = info(v->p.fn);
	if (fi->unsupported)
		eval_fail(E, loc, "this function cannot be used: %s", fi->unsupported);
	return v->p.fn;
}
