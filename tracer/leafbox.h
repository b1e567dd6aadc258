/* SPDX-License-Identifier: MIT */
/* leafbox.h: the boxes of a scene's few bounded leaves, tested against one
 * ray two or four at a time (bvh.c traces scenes of up to LEAFBOX_MAX leaves this
 * way, without Embree; docs/design.md §5). */
#ifndef ARVO_LEAFBOX_H
#define ARVO_LEAFBOX_H

#include <stdbool.h>

#include "../common/vec.h"
#include "shape.h"

#define LEAFBOX_MAX 8

/* Boxes as rows per axis (lo[axis][lane]), so that two or four lanes are
 * one vector operation. A lane holds leaf i at lane i; with 5 to 7 leaves
 * (split) lanes 0-2 hold leaves 0-2, lane 3 the box around leaves 3 to
 * n-1, and lanes 4 on those leaves: a ray that misses lane 3 misses them
 * all, and their lanes are not tested. */
struct leafbox {
	int n;
	bool wide;  /* the CPU runs AVX: four boxes per operation */
	bool split; /* lane 3 bounds leaves 3 to n-1, which sit one lane on */
	double lo[3][LEAFBOX_MAX];
	double hi[3][LEAFBOX_MAX];
};

/* Sets the n <= LEAFBOX_MAX boxes of *lb to b[0..n). */
void leafbox_set(struct leafbox *lb, int n, const struct bbox *b);

/* The leaves whose boxes ray r meets somewhere over [tmin, tmax], as bit i
 * for leaf i, and where it enters each (at[i], no later than the true
 * entry). Never leaves out a box the exact ray meets, except a ray lying in
 * the plane of a face (no motion along that axis): give boxes grown by a
 * margin beyond what they bound, so that such a ray misses what they hold.
 * Inline, so that the caller calls the version for its CPU straight away
 * (leafbox_wide with AVX, else leafbox_narrow: the same answers). */
unsigned leafbox_wide(const struct leafbox *lb, const struct ray *r, double tmin, double tmax,
                      double at[LEAFBOX_MAX]);
unsigned leafbox_narrow(const struct leafbox *lb, const struct ray *r, double tmin, double tmax,
                        double at[LEAFBOX_MAX]);
static inline unsigned leafbox_hits(const struct leafbox *lb, const struct ray *r, double tmin, double tmax,
                                    double at[LEAFBOX_MAX])
{
	return lb->wide ? leafbox_wide(lb, r, tmin, tmax, at) : leafbox_narrow(lb, r, tmin, tmax, at);
}

#endif
