/* SPDX-License-Identifier: MIT */
/* test_fn.c: the function machine (tracer/fn.c) on hand-made programs, and
 * the isosurface (tracer/shapes/isosurface.c) against the analytic sphere
 * and torus: hit distances, normals, inside, the container's walls, open,
 * and no re-hit from the surface it found. The compiler is tested through
 * the language (tests/lang/functions, tests/errors). */
#include <math.h>

#include "../../tracer/fn.h"
#include "geo_rand.h"
#include "test.h"

#define OP(o) ((struct fn_op){.op = (o)})
#define ARG(n) ((struct fn_op){.op = FO_ARG, .i = (n)})

static struct fn_op K(double k)
{
	struct fn_op o = {.op = FO_CONST};
	o.u.k = k;
	return o;
}

/* x² + y² + z² − r²: the unit sphere's field for r = 1. */
static const struct fn_op sphere_code[] = {
	{.op = FO_ARG, .i = 0}, {.op = FO_ARG, .i = 0}, {.op = FO_MUL}, {.op = FO_ARG, .i = 1},
	{.op = FO_ARG, .i = 1}, {.op = FO_MUL}, {.op = FO_ADD}, {.op = FO_ARG, .i = 2},
	{.op = FO_ARG, .i = 2}, {.op = FO_MUL}, {.op = FO_ADD}, {.op = FO_CONST, .u.k = 1}, {.op = FO_SUB},
};
static const struct fn sphere_fn = {.kind = FN_CODE, .nparams = 3, .depth = 1, .cost = 13,
                                    .code = sphere_code, .ncode = 13};

static void t_machine(void)
{
	double a[FN_MAX_PARAMS] = {1, 2, 2};
	CHECK_NEAR(fn_eval(&sphere_fn, a), 8, 1e-15);
	/* select(x − 2, 10, 20, 30) and a call of the sphere's field */
	struct fn_op sel[] = {ARG(0), K(2), OP(FO_SUB), K(10), K(20), K(30), OP(FO_SELECT4)};
	struct fn f = {.kind = FN_CODE, .nparams = 3, .code = sel, .ncode = 7};
	double b[FN_MAX_PARAMS] = {1}, c[FN_MAX_PARAMS] = {2}, d[FN_MAX_PARAMS] = {3};
	CHECK(fn_eval(&f, b) == 10 && fn_eval(&f, c) == 20 && fn_eval(&f, d) == 30);
	struct fn_op call[] = {ARG(1), ARG(0), K(0), {.op = FO_CALL, .i = 3, .u.f = &sphere_fn},
	                       K(2), OP(FO_POW), {.op = FO_MATH1, .i = FM_SQRT}};
	f.code = call, f.ncode = 7;
	double e[FN_MAX_PARAMS] = {3, 4, 0}; /* sqrt((16 + 9 − 1)²) */
	CHECK_NEAR(fn_eval(&f, e), 24, 1e-12);
	struct fn_op dz[] = {K(1), ARG(0), OP(FO_DIV)}; /* 1/0 is no trap: +inf */
	f.code = dz, f.ncode = 3;
	double z[FN_MAX_PARAMS] = {0};
	CHECK(isinf(fn_eval(&f, z)));
	struct fn_internal_info ii = fn_internal(61);
	CHECK(ii.name && ii.nparams == 4);
	CHECK(!fn_internal(76).name || fn_internal(76).nparams == 3);
	CHECK(!fn_internal(-1).name && !fn_internal(FN_INTERNAL_COUNT).name);
}

static struct object iso(const struct fn *f, bool sphere_container)
{
	static struct isosurface s[8];
	static int next;
	struct isosurface *p = &s[next++ % 8];
	*p = (struct isosurface){.fn = f, .sphere = sphere_container, .lo = v3(-2, -2, -2), .hi = v3(2, 2, 2),
	                         .r = 2, .max_gradient = 4.5, .accuracy = 1e-3};
	struct object o = mk_obj(OBJ_ISOSURFACE);
	o.g.isosurface.iso = p;
	return o;
}

static void t_iso_sphere(void)
{
	for (int k = 0; k < 2; k++) {
		struct object o = iso(&sphere_fn, k);
		struct ray r = {v3(0.3, 0.2, -5), v3(0, 0, 1)};
		struct hit h;
		double want = 5 - sqrt(1 - 0.09 - 0.04);
		CHECK(shape_intersect(&o, &r, 0, INFINITY, &h));
		CHECK_NEAR(h.t, want, 1e-9);
		CHECK_NEAR(v_dot(h.n, v_norm(h.p)), 1, 1e-6); /* outward, radial */
		CHECK(h.entering);
		CHECK(shape_intersect(&o, &r, h.t + 1e-7 * (1 + v_len(h.p)), INFINITY, &h)); /* the far side */
		CHECK_NEAR(h.t, 5 + sqrt(1 - 0.09 - 0.04), 1e-9);
		CHECK(!h.entering);
		CHECK(shape_inside(&o, v3(0.5, 0, 0)) && !shape_inside(&o, v3(1.5, 0, 0)));
		CHECK(!shape_intersect(&o, &(struct ray){v3(1.2, 0, -5), v3(0, 0, 1)}, 0, INFINITY, &h));
		struct bbox b = shape_bounds(&o);
		CHECK(b.lo.x == -2 && b.hi.z == 2);
	}
}

/* The field x² + y² + z² − 1 cut by a smaller box: the box's walls close
 * the solid unless open. */
static void t_iso_walls(void)
{
	struct object o = iso(&sphere_fn, false);
	struct isosurface s = *o.g.isosurface.iso;
	s.lo = v3(-0.5, -0.5, -0.5), s.hi = v3(0.5, 0.5, 0.5);
	o.g.isosurface.iso = &s;
	struct ray r = {v3(0, 0, -5), v3(0, 0, 1)};
	struct hit h;
	CHECK(shape_intersect(&o, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 4.5, 1e-12);
	CHECK_NEAR(h.n.z, -1, 1e-12);
	CHECK(shape_intersect(&o, &r, 4.6, INFINITY, &h)); /* leaving through the back wall */
	CHECK_NEAR(h.t, 5.5, 1e-12);
	o.flags |= OF_OPEN;
	CHECK(!shape_intersect(&o, &r, 0, INFINITY, &h));
}

/* The radial (u,v) about the container's centre: a hit's (u,v) gives its
 * point back, and the unit sphere's field has the sphere's area. */
static void t_iso_uv(void)
{
	struct object o = iso(&sphere_fn, true);
	struct ray r = {v3(0.3, 0.2, -5), v3(0, 0, 1)};
	struct hit h;
	struct vec3 p, pu, pv;
	CHECK(shape_intersect(&o, &r, 0, INFINITY, &h));
	CHECK(shape_uv_point(&o, h.u, h.v, &p, &pu, &pv));
	CHECK(v_len(v_sub(p, h.p)) < 1e-9);
	CHECK(v_dot(v_cross(pu, pv), h.n) > 0); /* outward */
	CHECK_NEAR(shape_area(&o), 4 * M_PI, 1e-6);
}

/* A torus field about y through f_torus; random rays from outside that hit
 * it must not hit it again from just beyond the hit (no self-shadowing). */
static void t_iso_torus(void)
{
	struct fn tor = {.kind = FN_INTERNAL, .internal = 70, .nparams = 5, .depth = 1, .cost = 50};
	/* f_torus with its radii as arguments 3 and 4: wrap it in a program */
	struct fn_op code[] = {ARG(0), ARG(1), ARG(2), K(1), K(0.25), {.op = FO_CALL, .i = 5, .u.f = &tor}};
	struct fn f = {.kind = FN_CODE, .nparams = 3, .depth = 2, .cost = 56, .code = code, .ncode = 6};
	struct object o = iso(&f, true);
	struct ray r = {v3(1, 3, 0), v3(0, -1, 0)};
	struct hit h;
	CHECK(shape_intersect(&o, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 2.75, 1e-9);
	CHECK_NEAR(h.n.y, 1, 1e-6);
	rng_seed(7);
	int hits = 0, rehits = 0;
	for (int i = 0; i < 400; i++) {
		struct vec3 a = v_scale(rnd_dir(), 1.9), b = v_scale(rnd_dir(), 0.8);
		struct ray q = {a, v_sub(b, a)};
		if (!shape_intersect(&o, &q, 0, INFINITY, &h) || !h.entering)
			continue;
		hits++;
		struct ray out = {h.p, v_neg(v_norm(q.d))}; /* back the way it came */
		rehits += shape_intersect(&o, &out, 1e-7 * (1 + v_len(h.p)), INFINITY, &h);
	}
	CHECK(hits > 100);
	CHECK(rehits == 0);
}

int main(void)
{
	RUN(t_machine);
	RUN(t_iso_sphere);
	RUN(t_iso_walls);
	RUN(t_iso_uv);
	RUN(t_iso_torus);
	return test_done();
}
