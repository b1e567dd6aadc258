/* SPDX-License-Identifier: MIT */
/* parser.h: recursive descent from tokens to the AST. */
#ifndef ARVO_PARSER_H
#define ARVO_PARSER_H

#include "../common/diag.h"
#include "ast.h"

/* Parses registered file `file` into an N_LIST allocated in `arena`.
 * Errors go to diag (several per run); returns the tree even then, with the
 * bad parts left out, so callers check diag->errors. */
struct node *parse_file(int file, struct diag *diag, struct arena *arena);

#endif
