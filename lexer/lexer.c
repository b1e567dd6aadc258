/* SPDX-License-Identifier: MIT */
/* lexer.c: hand-written scanner for the scene language.
 *
 * Numbers in every POV-Ray form (1, 1.5, .5, 5., 1e3, 2.5E-3), strings with
 * escapes, // comments and nesting block comments, #directives, and keywords
 * from one table. Errors are reported through the diag sink and come back as
 * TK_ERROR tokens, so the parser can carry on. */
#include "lexer.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ==== keyword table ======================================================= */

struct kw {
	const char *word; /* spelling */
	enum tok kind;    /* token */
};

static struct kw kwtab[] = {
#define KEYWORD(n, s, shape) {s, TK_##n},
#include "tokens.def"
};
static struct kw dirtab[] = {
#define DIRECTIVE(n, s) {s, TK_DIR_##n},
#include "tokens.def"
};
#define NKW (sizeof kwtab / sizeof kwtab[0])
#define NDIR (sizeof dirtab / sizeof dirtab[0])
static int tables_sorted;

static int kwcmp(const void *a, const void *b)
{
	return strcmp(((const struct kw *)a)->word, ((const struct kw *)b)->word);
}

static void sort_tables(void)
{
	if (tables_sorted)
		return;
	qsort(kwtab, NKW, sizeof kwtab[0], kwcmp);
	qsort(dirtab, NDIR, sizeof dirtab[0], kwcmp);
	tables_sorted = 1;
}

/* Binary search of a sorted table for the word s[0..len). */
static enum tok lookup(const struct kw *tab, size_t n, const char *s, int len, enum tok miss)
{
	char buf[64];
	if (len <= 0 || len >= (int)sizeof buf)
		return miss;
	memcpy(buf, s, (size_t)len);
	buf[len] = '\0';
	struct kw key = {buf, TK_EOF};
	sort_tables();
	const struct kw *k = bsearch(&key, tab, n, sizeof *tab, kwcmp);
	return k ? k->kind : miss;
}

enum tok lex_keyword(const char *s, int len) { return lookup(kwtab, NKW, s, len, TK_IDENT); }

/* ==== scanning ============================================================ */

void lex_init(struct lexer *lx, int file, struct diag *diag, struct arena *arena)
{
	const struct srcfile *f = srcfile_get(file);
	memset(lx, 0, sizeof *lx);
	lx->src = lx->p = lx->line_start = f->text;
	lx->end = f->text + f->len;
	lx->file = file;
	lx->line = 1;
	lx->diag = diag;
	lx->arena = arena;
	lx->max_string = 1 << 20;
}

static struct srcloc here(const struct lexer *lx, const char *p)
{
	return (struct srcloc){lx->file, lx->line, (int)(p - lx->line_start) + 1};
}

static void newline(struct lexer *lx, const char *next)
{
	lx->line++;
	lx->line_start = next;
}

/* Skips a block comment whose "/ *" starts at p; comments nest. */
static void skip_block_comment(struct lexer *lx)
{
	struct srcloc open = here(lx, lx->p);
	int depth = 0;
	while (lx->p < lx->end) {
		if (lx->p[0] == '/' && lx->p + 1 < lx->end && lx->p[1] == '*') {
			depth++;
			lx->p += 2;
		} else if (lx->p[0] == '*' && lx->p + 1 < lx->end && lx->p[1] == '/') {
			lx->p += 2;
			if (--depth == 0)
				return;
		} else {
			if (*lx->p == '\n')
				newline(lx, lx->p + 1);
			lx->p++;
		}
	}
	diag_error(lx->diag, open, "unterminated comment");
}

/* Skips blanks and comments. */
static void skip_space(struct lexer *lx)
{
	while (lx->p < lx->end) {
		char c = *lx->p;
		if (c == '\n') {
			newline(lx, ++lx->p);
		} else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
			lx->p++;
		} else if (c == '/' && lx->p + 1 < lx->end && lx->p[1] == '/') {
			while (lx->p < lx->end && *lx->p != '\n')
				lx->p++;
		} else if (c == '/' && lx->p + 1 < lx->end && lx->p[1] == '*') {
			skip_block_comment(lx);
		} else {
			break;
		}
	}
}

static int is_ident_start(int c) { return isalpha(c) || c == '_'; }
static int is_ident(int c) { return isalnum(c) || c == '_'; }

/* A number: digits [. digits] [e [+-] digits], or . digits [...]. */
static void scan_number(struct lexer *lx, struct token *t)
{
	const char *p = lx->p;
	while (p < lx->end && isdigit((unsigned char)*p))
		p++;
	if (p < lx->end && *p == '.') {
		p++;
		while (p < lx->end && isdigit((unsigned char)*p))
			p++;
	}
	if (p < lx->end && (*p == 'e' || *p == 'E')) {
		const char *q = p + 1;
		if (q < lx->end && (*q == '+' || *q == '-'))
			q++;
		if (q < lx->end && isdigit((unsigned char)*q)) {
			while (q < lx->end && isdigit((unsigned char)*q))
				q++;
			p = q;
		} else {
			diag_error(lx->diag, here(lx, p), "malformed number: exponent has no digits");
			t->kind = TK_ERROR;
			lx->p = q;
			return;
		}
	}
	char buf[128];
	size_t n = (size_t)(p - lx->p);
	if (n >= sizeof buf) {
		diag_error(lx->diag, t->loc, "number too long");
		t->kind = TK_ERROR;
		lx->p = p;
		return;
	}
	memcpy(buf, lx->p, n);
	buf[n] = '\0';
	t->kind = TK_NUMBER;
	t->num = strtod(buf, NULL);
	if (!isfinite(t->num)) { /* 1e400: no infinite radius reaches the scene */
		diag_error(lx->diag, t->loc, "number out of range: %s", buf);
		t->kind = TK_ERROR;
	}
	lx->p = p;
}

/* Appends the UTF-8 encoding of code point cp to out. */
static int put_utf8(char *out, unsigned cp)
{
	if (cp < 0x80)
		return out[0] = (char)cp, 1;
	if (cp < 0x800)
		return out[0] = (char)(0xC0 | cp >> 6), out[1] = (char)(0x80 | (cp & 0x3F)), 2;
	out[0] = (char)(0xE0 | cp >> 12);
	out[1] = (char)(0x80 | ((cp >> 6) & 0x3F));
	out[2] = (char)(0x80 | (cp & 0x3F));
	return 3;
}

/* Decodes one escape at p (just after the backslash) into out; returns the
 * bytes written, or -1 after reporting a bad escape. *pp advances. */
static int scan_escape(struct lexer *lx, const char **pp, char *out)
{
	const char *p = *pp;
	static const char from[] = "ntr\\\"'abfv", to[] = "\n\t\r\\\"'\a\b\f\v";
	const char *k = strchr(from, *p);
	if (*p && k) {
		*pp = p + 1;
		out[0] = to[k - from];
		return 1;
	}
	if (*p == 'u') {
		unsigned cp = 0;
		for (int i = 1; i <= 4; i++) {
			if (p + i >= lx->end || !isxdigit((unsigned char)p[i])) {
				diag_error(lx->diag, here(lx, p - 1), "'\\u' needs four hexadecimal digits");
				*pp = p + 1;
				return -1;
			}
			cp = cp * 16 + (unsigned)(isdigit((unsigned char)p[i]) ? p[i] - '0' : (tolower((unsigned char)p[i]) - 'a' + 10));
		}
		*pp = p + 5;
		return put_utf8(out, cp);
	}
	diag_error(lx->diag, here(lx, p - 1), "unknown escape sequence '\\%c'", isprint((unsigned char)*p) ? *p : '?');
	*pp = p + 1;
	return -1;
}

/* A string literal; the unescaped text goes to the arena. */
static void scan_string(struct lexer *lx, struct token *t)
{
	const char *p = lx->p + 1;
	size_t cap = 64, n = 0;
	char *buf = mem_alloc(cap);
	int bad = 0;
	for (;;) {
		if (p >= lx->end || *p == '\n') {
			diag_error(lx->diag, t->loc, "unterminated string");
			t->kind = TK_ERROR;
			lx->p = p;
			free(buf);
			return;
		}
		if (*p == '"')
			break;
		if (n + 4 >= cap)
			buf = mem_realloc(buf, cap *= 2);
		if (*p == '\\') {
			p++;
			int k = scan_escape(lx, &p, buf + n);
			if (k < 0)
				bad = 1;
			else
				n += (size_t)k;
		} else {
			buf[n++] = *p++;
		}
	}
	lx->p = p + 1;
	if ((long)n > lx->max_string) {
		diag_error(lx->diag, t->loc, "string too long (%zu bytes; the limit is %ld)", n, lx->max_string);
		bad = 1;
	}
	t->kind = bad ? TK_ERROR : TK_STRING;
	t->str = arena_strndup(lx->arena, buf, n);
	t->slen = (int)n;
	free(buf);
}

/* Punctuation, longest match first. */
static enum tok scan_punct(const char *p, const char *end, int *len)
{
	char c = p[0], d = p + 1 < end ? p[1] : '\0';
	*len = 2;
	if (c == '<' && d == '=')
		return TK_LE;
	if (c == '>' && d == '=')
		return TK_GE;
	if (c == '!' && d == '=')
		return TK_NE;
	*len = 1;
	switch (c) {
	case '{': return TK_LBRACE;
	case '}': return TK_RBRACE;
	case '(': return TK_LPAREN;
	case ')': return TK_RPAREN;
	case '[': return TK_LBRACKET;
	case ']': return TK_RBRACKET;
	case '<': return TK_LT;
	case '>': return TK_GT;
	case '=': return TK_EQ;
	case ',': return TK_COMMA;
	case ';': return TK_SEMI;
	case '.': return TK_DOT;
	case '+': return TK_PLUS;
	case '-': return TK_MINUS;
	case '*': return TK_STAR;
	case '/': return TK_SLASH;
	case '!': return TK_BANG;
	case '&': return TK_AMP;
	case '|': return TK_PIPE;
	case '^': return TK_CARET;
	case '?': return TK_QUESTION;
	case ':': return TK_COLON;
	default: return TK_ERROR;
	}
}

/* POV-Ray's directives that reach outside the scene (file I/O) and the
 * shell-outs other tools have: refused by name (docs/design.md §9, "Files"). */
static int file_directive(const char *w, int len)
{
	static const char *const names[] = {"fopen", "fclose", "read", "write", "system", "exec", "shell"};
	for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
		if ((int)strlen(names[i]) == len && memcmp(names[i], w, (size_t)len) == 0)
			return 1;
	return 0;
}

/* #word: a directive token. */
static void scan_directive(struct lexer *lx, struct token *t)
{
	const char *p = lx->p + 1;
	while (p < lx->end && (*p == ' ' || *p == '\t'))
		p++;
	const char *w = p;
	while (p < lx->end && is_ident((unsigned char)*p))
		p++;
	lx->p = p;
	t->kind = lookup(dirtab, NDIR, w, (int)(p - w), TK_ERROR);
	if (t->kind == TK_ERROR) {
		if (p == w)
			diag_error(lx->diag, t->loc, "expected a directive name after '#'");
		else if (file_directive(w, (int)(p - w)))
			diag_error(lx->diag, t->loc, "'#%.*s' is not supported: a scene cannot open, read or write "
			           "files or run commands", (int)(p - w), w);
		else
			diag_error(lx->diag, t->loc, "unknown directive '#%.*s'", p - w > 40 ? 40 : (int)(p - w), w);
	}
}

static void scan(struct lexer *lx, struct token *t)
{
	skip_space(lx);
	memset(t, 0, sizeof *t);
	t->text = lx->p;
	t->loc = here(lx, lx->p);
	if (lx->p >= lx->end) {
		t->kind = TK_EOF;
		/* point at the end of the last line, not at an empty line after it */
		if (lx->p > lx->src && lx->p == lx->line_start && lx->line > 1) {
			const char *q = lx->p - 1, *start = q;
			while (start > lx->src && start[-1] != '\n')
				start--;
			if (q > start && q[-1] == '\r')
				q--;
			t->loc = (struct srcloc){lx->file, lx->line - 1, (int)(q - start) + 1};
		}
		return;
	}
	unsigned char c = (unsigned char)*lx->p;
	if (isdigit(c) || (c == '.' && lx->p + 1 < lx->end && isdigit((unsigned char)lx->p[1]))) {
		scan_number(lx, t);
	} else if (is_ident_start(c)) {
		const char *p = lx->p;
		while (p < lx->end && is_ident((unsigned char)*p))
			p++;
		if (p - lx->p > MAX_IDENT) { /* every lookup hashes the whole name */
			diag_error(lx->diag, t->loc, "identifier too long (%ld characters; the limit is %d)", (long)(p - lx->p),
			           MAX_IDENT);
			t->kind = TK_ERROR;
		} else {
			t->kind = lex_keyword(lx->p, (int)(p - lx->p));
		}
		lx->p = p;
	} else if (c == '"') {
		scan_string(lx, t);
	} else if (c == '#') {
		scan_directive(lx, t);
	} else {
		int len;
		t->kind = scan_punct(lx->p, lx->end, &len);
		if (t->kind == TK_ERROR) {
			if (isprint(c))
				diag_error(lx->diag, t->loc, "unexpected character '%c'", c);
			else
				diag_error(lx->diag, t->loc, "unexpected byte 0x%02x", c);
		}
		lx->p += len;
	}
	t->len = (int)(lx->p - t->text);
}

void lex_next(struct lexer *lx, struct token *t)
{
	if (lx->has_ahead) {
		*t = lx->ahead;
		lx->has_ahead = false;
		return;
	}
	scan(lx, t);
}

const struct token *lex_peek(struct lexer *lx)
{
	if (!lx->has_ahead) {
		scan(lx, &lx->ahead);
		lx->has_ahead = true;
	}
	return &lx->ahead;
}

void lex_dump(FILE *out, struct lexer *lx)
{
	struct token t;
	do {
		lex_next(lx, &t);
		fprintf(out, "%d:%d %s", t.loc.line, t.loc.col, t.kind == TK_EOF ? "EOF" : tok_name(t.kind));
		if (t.kind == TK_NUMBER)
			fprintf(out, " %.17g", t.num);
		else if (t.kind == TK_IDENT)
			fprintf(out, " %.*s", t.len, t.text);
		else if (t.kind == TK_STRING) {
			fputs(" \"", out);
			for (int i = 0; i < t.slen; i++) {
				unsigned char ch = (unsigned char)t.str[i];
				if (ch == '"' || ch == '\\')
					fprintf(out, "\\%c", ch);
				else if (ch < 32 || ch == 127)
					fprintf(out, "\\x%02x", ch);
				else
					fputc(ch, out);
			}
			fputc('"', out);
		}
		fputc('\n', out);
	} while (t.kind != TK_EOF);
}
