/* SPDX-License-Identifier: MIT */
/* test_lexer.c: tokens, numbers in every POV-Ray form, strings, comments,
 * locations and lexical errors. */
#include <stdlib.h>
#include <string.h>

#include "../../common/arena.h"
#include "../../common/diag.h"
#include "../../lexer/lexer.h"
#include "test.h"

static struct arena arena;
static struct diag dg;
static char *errs;
static size_t errlen;

/* Starts a lexer over text; diagnostics go to an in-memory stream. */
static void start(struct lexer *lx, const char *text)
{
	FILE *f = open_memstream(&errs, &errlen);
	diag_init(&dg, f);
	int file = srcfile_add(mem_strdup("t.scn"), mem_strdup(text), strlen(text));
	lex_init(lx, file, &dg, &arena);
}

static const char *finish(void)
{
	fflush(dg.out);
	fclose(dg.out);
	return errs;
}

static void t_numbers(void)
{
	struct lexer lx;
	struct token t;
	start(&lx, "1 1.5 .5 5. 1e3 2.5E-3 2e+2 007");
	double want[] = {1, 1.5, .5, 5., 1e3, 2.5e-3, 2e2, 7};
	for (int i = 0; i < 8; i++) {
		lex_next(&lx, &t);
		CHECK(t.kind == TK_NUMBER);
		CHECK_NEAR(t.num, want[i], 0);
	}
	lex_next(&lx, &t);
	CHECK(t.kind == TK_EOF);
	CHECK(dg.errors == 0);
	finish();
	free(errs);
}

static void t_strings(void)
{
	struct lexer lx;
	struct token t;
	start(&lx, "\"a\\tb\\n\\\"q\\\\\" \"\\u00e9\" \"\"");
	lex_next(&lx, &t);
	CHECK(t.kind == TK_STRING);
	CHECK(t.slen == 7);
	CHECK(memcmp(t.str, "a\tb\n\"q\\", 7) == 0);
	lex_next(&lx, &t);
	CHECK(t.kind == TK_STRING);
	CHECK_STR(t.str, "\xc3\xa9");
	lex_next(&lx, &t);
	CHECK(t.kind == TK_STRING && t.slen == 0);
	finish();
	free(errs);
}

static void t_keywords_and_punct(void)
{
	struct lexer lx;
	struct token t;
	start(&lx, "sphere Sphere #declare # local <= >= != < > { } rgbft");
	enum tok want[] = {TK_SPHERE, TK_IDENT, TK_DIR_DECLARE, TK_DIR_LOCAL, TK_LE, TK_GE, TK_NE,
	                   TK_LT, TK_GT, TK_LBRACE, TK_RBRACE, TK_RGBFT, TK_EOF};
	for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
		lex_next(&lx, &t);
		CHECK(t.kind == want[i]);
	}
	CHECK(lex_keyword("torus", 5) == TK_TORUS);
	CHECK(lex_keyword("torusx", 6) == TK_IDENT);
	CHECK_STR(tok_name(TK_LBRACE), "'{'");
	CHECK_STR(tok_name(TK_DIR_MACRO), "'#macro'");
	CHECK(tok_shape(TK_SPHERE) == SH_BLOCK);
	CHECK(tok_shape(TK_TRANSLATE) == SH_EXPR);
	finish();
	free(errs);
}

static void t_comments_and_locations(void)
{
	struct lexer lx;
	struct token t;
	start(&lx, "a // line\n/* outer /* inner */ still */ b\n\tc");
	lex_next(&lx, &t);
	CHECK(t.loc.line == 1 && t.loc.col == 1);
	lex_next(&lx, &t);
	CHECK(t.kind == TK_IDENT && t.len == 1 && t.text[0] == 'b');
	CHECK(t.loc.line == 2 && t.loc.col == 31);
	lex_next(&lx, &t);
	CHECK(t.loc.line == 3 && t.loc.col == 2);
	const struct token *pk = lex_peek(&lx);
	CHECK(pk->kind == TK_EOF);
	lex_next(&lx, &t);
	CHECK(t.kind == TK_EOF);
	CHECK(dg.errors == 0);
	finish();
	free(errs);
}

static void t_errors(void)
{
	struct lexer lx;
	struct token t;
	start(&lx, "@ \"open\n1e+ \"\\q\" /* never closed");
	lex_next(&lx, &t);
	CHECK(t.kind == TK_ERROR);
	lex_next(&lx, &t);
	CHECK(t.kind == TK_ERROR);
	lex_next(&lx, &t);
	CHECK(t.kind == TK_ERROR);
	lex_next(&lx, &t);
	CHECK(t.kind == TK_ERROR);
	lex_next(&lx, &t);
	CHECK(t.kind == TK_EOF);
	CHECK(dg.errors == 5);
	const char *e = finish();
	CHECK(strstr(e, "t.scn:1:1: error: unexpected character '@'") != NULL);
	CHECK(strstr(e, "t.scn:1:3: error: unterminated string") != NULL);
	CHECK(strstr(e, "t.scn:2:2: error: malformed number: exponent has no digits") != NULL);
	CHECK(strstr(e, "t.scn:2:6: error: unknown escape sequence '\\q'") != NULL);
	CHECK(strstr(e, "t.scn:2:10: error: unterminated comment") != NULL);
	free(errs);
}

int main(void)
{
	arena_init(&arena);
	RUN(t_numbers);
	RUN(t_strings);
	RUN(t_keywords_and_punct);
	RUN(t_comments_and_locations);
	RUN(t_errors);
	arena_free(&arena);
	srcfile_free_all();
	return test_done();
}
