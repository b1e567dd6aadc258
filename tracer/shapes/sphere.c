/* SPDX-License-Identifier: MIT */
/* sphere.c: sphere { c, r }.
 *
 * Parametrisation (object frame), φ = 2πu, θ = πv, (u,v) ∈ [0,1]²:
 *
 *     T(u,v) = c + r·(sinθ cosφ, −cosθ, −sinθ sinφ)
 *
 * v = 0 is the south pole (c − r·y), v = 1 the north pole; u = 0 is the
 * half-meridian through +x, and u grows from +x towards −z (counter-clockwise
 * seen from +y). u wraps (seam at u = 0 ≡ 1).
 *
 *     ∂T/∂u = 2πr·sinθ·(−sinφ, 0, −cosφ)
 *     ∂T/∂v = πr·(cosθ cosφ, sinθ, −cosθ sinφ)
 *     ∂T/∂u × ∂T/∂v = 2π²r²·sinθ·n̂      (outward; 0 at both poles)
 *
 * Cell area: 2πr²·(u1−u0)·(cos πv0 − cos πv1), finite at the poles (a pole
 * cell is a spherical cap zone). Under a non-uniform scale the area is
 * integrated numerically (the integrand stays smooth). */
#include <math.h>

#include "prim.h"

#define S_C(o) ((o)->g.sphere.c)
#define S_R(o) ((o)->g.sphere.r)

static bool sph_uv_point(const struct object *o, double u, double v, struct vec3 *p,
                         struct vec3 *dpdu, struct vec3 *dpdv)
{
	double r = S_R(o), phi = 2 * M_PI * u, th = M_PI * v;
	double sp = sin(phi), cp = cos(phi), st = sin(th), ct = cos(th);
	if (!(r > 0))
		return false;
	if (p)
		*p = v_add(S_C(o), v3(r * st * cp, -r * ct, -r * st * sp));
	if (dpdu)
		*dpdu = v3(-2 * M_PI * r * st * sp, 0, -2 * M_PI * r * st * cp);
	if (dpdv)
		*dpdv = v3(M_PI * r * ct * cp, M_PI * r * st, -M_PI * r * ct * sp);
	return true;
}

/* (u,v) of a point q = (p − c)/r on the unit sphere; atan2 keeps θ accurate
 * near the poles, where acos would not be. */
static void sph_uv(struct vec3 q, double *u, double *v)
{
	*u = prim_turns(-q.z, q.x);
	*v = atan2(sqrt(q.x * q.x + q.z * q.z), -q.y) / M_PI;
}

/* The nearer root in range (tmin < t < tmax). */
bool sph_hit_t(const struct object *o, const struct ray *r, double tmin, double tmax, double *t)
{
	return prim_sphere_t(S_C(o), S_R(o), r, tmin, tmax, t);
}

/* The hit at root t (as sph_hit_t found it): the point projected back onto
 * the sphere and the normal; with uv, its (u,v) and partials too. */
bool sph_hit_at(const struct object *o, const struct ray *r, double t, bool uv, struct local_hit *lh)
{
	if (!prim_sphere_at(S_C(o), S_R(o), r, t, lh))
		return false;
	if (!uv)
		return true;
	sph_uv(lh->n, &lh->u, &lh->v);
	return sph_uv_point(o, lh->u, lh->v, NULL, &lh->dpdu, &lh->dpdv);
}

/* The nearer root in range, in full. */
static bool sph_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                          struct local_hit *lh)
{
	double t;
	return sph_hit_t(o, r, tmin, tmax, &t) && sph_hit_at(o, r, t, true, lh);
}

static bool sph_inside(const struct object *o, struct vec3 p)
{
	struct vec3 f = v_sub(p, S_C(o));
	return v_dot(f, f) < S_R(o) * S_R(o);
}

static struct bbox sph_bounds(const struct object *o)
{
	double r = fabs(S_R(o));
	return (struct bbox){v_sub(S_C(o), v3(r, r, r)), v_add(S_C(o), v3(r, r, r))};
}

static struct uv_range sph_uv_range(const struct object *o)
{
	(void)o;
	return (struct uv_range){0, 1, 0, 1, true, true, false};
}

/* cos πa − cos πb, written as a product so small cells near the poles keep
 * their precision. */
static double cos_diff(double a, double b)
{
	return 2 * sin(M_PI * 0.5 * (a + b)) * sin(M_PI * 0.5 * (b - a));
}

/* Closed form under similarities (v clipped to [0,1], u left periodic). */
static double sph_cell_area(const struct object *o, double u0, double u1, double v0, double v1)
{
	double s2;
	v0 = fmax(v0, 0);
	v1 = fmin(v1, 1);
	if (!(v1 > v0) || !(S_R(o) > 0))
		return 0;
	if (!shape_similarity(o, &s2))
		return shape_integrate_area(o, u0, u1, v0, v1);
	return s2 * 2 * M_PI * S_R(o) * S_R(o) * (u1 - u0) * cos_diff(v0, v1);
}

static void sph_dump(const struct object *o, FILE *out)
{
	fputs("center ", out), prim_dump_vec(out, o->g.sphere.c), fprintf(out, " radius %.6g", o->g.sphere.r);
}

const struct prim_ops shape_sphere_ops = {
	sph_intersect, sph_inside, sph_bounds, sph_uv_point, sph_uv_range, sph_cell_area, sph_dump, NULL,
};
