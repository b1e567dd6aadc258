/* SPDX-License-Identifier: MIT */
/* blob.c: blob { threshold T  sphere { c, r, strength s } … cylinder { a, b,
 * r, strength s } … }, POV-Ray's metaballs. Each component adds the field
 *
 *     s·(1 − d²/r²)²   where d < r (0 beyond),
 *
 * d the distance to the sphere's centre or to the cylinder's segment (so
 * cylinders have round ends); a component's own transform applies to its
 * distance. The surface is where the sum equals T, the inside where it is
 * greater. One sphere alone is the sphere of radius r·√(1 − √(T/s)).
 *
 * Intersection is exact: along the ray, d² is a quadratic in t on each
 * piece (a sphere; a cylinder's body and its two end caps), so each
 * component's field is a quartic in t there. The pieces' ends cut the ray
 * into intervals on which the field is one quartic; the first root of
 * field − T (tracer/polysolve.c) is the hit. The normal is −∇field.
 *
 * Parametrisation: the radial one of implicit surfaces (prim.h;
 * docs/parametrisations.md), about the centre of the components' bounds. */
#include <math.h>
#include <stdlib.h>

#include "../polysolve.h"
#include "prim.h"

#define BL(o) ((o)->g.blob.b)

/* One piece of one component along the ray: on (t0,t1), 1 − d²/r² is
 * w[0] + w[1]t + w[2]t², weighted by the strength s. */
struct piece {
	double t0, t1, w[3], s;
};

/* The piece where |o + t·d − P|² < r², clipped to (a0,b0) and (lo,hi):
 * 1 when there is one. */
static int ball_piece(const struct ray *lr, struct vec3 P, double rr, double s, double a0,
                      double b0, double lo, double hi, struct piece *out)
{
	struct vec3 f = v_sub(lr->o, P);
	double q2 = v_dot(lr->d, lr->d), q1 = 2 * v_dot(f, lr->d), q0 = v_dot(f, f), ta, tb;
	if (!prim_quadratic(q2, q1, q0 - rr, q1 * q1 - 4 * q2 * (q0 - rr), &ta, &tb))
		return 0;
	ta = fmax(ta, fmax(a0, lo));
	tb = fmin(tb, fmin(b0, hi));
	if (!(tb > ta))
		return 0;
	*out = (struct piece){ta, tb, {1 - q0 / rr, -q1 / rr, -q2 / rr}, s};
	return 1;
}

/* The pieces of component c along the blob-frame ray r within (lo,hi);
 * returns how many (0 to 3). */
static int comp_pieces(const struct blob_comp *c, const struct ray *r, double lo, double hi,
                       struct piece *out)
{
	struct ray lr = *r;
	if (c->xf)
		lr = (struct ray){xf_inv_point(c->xf, r->o), xf_inv_vector(c->xf, r->d)};
	double rr = c->r * c->r, dd = v_dot(lr.d, lr.d);
	int n = 0;
	if (!c->cylinder) {
		return ball_piece(&lr, c->a, rr, c->s, -INFINITY, INFINITY, lo, hi, out);
	}
	struct vec3 ax = v_sub(c->b, c->a);
	double L = v_len(ax);
	struct vec3 u = v_scale(ax, 1 / L);
	/* h(t) = (o + t·d − a)·u: the body has 0 ≤ h ≤ L */
	double h0 = v_dot(v_sub(lr.o, c->a), u), h1 = v_dot(lr.d, u);
	double ta = -INFINITY, tb = INFINITY; /* where 0 ≤ h ≤ L */
	if (h1 != 0) {
		double x = -h0 / h1, y = (L - h0) / h1;
		ta = fmin(x, y), tb = fmax(x, y);
	} else if (h0 < 0 || h0 > L) {
		ta = INFINITY, tb = -INFINITY;
	}
	/* body: |o + t·d − a|² − h(t)², the distance to the axis */
	struct vec3 f = v_sub(lr.o, c->a);
	double q2 = dd - h1 * h1, q1 = 2 * (v_dot(f, lr.d) - h0 * h1), q0 = v_dot(f, f) - h0 * h0, b0, b1;
	if (tb > ta && q2 > 1e-300 &&
	    prim_quadratic(q2, q1, q0 - rr, q1 * q1 - 4 * q2 * (q0 - rr), &b0, &b1)) {
		b0 = fmax(b0, fmax(ta, lo));
		b1 = fmin(b1, fmin(tb, hi));
		if (b1 > b0)
			out[n++] = (struct piece){b0, b1, {1 - q0 / rr, -q1 / rr, -q2 / rr}, c->s};
	}
	/* the caps: h < 0 near a, h > L near b */
	double a_lo = h1 > 0 ? -INFINITY : tb, a_hi = h1 > 0 ? ta : INFINITY;
	double b_lo = h1 > 0 ? tb : -INFINITY, b_hi = h1 > 0 ? INFINITY : ta;
	if (h1 == 0) { /* parallel to the ends: wholly in one cap or in the body */
		a_lo = h0 < 0 ? -INFINITY : INFINITY, a_hi = INFINITY;
		b_lo = h0 > L ? -INFINITY : INFINITY, b_hi = INFINITY;
	}
	n += ball_piece(&lr, c->a, rr, c->s, a_lo, a_hi, lo, hi, out + n);
	n += ball_piece(&lr, c->b, rr, c->s, b_lo, b_hi, lo, hi, out + n);
	return n;
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* The field at p and its gradient. */
static double field(const struct blob *B, struct vec3 p, struct vec3 *grad)
{
	double f = 0;
	struct vec3 g = v3(0, 0, 0);
	for (int i = 0; i < B->n; i++) {
		const struct blob_comp *c = &B->c[i];
		struct vec3 lp = c->xf ? xf_inv_point(c->xf, p) : p, near = c->a;
		if (c->cylinder) {
			struct vec3 ax = v_sub(c->b, c->a);
			double h = v_dot(v_sub(lp, c->a), ax) / v_dot(ax, ax);
			near = v_madd(c->a, ax, fmin(1, fmax(0, h)));
		}
		struct vec3 dv = v_sub(lp, near);
		double w = 1 - v_dot(dv, dv) / (c->r * c->r);
		if (w <= 0)
			continue;
		f += c->s * w * w;
		/* ∇(s w²) = s·2w·(−2/r²)·(p − near) */
		struct vec3 gl = v_scale(dv, -4 * c->s * w / (c->r * c->r));
		g = v_add(g, c->xf ? xf_normal(c->xf, gl) : gl);
	}
	if (grad)
		*grad = g;
	return f;
}

static bool bl_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	const struct blob *B = BL(o);
	struct piece local[96], *pc = local;
	int cap = 96, np = 0;
	for (int i = 0; i < B->n; i++) {
		if (np + 3 > cap) {
			struct piece *bigger = malloc(sizeof *bigger * (size_t)cap * 2);
			if (!bigger)
				break;
			for (int k = 0; k < np; k++)
				bigger[k] = pc[k];
			if (pc != local)
				free(pc);
			pc = bigger;
			cap *= 2;
		}
		np += comp_pieces(&B->c[i], r, tmin, tmax, pc + np);
	}
	bool found = false;
	if (np > 0) {
		double cut_local[192], *cuts = np <= 96 ? cut_local : malloc(sizeof *cuts * (size_t)np * 2);
		int nc = 0;
		if (cuts) {
			for (int i = 0; i < np; i++)
				cuts[nc++] = pc[i].t0, cuts[nc++] = pc[i].t1;
			qsort(cuts, (size_t)nc, sizeof *cuts, cmp_double);
		}
		for (int k = 0; k + 1 < nc && !found; k++) {
			double a = cuts[k], b = cuts[k + 1], m = 0.5 * (a + b);
			if (!(b > a))
				continue;
			/* Σ s·w(t)² − T on (a,b), in the variable x = t − m */
			double c[5] = {-B->threshold, 0, 0, 0, 0};
			for (int i = 0; i < np; i++) {
				if (!(pc[i].t0 <= m && m <= pc[i].t1))
					continue;
				const double *w = pc[i].w;
				/* w(m + x) = v0 + v1 x + v2 x² */
				double v0 = w[0] + m * (w[1] + m * w[2]), v1 = w[1] + 2 * m * w[2], v2 = w[2];
				double s = pc[i].s;
				c[0] += s * v0 * v0;
				c[1] += s * 2 * v0 * v1;
				c[2] += s * (v1 * v1 + 2 * v0 * v2);
				c[3] += s * 2 * v1 * v2;
				c[4] += s * v2 * v2;
			}
			double x[4];
			int nr = poly_roots(c, 4, a - m, b - m, x);
			for (int i = 0; i < nr; i++) {
				double t = m + x[i];
				if (!(t > tmin && t < tmax))
					continue;
				struct vec3 g;
				lh->t = t;
				lh->p = v_madd(r->o, r->d, t);
				field(B, lh->p, &g);
				lh->n = v_dot(g, g) > 0 ? v_neg(g) : v_neg(r->d);
				prim_radial_hit(B->centre, lh);
				found = true;
				break;
			}
		}
		if (cuts != cut_local)
			free(cuts);
	}
	if (pc != local)
		free(pc);
	return found;
}

static bool bl_inside(const struct object *o, struct vec3 p)
{
	return field(BL(o), p, NULL) > BL(o)->threshold;
}

static struct bbox bl_bounds(const struct object *o)
{
	const struct blob *B = BL(o);
	struct bbox all = bbox_empty();
	for (int i = 0; i < B->n; i++) {
		const struct blob_comp *c = &B->c[i];
		struct vec3 rv = v3(c->r, c->r, c->r);
		struct bbox b = {v_sub(c->a, rv), v_add(c->a, rv)};
		if (c->cylinder)
			b = bbox_union(b, (struct bbox){v_sub(c->b, rv), v_add(c->b, rv)});
		all = bbox_union(all, c->xf ? xf_bbox(c->xf, b) : b);
	}
	return all;
}

static bool bl_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	return prim_radial_point(o, BL(o)->centre, bl_intersect, u, v, p, dpdu, dpdv);
}

static struct uv_range bl_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, true, false};
}

static double bl_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	return shape_integrate_area(o, u0, u1, fmax(v0, 0), fmin(v1, 1));
}

static void bl_dump(const struct object *o, FILE *out)
{
	const struct blob *B = BL(o);
	fprintf(out, "threshold %.6g components %d", B->threshold, B->n);
	for (int i = 0; i < B->n; i++) {
		fprintf(out, " %s ", B->c[i].cylinder ? "cylinder" : "sphere");
		prim_dump_vec(out, B->c[i].a);
		if (B->c[i].cylinder)
			fputc(' ', out), prim_dump_vec(out, B->c[i].b);
		fprintf(out, " %.6g %.6g", B->c[i].r, B->c[i].s);
	}
}

const struct prim_ops shape_blob_ops = {
	bl_intersect, bl_inside, bl_bounds, bl_uv_point, bl_uv_range, bl_cell_area, bl_dump, NULL,
};
