/* SPDX-License-Identifier: MIT */
/* lathe.c: lathe { [spline] n, <r,y>… }: a profile in the (r,y) plane,
 * pieces of degree ≤ 3 (outline.h), revolved about the y axis. Inside: the
 * points whose (distance from y, y) lies inside the profile (even-odd).
 *
 * Parametrisation (object frame), φ = 2πu, N pieces; piece k = ⌊vN⌋,
 * f = vN − k, s = f (or 1 − f on pieces whose filled side is on their
 * right, so that the cross product below is outward):
 *
 *     (r, y) = profile_k(s),  e(φ) = (cosφ, 0, −sinφ)
 *     T(u,v) = r·e(φ) + y·ŷ
 *     ∂T/∂u = 2πr·(−sinφ, 0, −cosφ),  ∂T/∂v = ±N·(r′·e(φ) + y′·ŷ)
 *     ∂T/∂u × ∂T/∂v = ±2πNr·(y′·e(φ) − r′·ŷ)
 *
 * u wraps (u = 0 is the +x half-plane, growing towards −z, as the torus);
 * the Jacobian vanishes where the profile meets the axis (r = 0).
 *
 * Intersection: with t = (y(s) − Oy)/Dy the ray meets the surface where
 * (Ox·Dy + (y(s) − Oy)·Dx)² + (Oz·Dy + (y(s) − Oy)·Dz)² = Dy²·r(s)², a
 * polynomial of degree ≤ 6 in s solved on [0,1] (outline.c). A ray
 * perpendicular to the axis solves y(s) = Oy and then a quadratic in t. */
#include "outline.h"
#include "prim.h"

#define PROF(o) (&(o)->g.lathe.r->ol)

/* c = a·b for polynomials of degree na, nb. */
static void pmul(const double *a, int na, const double *b, int nb, double *c)
{
	for (int i = 0; i <= na + nb; i++)
		c[i] = 0;
	for (int i = 0; i <= na; i++)
		for (int j = 0; j <= nb; j++)
			c[i + j] += a[i] * b[j];
}

static const struct curve2 *piece_of(const struct outline *ol, double v, double *s)
{
	double x = v * ol->n, k = fmin(fmax(floor(x), 0), ol->n - 1);
	const struct curve2 *c = &ol->seg[(int)k];
	double f = x - k;
	*s = c->left < 0 ? 1 - f : f;
	return c;
}

static void surface_at(const struct outline *ol, const struct curve2 *c, double s, double phi,
                       struct vec3 *p, struct vec3 *dpdu, struct vec3 *dpdv)
{
	double r, y, dr, dy, cp = cos(phi), sp = sin(phi), sg = (c->left < 0 ? -1 : 1) * ol->n;
	curve2_eval(c, s, &r, &y, &dr, &dy);
	if (p)
		*p = v3(r * cp, y, -r * sp);
	if (dpdu)
		*dpdu = v3(-2 * M_PI * r * sp, 0, -2 * M_PI * r * cp);
	if (dpdv)
		*dpdv = v3(sg * dr * cp, sg * dy, -sg * dr * sp);
}

static bool la_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	const struct outline *ol = PROF(o);
	double s;
	if (ol->n == 0)
		return false;
	const struct curve2 *c = piece_of(ol, v, &s);
	surface_at(ol, c, s, 2 * M_PI * u, p, dpdu, dpdv);
	return true;
}

/* Can the ray meet piece c (its ring of heights lo..hi, radii ≤ R) in (t0,t1)? */
static bool ring_hit(const struct curve2 *c, struct vec3 O, struct vec3 D, double t0, double t1)
{
	if (D.y != 0) {
		double ta = (c->lo[1] - O.y) / D.y, tb = (c->hi[1] - O.y) / D.y;
		t0 = fmax(t0, fmin(ta, tb));
		t1 = fmin(t1, fmax(ta, tb));
	} else if (O.y < c->lo[1] || O.y > c->hi[1]) {
		return false;
	}
	if (!(t0 <= t1))
		return false;
	double a = D.x * D.x + D.z * D.z, b = O.x * D.x + O.z * D.z, R = fmax(fabs(c->lo[0]), fabs(c->hi[0]));
	double t = a > 0 ? fmin(fmax(-b / a, t0), t1) : t0;
	double x = O.x + t * D.x, z = O.z + t * D.z;
	return x * x + z * z <= R * R * (1 + 1e-9) + 1e-300;
}

/* Parameters s where the ray meets the surface of piece c; t in ts. */
static int piece_hits(const struct curve2 *c, struct vec3 O, struct vec3 D, double *ss, double *ts)
{
	int n = 0;
	double a = D.x * D.x + D.z * D.z;
	if (fabs(D.y) > 1e-9 * sqrt(a)) {
		double Y[4] = {c->y[0] - O.y, c->y[1], c->y[2], c->y[3]}, U[4], W[4], P[7], Q[7], R2[7];
		for (int k = 0; k < 4; k++) {
			U[k] = Y[k] * D.x + (k == 0 ? O.x * D.y : 0);
			W[k] = Y[k] * D.z + (k == 0 ? O.z * D.y : 0);
		}
		pmul(U, 3, U, 3, P);
		pmul(W, 3, W, 3, Q);
		pmul(c->x, 3, c->x, 3, R2);
		for (int k = 0; k < 7; k++)
			P[k] += Q[k] - D.y * D.y * R2[k];
		double s[6];
		int m = outline_roots(P, 6, 0, 1, s);
		for (int i = 0; i < m; i++) {
			double y;
			curve2_eval(c, s[i], NULL, &y, NULL, NULL);
			ss[n] = s[i];
			ts[n++] = (y - O.y) / D.y;
		}
		return n;
	}
	double Y[4] = {c->y[0] - O.y, c->y[1], c->y[2], c->y[3]}, s[3];
	int m = outline_roots(Y, 3, 0, 1, s);
	for (int i = 0; i < m; i++) {
		double r, t0, t1, b = 2 * (O.x * D.x + O.z * D.z);
		curve2_eval(c, s[i], &r, NULL, NULL, NULL);
		double cc = O.x * O.x + O.z * O.z - r * r;
		if (!prim_quadratic(a, b, cc, b * b - 4 * a * cc, &t0, &t1))
			continue;
		ss[n] = s[i], ts[n++] = t0;
		ss[n] = s[i], ts[n++] = t1;
	}
	return n;
}

static bool la_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	const struct outline *ol = PROF(o);
	double best = tmax, bs = 0;
	int bk = -1;
	for (int k = 0; k < ol->n; k++) {
		if (!ring_hit(&ol->seg[k], r->o, r->d, tmin, best))
			continue;
		double ss[6], ts[6];
		int m = piece_hits(&ol->seg[k], r->o, r->d, ss, ts);
		for (int i = 0; i < m; i++)
			if (ts[i] > tmin && ts[i] < best)
				best = ts[i], bs = ss[i], bk = k;
	}
	if (bk < 0)
		return false;
	const struct curve2 *c = &ol->seg[bk];
	struct vec3 p = v_madd(r->o, r->d, best);
	double phi = 2 * M_PI * (lh->u = prim_turns(-p.z, p.x));
	lh->v = (bk + (c->left < 0 ? 1 - bs : bs)) / ol->n;
	lh->t = best;
	lh->p = p;
	surface_at(ol, c, bs, phi, NULL, &lh->dpdu, &lh->dpdv);
	double rr, y, dr, dy;
	curve2_eval(c, bs, &rr, &y, &dr, &dy);
	double sg = (c->left < 0 ? -1 : 1) * (rr < 0 ? -1 : 1);
	lh->n = v3(sg * dy * cos(phi), -sg * dr, -sg * dy * sin(phi));
	if (!(v_dot(lh->n, lh->n) > 0))
		lh->n = v_neg(r->d);
	return true;
}

static bool la_inside(const struct object *o, struct vec3 p)
{
	return outline_inside(PROF(o), sqrt(p.x * p.x + p.z * p.z), p.y);
}

static struct bbox la_bounds(const struct object *o)
{
	const struct outline *ol = PROF(o);
	double R = fmax(fabs(ol->lo[0]), fabs(ol->hi[0]));
	return (struct bbox){v3(-R, ol->lo[1], -R), v3(R, ol->hi[1], R)};
}

static struct uv_range la_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, true, false};
}

/* Numeric, split where the pieces meet (the Jacobian has kinks there). */
static double la_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	int N = PROF(o)->n;
	v0 = fmax(v0, 0), v1 = fmin(v1, 1);
	double sum = 0;
	for (int k = (int)floor(v0 * N); k < N && (double)k / N < v1; k++) {
		double va = fmax(v0, (double)k / N), vb = fmin(v1, (double)(k + 1) / N);
		if (vb > va)
			sum += shape_integrate_area(o, u0, u1, va, vb);
	}
	return sum;
}

static void la_dump(const struct object *o, FILE *out)
{
	const struct outline *ol = PROF(o);
	fprintf(out, "pieces %d radius %.6g height %.6g %.6g", ol->n,
	        fmax(fabs(ol->lo[0]), fabs(ol->hi[0])), ol->lo[1], ol->hi[1]);
}

const struct prim_ops shape_lathe_ops = {
	la_intersect, la_inside, la_bounds, la_uv_point, la_uv_range, la_cell_area, la_dump, NULL,
};
