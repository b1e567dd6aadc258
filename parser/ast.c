/* SPDX-License-Identifier: MIT */
/* ast.c: node construction and the --dump-ast printer. */
#include "ast.h"

#include <string.h>

static const char *const kind_names[] = {
	"num", "str", "ident", "vector", "unary", "binary", "cond", "call", "member",
	"index", "colour", "array", "init", "function", "dirvalue", "block", "mod", "word", "entry",
	"skipped", "declare", "undef", "include", "if", "ifdef", "while", "for",
	"switch", "case", "break", "macro", "version", "message", "default", "list",
};

const char *ast_kind_name(enum node_kind k) { return kind_names[k]; }

struct node *ast_new(struct arena *a, enum node_kind kind, struct srcloc loc)
{
	struct node *n = ARENA_NEW(a, struct node);
	n->kind = kind;
	n->loc = loc;
	return n;
}

void ast_push(struct arena *a, struct node *n, struct node *kid)
{
	/* capacity is the next power of two at or above nkids */
	if ((n->nkids & (n->nkids - 1)) == 0) {
		int cap = n->nkids ? n->nkids * 2 : 2;
		struct node **k = ARENA_ARRAY(a, struct node *, cap);
		if (n->nkids)
			memcpy(k, n->kids, sizeof *k * (size_t)n->nkids);
		n->kids = k;
	}
	n->kids[n->nkids++] = kid;
}

static void dump_string(FILE *out, const char *s, int len)
{
	fputc('"', out);
	for (int i = 0; i < len; i++) {
		unsigned char c = (unsigned char)s[i];
		if (c == '"' || c == '\\')
			fprintf(out, "\\%c", c);
		else if (c == '\n')
			fputs("\\n", out);
		else if (c < 32 || c == 127)
			fprintf(out, "\\x%02x", c);
		else
			fputc(c, out);
	}
	fputc('"', out);
}

/* Prints the node head: kind, location, and its scalar payload. */
static void dump_head(FILE *out, const struct node *n)
{
	fprintf(out, "%s @%d:%d", kind_names[n->kind], n->loc.line, n->loc.col);
	switch (n->kind) {
	case N_NUM: fprintf(out, " %.17g", n->num); break;
	case N_STR: fputc(' ', out), dump_string(out, n->str, n->len); break;
	case N_IDENT: case N_CALL: case N_MEMBER: case N_UNDEF: case N_MACRO: case N_FOR:
		fprintf(out, " %s", n->str);
		break;
	case N_BLOCK:
		fprintf(out, " %s", n->str ? n->str : tok_name(n->op));
		break;
	case N_WORD: fprintf(out, " %s %s", tok_name(n->op), n->str); break;
	case N_DECLARE: fprintf(out, " %s %s", tok_name(n->op), n->str); break;
	case N_UNARY: case N_BINARY: case N_COLOUR: case N_MOD:
	case N_SKIPPED: case N_IFDEF: case N_CASE: case N_MESSAGE:
		fprintf(out, " %s", tok_name(n->op));
		break;
	default: break;
	}
	fputc('\n', out);
}

static void dump(FILE *out, const struct node *n, int depth, const char *label)
{
	fprintf(out, "%*s", depth * 2, "");
	if (label)
		fprintf(out, "%s: ", label);
	if (!n) {
		fputs("(none)\n", out);
		return;
	}
	dump_head(out, n);
	/* header children (indices, loop bounds, parameters) come first */
	int kids_first = n->kind == N_DECLARE || n->kind == N_FOR || n->kind == N_MACRO || n->kind == N_FUNC ||
	                 n->kind == N_CASE || n->kind == N_ARRAY;
	for (int i = 0; kids_first && i < n->nkids; i++)
		dump(out, n->kids[i], depth + 1, NULL);
	if (n->a)
		dump(out, n->a, depth + 1, n->kind == N_IF || n->kind == N_WHILE ? "cond" : NULL);
	if (n->b && n->kind != N_DECLARE)
		dump(out, n->b, depth + 1, n->kind == N_IF || n->kind == N_IFDEF ? "then" : NULL);
	if (n->c)
		dump(out, n->c, depth + 1, n->kind == N_BLOCK ? "layer" : "else");
	for (int i = 0; !kids_first && i < n->nkids; i++)
		dump(out, n->kids[i], depth + 1, NULL);
}

void ast_dump(FILE *out, const struct node *n) { dump(out, n, 0, NULL); }
