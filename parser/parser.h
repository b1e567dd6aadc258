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

/* The body of macro def, which did not parse where it was defined (its
 * directives split blocks: `#if (M) merge { #else union { #end`), parsed
 * now with errors reported to diag: the body, or NULL after an error. */
/* parse_file, and no warning for macros whose bodies only parse when
 * called if quiet_macros (POV-Ray's own include files). */
struct node *parse_file_quiet(int file, struct diag *diag, struct arena *arena, int quiet_macros);
struct node *parse_macro_body(const struct node *def, struct diag *diag, struct arena *arena);

#endif
