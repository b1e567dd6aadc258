/* SPDX-License-Identifier: MIT */
/* torus.c: torus { R, r }: major radius R in the xz-plane about the y axis,
 * minor (tube) radius r, centred at the origin.
 *
 * Parametrisation (object frame), φ = 2πu around y, θ = 2πv around the tube,
 * (u,v) ∈ [0,1]², both periodic:
 *
 *     T(u,v) = ((R + r cosθ) cosφ, r sinθ, −(R + r cosθ) sinφ)
 *     ∂T/∂u = 2π(R + r cosθ)·(−sinφ, 0, −cosφ)
 *     ∂T/∂v = 2πr·(−sinθ cosφ, cosθ, sinθ sinφ)
 *     ∂T/∂u × ∂T/∂v = 4π²r(R + r cosθ)·n̂   (outward)
 *
 * u = 0 is the +x half-plane, growing towards −z; v = 0 the outer equator
 * (θ = 0), v = ¼ the top. The Jacobian never vanishes when R > r; for a
 * spindle torus (r ≥ R) it vanishes where cosθ = −R/r, and cell areas split
 * there. Cell area: 2πr(u1−u0)·∫|R + r cosθ| dθ under similarities,
 * integrated numerically otherwise.
 *
 * Intersection solves the quartic in the distance s along the unit local
 * direction from the point of the ray nearest the centre (which removes the
 * cubic term and keeps the coefficients O(1) after scaling by R + r). Roots
 * are isolated by recursion on the derivatives (each interval between
 * consecutive critical points is monotone) and refined by safeguarded
 * Newton–bisection to full precision, so grazing and distant rays stay
 * accurate and no root is lost to a bad closed-form branch. */
#include <math.h>

#include "prim.h"

#define T_R(o) ((o)->g.torus.major)
#define T_r(o) ((o)->g.torus.minor)

/* ==== polynomial roots =================================================== */

/* c[0] + c[1]x + … + c[n]xⁿ by Horner, with its derivative in *d. */
static double peval(const double *c, int n, double x, double *d)
{
	double p = c[n], dp = 0;
	for (int i = n - 1; i >= 0; i--) {
		dp = dp * x + p;
		p = p * x + c[i];
	}
	if (d)
		*d = dp;
	return p;
}

/* The root of c in [lo,hi], where c(lo) and c(hi) have opposite signs and c
 * is monotone: Newton steps kept inside a shrinking bracket, bisection when
 * a step would leave it. lo and hi are never NaN (the ends of to_first's
 * interval or roots refined inside it), so d_max is fmax here, inline: a
 * call in this loop saved and restored the bracket around each step. */
static double refine(const double *c, int n, double lo, double hi, double flo)
{
	double x = 0.5 * (lo + hi);
	for (int it = 0; it < 200; it++) {
		double d, f = peval(c, n, x, &d);
		if (f == 0)
			return x;
		if ((f < 0) == (flo < 0))
			lo = x;
		else
			hi = x;
		double nx = d != 0 ? x - f / d : lo;
		if (!(nx > lo && nx < hi))
			nx = 0.5 * (lo + hi);
		if (nx == x || hi - lo <= 4e-16 * d_max(fabs(lo), fabs(hi)))
			return nx;
		x = nx;
	}
	return x;
}

/* The real roots of a polynomial in [lo,hi], ascending, one at a time, so
 * that a caller that wants the first root in some range stops there. Each
 * level n holds a polynomial of degree n, level n − 1 its derivative: the
 * roots of level n − 1 cut [lo,hi] into monotone intervals, and each
 * interval whose ends' values differ in sign holds one root, refined there.
 * An end where the value is 0 is itself a root (once). A root needs the
 * derivative's roots up to the end of its interval only, so the work past
 * the first root a caller takes is not done; the roots and their order are
 * what working them all out first gives. */
struct roots {
	double c[5];  /* the coefficients */
	double a, fa; /* the next interval's left end and the value there */
	double hi;
	double last;  /* the root given last (with k > 0) */
	int k;        /* roots given */
	int phase;    /* 0: intervals left; 1: hi's own zero left; 2: done */
};

/* Sets up levels 1 to n of g for c (degree n) over [lo,hi]. */
static void roots_init(struct roots *g, const double *c, int n, double lo, double hi)
{
	for (int i = 0; i <= n; i++)
		g[n].c[i] = c[i];
	for (int m = n; m >= 1; m--) {
		struct roots *l = &g[m];
		if (m > 1)
			for (int i = 1; i <= m; i++)
				g[m - 1].c[i - 1] = i * l->c[i];
		l->a = lo, l->hi = hi, l->k = 0, l->phase = 0, l->last = 0;
		l->fa = m > 1 ? peval(l->c, m, lo, NULL) : 0;
	}
}

static bool root_give(struct roots *l, double x, double *out)
{
	l->k++, l->last = x, *out = x;
	return true;
}

/* The next root of level n of g into *x; false when there are no more. */
static bool root_next(struct roots *g, int n, double *x)
{
	struct roots *l = &g[n];
	if (n == 1) {
		if (l->phase)
			return false;
		l->phase = 2;
		double r = l->c[1] != 0 ? -l->c[0] / l->c[1] : NAN;
		*x = r;
		return r >= l->a && r <= l->hi;
	}
	while (l->phase == 0) {
		double b;
		if (!root_next(g, n - 1, &b)) {
			b = l->hi;
			l->phase = 1;
		}
		double a = l->a, fa = l->fa, fb = peval(l->c, n, b, NULL);
		l->a = b, l->fa = fb;
		if (fa == 0) {
			if (l->k == 0 || l->last != a)
				return root_give(l, a, x);
		} else if ((fa < 0) != (fb < 0) && fb != 0) {
			return root_give(l, refine(l->c, n, a, b, fa), x);
		}
	}
	if (l->phase == 1) {
		l->phase = 2; /* l->fa is the value at hi */
		if (l->fa == 0 && (l->k == 0 || l->last != l->hi))
			return root_give(l, l->hi, x);
	}
	return false;
}

/* ==== parametrisation ===================================================== */

static bool to_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	double R = T_R(o), r = T_r(o), phi = 2 * M_PI * u, th = 2 * M_PI * v;
	if (!(R > 0) || !(r > 0))
		return false;
	double sp = sin(phi), cp = cos(phi), st = sin(th), ct = cos(th), rho = R + r * ct;
	if (p)
		*p = v3(rho * cp, r * st, -rho * sp);
	if (dpdu)
		*dpdu = v3(-2 * M_PI * rho * sp, 0, -2 * M_PI * rho * cp);
	if (dpdv)
		*dpdv = v3(-2 * M_PI * r * st * cp, 2 * M_PI * r * ct, 2 * M_PI * r * st * sp);
	return true;
}

/* ==== intersection ======================================================= */

/* A quartic's least value over an interval is at least the least of its
 * five Bernstein coefficients there (they are the corners of a polygon
 * whose hull holds the curve). b: those coefficients; halves the interval
 * (de Casteljau) up to depth times where that bound is too low. An end's
 * own coefficient is its value, so a low end ends the search. */
static bool bern_above(const double *b, double floor, int depth)
{
	if (!(b[0] > floor) || !(b[4] > floor))
		return false;
	if (b[1] > floor && b[2] > floor && b[3] > floor)
		return true;
	if (depth == 0)
		return false;
	double c0 = 0.5 * (b[0] + b[1]), c1 = 0.5 * (b[1] + b[2]), c2 = 0.5 * (b[2] + b[3]),
	       c3 = 0.5 * (b[3] + b[4]);
	double d0 = 0.5 * (c0 + c1), d1 = 0.5 * (c1 + c2), d2 = 0.5 * (c2 + c3);
	double e0 = 0.5 * (d0 + d1), e1 = 0.5 * (d1 + d2), f = 0.5 * (e0 + e1);
	double l[5] = {b[0], c0, d0, e0, f}, r[5] = {f, e1, d2, c3, b[4]};
	return bern_above(l, floor, depth - 1) && bern_above(r, floor, depth - 1);
}

/* Whether the quartic c (c[4] = 1, c[3] = 0, |c[i]| <= 8) is provably above
 * zero all over [a,b] ⊂ [-1.01, 1.01], so that root_next would find no root
 * there: its Bernstein coefficients, halved twice at most, all past 1e-9.
 * Rounding moves those coefficients by less than 1e-12 here (Taylor
 * coefficients below 30, scaled by (b − a)^k <= 17), and each value
 * Horner's rule gives root_next by less than 1e-13, so every value it
 * would look at is positive, and the answer is the one root_next gives.
 * Most of the torus's rays are settled so: those that pass it by, and
 * those spawned on it that leave and do not come back, whose value
 * starts at the offset times the gradient (1e-8 and up). docs/design.md,
 * "The torus". */
static bool quartic_above(const double *c, double a, double b)
{
	double t0 = c[0], t1 = c[1], t2 = c[2], t3 = 0, t4 = 1;
	/* the Taylor coefficients at a (three synthetic divisions by x − a) */
	for (int k = 0; k < 4; k++) {
		t3 += a * t4;
		if (k < 3)
			t2 += a * t3;
		if (k < 2)
			t1 += a * t2;
		if (k < 1)
			t0 += a * t1;
	}
	double h = b - a, m1 = t1 * h, m2 = t2 * h * h, m3 = t3 * h * h * h, m4 = t4 * h * h * h * h;
	double bc[5] = {t0, t0 + m1 / 4, t0 + m1 / 2 + m2 / 6, t0 + 0.75 * m1 + m2 / 2 + m3 / 4,
	                t0 + m1 + m2 + m3 + m4};
	return bern_above(bc, 1e-9, 2);
}

/* Sets g up for the distances s (in units of R + r, from the ray's point
 * nearest the centre along the unit direction) where the ray meets the
 * torus, within [s0,s1] (root_next(g, 4, …)); false when there are none
 * (quartic_above). */
static bool quartic_hits(double Rs, double rs, struct vec3 q, struct vec3 d, double s0, double s1,
                         struct roots *g)
{
	double c0 = v_dot(q, q), e = c0 + Rs * Rs - rs * rs, R4 = 4 * Rs * Rs;
	double a2 = d.x * d.x + d.z * d.z, a1 = 2 * (q.x * d.x + q.z * d.z), a0 = q.x * q.x + q.z * q.z;
	double c[5] = {e * e - R4 * a0, -R4 * a1, 2 * e - R4 * a2, 0, 1};
	if (quartic_above(c, s0, s1))
		return false;
	roots_init(g, c, 4, s0, s1);
	return true;
}

/* The unit outward normal at p (on the surface). */
static struct vec3 to_normal(double R, struct vec3 p)
{
	double rho = sqrt(p.x * p.x + p.z * p.z);
	if (!(rho > 0))
		return v3(0, p.y >= 0 ? 1 : -1, 0);
	return v_norm(v3(p.x - R * p.x / rho, p.y, p.z - R * p.z / rho));
}

/* Works in units of R + r from the ray's point nearest the centre, within
 * the bounding sphere; the first root with t in range is the hit, at t and
 * local point p. */
static bool to_first(const struct object *o, const struct ray *r, double tmin, double tmax, double *t,
                     struct vec3 *p)
{
	double R = T_R(o), rr = T_r(o), L = v_len(r->d), sc = R + rr;
	if (!(R > 0) || !(rr > 0) || !(L > 0))
		return false;
	struct vec3 d = v_scale(r->d, 1 / L);
	double tc = -v_dot(r->o, d); /* unit-speed distance to the nearest point */
	struct vec3 q = v_madd(r->o, d, tc);
	/* a second step removes what cancellation left of q·d for distant
	 * origins: the quartic below assumes q·d = 0 exactly */
	double tc2 = -v_dot(q, d);
	q = v_madd(q, d, tc2);
	tc += tc2;
	struct vec3 qs = v_scale(q, 1 / sc);
	double reach = 1 + 1e-9, half = reach * reach - v_dot(qs, qs);
	if (!(half > 0))
		return false;
	half = sqrt(half);
	double s0 = fmax(-half, (tmin * L - tc) / sc), s1 = fmin(half, (tmax * L - tc) / sc);
	if (!(s1 >= s0))
		return false;
	/* a ray that stays above or below the slab |y| <= r over [s0, s1] has
	 * no root there: no quartic to solve (its interval is left as it is) */
	double m = reach * rr / sc, y0 = qs.y + d.y * s0, y1 = qs.y + d.y * s1;
	if ((y0 > m && y1 > m) || (y0 < -m && y1 < -m))
		return false;
	struct roots g[5];
	double s;
	if (!quartic_hits(R / sc, rr / sc, qs, d, s0, s1, g))
		return false;
	while (root_next(g, 4, &s)) {
		*t = (tc + s * sc) / L;
		if (!(*t > tmin && *t < tmax))
			continue;
		*p = v_madd(q, d, s * sc);
		return true;
	}
	return false;
}

bool to_hit(const struct object *o, const struct ray *r, double tmin, double tmax, struct local_hit *lh)
{
	double t;
	struct vec3 p;
	if (!to_first(o, r, tmin, tmax, &t, &p))
		return false;
	lh->t = t;
	lh->p = p;
	lh->n = to_normal(T_R(o), p);
	return true;
}

static bool to_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	double R = T_R(o);
	if (!to_hit(o, r, tmin, tmax, lh))
		return false;
	struct vec3 p = lh->p;
	lh->u = prim_turns(-p.z, p.x);
	lh->v = prim_turns(p.y, sqrt(p.x * p.x + p.z * p.z) - R);
	return to_uv_point(o, lh->u, lh->v, NULL, &lh->dpdu, &lh->dpdv);
}

/* to_first: R > 0 and r > 0 there, so to_intersect's to_uv_point holds. */
static bool to_occluded(const struct object *o, const struct ray *r, double tmin, double tmax)
{
	double t;
	struct vec3 p;
	return to_first(o, r, tmin, tmax, &t, &p);
}

static bool to_inside(const struct object *o, struct vec3 p)
{
	double k = sqrt(p.x * p.x + p.z * p.z) - T_R(o);
	return k * k + p.y * p.y < T_r(o) * T_r(o);
}

static struct bbox to_bounds(const struct object *o)
{
	double a = fabs(T_R(o)) + fabs(T_r(o)), b = fabs(T_r(o));
	return (struct bbox){v3(-a, -b, -a), v3(a, b, a)};
}

static struct uv_range to_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, true, true};
}

/* ==== area ================================================================ */

/* ∫ (R + r cosθ) dθ over [a,b] (signed). */
static double tube_integral(double R, double r, double a, double b)
{
	return R * (b - a) + 2 * r * cos(0.5 * (a + b)) * sin(0.5 * (b - a));
}

/* Splits [v0,v1] where R + r cos 2πv changes sign (spindle tori only) and
 * sums each piece's area: closed form under similarities, else numeric. */
static double to_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	double R = T_R(o), r = T_r(o), s2;
	if (!(R > 0) || !(r > 0))
		return 0;
	bool sim = shape_similarity(o, &s2);
	double cuts[64];
	int nc = 0;
	cuts[nc++] = v0;
	if (r > R) {
		/* zeros at k ± ta, ta ∈ (¼,½), so this loop emits them ascending */
		double ta = acos(-R / r) / (2 * M_PI);
		for (double k = floor(v0) - 1; k <= v1 + 1 && nc < 60; k += 1)
			for (int sgn = -1; sgn <= 1; sgn += 2) {
				double z = k + sgn * ta;
				if (z > v0 && z < v1)
					cuts[nc++] = z;
			}
	}
	cuts[nc++] = v1;
	double sum = 0;
	for (int i = 0; i + 1 < nc; i++) {
		double a = cuts[i], b = cuts[i + 1];
		if (sim)
			sum += s2 * 2 * M_PI * r * (u1 - u0) *
			       fabs(tube_integral(R, r, 2 * M_PI * a, 2 * M_PI * b));
		else
			sum += shape_integrate_area(o, u0, u1, a, b);
	}
	return sum;
}

static void to_dump(const struct object *o, FILE *out)
{
	fprintf(out, "major %.6g minor %.6g", o->g.torus.major, o->g.torus.minor);
}

const struct prim_ops shape_torus_ops = {
	to_intersect, to_inside, to_bounds, to_uv_point, to_uv_range, to_cell_area, to_dump, to_occluded,
};
