/* SPDX-License-Identifier: MIT */
/* eval.c: walks the AST: expressions, directives, macros, includes.
 *
 * Items are evaluated into a sink (internal.h) that stands for the block they
 * appear in; objects.c knows what each block accepts. Errors are fatal: they
 * are reported once and longjmp back to eval_scene (Lua's luaD_throw). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "../lexer/lexer.h"
#include "../parser/parser.h"
#include "internal.h"

_Noreturn void eval_fail(struct eval *E, struct srcloc loc, const char *fmt, ...)
{
	char msg[512];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	diag_error(E->diag, loc, "%s", msg);
	longjmp(*E->fail, 1);
}

char *eval_strdup(struct eval *E, const char *s, int len) { return arena_strndup(&E->arena, s, (size_t)len); }

/* ==== conversions ========================================================= */

double val_want_float(struct eval *E, const struct value *v, struct srcloc loc)
{
	if (v->kind != V_FLOAT)
		eval_fail(E, loc, "expected a float, found %s", val_type_name(v));
	return v->v[0];
}

struct vec3 val_want_vec3(struct eval *E, const struct value *v, struct srcloc loc)
{
	if (v->kind == V_FLOAT)
		return v3(v->v[0], v->v[0], v->v[0]);
	if (v->kind != V_VECTOR)
		eval_fail(E, loc, "expected a vector, found %s", val_type_name(v));
	return v3(v->v[0], v->v[1], v->n >= 3 ? v->v[2] : 0);
}

struct colour val_want_colour(struct eval *E, const struct value *v, struct srcloc loc)
{
	struct colour c = {0, 0, 0, 0, 0};
	switch (v->kind) {
	case V_COLOUR: return val_to_colour(v);
	case V_FLOAT: return (struct colour){v->v[0], v->v[0], v->v[0], v->v[0], v->v[0]};
	case V_VECTOR:
		c.r = v->v[0], c.g = v->v[1];
		c.b = v->n > 2 ? v->v[2] : 0;
		c.f = v->n > 3 ? v->v[3] : 0;
		c.t = v->n > 4 ? v->v[4] : 0;
		return c;
	default: eval_fail(E, loc, "expected a colour, found %s", val_type_name(v));
	}
}

static bool eval_num(struct eval *E, const struct node *n, double *f, struct value *v);
/* The kinds eval_expr hands to eval_num. */
static inline bool is_num_kind(const struct node *n)
{
	return n->kind == N_NUM || n->kind == N_IDENT || n->kind == N_UNARY || n->kind == N_BINARY;
}
static inline bool leaf_num(struct eval *E, const struct node *n, double *f);
static bool vector_in_place(struct eval *E, const struct node *n, struct value *v);
static inline void enter(struct eval *E, const struct node *n);
static inline void check_finite(struct eval *E, const struct node *n, const struct value *v);

/* eval_float, inline where floats are read most: a vector's components, a
 * loop's test, the operands of & and |. */
static inline double float_of(struct eval *E, const struct node *n)
{
	double f;
	struct value v;
	if (leaf_num(E, n, &f) || eval_num(E, n, &f, &v))
		return f;
	return val_want_float(E, &v, n->loc);
}

double eval_float(struct eval *E, const struct node *n)
{
	return float_of(E, n);
}

struct vec3 eval_vec3(struct eval *E, const struct node *n)
{
	struct value v;
	if (!vector_in_place(E, n, &v))
		v = eval_expr(E, n);
	return val_want_vec3(E, &v, n->loc);
}

struct colour eval_colour(struct eval *E, const struct node *n)
{
	struct value v = eval_expr(E, n);
	return val_want_colour(E, &v, n->loc);
}

const char *eval_string(struct eval *E, const struct node *n, int *len)
{
	struct value v = eval_expr(E, n);
	if (v.kind != V_STRING)
		eval_fail(E, n->loc, "expected a string, found %s", val_type_name(&v));
	if (len)
		*len = v.n;
	return v.p.s;
}

/* ==== operators =========================================================== */

/* Component i of a float, vector or colour widened as POV-Ray promotes
 * them: a float is the same in every component, a short vector has zeros. */
static inline double component(const struct value *v, int i)
{
	return v->kind == V_FLOAT ? v->v[0] : i < v->n ? v->v[i] : 0;
}

static int is_numeric(const struct value *v)
{
	return v->kind == V_FLOAT || v->kind == V_VECTOR || v->kind == V_COLOUR;
}

/* + - * / on floats, vectors and colours (component-wise, with promotion). */
static struct value arith(struct eval *E, enum tok op, const struct value *a, const struct value *b, struct srcloc loc)
{
	const struct value *bad = !is_numeric(a) ? a : !is_numeric(b) ? b : NULL;
	if (bad)
		eval_fail(E, loc, "operator %s needs numbers, vectors or colours, found %s", tok_name(op), val_type_name(bad));
	if (a->kind == V_FLOAT && b->kind == V_FLOAT) {
		double x = a->v[0], y = b->v[0];
		if (op == TK_SLASH && y == 0)
			eval_fail(E, loc, "division by zero");
		return val_float(op == TK_PLUS ? x + y : op == TK_MINUS ? x - y : op == TK_STAR ? x * y : x / y);
	}
	struct value r;
	if (a->kind == V_COLOUR || b->kind == V_COLOUR) {
		r.kind = V_COLOUR;
		r.n = 5;
	} else {
		r.kind = V_VECTOR;
		r.n = a->kind == V_VECTOR ? a->n : b->n;
		if (a->kind == V_VECTOR && b->kind == V_VECTOR && b->n > r.n)
			r.n = b->n;
	}
	for (int i = 0; i < 5; i++) {
		if (i >= r.n) {
			r.v[i] = 0;
			continue;
		}
		double x = component(a, i), y = component(b, i);
		if (op == TK_SLASH && y == 0)
			eval_fail(E, loc, "division by zero");
		r.v[i] = op == TK_PLUS ? x + y : op == TK_MINUS ? x - y : op == TK_STAR ? x * y : x / y;
	}
	return r;
}

static _Noreturn __attribute__((noinline, cold)) void division_by_zero(struct eval *E, const struct node *n)
{
	eval_fail(E, n->loc, "division by zero");
}

/* A binary operator other than & and | on two floats (eval_num). */
static inline double binary_floats(struct eval *E, const struct node *n, double x, double y)
{
	switch (n->op) {
	case TK_PLUS: return x + y;
	case TK_MINUS: return x - y;
	case TK_STAR: return x * y;
	case TK_SLASH:
		if (y == 0)
			division_by_zero(E, n);
		return x / y;
	case TK_EQ: return x == y;
	case TK_NE: return x != y;
	case TK_LT: return x < y;
	case TK_LE: return x <= y;
	case TK_GT: return x > y;
	case TK_CARET: return pow(x, y); /* in a function's pigment { } */
	default: return x >= y;
	}
}

/* A binary operator other than & and | on its operands' values a and b. */
static struct value binary_values(struct eval *E, const struct node *n, const struct value *a, const struct value *b)
{
	switch (n->op) {
	case TK_PLUS: case TK_MINUS: case TK_STAR: case TK_SLASH:
		return arith(E, n->op, a, b, n->loc);
	default: {
		double x = val_want_float(E, a, n->a->loc), y = val_want_float(E, b, n->b->loc);
		return val_float(binary_floats(E, n, x, y));
	}
	}
}

/* Unary - + ! on its operand's value a. */
static struct value unary_value(struct eval *E, const struct node *n, struct value a)
{
	if (n->op == TK_BANG)
		return val_float(val_want_float(E, &a, n->a->loc) == 0);
	if (!is_numeric(&a))
		eval_fail(E, n->loc, "unary %s needs a number, vector or colour, found %s", tok_name(n->op), val_type_name(&a));
	if (n->op == TK_MINUS)
		for (int i = 0; i < 5; i++)
			a.v[i] = -a.v[i];
	return a;
}

/* ==== colours, vectors, members =========================================== */

static double srgb_to_linear(double c)
{
	return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static struct value colour_base(struct eval *E, const struct node *n);

/* A colour expression: its prefix applied to its operand, then POV-Ray's
 * trailing components (red/green/blue/filter/transmit value) in order. */
static struct value colour_prefix(struct eval *E, const struct node *n)
{
	struct value v = n->a ? colour_base(E, n) : val_colour(c_rgb(0, 0, 0));
	for (int i = 0; i < n->nkids; i++) {
		const struct node *k = n->kids[i];
		double f = eval_float(E, k->a);
		switch (k->op) {
		case TK_RED: v.v[0] = f; break;
		case TK_GREEN: v.v[1] = f; break;
		case TK_BLUE: v.v[2] = f; break;
		case TK_FILTER: v.v[3] = f; break;
		default: v.v[4] = f; break;
		}
	}
	/* the components are checked numbers, copied, but for what the sRGB
	 * conversion computes: only those are checked again (not eval_expr) */
	if (n->op == TK_SRGB || n->op == TK_SRGBF || n->op == TK_SRGBT || n->op == TK_SRGBFT)
		check_finite(E, n, &v);
	return v;
}

/* rgb/rgbf/rgbt/rgbft/srgb…/color prefix applied to its operand. */
static struct value colour_base(struct eval *E, const struct node *n)
{
	struct value a;
	if (!vector_in_place(E, n->a, &a))
		a = eval_expr(E, n->a);
	if (n->op == TK_COLOR || n->op == TK_COLOUR)
		return val_colour(val_want_colour(E, &a, n->a->loc));
	int srgb = n->op == TK_SRGB || n->op == TK_SRGBF || n->op == TK_SRGBT || n->op == TK_SRGBFT;
	int hasf = n->op == TK_RGBF || n->op == TK_RGBFT || n->op == TK_SRGBF || n->op == TK_SRGBFT;
	int hast = n->op == TK_RGBT || n->op == TK_RGBFT || n->op == TK_SRGBT || n->op == TK_SRGBFT;
	int want = 3 + hasf + hast;
	double c[5] = {0, 0, 0, 0, 0};
	if (a.kind == V_FLOAT) {
		for (int i = 0; i < want; i++)
			c[i] = a.v[0];
	} else if (a.kind == V_VECTOR || a.kind == V_COLOUR) {
		int have = a.kind == V_COLOUR ? 5 : a.n;
		if (a.kind == V_VECTOR && have != want)
			eval_fail(E, n->a->loc, "%s needs a %d-component vector, found %d components", tok_name(n->op), want, have);
		for (int i = 0; i < want && i < have; i++)
			c[i] = a.v[i];
	} else {
		eval_fail(E, n->a->loc, "expected a float or vector after %s, found %s", tok_name(n->op), val_type_name(&a));
	}
	struct colour r = {c[0], c[1], c[2], 0, 0};
	if (hasf)
		r.f = c[3];
	if (hast)
		r.t = c[hasf ? 4 : 3];
	if (srgb)
		r.r = srgb_to_linear(r.r), r.g = srgb_to_linear(r.g), r.b = srgb_to_linear(r.b);
	return val_colour(r);
}

static struct value vector_literal(struct eval *E, const struct node *n)
{
	if (n->nkids < 2 || n->nkids > 5) {
		if (n->nkids == 12 || n->nkids == 16) { /* matrix <…>: kept as an array of floats */
			struct array *arr = ARENA_NEW(&E->arena, struct array);
			arr->ndims = 1;
			arr->dims[0] = n->nkids;
			arr->n = n->nkids;
			arr->items = ARENA_ARRAY(&E->arena, struct value, n->nkids);
			for (int i = 0; i < n->nkids; i++)
				arr->items[i] = val_float(eval_float(E, n->kids[i]));
			struct value r = {.kind = V_ARRAY};
			r.p.arr = arr;
			return r;
		}
		eval_fail(E, n->loc, "a vector has 2 to 5 components, found %d", n->nkids);
	}
	double c[5];
	for (int i = 0; i < n->nkids; i++)
		c[i] = eval_float(E, n->kids[i]);
	return val_vector(n->nkids, c);
}

/* eval_expr of a vector literal <a, b, …> of 2 to 5 components, written
 * into *v in place (the commonest vectors: a colour's, a translate's, an
 * operand's) with the same count and nesting; false, having done nothing,
 * for anything else. */
static bool vector_in_place(struct eval *E, const struct node *n, struct value *v)
{
	if (n->kind != N_VEC || n->nkids < 2 || n->nkids > 5)
		return false;
	enter(E, n);
	v->kind = V_VECTOR;
	v->n = n->nkids;
	v->p.s = NULL;
	for (int i = 0; i < 5; i++) /* a vector's components are checked each */
		v->v[i] = i < n->nkids ? float_of(E, n->kids[i]) : 0;
	E->depth--;
	return true;
}

static struct value member(struct eval *E, const struct node *n)
{
	static const struct { const char *name; int index; } members[] = {
		{"x", 0}, {"u", 0}, {"red", 0}, {"y", 1}, {"v", 1}, {"green", 1},
		{"z", 2}, {"blue", 2}, {"t", 3}, {"filter", 3}, {"transmit", 4},
	};
	struct value a = eval_expr(E, n->a);
	if (a.kind != V_VECTOR && a.kind != V_COLOUR)
		eval_fail(E, n->loc, "'.%s' needs a vector or colour, found %s", n->str, val_type_name(&a));
	if (strcmp(n->str, "gray") == 0 || strcmp(n->str, "grey") == 0)
		return val_float(0.297 * a.v[0] + 0.589 * a.v[1] + 0.114 * a.v[2]);
	for (size_t i = 0; i < sizeof members / sizeof members[0]; i++) {
		if (strcmp(members[i].name, n->str) == 0) {
			int k = members[i].index;
			if (a.kind == V_VECTOR && k >= a.n)
				eval_fail(E, n->loc, "'.%s' needs a vector of at least %d components, found %d", n->str, k + 1, a.n);
			return val_float(a.v[k]);
		}
	}
	eval_fail(E, n->loc, "unknown member '.%s'", n->str);
}

/* ==== arrays ============================================================== */

/* Resolves A[i][j]… to the element slot; fails on a bad index. */
static struct value *index_slot(struct eval *E, const struct node *n)
{
	const struct node *chain[5];
	int k = 0;
	const struct node *root = n;
	while (root->kind == N_INDEX) {
		if (k == 5)
			eval_fail(E, root->loc, "too many indices (an array has at most 5 dimensions)");
		chain[k++] = root;
		root = root->a;
	}
	struct value base = eval_expr(E, root);
	if (base.kind != V_ARRAY)
		eval_fail(E, n->loc, "'[' needs an array, found %s", val_type_name(&base));
	struct array *arr = base.p.arr;
	if (k != arr->ndims)
		eval_fail(E, n->loc, "the array has %d dimension%s, %d ind%s given", arr->ndims,
		          arr->ndims == 1 ? "" : "s", k, k == 1 ? "ex" : "ices");
	long off = 0;
	for (int d = 0; d < k; d++) {
		const struct node *ix = chain[k - 1 - d];
		double f = eval_float(E, ix->b);
		if (!(f >= 0 && f < arr->dims[d])) /* compared as a double: no conversion out of range */
			eval_fail(E, ix->b->loc, "array index %g out of range (0 to %d)", f, arr->dims[d] - 1);
		long i = (long)f;
		off = off * arr->dims[d] + i;
	}
	return &arr->items[off];
}

/* Fills arr's items from an initialiser nested as deep as the dimensions. */
static void fill_init(struct eval *E, struct array *arr, const struct node *init, int dim, long *pos)
{
	if (init->nkids != arr->dims[dim])
		eval_fail(E, init->loc, "the initialiser has %d element%s, the array dimension has %d", init->nkids,
		          init->nkids == 1 ? "" : "s", arr->dims[dim]);
	for (int i = 0; i < init->nkids; i++) {
		const struct node *k = init->kids[i];
		if (dim + 1 < arr->ndims) {
			if (k->kind != N_INIT)
				eval_fail(E, k->loc, "expected '{' for dimension %d of the initialiser", dim + 2);
			fill_init(E, arr, k, dim + 1, pos);
		} else {
			if (k->kind == N_INIT)
				eval_fail(E, k->loc, "the initialiser is nested deeper than the array's %d dimension%s",
				          arr->ndims, arr->ndims == 1 ? "" : "s");
			arr->items[(*pos)++] = eval_expr(E, k);
		}
	}
}

static struct value array_new(struct eval *E, const struct node *n)
{
	struct array *arr = ARENA_NEW(&E->arena, struct array);
	arr->ndims = n->nkids;
	if (arr->ndims > 5)
		eval_fail(E, n->loc, "an array has at most 5 dimensions");
	arr->n = 1;
	for (int i = 0; i < n->nkids; i++) {
		double f = eval_float(E, n->kids[i]);
		if (!(f >= 1) || f > MAX_ARRAY)
			eval_fail(E, n->kids[i]->loc, "array size must be 1 to %ld, found %g", MAX_ARRAY, f);
		arr->dims[i] = (int)f;
		arr->n *= arr->dims[i];
		if (arr->n > MAX_ARRAY)
			eval_fail(E, n->loc, "array too large (%ld elements; the limit is %ld)", arr->n, MAX_ARRAY);
	}
	arr->items = ARENA_ARRAY(&E->arena, struct value, arr->n);
	if (n->a) {
		long pos = 0;
		fill_init(E, arr, n->a, 0, &pos);
	}
	struct value r = {.kind = V_ARRAY};
	r.p.arr = arr;
	return r;
}

static struct value array_copy(struct eval *E, struct value v)
{
	struct array *a = ARENA_NEW(&E->arena, struct array);
	*a = *v.p.arr;
	a->items = ARENA_ARRAY(&E->arena, struct value, a->n);
	memcpy(a->items, v.p.arr->items, sizeof *a->items * (size_t)a->n);
	v.p.arr = a;
	return v;
}

/* ==== macros ============================================================== */

/* Calls macro `def` for call node `call`; its body goes into sink s. */
static void call_macro(struct eval *E, const struct node *def, const struct node *call, struct sink *s)
{
	if (call->nkids != def->nkids)
		eval_fail(E, call->loc, "macro '%s' takes %d argument%s, %d given", def->str, def->nkids,
		          def->nkids == 1 ? "" : "s", call->nkids);
	if (E->macro_depth >= MAX_MACRO_DEPTH)
		eval_fail(E, call->loc, "macro recursion too deep (more than %d nested calls)", MAX_MACRO_DEPTH);
	if (++E->calls > E->opt->max_calls)
		eval_fail(E, call->loc, "macro call limit (%ld) exceeded; raise it with --max-calls", E->opt->max_calls);
	if (!def->b && def->lazy) { /* a body that only parses as POV-Ray's tokens would, if at all */
		struct node *b = parse_macro_body(def, E->diag, &E->arena);
		if (!b)
			eval_fail(E, call->loc, "macro '%s' cannot be run: its body has the syntax error above", def->str);
		((struct node *)def)->b = b;
	}
	struct value args[64];
	if (call->nkids > 64)
		eval_fail(E, call->loc, "too many macro arguments (at most 64)");
	for (int i = 0; i < call->nkids; i++) {
		if (!call->kids[i])
			eval_fail(E, call->loc, "argument %d of macro '%s' is empty", i + 1, def->str);
		args[i] = eval_expr(E, call->kids[i]);
		if (args[i].kind == V_ARRAY)
			args[i] = array_copy(E, args[i]);
	}
	struct scope *sc = scope_new(E);
	scope_push(E, sc, call->loc);
	for (int i = 0; i < def->nkids; i++)
		*env_declare(E, def->kids[i]->str, true) = args[i];
	E->macro_depth++;
	eval_items(E, def->b, s);
	E->macro_depth--;
	E->breaking = 0;
	/* arguments that were plain identifiers are passed by reference */
	for (int i = 0; i < def->nkids; i++) {
		const struct node *a = call->kids[i];
		if (a->kind != N_IDENT)
			continue;
		struct value nv = *env_lookup(E, def->kids[i]->str);
		scope_pop(E);
		struct value *slot = env_lookup(E, a->str);
		if (slot)
			*slot = nv;
		scope_push(E, sc, call->loc);
	}
	scope_pop(E);
	scope_release(E, sc);
}

/* A macro call in an expression: its body must yield exactly one value. */
static struct value macro_value(struct eval *E, const struct node *def, const struct node *call)
{
	struct sink s;
	sink_init(&s, SK_VALUE, TK_EOF, call->loc, NULL);
	call_macro(E, def, call, &s);
	if (s.nresults == 0)
		eval_fail(E, call->loc, "macro '%s' yields no value here", def->str);
	return s.result;
}

/* ==== expressions ========================================================= */

/* (#if (A) 1 #else 2 #end): the branch taken yields one value. Apart from
 * eval_expr so that its sink does not weigh on every expression's frame
 * (the stack guard counts them). */
static __attribute__((noinline)) struct value dir_value(struct eval *E, const struct node *n)
{
	struct sink s;
	sink_init(&s, SK_VALUE, TK_EOF, n->loc, NULL);
	eval_item(E, n->a, &s);
	if (s.nresults == 0)
		eval_fail(E, n->loc, "this %s yields no value here", tok_name(n->a->op ? n->a->op : TK_DIR_IF));
	return s.result;
}

/* The value of name n in *out (a declared one, else a built-in constant). */
static void identifier(struct eval *E, const struct node *n, struct value *out)
{
	struct value *v = env_lookup_node(E, n);
	if (v) {
		if (v->kind == V_NONE)
			eval_fail(E, n->loc, "'%s' has no value", n->str);
		*out = *v;
		return;
	}
	if (builtin_constant(E, n->str, out))
		return;
	if (env_macro(E, n->str))
		eval_fail(E, n->loc, "macro '%s' used without arguments", n->str);
	if (tok_is_pov_word(n->str))
		eval_fail(E, n->loc, "'%s' is not supported", n->str);
	eval_fail(E, n->loc, "undeclared identifier '%s'", n->str);
}

static struct value eval_expr_node(struct eval *E, const struct node *n);

static _Noreturn __attribute__((noinline, cold)) void enter_fail(struct eval *E, const struct node *n, int why)
{
	struct srcloc loc = n->loc;
	if (why == 0)
		eval_fail(E, loc, "nesting too deep (more than %d levels of blocks, directives, macro calls, includes and expressions)",
		          MAX_EVAL_DEPTH);
	if (why == 1)
		eval_fail(E, loc, "nesting too deep (the evaluator's stack is used up)");
	eval_fail(E, loc, "evaluation step limit (%ld) exceeded; raise it with --max-steps", E->opt->max_steps);
}

/* Counts one level of the evaluator's recursion at node n: the count bounds
 * it at MAX_EVAL_DEPTH wherever the nesting comes from (directives, blocks,
 * macro calls, includes, expressions), and the stack in use is checked
 * against three quarters of the stack limit as a second guard (docs/design.md §9). */
static inline void enter(struct eval *E, const struct node *n)
{
	char here;
	if (E->depth >= MAX_EVAL_DEPTH)
		enter_fail(E, n, 0);
	if ((uintptr_t)&here < E->stack_floor)
		enter_fail(E, n, 1);
	if (++E->steps > E->max_steps) /* bounds the time any scene can take */
		enter_fail(E, n, 2);
	E->depth++;
}

/* enter() for a number or a name: they nest nothing and take no stack of
 * their own (they are read in the frame of the expression that holds them,
 * or one frame below a checked one), so they count against the depth and
 * the step limits but skip the stack guard. */
static inline void enter_leaf(struct eval *E, const struct node *n)
{
	if (E->depth >= MAX_EVAL_DEPTH)
		enter_fail(E, n, 0);
	if (++E->steps > E->max_steps)
		enter_fail(E, n, 2);
}

static _Noreturn __attribute__((noinline, cold)) void not_finite(struct eval *E, const struct node *n, double x)
{
	eval_fail(E, n->loc, "the result is not a finite number (%s)", isnan(x) ? "NaN" : "infinite");
}

/* Every number the language computes passes here: an infinity or a NaN
 * (1e200 * 1e200, exp(1000), inf - inf) is an error where it was made, so no
 * non-finite number reaches the scene (docs/design.md §8). */
static inline void check_finite(struct eval *E, const struct node *n, const struct value *v)
{
	if (v->kind == V_FLOAT) {
		if (!isfinite(v->v[0]))
			not_finite(E, n, v->v[0]);
	} else if (v->kind == V_VECTOR || v->kind == V_COLOUR) {
		for (int i = 0, k = v->kind == V_COLOUR ? 5 : v->n; i < k; i++)
			if (!isfinite(v->v[i]))
				not_finite(E, n, v->v[i]);
	}
}

/* The end of eval_num's general case: v checked, and a float in *f. */
static bool num_or_value(struct eval *E, const struct node *n, struct value *v, double *f)
{
	E->depth--;
	check_finite(E, n, v);
	if (v->kind != V_FLOAT)
		return false;
	*f = v->v[0];
	return true;
}

/* A number, or a name whose value is a float, evaluated in place (the
 * commonest operands, without a call of eval_num): true and the float in
 * *f; false, having done nothing, for anything else. */
static inline bool leaf_num(struct eval *E, const struct node *n, double *f)
{
	double r;
	if (n->kind == N_NUM) {
		r = n->num;
	} else if (n->kind == N_IDENT) {
		const struct value *p = env_lookup_node(E, n); /* no side effect but the memo */
		if (!p || p->kind != V_FLOAT)
			return false;
		r = p->v[0];
	} else {
		return false;
	}
	enter_leaf(E, n);
	if (!isfinite(r))
		not_finite(E, n, r);
	*f = r;
	return true;
}

/* The plain function of N_CALL n when the call is one of a built-in like
 * sin() with its one argument (not a macro or a declared function of that
 * name): eval_num calls it directly. NULL otherwise. */
static inline double (*float_builtin(struct eval *E, const struct node *n))(double)
{
	return n->nkids == 1 && n->kids[0] ? env_call_float_fn(E, n) : NULL;
}

/* eval_expr for the expressions that are mostly floats (numbers, names,
 * operators: a loop's test, arithmetic, a vector's components): the same
 * checks, counts and order of evaluation, but a float comes back in *f
 * (and true) without a struct value made and copied at every level; any
 * other value comes back in *v (and false). */
static bool eval_num(struct eval *E, const struct node *n, double *f, struct value *v)
{
	double x, y, r;
	struct value a, b;
	switch (n->kind) {
	case N_NUM:
		enter_leaf(E, n);
		r = n->num;
		break;
	case N_IDENT: {
		enter_leaf(E, n);
		const struct value *p = env_lookup_node(E, n);
		if (!p || p->kind != V_FLOAT) {
			identifier(E, n, v);
			check_finite(E, n, v);
			if (v->kind != V_FLOAT)
				return false;
			*f = v->v[0];
			return true;
		}
		r = p->v[0];
		break;
	}
	case N_UNARY:
		enter(E, n);
		if (!eval_num(E, n->a, &x, &a)) {
			*v = unary_value(E, n, a);
			return num_or_value(E, n, v, f);
		}
		E->depth--;
		r = n->op == TK_BANG ? x == 0 : n->op == TK_MINUS ? -x : x;
		break;
	case N_BINARY: {
		enter(E, n);
		bool fa = leaf_num(E, n->a, &x) || eval_num(E, n->a, &x, &a);
		if (n->op == TK_AMP || n->op == TK_PIPE) {
			if (!fa)
				x = val_want_float(E, &a, n->a->loc);
			y = float_of(E, n->b); /* both sides are evaluated, as in POV-Ray */
			E->depth--;
			r = n->op == TK_AMP ? (x != 0 && y != 0) : (x != 0 || y != 0);
			break;
		}
		bool fb = leaf_num(E, n->b, &y) || eval_num(E, n->b, &y, &b);
		if (!fa || !fb) {
			if (fa)
				a = val_float(x);
			if (fb)
				b = val_float(y);
			*v = binary_values(E, n, &a, &b);
			return num_or_value(E, n, v, f);
		}
		r = binary_floats(E, n, x, y);
		E->depth--;
		break;
	}
	case N_CALL: {
		double (*fn)(double) = float_builtin(E, n);
		if (!fn)
			goto general;
		/* as eval_expr and builtin_call would: the call counted, then its
		 * argument, which must be a float (the message of their F()) */
		enter(E, n);
		if (!(leaf_num(E, n->kids[0], &x) || eval_num(E, n->kids[0], &x, &a)))
			x = val_want_float(E, &a, n->kids[0]->loc);
		E->depth--;
		r = fn(x);
		break;
	}
	case N_VEC:
		if (!vector_in_place(E, n, v))
			goto general;
		return false;
	default:
	general:
		*v = eval_expr(E, n);
		if (v->kind != V_FLOAT)
			return false;
		*f = v->v[0];
		return true;
	}
	if (!isfinite(r))
		not_finite(E, n, r);
	*f = r;
	return true;
}

struct value eval_expr(struct eval *E, const struct node *n)
{
	if (is_num_kind(n)) {
		double f;
		struct value v;
		return eval_num(E, n, &f, &v) ? val_float(f) : v;
	}
	enter(E, n);
	struct value v = eval_expr_node(E, n);
	E->depth--;
	if (n->kind != N_VEC && n->kind != N_COLOUR) /* their components were checked each */
		check_finite(E, n, &v);
	return v;
}

/* Everything but what eval_num evaluates. */
static struct value eval_expr_node(struct eval *E, const struct node *n)
{
	switch (n->kind) {
	case N_STR: return val_string(n->str, n->len);
	case N_VEC: return vector_literal(E, n);
	case N_COND: {
		double c = eval_float(E, n->a);
		return eval_expr(E, c != 0 ? n->b : n->c);
	}
	case N_CALL: {
		struct value *fv;
		const struct node *def = env_call_lookup(E, n, &fv);
		if (def)
			return macro_value(E, def, n);
		if (fv && fv->kind == V_FUNCTION)
			return function_call(E, n, fv->p.fn);
		struct value r;
		if (builtin_call(E, n, &r))
			return r;
		if (strcmp(n->str, "file_exists") == 0) /* POV-Ray's; a scene may not probe files */
			eval_fail(E, n->loc, "file_exists() is not supported: a scene cannot look for files");
		eval_fail(E, n->loc, "undeclared macro or function '%s'", n->str);
	}
	case N_MEMBER: return member(E, n);
	case N_INDEX: {
		struct value *slot = index_slot(E, n);
		if (slot->kind == V_NONE)
			eval_fail(E, n->loc, "array element used before it was given a value");
		return *slot;
	}
	case N_COLOUR: return colour_prefix(E, n);
	case N_ARRAY: return array_new(E, n);
	case N_FUNC: return function_value(E, n);
	case N_DIRVALUE: return dir_value(E, n);
	case N_BLOCK: return eval_block(E, n);
	case N_MOD:
		if (n->op == TK_TRANSFORM)
			return eval_block(E, n);
		/* fall through */
	default:
		eval_fail(E, n->loc, "expected an expression, found %s", n->op ? tok_name(n->op) : ast_kind_name(n->kind));
	}
}

/* ==== directives ========================================================== */

static void count_iteration(struct eval *E, struct srcloc loc)
{
	if (++E->iterations > E->opt->max_iterations)
		eval_fail(E, loc, "loop iteration limit (%ld) exceeded; raise it with --max-iterations", E->opt->max_iterations);
}

void eval_count_object(struct eval *E, struct srcloc loc)
{
	if (++E->objects > E->opt->max_objects)
		eval_fail(E, loc, "object limit (%ld objects and lights) exceeded; raise it with --max-objects", E->opt->max_objects);
}

/* #declare A[i][j] = v: the element's slot, found as A[i][j] would be. */
static __attribute__((noinline)) void declare_element(struct eval *E, const struct node *n)
{
	const struct node *chain = NULL;
	/* rebuild A[i][j] as index nodes on the stack */
	struct node id = {.kind = N_IDENT, .loc = n->loc, .str = n->str, .len = n->len};
	struct node ix[5];
	if (n->nkids > 5)
		eval_fail(E, n->loc, "too many indices (an array has at most 5 dimensions)");
	chain = &id;
	for (int i = 0; i < n->nkids; i++) {
		ix[i] = (struct node){.kind = N_INDEX, .loc = n->kids[i]->loc, .a = (struct node *)chain, .b = n->kids[i]};
		chain = &ix[i];
	}
	struct value v = eval_expr(E, n->a);
	*index_slot(E, chain) = v;
}

static __attribute__((noinline)) void exec_declare(struct eval *E, const struct node *n)
{
	bool local = n->op == TK_DIR_LOCAL;
	if (!env_declared_before(E, n) && builtin_is_name(n->str))
		eval_fail(E, n->b ? n->b->loc : n->loc, "'%s' is a built-in name and cannot be declared", n->str);
	if (n->nkids > 0) { /* #declare A[i] = v */
		declare_element(E, n);
		return;
	}
	struct value v;
	double f;
	if (!is_num_kind(n->a)) {
		v = eval_expr(E, n->a);
	} else if (eval_num(E, n->a, &f, &v)) { /* eval_expr's float, stored without a copy */
		*env_declare_node(E, n, local) = val_float(f);
		return;
	}
	if (v.kind == V_ARRAY)
		v = array_copy(E, v);
	if (v.kind == V_NONE)
		eval_fail(E, n->a->loc, "nothing to declare");
	*env_declare_node(E, n, local) = v;
}

static __attribute__((noinline)) void exec_for(struct eval *E, const struct node *n, struct sink *s)
{
	double start = eval_float(E, n->kids[0]);
	double end = eval_float(E, n->kids[1]);
	double step = n->nkids > 2 ? eval_float(E, n->kids[2]) : 1;
	if (step == 0)
		eval_fail(E, n->kids[2]->loc, "#for step must not be zero");
	*env_declare(E, n->str, true) = val_float(start);
	for (;;) {
		struct value *var = env_lookup_node(E, n);
		double v = var ? val_want_float(E, var, n->loc) : start;
		if (step > 0 ? v > end : v < end)
			break;
		count_iteration(E, n->loc);
		eval_items(E, n->b, s);
		if (E->breaking) {
			E->breaking = 0;
			break;
		}
		var = env_lookup_node(E, n);
		if (!var)
			eval_fail(E, n->loc, "loop variable '%s' was undefined inside the loop", n->str);
		*var = val_float(val_want_float(E, var, n->loc) + step);
	}
}

static __attribute__((noinline)) void exec_switch(struct eval *E, const struct node *n, struct sink *s)
{
	double v = eval_float(E, n->a);
	int matched = 0;
	for (int i = 0; i < n->nkids && !E->breaking; i++) {
		const struct node *c = n->kids[i];
		if (!matched) {
			if (c->op == TK_DIR_CASE)
				matched = eval_float(E, c->kids[0]) == v;
			else if (c->op == TK_DIR_RANGE)
				matched = v >= eval_float(E, c->kids[0]) && v <= eval_float(E, c->kids[1]);
			else
				matched = 1;
		}
		if (matched)
			eval_items(E, c->b, s);
	}
	E->breaking = 0;
}

static int ifdef_test(struct eval *E, const struct node *a)
{
	if (a->kind == N_IDENT)
		return env_lookup(E, a->str) != NULL || env_macro(E, a->str) != NULL;
	if (a->kind == N_INDEX)
		return index_slot(E, a)->kind != V_NONE;
	eval_fail(E, a->loc, "#ifdef needs an identifier");
}

static __attribute__((noinline)) void exec_message(struct eval *E, const struct node *n)
{
	int len;
	const char *s = eval_string(E, n->a, &len);
	if (n->op == TK_DIR_DEBUG) {
		fwrite(s, 1, (size_t)len, E->opt->debug_out);
	} else if (n->op == TK_DIR_WARNING) {
		diag_warning(E->diag, n->loc, "%.*s", len, s);
	} else {
		eval_fail(E, n->loc, "%.*s", len, s);
	}
}

/* ==== include ============================================================= */

static char *dir_of(struct eval *E, const char *path)
{
	const char *slash = strrchr(path, '/');
	if (!slash)
		return eval_strdup(E, ".", 1);
	if (slash == path)
		return eval_strdup(E, "/", 1);
	return eval_strdup(E, path, (int)(slash - path));
}

/* A parsed include file: read and parsed once per run, however often it is
 * included (ASTs are immutable). */
struct inc_cache {
	char *real;              /* real path (key) */
	int file;                /* file table index */
	struct node *ast;        /* parsed items */
	const char *dir;         /* its directory, for the includes it makes */
	struct inc_cache *next;
};

/* Reads and parses an include file, or finds it parsed already. */
__attribute__((noinline)) static struct inc_cache *load_include(struct eval *E, const struct node *n, const char *name)
{
	const char *dir;
	char *real = eval_find_file(E, name, n->loc, "include file", &dir);
	for (struct inc_cache *c = E->includes; c; c = c->next) {
		if (strcmp(c->real, real) == 0) {
			free(real);
			return c;
		}
	}
	size_t size;
	char *text = srcfile_read(real, &size);
	if (!text) {
		int err = errno;
		free(real);
		E->missing = 1;
		eval_fail(E, n->loc, "cannot read include file '%s': %s", name, strerror(err));
	}
	if (E->opt->on_file)
		E->opt->on_file(real, E->opt->on_file_ctx);
	/* messages name the file as found in its directory */
	char *shown = mem_alloc(strlen(dir) + strlen(name) + 2);
	sprintf(shown, "%s/%s", dir, name);
	if (name[0] == '/')
		strcpy(shown, name);
	if (strncmp(shown, "./", 2) == 0)
		memmove(shown, shown + 2, strlen(shown + 2) + 1);
	struct inc_cache *c = ARENA_NEW(&E->arena, struct inc_cache);
	c->real = eval_strdup(E, real, (int)strlen(real));
	free(real);
	c->file = srcfile_add(shown, text, size);
	int errors = E->diag->errors;
	c->ast = parse_file_quiet(c->file, E->diag, &E->arena,
	                          E->opt->pov_include_dir && strcmp(dir, E->opt->pov_include_dir) == 0);
	if (E->diag->errors > errors)
		longjmp(*E->fail, 1);
	c->dir = dir_of(E, srcfile_get(c->file)->name);
	c->next = E->includes;
	E->includes = c;
	return c;
}

static __attribute__((noinline)) void exec_include(struct eval *E, const struct node *n, struct sink *s)
{
	int len;
	const char *name = eval_string(E, n->a, &len);
	if (E->include_depth >= MAX_INCLUDE_DEPTH)
		eval_fail(E, n->loc, "#include nested too deeply (more than %d levels)", MAX_INCLUDE_DEPTH);
	struct inc_cache *c = load_include(E, n, name);
	E->dir_stack[E->include_depth + 1] = c->dir;
	E->include_depth++;
	struct scope *sc = scope_new(E);
	scope_push(E, sc, n->loc);
	eval_items(E, c->ast, s);
	scope_pop(E);
	scope_release(E, sc);
	E->include_depth--;
}

/* ==== items =============================================================== */

/* Every nested list of items (a directive's body, a block, a macro body, an
 * include) passes here, and every expression through eval_expr, so one
 * counter bounds the evaluator's recursion whatever mix makes it. */
void eval_items(struct eval *E, const struct node *list, struct sink *s)
{
	enter(E, list);
	for (int i = 0; i < list->nkids && !E->breaking; i++)
		eval_item(E, list->kids[i], s);
	E->depth--;
}

/* The directives and items eval_item hands on, each a function of its own,
 * so that eval_item is a dispatch that saves no registers of its own (it
 * runs for every item of every loop body and block). */
static __attribute__((noinline)) void exec_if(struct eval *E, const struct node *n, struct sink *s)
{
	if (float_of(E, n->a) != 0)
		eval_items(E, n->b, s);
	else if (n->c)
		n->c->kind == N_IF ? eval_item(E, n->c, s) : eval_items(E, n->c, s);
}

static __attribute__((noinline)) void exec_ifdef(struct eval *E, const struct node *n, struct sink *s)
{
	int def = ifdef_test(E, n->a);
	if (def == (n->op == TK_DIR_IFDEF))
		eval_items(E, n->b, s);
	else if (n->c)
		eval_items(E, n->c, s);
}

static __attribute__((noinline)) void exec_while(struct eval *E, const struct node *n, struct sink *s)
{
	while (float_of(E, n->a) != 0) {
		count_iteration(E, n->loc);
		eval_items(E, n->b, s);
		if (E->breaking) {
			E->breaking = 0;
			break;
		}
	}
}

static __attribute__((noinline)) void exec_macro(struct eval *E, const struct node *n)
{
	if (builtin_is_name(n->str))
		eval_fail(E, n->loc, "'%s' is a built-in name and cannot be a macro", n->str);
	env_define_macro(E, n->str, n);
}

static __attribute__((noinline)) void exec_version(struct eval *E, const struct node *n)
{
	double v = eval_float(E, n->a);
	E->scene->version = v;
	if (E->include_depth == 0 && v < 4.0) {
		E->scene->legacy_lights = true;
		/* a POV-Ray scene: arvo's library then reads POV-Ray's files
		 * of the same names after itself (docs/design.md §2) */
		if (E->opt->pov_include_dir)
			*env_declare(E, "Arvo_Povray_Includes", false) = val_float(1);
	}
}

/* An item that is an expression (or a macro call, which may yield items). */
static __attribute__((noinline)) void item_value(struct eval *E, const struct node *n, struct sink *s)
{
	if (n->kind == N_CALL) {
		struct value *fv;
		const struct node *def = env_call_lookup(E, n, &fv);
		if (def) {
			call_macro(E, def, n, s);
			return;
		}
	}
	struct value ignored;
	if (s->kind == SK_NORMAL && n->kind == N_IDENT && !env_lookup(E, n->str) &&
	    !builtin_constant(E, n->str, &ignored) && tok_is_pov_word(n->str)) {
		s->pending = 1; /* bumps, turbulence, slope_map …: normal_block ignores this normal */
		if (!E->warned_normal++)
			diag_warning(E->diag, n->loc, "'%s' is not supported in 'normal' yet; the normal is ignored", n->str);
		return;
	}
	if (s->kind == SK_OBJECT && n->kind == N_VEC && object_long_vector(E, s, n))
		return;
	struct value v = eval_expr(E, n);
	sink_value(E, s, &v, n->loc);
}

void eval_item(struct eval *E, const struct node *n, struct sink *s)
{
	if (s->kind == SK_SCENE || s->kind == SK_VALUE || n->kind >= N_DECLARE)
		E->stmt = n->loc; /* a statement or a directive, not a block's inner item */
	switch (n->kind) {
	case N_DECLARE: exec_declare(E, n); return;
	case N_UNDEF: env_undef(E, n->str); return;
	case N_INCLUDE: exec_include(E, n, s); return;
	case N_IF: exec_if(E, n, s); return;
	case N_IFDEF: exec_ifdef(E, n, s); return;
	case N_WHILE: exec_while(E, n, s); return;
	case N_FOR: exec_for(E, n, s); return;
	case N_SWITCH: exec_switch(E, n, s); return;
	case N_BREAK: E->breaking = 1; return;
	case N_MACRO: exec_macro(E, n); return;
	case N_VERSION: exec_version(E, n); return;
	case N_MESSAGE: exec_message(E, n); return;
	case N_DEFAULT: case N_BLOCK: case N_MOD: case N_WORD: case N_SKIPPED: case N_ENTRY:
		sink_keyword(E, s, n);
		return;
	default: item_value(E, n, s); return;
	}
}

/* ==== driver ============================================================== */

void eval_default_options(struct eval_options *o)
{
	memset(o, 0, sizeof *o);
	o->width = 320;
	o->height = 240;
	o->max_iterations = 10000000;
	o->max_calls = 1000000;
	o->max_steps = 1000000000;
	o->max_objects = 1000000;
	o->debug_out = stdout;
}

const char *eval_undeclarable(const char *name, int len)
{
	char buf[64];
	if (len <= 0 || len >= (int)sizeof buf) /* (no reserved or built-in name is that long) */
		return NULL;
	memcpy(buf, name, (size_t)len);
	buf[len] = 0;
	return lex_keyword(buf, len) != TK_IDENT ? "a reserved word" : builtin_is_name(buf) ? "a built-in name" : NULL;
}

/* -D NAME=VALUE: a float, or a string when VALUE is quoted. */
static void declare_define(struct eval *E, const char *def)
{
	const char *eq = strchr(def, '=');
	const char *val = eq ? eq + 1 : "1";
	int nlen = eq ? (int)(eq - def) : (int)strlen(def);
	char *name = eval_strdup(E, def, nlen);
	size_t vl = strlen(val);
	struct value v;
	if (vl >= 2 && val[0] == '"' && val[vl - 1] == '"') {
		v = val_string(eval_strdup(E, val + 1, (int)vl - 2), (int)vl - 2);
	} else {
		char *end;
		v = val_float(strtod(val, &end));
	}
	*env_declare(E, name, false) = v;
}

/* The evaluator running now, for the memory budget's handler. */
static struct eval *running;

/* Over the --max-memory budget while building the scene: an error at the
 * statement being evaluated, and exit status 70 (docs/design.md §8). */
static void eval_over_budget(size_t request)
{
	struct eval *E = running;
	char size[32];
	(void)request;
	if (!E) /* already unwinding: let the allocation go ahead */
		return;
	mem_format_size(size, sizeof size, mem_budget());
	E->out_of_memory = 1;
	running = NULL; /* the error path allocates nothing more under this handler */
	eval_fail(E, E->stmt, "out of memory: the scene needs more than the %s that --max-memory allows", size);
}

int eval_scene(const char *path, const struct eval_options *opt, struct diag *diag, struct scene *out)
{
	scene_init(out);
	size_t size;
	char *text = srcfile_read(path, &size);
	if (!text) {
		diag_error(diag, srcloc_none(), "cannot open '%s': %s", path, strerror(errno));
		return 66;
	}
	if (opt->on_file)
		opt->on_file(path, opt->on_file_ctx);
	int file = srcfile_add(mem_strdup(path), text, size);
	out->name = arena_strndup(&out->arena, path, strlen(path));

	struct eval *E = mem_calloc(1, sizeof *E);
	jmp_buf jb;
	char base;
	struct rlimit rl;
	size_t stack_max = (size_t)64 << 20;
	if (getrlimit(RLIMIT_STACK, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY && rl.rlim_cur < stack_max)
		stack_max = (size_t)rl.rlim_cur;
	stack_max = stack_max / 4 * 3;
	E->stack_floor = (uintptr_t)&base > stack_max ? (uintptr_t)&base - stack_max : 0;
	E->max_steps = opt->max_steps;
	E->diag = diag;
	E->opt = opt;
	E->scene = out;
	E->fail = &jb;
	arena_init(&E->arena);
	E->env_gen = 1;
	E->default_tex = scene_default_texture();
	int rc = 0;
	E->stmt = (struct srcloc){file, 1, 1};
	running = E;
	mem_over_fn outer = mem_set_budget(mem_budget(), eval_over_budget);
	if (setjmp(jb) == 0) {
		struct node *ast = parse_file(file, diag, &E->arena);
		if (diag->errors == 0) {
			scope_push(E, scope_new(E), srcloc_none());
			E->dir_stack[0] = dir_of(E, path);
			for (int i = 0; i < opt->ndefines; i++)
				declare_define(E, opt->defines[i]);
			struct sink s;
			sink_init(&s, SK_SCENE, TK_EOF, ast->loc, out);
			eval_items(E, ast, &s);
			objects_finish(E);
		}
	}
	mem_set_budget(mem_budget(), outer);
	running = NULL;
	if (diag->errors > 0)
		rc = E->out_of_memory ? 70 : E->missing ? 66 : 65;
	free(E->rng);
	arena_free(&E->arena);
	free(E);
	return rc;
}
