/* SPDX-License-Identifier: MIT */
/* tools.h: the subcommands that work on finished images (docs/golden.md,
 * man/arvo.1): `arvo compare` and `arvo merge`. Each takes the arguments
 * after the program name (argv[0] is the subcommand), prints its report and
 * errors itself, and returns the exit status. */
#ifndef ARVO_TOOLS_H
#define ARVO_TOOLS_H

#include "../tracer/output/framebuffer.h"

/* How `arvo compare` decides: the metric, the tolerance and the share of
 * pixels allowed to differ. */
enum cmp_metric { CMP_MAX, CMP_MEAN, CMP_RMSE, CMP_PSNR, CMP_REL };

/* The figures of one layer (or of every channel): differences d = |a - b|
 * (0 where a and b are equal, both infinite the same way, or both NaN). */
struct cmp_figures {
	double mean, rmse, max; /* of d over every value */
	double psnr;            /* 20·log10(1 / rmse), +inf when rmse is 0 (idiff's) */
	double rel;             /* the largest d / max(|a|, |b|) */
	long over;              /* pixels with some value over the tolerance */
	long pixels;            /* pixels compared */
	int max_x, max_y;       /* where max is (in the display window) */
	const char *max_ch;     /* and in which channel */
};

/* Compares the channels of a whose names pass keep (NULL: all) against the
 * same channels of b (same size): fills *f. A value is over the tolerance
 * when d > tol (CMP_REL: when d / max(|a|, |b|) > tol). */
void cmp_layer(const struct framebuffer *a, const struct framebuffer *b, const char *layer,
               enum cmp_metric m, double tol, struct cmp_figures *f);
/* Does a layer with figures f match under (m, tol, failpercent)? */
int cmp_match(const struct cmp_figures *f, enum cmp_metric m, double tol, double failpercent);

int tool_compare(int argc, char **argv);
int tool_merge(int argc, char **argv);

#endif
