/* SPDX-License-Identifier: MIT */
/* shape.c: dispatch from the scene's objects to the primitive files, the
 * object↔world conversions, and the area helpers the primitives share. */
#include "shape.h"

#include <math.h>

#include "shapes/prim.h"

/* The primitive table, indexed by enum object_kind (NULL for CSG kinds). */
static const struct prim_ops *const ops_of[OBJ_KIND_COUNT] = {
#define PRIM(n, w) [OBJ_##n] = &shape_##w##_ops,
#include "objects.def"
};

static const struct prim_ops *ops(const struct object *o)
{
	return (unsigned)o->kind < OBJ_KIND_COUNT ? ops_of[o->kind] : NULL;
}

/* ==== intersection ======================================================= */

/* The world ray expressed in the object's frame (same t): r itself when
 * the object has no transform, else *tmp. */
static inline const struct ray *local_ray(const struct object *o, const struct ray *r, struct ray *tmp)
{
	if (!o->xf) /* no transform: the world frame */
		return r;
	*tmp = (struct ray){xf_inv_point(o->xf, r->o), xf_inv_vector(o->xf, r->d)};
	return tmp;
}

/* Fills a world hit from a local one whose world normal, normalised, is
 * n (to_world's); without uv, (u,v) are NaN and the partials zero. Inline
 * in each caller: as a call it cost the light pass of
 * tests/accuracy/sphere.scn (1M rays) 44 M of its 1,946 M instructions. */
__attribute__((always_inline)) static inline void to_world_n(const struct object *o, const struct ray *r,
                                                             const struct local_hit *lh, bool uv, struct hit *h,
                                                             struct vec3 n)
{
	const struct xform *x = o->xf;
	if (o->flags & OF_INVERSE)
		n = v_neg(n);
	h->t = lh->t;
	h->p = x ? xf_point(x, lh->p) : lh->p;
	h->n = n;
	h->obj = o;
	h->entering = v_dot(r->d, n) < 0;
	if (!uv) {
		h->u = h->v = NAN;
		h->dpdu = h->dpdv = v3(0, 0, 0);
		return;
	}
	h->u = lh->u;
	h->v = lh->v;
	h->dpdu = x ? xf_vector(x, lh->dpdu) : lh->dpdu;
	h->dpdv = x ? xf_vector(x, lh->dpdv) : lh->dpdv;
}

__attribute__((always_inline)) static inline void to_world(const struct object *o, const struct ray *r,
                                                           const struct local_hit *lh, bool uv, struct hit *h)
{
	to_world_n(o, r, lh, uv, h, v_norm(o->xf ? xf_normal(o->xf, lh->n) : lh->n));
}

/* shape_intersect's steps; uv false: shape_intersect_bare's. */
static inline __attribute__((always_inline)) bool intersect_as(const struct object *o, const struct ray *r,
                                                               double tmin, double tmax, struct hit *h, bool uv)
{
	const struct prim_ops *p = ops(o);
	if (!p)
		return csg_is_csg(o) && csg_intersect(o, r, tmin, tmax, h);
	struct ray tmp;
	const struct ray *lr = local_ray(o, r, &tmp);
	struct local_hit lh;
	if (!(!uv && o->kind == OBJ_TORUS ? to_hit(o, lr, tmin, tmax, &lh) : p->intersect(o, lr, tmin, tmax, &lh)))
		return false;
	to_world(o, r, &lh, uv, h);
	return true;
}

bool shape_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                     struct hit *h)
{
	return intersect_as(o, r, tmin, tmax, h, true);
}

bool shape_intersect_bare(const struct object *o, const struct ray *r, double tmin, double tmax,
                          struct hit *h)
{
	return intersect_as(o, r, tmin, tmax, h, false);
}

bool shape_hit_t(const struct object *o, const struct ray *r, double tmin, double tmax, double *t)
{
	struct hit h;
	if (o->kind == OBJ_SPHERE || o->kind == OBJ_PLANE) {
		struct ray tmp;
		const struct ray *lr = local_ray(o, r, &tmp);
		return o->kind == OBJ_SPHERE ? sph_hit_t(o, lr, tmin, tmax, t) : pl_hit_t(o, lr, tmin, tmax, t);
	}
	if (!shape_intersect(o, r, tmin, tmax, &h))
		return false;
	*t = h.t;
	return true;
}

/* shape_hit_at for sphere o: through its frame, or with its (u,v). */
static __attribute__((noinline)) bool sphere_hit_at(const struct object *o, const struct ray *r, double t, bool uv,
                                                    struct hit *h)
{
	struct ray tmp;
	const struct ray *lr = local_ray(o, r, &tmp);
	struct local_hit lh;
	if (!(uv ? sph_hit_at(o, lr, t, true, &lh) : prim_sphere_at(o->g.sphere.c, o->g.sphere.r, lr, t, &lh)))
		return false; /* (without uv, the same point and normal inline) */
	to_world(o, r, &lh, uv, h);
	return true;
}

bool shape_hit_at(const struct object *o, const struct ray *r, double tmin, double tmax, double t,
                  bool uv, struct hit *h)
{
	if (o->kind != OBJ_SPHERE)
		return shape_intersect(o, r, tmin, tmax, h);
	if (o->xf || uv)
		return sphere_hit_at(o, r, t, uv, h);
	/* the common case without a frame or (u,v) (a light ray's, an eye
	 * ray's without a map): its small frame kept apart from the other's */
	struct local_hit lh;
	if (!prim_sphere_at(o->g.sphere.c, o->g.sphere.r, r, t, &lh))
		return false;
	to_world(o, r, &lh, false, h);
	return true;
}

bool shape_plane_hit_t(const struct object *o, const struct pl_prep *p, const struct ray *r, double tmin,
                       double tmax, double *t)
{
	struct ray tmp;
	const struct ray *lr = local_ray(o, r, &tmp);
	return pl_prep_hit_t(p, lr, tmin, tmax, t);
}

/* shape_plane_hit_at for plane o with a transform. */
static __attribute__((noinline)) void plane_hit_xf(const struct object *o, const struct pl_prep *p,
                                                   const struct ray *r, double t, bool uv, struct hit *h)
{
	struct ray tmp;
	const struct ray *lr = local_ray(o, r, &tmp);
	struct local_hit lh;
	pl_prep_hit(p, lr, t, &lh);
	to_world(o, r, &lh, uv, h);
}

void shape_plane_hit_at(const struct object *o, const struct pl_prep *p, const struct ray *r, double t, bool uv,
                        struct hit *h)
{
	if (o->xf) {
		plane_hit_xf(o, p, r, t, uv, h);
		return;
	}
	struct local_hit lh; /* without a transform (its small frame kept apart from the other's) */
	pl_prep_hit(p, r, t, &lh); /* (lh.n is p->n, whose v_norm is p->nw) */
	to_world_n(o, r, &lh, uv, h, p->nw);
}

bool shape_occluded(const struct object *o, const struct ray *r, double tmin, double tmax)
{
	const struct prim_ops *p = ops(o);
	struct hit h;
	double t;
	if (o->kind == OBJ_SPHERE)
		return shape_hit_t(o, r, tmin, tmax, &t);
	if (!p)
		return csg_is_csg(o) && csg_intersect(o, r, tmin, tmax, &h);
	struct ray tmp;
	const struct ray *lr = local_ray(o, r, &tmp);
	struct local_hit lh;
	return p->occluded ? p->occluded(o, lr, tmin, tmax) : p->intersect(o, lr, tmin, tmax, &lh);
}


bool shape_inside(const struct object *o, struct vec3 world_p)
{
	const struct prim_ops *p = ops(o);
	if (!p)
		return csg_is_csg(o) && csg_inside(o, world_p);
	bool in = p->inside(o, xf_inv_point(obj_xf(o), world_p));
	return (o->flags & OF_INVERSE) ? !in : in;
}

/* ==== bounds ============================================================= */

struct bbox shape_bounds(const struct object *o)
{
	const struct prim_ops *p = ops(o);
	if (!p)
		return csg_is_csg(o) ? csg_bounds(o) : bbox_empty();
	struct bbox b = p->bounds(o);
	if (!bbox_finite(b))
		return prim_infinite_box();
	return o->xf ? xf_bbox(o->xf, b) : b;
}

struct bbox shape_solid_bounds(const struct object *o)
{
	if (csg_is_csg(o))
		return csg_solid_bounds(o);
	if ((o->flags & OF_INVERSE) || o->kind == OBJ_PLANE)
		return prim_infinite_box();
	return shape_bounds(o);
}

bool shape_bounded(const struct object *o) { return bbox_finite(shape_bounds(o)); }

/* An upper bound on how far the linear part of a stretches a vector (its
 * largest singular value): the square root of a bound on the greatest
 * eigenvalue of AᵀA and of AAᵀ (the same eigenvalues), each its largest
 * absolute row sum (Gershgorin). Exact for a rotation with any scale
 * before or after it (one of the two products is then diagonal), which is
 * how scene files transform objects. */
static double xf_stretch(const struct xform *a)
{
	double s = 0, m[3][3]; /* the linear part over its largest entry: no squares under- or overflow */
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			s = fmax(s, fabs(a->m[i][j]));
	if (!(s > 0) || !isfinite(s))
		return s > 0 ? INFINITY : 0;
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			m[i][j] = a->m[i][j] / s;
	double best = INFINITY;
	for (int t = 0; t < 2; t++) {
		double most = 0;
		for (int i = 0; i < 3; i++) {
			double row = 0;
			for (int j = 0; j < 3; j++) {
				double b = 0;
				for (int k = 0; k < 3; k++)
					b += t ? m[i][k] * m[j][k] : m[k][i] * m[k][j];
				row += fabs(b);
			}
			most = fmax(most, row);
		}
		best = fmin(best, most);
	}
	return s * sqrt(best) * (1 + 1e-12); /* the sums' rounding */
}

bool shape_bsphere(const struct object *o, struct vec3 *c, double *r)
{
	struct bbox wb = shape_bounds(o);
	if (!bbox_finite(wb))
		return false;
	*c = bbox_centre(wb), *r = bbox_radius(wb);
	const struct prim_ops *p = ops(o);
	if (!p)
		return true;
	struct vec3 oc;
	double orr;
	if (o->kind == OBJ_SPHERE) {
		oc = o->g.sphere.c, orr = fabs(o->g.sphere.r);
	} else {
		struct bbox ob = p->bounds(o);
		oc = bbox_centre(ob), orr = bbox_radius(ob);
	}
	if (o->xf)
		oc = xf_point(o->xf, oc), orr *= xf_stretch(o->xf);
	if (orr < *r)
		*c = oc, *r = orr;
	return true;
}

bool shape_dump(const struct object *o, FILE *out)
{
	const struct prim_ops *ps = ops(o);
	if (!ps)
		return false;
	ps->dump(o, out);
	return true;
}

/* ==== parametrisation ===================================================== */

bool shape_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                    struct vec3 *dpdu, struct vec3 *dpdv)
{
	const struct prim_ops *ps = ops(o);
	struct vec3 lp, lu, lv;
	if (!ps || !ps->uv_point || !ps->uv_point(o, u, v, &lp, &lu, &lv))
		return false;
	if (p)
		*p = xf_point(obj_xf(o), lp);
	if (dpdu)
		*dpdu = xf_vector(obj_xf(o), lu);
	if (dpdv)
		*dpdv = xf_vector(obj_xf(o), lv);
	return true;
}

bool shape_uv_range(const struct object *o, struct uv_range *out)
{
	const struct prim_ops *p = ops(o);
	if (!p || !p->uv_range) /* a surface without a parametrisation (isosurface) */
		return false;
	*out = p->uv_range(o);
	return true;
}

double shape_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	const struct prim_ops *p = ops(o);
	if (!p || !p->cell_area || !(u1 > u0) || !(v1 > v0))
		return 0;
	return p->cell_area(o, u0, u1, v0, v1);
}

double shape_area(const struct object *o)
{
	struct uv_range d;
	if (!shape_uv_range(o, &d))
		return 0;
	if (!d.bounded)
		return INFINITY;
	return shape_cell_area(o, d.u0, d.u1, d.v0, d.v1);
}

/* ==== helpers for the primitives ========================================= */

bool shape_similarity(const struct object *o, double *area_scale)
{
	const double(*m)[4] = obj_xf(o)->m;
	double g[3][3];
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			g[i][j] = m[0][i] * m[0][j] + m[1][i] * m[1][j] + m[2][i] * m[2][j];
	double s2 = (g[0][0] + g[1][1] + g[2][2]) / 3, tol = 1e-13 * s2;
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			if (fabs(g[i][j] - (i == j ? s2 : 0)) > tol)
				return false;
	*area_scale = s2;
	return true;
}

void shape_basis(struct vec3 w, struct vec3 *e1, struct vec3 *e2)
{
	struct vec3 a = fabs(w.x) < 0.9 ? v3(1, 0, 0) : v3(0, 0, 1);
	*e1 = v_norm(v_madd(a, w, -v_dot(a, w)));
	*e2 = v_cross(w, *e1);
}

double shape_planar_scale(const struct object *o, struct vec3 n)
{
	struct vec3 t1, t2;
	shape_basis(v_norm(n), &t1, &t2);
	return v_len(v_cross(xf_vector(obj_xf(o), t1), xf_vector(obj_xf(o), t2)));
}

/* Gauss–Legendre nodes and weights on [-1,1], 5 and 7 points. */
static const double gl5_x[5] = {-0.9061798459386640, -0.5384693101056831, 0,
                                0.5384693101056831, 0.9061798459386640};
static const double gl5_w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                0.4786286704993665, 0.2369268850561891};
static const double gl7_x[7] = {-0.9491079123427585, -0.7415311855993945, -0.4058451513773972,
                                0, 0.4058451513773972, 0.7415311855993945, 0.9491079123427585};
static const double gl7_w[7] = {0.1294849661688697, 0.2797053914892767, 0.3818300505051189,
                                0.4179591836734694, 0.3818300505051189, 0.2797053914892767,
                                0.1294849661688697};

/* ‖∂T/∂u × ∂T/∂v‖ in the world at (u,v). */
static double jacobian(const struct object *o, double u, double v)
{
	struct vec3 du, dv;
	if (!shape_uv_point(o, u, v, NULL, &du, &dv))
		return 0;
	return v_len(v_cross(du, dv));
}

/* Tensor Gauss–Legendre rule with n points per axis over the cell. */
static double gl_rule(const struct object *o, int n, const double *x, const double *w,
                      double u0, double u1, double v0, double v1)
{
	double hu = 0.5 * (u1 - u0), hv = 0.5 * (v1 - v0), mu = u0 + hu, mv = v0 + hv, s = 0;
	for (int i = 0; i < n; i++)
		for (int j = 0; j < n; j++)
			s += w[i] * w[j] * jacobian(o, mu + hu * x[i], mv + hv * x[j]);
	return s * hu * hv;
}

/* Adaptive cubature: accept the 7-point result where it agrees with the
 * 5-point one, else split the cell in four (depth-limited). */
static double adapt(const struct object *o, double u0, double u1, double v0, double v1,
                    int depth)
{
	double a7 = gl_rule(o, 7, gl7_x, gl7_w, u0, u1, v0, v1);
	double a5 = gl_rule(o, 5, gl5_x, gl5_w, u0, u1, v0, v1);
	if (fabs(a7 - a5) <= 1e-12 * fabs(a7) || depth >= 8)
		return a7;
	double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
	return adapt(o, u0, um, v0, vm, depth + 1) + adapt(o, um, u1, v0, vm, depth + 1) +
	       adapt(o, u0, um, vm, v1, depth + 1) + adapt(o, um, u1, vm, v1, depth + 1);
}

double shape_integrate_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	if (!(u1 > u0) || !(v1 > v0))
		return 0;
	return adapt(o, u0, u1, v0, v1, 0);
}

/* ==== radial parametrisation of implicit surfaces ======================== */

/* The direction of (u,v) and its partials. */
static struct vec3 radial_dir(double u, double v, struct vec3 *wu, struct vec3 *wv)
{
	double ph = 2 * M_PI * u, th = M_PI * v, sp = sin(ph), cp = cos(ph), st = sin(th), ct = cos(th);
	*wu = v3(-2 * M_PI * st * sp, 0, -2 * M_PI * st * cp);
	*wv = v3(M_PI * ct * cp, M_PI * st, -M_PI * ct * sp);
	return v3(st * cp, -ct, -st * sp);
}

/* The partials of T = c + ρ(u,v)·w(u,v) on the surface with normal n:
 * ∂ρ/∂u = −ρ (n·∂w/∂u)/(n·w) keeps T on the surface. */
static bool radial_partials(struct vec3 n, double rho, struct vec3 w, struct vec3 wu,
                            struct vec3 wv, struct vec3 *dpdu, struct vec3 *dpdv)
{
	double nw = v_dot(n, w);
	if (!(fabs(nw) > 1e-9 * v_len(n)))
		return false;
	struct vec3 tu = v_scale(wu, rho), tv = v_scale(wv, rho);
	if (dpdu)
		*dpdu = v_madd(tu, w, -v_dot(n, tu) / nw);
	if (dpdv)
		*dpdv = v_madd(tv, w, -v_dot(n, tv) / nw);
	return true;
}

void prim_radial_hit(struct vec3 c, struct local_hit *lh)
{
	struct vec3 q = v_sub(lh->p, c), wu, wv;
	double rho = v_len(q);
	lh->u = prim_turns(-q.z, q.x);
	lh->v = atan2(sqrt(q.x * q.x + q.z * q.z), -q.y) / M_PI;
	struct vec3 w = radial_dir(lh->u, lh->v, &wu, &wv);
	if (!(rho > 0) || !radial_partials(lh->n, rho, w, wu, wv, &lh->dpdu, &lh->dpdv)) {
		/* at c itself, or seen edge-on from c: the sphere's partials */
		lh->dpdu = v_scale(wu, rho);
		lh->dpdv = v_scale(wv, rho);
	}
}

bool prim_radial_point(const struct object *o, struct vec3 c,
                       bool (*intersect)(const struct object *, const struct ray *, double,
                                         double, struct local_hit *),
                       double u, double v, struct vec3 *p, struct vec3 *dpdu, struct vec3 *dpdv)
{
	struct vec3 wu, wv, w = radial_dir(u, v, &wu, &wv);
	struct ray r = {c, w};
	struct local_hit lh;
	if (!intersect(o, &r, 0, INFINITY, &lh))
		return false;
	if (!radial_partials(lh.n, lh.t, w, wu, wv, dpdu, dpdv))
		return false;
	if (p)
		*p = lh.p;
	return true;
}
