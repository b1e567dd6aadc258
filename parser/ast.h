/* SPDX-License-Identifier: MIT */
/* ast.h: the syntax tree. One node type, a tagged kind, every node located.
 *
 * Scene files are lists of items. An item is a directive, a keyword item
 * (`sphere { … }`, `translate <1,0,0>`, `no_shadow`, `method point`), a
 * bracketed entry (`[0.5 colour Red]`) or an expression (an object's
 * parameters, a macro call). What an item means depends on the block it is in;
 * the evaluator decides and reports misplaced ones. */
#ifndef ARVO_AST_H
#define ARVO_AST_H

#include <stdio.h>

#include "../common/arena.h"
#include "../common/srcloc.h"
#include "../lexer/token.h"

enum node_kind {
	/* expressions */
	N_NUM,     /* num */
	N_STR,     /* str, len */
	N_IDENT,   /* str: name */
	N_VEC,     /* kids: components */
	N_UNARY,   /* op, a */
	N_BINARY,  /* op, a, b */
	N_COND,    /* a ? b : c */
	N_CALL,    /* str: callee, kids: arguments (a NULL kid is an empty argument) */
	N_MEMBER,  /* a . str */
	N_INDEX,   /* a [ b ] */
	N_COLOUR,  /* op: rgb/rgbf/…/color keyword, a: operand */
	N_ARRAY,   /* kids: dimensions, a: initialiser (N_INIT) or NULL */
	N_INIT,    /* { kids } array initialiser */
	N_FUNC,    /* function: kids: parameters (N_IDENT; none: x y z), a: body (an expression,
	            * N_BLOCK pigment, or N_BLOCK pigment with str "pattern") */
	N_DIRVALUE, /* a: #if/#ifdef/#ifndef/#switch inside an expression, whose chosen
	            * branch yields the value: (#if (A) 1 #else 2 #end) */
	/* block items */
	N_BLOCK,   /* op: keyword, kids: items inside { } */
	N_MOD,     /* op: keyword, kids: its arguments (0, 1 or more) */
	N_WORD,    /* op: keyword, str: the word after it */
	N_ENTRY,   /* [ kids ] */
	N_SKIPPED, /* op: keyword whose block was skipped */
	/* directives */
	N_DECLARE, /* str: name, op: TK_DIR_DECLARE or TK_DIR_LOCAL, kids: indices, a: value, b: the name (N_IDENT, for its location) */
	N_UNDEF,   /* str */
	N_INCLUDE, /* a: file name expression */
	N_IF,      /* a: cond, b: then (N_LIST), c: else (N_LIST, N_IF for #elseif, or NULL) */
	N_IFDEF,   /* op: IFDEF/IFNDEF, a: the identifier expression, b: then, c: else */
	N_WHILE,   /* a: cond, b: body */
	N_FOR,     /* str: variable, kids: start, end[, step], b: body */
	N_SWITCH,  /* a: value, kids: N_CASE clauses */
	N_CASE,    /* op: CASE/RANGE/ELSE, kids: values (1 for case, 2 for range), b: body */
	N_BREAK,
	N_MACRO,   /* str: name, kids: parameters (N_IDENT), b: body */
	N_VERSION, /* a */
	N_MESSAGE, /* op: DEBUG/WARNING/ERROR, a: the string */
	N_DEFAULT, /* kids: items */
	N_LIST,    /* kids: items (a file, a branch, a body) */
};

struct lazy_body;

struct node {
	enum node_kind kind;
	struct srcloc loc;  /* where the construct starts */
	enum tok op;        /* operator or keyword */
	double num;         /* N_NUM */
	const char *str;    /* names and strings (arena) */
	int len;            /* length of str */
	struct node *a, *b, *c; /* fixed children, per kind */
	struct node **kids; /* variable children (arena) */
	int nkids;
	const struct lazy_body *lazy; /* N_MACRO whose body did not parse: parsed
	                               * when called (parse_macro_body), as POV-Ray
	                               * reads a macro's tokens only then */
	/* The evaluator's memo of what the name of an N_IDENT, N_CALL or
	 * N_DECLARE resolved to, valid while the scopes are as they were
	 * (eval/env.c); written through a const node, never read elsewhere. */
	void *memo;
	unsigned long memo_gen;
};

struct node *ast_new(struct arena *a, enum node_kind kind, struct srcloc loc);
/* Appends kid to n's list (the arena array grows by doubling). */
void ast_push(struct arena *a, struct node *n, struct node *kid);
/* --dump-ast: stable, indented text. */
void ast_dump(FILE *out, const struct node *n);
const char *ast_kind_name(enum node_kind k);

#endif
