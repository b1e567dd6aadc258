/* SPDX-License-Identifier: MIT */
/* test_csg.c: CSG (tracer/csg.c) on known configurations, the equivalence
 * difference(A,B) = intersection(A, inverse B), bounds, large nodes, and a
 * random consistency check: along any ray, the reported hit is the first
 * place where inside() changes, and `entering` agrees with it. */
#include <stdio.h>

#include "geo_rand.h"
#include "test.h"

static struct object sphere(struct vec3 c, double r)
{
	struct object o = mk_obj(OBJ_SPHERE);
	o.g.sphere.c = c;
	o.g.sphere.r = r;
	return o;
}

static struct object csg(enum object_kind k, struct object **kids, int n)
{
	struct object o = mk_obj(k);
	o.g.csg.kids = kids;
	o.g.csg.n = n;
	return o;
}

static struct ray ray(struct vec3 o, struct vec3 d) { return (struct ray){o, d}; }

/* box [−1,1]³ minus a sphere of radius ½ centred on its +x face */
static void t_difference_box_sphere(void)
{
	struct object b = mk_obj(OBJ_BOX), s = sphere(v3(1, 0, 0), 0.5);
	b.g.box.lo = v3(-1, -1, -1), b.g.box.hi = v3(1, 1, 1);
	struct object *k[] = {&b, &s};
	struct object d = csg(OBJ_DIFFERENCE, k, 2);
	struct hit h;
	CHECK(shape_inside(&d, v3(0, 0, 0)));
	CHECK(shape_inside(&d, v3(0.4, 0, 0)));
	CHECK(!shape_inside(&d, v3(0.9, 0, 0)));
	CHECK(!shape_inside(&d, v3(2, 0, 0)));
	struct ray r = ray(v3(-5, 0, 0), v3(1, 0, 0));
	CHECK(shape_intersect(&d, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 4, 1e-12);
	CHECK_NEAR(h.n.x, -1, 1e-15);
	CHECK(h.entering && h.obj == &b);
	CHECK(shape_intersect(&d, &r, 4, INFINITY, &h)); /* leaves through the bite */
	CHECK_NEAR(h.t, 5.5, 1e-12);
	CHECK_NEAR(h.n.x, 1, 1e-12);
	CHECK(!h.entering && h.obj == &s);
	r = ray(v3(5, 0, 0), v3(-1, 0, 0)); /* the x = 1 face is bitten away there */
	CHECK(shape_intersect(&d, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 4.5, 1e-12);
	CHECK_NEAR(h.n.x, 1, 1e-12); /* sphere's inward side, flipped to face out */
	CHECK(h.entering && h.obj == &s);
	r = ray(v3(5, 0.8, 0), v3(-1, 0, 0)); /* misses the bite */
	CHECK(shape_intersect(&d, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 4, 1e-12);
	CHECK(h.obj == &b);
	CHECK(shape_occluded(&d, &r, 0, 4.5));
	CHECK(!shape_occluded(&d, &r, 0, 3.9));
}

/* two unit spheres with centres ±½ on x: a lens, and the peanut */
static void t_intersection_merge_union(void)
{
	struct object a = sphere(v3(-0.5, 0, 0), 1), b = sphere(v3(0.5, 0, 0), 1);
	struct object *k[] = {&a, &b};
	struct object in = csg(OBJ_INTERSECTION, k, 2), mg = csg(OBJ_MERGE, k, 2),
	              un = csg(OBJ_UNION, k, 2);
	struct hit h;
	struct ray r = ray(v3(-5, 0, 0), v3(1, 0, 0)), c = ray(v3(0, 0, 0), v3(1, 0, 0));
	CHECK(shape_intersect(&in, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 4.5, 1e-12);
	CHECK(h.obj == &b && h.entering);
	CHECK(shape_inside(&in, v3(0, 0, 0)) && !shape_inside(&in, v3(0.9, 0, 0)));
	CHECK(shape_intersect(&mg, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 3.5, 1e-12);
	CHECK(shape_intersect(&mg, &c, 0, INFINITY, &h)); /* no inner surface */
	CHECK_NEAR(h.t, 1.5, 1e-12);
	CHECK(!h.entering);
	CHECK(shape_intersect(&un, &c, 0, INFINITY, &h)); /* union keeps it */
	CHECK_NEAR(h.t, 0.5, 1e-12);
	CHECK(shape_inside(&un, v3(1.2, 0, 0)) && !shape_inside(&un, v3(1.6, 0, 0)));
	un.flags |= OF_INVERSE;
	CHECK(!shape_inside(&un, v3(1.2, 0, 0)) && shape_inside(&un, v3(1.6, 0, 0)));
	CHECK(shape_intersect(&un, &c, 0, INFINITY, &h));
	CHECK_NEAR(h.n.x, -1, 1e-12);
}

/* Random rays: difference(A,B) and intersection(A, inverse B) agree. */
static void t_difference_is_intersection_with_inverse(void)
{
	rng_seed(11);
	int bad = 0, hits = 0;
	for (int i = 0; i < 2000; i++) {
		struct object a = rnd_prim(OBJ_BOX, false), b = rnd_prim(OBJ_SPHERE, false);
		a.xf = xf_keep(rnd_xform(false, true));
		b.xf = xf_keep(rnd_xform(true, false));
		struct object bi = b;
		bi.flags |= OF_INVERSE;
		struct object *k1[] = {&a, &b}, *k2[] = {&a, &bi};
		struct object d = csg(OBJ_DIFFERENCE, k1, 2), n = csg(OBJ_INTERSECTION, k2, 2);
		struct vec3 at = v_scale(v_add(shape_bounds(&a).lo, shape_bounds(&a).hi), 0.5);
		at = v_add(at, rnd_vec(-0.5, 0.5));
		struct ray r = ray(v_madd(at, rnd_dir(), rndr(0, 8)), v3(0, 0, 0));
		r.d = v_norm(v_sub(at, r.o));
		struct hit h1, h2;
		bool g1 = shape_intersect(&d, &r, 0, INFINITY, &h1), g2 = shape_intersect(&n, &r, 0, INFINITY, &h2);
		hits += g1;
		bad += g1 != g2 || (g1 && (h1.t != h2.t || v_len(v_sub(h1.n, h2.n)) > 1e-15 ||
		                           h1.entering != h2.entering));
		bad += shape_inside(&d, r.o) != shape_inside(&n, r.o);
	}
	CHECK(bad == 0);
	CHECK(hits > 300);
}

static bool box_eq(struct bbox a, struct bbox b)
{
	return v_len(v_sub(a.lo, b.lo)) < 1e-12 && v_len(v_sub(a.hi, b.hi)) < 1e-12;
}

static void t_bounds(void)
{
	struct object s = sphere(v3(0, 0, 0), 1), t = sphere(v3(5, 0, 0), 1), p = mk_obj(OBJ_PLANE);
	p.g.plane.n = v3(0, 1, 0);
	struct object *sp[] = {&s, &p}, *ps[] = {&p, &s}, *st[] = {&s, &t};
	struct object i1 = csg(OBJ_INTERSECTION, sp, 2), d1 = csg(OBJ_DIFFERENCE, ps, 2),
	              d2 = csg(OBJ_DIFFERENCE, sp, 2), u = csg(OBJ_UNION, st, 2),
	              i2 = csg(OBJ_INTERSECTION, st, 2);
	CHECK(shape_bounded(&i1) && box_eq(shape_bounds(&i1), shape_bounds(&s)));
	CHECK(!shape_bounded(&d1));
	CHECK(shape_bounded(&d2) && box_eq(shape_bounds(&d2), shape_bounds(&s)));
	CHECK(box_eq(shape_bounds(&u), (struct bbox){v3(-1, -1, -1), v3(6, 1, 1)}));
	struct bbox e = shape_bounds(&i2); /* disjoint: empty */
	CHECK(e.lo.x > e.hi.x);
	s.flags |= OF_INVERSE; /* the surface stays bounded, the solid does not */
	CHECK(shape_bounded(&s));
	CHECK(!isfinite(shape_solid_bounds(&s).hi.x));
	CHECK(shape_cell_area(&u, 0, 1, 0, 1) == 0);
	struct uv_range ur;
	CHECK(!shape_uv_range(&u, &ur) && !shape_uv_point(&u, 0.5, 0.5, NULL, NULL, NULL));
}

/* A merge of 20 overlapping spheres on a line (beyond the child cache). */
static void t_large_merge(void)
{
	struct object s[20], *k[20];
	for (int i = 0; i < 20; i++) {
		s[i] = sphere(v3(i, 0, 0), 0.75);
		k[i] = &s[i];
	}
	struct object m = csg(OBJ_MERGE, k, 20), in = csg(OBJ_INTERSECTION, k, 2);
	struct hit h;
	struct ray r = ray(v3(-5, 0, 0), v3(1, 0, 0));
	CHECK(shape_intersect(&m, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 4.25, 1e-12);
	CHECK(shape_intersect(&m, &r, 4.25, INFINITY, &h));
	CHECK_NEAR(h.t, 24.75, 1e-12);
	CHECK(h.obj == &s[19] && !h.entering);
	struct object *nest[] = {&m, &in};
	struct object d = csg(OBJ_DIFFERENCE, nest, 2); /* carve the first lens out */
	CHECK(shape_intersect(&d, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 4.25, 1e-12);
	CHECK(shape_intersect(&d, &r, 4.25, INFINITY, &h));
	CHECK_NEAR(h.t, 5.25, 1e-12); /* enters the lens: leaves the result */
	CHECK(!h.entering && h.obj == &s[1]);
}

/* ---- random consistency -------------------------------------------------- */

static const enum object_kind solid_kinds[] = {OBJ_SPHERE, OBJ_BOX, OBJ_CYLINDER, OBJ_CONE, OBJ_TORUS};

/* Checks one ray against node o; returns the number of inconsistencies. */
static int consistent(const struct object *o, const struct ray *r, double far)
{
	struct hit h;
	bool got = shape_intersect(o, r, 0, far, &h);
	double end = got ? h.t : far, del = 1e-7;
	bool s0 = shape_inside(o, r->o);
	if (got && fabs(v_dot(h.n, r->d)) < 1e-3)
		return 0; /* grazing: inside() across it is not meaningful */
	int bad = 0;
	for (int i = 1; i < 200; i++) {
		double t = end * i / 200.0;
		if (got && t > end - del)
			break;
		bad += shape_inside(o, ray_at(*r, t)) != s0;
	}
	if (got) {
		bool before = shape_inside(o, ray_at(*r, h.t - del)), after = shape_inside(o, ray_at(*r, h.t + del));
		bad += before == after;
		bad += h.entering != after;
	}
	return bad;
}

static void t_random_consistency(void)
{
	static const enum object_kind ops[] = {OBJ_INTERSECTION, OBJ_DIFFERENCE, OBJ_MERGE};
	rng_seed(12);
	int bad = 0, hits = 0;
	for (int i = 0; i < 3000; i++) {
		struct object p[4], *k[4], inner, extra, *k2[2];
		int n = 2 + (int)(rnd() * 3);
		for (int j = 0; j < n; j++) {
			p[j] = rnd_prim(solid_kinds[(int)(rnd() * 5)], false);
			p[j].xf = xf_keep(rnd_xform(false, true));
			if (rnd() < 0.15)
				p[j].flags |= OF_INVERSE;
			k[j] = &p[j];
		}
		/* not union: its inner surfaces are hits where inside() does not change */
		struct object top = csg(ops[(int)(rnd() * 3)], k, n);
		struct object *use = &top;
		if (i % 3 == 0) { /* nest it */
			inner = top;
			k2[0] = &inner;
			extra = rnd_prim(OBJ_SPHERE, false);
			k2[1] = &extra;
			top = csg(ops[(int)(rnd() * 3)], k2, 2);
		}
		struct vec3 at; /* aim at a child's surface */
		shape_uv_point(k[(int)(rnd() * n)], rndr(0.01, 0.99), rndr(0.01, 0.99), &at, NULL, NULL);
		struct ray r = ray(v_madd(at, rnd_dir(), 8), v3(0, 0, 0));
		r.d = v_norm(v_sub(at, r.o));
		struct hit h;
		hits += shape_intersect(use, &r, 0, 30, &h);
		bad += consistent(use, &r, 30);
	}
	printf("# %d hits, %d inconsistencies\n", hits, bad);
	CHECK(bad == 0);
	CHECK(hits > 600);
}

int main(void)
{
	RUN(t_difference_box_sphere);
	RUN(t_intersection_merge_union);
	RUN(t_difference_is_intersection_with_inverse);
	RUN(t_bounds);
	RUN(t_large_merge);
	RUN(t_random_consistency);
	return test_done();
}
