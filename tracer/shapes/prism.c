/* SPDX-License-Identifier: MIT */
/* prism.c: prism { [spline] [sweep] h0, h1, n, <a,b>… [open] }: an outline in
 * the x-z plane swept along y from h0 to h1, and the extrusion code text.c
 * shares (extrude.h). The code works in a sweep frame (a,h,b): for the prism
 * (a,h,b) = (x,y,z); for text (x,y,z) = (a,−b,h), a rotation, so both are
 * right-handed and normals carry over.
 *
 * Parametrisation (sweep frame), N pieces over all parts, H = h1 − h0, the
 * unit square cut in thirds along v (open: the wall takes all of v):
 *
 *   v ∈ [0,⅓] bottom cap:  T = (A0 + u·ΔA, h0, B0 + 3v·ΔB)
 *   v ∈ [⅓,⅔] wall:        piece k = ⌊uN⌋, f = uN − k, s = f (or 1 − f),
 *                          h = h0 + (3v − 1)·H, T = (σ·a(s), h, σ·b(s))
 *   v ∈ [⅔,1] top cap:     T = (A0 + u·ΔA, h1, B1 − (3v − 2)·ΔB)
 *
 * where [A0,A1]×[B0,B1] is the outline's bounding rectangle at that height
 * and σ = 1 (linear sweep) or h (conic sweep). On the wall, s runs against u
 * on pieces whose filled side is on their left, so ∂T/∂u × ∂T/∂v is always
 * outward; ∂T/∂u = ±N·σ·(a′, 0, b′), ∂T/∂v = 3H·(0,1,0) (linear) or
 * 3H·(a, 1, b) (conic). Cap points outside the outline are off the surface
 * (like the triangle's half square).
 *
 * Walls: the ray meets the swept curve where α·a(s) + β·b(s) + γ = 0, one
 * polynomial of the piece's degree (≤ 3) for both sweeps: for a linear sweep
 * this is the ray's line in the (a,b) plane, for a conic one the plane
 * through the origin holding the ray. Its roots in [0,1] are exact (outline.c);
 * t follows from s. Caps: the plane hit, then the point-in-outline test. */
#include "extrude.h"

static const struct extrusion *EXT(const struct object *o)
{
	return o->kind == OBJ_TEXT ? o->g.text.e : o->g.prism.e;
}

static struct vec3 to_sweep(const struct extrusion *e, struct vec3 p)
{
	return e->zaxis ? v3(p.x, p.z, -p.y) : p;
}

static struct vec3 to_obj(const struct extrusion *e, struct vec3 q)
{
	return e->zaxis ? v3(q.x, -q.z, q.y) : q;
}

/* The cross-section's scale at height h. */
static double sigma(const struct extrusion *e, double h) { return e->conic ? h : 1; }

/* v of the wall's bottom, and dv per unit of h/H. */
static double v_off(const struct extrusion *e) { return e->open ? 0 : 1.0 / 3; }
static double v_len3(const struct extrusion *e) { return e->open ? 1 : 3; }

/* Bounding rectangle [r0,r1]×[r2,r3] of the (a,b) extent lo..hi scaled at
 * every height in [h0,h1]. */
static void swept_rect(const struct extrusion *e, const double lo[2], const double hi[2], double r[4])
{
	double s0 = sigma(e, e->h0), s1 = sigma(e, e->h1);
	for (int k = 0; k < 2; k++) {
		r[2 * k] = fmin(fmin(lo[k] * s0, lo[k] * s1), fmin(hi[k] * s0, hi[k] * s1));
		r[2 * k + 1] = fmax(fmax(lo[k] * s0, lo[k] * s1), fmax(hi[k] * s0, hi[k] * s1));
	}
}

/* Does the ray meet the box [r0,r1]×[h0,h1]×[r2,r3] within (t0,t1)? */
static bool box_hit(const double r[4], double h0, double h1, struct vec3 O, struct vec3 D, double t0,
                    double t1)
{
	double lo[3] = {r[0], h0, r[2]}, hi[3] = {r[1], h1, r[3]};
	double o[3] = {O.x, O.y, O.z}, d[3] = {D.x, D.y, D.z};
	for (int k = 0; k < 3; k++) {
		if (d[k] == 0) {
			if (o[k] < lo[k] || o[k] > hi[k])
				return false;
			continue;
		}
		double ta = (lo[k] - o[k]) / d[k], tb = (hi[k] - o[k]) / d[k];
		t0 = fmax(t0, fmin(ta, tb));
		t1 = fmin(t1, fmax(ta, tb));
		if (t0 > t1)
			return false;
	}
	return true;
}

static bool in_parts(const struct extrusion *e, double a, double b)
{
	for (int i = 0; i < e->nparts; i++)
		if (outline_inside(&e->part[i], a, b))
			return true;
	return false;
}

/* The wall point and partials at piece c (global index k), s, height h. */
static void wall_at(const struct extrusion *e, const struct curve2 *c, double s, double h,
                    struct vec3 *p, struct vec3 *dpdu, struct vec3 *dpdv)
{
	double a, b, ta, tb, sc = sigma(e, h), H = e->h1 - e->h0;
	curve2_eval(c, s, &a, &b, &ta, &tb);
	double du = (c->left > 0 ? -1 : 1) * e->nseg * sc;
	*p = v3(sc * a, h, sc * b);
	*dpdu = v3(du * ta, 0, du * tb);
	*dpdv = e->conic ? v_scale(v3(a, 1, b), v_len3(e) * H) : v3(0, v_len3(e) * H, 0);
}

/* A cap's rectangle at height h: A0, A1, B0, B1. */
static void cap_rect(const struct extrusion *e, double h, double r[4])
{
	double sc = sigma(e, h);
	r[0] = fmin(e->lo[0] * sc, e->hi[0] * sc);
	r[1] = fmax(e->lo[0] * sc, e->hi[0] * sc);
	r[2] = fmin(e->lo[1] * sc, e->hi[1] * sc);
	r[3] = fmax(e->lo[1] * sc, e->hi[1] * sc);
}

static void cap_at(const struct extrusion *e, bool top, double u, double v, struct vec3 *p,
                   struct vec3 *dpdu, struct vec3 *dpdv)
{
	double r[4];
	cap_rect(e, top ? e->h1 : e->h0, r);
	double da = r[1] - r[0], db = r[3] - r[2];
	if (top) {
		*p = v3(r[0] + u * da, e->h1, r[3] - (3 * v - 2) * db);
		*dpdv = v3(0, 0, -3 * db);
	} else {
		*p = v3(r[0] + u * da, e->h0, r[2] + 3 * v * db);
		*dpdv = v3(0, 0, 3 * db);
	}
	*dpdu = v3(da, 0, 0);
}

/* A wall hit being found: piece, parameter, height. */
struct wall_hit {
	const struct curve2 *c;
	int k;
	double s, h;
};

/* The nearest wall hit of one part before *best. */
static bool part_walls(const struct extrusion *e, const struct outline *ol, struct vec3 O,
                       struct vec3 D, double tmin, double *best, struct wall_hit *wh)
{
	double al, be, ga, dd = D.x * D.x + D.z * D.z;
	if (e->conic) {
		al = O.y * D.z - O.z * D.y;
		be = O.x * D.y - O.y * D.x;
	} else {
		if (dd == 0)
			return false;
		al = D.z;
		be = -D.x;
	}
	ga = O.z * D.x - O.x * D.z;
	bool found = false;
	for (int i = 0; i < ol->n; i++) {
		const struct curve2 *c = &ol->seg[i];
		double f00 = al * c->lo[0] + be * c->lo[1] + ga, f11 = al * c->hi[0] + be * c->hi[1] + ga;
		double f01 = al * c->lo[0] + be * c->hi[1] + ga, f10 = al * c->hi[0] + be * c->lo[1] + ga;
		if ((f00 > 0 && f11 > 0 && f01 > 0 && f10 > 0) || (f00 < 0 && f11 < 0 && f01 < 0 && f10 < 0))
			continue;
		double q[4], s[3];
		for (int k = 0; k < 4; k++)
			q[k] = al * c->x[k] + be * c->y[k] + (k == 0 ? ga : 0);
		int m = outline_roots(q, 3, 0, 1, s);
		for (int j = 0; j < m; j++) {
			double a, b, t;
			curve2_eval(c, s[j], &a, &b, NULL, NULL);
			if (!e->conic) {
				t = ((a - O.x) * D.x + (b - O.z) * D.z) / dd;
			} else {
				double da = D.x - D.y * a, db = D.z - D.y * b;
				t = fabs(da) >= fabs(db) ? (O.y * a - O.x) / da : (O.y * b - O.z) / db;
			}
			double h = O.y + t * D.y;
			if (!(t > tmin && t < *best) || h < e->h0 || h > e->h1)
				continue;
			*best = t;
			*wh = (struct wall_hit){c, ol->first + i, s[j], h};
			found = true;
		}
	}
	return found;
}

bool ext_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                   struct local_hit *lh)
{
	const struct extrusion *e = EXT(o);
	struct vec3 O = to_sweep(e, r->o), D = to_sweep(e, r->d);
	double best = tmax;
	int cap = -1; /* 0 bottom, 1 top, -1 wall, -2 nothing */
	bool any = false;
	if (!e->open && D.y != 0)
		for (int k = 0; k < 2; k++) {
			double hc = k ? e->h1 : e->h0, t = (hc - O.y) / D.y, sc = sigma(e, hc);
			if (!(t > tmin && t < best) || sc == 0)
				continue;
			if (in_parts(e, (O.x + t * D.x) / sc, (O.z + t * D.z) / sc)) {
				best = t;
				cap = k;
				any = true;
			}
		}
	struct wall_hit wh = {0};
	for (int i = 0; i < e->nparts; i++) {
		double rb[4];
		swept_rect(e, e->part[i].lo, e->part[i].hi, rb);
		if (!box_hit(rb, e->h0, e->h1, O, D, tmin, best))
			continue;
		if (part_walls(e, &e->part[i], O, D, tmin, &best, &wh)) {
			cap = -1;
			any = true;
		}
	}
	if (!any)
		return false;
	struct vec3 p, du, dv;
	if (cap >= 0) {
		double rc[4];
		cap_rect(e, cap ? e->h1 : e->h0, rc);
		p = v_madd(O, D, best);
		lh->u = rc[1] > rc[0] ? (p.x - rc[0]) / (rc[1] - rc[0]) : 0;
		lh->v = rc[3] > rc[2] ? (cap ? 2.0 / 3 + (rc[3] - p.z) / (rc[3] - rc[2]) / 3
		                             : (p.z - rc[2]) / (rc[3] - rc[2]) / 3)
		                      : (cap ? 1 : 0);
		cap_at(e, cap, lh->u, lh->v, &p, &du, &dv);
		p = v_madd(O, D, best);
	} else {
		double f = wh.c->left > 0 ? 1 - wh.s : wh.s;
		lh->u = (wh.k + f) / e->nseg;
		lh->v = v_off(e) + (wh.h - e->h0) / (e->h1 - e->h0) / v_len3(e);
		wall_at(e, wh.c, wh.s, wh.h, &p, &du, &dv);
		p = v_madd(O, D, best);
	}
	lh->t = best;
	lh->p = to_obj(e, p);
	lh->dpdu = to_obj(e, du);
	lh->dpdv = to_obj(e, dv);
	lh->n = v_cross(lh->dpdu, lh->dpdv);
	if (!(v_dot(lh->n, lh->n) > 0)) /* a cusp of the outline: face the ray */
		lh->n = v_neg(r->d);
	return true;
}

bool ext_inside(const struct object *o, struct vec3 p)
{
	const struct extrusion *e = EXT(o);
	struct vec3 q = to_sweep(e, p);
	double sc = sigma(e, q.y);
	if (!(q.y > e->h0 && q.y < e->h1) || sc == 0)
		return false;
	return in_parts(e, q.x / sc, q.z / sc);
}

struct bbox ext_bounds(const struct object *o)
{
	const struct extrusion *e = EXT(o);
	double r[4];
	swept_rect(e, e->lo, e->hi, r);
	struct vec3 a = to_obj(e, v3(r[0], e->h0, r[2])), b = to_obj(e, v3(r[1], e->h1, r[3]));
	return (struct bbox){v_min(a, b), v_max(a, b)};
}

/* The piece with global index k. */
static const struct curve2 *piece(const struct extrusion *e, int k)
{
	for (int i = e->nparts - 1; i >= 0; i--)
		if (k >= e->part[i].first)
			return &e->part[i].seg[k - e->part[i].first];
	return &e->part[0].seg[0];
}

bool ext_uv_point(const struct object *o, double u, double v, struct vec3 *p, struct vec3 *dpdu,
                  struct vec3 *dpdv)
{
	const struct extrusion *e = EXT(o);
	struct vec3 q, du, dv;
	if (e->nseg == 0)
		return false;
	if (!e->open && (v < 1.0 / 3 || v > 2.0 / 3)) {
		cap_at(e, v > 2.0 / 3, u, v, &q, &du, &dv);
	} else {
		double x = u * e->nseg, k = floor(x);
		k = fmin(fmax(k, 0), e->nseg - 1);
		const struct curve2 *c = piece(e, (int)k);
		double f = x - k, s = c->left > 0 ? 1 - f : f;
		double h = e->h0 + (v - v_off(e)) * v_len3(e) * (e->h1 - e->h0);
		wall_at(e, c, s, h, &q, &du, &dv);
	}
	if (p)
		*p = to_obj(e, q);
	if (dpdu)
		*dpdu = to_obj(e, du);
	if (dpdv)
		*dpdv = to_obj(e, dv);
	return true;
}

struct uv_range ext_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, false, false};
}

/* Area of a cap over u ∈ [u0,u1] and w ∈ [w0,w1] (w: 3v, or 3v − 2 on top). */
static double cap_area(const struct object *o, const struct extrusion *e, bool top, double u0,
                       double u1, double w0, double w1)
{
	double r[4], h = top ? e->h1 : e->h0, sc = fabs(sigma(e, h));
	cap_rect(e, h, r);
	if (!(sc > 0))
		return 0;
	double da = r[1] - r[0], db = r[3] - r[2];
	double a0 = r[0] + u0 * da, a1 = r[0] + u1 * da;
	double b0 = top ? r[3] - w1 * db : r[2] + w0 * db, b1 = top ? r[3] - w0 * db : r[2] + w1 * db;
	double sum = 0;
	for (int i = 0; i < e->nparts; i++)
		sum += outline_rect_area(&e->part[i], a0 / sc, a1 / sc, b0 / sc, b1 / sc);
	return sum * sc * sc * shape_planar_scale(o, to_obj(e, v3(0, 1, 0)));
}

double ext_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	const struct extrusion *e = EXT(o);
	u0 = fmax(u0, 0), u1 = fmin(u1, 1), v0 = fmax(v0, 0), v1 = fmin(v1, 1);
	if (!(u1 > u0) || !(v1 > v0))
		return 0;
	double sum = 0, wa = v0, wb = v1;
	if (!e->open) {
		const double third = 1.0 / 3;
		if (v0 < third)
			sum += cap_area(o, e, false, u0, u1, 3 * v0, 3 * fmin(v1, third));
		if (v1 > 2 * third)
			sum += cap_area(o, e, true, u0, u1, 3 * fmax(v0, 2 * third) - 2, 3 * v1 - 2);
		wa = fmax(v0, third);
		wb = fmin(v1, 2 * third);
	}
	if (!(wb > wa))
		return sum;
	int N = e->nseg;
	for (int k = (int)floor(u0 * N); k < N && (double)k / N < u1; k++) {
		double ua = fmax(u0, (double)k / N), ub = fmin(u1, (double)(k + 1) / N);
		if (ub > ua)
			sum += shape_integrate_area(o, ua, ub, wa, wb);
	}
	return sum;
}

static void pr_dump(const struct object *o, FILE *out)
{
	const struct extrusion *e = o->g.prism.e;
	fprintf(out, "%s %.6g %.6g pieces %d%s", e->conic ? "conic_sweep" : "linear_sweep", e->h0,
	        e->h1, e->nseg, e->open ? " open" : "");
}

const struct prim_ops shape_prism_ops = {
	ext_intersect, ext_inside, ext_bounds, ext_uv_point, ext_uv_range, ext_cell_area, pr_dump, NULL,
};
