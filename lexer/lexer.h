/* SPDX-License-Identifier: MIT */
/* lexer.h: one lexer per open file; tokens pulled on demand, one of lookahead. */
#ifndef ARVO_LEXER_H
#define ARVO_LEXER_H

#include <stdbool.h>
#include <stdio.h>

#include "../common/arena.h"
#include "../common/diag.h"
#include "token.h"

#define MAX_IDENT 1024 /* characters in an identifier */

struct lexer {
	const char *src;        /* start of the file's text */
	const char *p;          /* next unread character */
	const char *end;        /* one past the last character */
	const char *line_start; /* first character of the current line */
	int file;               /* file table index, for locations */
	int line;               /* current line, 1-based */
	struct diag *diag;      /* where lexical errors go */
	struct arena *arena;    /* holds unescaped strings */
	struct token ahead;     /* the lookahead token, when has_ahead */
	bool has_ahead;
	long max_string;        /* longest string literal accepted */
};

/* Starts lexing registered file `file`; strings are kept in `arena`. */
void lex_init(struct lexer *lx, int file, struct diag *diag, struct arena *arena);
/* Reads the next token into *t (TK_EOF at the end, forever). */
void lex_next(struct lexer *lx, struct token *t);
/* The next token, without consuming it. */
const struct token *lex_peek(struct lexer *lx);
/* Looks a word up in the keyword table; TK_IDENT if it is not reserved. */
enum tok lex_keyword(const char *s, int len);
/* --dump-tokens: one token per line, "line:col KIND text". */
void lex_dump(FILE *out, struct lexer *lx);

#endif
