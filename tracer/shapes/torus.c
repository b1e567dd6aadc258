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

/* Real roots of the degree-n polynomial c in [lo,hi], ascending. */
static int roots_in(const double *c, int n, double lo, double hi, double *out)
{
	if (n == 1) {
		double x = c[1] != 0 ? -c[0] / c[1] : NAN;
		out[0] = x;
		return x >= lo && x <= hi;
	}
	double dc[4], b[6];
	for (int i = 1; i <= n; i++)
		dc[i - 1] = i * c[i];
	int m = roots_in(dc, n - 1, lo, hi, b + 1), k = 0;
	b[0] = lo;
	b[m + 1] = hi;
	for (int i = 0; i <= m; i++) {
		double f0 = peval(c, n, b[i], NULL), f1 = peval(c, n, b[i + 1], NULL);
		if (f0 == 0) {
			if (k == 0 || out[k - 1] != b[i])
				out[k++] = b[i];
		} else if ((f0 < 0) != (f1 < 0) && f1 != 0) {
			out[k++] = refine(c, n, b[i], b[i + 1], f0);
		}
	}
	if (peval(c, n, hi, NULL) == 0 && (k == 0 || out[k - 1] != hi))
		out[k++] = hi;
	return k;
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

/* Distances s (in units of R + r, from the ray's point nearest the centre
 * along the unit direction) where the ray meets the torus, within [s0,s1]. */
static int quartic_hits(double Rs, double rs, struct vec3 q, struct vec3 d, double s0, double s1,
                        double *s)
{
	double c0 = v_dot(q, q), e = c0 + Rs * Rs - rs * rs, R4 = 4 * Rs * Rs;
	double a2 = d.x * d.x + d.z * d.z, a1 = 2 * (q.x * d.x + q.z * d.z), a0 = q.x * q.x + q.z * q.z;
	double c[5] = {e * e - R4 * a0, -R4 * a1, 2 * e - R4 * a2, 0, 1};
	return roots_in(c, 4, s0, s1, s);
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
	double s[4];
	int n = quartic_hits(R / sc, rr / sc, qs, d, s0, s1, s);
	for (int i = 0; i < n; i++) {
		*t = (tc + s[i] * sc) / L;
		if (!(*t > tmin && *t < tmax))
			continue;
		*p = v_madd(q, d, s[i] * sc);
		return true;
	}
	return false;
}

static bool to_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	double R = T_R(o), t;
	struct vec3 p;
	if (!to_first(o, r, tmin, tmax, &t, &p))
		return false;
	lh->t = t;
	lh->p = p;
	lh->n = to_normal(R, p);
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
