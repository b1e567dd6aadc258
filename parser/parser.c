/* SPDX-License-Identifier: MIT */
/* parser.c: recursive descent, one function per rule (EBNF above each).
 *
 * Items are parsed without knowing what block they are in: a keyword's shape
 * (tokens.def) says what follows it. Binary operators use a precedence table.
 * After an error the parser enters panic mode and skips to a synchronising
 * token (a directive, a block keyword, '}'), so one run reports several
 * errors without cascades. */
#include "parser.h"

#include <stdarg.h>
#include <string.h>

#include "../lexer/lexer.h"

#define MAX_DEPTH 200 /* nesting guard for blocks and expressions */

/* A macro body kept as tokens (parse_macro): the lexer and parser state at
 * its first token. */
struct lazy_body {
	struct lexer lx;
	struct token tok, prev;
};

struct parser {
	struct lexer lx;     /* the file's lexer */
	struct token tok;    /* current token */
	struct token prev;   /* last consumed token */
	struct arena *arena; /* where nodes go */
	struct diag *diag;
	int panic;           /* suppress errors until resynchronised */
	int depth;           /* recursion depth (blocks, directives, expressions) */
	long ntok;           /* tokens consumed: synchronize() checks progress */
	int no_gt;           /* inside <…>: '>' closes the vector */
	int in_mesh_list;    /* inside vertex_vectors { 14 <…> … } and the like: numbers are never compared */
	int in_normal;       /* inside normal { }: unsupported words are left to the evaluator */
	int in_func;         /* inside function { }: '^' is a power; unsupported words in its
	                      * pattern { } are left to the evaluator (a macro may never run it) */
	int in_texture;      /* inside texture { }: textures in a row are a pattern's (checker
	                      * texture { A } texture { B }), not layers */
	int quiet_macros;    /* no warning for a macro read only when called (POV-Ray's own files) */
	int first_set;       /* a macro body's quiet trial (parse_macro): its first error */
	struct srcloc first_loc;
	char first_msg[256];
};

static struct node *parse_expr(struct parser *p);
static struct node *parse_item(struct parser *p);
static void parse_items(struct parser *p, struct node *list);

/* ==== token helpers ======================================================= */

static void advance(struct parser *p)
{
	p->prev = p->tok;
	p->ntok++;
	lex_next(&p->lx, &p->tok);
	while (p->tok.kind == TK_ERROR) {
		p->panic = 1; /* already reported: no cascade of parse errors */
		lex_next(&p->lx, &p->tok);
	}
}

static int check(const struct parser *p, enum tok k) { return p->tok.kind == k; }

static int accept(struct parser *p, enum tok k)
{
	if (!check(p, k))
		return 0;
	advance(p);
	return 1;
}

/* Describes the current token for messages: "'}'", "identifier 'Foo'", "number". */
static const char *found(struct parser *p)
{
	static char buf[96];
	const struct token *t = &p->tok;
	if (t->kind == TK_IDENT)
		snprintf(buf, sizeof buf, "identifier '%.*s'", t->len > 40 ? 40 : t->len, t->text);
	else if (t->kind == TK_NUMBER)
		snprintf(buf, sizeof buf, "number %.*s", t->len > 40 ? 40 : t->len, t->text);
	else
		snprintf(buf, sizeof buf, "%s", tok_name(t->kind));
	return buf;
}

/* Reports at loc unless in panic mode; enters panic mode. */
__attribute__((format(printf, 3, 4)))
static void error_at(struct parser *p, struct srcloc loc, const char *fmt, ...)
{
	if (p->panic)
		return;
	p->panic = 1;
	char msg[256];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	if (!p->first_set) {
		p->first_set = 1, p->first_loc = loc;
		memcpy(p->first_msg, msg, sizeof msg);
	}
	diag_error(p->diag, loc, "%s", msg);
}

static void expected(struct parser *p, const char *what)
{
	error_at(p, p->tok.loc, "expected %s, found %s", what, found(p));
}

/* Consumes a closing token or reports "'}' expected (to close '{' at L:C)". */
static void expect_close(struct parser *p, enum tok close, enum tok open, struct srcloc at)
{
	if (accept(p, close))
		return;
	if (p->panic)
		return;
	char msg[200];
	snprintf(msg, sizeof msg, "%s expected (to close %s at %d:%d), found %s", tok_name(close),
	         tok_name(open), at.line, at.col, found(p));
	error_at(p, p->tok.loc, "%s", msg);
}

static int expect(struct parser *p, enum tok k)
{
	if (accept(p, k))
		return 1;
	error_at(p, p->tok.loc, "expected %s, found %s", tok_name(k), found(p));
	return 0;
}

/* Skips to a token an item can start with, then leaves panic mode. `start`
 * is p->ntok before the item: an item that consumed nothing is skipped, so
 * every call makes progress and no loop of items can spin in place. */
static void synchronize(struct parser *p, long start)
{
	if (!p->panic)
		return;
	if (p->ntok == start && !check(p, TK_EOF))
		advance(p);
	while (!check(p, TK_EOF)) {
		enum tok k = p->tok.kind;
		if (k == TK_RBRACE || tok_is_directive(k) || (tok_is_keyword(k) && tok_shape(k) == SH_BLOCK))
			break;
		if (p->prev.kind == TK_RBRACE || p->prev.kind == TK_SEMI)
			break;
		advance(p);
	}
	p->panic = 0;
}

static struct node *node(struct parser *p, enum node_kind k, struct srcloc loc)
{
	return ast_new(p->arena, k, loc);
}

/* Counts one level of nesting; false (depth unchanged) past MAX_DEPTH. */
static int enter(struct parser *p)
{
	if (p->depth >= MAX_DEPTH) {
		error_at(p, p->tok.loc, "nesting too deep (more than %d levels)", MAX_DEPTH);
		return 0;
	}
	p->depth++;
	return 1;
}

static void leave(struct parser *p) { p->depth--; }

/* Can the current token start an expression? */
static int starts_expr(const struct parser *p)
{
	enum tok k = p->tok.kind;
	return k == TK_NUMBER || k == TK_STRING || k == TK_IDENT || k == TK_LPAREN || k == TK_LT ||
	       k == TK_MINUS || k == TK_PLUS || k == TK_BANG || tok_shape(k) == SH_PREFIX ||
	       k == TK_ARRAY || k == TK_FUNCTION;
}

/* ==== expressions ========================================================= */

static struct node *parse_keyword_item(struct parser *p);
static struct node *parse_directive(struct parser *p);

/* A value where a block may stand too: array initialisers, macro arguments,
 * #declare right-hand sides (sphere { … }, texture { … }, transform { … }). */
static struct node *word_block(struct parser *p, struct node *id);

static struct node *parse_value(struct parser *p)
{
	enum kw_shape sh = tok_shape(p->tok.kind);
	if (tok_is_keyword(p->tok.kind) && (sh == SH_BLOCK || sh == SH_BLOCK_OR_EXPR || sh == SH_SKIP))
		return parse_keyword_item(p);
	struct node *e = parse_expr(p);
	if (e && e->kind == N_IDENT && check(p, TK_LBRACE)) /* #declare T = text { … } */
		return word_block(p, e);
	return e;
}

/* Binary operator precedence; 0 when tok is not a binary operator here. */
static int binprec(const struct parser *p, enum tok k)
{
	switch (k) {
	case TK_PIPE: case TK_AMP: return 1; /* one level, left to right (as POV-Ray 3.7) */
	case TK_EQ: case TK_NE: case TK_LT: case TK_LE: case TK_GE: return 2;
	case TK_GT: return p->no_gt ? 0 : 2;
	case TK_PLUS: case TK_MINUS: return 3;
	case TK_STAR: case TK_SLASH: return 4;
	default: return 0;
	}
}

/* args := '(' [expr {',' expr}] ')'   (an empty slot is a NULL kid) */
static void parse_args(struct parser *p, struct node *call)
{
	struct srcloc open = p->tok.loc;
	advance(p); /* ( */
	int saved = p->no_gt;
	p->no_gt = 0;
	if (!check(p, TK_RPAREN)) {
		do {
			if (check(p, TK_COMMA) || check(p, TK_RPAREN))
				ast_push(p->arena, call, NULL);
			else
				ast_push(p->arena, call, parse_value(p));
		} while (accept(p, TK_COMMA));
	}
	p->no_gt = saved;
	expect_close(p, TK_RPAREN, TK_LPAREN, open);
}

/* Does the current token start a further value without a comma before it?
 * POV-Ray takes `<1 0 0>` and `area_light <4 0 0> <0 0 4> 10 10`: a
 * number, a name or a parenthesis cannot continue the value before it. */
static int next_value(const struct parser *p)
{
	enum tok k = p->tok.kind;
	return !p->panic && (k == TK_NUMBER || k == TK_IDENT || k == TK_LPAREN);
}

/* vector := '<' expr {[','] expr} '>' */
static struct node *parse_vector(struct parser *p)
{
	struct node *v = node(p, N_VEC, p->tok.loc);
	advance(p);
	int saved = p->no_gt;
	p->no_gt = 1;
	do
		ast_push(p->arena, v, parse_expr(p));
	while ((accept(p, TK_COMMA) && !check(p, TK_GT)) || next_value(p)); /* <1,2,3,> too */
	p->no_gt = saved;
	expect_close(p, TK_GT, TK_LT, v->loc);
	return v;
}

/* init := '{' (expr | init) {',' (expr | init)} [','] '}' */
static struct node *parse_init(struct parser *p)
{
	struct node *n = node(p, N_INIT, p->tok.loc);
	advance(p);
	if (!enter(p))
		return n;
	while (!check(p, TK_RBRACE) && !check(p, TK_EOF)) {
		ast_push(p->arena, n, check(p, TK_LBRACE) ? parse_init(p) : parse_value(p));
		/* POV-Ray reads {"a" "b"} as {"a", "b"} */
		if ((!accept(p, TK_COMMA) && !check(p, TK_STRING)) || p->panic)
			break;
	}
	leave(p);
	expect_close(p, TK_RBRACE, TK_LBRACE, n->loc);
	return n;
}

/* array := 'array' '[' expr ']' {'[' expr ']'} [init] */
static struct node *parse_array(struct parser *p)
{
	struct node *n = node(p, N_ARRAY, p->tok.loc);
	advance(p);
	if (!check(p, TK_LBRACKET))
		expected(p, "'[' after 'array'");
	while (check(p, TK_LBRACKET)) {
		struct srcloc open = p->tok.loc;
		advance(p);
		ast_push(p->arena, n, parse_expr(p));
		expect_close(p, TK_RBRACKET, TK_LBRACKET, open);
	}
	if (check(p, TK_LBRACE))
		n->a = parse_init(p);
	return n;
}

/* Reads an identifier-like word (identifiers and keywords) after '.'. */
static int word_token(const struct parser *p)
{
	return p->tok.kind == TK_IDENT || tok_is_keyword(p->tok.kind);
}

/* postfix := primary {'.' word | '[' expr ']'} */
static struct node *parse_postfix(struct parser *p, struct node *e)
{
	for (;;) {
		if (check(p, TK_DOT)) {
			struct node *m = node(p, N_MEMBER, p->tok.loc);
			advance(p);
			if (!word_token(p)) {
				expected(p, "a member name after '.'");
				return e;
			}
			m->str = arena_strndup(p->arena, p->tok.text, (size_t)p->tok.len);
			m->len = p->tok.len;
			m->a = e;
			advance(p);
			e = m;
		} else if (check(p, TK_LBRACKET)) {
			struct node *ix = node(p, N_INDEX, p->tok.loc);
			advance(p);
			int saved = p->no_gt;
			p->no_gt = 0;
			ix->a = e;
			ix->b = parse_expr(p);
			p->no_gt = saved;
			expect_close(p, TK_RBRACKET, TK_LBRACKET, ix->loc);
			e = ix;
		} else {
			return e;
		}
	}
}

static struct node *parse_block_body(struct parser *p, struct node *blk);

/* params := ident {',' ident}, each pushed onto n as an N_IDENT (function
 * and macro headers); 0 after an error, reported. */
static int parse_params(struct parser *p, struct node *n)
{
	do {
		if (!check(p, TK_IDENT)) {
			expected(p, "a parameter name");
			return 0;
		}
		struct node *id = node(p, N_IDENT, p->tok.loc);
		id->str = arena_strndup(p->arena, p->tok.text, (size_t)p->tok.len);
		id->len = p->tok.len;
		ast_push(p->arena, n, id);
		advance(p);
	} while (accept(p, TK_COMMA));
	return 1;
}

/* function := 'function' ['(' [ident {',' ident}] ')'] '{' body '}'
 * body := 'pigment' block | 'pattern' block | expr   (in expr, a '^' b is a power) */
static struct node *parse_function(struct parser *p)
{
	struct node *n = node(p, N_FUNC, p->tok.loc);
	advance(p);
	if (check(p, TK_LPAREN)) {
		struct srcloc open = p->tok.loc;
		advance(p);
		if (!check(p, TK_RPAREN) && !parse_params(p, n))
			return n;
		expect_close(p, TK_RPAREN, TK_LPAREN, open);
	}
	struct srcloc open = p->tok.loc;
	if (!check(p, TK_LBRACE)) {
		expected(p, "'{' after 'function'");
		return n;
	}
	if (!enter(p))
		return n;
	advance(p);
	int saved = p->no_gt;
	p->no_gt = 0;
	p->in_func++;
	if (check(p, TK_PIGMENT) || check(p, TK_TRANSFORM)) {
		n->a = parse_keyword_item(p);
	} else if (check(p, TK_IDENT) && p->tok.len == 7 && memcmp(p->tok.text, "pattern", 7) == 0) {
		struct node *b = node(p, N_BLOCK, p->tok.loc);
		b->op = TK_PIGMENT;
		b->str = "pattern";
		advance(p);
		n->a = parse_block_body(p, b);
	} else {
		n->a = parse_expr(p);
	}
	p->in_func--;
	p->no_gt = saved;
	leave(p);
	if (p->panic) { /* skip the rest of the body, so its '}' closes nothing else */
		for (int depth = 0; !check(p, TK_EOF) && !(depth == 0 && check(p, TK_RBRACE)); advance(p))
			depth += check(p, TK_LBRACE) - check(p, TK_RBRACE);
		accept(p, TK_RBRACE);
		return n;
	}
	expect_close(p, TK_RBRACE, TK_LBRACE, open);
	return n;
}

static bool colour_component(enum tok k)
{
	return k == TK_RED || k == TK_GREEN || k == TK_BLUE || k == TK_FILTER || k == TK_TRANSMIT;
}

/* primary := number | string | ident [args] | '(' expr ')' | vector
 *          | colour-keyword [expr] {('red'|'green'|'blue'|'filter'|'transmit') expr}
 *          | array */
static struct node *parse_primary(struct parser *p)
{
	struct token t = p->tok;
	struct node *n;
	if (t.kind == TK_NUMBER) {
		n = node(p, N_NUM, t.loc);
		n->num = t.num;
		advance(p);
	} else if (t.kind == TK_STRING) {
		n = node(p, N_STR, t.loc);
		n->str = t.str;
		n->len = t.slen;
		advance(p);
	} else if (t.kind == TK_IDENT) {
		advance(p);
		n = node(p, check(p, TK_LPAREN) ? N_CALL : N_IDENT, t.loc);
		n->str = arena_strndup(p->arena, t.text, (size_t)t.len);
		n->len = t.len;
		if (n->kind == N_CALL)
			parse_args(p, n);
	} else if (t.kind == TK_LPAREN) {
		advance(p);
		int saved = p->no_gt;
		p->no_gt = 0;
		n = parse_expr(p);
		p->no_gt = saved;
		expect_close(p, TK_RPAREN, TK_LPAREN, t.loc);
	} else if (t.kind == TK_LT) {
		n = parse_vector(p);
	} else if (tok_shape(t.kind) == SH_PREFIX || t.kind == TK_RED || t.kind == TK_GREEN || t.kind == TK_BLUE) {
		/* a bare `red 0.75 green 0.75 blue 0.85` (POV-Ray's oldest pigment
		 * syntax) is `color red 0.75 …` */
		int bare = tok_shape(t.kind) != SH_PREFIX;
		n = node(p, N_COLOUR, t.loc);
		n->op = bare ? TK_COLOR : t.kind;
		if (!bare)
			advance(p);
		if ((t.kind == TK_COLOR || t.kind == TK_COLOUR) && tok_shape(p->tok.kind) == SH_PREFIX) {
			if (!enter(p)) /* "color color … rgb": bounded like any nesting */
				return n;
			struct node *r = parse_primary(p); /* "color rgb …" */
			leave(p);
			return r;
		}
		if (!bare && (!(t.kind == TK_COLOR || t.kind == TK_COLOUR) || !colour_component(p->tok.kind)))
			n->a = parse_expr(p); /* "color red 1 …" has none */
		/* POV-Ray's trailing components: rgb 1 filter 0.5, color red 1 green 0.5 */
		while (colour_component(p->tok.kind) && !p->panic) {
			struct node *c = node(p, N_COLOUR, p->tok.loc);
			c->op = p->tok.kind;
			advance(p);
			c->a = parse_expr(p);
			ast_push(p->arena, n, c);
		}
		return n;
	} else if (t.kind == TK_DIR_IF || t.kind == TK_DIR_IFDEF || t.kind == TK_DIR_IFNDEF || t.kind == TK_DIR_SWITCH) {
		/* POV-Ray's directives work between any tokens; arvo takes a
		 * conditional where a value stands: its branch yields the value */
		n = node(p, N_DIRVALUE, t.loc);
		n->a = parse_directive(p);
		return n;
	} else if (t.kind == TK_ARRAY) {
		return parse_array(p);
	} else if (t.kind == TK_FUNCTION) {
		return parse_function(p);
	} else {
		expected(p, "an expression");
		return node(p, N_NUM, t.loc);
	}
	return parse_postfix(p, n);
}

/* unary := ('-' | '+' | '!') unary | postfix */
static struct node *parse_unary(struct parser *p)
{
	if (check(p, TK_MINUS) || check(p, TK_PLUS) || check(p, TK_BANG)) {
		struct node *n = node(p, N_UNARY, p->tok.loc);
		n->op = p->tok.kind;
		advance(p);
		if (!enter(p))
			return n;
		n->a = parse_unary(p);
		leave(p);
		return n;
	}
	struct node *e = parse_primary(p);
	if (p->in_func && check(p, TK_CARET)) { /* a ^ b, right to left, above unary minus */
		struct node *n = node(p, N_BINARY, p->tok.loc);
		n->op = TK_CARET;
		advance(p);
		n->a = e;
		if (!enter(p))
			return n;
		n->b = parse_unary(p);
		leave(p);
		return n;
	}
	return e;
}

/* binary := unary {op binary}   (precedence climbing, left associative) */
static struct node *parse_binary(struct parser *p, int min_prec)
{
	struct node *left = parse_unary(p);
	int chain = 0; /* each operator nests its left operand one level deeper */
	for (;;) {
		int prec = binprec(p, p->tok.kind);
		if (prec == 0 || prec < min_prec || p->panic)
			break;
		/* `box { <0,0,0> <1,1,1> }`: a '<' right after a vector starts the
		 * next vector (POV-Ray compares floats only) */
		if (p->tok.kind == TK_LT && left && left->kind == N_VEC)
			break;
		/* `vertex_vectors { 14 <-1, -1, -1>, … }`: the count, then a vector */
		if (p->tok.kind == TK_LT && p->in_mesh_list && left && left->kind == N_NUM)
			break;
		if (p->depth >= MAX_DEPTH) {
			error_at(p, p->tok.loc, "expression too long (more than %d operators and levels of nesting)", MAX_DEPTH);
			break;
		}
		p->depth++, chain++;
		struct node *n = node(p, N_BINARY, p->tok.loc);
		n->op = p->tok.kind;
		advance(p);
		n->a = left;
		n->b = parse_binary(p, prec + 1);
		left = n;
	}
	p->depth -= chain;
	return left;
}

/* expr := binary ['?' expr ':' expr] */
static struct node *parse_expr(struct parser *p)
{
	if (!enter(p))
		return node(p, N_NUM, p->tok.loc);
	struct node *e = parse_binary(p, 1);
	if (check(p, TK_QUESTION)) {
		struct node *c = node(p, N_COND, p->tok.loc);
		advance(p);
		c->a = e;
		c->b = parse_expr(p);
		expect(p, TK_COLON);
		c->c = parse_expr(p);
		e = c;
	}
	leave(p);
	return e;
}

/* ==== block items ========================================================= */

/* block := '{' items '}' */
static struct node *parse_block_body(struct parser *p, struct node *blk)
{
	struct srcloc open = p->tok.loc;
	if (!check(p, TK_LBRACE)) {
		error_at(p, p->tok.loc, "expected '{' after %s, found %s", tok_name(blk->op), found(p));
		return blk;
	}
	if (p->depth >= MAX_DEPTH) { /* reported at the block's keyword */
		error_at(p, blk->loc, "nesting too deep (more than %d levels)", MAX_DEPTH);
		advance(p);
		return blk;
	}
	enter(p);
	advance(p);
	while (!check(p, TK_RBRACE) && !check(p, TK_EOF)) {
		long start = p->ntok;
		struct node *it = parse_item(p);
		if (it)
			ast_push(p->arena, blk, it);
		synchronize(p, start);
		if (tok_is_directive(p->tok.kind) && (check(p, TK_DIR_END) || check(p, TK_DIR_ELSE) ||
		    check(p, TK_DIR_ELSEIF) || check(p, TK_DIR_CASE) || check(p, TK_DIR_RANGE)))
			break;
	}
	leave(p);
	expect_close(p, TK_RBRACE, TK_LBRACE, open);
	return blk;
}

/* skipped := '{' anything balanced '}' */
static void skip_braces(struct parser *p)
{
	struct srcloc open = p->tok.loc;
	if (!expect(p, TK_LBRACE))
		return;
	int depth = 1;
	while (depth > 0 && !check(p, TK_EOF)) {
		if (check(p, TK_LBRACE))
			depth++;
		else if (check(p, TK_RBRACE))
			depth--;
		advance(p);
	}
	if (depth > 0)
		expect_close(p, TK_RBRACE, TK_LBRACE, open);
}

/* keyword-item := kw block | kw expr | kw {expr ','} | kw [expr] | kw word | kw */
static struct node *parse_keyword_item(struct parser *p)
{
	struct token t = p->tok;
	enum kw_shape sh = tok_shape(t.kind);
	if (sh == SH_PREFIX || sh == SH_VALUE) {
		struct node *e = parse_expr(p);
		accept(p, TK_COMMA); /* checker color A, color B */
		return e;
	}
	advance(p);
	struct node *n = node(p, N_MOD, t.loc);
	n->op = t.kind;
	if (sh != SH_BLOCK && sh != SH_BLOCK_OR_EXPR && sh != SH_SKIP && check(p, TK_LBRACE)) {
		/* a keyword arvo knows, in a block form it does not (media { }) */
		skip_braces(p);
		error_at(p, t.loc, "%s { } is not supported", tok_name(t.kind));
		return n;
	}
	switch (sh) {
	case SH_BLOCK:
		if (t.kind == TK_CLIPPED_BY && !check(p, TK_LBRACE))
			return n; /* bounded_by { clipped_by }: a word */
		if (t.kind == TK_CYLINDER && !check(p, TK_LBRACE)) {
			ast_push(p->arena, n, parse_expr(p)); /* the camera's cylinder N */
			return n;
		}
		n->kind = N_BLOCK;
		if (t.kind == TK_VERTEX_VECTORS || t.kind == TK_NORMAL_VECTORS || t.kind == TK_UV_VECTORS ||
		    t.kind == TK_FACE_INDICES || t.kind == TK_NORMAL_INDICES || t.kind == TK_UV_INDICES) {
			p->in_mesh_list++;
			parse_block_body(p, n);
			p->in_mesh_list--;
			return n;
		}
		if (t.kind == TK_NORMAL) {
			p->in_normal++;
			parse_block_body(p, n);
			p->in_normal--;
			return n;
		}
		p->in_texture += t.kind == TK_TEXTURE;
		parse_block_body(p, n);
		p->in_texture -= t.kind == TK_TEXTURE;
		/* POV-Ray's layered texture: `texture { A } texture { B }` in a row
		 * is one texture, B over A; c links the next layer up */
		if (t.kind == TK_TEXTURE && check(p, TK_TEXTURE) && !p->in_texture && !p->panic && enter(p)) {
			n->c = parse_keyword_item(p);
			leave(p);
		}
		return n;
	case SH_BLOCK_OR_EXPR:
		if (check(p, TK_LBRACE)) {
			n->kind = N_BLOCK;
			return parse_block_body(p, n);
		}
		ast_push(p->arena, n, parse_expr(p));
		return n;
	case SH_EXPR: /* one value expected; a list is parsed and counted later */
	case SH_LIST:
		do
			ast_push(p->arena, n, parse_expr(p));
		while ((accept(p, TK_COMMA) && !p->panic) ||
		       (t.kind == TK_AREA_LIGHT && (next_value(p) || check(p, TK_LT))));
		return n;
	case SH_OPTEXPR:
		if (starts_expr(p))
			ast_push(p->arena, n, parse_expr(p));
		return n;
	case SH_WORD:
		n->kind = N_WORD;
		if (!word_token(p)) {
			error_at(p, p->tok.loc, "expected a word after %s, found %s", tok_name(t.kind), found(p));
			return n;
		}
		n->str = arena_strndup(p->arena, p->tok.text, (size_t)p->tok.len);
		n->len = p->tok.len;
		advance(p);
		return n;
	case SH_SKIP:
		n->kind = N_SKIPPED;
		skip_braces(p);
		return n;
	default:
		return n; /* SH_FLAG */
	}
}

/* The body of a directive: items up to #end/#else/#elseif/#case/#range. */
static struct node *parse_body(struct parser *p)
{
	struct node *list = node(p, N_LIST, p->tok.loc);
	parse_items(p, list);
	return list;
}

/* Consumes '#end' for a directive opened at `at`. */
static void expect_end(struct parser *p, enum tok opener, struct srcloc at)
{
	expect_close(p, TK_DIR_END, opener, at);
}

/* paren := '(' expr ')' */
static struct node *parse_paren(struct parser *p)
{
	struct srcloc open = p->tok.loc;
	if (!expect(p, TK_LPAREN))
		return node(p, N_NUM, open);
	struct node *e = parse_expr(p);
	expect_close(p, TK_RPAREN, TK_LPAREN, open);
	return e;
}

/* declare := ('#declare' | '#local') ident {'[' expr ']'} '=' value [';']
 * value := block-keyword-item | expr */
static struct node *parse_declare(struct parser *p, struct token d)
{
	struct node *n = node(p, N_DECLARE, d.loc);
	n->op = d.kind;
	struct token name = p->tok;
	bool have_name = false;
	if (check(p, TK_IDENT) && p->tok.len == 10 && memcmp(p->tok.text, "deprecated", 10) == 0) {
		advance(p);
		if (check(p, TK_ONCE) || check(p, TK_STRING)) {
			/* POV-Ray's #declare deprecated [once] "message" Name = … */
			accept(p, TK_ONCE);
			accept(p, TK_STRING);
		} else {
			have_name = true; /* a variable called deprecated */
		}
	}
	if (!have_name) {
		if (!check(p, TK_IDENT)) {
			if (tok_is_keyword(p->tok.kind)) {
				error_at(p, p->tok.loc, "%s is a reserved word and cannot be declared", tok_name(p->tok.kind));
				advance(p); /* so resynchronising does not restart at it */
			} else {
				expected(p, "an identifier");
			}
			return n;
		}
		name = p->tok;
		advance(p);
	}
	n->str = arena_strndup(p->arena, name.text, (size_t)name.len);
	n->len = name.len;
	n->b = node(p, N_IDENT, name.loc); /* where the name is */
	n->b->str = n->str;
	n->b->len = n->len;
	while (check(p, TK_LBRACKET)) {
		struct srcloc open = p->tok.loc;
		advance(p);
		ast_push(p->arena, n, parse_expr(p));
		expect_close(p, TK_RBRACKET, TK_LBRACKET, open);
	}
	if (!expect(p, TK_EQ))
		return n;
	n->a = parse_value(p);
	accept(p, TK_SEMI);
	return n;
}

/* if := '#if' paren items {'#elseif' paren items} ['#else' items] '#end' */
static struct node *parse_if(struct parser *p, struct token d)
{
	struct node *n = node(p, N_IF, d.loc), *cur = n;
	n->a = parse_paren(p);
	n->b = parse_body(p);
	while (check(p, TK_DIR_ELSEIF)) {
		struct node *e = node(p, N_IF, p->tok.loc);
		advance(p);
		e->a = parse_paren(p);
		e->b = parse_body(p);
		cur->c = e;
		cur = e;
	}
	if (accept(p, TK_DIR_ELSE))
		cur->c = parse_body(p);
	expect_end(p, d.kind, d.loc);
	return n;
}

/* ifdef := ('#ifdef' | '#ifndef') '(' ident ')' items ['#else' items] '#end' */
static struct node *parse_ifdef(struct parser *p, struct token d)
{
	struct node *n = node(p, N_IFDEF, d.loc);
	n->op = d.kind;
	n->a = parse_paren(p);
	n->b = parse_body(p);
	if (accept(p, TK_DIR_ELSE))
		n->c = parse_body(p);
	expect_end(p, d.kind, d.loc);
	return n;
}

/* After an error in a directive's '( … )' header: skip to its ')' so the
 * body and '#end' still pair up. */
static void recover_header(struct parser *p)
{
	while (!check(p, TK_EOF) && !check(p, TK_RPAREN) && !tok_is_directive(p->tok.kind))
		advance(p);
	accept(p, TK_RPAREN);
}

/* for := '#for' '(' ident ',' expr ',' expr [',' expr] ')' items '#end' */
static struct node *parse_for(struct parser *p, struct token d)
{
	struct node *n = node(p, N_FOR, d.loc);
	struct srcloc open = p->tok.loc;
	if (!expect(p, TK_LPAREN))
		return n;
	if (!check(p, TK_IDENT)) {
		expected(p, "a loop variable");
		recover_header(p);
	} else {
		n->str = arena_strndup(p->arena, p->tok.text, (size_t)p->tok.len);
		n->len = p->tok.len;
		advance(p);
		for (int i = 0; i < 3 && !p->panic; i++) {
			if (i == 2 && !check(p, TK_COMMA))
				break;
			if (expect(p, TK_COMMA))
				ast_push(p->arena, n, parse_expr(p));
		}
		if (p->panic)
			recover_header(p);
		else
			expect_close(p, TK_RPAREN, TK_LPAREN, open);
	}
	n->b = parse_body(p);
	expect_end(p, d.kind, d.loc);
	return n;
}

/* switch := '#switch' paren {clause} '#end'
 * clause := ('#case' paren | '#range' '(' expr ',' expr ')' | '#else') items */
static struct node *parse_switch(struct parser *p, struct token d)
{
	struct node *n = node(p, N_SWITCH, d.loc);
	n->a = parse_paren(p);
	while (check(p, TK_DIR_CASE) || check(p, TK_DIR_RANGE) || check(p, TK_DIR_ELSE)) {
		struct node *c = node(p, N_CASE, p->tok.loc);
		c->op = p->tok.kind;
		advance(p);
		if (c->op == TK_DIR_CASE) {
			ast_push(p->arena, c, parse_paren(p));
		} else if (c->op == TK_DIR_RANGE) {
			struct srcloc open = p->tok.loc;
			if (expect(p, TK_LPAREN)) {
				ast_push(p->arena, c, parse_expr(p));
				expect(p, TK_COMMA);
				ast_push(p->arena, c, parse_expr(p));
				expect_close(p, TK_RPAREN, TK_LPAREN, open);
			}
		}
		c->b = parse_body(p);
		ast_push(p->arena, n, c);
		if (p->panic)
			break;
	}
	if (!check(p, TK_DIR_END) && !check(p, TK_EOF) && !p->panic) {
		expected(p, "'#case', '#range', '#else' or '#end' in '#switch'");
		parse_body(p); /* skip what is there, so '#end' still closes the switch */
		p->panic = 0;
		p->panic = 1;
		if (check(p, TK_DIR_END)) {
			advance(p);
			p->panic = 0;
			return n;
		}
	}
	expect_end(p, d.kind, d.loc);
	return n;
}

/* macro := '#macro' ident '(' [ident {',' ident}] ')' items '#end' */
static struct node *parse_macro(struct parser *p, struct token d)
{
	struct node *n = node(p, N_MACRO, d.loc);
	if (!check(p, TK_IDENT)) {
		expected(p, "a macro name");
		return n;
	}
	n->str = arena_strndup(p->arena, p->tok.text, (size_t)p->tok.len);
	n->len = p->tok.len;
	advance(p);
	struct srcloc open = p->tok.loc;
	if (!expect(p, TK_LPAREN))
		return n;
	if (!check(p, TK_RPAREN))
		parse_params(p, n);
	if (p->panic)
		recover_header(p);
	else
		expect_close(p, TK_RPAREN, TK_LPAREN, open);
	if (p->panic) {
		n->b = parse_body(p);
		expect_end(p, d.kind, d.loc);
		return n;
	}
	/* POV-Ray reads a macro's tokens only when it is called, so its
	 * directives may split blocks (`#if (M) merge { #else union { #end`),
	 * which arvo's tree cannot hold. The body is tried quietly first: if
	 * it parses it is parsed again for real (its warnings then appear);
	 * if not it is skipped to its #end and parsed at its first call. */
	struct lexer lx0 = p->lx;
	struct token tok0 = p->tok, prev0 = p->prev;
	int depth0 = p->depth;
	long ntok0 = p->ntok;
	struct diag *real = p->diag, quiet;
	diag_init(&quiet, NULL);
	p->diag = p->lx.diag = &quiet;
	int first0 = p->first_set;
	p->first_set = 0;
	parse_body(p);
	expect_end(p, d.kind, d.loc);
	int ok = quiet.errors == 0;
	p->lx = lx0, p->tok = tok0, p->prev = prev0, p->depth = depth0, p->ntok = ntok0, p->panic = 0;
	p->diag = real;
	struct srcloc wloc = p->first_set ? p->first_loc : d.loc;
	char wmsg[256];
	snprintf(wmsg, sizeof wmsg, "%s", p->first_set ? p->first_msg : "a lexical error");
	p->first_set = first0;
	if (ok) {
		n->b = parse_body(p);
		expect_end(p, d.kind, d.loc);
		return n;
	}
	struct lazy_body *lb = ARENA_NEW(p->arena, struct lazy_body);
	lb->lx = lx0, lb->tok = tok0, lb->prev = prev0;
	n->lazy = lb;
	p->lx.diag = &quiet;
	for (int level = 0; !check(p, TK_EOF); advance(p)) {
		enum tok k = p->tok.kind;
		if (k == TK_DIR_IF || k == TK_DIR_IFDEF || k == TK_DIR_IFNDEF || k == TK_DIR_WHILE ||
		    k == TK_DIR_FOR || k == TK_DIR_SWITCH || k == TK_DIR_MACRO)
			level++;
		else if (k == TK_DIR_END && level-- == 0)
			break;
	}
	p->lx.diag = real;
	p->panic = 0;
	if (check(p, TK_DIR_END) && !p->quiet_macros) /* else the missing #end is the error */
		diag_warning(real, wloc, "macro '%s' is read only when called, as in POV-Ray: as written it does not parse (%s)",
		             n->str, wmsg);
	expect_end(p, d.kind, d.loc);
	return n;
}

struct node *parse_macro_body(const struct node *def, struct diag *diag, struct arena *arena)
{
	struct parser p;
	memset(&p, 0, sizeof p);
	p.arena = arena;
	p.diag = diag;
	p.lx = def->lazy->lx;
	p.lx.diag = diag;
	p.tok = def->lazy->tok;
	p.prev = def->lazy->prev;
	int before = diag->errors;
	struct node *body = parse_body(&p);
	expect_end(&p, TK_DIR_MACRO, def->loc);
	return diag->errors > before ? NULL : body;
}

/* directive := declare | if | ifdef | while | for | switch | macro
 *            | '#undef' ident | '#include' expr | '#version' expr [';']
 *            | ('#debug' | '#warning' | '#error') expr | '#default' block | '#break' */
static struct node *parse_directive_body(struct parser *p, struct token d);

/* Directives nest under the same guard as blocks: 45,000 nested '#if' are
 * an error, not a stack overflow (docs/design.md §8). */
static struct node *parse_directive(struct parser *p)
{
	struct token d = p->tok;
	if (!enter(p)) {
		advance(p);
		return NULL;
	}
	advance(p);
	struct node *n = parse_directive_body(p, d);
	leave(p);
	return n;
}

static struct node *parse_directive_body(struct parser *p, struct token d)
{
	struct node *n;
	switch (d.kind) {
	case TK_DIR_DECLARE: case TK_DIR_LOCAL: return parse_declare(p, d);
	case TK_DIR_IF: return parse_if(p, d);
	case TK_DIR_IFDEF: case TK_DIR_IFNDEF: return parse_ifdef(p, d);
	case TK_DIR_FOR: return parse_for(p, d);
	case TK_DIR_SWITCH: return parse_switch(p, d);
	case TK_DIR_MACRO: return parse_macro(p, d);
	case TK_DIR_WHILE:
		n = node(p, N_WHILE, d.loc);
		n->a = parse_paren(p);
		n->b = parse_body(p);
		expect_end(p, d.kind, d.loc);
		return n;
	case TK_DIR_UNDEF:
		n = node(p, N_UNDEF, d.loc);
		if (!check(p, TK_IDENT)) {
			expected(p, "an identifier after '#undef'");
			return n;
		}
		n->str = arena_strndup(p->arena, p->tok.text, (size_t)p->tok.len);
		n->len = p->tok.len;
		advance(p);
		return n;
	case TK_DIR_INCLUDE:
		n = node(p, N_INCLUDE, d.loc);
		n->a = parse_expr(p);
		return n;
	case TK_DIR_VERSION:
		n = node(p, N_VERSION, d.loc);
		n->a = parse_expr(p);
		accept(p, TK_SEMI);
		return n;
	case TK_DIR_DEBUG: case TK_DIR_WARNING: case TK_DIR_ERROR:
		n = node(p, N_MESSAGE, d.loc);
		n->op = d.kind;
		n->a = parse_expr(p);
		return n;
	case TK_DIR_DEFAULT:
		n = node(p, N_DEFAULT, d.loc);
		n->op = d.kind;
		return parse_block_body(p, n);
	case TK_DIR_BREAK:
		return node(p, N_BREAK, d.loc);
	case TK_DIR_FOPEN: case TK_DIR_FCLOSE: case TK_DIR_READ: case TK_DIR_WRITE:
		/* an error where it is parsed, so a macro that is never called
		 * (strings.inc's Parse_String) may hold one */
		error_at(p, d.loc, "%s is not supported: a scene cannot open, read or write files or run commands",
		         tok_name(d.kind));
		return NULL;
	default:
		error_at(p, d.loc, "%s without a matching opening directive", tok_name(d.kind));
		return NULL;
	}
}

/* A word arvo has no keyword for, followed by '{': POV-Ray's old
 * `default { }` (#default), a `radiosity { }` block (ignored with a
 * warning: the scene renders without it), or an error naming the word. */
static struct node *word_block(struct parser *p, struct node *id)
{
	if (strcmp(id->str, "default") == 0) {
		struct node *n = node(p, N_DEFAULT, id->loc);
		n->op = TK_DIR_DEFAULT;
		return parse_block_body(p, n);
	}
	skip_braces(p);
	if ((p->in_normal || p->in_func) && tok_is_pov_word(id->str))
		return id; /* normal { slope_map { } }: the evaluator ignores the normal;
		            * function { pattern { warp { } } }: an error if it is used */
	if (strcmp(id->str, "radiosity") == 0)
		diag_warning(p->diag, id->loc, "'radiosity' is not supported; ignored (the scene renders with its ambient light)");
	else if (tok_is_pov_word(id->str))
		error_at(p, id->loc, "'%s' is not supported", id->str);
	else
		error_at(p, id->loc, "unknown keyword '%s' before '{'", id->str);
	return NULL;
}

/* item := directive | keyword-item | '[' items ']' | expr [','] */
static struct node *parse_item(struct parser *p)
{
	enum tok k = p->tok.kind;
	if (tok_is_directive(k))
		return parse_directive(p);
	if (tok_is_keyword(k))
		return parse_keyword_item(p);
	if (k == TK_LBRACKET) {
		struct node *n = node(p, N_ENTRY, p->tok.loc);
		if (!enter(p)) {
			advance(p);
			return NULL;
		}
		advance(p);
		while (!check(p, TK_RBRACKET) && !check(p, TK_EOF) && !p->panic) {
			struct node *it = parse_item(p);
			if (it)
				ast_push(p->arena, n, it);
		}
		leave(p);
		expect_close(p, TK_RBRACKET, TK_LBRACKET, n->loc);
		return n;
	}
	if (starts_expr(p)) {
		struct node *e = parse_expr(p);
		if (e && e->kind == N_IDENT && check(p, TK_LBRACE))
			return word_block(p, e);
		accept(p, TK_COMMA);
		return e;
	}
	if (k == TK_SEMI)
		error_at(p, p->tok.loc, "unexpected ';'");
	else
		error_at(p, p->tok.loc, "unexpected %s", found(p));
	advance(p);
	return NULL;
}

/* items := {item}, stopping at '}', EOF or a clause directive. */
static void parse_items(struct parser *p, struct node *list)
{
	for (;;) {
		enum tok k = p->tok.kind;
		if (k == TK_EOF || k == TK_RBRACE || k == TK_DIR_END || k == TK_DIR_ELSE ||
		    k == TK_DIR_ELSEIF || k == TK_DIR_CASE || k == TK_DIR_RANGE)
			return;
		long start = p->ntok;
		struct node *it = parse_item(p);
		if (it)
			ast_push(p->arena, list, it);
		synchronize(p, start);
	}
}

/* file := items EOF */
struct node *parse_file(int file, struct diag *diag, struct arena *arena)
{
	return parse_file_quiet(file, diag, arena, 0);
}

struct node *parse_file_quiet(int file, struct diag *diag, struct arena *arena, int quiet_macros)
{
	struct parser p;
	memset(&p, 0, sizeof p);
	p.quiet_macros = quiet_macros;
	p.arena = arena;
	p.diag = diag;
	lex_init(&p.lx, file, diag, arena);
	advance(&p);
	struct node *root = node(&p, N_LIST, p.tok.loc);
	for (;;) {
		parse_items(&p, root);
		if (check(&p, TK_EOF))
			break;
		/* a stray closer at file level */
		error_at(&p, p.tok.loc, "unexpected %s", found(&p));
		advance(&p);
		synchronize(&p, p.ntok);
	}
	return root;
}
