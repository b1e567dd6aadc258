/* SPDX-License-Identifier: MIT */
/* cone.c: cone { a, ra, b, rb [open] }: a truncated cone, radius ra at a and
 * rb at b (either may be 0: an apex).
 *
 * Parametrisation (object frame), laid out like the cylinder's: w = (b−a)/h,
 * e1, e2 = shape_basis(w), R(φ) = cosφ·e1 + sinφ·e2, φ = 2πu; v runs along
 * the meridian by arc length from the centre of cap a (or from a when that
 * end is open or an apex), up the slant side, to the centre of cap b:
 *
 *     ca = ra if cap a exists else 0,  cb = rb if cap b exists else 0
 *     S = √(h² + (rb − ra)²) (slant length),  L = ca + S + cb,  s = v·L
 *     cap a  (s ≤ ca):          T = a + s·R(φ)
 *     side   (σ = (s − ca)/S):  T = a + (ra + (rb − ra)σ)·R(φ) + σh·w
 *     cap b  (s ≥ ca + S):      T = b + (L − s)·R(φ)
 *
 *     ∂T/∂u = 2πρ·(−sinφ·e1 + cosφ·e2), ρ the distance from the axis;
 *     ∂T/∂v = L·R(φ) (cap a), (L/S)·((rb − ra)·R(φ) + h·w) (side), −L·R(φ) (cap b)
 *     ‖∂T/∂u × ∂T/∂v‖ = 2πρL: zero at cap centres and at an apex (ρ = 0).
 *
 * A cap exists when the cone is not open and its radius is > 0. u wraps.
 * Cell areas split at the seams; caps are exact under any affine map, the
 * side exact under similarities and integrated numerically otherwise. */
#include <math.h>
#include <string.h>

#include "prim.h"

/* The cone's frame and meridian layout. */
struct kframe {
	struct vec3 a, w, e1, e2; /* base point, unit axis, radial axes */
	double h, ra, rb;         /* height and end radii */
	double slant;             /* side length along a meridian */
	double s1, s2, len;       /* arc length at the seams, and in all */
};

/* The frame without the lengths along a meridian (slant, s1, s2, len):
 * what the candidates need (kn_lengths completes it). */
static bool kn_axes(const struct object *o, struct kframe *f)
{
	struct vec3 ab = v_sub(o->g.cone.b, o->g.cone.a);
	f->h = v_len(ab);
	f->ra = fmax(o->g.cone.ra, 0);
	f->rb = fmax(o->g.cone.rb, 0);
	if (!(f->h > 0) || !(f->ra > 0 || f->rb > 0))
		return false;
	f->a = o->g.cone.a;
	f->w = v_scale(ab, 1 / f->h);
	shape_basis(f->w, &f->e1, &f->e2);
	return true;
}

/* kn_axes of the cone this thread asked last, kept: a query tests the same
 * cone ray after ray, and the frame is a function of its ends and radii
 * alone (compared bit for bit), so the copy is what kn_axes would give
 * (its square root, division, basis and two calls of fmax spared). */
static _Thread_local struct {
	struct vec3 a, b;
	double ra, rb;
	bool ok;
	struct kframe f;
} kn_last;

static bool kn_axes_kept(const struct object *o, struct kframe *f)
{
	if (memcmp(&kn_last.a, &o->g.cone.a, sizeof kn_last.a) || memcmp(&kn_last.b, &o->g.cone.b, sizeof kn_last.b) ||
	    memcmp(&kn_last.ra, &o->g.cone.ra, sizeof kn_last.ra) || memcmp(&kn_last.rb, &o->g.cone.rb, sizeof kn_last.rb)) {
		kn_last.a = o->g.cone.a, kn_last.b = o->g.cone.b, kn_last.ra = o->g.cone.ra, kn_last.rb = o->g.cone.rb;
		kn_last.f = (struct kframe){.h = 0};
		kn_last.ok = kn_axes(o, &kn_last.f);
	}
	*f = kn_last.f;
	return kn_last.ok;
}

static void kn_lengths(const struct object *o, struct kframe *f)
{
	bool caps = !(o->flags & OF_OPEN);
	f->slant = hypot(f->h, f->rb - f->ra);
	f->s1 = caps ? f->ra : 0;
	f->s2 = f->s1 + f->slant;
	f->len = f->s2 + (caps ? f->rb : 0);
}

static bool kn_frame(const struct object *o, struct kframe *f)
{
	if (!kn_axes(o, f))
		return false;
	kn_lengths(o, f);
	return true;
}

/* T and its partials at angle φ and meridian arc length s. */
static void kn_eval(const struct kframe *f, double phi, double s, struct vec3 *p,
                    struct vec3 *dpdu, struct vec3 *dpdv)
{
	struct vec3 rad = v_add(v_scale(f->e1, cos(phi)), v_scale(f->e2, sin(phi)));
	struct vec3 tan = v_add(v_scale(f->e1, -sin(phi)), v_scale(f->e2, cos(phi)));
	double rho, z;
	struct vec3 dv;
	if (s < f->s1) {
		rho = s, z = 0, dv = rad;
	} else if (s <= f->s2) {
		double sg = (s - f->s1) / f->slant;
		rho = f->ra + (f->rb - f->ra) * sg, z = sg * f->h;
		dv = v_scale(v_madd(v_scale(rad, f->rb - f->ra), f->w, f->h), 1 / f->slant);
	} else {
		rho = f->len - s, z = f->h, dv = v_neg(rad);
	}
	if (p)
		*p = v_madd(v_madd(f->a, rad, rho), f->w, z);
	if (dpdu)
		*dpdu = v_scale(tan, 2 * M_PI * rho);
	if (dpdv)
		*dpdv = v_scale(dv, f->len);
}

static bool kn_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                        struct vec3 *dpdu, struct vec3 *dpdv)
{
	struct kframe f;
	if (!kn_frame(o, &f))
		return false;
	kn_eval(&f, 2 * M_PI * u, v * f.len, p, dpdu, dpdv);
	return true;
}

/* Roots of the side's quadric x² + y² = (ra + k·z)² in the axis frame. The
 * ray origin is first moved to its point nearest the axis midpoint (t is
 * shifted back), which keeps the coefficients small for distant rays. */
static int kn_side_roots(const struct kframe *f, const struct ray *r, double t[2])
{
	struct vec3 mid = v_madd(f->a, f->w, 0.5 * f->h);
	double dd = v_dot(r->d, r->d);
	if (!(dd > 0))
		return 0;
	double tc = -v_dot(v_sub(r->o, mid), r->d) / dd;
	struct vec3 q = v_sub(ray_at(*r, tc), f->a);
	double ox = v_dot(q, f->e1), oy = v_dot(q, f->e2), oz = v_dot(q, f->w);
	double dx = v_dot(r->d, f->e1), dy = v_dot(r->d, f->e2), dz = v_dot(r->d, f->w);
	double k = (f->rb - f->ra) / f->h, rz = f->ra + k * oz;
	double A = dx * dx + dy * dy - k * k * dz * dz;
	double B = 2 * (ox * dx + oy * dy - k * rz * dz);
	double C = ox * ox + oy * oy - rz * rz;
	if (fabs(A) <= 1e-14 * dd) { /* ray parallel to a generator line */
		if (B == 0)
			return 0;
		t[0] = tc - C / B;
		return 1;
	}
	if (!prim_quadratic(A, B, C, B * B - 4 * A * C, &t[0], &t[1]))
		return 0;
	t[0] += tc;
	t[1] += tc;
	return 2;
}

/* Collects the ray's hits with the side (within its height) and the caps. */
static int kn_candidates(const struct object *o, const struct kframe *f, const struct ray *r,
                         struct cand c[4])
{
	double t[2];
	int n = 0, m = kn_side_roots(f, r, t);
	struct vec3 q = v_sub(r->o, f->a);
	double oz = v_dot(q, f->w), dz = v_dot(r->d, f->w);
	for (int i = 0; i < m; i++) {
		double z = oz + t[i] * dz;
		if (z >= 0 && z <= f->h)
			c[n++] = (struct cand){t[i], 0};
	}
	if ((o->flags & OF_OPEN) || dz == 0)
		return n;
	for (int k = 0; k < 2; k++) {
		double rad = k ? f->rb : f->ra, z = k ? f->h : 0;
		if (!(rad > 0))
			continue;
		double tc = (z - oz) / dz;
		struct vec3 pr = v_madd(v_madd(q, r->d, tc), f->w, -z);
		if (v_dot(pr, pr) <= rad * rad)
			c[n++] = (struct cand){tc, 1 + k};
	}
	return n;
}

/* Fills the hit for part `part` at parameter t. */
static void kn_fill(const struct kframe *f, const struct ray *r, double t, int part,
                    struct local_hit *lh)
{
	struct vec3 q = v_sub(ray_at(*r, t), f->a);
	double x = v_dot(q, f->e1), y = v_dot(q, f->e2), z = v_dot(q, f->w);
	double phi = atan2(y, x), rho = sqrt(x * x + y * y), s;
	if (part == 0)
		s = f->s1 + fmin(fmax(z / f->h, 0), 1) * f->slant;
	else if (part == 1)
		s = fmin(rho, f->ra);
	else
		s = f->len - fmin(rho, f->rb);
	lh->t = t;
	lh->u = prim_turns(y, x);
	lh->v = s / f->len;
	kn_eval(f, phi, s, &lh->p, &lh->dpdu, &lh->dpdv);
	struct vec3 rad = v_add(v_scale(f->e1, cos(phi)), v_scale(f->e2, sin(phi)));
	if (part == 0)
		lh->n = v_madd(v_scale(rad, f->h), f->w, -(f->rb - f->ra));
	else
		lh->n = part == 1 ? v_neg(f->w) : f->w;
}

/* The nearest candidate in range. */
static bool kn_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                         struct local_hit *lh)
{
	struct kframe f;
	struct cand c[4];
	if (!kn_axes_kept(o, &f))
		return false;
	int best = prim_cand_nearest(c, kn_candidates(o, &f, r, c), tmin, tmax);
	if (best < 0)
		return false;
	kn_lengths(o, &f);
	kn_fill(&f, r, c[best].t, c[best].part, lh);
	return true;
}

/* kn_intersect's answer without the hit: a candidate in range. */
static bool kn_occluded(const struct object *o, const struct ray *r, double tmin, double tmax)
{
	struct kframe f;
	struct cand c[4];
	if (!kn_axes_kept(o, &f))
		return false;
	return prim_cand_any(c, kn_candidates(o, &f, r, c), tmin, tmax);
}

static bool kn_inside(const struct object *o, struct vec3 p)
{
	struct kframe f;
	if (!kn_frame(o, &f))
		return false;
	struct vec3 q = v_sub(p, f.a);
	double z = v_dot(q, f.w), rz = f.ra + (f.rb - f.ra) * z / f.h;
	struct vec3 qp = v_madd(q, f.w, -z);
	return z > 0 && z < f.h && v_dot(qp, qp) < rz * rz;
}

/* Bounds of one rim circle of radius r about c, axis w. */
static struct bbox rim(struct vec3 c, struct vec3 w, double r)
{
	struct vec3 e = v3(r * sqrt(fmax(0, 1 - w.x * w.x)), r * sqrt(fmax(0, 1 - w.y * w.y)),
	                   r * sqrt(fmax(0, 1 - w.z * w.z)));
	return (struct bbox){v_sub(c, e), v_add(c, e)};
}

static struct bbox kn_bounds(const struct object *o)
{
	struct vec3 w = v_norm(v_sub(o->g.cone.b, o->g.cone.a));
	return bbox_union(rim(o->g.cone.a, w, fabs(o->g.cone.ra)),
	                  rim(o->g.cone.b, w, fabs(o->g.cone.rb)));
}

static struct uv_range kn_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, true, false};
}

/* Object-frame side area for σ ∈ [g0,g1] and Δu: Δφ·S·∫ρ dσ. */
static double side_area(const struct kframe *f, double du, double g0, double g1)
{
	double mean = f->ra + (f->rb - f->ra) * 0.5 * (g0 + g1);
	return 2 * M_PI * du * f->slant * (g1 - g0) * mean;
}

/* Split at the seams: caps exact, side closed form or numeric. */
static double kn_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	struct kframe f;
	double s2;
	if (!kn_frame(o, &f))
		return 0;
	double s0 = fmax(v0, 0) * f.len, s1 = fmin(v1, 1) * f.len, sum = 0, du = u1 - u0;
	if (!(s1 > s0))
		return 0;
	double cap = shape_planar_scale(o, f.w);
	if (s0 < f.s1) { /* cap a: annular sector between radii s0 and min(s1, ca) */
		double r1 = fmin(s1, f.s1);
		sum += M_PI * du * (r1 - s0) * (r1 + s0) * cap;
	}
	if (s1 > f.s2) { /* cap b */
		double r0 = f.len - s1, r1 = f.len - fmax(s0, f.s2);
		sum += M_PI * du * (r1 - r0) * (r1 + r0) * cap;
	}
	double z0 = fmax(s0, f.s1), z1 = fmin(s1, f.s2);
	if (z1 > z0) { /* side */
		if (shape_similarity(o, &s2))
			sum += s2 * side_area(&f, du, (z0 - f.s1) / f.slant, (z1 - f.s1) / f.slant);
		else
			sum += shape_integrate_area(o, u0, u1, z0 / f.len, z1 / f.len);
	}
	return sum;
}

static void kn_dump(const struct object *o, FILE *out)
{
	fputs("base ", out), prim_dump_vec(out, o->g.cone.a), fprintf(out, " radius %.6g cap ", o->g.cone.ra);
	prim_dump_vec(out, o->g.cone.b), fprintf(out, " radius %.6g", o->g.cone.rb);
}

const struct prim_ops shape_cone_ops = {
	kn_intersect, kn_inside, kn_bounds, kn_uv_point, kn_uv_range, kn_cell_area, kn_dump, kn_occluded,
};
