/* SPDX-License-Identifier: MIT */
/* test_shapes.c: geometric property tests of the primitives (tracer/shape.h):
 * known hits, no re-hit of convex shapes from their own surface under random
 * transforms, (u,v) → point → (u,v) round trips through intersection,
 * partials against finite differences, cell areas against analytic areas,
 * torus hit accuracy at grazing incidence and from far away, the torus's
 * hits bit for bit as a plain quartic solver finds them, and shadow
 * tests that agree with intersection. Every
 * random test uses fixed seeds (geo_rand.h). */
#include <stdio.h>
#include <string.h>

#include "geo_rand.h"
#include "test.h"

static const enum object_kind all_kinds[] = {OBJ_SPHERE, OBJ_PLANE,  OBJ_BOX,   OBJ_DISC,
                                             OBJ_CYLINDER, OBJ_CONE, OBJ_TORUS, OBJ_TRIANGLE};
static const enum object_kind convex_kinds[] = {OBJ_SPHERE,   OBJ_PLANE, OBJ_BOX,     OBJ_DISC,
                                                OBJ_CYLINDER, OBJ_CONE,  OBJ_TRIANGLE};
#define NKINDS(a) ((int)(sizeof(a) / sizeof(a[0])))

static bool is_flat(enum object_kind k) { return k == OBJ_PLANE || k == OBJ_DISC || k == OBJ_TRIANGLE; }

static double dist(struct vec3 a, struct vec3 b) { return v_len(v_sub(a, b)); }

/* ==== known values ======================================================= */

static void t_sphere_known(void)
{
	struct object o = mk_obj(OBJ_SPHERE);
	o.g.sphere.c = v3(1, 2, 3);
	o.g.sphere.r = 2;
	struct ray r = {v3(1, 2, -7), v3(0, 0, 1)};
	struct hit h;
	CHECK(shape_intersect(&o, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 8, 1e-12);
	CHECK_NEAR(h.n.z, -1, 1e-12);
	CHECK(h.entering);
	CHECK(h.obj == &o);
	/* (0,0,−1) relative: θ = π/2, φ = π/2 (T's z is −sinθ sinφ) */
	CHECK_NEAR(h.u, 0.25, 1e-12);
	CHECK_NEAR(h.v, 0.5, 1e-12);
	CHECK(shape_intersect(&o, &r, 8.5, INFINITY, &h));
	CHECK_NEAR(h.t, 12, 1e-12);
	CHECK(!h.entering);
	CHECK(!shape_intersect(&o, &r, 0, 7.9, &h));
	CHECK(shape_inside(&o, v3(1, 2, 3)));
	CHECK(!shape_inside(&o, v3(1, 2, 5.01)));
	CHECK_NEAR(shape_area(&o), 16 * M_PI, 1e-12);
	o.flags |= OF_INVERSE;
	CHECK(!shape_inside(&o, v3(1, 2, 3)));
	CHECK(shape_intersect(&o, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.n.z, 1, 1e-12);
	CHECK(!h.entering);
}

static void t_plane_box_known(void)
{
	struct object p = mk_obj(OBJ_PLANE);
	p.g.plane.n = v3(0, 2, 0); /* not unit: plane y = 0.5 */
	p.g.plane.d = 1;
	struct ray r = {v3(3, 5, -2), v3(0, -1, 0)};
	struct hit h;
	CHECK(shape_intersect(&p, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 4.5, 1e-12);
	CHECK_NEAR(h.n.y, 1, 1e-15);
	CHECK_NEAR(h.u, 3, 1e-12);  /* u = x */
	CHECK_NEAR(h.v, 2, 1e-12);  /* v = −z */
	CHECK(shape_inside(&p, v3(0, 0, 0)));
	CHECK(!shape_bounded(&p));
	CHECK_NEAR(shape_cell_area(&p, 0, 2, 0, 3), 6, 1e-12);

	struct object b = mk_obj(OBJ_BOX);
	b.g.box.lo = v3(1, 1, 1); /* corners given swapped on purpose */
	b.g.box.hi = v3(-1, -2, -3);
	struct ray rb = {v3(-5, 0, 0), v3(2, 0, 0)};
	CHECK(shape_intersect(&b, &rb, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 2, 1e-12);
	CHECK_NEAR(h.n.x, -1, 1e-15);
	/* −x face: u ∈ [0,⅓], v ∈ [0,½]; at y = 0, z = 0: s = 1 − (0+2)/3, w = (0+3)/4 */
	CHECK_NEAR(h.u, (1 - 2.0 / 3) / 3, 1e-12);
	CHECK_NEAR(h.v, 0.75 / 2, 1e-12);
	CHECK_NEAR(shape_area(&b), 2 * (2 * 3 + 3 * 4 + 4 * 2), 1e-12);
	CHECK(shape_inside(&b, v3(0.5, -1.5, -2.5)));
	CHECK(!shape_inside(&b, v3(0.5, -1.5, -3.5)));
}

static void t_round_shapes_known(void)
{
	struct hit h;
	struct object c = mk_obj(OBJ_CYLINDER);
	c.g.cylinder.a = v3(0, 0, 0);
	c.g.cylinder.b = v3(0, 2, 0);
	c.g.cylinder.r = 1;
	struct ray r = {v3(0, 5, 0.5), v3(0, -1, 0)};
	CHECK(shape_intersect(&c, &r, 0, INFINITY, &h)); /* top cap */
	CHECK_NEAR(h.t, 3, 1e-12);
	CHECK_NEAR(h.n.y, 1, 1e-15);
	CHECK_NEAR(h.v, (1 + 2 + 0.5) / 4, 1e-12);
	c.flags |= OF_OPEN;
	struct ray rs = {v3(-5, 1, 0), v3(1, 0, 0)};
	CHECK(shape_intersect(&c, &rs, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 4, 1e-12);
	CHECK_NEAR(h.v, 0.5, 1e-12);
	CHECK(!shape_intersect(&c, &r, 0, INFINITY, &h)); /* straight down the open tube */

	struct object k = mk_obj(OBJ_CONE);
	k.g.cone.a = v3(0, 0, 0);
	k.g.cone.b = v3(0, 1, 0);
	k.g.cone.ra = 1;
	k.g.cone.rb = 0;
	struct ray rk = {v3(-5, 0.5, 0), v3(1, 0, 0)};
	CHECK(shape_intersect(&k, &rk, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 4.5, 1e-12);
	CHECK_NEAR(h.n.x, -M_SQRT1_2, 1e-12);
	CHECK_NEAR(h.n.y, M_SQRT1_2, 1e-12);
	CHECK_NEAR(shape_area(&k), M_PI * M_SQRT2 + M_PI, 1e-12);

	struct object d = mk_obj(OBJ_DISC);
	d.g.disc.c = v3(0, 0, 1);
	d.g.disc.n = v3(0, 0, -3);
	d.g.disc.r = 2;
	d.g.disc.hole = 1;
	struct ray rd = {v3(1.5, 0, 5), v3(0, 0, -1)};
	CHECK(shape_intersect(&d, &rd, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 4, 1e-12);
	CHECK_NEAR(h.n.z, -1, 1e-15);
	CHECK(!h.entering);
	CHECK_NEAR(h.v, 0.5, 1e-12);
	rd.o.x = 0.5; /* through the hole */
	CHECK(!shape_intersect(&d, &rd, 0, INFINITY, &h));
	CHECK_NEAR(shape_area(&d), 3 * M_PI, 1e-12);

	struct object t = mk_obj(OBJ_TRIANGLE);
	t.g.triangle.p[0] = v3(0, 0, 0);
	t.g.triangle.p[1] = v3(2, 0, 0);
	t.g.triangle.p[2] = v3(0, 2, 0);
	struct ray rt = {v3(0.5, 0.25, 3), v3(0, 0, -1)};
	CHECK(shape_intersect(&t, &rt, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 3, 1e-15);
	CHECK_NEAR(h.u, 0.25, 1e-15);
	CHECK_NEAR(h.v, 0.125, 1e-15);
	CHECK_NEAR(h.n.z, 1, 1e-15);
	CHECK_NEAR(shape_area(&t), 2, 1e-15);
}

/* ==== (1) no re-hit from the surface ====================================== */

/* A random point on the surface (away from seams and edges). */
static struct vec3 surface_point(const struct object *o)
{
	struct uv_range d;
	struct vec3 p = v3(0, 0, 0);
	shape_uv_range(o, &d);
	double u = d.bounded ? rndr(0.01, 0.99) : rndr(-5, 5), v = d.bounded ? rndr(0.01, 0.99) : rndr(-5, 5);
	if (o->kind == OBJ_TRIANGLE)
		while (u + v > 0.98)
			u = rndr(0.01, 0.98), v = rndr(0.01, 0.98);
	shape_uv_point(o, u, v, &p, NULL, NULL);
	return p;
}

/* A direction in the hemisphere about n, at least ~1e-3 from the tangent
 * plane (both sides when two_sided). Returns false when unlucky. */
static bool away_dir(struct vec3 n, bool two_sided, struct vec3 *d)
{
	*d = rnd_dir();
	double c = v_dot(*d, n);
	if (fabs(c) < 1e-3)
		return false;
	if (c < 0 && !two_sided)
		*d = v_madd(*d, n, -2 * c);
	return true;
}

/* Spawns rays off hit h of o; returns how many re-hit o. */
static int spawn_from(const struct object *o, const struct hit *h, double eps, int *tries)
{
	int fails = 0;
	for (int j = 0; j < 8; j++) {
		struct vec3 d;
		if (!away_dir(h->n, is_flat(o->kind), &d))
			continue;
		struct ray s = {h->p, d};
		struct hit h2;
		(*tries)++;
		if (shape_intersect(o, &s, eps, INFINITY, &h2)) {
			if (fails++ == 0)
				printf("#   kind %d re-hit at t=%g (cos %g)\n", o->kind, h2.t, v_dot(d, h->n));
		}
	}
	return fails;
}

static void t_no_rehit_convex(void)
{
	rng_seed(1);
	for (int k = 0; k < NKINDS(convex_kinds); k++) {
		int fails = 0, tries = 0;
		for (int i = 0; i < 400; i++) {
			struct object o = rnd_prim(convex_kinds[k], false);
			o.xf = xf_keep(rnd_xform(i % 4 == 0, true));
			double sc = obj_scale(&o), eps = 1e-9 * sc;
			struct vec3 q = surface_point(&o);
			struct ray r = {v_madd(q, rnd_dir(), 2 * sc), v3(0, 0, 0)};
			r.d = v_norm(v_sub(q, r.o));
			struct hit h, h2;
			if (!shape_intersect(&o, &r, 0, INFINITY, &h))
				continue;
			fails += spawn_from(&o, &h, eps, &tries);
			/* and off the exit point of solids, from inside */
			struct ray in = {h.p, r.d};
			if (!is_flat(o.kind) && shape_intersect(&o, &in, eps, INFINITY, &h2))
				fails += spawn_from(&o, &h2, eps, &tries);
		}
		printf("# kind %d: %d re-hits in %d rays\n", convex_kinds[k], fails, tries);
		CHECK(fails == 0);
		CHECK(tries > 2000);
	}
}

/* ==== (2) uv → point → uv ================================================= */

/* Seams of the cylinder/cone meridian layout (docs/parametrisations.md). */
static int seams(const struct object *o, double s[2])
{
	bool caps = !(o->flags & OF_OPEN);
	double ca, cb, side;
	if (o->kind == OBJ_CYLINDER) {
		ca = cb = caps ? o->g.cylinder.r : 0;
		side = v_len(v_sub(o->g.cylinder.b, o->g.cylinder.a));
	} else if (o->kind == OBJ_CONE) {
		ca = caps ? o->g.cone.ra : 0;
		cb = caps ? o->g.cone.rb : 0;
		side = hypot(v_len(v_sub(o->g.cone.b, o->g.cone.a)), o->g.cone.rb - o->g.cone.ra);
	} else {
		return 0;
	}
	double len = ca + side + cb;
	s[0] = ca / len;
	s[1] = (ca + side) / len;
	return 2;
}

/* A random (u,v) at least `m` from every seam, edge and pole. */
static void rnd_uv(const struct object *o, double m, double *u, double *v)
{
	double s[2];
	int ns = seams(o, s);
	for (;;) {
		if (o->kind == OBJ_PLANE) {
			*u = rndr(-10, 10), *v = rndr(-10, 10);
			return;
		}
		*u = rndr(m, 1 - m), *v = rndr(m, 1 - m);
		if (o->kind == OBJ_TRIANGLE && *u + *v > 1 - m)
			continue;
		if (o->kind == OBJ_BOX) { /* keep off the atlas' face boundaries */
			double fu = 3 * *u - floor(3 * *u), fv = 2 * *v - floor(2 * *v);
			if (fu < m || fu > 1 - m || fv < m || fv > 1 - m)
				continue;
		}
		bool near = false;
		for (int i = 0; i < ns; i++)
			near |= fabs(*v - s[i]) < m;
		if (!near)
			return;
	}
}

/* One round trip; returns false (and reports) on a mismatch. */
static bool round_trip(const struct object *o, double u, double v)
{
	struct vec3 p, du, dv;
	CHECK(shape_uv_point(o, u, v, &p, &du, &dv));
	struct vec3 cr = v_cross(du, dv), n = v_norm(cr);
	double sc = obj_scale(o);
	struct ray r = {v_madd(p, n, 1e-4 * sc), v_neg(n)};
	struct hit h;
	if (!shape_intersect(o, &r, 0, INFINITY, &h)) {
		printf("#   kind %d: no hit at uv (%.6f, %.6f)\n", o->kind, u, v);
		return false;
	}
	double orient = v_dot(h.n, cr) * xf_det(obj_xf(o));
	bool ok = fabs(h.u - u) < 1e-9 && fabs(h.v - v) < 1e-9 && dist(h.p, p) < 1e-9 * sc &&
	          orient > 0 && fabs(fabs(v_dot(h.n, n)) - 1) < 1e-9 &&
	          dist(h.dpdu, du) < 1e-7 * v_len(du) && dist(h.dpdv, dv) < 1e-7 * v_len(dv);
	if (!ok)
		printf("#   kind %d: uv (%.12f, %.12f) -> (%.12f, %.12f), |dp| %g, orient %g\n", o->kind,
		       u, v, h.u, h.v, dist(h.p, p), orient);
	return ok;
}

static void t_uv_round_trip(void)
{
	rng_seed(2);
	for (int k = 0; k < NKINDS(all_kinds); k++) {
		int bad = 0;
		for (int i = 0; i < 600; i++) {
			struct object o = rnd_prim(all_kinds[k], i % 3 == 1);
			o.xf = xf_keep(rnd_xform(i % 4 == 0, true));
			double u, v;
			rnd_uv(&o, 0.01, &u, &v);
			bad += !round_trip(&o, u, v);
		}
		CHECK(bad == 0);
	}
}

/* ==== (3) partials against finite differences ============================= */

/* Relative disagreement of the analytic partial a with the central
 * difference of T along (eu,ev) with step h. */
static double fd_error(const struct object *o, double u, double v, double eu, double ev,
                       double h, struct vec3 a)
{
	struct vec3 p1, p0;
	shape_uv_point(o, u + eu * h, v + ev * h, &p1, NULL, NULL);
	shape_uv_point(o, u - eu * h, v - ev * h, &p0, NULL, NULL);
	struct vec3 fd = v_scale(v_sub(p1, p0), 0.5 / h);
	return dist(fd, a) / (v_len(a) + 1e-6 * obj_scale(o));
}

static void t_partials_fd(void)
{
	rng_seed(3);
	for (int k = 0; k < NKINDS(all_kinds); k++) {
		double worst = 0;
		for (int i = 0; i < 500; i++) {
			struct object o = rnd_prim(all_kinds[k], i % 3 == 1);
			o.xf = xf_keep(rnd_xform(false, true));
			double u, v, h = o.kind == OBJ_PLANE ? 1e-4 : 1e-6;
			struct vec3 p, du, dv;
			rnd_uv(&o, 0.01, &u, &v);
			shape_uv_point(&o, u, v, &p, &du, &dv);
			worst = fmax(worst, fd_error(&o, u, v, 1, 0, h, du));
			worst = fmax(worst, fd_error(&o, u, v, 0, 1, h, dv));
		}
		printf("# kind %d: worst relative partial error %.3g\n", all_kinds[k], worst);
		CHECK(worst < 1e-5);
	}
}

/* ==== (4) cell areas ====================================================== */

/* Σ of shape_cell_area over an nu×nv grid on [u0,u1]×[v0,v1]. */
static double grid_sum(const struct object *o, int nu, int nv, double u0, double u1, double v0,
                       double v1)
{
	double s = 0;
	for (int i = 0; i < nu; i++)
		for (int j = 0; j < nv; j++)
			s += shape_cell_area(o, u0 + (u1 - u0) * i / nu, u0 + (u1 - u0) * (i + 1) / nu,
			                     v0 + (v1 - v0) * j / nv, v0 + (v1 - v0) * (j + 1) / nv);
	return s;
}

#define CHECK_REL(a, b, rel) CHECK_NEAR((a) / (b), 1.0, rel)

static void t_cell_area_totals(void)
{
	rng_seed(4);
	struct xform sim = xf_then(xf_then(xf_scale(v3(1.7, 1.7, 1.7)), xf_rotate(v3(10, 20, 30))),
	                           xf_translate(v3(1, 2, 3)));
	double s2 = 1.7 * 1.7;
	struct object o = mk_obj(OBJ_SPHERE);
	o.g.sphere.r = 1.3;
	o.xf = xf_keep(sim);
	CHECK_REL(grid_sum(&o, 37, 23, 0, 1, 0, 1), 4 * M_PI * 1.69 * s2, 1e-12);

	o = mk_obj(OBJ_BOX); /* grid lines do not follow the face blocks */
	o.g.box.lo = v3(0, 0, 0), o.g.box.hi = v3(1, 2, 3);
	o.xf = xf_keep(xf_then(xf_scale(v3(2, 3, 0.5)), xf_rotate(v3(30, 0, 60)))); /* non-uniform: exact */
	CHECK_REL(grid_sum(&o, 7, 5, 0, 1, 0, 1), 2 * (2 * 6 + 6 * 1.5 + 1.5 * 2), 1e-12);

	o = mk_obj(OBJ_CYLINDER);
	o.g.cylinder.a = v3(0, -1, 0), o.g.cylinder.b = v3(0, 1, 0), o.g.cylinder.r = 0.5;
	o.xf = xf_keep(sim);
	CHECK_REL(grid_sum(&o, 9, 13, 0, 1, 0, 1), (2 * M_PI * 0.5 * 2 + 2 * M_PI * 0.25) * s2, 1e-12);
	o.xf = xf_keep(xf_scale(v3(1, 3, 1))); /* stretched along the axis: the side goes numeric */
	CHECK_REL(grid_sum(&o, 9, 13, 0, 1, 0, 1), 2 * M_PI * 0.5 * 6 + 2 * M_PI * 0.25, 1e-9);
	o.flags |= OF_OPEN;
	CHECK_REL(grid_sum(&o, 9, 13, 0, 1, 0, 1), 2 * M_PI * 0.5 * 6, 1e-9);

	o = mk_obj(OBJ_CONE);
	o.g.cone.a = v3(0, 0, 0), o.g.cone.b = v3(0, 0, 2), o.g.cone.ra = 1, o.g.cone.rb = 0.25;
	o.xf = xf_keep(sim);
	double slant = hypot(2, 0.75);
	CHECK_REL(grid_sum(&o, 11, 17, 0, 1, 0, 1), (M_PI * 1.25 * slant + M_PI * (1 + 0.0625)) * s2,
	          1e-12);

	o = mk_obj(OBJ_TORUS);
	o.g.torus.major = 2, o.g.torus.minor = 0.5;
	o.xf = xf_keep(sim);
	CHECK_REL(grid_sum(&o, 13, 11, 0, 1, 0, 1), 4 * M_PI * M_PI * 2 * 0.5 * s2, 1e-12);
	o.g.torus.major = 0.5, o.g.torus.minor = 1; /* spindle: |R + r cosθ| */
	double ta = acos(-0.5);
	CHECK_REL(grid_sum(&o, 13, 11, 0, 1, 0, 1),
	          2 * M_PI * 1 * (4 * 0.5 * ta - 2 * M_PI * 0.5 + 4 * sin(ta)) * s2, 1e-12);

	o = mk_obj(OBJ_DISC);
	o.g.disc.n = v3(0, 1, 0), o.g.disc.r = 2, o.g.disc.hole = 0.5;
	o.xf = xf_keep(xf_scale(v3(3, 7, 0.5)));
	CHECK_REL(grid_sum(&o, 10, 10, 0, 1, 0, 1), M_PI * (4 - 0.25) * 1.5, 1e-12);

	o = mk_obj(OBJ_TRIANGLE);
	o.g.triangle.p[1] = v3(1, 0, 0), o.g.triangle.p[2] = v3(0, 1, 0);
	o.xf = xf_keep(xf_scale(v3(2, 3, 5)));
	CHECK_REL(grid_sum(&o, 7, 9, 0, 1, 0, 1), 3, 1e-12);
	CHECK_NEAR(shape_cell_area(&o, 0.6, 0.9, 0.6, 0.9), 0, 0); /* beyond u + v = 1 */

	o = mk_obj(OBJ_PLANE);
	o.g.plane.n = v3(0, 0, 1);
	o.xf = xf_keep(xf_scale(v3(2, 3, 5)));
	CHECK_REL(grid_sum(&o, 4, 4, -1, 1, -2, 2), 8 * 6, 1e-12);
}

/* Spheroids (a sphere scaled along its polar axis, y) take the numeric path. */
static void t_cell_area_spheroid(void)
{
	struct object o = mk_obj(OBJ_SPHERE);
	o.g.sphere.r = 1;
	double a = 1.5, c = 3, e = sqrt(1 - a * a / (c * c));
	o.xf = xf_keep(xf_then(xf_scale(v3(a, c, a)), xf_rotate(v3(20, 40, 60))));
	double prolate = 2 * M_PI * a * a * (1 + c / (a * e) * asin(e));
	CHECK_REL(grid_sum(&o, 16, 16, 0, 1, 0, 1), prolate, 1e-9);
	CHECK_REL(shape_area(&o), prolate, 1e-9);
	c = 0.5, e = sqrt(1 - c * c / (a * a));
	o.xf = xf_keep(xf_scale(v3(a, c, a)));
	double oblate = 2 * M_PI * a * a * (1 + (1 - e * e) / e * atanh(e));
	CHECK_REL(grid_sum(&o, 16, 16, 0, 1, 0, 1), oblate, 1e-9);
	/* pole cells are finite and add up */
	double cap = shape_cell_area(&o, 0, 1, 0, 1.0 / 64), parts = 0;
	for (int i = 0; i < 8; i++)
		parts += shape_cell_area(&o, i / 8.0, (i + 1) / 8.0, 0, 1.0 / 64);
	CHECK(isfinite(cap) && cap > 0);
	CHECK_REL(parts, cap, 1e-10);
}

/* Pole, apex and centre cells: finite, equal to the analytic cap or zone. */
static void t_cell_area_singular(void)
{
	struct object o = mk_obj(OBJ_SPHERE);
	o.g.sphere.r = 2;
	for (int n = 4; n <= 4096; n *= 8) {
		double dv = 1.0 / n, cap = 2 * M_PI * 4 * 2 * pow(sin(M_PI * dv / 2), 2);
		double south = shape_cell_area(&o, 0, 1, 0, dv), north = shape_cell_area(&o, 0, 1, 1 - dv, 1);
		CHECK(isfinite(south) && south > 0);
		CHECK_REL(south, cap, 1e-12);
		CHECK_REL(north, cap, 1e-12);
		CHECK_REL(shape_cell_area(&o, 0.25, 0.5, 0, dv), cap / 4, 1e-12);
		/* a zone next to the pole: 2πr²(cos θ0 − cos θ1) */
		CHECK_REL(shape_cell_area(&o, 0, 1, dv, 2 * dv),
		          2 * M_PI * 4 * (cos(M_PI * dv) - cos(2 * M_PI * dv)), 1e-10);
	}
	struct object k = mk_obj(OBJ_CONE); /* open cone, apex at b */
	k.g.cone.b = v3(0, 1, 0), k.g.cone.ra = 1, k.g.cone.rb = 0, k.flags = OF_OPEN;
	double dv = 1e-3, apex = shape_cell_area(&k, 0, 1, 1 - dv, 1);
	CHECK(isfinite(apex) && apex > 0);
	CHECK_REL(apex, M_PI * dv * M_SQRT2 * dv, 1e-10); /* small cone of slant √2·dv */
	struct object d = mk_obj(OBJ_DISC);
	d.g.disc.n = v3(0, 0, 1), d.g.disc.r = 3;
	CHECK_REL(shape_cell_area(&d, 0, 0.5, 0, 0.01), 0.5 * M_PI * 0.03 * 0.03, 1e-12);
}

/* ==== (5) torus accuracy =================================================== */

/* Distance of a world point to the torus surface, in its own frame. */
static double torus_dist(const struct object *o, struct vec3 wp)
{
	struct vec3 p = xf_inv_point(obj_xf(o), wp);
	double k = sqrt(p.x * p.x + p.z * p.z) - o->g.torus.major;
	return fabs(sqrt(k * k + p.y * p.y) - o->g.torus.minor);
}

static void t_torus_known(void)
{
	struct object o = mk_obj(OBJ_TORUS);
	o.g.torus.major = 2, o.g.torus.minor = 0.5;
	struct hit h;
	struct ray r = {v3(-10, 0, 0), v3(1, 0, 0)};
	CHECK(shape_intersect(&o, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 7.5, 1e-13);
	CHECK_NEAR(h.n.x, -1, 1e-13);
	CHECK(shape_intersect(&o, &r, 7.5, INFINITY, &h));
	CHECK_NEAR(h.t, 8.5, 1e-13);
	CHECK(!h.entering);
	CHECK(shape_intersect(&o, &r, 9, INFINITY, &h)); /* the hole, then the far side */
	CHECK_NEAR(h.t, 11.5, 1e-13);
	struct ray ry = {v3(2, -5, 0), v3(0, 3, 0)};
	CHECK(shape_intersect(&o, &ry, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 1.5, 1e-13);
	CHECK_NEAR(h.v, 0.75, 1e-13);
	struct ray miss = {v3(-10, 0.5 + 1e-9, 0), v3(1, 0, 0)};
	CHECK(!shape_intersect(&o, &miss, 0, INFINITY, &h));
	CHECK(shape_inside(&o, v3(0, 0, 2.2)) && !shape_inside(&o, v3(0, 0, 0)));
}

/* Rays tangent to the surface at a random point, pushed inwards by 10^-11 …
 * 10^-3 of the tube radius: each must be hit before it reaches that inner
 * point (when it starts outside), and every hit must be on the surface. */
static void t_torus_grazing(void)
{
	rng_seed(5);
	int hits = 0, missed = 0;
	double worst = 0;
	for (int i = 0; i < 4000; i++) {
		struct object o = rnd_prim(OBJ_TORUS, false);
		o.xf = xf_keep(rnd_xform(i % 2 == 0, true));
		double u = rnd(), v = rnd(), sc = o.g.torus.major + o.g.torus.minor;
		struct vec3 p, du, dv;
		shape_uv_point(&o, u, v, &p, &du, &dv);
		struct vec3 n = v_norm(v_cross(du, dv)), t = v_norm(v_madd(du, dv, rndr(-3, 3)));
		t = v_norm(v_madd(t, n, -v_dot(t, n))); /* tangent */
		double depth = pow(10, rndr(-11, -3)) * obj_scale(&o);
		struct vec3 target = v_madd(p, n, xf_det(obj_xf(&o)) > 0 ? -depth : depth);
		struct ray r = {v_madd(target, t, -2 * obj_scale(&o)), t};
		struct hit h;
		bool got = shape_intersect(&o, &r, 0, INFINITY, &h);
		if (got) {
			hits++;
			worst = fmax(worst, torus_dist(&o, h.p) / sc);
		}
		if (!shape_inside(&o, r.o) && shape_inside(&o, target) &&
		    (!got || h.t > 2 * obj_scale(&o) * (1 + 1e-9)))
			missed++;
	}
	printf("# grazing: %d hits, %d missed entries, worst distance %.3g·scale\n", hits, missed,
	       worst);
	CHECK(hits > 3500);
	CHECK(missed == 0);
	CHECK(worst < 1e-9);
}

/* Rays from 10³ … 10⁶ scales away, aimed at a random surface point. */
static void t_torus_far(void)
{
	rng_seed(6);
	int hits = 0;
	double worst = 0;
	for (int i = 0; i < 4000; i++) {
		struct object o = rnd_prim(OBJ_TORUS, false);
		o.xf = xf_keep(rnd_xform(i % 2 == 0, true));
		double sc = o.g.torus.major + o.g.torus.minor;
		struct vec3 p;
		shape_uv_point(&o, rnd(), rnd(), &p, NULL, NULL);
		struct vec3 from = v_madd(p, rnd_dir(), pow(10, rndr(3, 6)) * obj_scale(&o));
		struct ray r = {from, v_sub(p, from)};
		struct hit h;
		if (!shape_intersect(&o, &r, 0, INFINITY, &h))
			continue;
		hits++;
		worst = fmax(worst, torus_dist(&o, h.p) / sc);
	}
	printf("# far: %d hits, worst distance %.3g·scale\n", hits, worst);
	CHECK(hits > 3900);
	CHECK(worst < 1e-9);
}

/* shape_occluded answers as shape_intersect does over the same interval,
 * for every kind (box and torus have a shadow test of their own, which
 * fills in no hit), from anywhere, from the surface and along the axes. */
static void t_occluded_as_intersect(void)
{
	rng_seed(7);
	int differ = 0, hits = 0, total = 0;
	for (int k = 0; k < NKINDS(all_kinds); k++)
		for (int i = 0; i < 3000; i++) {
			struct object o = rnd_prim(all_kinds[k], i % 7 == 0);
			if (i % 2)
				o.xf = xf_keep(rnd_xform(i % 4 == 1, true));
			struct ray r = {rnd_vec(-4, 4), rnd_dir()};
			if (i % 3 == 0) { /* aimed at a surface point, or leaving it */
				struct vec3 p;
				shape_uv_point(&o, rnd(), rnd(), &p, NULL, NULL);
				if (i % 6 == 0)
					r.o = p;
				else
					r.d = v_sub(p, r.o);
			}
			if (i % 5 == 0)
				r.d = v3(0, i % 10 ? 1 : -1, 0);
			double tmin = i % 4 ? 0 : 1e-9, tmax = i % 8 < 5 ? INFINITY : rndr(0.1, 6);
			struct hit h;
			bool hit = shape_intersect(&o, &r, tmin, tmax, &h);
			differ += hit != shape_occluded(&o, &r, tmin, tmax);
			hits += hit, total++;
		}
	printf("# %d hits of %d rays, %d answers differ\n", hits, total, differ);
	CHECK(differ == 0);
	CHECK(hits > total / 5 && hits < total * 4 / 5);
}

/* ---- the torus against the plain solver ----------------------------------
 * torus.c finds its quartic's roots one at a time, stops at the first the
 * query takes, and skips the search where the quartic is provably positive
 * (docs/design.md, "The torus"). The plain way below, every root of the
 * quartic and of its derivatives refined in turn, must give the same t and
 * point bit for bit, and the same answer when it finds none. */

static double ref_peval(const double *c, int n, double x, double *d)
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

static double ref_refine(const double *c, int n, double lo, double hi, double flo)
{
	double x = 0.5 * (lo + hi);
	for (int it = 0; it < 200; it++) {
		double d, f = ref_peval(c, n, x, &d);
		if (f == 0)
			return x;
		if ((f < 0) == (flo < 0))
			lo = x;
		else
			hi = x;
		double nx = d != 0 ? x - f / d : lo;
		if (!(nx > lo && nx < hi))
			nx = 0.5 * (lo + hi);
		if (nx == x || hi - lo <= 4e-16 * fmax(fabs(lo), fabs(hi)))
			return nx;
		x = nx;
	}
	return x;
}

static int ref_roots(const double *c, int n, double lo, double hi, double *out)
{
	if (n == 1) {
		double x = c[1] != 0 ? -c[0] / c[1] : NAN;
		out[0] = x;
		return x >= lo && x <= hi;
	}
	double dc[4], b[6];
	for (int i = 1; i <= n; i++)
		dc[i - 1] = i * c[i];
	int m = ref_roots(dc, n - 1, lo, hi, b + 1), k = 0;
	b[0] = lo;
	b[m + 1] = hi;
	for (int i = 0; i <= m; i++) {
		double f0 = ref_peval(c, n, b[i], NULL), f1 = ref_peval(c, n, b[i + 1], NULL);
		if (f0 == 0) {
			if (k == 0 || out[k - 1] != b[i])
				out[k++] = b[i];
		} else if ((f0 < 0) != (f1 < 0) && f1 != 0) {
			out[k++] = ref_refine(c, n, b[i], b[i + 1], f0);
		}
	}
	if (ref_peval(c, n, hi, NULL) == 0 && (k == 0 || out[k - 1] != hi))
		out[k++] = hi;
	return k;
}

/* torus.c's to_first, the plain way: r in the torus's frame. */
static bool ref_torus(double R, double rr, const struct ray *r, double tmin, double tmax, double *t,
                      struct vec3 *p)
{
	double L = v_len(r->d), sc = R + rr;
	struct vec3 d = v_scale(r->d, 1 / L);
	double tc = -v_dot(r->o, d);
	struct vec3 q = v_madd(r->o, d, tc);
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
	double m = reach * rr / sc, y0 = qs.y + d.y * s0, y1 = qs.y + d.y * s1;
	if ((y0 > m && y1 > m) || (y0 < -m && y1 < -m))
		return false;
	double Rs = R / sc, rs = rr / sc, c0 = v_dot(qs, qs), e = c0 + Rs * Rs - rs * rs, R4 = 4 * Rs * Rs;
	double a2 = d.x * d.x + d.z * d.z, a1 = 2 * (qs.x * d.x + qs.z * d.z), a0 = qs.x * qs.x + qs.z * qs.z;
	double c[5] = {e * e - R4 * a0, -R4 * a1, 2 * e - R4 * a2, 0, 1}, s[4];
	int n = ref_roots(c, 4, s0, s1, s);
	for (int i = 0; i < n; i++) {
		*t = (tc + s[i] * sc) / L;
		if (!(*t > tmin && *t < tmax))
			continue;
		*p = v_madd(q, d, s[i] * sc);
		return true;
	}
	return false;
}

/* Rays spawned on the surface (offset 1e-7 of the coordinates' size to
 * either side, as the eye pass spawns them, half of them leaving on that
 * side, the rest in any direction), rays aimed
 * at it and rays from anywhere, on ring and spindle tori, transformed or
 * not. */
static void t_torus_reference(void)
{
	rng_seed(8);
	int differ = 0, hits = 0, total = 0, spawned_miss = 0;
	for (int i = 0; i < 20000; i++) {
		struct object o = rnd_prim(OBJ_TORUS, false);
		if (i % 5 == 4)
			o.g.torus.minor = rndr(1.05, 1.5) * o.g.torus.major;
		if (i % 2)
			o.xf = xf_keep(rnd_xform(i % 4 == 1, true));
		struct ray r = {rnd_vec(-4, 4), rnd_dir()};
		if (i % 3 == 0) {
			struct vec3 p, du, dv;
			shape_uv_point(&o, rnd(), rnd(), &p, &du, &dv);
			struct vec3 n = v_norm(v_cross(du, dv));
			double big = fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z)));
			double side = i % 4 < 2 ? 1 : -1;
			r.o = v_madd(p, n, side * 1e-7 * (1 + big));
			if (i % 6 == 0 && v_dot(r.d, n) * side < 0) /* leaving on its side */
				r.d = v_scale(r.d, -1);
		} else if (i % 3 == 1) {
			struct vec3 p;
			shape_uv_point(&o, rnd(), rnd(), &p, NULL, NULL);
			r.d = v_sub(p, r.o);
		}
		double tmax = i % 8 < 6 ? INFINITY : rndr(0.1, 6);
		struct ray lr = r;
		if (o.xf)
			lr = (struct ray){xf_inv_point(o.xf, r.o), xf_inv_vector(o.xf, r.d)};
		struct hit h;
		double t = 0;
		struct vec3 lp = v3(0, 0, 0);
		bool want = ref_torus(o.g.torus.major, o.g.torus.minor, &lr, 0, tmax, &t, &lp);
		bool got = shape_intersect(&o, &r, 0, tmax, &h);
		struct vec3 wp = o.xf ? xf_point(o.xf, lp) : lp;
		if (got != want || shape_occluded(&o, &r, 0, tmax) != want ||
		    (got && (memcmp(&h.t, &t, sizeof t) || memcmp(&h.p, &wp, sizeof wp))))
			differ++;
		hits += want, total++;
		spawned_miss += i % 3 == 0 && !want;
	}
	printf("# %d hits of %d rays (%d spawned on the surface miss), %d differ\n", hits, total,
	       spawned_miss, differ);
	CHECK(differ == 0);
	CHECK(hits > total / 4 && spawned_miss > total / 12);
}

/* quartic_above's bound is in units of R + r, so the skip is the plain
 * solver's answer at any scale: tori of major radius 1e-4 to 1e6 (ring and
 * spindle), rays from near and from 1e6 radii away, aimed at the surface,
 * spawned on it, and grazing it (along a tangent, from either side of the
 * surface by a few ulps to 1e-6 of its size): the same hit, bit for bit,
 * and the same shadow answer as ref_torus. */
static void t_torus_scales(void)
{
	rng_seed(21);
	const double scale[] = {1e-4, 1e-2, 1, 1e3, 1e6};
	int differ = 0, hits = 0, total = 0, grazing_hits = 0;
	for (int i = 0; i < 30000; i++) {
		double k = scale[i % 5];
		struct object o = mk_obj(OBJ_TORUS);
		o.g.torus.major = k * rndr(0.5, 2);
		o.g.torus.minor = o.g.torus.major * (i % 7 == 3 ? rndr(1.05, 1.5) : rndr(0.02, 0.7));
		double far = i % 4 == 0 ? 1e6 : 4;
		struct ray r = {v_scale(rnd_vec(-far, far), k), rnd_dir()};
		struct vec3 p, du, dv;
		shape_uv_point(&o, rnd(), rnd(), &p, &du, &dv);
		struct vec3 n = v_norm(v_cross(du, dv));
		int kind = i % 3;
		if (kind == 0) { /* aimed at the surface */
			r.d = v_sub(p, r.o);
		} else if (kind == 1) { /* grazing: along a tangent through a point beside it */
			struct vec3 tg = v_norm(v_add(v_scale(v_norm(du), rndr(-1, 1)), v_scale(v_norm(dv), rndr(-1, 1))));
			double big = fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z)));
			double off = (rnd() < 0.5 ? 1e-15 : 1e-7 * rnd()) * big * (rnd() < 0.5 ? 1 : -1);
			struct vec3 at = v_madd(p, n, off);
			r.o = v_madd(at, tg, -rndr(0.01, 3) * k);
			r.d = v_scale(tg, rndr(0.1, 10));
		} else { /* spawned on it, leaving or not */
			double big = fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z)));
			r.o = v_madd(p, n, (i % 2 ? 1 : -1) * 1e-7 * big);
		}
		double tmax = i % 8 < 6 ? INFINITY : rndr(0.1, 6);
		struct hit h;
		double t = 0;
		struct vec3 lp = v3(0, 0, 0);
		bool want = ref_torus(o.g.torus.major, o.g.torus.minor, &r, 0, tmax, &t, &lp);
		bool got = shape_intersect(&o, &r, 0, tmax, &h);
		if (got != want || shape_occluded(&o, &r, 0, tmax) != want ||
		    (got && (memcmp(&h.t, &t, sizeof t) || memcmp(&h.p, &lp, sizeof lp))))
			differ++;
		hits += want, total++;
		grazing_hits += kind == 1 && want;
	}
	printf("# %d hits of %d rays (%d grazing), %d differ\n", hits, total, grazing_hits, differ);
	CHECK(differ == 0);
	CHECK(hits > total / 4 && grazing_hits > total / 20);
}

/* shape_intersect_bare finds what shape_intersect finds, bit for bit, less
 * the (u,v) (NaN) and the partials (zero), for every kind. */
static void t_bare_as_intersect(void)
{
	rng_seed(9);
	int differ = 0, hits = 0, total = 0;
	for (int k = 0; k < NKINDS(all_kinds); k++)
		for (int i = 0; i < 2000; i++) {
			struct object o = rnd_prim(all_kinds[k], i % 7 == 0);
			if (i % 2)
				o.xf = xf_keep(rnd_xform(i % 4 == 1, true));
			struct ray r = {rnd_vec(-4, 4), rnd_dir()};
			if (i % 3 == 0) {
				struct vec3 p;
				shape_uv_point(&o, rnd(), rnd(), &p, NULL, NULL);
				r.d = v_sub(p, r.o);
			}
			struct hit a, b;
			bool got = shape_intersect(&o, &r, 0, INFINITY, &a);
			if (got != shape_intersect_bare(&o, &r, 0, INFINITY, &b))
				differ++;
			else if (got && (memcmp(&a.t, &b.t, sizeof a.t) || memcmp(&a.p, &b.p, sizeof a.p) ||
			                 memcmp(&a.n, &b.n, sizeof a.n) || a.obj != b.obj || a.entering != b.entering ||
			                 !isnan(b.u) || !isnan(b.v) || v_len(b.dpdu) != 0 || v_len(b.dpdv) != 0))
				differ++;
			hits += got, total++;
		}
	printf("# %d hits of %d rays, %d differ\n", hits, total, differ);
	CHECK(differ == 0);
	CHECK(hits > total / 3);
}

/* Two cones alike but for one radius, asked in turn (cone.c keeps the last
 * cone's frame per thread): each hit where its own radius puts it. */
static void t_cone_alternating(void)
{
	struct object k[4];
	for (int i = 0; i < 4; i++) {
		k[i] = mk_obj(OBJ_CONE);
		k[i].g.cone.a = v3(0, 0, 0), k[i].g.cone.b = v3(0, 2, 0);
		k[i].g.cone.ra = 1, k[i].g.cone.rb = 0;
	}
	k[1].g.cone.rb = 1;       /* a cylinder: radius 1 at y = 1 */
	k[2].g.cone.ra = 0.5;     /* radius 0.25 at y = 1 */
	k[3].g.cone.b = v3(0, 4, 0); /* radius 0.75 at y = 1 */
	const double want[4] = {4.5, 4, 4.75, 4.25};
	struct ray r = {v3(-5, 1, 0), v3(1, 0, 0)};
	int bad = 0;
	for (int n = 0; n < 12; n++) {
		int i = (n * 7) % 4;
		struct hit h;
		bad += !shape_intersect(&k[i], &r, 0, INFINITY, &h) || fabs(h.t - want[i]) > 1e-12;
		bad += shape_occluded(&k[i], &r, 0, want[i] - 1e-9) || !shape_occluded(&k[i], &r, 0, want[i] + 1e-9);
	}
	CHECK(bad == 0);
}

/* shape_bsphere holds the surface: points sampled over every bounded
 * kind's (u,v) domain under random transforms (scale then rotate, mirrored
 * one time in four, and rotate then scale) lie within it; it is never
 * wider than the sphere around the world bounds; and for a sphere it is
 * the sphere itself: c and r exactly without a transform, the scaled radius
 * under a uniform scale, the largest axis under a non-uniform one. */
static void t_bsphere(void)
{
	rng_seed(33);
	int outside = 0, wider = 0, points = 0;
	for (int i = 0; i < 4000; i++) {
		enum object_kind k = all_kinds[i % NKINDS(all_kinds)];
		if (k == OBJ_PLANE)
			continue;
		struct object o = rnd_prim(k, false);
		struct xform x = rnd_xform(i % 3 == 0, true);
		if (i % 5 == 1) /* rotate, then scale */
			x = xf_then(xf_rotate(rnd_vec(-180, 180)), xf_scale(rnd_vec(0.4, 2.5)));
		if (i % 7 != 0)
			o.xf = xf_keep(x);
		struct vec3 c;
		double r;
		CHECK(shape_bsphere(&o, &c, &r));
		struct bbox b = shape_bounds(&o);
		wider += r > 0.5 * v_len(v_sub(b.hi, b.lo));
		for (int q = 0; q < 64; q++) {
			struct vec3 p;
			double u = rnd(), v = rnd();
			if (k == OBJ_TRIANGLE && u + v > 1) /* the triangle is u + v <= 1 of its (u,v) square */
				u = 1 - u, v = 1 - v;
			if (!shape_uv_point(&o, u, v, &p, NULL, NULL))
				continue;
			points++;
			outside += dist(p, c) > r * (1 + 1e-12);
		}
	}
	printf("# %d surface points, %d outside, %d spheres wider than the bounds'\n", points, outside, wider);
	CHECK(points > 100000);
	CHECK(outside == 0 && wider == 0);
	struct object o = mk_obj(OBJ_SPHERE);
	o.g.sphere.c = v3(1, 2, 3);
	o.g.sphere.r = 2;
	struct vec3 c;
	double r;
	CHECK(shape_bsphere(&o, &c, &r));
	CHECK(c.x == 1 && c.y == 2 && c.z == 3 && r == 2);
	o.xf = xf_keep(xf_then(xf_then(xf_scale(v3(3, 3, 3)), xf_rotate(v3(30, 40, 50))), xf_translate(v3(0, 5, 0))));
	CHECK(shape_bsphere(&o, &c, &r));
	CHECK_NEAR(r, 6, 1e-9);
	CHECK_NEAR(dist(c, xf_point(o.xf, v3(1, 2, 3))), 0, 1e-12);
	o.xf = xf_keep(xf_then(xf_scale(v3(1, 4, 2)), xf_rotate(v3(10, 20, 30))));
	CHECK(shape_bsphere(&o, &c, &r));
	CHECK_NEAR(r, 8, 1e-9);
	o.xf = xf_keep(xf_then(xf_rotate(v3(10, 20, 30)), xf_scale(v3(1, 4, 2))));
	CHECK(shape_bsphere(&o, &c, &r));
	CHECK_NEAR(r, 8, 1e-9);
	struct object pl = mk_obj(OBJ_PLANE);
	pl.g.plane.n = v3(0, 1, 0);
	CHECK(!shape_bsphere(&pl, &c, &r));
}

int main(void)
{
	RUN(t_sphere_known);
	RUN(t_plane_box_known);
	RUN(t_round_shapes_known);
	RUN(t_no_rehit_convex);
	RUN(t_uv_round_trip);
	RUN(t_partials_fd);
	RUN(t_cell_area_totals);
	RUN(t_cell_area_spheroid);
	RUN(t_cell_area_singular);
	RUN(t_torus_known);
	RUN(t_torus_grazing);
	RUN(t_torus_far);
	RUN(t_occluded_as_intersect);
	RUN(t_torus_reference);
	RUN(t_torus_scales);
	RUN(t_bare_as_intersect);
	RUN(t_cone_alternating);
	RUN(t_bsphere);
	return test_done();
}
