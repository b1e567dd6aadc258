/* SPDX-License-Identifier: MIT */
/* test_implicit.c: the implicit surfaces against shapes with known answers:
 * a quartic torus against the torus primitive, quadric and superellipsoid
 * <1,1> against the sphere, a one-component blob against the sphere of
 * radius r·√(1 − √(T/s)), their (u,v) round trips and areas through the
 * radial parametrisation, and the camera types' central and edge rays. */
#include <stdio.h>

#include "../../tracer/camera.h"
#include "geo_rand.h"
#include "test.h"

/* The polynomial of a torus (R, r) about y: (|p|² + R² − r²)² − 4R²(x² + z²). */
static struct polynomial torus_poly(double R, double r, struct poly_term *t)
{
	double A = R * R - r * r;
	int n = 0;
	t[n++] = (struct poly_term){1, {4, 0, 0}};
	t[n++] = (struct poly_term){1, {0, 4, 0}};
	t[n++] = (struct poly_term){1, {0, 0, 4}};
	t[n++] = (struct poly_term){2, {2, 2, 0}};
	t[n++] = (struct poly_term){2, {2, 0, 2}};
	t[n++] = (struct poly_term){2, {0, 2, 2}};
	t[n++] = (struct poly_term){2 * A - 4 * R * R, {2, 0, 0}};
	t[n++] = (struct poly_term){2 * A, {0, 2, 0}};
	t[n++] = (struct poly_term){2 * A - 4 * R * R, {0, 0, 2}};
	t[n++] = (struct poly_term){A * A, {0, 0, 0}};
	return (struct polynomial){4, n, t};
}

/* Random rays towards a ball of radius `reach` about the origin. */
static struct ray aimed_ray(double reach)
{
	struct vec3 o = v_scale(rnd_dir(), rndr(3, 6) * reach);
	struct vec3 at = rnd_vec(-reach, reach);
	return (struct ray){o, v_scale(v_sub(at, o), rndr(0.5, 2))};
}

static void t_quartic_torus(void)
{
	struct poly_term terms[10];
	struct polynomial P = torus_poly(1.5, 0.5, terms);
	struct object q = mk_obj(OBJ_POLY), t = mk_obj(OBJ_TORUS);
	q.g.poly.p = &P;
	t.g.torus.major = 1.5;
	t.g.torus.minor = 0.5;
	rng_seed(12);
	int hits = 0, agree = 0;
	for (int i = 0; i < 2000; i++) {
		struct xform X = rnd_xform(false, true);
		q.xf = t.xf = xf_keep(X);
		struct ray r = aimed_ray(2.5);
		struct hit hq, ht;
		bool a = shape_intersect(&q, &r, 1e-9, INFINITY, &hq), b = shape_intersect(&t, &r, 1e-9, INFINITY, &ht);
		hits += b;
		if (a == b && (!a || (fabs(hq.t - ht.t) <= 1e-9 * ht.t && v_dot(hq.n, ht.n) > 1 - 1e-9)))
			agree++;
		struct vec3 p = rnd_vec(-2.5, 2.5);
		CHECK(shape_inside(&q, p) == shape_inside(&t, p));
	}
	CHECK(hits > 500);
	CHECK(agree == 2000);
}

/* quadric x² + y² + z² − 1 and superellipsoid <1,1>: the unit sphere. */
static void t_sphere_likes(void)
{
	struct poly_term terms[4] = {{1, {2, 0, 0}}, {1, {0, 2, 0}}, {1, {0, 0, 2}}, {-1, {0, 0, 0}}};
	struct polynomial P = {2, 4, terms};
	struct object q = mk_obj(OBJ_POLY), se = mk_obj(OBJ_SUPERELLIPSOID), s = mk_obj(OBJ_SPHERE);
	q.g.poly.p = &P;
	se.g.superellipsoid.e = se.g.superellipsoid.n = 1;
	s.g.sphere.r = 1;
	rng_seed(7);
	int n = 0;
	for (int i = 0; i < 1000; i++) {
		struct ray r = aimed_ray(1.2);
		struct hit hs, hq, he;
		bool b = shape_intersect(&s, &r, 0, INFINITY, &hs);
		CHECK(shape_intersect(&q, &r, 0, INFINITY, &hq) == b);
		CHECK(shape_intersect(&se, &r, 0, INFINITY, &he) == b);
		if (!b)
			continue;
		n++;
		CHECK_NEAR(hq.t, hs.t, 1e-12 * hs.t);
		CHECK_NEAR(he.t, hs.t, 1e-9 * hs.t);
		CHECK(v_dot(he.n, hs.n) > 1 - 1e-9);
		/* the radial (u,v) about the origin is the sphere's own */
		CHECK_NEAR(he.u, hs.u, 1e-9);
		CHECK_NEAR(he.v, hs.v, 1e-9);
	}
	CHECK(n > 300);
	CHECK_NEAR(shape_area(&se), 4 * M_PI, 1e-6);
	/* small exponents: a face centre of the cube */
	se.g.superellipsoid.e = se.g.superellipsoid.n = 0.05;
	struct ray r = {v3(0.1, 0.2, -5), v3(0, 0, 1)};
	struct hit h;
	CHECK(shape_intersect(&se, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 4, 1e-9);
	CHECK_NEAR(h.n.z, -1, 1e-9);
}

/* One sphere component (r 2, strength 3, threshold 0.75): the surface is
 * the sphere of radius 2·√(1 − √(0.75/3)) = √2. */
static void t_blob_sphere(void)
{
	struct blob_comp c = {.a = v3(0.5, -0.25, 1), .r = 2, .s = 3};
	struct blob B = {0.75, 1, &c, v3(0.5, -0.25, 1)};
	struct object b = mk_obj(OBJ_BLOB), s = mk_obj(OBJ_SPHERE);
	b.g.blob.b = &B;
	s.g.sphere.c = c.a;
	s.g.sphere.r = sqrt(2);
	rng_seed(3);
	int n = 0;
	for (int i = 0; i < 1000; i++) {
		struct xform X = rnd_xform(false, true);
		b.xf = s.xf = xf_keep(X);
		struct ray r = aimed_ray(2);
		struct hit hb, hs;
		bool hit = shape_intersect(&s, &r, 1e-9, INFINITY, &hs);
		CHECK(shape_intersect(&b, &r, 1e-9, INFINITY, &hb) == hit);
		if (!hit)
			continue;
		n++;
		CHECK_NEAR(hb.t, hs.t, 1e-9 * hs.t);
		CHECK(v_dot(hb.n, hs.n) > 1 - 1e-9);
		CHECK_NEAR(hb.u, hs.u, 1e-9);
		CHECK_NEAR(hb.v, hs.v, 1e-9);
	}
	CHECK(n > 250); /* 293 of the 1000 rays hit */
	b.xf = s.xf = NULL;
	CHECK_NEAR(shape_area(&b), 8 * M_PI, 1e-6);
	CHECK(shape_inside(&b, v3(0.5, -0.25, 2.4)));
	CHECK(!shape_inside(&b, v3(0.5, -0.25, 2.5)));
	/* a second, negative component at the centre carves a hollow */
	struct blob_comp two[2] = {c, {.a = c.a, .r = 1, .s = -3}};
	struct blob B2 = {0.75, 2, two, c.a};
	b.g.blob.b = &B2;
	CHECK(!shape_inside(&b, c.a));
	struct ray r = {v3(0.5, -0.25, -5), v3(0, 0, 1)};
	struct hit h1, h2;
	CHECK(shape_intersect(&b, &r, 0, INFINITY, &h1));
	CHECK_NEAR(h1.t, 6 - sqrt(2), 1e-3); /* the outer wall barely moves */
	CHECK(shape_intersect(&b, &r, h1.t + 1e-6, INFINITY, &h2));
	CHECK(h2.t < 6 && !h2.entering);
}

/* (u,v) → T(u,v) → ray → (u,v) on a quartic torus seen from its centre. */
static void t_radial_round_trip(void)
{
	struct poly_term terms[10];
	struct polynomial P = torus_poly(1.5, 0.5, terms);
	struct object q = mk_obj(OBJ_POLY);
	q.g.poly.p = &P;
	rng_seed(5);
	int n = 0;
	for (int i = 0; i < 200; i++) {
		double u = rndr(0.02, 0.98), v = rndr(0.45, 0.55); /* the inner wall, seen from 0 within ±19.5° */
		struct vec3 p, du, dv;
		if (!shape_uv_point(&q, u, v, &p, &du, &dv))
			continue;
		n++;
		struct vec3 n0 = v_cross(du, dv);
		struct ray r = {v_madd(p, n0, 1e-3 / v_len(n0)), v_neg(n0)};
		struct hit h;
		CHECK(shape_intersect(&q, &r, 0, INFINITY, &h));
		CHECK_NEAR(h.u, u, 1e-9);
		CHECK_NEAR(h.v, v, 1e-9);
		/* partials against a finite difference */
		struct vec3 p2;
		shape_uv_point(&q, u + 1e-6, v, &p2, NULL, NULL);
		CHECK(v_len(v_sub(v_scale(v_sub(p2, p), 1e6), du)) < 1e-4 * v_len(du));
	}
	CHECK(n > 150);
}

static void t_cameras(void)
{
	struct camera sc = scene_default_camera();
	struct cam c;
	const enum camera_kind kinds[] = {CAM_FISHEYE, CAM_ULTRA_WIDE, CAM_PANORAMIC, CAM_CYL1,
	                                  CAM_CYL2, CAM_CYL3, CAM_CYL4, CAM_SPHERICAL};
	for (int k = 0; k < 8; k++) { /* the centre looks along direction */
		sc.kind = kinds[k];
		cam_setup(&c, &sc);
		struct ray r = cam_ray(&c, 0.5, 0.5, 0, 0);
		struct vec3 d = v_norm(r.d);
		CHECK_NEAR(d.z, 1, 1e-12);
	}
	sc.kind = CAM_FISHEYE;
	sc.angle = 180;
	cam_setup(&c, &sc);
	struct ray r = cam_ray(&c, 0.5, 0, 0, 0); /* top edge: 90° up */
	CHECK_NEAR(v_norm(r.d).y, 1, 1e-12);
	r = cam_ray(&c, 0.02, 0.02, 0, 0); /* a corner: outside the circle */
	CHECK(v_dot(r.d, r.d) == 0);
	sc.kind = CAM_SPHERICAL;
	sc.angle = 360;
	sc.v_angle = 180;
	cam_setup(&c, &sc);
	r = cam_ray(&c, 0.75, 0.5, 0, 0); /* a quarter turn right */
	CHECK_NEAR(v_norm(r.d).x, 1, 1e-12);
	r = cam_ray(&c, 0.5, 0.25, 0, 0); /* 45° up */
	CHECK_NEAR(v_norm(r.d).y, sqrt(0.5), 1e-12);
	sc.kind = CAM_CYL3;
	sc.angle = 90;
	cam_setup(&c, &sc);
	r = cam_ray(&c, 0.5, 0, 0, 0); /* top: moved up by half of up */
	CHECK_NEAR(r.o.y, 0.5, 1e-12);
	CHECK_NEAR(r.d.y, 0, 1e-12);
}

int main(void)
{
	RUN(t_quartic_torus);
	RUN(t_sphere_likes);
	RUN(t_blob_sphere);
	RUN(t_radial_round_trip);
	RUN(t_cameras);
	return test_done();
}
