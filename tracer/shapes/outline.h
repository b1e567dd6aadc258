/* SPDX-License-Identifier: MIT */
/* outline.h: closed 2D outlines made of polynomial curve pieces, and the
 * solids built from them: prism and text (an outline extruded along an
 * axis), polygon (a flat outline), lathe (a profile revolved about y).
 *
 * A piece is P(s) = c0 + c1·s + c2·s² + c3·s³ for s ∈ [0,1] (lines,
 * TrueType's quadratics, cubics and POV-Ray's splines are all of this form),
 * so the intersections below solve polynomials of degree ≤ 3 (≤ 6 for the
 * lathe) exactly, with no flattening. The evaluator builds these structures
 * (eval/outlines.c, eval/font.c); outline_finish computes the bounds and the
 * fill side of every piece. docs/parametrisations.md has each primitive's
 * (u,v). */
#ifndef ARVO_OUTLINE_H
#define ARVO_OUTLINE_H

#include <stdbool.h>

/* One curve piece: x(s) = x[0] + x[1]s + x[2]s² + x[3]s³, y likewise. */
struct curve2 {
	double x[4], y[4];
	double p0[2], p1[2]; /* the end points exactly as given (shared by neighbours) */
	double lo[2], hi[2]; /* bounds of the piece over s ∈ [0,1] */
	signed char left;    /* +1: the filled side is left of the travel direction, −1: right */
};

/* A set of pieces forming closed contours (an unclosed lathe profile is
 * allowed). Filled: the points the pieces wind around (nonzero rule), or
 * that an odd number of pieces surround (even-odd). */
struct outline {
	struct curve2 *seg;
	int n;
	bool nonzero;        /* TrueType's rule; POV-Ray's prism/polygon/lathe use even-odd */
	int first;           /* index of seg[0] among all pieces of the solid (u layout) */
	double lo[2], hi[2]; /* bounds of all pieces */
};

/* prism and text: outlines in the (a,b) plane swept along h ∈ [h0,h1]. In
 * a linear sweep every cross-section is the outline; in a conic sweep the
 * cross-section at height h is the outline scaled by h (POV-Ray's cone from
 * the origin). Text keeps one outline per glyph so that rays skip glyphs by
 * their boxes. */
struct extrusion {
	struct outline *part;
	int nparts;
	int nseg;            /* pieces over all parts */
	double h0, h1;       /* h0 < h1 */
	bool conic, open;    /* conic_sweep; open: no caps */
	bool zaxis;          /* text: object (x,y,z) = (a,−b,h); prism: (x,y,z) = (a,h,b) */
	double lo[2], hi[2]; /* outline bounds over all parts (unscaled) */
};

/* polygon: a flat outline in the plane through o spanned by e1, e2
 * (n = e1 × e2). */
struct flat_outline {
	struct outline ol;
	double o[3], e1[3], e2[3], n[3];
};

/* lathe: a profile in the (r,y) plane (r = x, the distance from the y
 * axis) revolved about y. */
struct revolution {
	struct outline ol;
};

/* sor: r² = A·y³ + B·y² + C·y + D on [y0[i], y1[i]] for each piece i,
 * revolved about y; caps at both ends unless open. */
struct sor_piece {
	double A, B, C, D, y0, y1, rmax;
};
struct sor_shape {
	struct sor_piece *p;
	int n;
	double ylo, yhi, rmax; /* height range, largest radius */
	double rbase, rcap;    /* radius at ylo and at yhi */
};

/* A piece from its end points and power-basis coefficients (p0 = c0). */
struct curve2 curve2_make(const double cx[4], const double cy[4], const double p0[2],
                          const double p1[2]);
/* Computes bounds and fill sides; call once the pieces are in place. */
void outline_finish(struct outline *ol);
/* Is (x,y) inside the filled outline? */
bool outline_inside(const struct outline *ol, double x, double y);
/* Real roots in [lo,hi] of c[0] + c[1]x + … + c[n]xⁿ (n ≤ 6), ascending;
 * roots of even multiplicity (touching) may be missed. */
int outline_roots(const double *c, int n, double lo, double hi, double *out);
/* Position and derivative of piece c at s. */
void curve2_eval(const struct curve2 *c, double s, double *x, double *y, double *dx, double *dy);
/* Area of the filled outline inside [x0,x1]×[y0,y1]: exact when no piece
 * crosses the rectangle, else sampled on a 16×16 grid. */
double outline_rect_area(const struct outline *ol, double x0, double x1, double y0, double y1);

#endif
