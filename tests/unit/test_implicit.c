/* SPDX-License-Identifier: MIT */
/* test_implicit.c: the implicit surfaces against shapes with known answers:
 * a quartic torus against the torus primitive, quadric and superellipsoid
 * <1,1> against the sphere, a one-component blob against the sphere of
 * radius r·√(1 − √(T/s)), their (u,v) round trips and areas through the
 * radial parametrisation, a mesh cube against the box (hits, inside, atlas
 * areas) and a large random mesh against brute force, the camera types'
 * central and edge rays, and the inline perspective ray (cam_ray_to)
 * against cam_ray, bit for bit. */
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

/* The 12 triangles of the cube [−1,1]³, counter-clockwise from outside. */
static struct mesh cube_mesh(struct arena *a)
{
	static struct vec3 P[8] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
	                           {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
	static struct mesh_tri T[12] = {
		{{0, 2, 1}, {-1, -1, -1}}, {{0, 3, 2}, {-1, -1, -1}}, {{4, 5, 6}, {-1, -1, -1}},
		{{4, 6, 7}, {-1, -1, -1}}, {{0, 1, 5}, {-1, -1, -1}}, {{0, 5, 4}, {-1, -1, -1}},
		{{3, 6, 2}, {-1, -1, -1}}, {{3, 7, 6}, {-1, -1, -1}}, {{0, 7, 3}, {-1, -1, -1}},
		{{0, 4, 7}, {-1, -1, -1}}, {{1, 2, 6}, {-1, -1, -1}}, {{1, 6, 5}, {-1, -1, -1}}};
	struct mesh m = {.nv = 8, .nt = 12, .vert = P, .tri = T, .has_inside = true, .inside_dir = {0.3, 1, 0.1}};
	int bad;
	CHECK(mesh_finish(&m, a, &bad));
	return m;
}

static void t_mesh_cube(void)
{
	struct arena a;
	arena_init(&a);
	struct mesh m = cube_mesh(&a);
	struct object me = mk_obj(OBJ_MESH), bx = mk_obj(OBJ_BOX);
	me.g.mesh.m = &m;
	bx.g.box.lo = v3(-1, -1, -1);
	bx.g.box.hi = v3(1, 1, 1);
	rng_seed(9);
	int n = 0;
	for (int i = 0; i < 2000; i++) {
		struct xform X = rnd_xform(false, true);
		me.xf = bx.xf = xf_keep(X);
		struct ray r = aimed_ray(1.5);
		struct hit hm, hb;
		bool b = shape_intersect(&bx, &r, 1e-9, INFINITY, &hb);
		CHECK(shape_intersect(&me, &r, 1e-9, INFINITY, &hm) == b);
		if (b) {
			n++;
			CHECK_NEAR(hm.t, hb.t, 1e-12 * hb.t);
			CHECK(v_dot(hm.n, hb.n) > 1 - 1e-12);
			CHECK(hm.entering == hb.entering);
		}
		struct vec3 p = xf_point(&X, rnd_vec(-1.3, 1.3));
		CHECK(shape_inside(&me, p) == shape_inside(&bx, p));
	}
	CHECK(n > 500);
	me.xf = NULL;
	CHECK_NEAR(shape_area(&me), 24, 1e-12);
	/* a 4×4 atlas: triangle 5 is cell (1,1); its half below the diagonal */
	CHECK_NEAR(shape_cell_area(&me, 0.25, 0.5, 0.25, 0.5), 2, 1e-12);
	CHECK_NEAR(shape_cell_area(&me, 0.25, 0.375, 0.25, 0.375), 1, 1e-12); /* a quarter of the cell, |e1×e2| = 4 */
	CHECK_NEAR(shape_cell_area(&me, 0.5, 1, 0.75, 1), 0, 0); /* past the 12th triangle */
	/* round trip through the atlas */
	for (int i = 0; i < 200; i++) {
		double u = rndr(0, 1), v = rndr(0, 0.75);
		double ca = u * 4 - floor(u * 4), cb = v * 4 - floor(v * 4);
		if (ca + cb > 0.98 || ca < 0.01 || cb < 0.01)
			continue;
		struct vec3 p, du, dv;
		CHECK(shape_uv_point(&me, u, v, &p, &du, &dv));
		struct vec3 nn = v_cross(du, dv);
		struct ray r = {v_madd(p, nn, 0.5 / v_len(nn)), v_neg(nn)};
		struct hit h;
		CHECK(shape_intersect(&me, &r, 0, INFINITY, &h));
		CHECK_NEAR(h.u, u, 1e-12);
		CHECK_NEAR(h.v, v, 1e-12);
		CHECK(h.entering);
	}
	arena_free(&a);
}

/* 3000 random triangles: the hierarchy finds what a loop over all finds. */
static void t_mesh_brute(void)
{
	enum { NT = 3000 };
	static struct vec3 V[3 * NT];
	static struct mesh_tri T[NT];
	rng_seed(21);
	for (int i = 0; i < NT; i++) {
		struct vec3 c = rnd_vec(-5, 5);
		for (int k = 0; k < 3; k++) {
			V[3 * i + k] = v_add(c, rnd_vec(-0.4, 0.4));
			T[i].v[k] = 3 * i + k;
			T[i].n[k] = -1;
		}
	}
	struct arena a;
	arena_init(&a);
	struct mesh m = {.nv = 3 * NT, .nt = NT, .vert = V, .tri = T};
	int bad;
	CHECK(mesh_finish(&m, &a, &bad));
	struct object me = mk_obj(OBJ_MESH);
	me.g.mesh.m = &m;
	int agree = 0, hits = 0;
	for (int i = 0; i < 500; i++) {
		struct ray r = aimed_ray(5);
		double best = INFINITY;
		for (int t = 0; t < NT; t++) {
			struct object tr = mk_obj(OBJ_TRIANGLE);
			for (int k = 0; k < 3; k++)
				tr.g.triangle.p[k] = V[3 * t + k];
			struct hit h;
			if (shape_intersect(&tr, &r, 0, best, &h))
				best = h.t;
		}
		struct hit h;
		bool got = shape_intersect(&me, &r, 0, INFINITY, &h);
		hits += got;
		agree += got == (best < INFINITY) && (!got || h.t == best);
	}
	CHECK(hits > 200);
	CHECK(agree == 500);
	arena_free(&a);
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
	sc.kind = CAM_OMNIMAX; /* 4:3 is wider than the dome: its axis is below the image centre */
	sc.angle = 0;
	cam_setup(&c, &sc);
	r = cam_ray(&c, 0.5, 0.5 + 0.283458 / 2, 0, 0);
	CHECK_NEAR(v_norm(r.d).z, 1, 1e-12);
	r = cam_ray(&c, 0.01, 0.01, 0, 0);
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

/* cam_ray_to (the eye pass's inline camera ray) gives cam_ray's bits:
 * a perspective camera with skewed, unnormalised vectors over the whole
 * film, and the cameras it hands back to cam_ray (a lens, orthographic). */
static void t_cam_ray_to(void)
{
	struct camera sc = scene_default_camera();
	sc.location = v3(0.3, -1.7, 2.9);
	sc.direction = v3(0.1, 0.2, 1.3);
	sc.right = v3(1.31, 0.05, -0.2);
	sc.up = v3(0.02, 0.97, 0.11);
	struct cam c;
	int same = 0, n = 0, fast = 0;
	for (int k = 0; k < 3; k++) {
		sc.kind = k == 2 ? CAM_ORTHOGRAPHIC : CAM_PERSPECTIVE;
		sc.aperture = k == 1 ? 0.2 : 0;
		cam_setup(&c, &sc);
		fast += c.kind == CAM_PERSPECTIVE && !(c.aperture > 0);
		for (int y = 0; y < 37; y++)
			for (int x = 0; x < 53; x++, n++) {
				double sx = (x + 0.5) / 53, sy = (y + 0.5) / 37, l1 = x / 53.0, l2 = y / 37.0;
				struct ray a = cam_ray(&c, sx, sy, l1, l2), b;
				cam_ray_to(&c, sx, sy, l1, l2, &b);
				same += !memcmp(&a.o, &b.o, sizeof a.o) && !memcmp(&a.d, &b.d, sizeof a.d);
			}
	}
	CHECK(fast == 1);
	CHECK(same == n);
	CHECK(n == 3 * 53 * 37);
}

int main(void)
{
	RUN(t_quartic_torus);
	RUN(t_sphere_likes);
	RUN(t_blob_sphere);
	RUN(t_radial_round_trip);
	RUN(t_mesh_cube);
	RUN(t_mesh_brute);
	RUN(t_cameras);
	RUN(t_cam_ray_to);
	return test_done();
}
