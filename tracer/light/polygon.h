/* SPDX-License-Identifier: MIT */
/* polygon.h: plane polygons for the illumination maps' footprint deposits
 * (illum_deposit_poly): clipping to axis-aligned slabs, exact moments by
 * Green's theorem, and splitting self-intersecting polygons into simple loops.
 *
 * A polygon is a closed sequence of corners p[0..n), the edge p[n-1]→p[0]
 * implied. Nothing here assumes convexity or a winding: the moments of a
 * closed polygon are integrals weighted by its WINDING NUMBER (+1 inside a
 * counter-clockwise simple polygon, −1 inside a clockwise one), and clipping
 * keeps that meaning, so non-convex simple polygons clip and integrate
 * exactly. Pure functions of their arguments, no allocation except in
 * poly_split. */
#ifndef ARVO_POLYGON_H
#define ARVO_POLYGON_H

#include <stdbool.h>
#include <stddef.h>

struct pt2 {
	double x, y;
};

/* The integrals of 1, x, y and x·y over a polygon, weighted by its winding
 * number, with x and y measured from an origin the caller chooses. */
struct moments {
	double a;  /* ∫ 1: the signed area */
	double x;  /* ∫ x */
	double y;  /* ∫ y */
	double xy; /* ∫ x·y */
};

/* Signed area of p[0..n) (> 0 counter-clockwise). */
double poly_area(const struct pt2 *p, int n);

/* The moments of p[0..n) (n ≥ 1) about origin o. Computed about p[0] and
 * then shifted, so a polygon far smaller than its distance from o keeps its
 * relative precision. Degenerate input (n < 3, collinear) gives ~0. */
struct moments poly_moments(const struct pt2 *p, int n, struct pt2 o);

/* Sutherland–Hodgman: the part of p[0..n) with lo ≤ coordinate ≤ hi
 * (axis 0: x, 1: y; an infinite bound leaves that side open) into out,
 * which needs room for 4n points; tmp needs 2n. Returns the corner count
 * (< 3: nothing left). Points exactly on a bound count as inside, and a
 * crossing point gets the bound exactly. For a non-convex input the result
 * may have zero-width bridges along the bound; they add nothing to the
 * moments, which stay exact. */
int poly_clip_slab(const struct pt2 *p, int n, int axis, double lo, double hi, struct pt2 *out,
                   struct pt2 *tmp);

/* poly_clip_slab where the least and greatest of the corners' coordinates
 * on the axis are known (mn, mx): the same result, without looking for
 * them. */
int poly_clip_range(const struct pt2 *p, int n, int axis, double lo, double hi, double mn, double mx,
                    struct pt2 *out, struct pt2 *tmp);

/* The first pair of non-adjacent edges of p[0..n) that cross properly (each
 * edge's ends strictly on opposite sides of the other's line): edges a < b
 * (edge k runs p[k]→p[k+1]) and the crossing point. False for a simple
 * polygon; touching or collinear overlaps do not count. */
bool poly_crossing(const struct pt2 *p, int n, int *a, int *b, struct pt2 *x);

/* The simple loops a polygon splits into: loop k is pt[start[k] ..
 * start[k] + len[k]). Storage grows as needed and is kept between calls. */
struct loops {
	struct pt2 *pt;  /* corners of every loop (and of split-off parents) */
	int *start;      /* first corner of loop k in pt */
	int *len;        /* corner count of loop k (≥ 3) */
	int n;           /* loops */
	int npt;         /* corners used in pt */
	int cap_pt;      /* corners allocated in pt */
	int cap_loop;    /* entries allocated in start and len */
};

#define POLY_SPLIT_MAX 64 /* corners above which poly_split does not look for crossings */

/* Splits p[0..n) (n ≥ 3) at its proper self-crossings, one at a time, into
 * loops without any: a crossing of edges a < b at x gives the loops
 * x, p[a+1..b] and x, p[b+1..n), p[0..a], each shorter than its parent, so
 * the split ends (at most n − 3 splits). A simple polygon stays one loop; a
 * "bow-tie" quadrilateral becomes its two triangles. The search costs
 * O(n²) per loop, so a polygon of more than POLY_SPLIT_MAX corners is left
 * whole. */
void poly_split(struct loops *l, const struct pt2 *p, int n);
/* Bytes held by l. */
size_t loops_bytes(const struct loops *l);
void loops_free(struct loops *l);

#endif
