/* SPDX-License-Identifier: MIT */
/* diag.c: diagnostics with source line and caret (after chibicc's verror_at). */
#include "diag.h"

#include <stdarg.h>
#include <string.h>

void diag_init(struct diag *d, FILE *out)
{
	memset(d, 0, sizeof *d);
	d->out = out;
	d->max_errors = 20;
}

/* Prints the line of f that holds loc, then a caret under its column. */
static void quote_line(FILE *out, const struct srcfile *f, struct srcloc loc)
{
	const char *p = f->text, *end = f->text + f->len;
	for (int l = 1; l < loc.line && p < end; p++)
		if (*p == '\n')
			l++;
	const char *e = p;
	while (e < end && *e != '\n' && *e != '\r')
		e++;
	fprintf(out, "%.*s\n", (int)(e - p), p);
	for (int c = 1; c < loc.col && p + c - 1 < e; c++)
		fputc(p[c - 1] == '\t' ? '\t' : ' ', out);
	fputs("^\n", out);
}

/* Reports one message; the va_list form behind diag_report and diag_fail. */
__attribute__((format(printf, 4, 0)))
static void report(struct diag *d, enum diag_kind kind, struct srcloc loc, const char *fmt, va_list ap)
{
	static const char *const names[] = {"error", "warning", "note"};
	if (kind != DIAG_NOTE)
		vsnprintf(d->last, sizeof d->last, fmt, ap);
	if (kind == DIAG_ERROR)
		d->errors++;
	else if (kind == DIAG_WARNING)
		d->warnings++;
	if (kind == DIAG_ERROR && d->max_errors > 0 && d->errors > d->max_errors) {
		if (d->errors == d->max_errors + 1 && d->out)
			fprintf(d->out, "arvo: too many errors; stopping here\n");
		return;
	}
	if (!d->out)
		return;
	const struct srcfile *f = srcfile_get(loc.file);
	if (f)
		fprintf(d->out, "%s:%d:%d: %s: ", f->name, loc.line, loc.col, names[kind]);
	else
		fprintf(d->out, "arvo: %s: ", names[kind]);
	fputs(kind == DIAG_NOTE ? "" : d->last, d->out);
	if (kind == DIAG_NOTE)
		vfprintf(d->out, fmt, ap);
	fputc('\n', d->out);
	if (f && loc.line > 0)
		quote_line(d->out, f, loc);
}

void diag_report(struct diag *d, enum diag_kind kind, struct srcloc loc, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	report(d, kind, loc, fmt, ap);
	va_end(ap);
}

int diag_fail(struct diag *d, int status, struct srcloc loc, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	report(d, DIAG_ERROR, loc, fmt, ap);
	va_end(ap);
	return status;
}
