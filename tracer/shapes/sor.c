/* SPDX-License-Identifier: MIT */
/* sor.c: sor { n, <r,y>… [open] }: a surface of revolution about y whose
 * squared radius is a cubic in the height on each piece,
 * r² = f(y) = A·y³ + B·y² + C·y + D on [y0,y1] (POV-Ray's interpolation of
 * the points, the first and last only setting the end slopes: eval), with
 * flat caps at both ends unless open.
 *
 * Parametrisation (object frame), φ = 2πu, e(φ) = (cosφ, 0, −sinφ), N pieces;
 * closed: v ∈ [0,¼] base cap, [¼,¾] side, [¾,1] top cap (open: side only):
 *
 *   base:  ρ = 4v·r_base,           T = ρ·e(φ) + y_lo·ŷ,  ∂T/∂v = 4r_base·e(φ)
 *   side:  w = (v − ¼)·2N (open: vN), piece k = ⌊w⌋, y = y0 + (w − k)(y1 − y0),
 *          ρ = √f(y),  T = ρ·e(φ) + y·ŷ,  ∂T/∂v = 2N(y1 − y0)·(ρ′·e(φ) + ŷ)
 *   top:   ρ = 4(1 − v)·r_cap,      T = ρ·e(φ) + y_hi·ŷ,  ∂T/∂v = −4r_cap·e(φ)
 *   ∂T/∂u = 2πρ·(−sinφ, 0, −cosφ) everywhere; ∂T/∂u × ∂T/∂v is outward.
 *
 * The Jacobian vanishes at the cap centres and where the side meets the
 * axis. Intersection: ρ(t)² = f(Oy + t·Dy) is a cubic in t on each piece,
 * solved within the piece's slab and bounding cylinder (outline.c). */
#include "outline.h"
#include "prim.h"

#define SS(o) ((o)->g.sor.s)

static double f_of(const struct sor_piece *p, double y, double *d)
{
	if (d)
		*d = (3 * p->A * y + 2 * p->B) * y + p->C;
	return ((p->A * y + p->B) * y + p->C) * y + p->D;
}

static bool closed(const struct object *o) { return !(o->flags & OF_OPEN); }

/* The side's v per piece, and where it starts. */
static double side_len(const struct object *o) { return closed(o) ? 2.0 * SS(o)->n : SS(o)->n; }
static double side_off(const struct object *o) { return closed(o) ? 0.25 : 0; }

static void ring(double rho, double y, double phi, struct vec3 *p, struct vec3 *dpdu)
{
	double c = cos(phi), s = sin(phi);
	if (p)
		*p = v3(rho * c, y, -rho * s);
	if (dpdu)
		*dpdu = v3(-2 * M_PI * rho * s, 0, -2 * M_PI * rho * c);
}

static bool so_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	const struct sor_shape *S = SS(o);
	double phi = 2 * M_PI * u, c = cos(phi), s = sin(phi);
	struct vec3 e = v3(c, 0, -s);
	if (closed(o) && v < 0.25) {
		ring(4 * v * S->rbase, S->ylo, phi, p, dpdu);
		if (dpdv)
			*dpdv = v_scale(e, 4 * S->rbase);
		return true;
	}
	if (closed(o) && v > 0.75) {
		ring(4 * (1 - v) * S->rcap, S->yhi, phi, p, dpdu);
		if (dpdv)
			*dpdv = v_scale(e, -4 * S->rcap);
		return true;
	}
	double L = side_len(o), w = (v - side_off(o)) * L, k = fmin(fmax(floor(w), 0), S->n - 1);
	const struct sor_piece *pc = &S->p[(int)k];
	double y = pc->y0 + (w - k) * (pc->y1 - pc->y0), df, f = f_of(pc, y, &df);
	double rho = sqrt(fmax(f, 0)), drho = rho > 0 ? df / (2 * rho) : 0;
	ring(rho, y, phi, p, dpdu);
	if (dpdv)
		*dpdv = v_scale(v_add(v_scale(e, drho), v3(0, 1, 0)), L * (pc->y1 - pc->y0));
	return true;
}

/* t interval where the ray is within the piece's slab and bounding
 * cylinder, clipped to (t0,t1). */
static bool piece_span(const struct sor_piece *pc, struct vec3 O, struct vec3 D, double *t0, double *t1)
{
	if (D.y != 0) {
		double ta = (pc->y0 - O.y) / D.y, tb = (pc->y1 - O.y) / D.y;
		*t0 = fmax(*t0, fmin(ta, tb));
		*t1 = fmin(*t1, fmax(ta, tb));
	} else if (O.y < pc->y0 || O.y > pc->y1) {
		return false;
	}
	double a = D.x * D.x + D.z * D.z, b = 2 * (O.x * D.x + O.z * D.z);
	double c = O.x * O.x + O.z * O.z - pc->rmax * pc->rmax * (1 + 1e-9), ta, tb;
	if (a > 0) {
		if (!prim_quadratic(a, b, c, b * b - 4 * a * c, &ta, &tb))
			return false;
		*t0 = fmax(*t0, ta);
		*t1 = fmin(*t1, tb);
	} else if (c > 0) {
		return false;
	}
	return *t0 <= *t1 && isfinite(*t0) && isfinite(*t1);
}

static bool so_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	const struct sor_shape *S = SS(o);
	struct vec3 O = r->o, D = r->d;
	double best = tmax;
	int part = -3; /* -1 base, -2 top, k ≥ 0 side piece */
	if (closed(o) && D.y != 0)
		for (int k = 0; k < 2; k++) {
			double yc = k ? S->yhi : S->ylo, rc = k ? S->rcap : S->rbase, t = (yc - O.y) / D.y;
			double x = O.x + t * D.x, z = O.z + t * D.z;
			if (rc > 0 && t > tmin && t < best && x * x + z * z <= rc * rc)
				best = t, part = -1 - k;
		}
	double a = D.x * D.x + D.z * D.z, b = 2 * (O.x * D.x + O.z * D.z), c = O.x * O.x + O.z * O.z;
	for (int k = 0; k < S->n; k++) {
		const struct sor_piece *pc = &S->p[k];
		double t0 = tmin, t1 = best;
		if (!piece_span(pc, O, D, &t0, &t1))
			continue;
		double y[4] = {O.y, D.y, 0, 0}, y2[4] = {O.y * O.y, 2 * O.y * D.y, D.y * D.y, 0};
		double y3[4] = {O.y * y2[0], 3 * O.y * O.y * D.y, 3 * O.y * D.y * D.y, D.y * D.y * D.y};
		double q[4];
		for (int i = 0; i < 4; i++)
			q[i] = (i == 0 ? c : i == 1 ? b : i == 2 ? a : 0) -
			       (pc->A * y3[i] + pc->B * y2[i] + pc->C * y[i] + (i == 0 ? pc->D : 0));
		double ts[3];
		int m = outline_roots(q, 3, t0, t1, ts);
		for (int i = 0; i < m; i++)
			if (ts[i] > tmin && ts[i] < best) {
				best = ts[i];
				part = k;
				break;
			}
	}
	if (part == -3)
		return false;
	struct vec3 p = v_madd(O, D, best);
	double rho = sqrt(p.x * p.x + p.z * p.z);
	lh->t = best;
	lh->p = p;
	lh->u = prim_turns(-p.z, p.x);
	if (part == -1) {
		lh->v = S->rbase > 0 ? fmin(rho / S->rbase, 1) * 0.25 : 0;
		lh->n = v3(0, -1, 0);
	} else if (part == -2) {
		lh->v = 1 - (S->rcap > 0 ? fmin(rho / S->rcap, 1) * 0.25 : 0);
		lh->n = v3(0, 1, 0);
	} else {
		const struct sor_piece *pc = &S->p[part];
		double df, w = (p.y - pc->y0) / (pc->y1 - pc->y0);
		f_of(pc, p.y, &df);
		lh->v = side_off(o) + (part + fmin(fmax(w, 0), 1)) / side_len(o);
		lh->n = v3(p.x, -0.5 * df, p.z);
		if (!(v_dot(lh->n, lh->n) > 0))
			lh->n = v3(0, p.y > 0.5 * (S->ylo + S->yhi) ? 1 : -1, 0);
	}
	return so_uv_point(o, lh->u, lh->v, NULL, &lh->dpdu, &lh->dpdv);
}

static bool so_inside(const struct object *o, struct vec3 p)
{
	const struct sor_shape *S = SS(o);
	if (!(p.y > S->ylo && p.y < S->yhi))
		return false;
	for (int k = 0; k < S->n; k++)
		if (p.y >= S->p[k].y0 && p.y <= S->p[k].y1)
			return p.x * p.x + p.z * p.z < f_of(&S->p[k], p.y, NULL);
	return false;
}

static struct bbox so_bounds(const struct object *o)
{
	const struct sor_shape *S = SS(o);
	return (struct bbox){v3(-S->rmax, S->ylo, -S->rmax), v3(S->rmax, S->yhi, S->rmax)};
}

static struct uv_range so_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, true, false};
}

/* Caps: annular sectors, exact under any affine map. Side: numeric, split
 * where the pieces meet. */
static double so_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	const struct sor_shape *S = SS(o);
	v0 = fmax(v0, 0), v1 = fmin(v1, 1);
	double sum = 0, a = v0, b = v1, cap = shape_planar_scale(o, v3(0, 1, 0)) * M_PI * (u1 - u0);
	if (closed(o)) {
		if (v0 < 0.25) {
			double r0 = 4 * v0 * S->rbase, r1 = 4 * fmin(v1, 0.25) * S->rbase;
			sum += cap * (r1 * r1 - r0 * r0);
		}
		if (v1 > 0.75) {
			double r0 = 4 * (1 - v1) * S->rcap, r1 = 4 * (1 - fmax(v0, 0.75)) * S->rcap;
			sum += cap * (r1 * r1 - r0 * r0);
		}
		a = fmax(v0, 0.25), b = fmin(v1, 0.75);
	}
	double L = side_len(o), off = side_off(o);
	for (int k = 0; k < S->n; k++) {
		double va = fmax(a, off + k / L), vb = fmin(b, off + (k + 1) / L);
		if (vb > va)
			sum += shape_integrate_area(o, u0, u1, va, vb);
	}
	return sum;
}

static void so_dump(const struct object *o, FILE *out)
{
	const struct sor_shape *S = SS(o);
	fprintf(out, "pieces %d radius %.6g height %.6g %.6g%s", S->n, S->rmax, S->ylo, S->yhi,
	        closed(o) ? "" : " open");
}

const struct prim_ops shape_sor_ops = {
	so_intersect, so_inside, so_bounds, so_uv_point, so_uv_range, so_cell_area, so_dump, NULL,
};
