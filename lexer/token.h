/* SPDX-License-Identifier: MIT */
/* token.h: token kinds (from tokens.def) and the token record. */
#ifndef ARVO_TOKEN_H
#define ARVO_TOKEN_H

#include <stdbool.h>

#include "../common/srcloc.h"

enum tok {
	TK_EOF,
	TK_ERROR,  /* a lexical error already reported */
	TK_NUMBER,
	TK_STRING,
	TK_IDENT,
#define PUNCT(n, s) TK_##n,
#include "tokens.def"
	TK_DIR_FIRST_,
#define DIRECTIVE(n, s) TK_DIR_##n,
#include "tokens.def"
	TK_KW_FIRST_,
#define KEYWORD(n, s, shape) TK_##n,
#include "tokens.def"
	TK_COUNT_
};

/* What follows a keyword that starts a block item (see tokens.def). */
enum kw_shape { SH_NONE, SH_BLOCK, SH_EXPR, SH_FLAG, SH_LIST, SH_OPTEXPR, SH_WORD,
	SH_BLOCK_OR_EXPR, SH_SKIP, SH_PREFIX, SH_VALUE };

struct token {
	enum tok kind;
	const char *text;  /* view into the source */
	int len;           /* length of text */
	double num;        /* TK_NUMBER: its value */
	const char *str;   /* TK_STRING: unescaped contents (NUL-terminated) */
	int slen;          /* TK_STRING: length of str */
	struct srcloc loc; /* where the token starts */
};

/* Printable spelling of a kind: "'{'", "'#declare'", "'sphere'", "number". */
const char *tok_name(enum tok k);
/* The bare word of a keyword or directive ("sphere", "declare"), else NULL. */
const char *tok_word(enum tok k);
enum kw_shape tok_shape(enum tok k);
/* Is s one of POV-Ray 3.7's reserved words (povwords.c)? */
bool tok_is_pov_word(const char *s);
static inline int tok_is_keyword(enum tok k) { return k > TK_KW_FIRST_ && k < TK_COUNT_; }
static inline int tok_is_directive(enum tok k) { return k > TK_DIR_FIRST_ && k < TK_KW_FIRST_; }

#endif
