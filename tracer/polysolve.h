/* SPDX-License-Identifier: MIT */
/* polysolve.h: real roots of polynomials of degree ≤ POLY_MAX_DEGREE by
 * Sturm sequences (docs/design.md §5, "Algebraic surfaces"). Used by the
 * polynomial surfaces (poly, quartic, cubic, quadric) and by the blob.
 *
 * Coefficients are in ascending powers: c[0] + c[1]·x + … + c[n]·xⁿ. */
#ifndef ARVO_POLYSOLVE_H
#define ARVO_POLYSOLVE_H

#define POLY_MAX_DEGREE 8

/* The distinct real roots of c in the open interval (lo, hi), ascending,
 * written to roots (room for n). lo and hi may be ±INFINITY. Leading
 * coefficients that are negligible next to the others (relative 1e-14) are
 * dropped, so a ray along which a quartic degenerates to a cubic still finds
 * the cubic's roots. Simple roots are refined to full double precision by
 * bracketed Newton–bisection; a root of even multiplicity (a tangent ray),
 * where the polynomial does not change sign, is located by the Sturm count
 * alone, to about √ε relative. Returns the number of roots (0 when c is the
 * zero polynomial, or n exceeds POLY_MAX_DEGREE). */
int poly_roots(const double *c, int n, double lo, double hi, double *roots);

/* c(x) by Horner; the derivative in *d when d is not NULL. */
double poly_eval(const double *c, int n, double x, double *d);

/* The root of c in [lo,hi], where c(lo) has the sign of flo and c(hi) the
 * other: Newton steps inside a shrinking bracket, bisection when a step
 * would leave it; to full double precision. */
double poly_refine(const double *c, int n, double lo, double hi, double flo);

#endif
