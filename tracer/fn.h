/* SPDX-License-Identifier: MIT */
/* fn.h: POV-Ray's user-defined functions, compiled (docs/design.md §2,
 * "Functions").
 *
 * The evaluator compiles a `function { … }` body once into a flat program
 * for a small stack machine (eval/function.c); the tracer and the evaluator
 * then run it with fn_eval. A program is read-only once made: evaluation
 * allocates nothing, touches no shared state and is safe on any number of
 * threads. Calls between functions are resolved when the caller is compiled,
 * so they form a DAG whose depth and total size are bounded then. */
#ifndef ARVO_FN_H
#define ARVO_FN_H

#include "scene.h"

#define FN_MAX_PARAMS 32   /* parameters of one function */
#define FN_MAX_STACK 64    /* operand stack of one call */
#define FN_MAX_DEPTH 64    /* nested calls between functions */
#define FN_MAX_COST 1000000L /* operations one evaluation may take */

enum fn_kind {
	FN_CODE,     /* a compiled expression */
	FN_INTERNAL, /* internal(N): one of POV-Ray's built-in f_* functions */
	FN_PATTERN,  /* pattern { … }: a pattern's value */
	FN_PIGMENT,  /* pigment { … }: a colour (r g b filter transmit) */
};

enum fn_opcode {
	FO_CONST, FO_ARG,                        /* push k; push argument i */
	FO_ADD, FO_SUB, FO_MUL, FO_DIV, FO_POW,  /* binary, on the top two */
	FO_LT, FO_LE, FO_GT, FO_GE, FO_EQ, FO_NE, FO_AND, FO_OR,
	FO_NEG, FO_NOT,                          /* unary */
	FO_MATH1,                                /* i: enum fn_math1 */
	FO_MATH2,                                /* i: enum fn_math2 */
	FO_SELECT3, FO_SELECT4,                  /* select(a, b, c[, d]) */
	FO_CALL,                                 /* f, i arguments: a float function */
	FO_CALLC,                                /* f, i arguments, then component j of its colour */
};

enum fn_math1 {
	FM_ABS, FM_ACOS, FM_ACOSH, FM_ASIN, FM_ASINH, FM_ATAN, FM_ATANH, FM_CEIL, FM_COS,
	FM_COSH, FM_DEGREES, FM_EXP, FM_FLOOR, FM_INT, FM_LN, FM_LOG, FM_RADIANS, FM_SIN,
	FM_SINH, FM_SQRT, FM_TAN, FM_TANH,
};

enum fn_math2 { FM_ATAN2, FM_DIV, FM_MAX, FM_MIN, FM_MOD, FM_POW2 };

struct fn;

struct fn_op {
	unsigned char op;  /* enum fn_opcode */
	unsigned char j;   /* FO_CALLC: colour component */
	unsigned short i;  /* FO_ARG: index; FO_MATH*: which; FO_CALL*: argument count */
	union {
		double k;          /* FO_CONST */
		const struct fn *f; /* FO_CALL, FO_CALLC */
	} u;
};

struct fn {
	enum fn_kind kind;
	int nparams;             /* arguments a call passes */
	int depth;               /* 1 + the deepest function it calls */
	long cost;               /* operations one evaluation takes, callees included */
	const struct fn_op *code; /* FN_CODE */
	int ncode;
	int internal;            /* FN_INTERNAL: POV-Ray's number */
	struct pigment pig;      /* FN_PATTERN, FN_PIGMENT; FN_INTERNAL: its pattern's noise_gen is the
	                          * scene's noise generator (0 until the scene ends: 2) */
	struct srcloc loc;       /* where `function` was written */
};

/* A float function's value for args[0 .. nparams-1] (a pigment function
 * gives its colour's grey). Not finite when the maths is not (a division by
 * zero at render time). */
double fn_eval(const struct fn *f, const double *args);
/* A pigment function's colour at (args[0], args[1], args[2]). */
struct colour fn_eval_colour(const struct fn *f, const double *args);

/* POV-Ray's internal(N) functions that arvo has: the name functions.inc
 * gives it and its parameter count, or NULL name when N is not built. */
struct fn_internal_info {
	const char *name;
	int nparams;
};
struct fn_internal_info fn_internal(int n);
#define FN_INTERNAL_COUNT 79

#endif
