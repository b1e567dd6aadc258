/* SPDX-License-Identifier: MIT */
/* geo_rand.h: deterministic random geometry for the shape, CSG and BVH
 * tests: a splitmix64 generator with fixed seeds, random directions,
 * transforms and primitives. Header-only, like test.h. */
#ifndef ARVO_GEO_RAND_H
#define ARVO_GEO_RAND_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "../../tracer/shape.h"

static uint64_t geo_rng; /* splitmix64 state */

static inline void rng_seed(uint64_t s) { geo_rng = s; }

/* splitmix64 (Steele, Lea, Flood 2014). */
static inline uint64_t rng_next(void)
{
	uint64_t z = (geo_rng += 0x9e3779b97f4a7c15ULL);
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	return z ^ (z >> 31);
}

/* Uniform in [0,1). */
static inline double rnd(void) { return (double)(rng_next() >> 11) * 0x1.0p-53; }
static inline double rndr(double a, double b) { return a + (b - a) * rnd(); }
static inline struct vec3 rnd_vec(double a, double b) { return v3(rndr(a, b), rndr(a, b), rndr(a, b)); }

/* Uniform on the unit sphere. */
static inline struct vec3 rnd_dir(void)
{
	double z = rndr(-1, 1), phi = rndr(0, 2 * M_PI), s = sqrt(fmax(0, 1 - z * z));
	return v3(s * cos(phi), s * sin(phi), z);
}

/* A transform kept where an object can point at it: a ring of slots, enough
 * for every object a test holds at once. */
static inline const struct xform *xf_keep(struct xform x)
{
	static struct xform ring[1 << 14];
	static unsigned next;
	struct xform *k = &ring[next++ & ((1u << 14) - 1)];
	*k = x;
	return k;
}

/* A fresh object of kind k with the identity transform. */
static inline struct object mk_obj(enum object_kind k)
{
	struct object o;
	memset(&o, 0, sizeof o);
	o.kind = k;
	o.xf = NULL;
	return o;
}

/* Scale (non-uniform unless uniform is set, mirrored one time in four when
 * mirror is set), then rotate, then translate, all random. */
static inline struct xform rnd_xform(bool uniform, bool mirror)
{
	struct vec3 s;
	if (uniform) {
		double k = rndr(0.4, 2.5);
		s = v3(k, k, k);
	} else {
		s = v3(rndr(0.4, 2.5), rndr(0.4, 2.5), rndr(0.4, 2.5));
	}
	if (mirror && rnd() < 0.25)
		s.x = -s.x;
	struct xform x = xf_scale(s);
	x = xf_then(x, xf_rotate(rnd_vec(-180, 180)));
	return xf_then(x, xf_translate(rnd_vec(-3, 3)));
}

/* Determinant of the transform's linear part. */
static inline double xf_det(const struct xform *x)
{
	const double(*m)[4] = x->m;
	return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
	       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
	       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* Random geometry of kind k in its own frame (identity xf); open asks for
 * OF_OPEN on cylinders and cones. */
static inline struct object rnd_prim(enum object_kind k, bool open)
{
	struct object o = mk_obj(k);
	switch (k) {
	case OBJ_SPHERE:
		o.g.sphere.c = rnd_vec(-1, 1);
		o.g.sphere.r = rndr(0.5, 2);
		break;
	case OBJ_PLANE:
		o.g.plane.n = v_scale(rnd_dir(), rndr(0.5, 2));
		o.g.plane.d = rndr(-1, 1);
		break;
	case OBJ_BOX:
		o.g.box.lo = rnd_vec(-1, 1);
		o.g.box.hi = v_add(o.g.box.lo, rnd_vec(0.3, 2));
		break;
	case OBJ_DISC:
		o.g.disc.c = rnd_vec(-1, 1);
		o.g.disc.n = v_scale(rnd_dir(), rndr(0.5, 2));
		o.g.disc.r = rndr(0.5, 2);
		o.g.disc.hole = rnd() < 0.5 ? 0 : rndr(0.1, 0.4) * o.g.disc.r;
		break;
	case OBJ_CYLINDER:
		o.g.cylinder.a = rnd_vec(-1, 1);
		o.g.cylinder.b = v_madd(o.g.cylinder.a, rnd_dir(), rndr(0.5, 3));
		o.g.cylinder.r = rndr(0.3, 1.5);
		break;
	case OBJ_CONE:
		o.g.cone.a = rnd_vec(-1, 1);
		o.g.cone.b = v_madd(o.g.cone.a, rnd_dir(), rndr(0.5, 3));
		o.g.cone.ra = rndr(0.3, 1.5);
		o.g.cone.rb = rnd() < 0.3 ? 0 : rndr(0.1, 1.5);
		break;
	case OBJ_TORUS:
		o.g.torus.major = rndr(1, 2);
		o.g.torus.minor = rndr(0.2, 0.8) * o.g.torus.major;
		break;
	case OBJ_TRIANGLE:
		do {
			for (int i = 0; i < 3; i++)
				o.g.triangle.p[i] = rnd_vec(-1.5, 1.5);
		} while (v_len(v_cross(v_sub(o.g.triangle.p[1], o.g.triangle.p[0]),
		                       v_sub(o.g.triangle.p[2], o.g.triangle.p[0]))) < 0.5);
		break;
	default:
		break;
	}
	if (open)
		o.flags |= OF_OPEN;
	return o;
}

/* Size of the object in the world: its bounds' diagonal (10 when unbounded). */
static inline double obj_scale(const struct object *o)
{
	if (!shape_bounded(o))
		return 10;
	struct bbox b = shape_bounds(o);
	return v_len(v_sub(b.hi, b.lo));
}

#endif
