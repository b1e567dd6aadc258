/* SPDX-License-Identifier: MIT */
/* token.c: names and shapes of tokens, generated from tokens.def. */
#include "token.h"

#include <stddef.h>

static const char *const names[TK_COUNT_] = {
	[TK_EOF] = "end of file", [TK_ERROR] = "invalid token", [TK_NUMBER] = "number",
	[TK_STRING] = "string", [TK_IDENT] = "identifier",
#define PUNCT(n, s) [TK_##n] = "'" s "'",
#include "tokens.def"
#define DIRECTIVE(n, s) [TK_DIR_##n] = "'#" s "'",
#include "tokens.def"
#define KEYWORD(n, s, shape) [TK_##n] = "'" s "'",
#include "tokens.def"
};

static const char *const words[TK_COUNT_] = {
#define DIRECTIVE(n, s) [TK_DIR_##n] = s,
#include "tokens.def"
#define KEYWORD(n, s, shape) [TK_##n] = s,
#include "tokens.def"
};

static const unsigned char shapes[TK_COUNT_] = {
#define KEYWORD(n, s, shape) [TK_##n] = SH_##shape,
#include "tokens.def"
};

const char *tok_name(enum tok k) { return k < TK_COUNT_ && names[k] ? names[k] : "?"; }
const char *tok_word(enum tok k) { return k < TK_COUNT_ ? words[k] : NULL; }
enum kw_shape tok_shape(enum tok k) { return k < TK_COUNT_ ? (enum kw_shape)shapes[k] : SH_NONE; }
