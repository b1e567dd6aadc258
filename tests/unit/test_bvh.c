/* SPDX-License-Identifier: MIT */
/* test_bvh.c: the BVH (tracer/bvh.c) returns exactly the hit a brute-force
 * loop over every object returns (same t, same primitive), for thousands of
 * random rays through a random scene of 1000 spheres, boxes and triangles
 * with planes, a flattened union and a CSG leaf; shadow queries and skip
 * masks agree too; degenerate and empty scenes work; rays leaving sphere
 * surfaces agree too, and so do shadow and camera rays asked as one
 * packet. */
#include <stdio.h>
#include <string.h>
#include <stdlib.h>

#include "../../tracer/bvh.h"
#include "../../tracer/leafbox.h"
#include "geo_rand.h"
#include "test.h"

#define NOBJ 1000

/* The random scene: objects in the scene-model sense, top level in top[]. */
struct scene_fixture {
	struct object prims[NOBJ + 16]; /* primitives (some are union/CSG children) */
	struct object nodes[4];         /* CSG nodes */
	struct object *kids[16];        /* children of the CSG nodes */
	struct object *top[NOBJ + 8];   /* the top-level list */
	int ntop;                       /* entries of top */
};

/* One random bounded primitive somewhere in [−50,50]³. */
static struct object scatter(int i)
{
	struct object o;
	if (i % 3 == 0) {
		o = mk_obj(OBJ_SPHERE);
		o.g.sphere.c = rnd_vec(-50, 50);
		o.g.sphere.r = rndr(0.2, 3);
	} else if (i % 3 == 1) {
		o = rnd_prim(OBJ_BOX, false);
		o.xf = xf_keep(xf_then(rnd_xform(false, true), xf_translate(rnd_vec(-50, 50))));
	} else {
		o = mk_obj(OBJ_TRIANGLE);
		struct vec3 c = rnd_vec(-50, 50);
		for (int k = 0; k < 3; k++)
			o.g.triangle.p[k] = v_add(c, rnd_vec(-4, 4));
	}
	return o;
}

static void build_scene(struct scene_fixture *s)
{
	memset(s, 0, sizeof *s);
	for (int i = 0; i < NOBJ; i++) {
		s->prims[i] = scatter(i);
		s->top[s->ntop++] = &s->prims[i];
	}
	/* two planes (unbounded), far below and to the side */
	for (int i = 0; i < 2; i++) {
		struct object *p = &s->prims[NOBJ + i];
		*p = mk_obj(OBJ_PLANE);
		p->g.plane.n = i ? v3(1, 0.1, 0) : v3(0, 1, 0);
		p->g.plane.d = -80;
		s->top[s->ntop++] = p;
	}
	/* a union of five spheres (flattened by the build) */
	for (int i = 0; i < 5; i++) {
		s->prims[NOBJ + 2 + i] = mk_obj(OBJ_SPHERE);
		s->prims[NOBJ + 2 + i].g.sphere.c = v3(10 * i - 20, 0, 0);
		s->prims[NOBJ + 2 + i].g.sphere.r = 4;
		s->kids[i] = &s->prims[NOBJ + 2 + i];
	}
	s->nodes[0] = mk_obj(OBJ_UNION);
	s->nodes[0].g.csg.kids = s->kids, s->nodes[0].g.csg.n = 5;
	s->top[s->ntop++] = &s->nodes[0];
	/* a difference (kept whole as a leaf): box minus sphere */
	struct object *b = &s->prims[NOBJ + 7], *c = &s->prims[NOBJ + 8];
	*b = mk_obj(OBJ_BOX);
	b->g.box.lo = v3(20, 20, 20), b->g.box.hi = v3(30, 30, 30);
	*c = mk_obj(OBJ_SPHERE);
	c->g.sphere.c = v3(30, 30, 30), c->g.sphere.r = 6;
	s->kids[5] = b, s->kids[6] = c;
	s->nodes[1] = mk_obj(OBJ_DIFFERENCE);
	s->nodes[1].g.csg.kids = s->kids + 5, s->nodes[1].g.csg.n = 2;
	s->top[s->ntop++] = &s->nodes[1];
}

/* Nearest hit by testing every top-level object. */
static bool brute(struct object **top, int n, const struct ray *r, double tmin, double tmax,
                  unsigned skip, struct hit *h)
{
	bool found = false;
	for (int i = 0; i < n; i++)
		if (!(top[i]->flags & skip) && shape_intersect(top[i], r, tmin, tmax, h))
			tmax = h->t, found = true;
	return found;
}

/* A random ray: from anywhere in a large box, or from a surface. */
static struct ray rnd_ray(void)
{
	struct ray r = {rnd_vec(-70, 70), rnd_dir()};
	if (rnd() < 0.3) /* aim at the cloud's middle */
		r.d = v_norm(v_sub(rnd_vec(-20, 20), r.o));
	return r;
}

static void t_same_as_brute_force(void)
{
	static struct scene_fixture s;
	rng_seed(21);
	build_scene(&s);
	struct bvh *b = bvh_build(s.top, s.ntop);
	int unb, n = bvh_count(b, &unb);
	CHECK(n == NOBJ + 5 + 1);
	CHECK(unb == 2);
	int mism = 0, hits = 0;
	for (int i = 0; i < 20000; i++) {
		struct ray r = rnd_ray();
		double tmin = i % 2 ? 1e-6 : 5, tmax = i % 5 ? INFINITY : 60;
		struct hit hb, hf;
		bool gb = brute(s.top, s.ntop, &r, tmin, tmax, 0, &hb);
		bool gf = bvh_intersect(b, &r, tmin, tmax, &hf);
		hits += gb;
		if (gb != gf || (gb && (hb.t != hf.t || hb.obj != hf.obj))) {
			if (mism++ < 5)
				printf("#   ray %d: brute %d t=%.17g, bvh %d t=%.17g\n", i, gb, gb ? hb.t : 0, gf,
				       gf ? hf.t : 0);
		}
	}
	printf("# %d hits of 20000 rays, %d mismatches\n", hits, mism);
	CHECK(mism == 0);
	CHECK(hits > 8000);
	bvh_free(b);
}

/* Shadow queries, with and without a skip mask. */
static void t_occluded_and_skip(void)
{
	static struct scene_fixture s;
	rng_seed(22);
	build_scene(&s);
	for (int i = 0; i < NOBJ; i += 7)
		s.prims[i].flags |= OF_NO_SHADOW;
	struct bvh *b = bvh_build(s.top, s.ntop);
	int mism = 0, blocked = 0;
	for (int i = 0; i < 20000; i++) {
		struct ray r = rnd_ray();
		double len = rndr(1, 150);
		unsigned skip = i % 2 ? OF_NO_SHADOW : 0;
		struct hit h;
		bool gb = brute(s.top, s.ntop, &r, 1e-6, len, skip, &h);
		bool gf = skip ? bvh_occluded_skip(b, &r, 1e-6, len, skip) : bvh_occluded(b, &r, 1e-6, len);
		blocked += gb;
		mism += gb != gf;
		if (skip) { /* and the nearest hit with the mask */
			struct hit h2;
			bool g2 = bvh_intersect_skip(b, &r, 1e-6, len, skip, &h2);
			mism += g2 != gb || (gb && (h.t != h2.t || h.obj != h2.obj));
		}
	}
	printf("# %d of 20000 segments blocked, %d mismatches\n", blocked, mism);
	CHECK(mism == 0);
	CHECK(blocked > 5000);
	bvh_free(b);
}

/* Every centroid in one place: the build must stop splitting and still work. */
static void t_degenerate_and_empty(void)
{
	static struct object o[300];
	struct object *top[300];
	for (int i = 0; i < 300; i++) {
		o[i] = mk_obj(OBJ_SPHERE);
		o[i].g.sphere.r = 1 + i * 0.001;
		top[i] = &o[i];
	}
	struct bvh *b = bvh_build(top, 300);
	struct ray r = {v3(-10, 0, 0), v3(1, 0, 0)};
	struct hit h;
	CHECK(bvh_intersect(b, &r, 0, INFINITY, &h));
	CHECK_NEAR(h.t, 10 - 1.299, 1e-12);
	CHECK(h.obj == &o[299]);
	CHECK(bvh_intersect(b, &r, 9, INFINITY, &h)); /* from inside them all */
	CHECK_NEAR(h.t, 11, 1e-12);
	CHECK(h.obj == &o[0]);
	bvh_free(b);

	b = bvh_build(NULL, 0);
	CHECK(!bvh_intersect(b, &r, 0, INFINITY, &h));
	CHECK(!bvh_occluded(b, &r, 0, INFINITY));
	CHECK(bvh_count(b, NULL) == 0);
	struct bbox e = bvh_bounds(b);
	CHECK(e.lo.x > e.hi.x);
	bvh_free(b);
}

/* Axis-parallel rays (zero direction components) and rays along box faces. */
static void t_axis_rays(void)
{
	static struct scene_fixture s;
	rng_seed(23);
	build_scene(&s);
	struct bvh *b = bvh_build(s.top, s.ntop);
	int mism = 0;
	for (int i = 0; i < 6000; i++) {
		struct ray r = {rnd_vec(-60, 60), v3(0, 0, 0)};
		int ax = i % 3;
		r.d = v3(ax == 0 ? (i & 8 ? 1 : -1) : 0, ax == 1 ? (i & 8 ? 1 : -1) : 0,
		         ax == 2 ? (i & 8 ? 1 : -1) : 0);
		struct hit hb, hf;
		bool gb = brute(s.top, s.ntop, &r, 0, INFINITY, 0, &hb);
		bool gf = bvh_intersect(b, &r, 0, INFINITY, &hf);
		mism += gb != gf || (gb && (hb.t != hf.t || hb.obj != hf.obj));
	}
	CHECK(mism == 0);
	bvh_free(b);
}

/* Rays that start on a sphere (as reflected, refracted and shadow rays do),
 * in and out of it, among touching and overlapping spheres, some moved or
 * turned and scaled: the nearest and any hit agree with brute force (the
 * spheres' t-only test, whose full hit is filled in at the end, included). */
static void t_from_surfaces(void)
{
	enum { NS = 400 };
	static struct object o[NS];
	struct object *top[NS];
	rng_seed(24);
	for (int i = 0; i < NS; i++) {
		o[i] = mk_obj(OBJ_SPHERE);
		o[i].g.sphere.r = rndr(0.05, 2);
		/* every other sphere touches or overlaps the previous one */
		struct vec3 c = i % 2 && i ? v_madd(o[i - 1].g.sphere.c, rnd_dir(), o[i - 1].g.sphere.r + o[i].g.sphere.r * rndr(0.5, 1))
		                           : rnd_vec(-20, 20);
		o[i].g.sphere.c = c;
		if (i % 5 == 0) { /* the same sphere through a similarity */
			o[i].g.sphere.c = v3(0, 0, 0);
			o[i].g.sphere.r = 1;
			o[i].xf = xf_keep(xf_then(xf_then(xf_scale(v3(0.7, 0.7, 0.7)), xf_rotate(rnd_vec(0, 90))),
			                          xf_translate(c)));
		}
		top[i] = &o[i];
	}
	struct bvh *b = bvh_build(top, NS);
	int mism = 0, hits = 0;
	for (int i = 0; i < 20000; i++) {
		const struct object *s = &o[(int)(rnd() * NS) % NS];
		struct vec3 d = rnd_dir(), q;
		shape_uv_point(s, rnd(), rnd(), &q, NULL, NULL);
		struct ray r = {v_madd(q, d, i % 3 ? 1e-6 : 0), d};
		double tmin = i % 2 ? 1e-9 : 0, tmax = i % 4 ? INFINITY : rndr(0.01, 30);
		struct hit hb, hf;
		bool gb = brute(top, NS, &r, tmin, tmax, 0, &hb);
		bool gf = bvh_intersect(b, &r, tmin, tmax, &hf);
		hits += gb;
		bool bad = gb != gf || (gb && (hb.t != hf.t || hb.obj != hf.obj || hb.u != hf.u || hb.v != hf.v ||
		                               hb.n.x != hf.n.x || hb.p.y != hf.p.y || hb.dpdv.z != hf.dpdv.z ||
		                               hb.entering != hf.entering));
		bool go = bvh_occluded(b, &r, tmin, tmax);
		if ((bad || go != gb) && mism < 8)
			printf("#   ray %d from %d (xf %d): brute %d t=%.17g obj %d, bvh %d t=%.17g obj %d, occluded %d\n", i,
			       (int)(s - o), s->xf != NULL, gb, gb ? hb.t : 0, gb ? (int)(hb.obj - o) : -1, gf,
			       gf ? hf.t : 0, gf ? (int)(hf.obj - o) : -1, go);
		mism += bad + (go != gb);
	}
	printf("# %d hits of 20000 rays from surfaces, %d mismatches\n", hits, mism);
	CHECK(mism == 0);
	CHECK(hits > 5000);
	bvh_free(b);
}

/* Shadow rays as one packet (bvh_occluded_packet) answer as they do one by
 * one and as brute force does: 1 to 16 rays at a time, from nearby points
 * on the scene's surfaces towards one light point (as a 4×4 block's camera
 * hits send them), or from anywhere to anywhere, with and without a skip
 * mask, over (0, tmax). */
static void t_occluded_packet(void)
{
	static struct scene_fixture s;
	rng_seed(25);
	build_scene(&s);
	for (int i = 0; i < NOBJ; i += 5)
		s.prims[i].flags |= OF_NO_SHADOW;
	struct bvh *b = bvh_build(s.top, s.ntop);
	int mism = 0, blocked = 0, total = 0;
	for (int k = 0; k < 3000; k++) {
		int n = 1 + k % BVH_PACKET;
		unsigned skip = k % 2 ? OF_NO_SHADOW : 0;
		struct vec3 light = rnd_vec(-90, 90), at = rnd_vec(-40, 40);
		struct ray r[BVH_PACKET];
		double tmax[BVH_PACKET];
		bool got[BVH_PACKET];
		for (int i = 0; i < n; i++) {
			struct vec3 p = v_add(at, rnd_vec(-1, 1));
			if (k % 3 == 0) { /* on the nearest surface along a camera-like ray */
				struct ray c = {light, v_norm(v_sub(p, light))};
				struct hit h;
				if (brute(s.top, s.ntop, &c, 0, INFINITY, 0, &h))
					p = v_madd(h.p, h.n, 1e-7 * (1 + fabs(h.p.x) + fabs(h.p.y) + fabs(h.p.z)));
				light = v_add(light, v3(0, 200, 0)); /* the light is elsewhere */
			}
			if (k % 7 == 6)
				p = rnd_vec(-70, 70), light = rnd_vec(-70, 70);
			struct vec3 d = v_sub(light, p);
			double len = v_len(d);
			r[i] = (struct ray){p, v_scale(d, 1 / len)};
			tmax[i] = k % 11 == 10 ? INFINITY : len * (1 - 1e-9);
		}
		bvh_occluded_packet(b, n, r, tmax, skip, got);
		for (int i = 0; i < n; i++) {
			struct hit h;
			bool gb = brute(s.top, s.ntop, &r[i], 0, tmax[i], skip, &h);
			bool g1 = bvh_occluded_skip(b, &r[i], 0, tmax[i], skip);
			if ((gb != got[i] || g1 != got[i]) && mism++ < 5)
				printf("#   packet %d lane %d: brute %d, one %d, packet %d\n", k, i, gb, g1, got[i]);
			blocked += gb;
			total++;
		}
	}
	printf("# %d of %d shadow rays blocked, %d mismatches\n", blocked, total, mism);
	CHECK(mism == 0);
	CHECK(blocked > total / 10 && blocked < total * 9 / 10);
	bvh_free(b);

	/* a scene of three spheres, traced without Embree (BRUTE_MAX) */
	static struct object few[3];
	struct object *ftop[3];
	for (int i = 0; i < 3; i++) {
		few[i] = mk_obj(OBJ_SPHERE);
		few[i].g.sphere.c = v3(3 * i, 0, 0), few[i].g.sphere.r = 1;
		ftop[i] = &few[i];
	}
	b = bvh_build(ftop, 3);
	struct ray fr[BVH_PACKET];
	double ft[BVH_PACKET];
	bool fgot[BVH_PACKET];
	int fblocked = 0, fmism = 0;
	for (int i = 0; i < BVH_PACKET; i++) {
		fr[i] = (struct ray){v3(-5 + i, 5, 0), v_norm(v3(0.3 * (i % 5) - 0.6, -1, 0))};
		ft[i] = i % 3 ? INFINITY : 4.5;
	}
	bvh_occluded_packet(b, BVH_PACKET, fr, ft, 0, fgot);
	for (int i = 0; i < BVH_PACKET; i++) {
		fblocked += fgot[i];
		fmism += fgot[i] != bvh_occluded_skip(b, &fr[i], 0, ft[i], 0);
	}
	CHECK(fmism == 0);
	CHECK(fblocked > 0 && fblocked < BVH_PACKET);
	bvh_free(b);

	b = bvh_build(NULL, 0); /* nothing to block: every lane is clear */
	struct ray r[2] = {{v3(0, 0, 0), v3(1, 0, 0)}, {v3(1, 1, 1), v3(0, 1, 0)}};
	double tmax[2] = {INFINITY, 5};
	bool got[2] = {true, true};
	bvh_occluded_packet(b, 2, r, tmax, 0, got);
	CHECK(!got[0] && !got[1]);
	bvh_free(b);
}

/* Packets of rays tangent to a sphere, the only leaf (a hierarchy without
 * an Embree scene: brute), their lines a rounding error from its rim, so
 * d·n at the hit is a few ulps either side of 0: each lane's hit, point,
 * normal and entering as the ray alone gets it, bit for bit. With native
 * 16-wide packets hits16 finishes them; it read the packet's rows while
 * rows, never set without Embree, was garbage (every hit's point wrong). */
static void t_tangent_packet(void)
{
	rng_seed(41);
	int mism = 0, hits = 0, total = 0, ins = 0;
	for (int k = 0; k < 4000; k++) {
		static struct object sp;
		struct object *one[1] = {&sp};
		memset(&sp, 0, sizeof sp);
		sp.kind = OBJ_SPHERE;
		sp.g.sphere.c = rnd_vec(-50, 50), sp.g.sphere.r = rndr(0.1, 20);
		struct bvh *b = bvh_build(one, 1);
		struct vec3 c = sp.g.sphere.c, u = rnd_dir();
		struct vec3 side = v_norm(v_cross(u, rnd_dir()));
		struct ray r[BVH_PACKET];
		for (int i = 0; i < BVH_PACKET; i++) {
			struct vec3 o = v_madd(v_madd(c, side, sp.g.sphere.r * (1 + (i - 8) * 2e-16)), u,
			                       -rndr(1, 60) * sp.g.sphere.r);
			r[i] = (struct ray){o, v_scale(u, rndr(0.3, 3))};
		}
		struct hit h[BVH_PACKET];
		bool found[BVH_PACKET];
		bvh_intersect_packet(b, BVH_PACKET, r, 0, INFINITY, BVH_NO_UV, h, found);
		for (int i = 0; i < BVH_PACKET; i++) {
			struct hit h1;
			bool f1 = bvh_intersect_skip(b, &r[i], 0, INFINITY, BVH_NO_UV, &h1);
			if (f1 != found[i] || (f1 && (memcmp(&h1.t, &h[i].t, sizeof h1.t) || h1.obj != h[i].obj ||
			                              memcmp(&h1.p, &h[i].p, sizeof h1.p) ||
			                              memcmp(&h1.n, &h[i].n, sizeof h1.n) || h1.entering != h[i].entering)))
				if (mism++ < 3)
					printf("#   packet %d lane %d: alone p.x %.17g entering %d, in the packet p.x %.17g entering %d\n",
					       k, i, h1.p.x, h1.entering, h[i].p.x, h[i].entering);
			hits += f1, ins += f1 && h1.entering, total++;
		}
		bvh_free(b);
	}
	printf("# %d of %d tangent rays hit (%d entering), %d mismatches\n", hits, total, ins, mism);
	CHECK(mism == 0);
	CHECK(hits > total / 4 && ins > hits / 2 && ins < hits); /* some at the rim not entering */
}

/* Camera rays as one packet (bvh_intersect_packet) get the hits they get
 * one by one (bvh_intersect_skip), bit for bit (t, object, point, normal,
 * entering; with AVX-512 a packet's sphere hits are finished sixteen lanes
 * at a time, hits16): 1 to 16 rays at a time from
 * one eye towards nearby points of the cloud of spheres, boxes and
 * triangles, from inside a sphere, just grazing one (where a sphere's cheap
 * rejections, run on all lanes at once with AVX-512, are closest to
 * turning a lane away; there its roots are solved on all lanes at once
 * too, roots16), or anywhere, from tmin 0, a tmin inside the cloud or
 * a negative one, with and without a skip mask (and BVH_UV_UNREAD). */
static void t_intersect_packet(void)
{
	static struct scene_fixture s;
	rng_seed(31);
	build_scene(&s);
	for (int i = 0; i < NOBJ; i += 7)
		s.prims[i].flags |= OF_NO_IMAGE;
	struct bvh *b = bvh_build(s.top, s.ntop);
	int mism = 0, hits = 0, total = 0;
	for (int k = 0; k < 3000; k++) {
		int n = 1 + k % BVH_PACKET;
		unsigned skip = k % 2 ? OF_NO_IMAGE : 0;
		double tmin = k % 5 == 3 ? 30 : k % 5 == 4 ? -10 : 0;
		struct vec3 eye = rnd_vec(-90, 90), at = rnd_vec(-40, 40);
		const struct object *sp = &s.prims[3 * (k % (NOBJ / 3))]; /* a sphere (scatter) */
		struct ray r[BVH_PACKET];
		for (int i = 0; i < n; i++) {
			struct vec3 p = v_add(at, rnd_vec(-2, 2));
			if (k % 4 == 2) /* from inside sphere sp */
				eye = sp->g.sphere.c;
			if (k % 9 == 8)
				p = rnd_vec(-70, 70), eye = rnd_vec(-70, 70);
			r[i] = (struct ray){eye, v_norm(v_sub(p, eye))};
			if (k % 4 == 1) { /* grazing sphere sp: parallel to eye → centre, its rim a few ulps away */
				struct vec3 c = sp->g.sphere.c, u = v_norm(v_sub(c, eye));
				struct vec3 side = v_norm(v_cross(u, fabs(u.x) < 0.9 ? v3(1, 0, 0) : v3(0, 1, 0)));
				struct vec3 o = v_madd(c, side, sp->g.sphere.r * (1 + (i - 8) * 1e-15));
				r[i] = (struct ray){v_madd(o, u, -v_len(v_sub(c, eye))), u};
			}
		}
		struct hit h[BVH_PACKET];
		bool found[BVH_PACKET];
		/* every third packet as the eye pass asks without maps: the same hits */
		bvh_intersect_packet(b, n, r, tmin, INFINITY, skip | BVH_NO_UV | (k % 3 ? 0 : BVH_UV_UNREAD), h, found);
		for (int i = 0; i < n; i++) {
			struct hit h1;
			bool f1 = bvh_intersect_skip(b, &r[i], tmin, INFINITY, skip | BVH_NO_UV, &h1);
			bool bad = f1 != found[i] ||
			           (f1 && (h1.t != h[i].t || h1.obj != h[i].obj || h1.n.x != h[i].n.x ||
			                   h1.n.y != h[i].n.y || h1.n.z != h[i].n.z || h1.p.x != h[i].p.x ||
			                   h1.p.y != h[i].p.y || h1.p.z != h[i].p.z || h1.entering != h[i].entering));
			if (bad && mism++ < 5)
				printf("#   packet %d lane %d: one %d t %.17g, packet %d t %.17g\n", k, i, f1, f1 ? h1.t : 0,
				       found[i], found[i] ? h[i].t : 0);
			hits += f1;
			total++;
		}
	}
	printf("# %d of %d packet rays hit, %d mismatches\n", hits, total, mism);
	CHECK(mism == 0);
	CHECK(hits > total / 4 && hits < total);
	bvh_free(b);
}

/* Leaves a ray meets at one t go to the first in collection order, as
 * brute force gives, though the hierarchy numbers its leaves in spatial
 * (Morton) order: here nested boxes sharing the corner (0,0,0), listed
 * largest first, so that the smaller ones, whose centres lie nearer the
 * scene's low corner, come first in Morton order. A ray entering through
 * the shared face z = 0 meets every box there at the same t. */
static void t_ties_collection_order(void)
{
	enum { NB = 40 };
	static struct object o[NB];
	struct object *top[NB];
	for (int i = 0; i < NB; i++) {
		double side = NB - i;
		o[i] = mk_obj(OBJ_BOX);
		o[i].g.box.lo = v3(0, 0, 0), o[i].g.box.hi = v3(side, side, side);
		top[i] = &o[i];
	}
	struct bvh *b = bvh_build(top, NB);
	CHECK(bvh_walks(b)); /* through Embree: more leaves than brute tests */
	rng_seed(41);
	int mism = 0, first = 0, total = 0;
	for (int k = 0; k < 400; k++) {
		struct ray r[BVH_PACKET];
		for (int i = 0; i < BVH_PACKET; i++)
			r[i] = (struct ray){v3(rndr(0.01, 0.99), rndr(0.01, 0.99), -5), v3(rndr(-0.1, 0.1), rndr(-0.1, 0.1), 1)};
		struct hit h[BVH_PACKET];
		bool found[BVH_PACKET];
		bvh_intersect_packet(b, BVH_PACKET, r, 0, INFINITY, 0, h, found);
		for (int i = 0; i < BVH_PACKET; i++) {
			struct hit hb, h1;
			bool gb = brute(top, NB, &r[i], 0, INFINITY, 0, &hb);
			bool g1 = bvh_intersect(b, &r[i], 0, INFINITY, &h1);
			mism += gb != g1 || gb != found[i] ||
			        (gb && (hb.obj != h1.obj || hb.t != h1.t || hb.obj != h[i].obj || hb.t != h[i].t));
			first += gb && hb.obj == &o[0];
			total++;
		}
	}
	printf("# %d of %d rays tie at the shared face and go to the first box, %d mismatches\n", first, total,
	       mism);
	CHECK(mism == 0);
	CHECK(first > total / 2);
	bvh_free(b);
}

/* Scenes of at most four cheap bounded leaves are traced without Embree
 * (bvh.c's BRUTE_MAX), and so are scenes of at most eight of any kind, by
 * their boxes (LEAFBOX_MAX): the hits are those of brute force and of the
 * same leaves with eight more, out of every ray's way, which puts Embree
 * back, bit for bit (nearest, any hit, and the full hit filled in at the
 * end), for rays in any direction and along the axes. A torus's t is the
 * same to 1e-12 (of 1 + t) only: its root is refined within the interval asked, which
 * ends at the best hit so far, found in a different order each way. */
static void t_small_scenes(void)
{
	enum { NK = 8, FAR = 8 };
	static struct object o[NK + 1 + FAR];
	struct object *top[NK + 1 + FAR];
	const enum object_kind kind[NK] = {OBJ_SPHERE, OBJ_SPHERE, OBJ_BOX,      OBJ_SPHERE,
	                                OBJ_TORUS,  OBJ_CONE,   OBJ_CYLINDER, OBJ_BOX};
	rng_seed(25);
	int mism = 0, hits = 0, torus_hits = 0;
	for (int k = 1; k <= NK; k++) {
		for (int i = 0; i < k; i++) { /* touching spheres, one moved, a box, a torus… */
			o[i] = mk_obj(kind[i]);
			if (i == 2) {
				o[i].g.box.lo = v3(-1, -1, -1), o[i].g.box.hi = v3(0.5, 1, 2);
			} else if (kind[i] == OBJ_SPHERE) {
				o[i].g.sphere.c = v3(1.5 * i, 0.3 * i, 0);
				o[i].g.sphere.r = 1 - 0.1 * i;
			} else {
				o[i] = rnd_prim(kind[i], false);
				o[i].xf = xf_keep(xf_then(rnd_xform(false, true), xf_translate(rnd_vec(-2, 2))));
			}
			if (i == 3)
				o[i].xf = xf_keep(xf_then(xf_rotate(v3(10, 20, 30)), xf_translate(v3(0, 2, 0))));
			top[i] = &o[i];
		}
		o[k] = mk_obj(OBJ_PLANE); /* a floor, unbounded */
		o[k].g.plane.n = v3(0, 1, 0), o[k].g.plane.d = -1.5;
		top[k] = &o[k];
		for (int i = 0; i < FAR; i++) { /* far behind every ray's start */
			o[k + 1 + i] = mk_obj(OBJ_SPHERE);
			o[k + 1 + i].g.sphere.c = v3(3 * i, 0, -500), o[k + 1 + i].g.sphere.r = 1;
			top[k + 1 + i] = &o[k + 1 + i];
		}
		struct bvh *small = bvh_build(top, k + 1), *big = bvh_build(top, k + 1 + FAR);
		int nb = bvh_count(big, NULL);
		CHECK(bvh_count(small, NULL) == k && nb == k + FAR);
		for (int i = 0; i < 4000; i++) {
			struct ray r = {rnd_vec(-4, 4), rnd_dir()};
			if (r.d.z < 0)
				r.d.z = -r.d.z;
			if (i % 2) { /* from a surface */
				const struct object *s = &o[(int)(rnd() * k) % k];
				struct vec3 q;
				shape_uv_point(s, rnd(), rnd(), &q, NULL, NULL);
				r.o = q;
			}
			if (i % 5 == 0) /* along an axis or a plane of two */
				r.d = i % 10 ? v3(0, r.d.y, r.d.z < 0.1 ? 0 : r.d.z) : v3(i % 20 ? -1 : 1, 0, 0);
			double tmin = i % 3 ? 1e-9 : 0, tmax = i % 4 ? INFINITY : rndr(0.01, 10);
			struct hit hb, hs, he;
			bool gb = brute(top, k + 1, &r, tmin, tmax, 0, &hb);
			bool gs = bvh_intersect(small, &r, tmin, tmax, &hs);
			bool ge = bvh_intersect(big, &r, tmin, tmax, &he);
			hits += gs;
			bool bad = gb != gs || gs != ge || (gs && (hb.obj != hs.obj || he.obj != hs.obj));
			if (gs && !bad && hs.obj->kind == OBJ_TORUS) /* see above */
				bad = !(fabs(hb.t - hs.t) <= 1e-12 * (1 + hs.t) && fabs(he.t - hs.t) <= 1e-12 * (1 + hs.t));
			else if (gs && !bad)
				bad = hb.t != hs.t || he.t != hs.t || he.u != hs.u || he.v != hs.v || he.n.x != hs.n.x ||
				      he.p.y != hs.p.y || he.dpdu.z != hs.dpdu.z || he.entering != hs.entering;
			bad |= bvh_occluded(small, &r, tmin, tmax) != gb || bvh_occluded(big, &r, tmin, tmax) != gb;
			torus_hits += gs && hs.obj->kind == OBJ_TORUS;
			if (bad && mism < 5)
				printf("#   %d leaves, ray %d: brute %d t=%.17g, small %d t=%.17g, embree %d t=%.17g\n", k, i, gb,
				       gb ? hb.t : 0, gs, gs ? hs.t : 0, ge, ge ? he.t : 0);
			mism += bad;
		}
		bvh_free(small), bvh_free(big);
	}
	printf("# %d hits (%d on a torus) of %d rays in scenes of 1-8 leaves, %d mismatches\n", hits, torus_hits,
	       NK * 4000, mism);
	CHECK(mism == 0);
	CHECK(hits > NK * 2000);
	CHECK(torus_hits > 1000);
}

static bool never(const void *ctx, const struct object *o)
{
	(void)ctx, (void)o;
	return false;
}

static bool always(const void *ctx, const struct object *o)
{
	(void)ctx, (void)o;
	return true;
}

/* bvh_intersect_lazy: with full saying no, the object and t of the nearest
 * hit (a sphere or plane found by its t alone, or any other leaf in full);
 * with full saying yes, the whole hit, bit for bit. On the random scene
 * (Embree) and on a sphere over a plane (no Embree). */
static void t_lazy(void)
{
	static struct scene_fixture s;
	rng_seed(26);
	build_scene(&s);
	struct object small[2] = {mk_obj(OBJ_SPHERE), mk_obj(OBJ_PLANE)};
	small[0].g.sphere.c = v3(0, 3, 0), small[0].g.sphere.r = 1;
	small[1].g.plane.n = v3(0, 1, 0);
	struct object *stop[2] = {&small[0], &small[1]};
	int mism = 0, hits = 0;
	for (int k = 0; k < 2; k++) {
		struct bvh *b = k ? bvh_build(stop, 2) : bvh_build(s.top, s.ntop);
		for (int i = 0; i < 10000; i++) {
			struct ray r = k ? (struct ray){v3(rndr(-0.5, 0.5), 10, rndr(-0.5, 0.5)), v3(rndr(-0.3, 0.3), -1, rndr(-0.3, 0.3))}
			                 : rnd_ray();
			if (k && i % 2) /* from inside the sphere */
				r.o = v3(0, 3, 0);
			struct hit hf, hn, ha;
			bool gf = bvh_intersect_skip(b, &r, 1e-9, INFINITY, BVH_NO_UV, &hf);
			bool gn = bvh_intersect_lazy(b, &r, 1e-9, INFINITY, BVH_NO_UV, &hn, never, NULL);
			bool ga = bvh_intersect_lazy(b, &r, 1e-9, INFINITY, BVH_NO_UV, &ha, always, NULL);
			hits += gf;
			bool bad = gf != gn || gf != ga ||
			           (gf && (hn.obj != hf.obj || hn.t != hf.t || ha.obj != hf.obj || ha.t != hf.t ||
			                   ha.p.x != hf.p.x || ha.p.y != hf.p.y || ha.n.z != hf.n.z || ha.entering != hf.entering));
			if (bad && mism < 5)
				printf("#   scene %d ray %d: full %d t=%.17g, lazy %d t=%.17g\n", k, i, gf, gf ? hf.t : 0, gn,
				       gn ? hn.t : 0);
			mism += bad;
		}
		bvh_free(b);
	}
	printf("# %d hits of 20000 rays, %d mismatches\n", hits, mism);
	CHECK(mism == 0);
	CHECK(hits > 12000);
}

/* The slab test of leafbox.c for one box alone, as its plain C version
 * runs it: the bits and entries leafbox_hits gives each leaf, whichever
 * lanes hold them. */
static bool one_box(struct bbox b, const struct ray *r, double tmin, double tmax, double *at)
{
	const double o[3] = {r->o.x, r->o.y, r->o.z}, iv[3] = {1 / r->d.x, 1 / r->d.y, 1 / r->d.z};
	const double lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
	double t0 = tmin, t1 = tmax;
	for (int k = 0; k < 3; k++) {
		double a = (lo[k] - o[k]) * iv[k], c = (hi[k] - o[k]) * iv[k];
		double n = a < c ? a : c, f = a < c ? c : a;
		t0 = n > t0 ? n : t0;
		t1 = f < t1 ? f : t1;
	}
	*at = t0 - 1e-12 * fabs(t0);
	return *at <= t1 + 1e-12 * fabs(t1);
}

/* leafbox_hits (tracer/leafbox.h) never leaves out a box the ray meets:
 * for random boxes and rays (some along axes, some from a face), every
 * point of the ray over [tmin, tmax] found inside a box has that box's bit
 * set and its entry no later; the SSE2 and the AVX versions (when the CPU
 * has it) give the same bits and entries. */
static void t_leafbox(void)
{
	rng_seed(27);
	int missed = 0, differ = 0, inside = 0, set = 0, alone = 0;
	for (int k = 0; k < 3000; k++) {
		struct bbox b[LEAFBOX_MAX];
		int n = 1 + k % LEAFBOX_MAX;
		for (int i = 0; i < n; i++) {
			struct vec3 c = rnd_vec(-3, 3), e = rnd_vec(0.05, 2);
			b[i] = (struct bbox){v_sub(c, e), v_add(c, e)};
		}
		struct leafbox lb;
		leafbox_set(&lb, n, b);
		struct ray r = {rnd_vec(-6, 6), rnd_dir()};
		if (k % 4 == 0) /* aimed at a box */
			r.d = v_norm(v_sub(v_scale(v_add(b[k % n].lo, b[k % n].hi), 0.5), r.o));
		if (k % 4 == 1)
			r.d = v3(0, k % 8 == 1 ? 1 : -1, 0);
		if (k % 4 == 2) /* from a face of box 0 */
			r.o.x = b[0].lo.x, r.o.y = b[0].lo.y + 0.3 * (b[0].hi.y - b[0].lo.y);
		double tmin = k % 3 ? 0 : rndr(0, 2), tmax = k % 5 ? INFINITY : rndr(2, 12), at[LEAFBOX_MAX];
		unsigned m = leafbox_hits(&lb, &r, tmin, tmax, at);
		for (int i = 0; i < n; i++)
			for (int j = 0; j <= 200; j++) {
				double t = tmin + (fmin(tmax, 20) - tmin) * j / 200;
				struct vec3 p = ray_at(r, t);
				if (p.x < b[i].lo.x || p.x > b[i].hi.x || p.y < b[i].lo.y || p.y > b[i].hi.y || p.z < b[i].lo.z ||
				    p.z > b[i].hi.z)
					continue;
				inside++;
				missed += !(m >> i & 1) || !(at[i] <= t);
				break;
			}
		set += __builtin_popcount(m);
		for (int i = 0; i < n; i++) { /* each leaf as if tested alone (5-7 leaves: behind lane 3's box) */
			double a;
			bool hit = one_box(b[i], &r, tmin, tmax, &a);
			alone += hit != (m >> i & 1) || (hit && memcmp(&a, &at[i], sizeof a) != 0);
		}
		if (lb.wide) {
			double at2[LEAFBOX_MAX];
			lb.wide = false;
			unsigned m2 = leafbox_hits(&lb, &r, tmin, tmax, at2);
			bool same = m2 == m;
			for (int i = 0; i < n; i++)
				same &= !(m >> i & 1) || at2[i] == at[i];
			differ += !same;
		}
	}
	printf("# %d boxes met at a sampled point, %d bits set, %d missed, %d differ between SSE2 and AVX, %d from a"
	       " box tested alone\n", inside, set, missed, differ, alone);
	CHECK(missed == 0 && differ == 0 && alone == 0);
	CHECK(inside > 1000 && set >= inside);
}

/* Rays leaving a convex object outward (shape_convex: spheres, boxes,
 * closed cylinders and cones, transformed, and a plane's half-space; not a
 * torus, an open cylinder or an inverse sphere) cannot hit it again: shape_intersect finds no hit, and
 * bvh_intersect_from and bvh_occluded_from, which do not test it, answer
 * bit for bit as bvh_intersect_skip and bvh_occluded_skip, in a scene of a
 * few leaves (tested by their boxes) and in one of many (Embree), from
 * points offset along the outward normal as the eye pass offsets them, in
 * directions down to grazing. */
static void t_leaving_convex(void)
{
	enum { NO = 40 };
	static struct object o[NO + 1];
	struct object *top[NO + 1];
	const enum object_kind kind[5] = {OBJ_SPHERE, OBJ_BOX, OBJ_CYLINDER, OBJ_CONE, OBJ_TORUS};
	rng_seed(26);
	for (int i = 0; i < NO; i++) {
		o[i] = rnd_prim(kind[i % 5], false);
		if (i % 3)
			o[i].xf = xf_keep(xf_then(rnd_xform(false, true), xf_translate(rnd_vec(-4, 4))));
		top[i] = &o[i];
	}
	o[NO] = mk_obj(OBJ_PLANE);
	o[NO].g.plane.n = v3(0, 1, 0), o[NO].g.plane.d = -6;
	top[NO] = &o[NO];
	struct object open = rnd_prim(OBJ_CYLINDER, true), cone = rnd_prim(OBJ_CONE, false), inv = rnd_prim(OBJ_SPHERE, false);
	inv.flags |= OF_INVERSE;
	CHECK(shape_convex(&o[0]) && shape_convex(&o[1]) && shape_convex(&o[2]) && shape_convex(&cone));
	CHECK(shape_convex(&o[NO]) && !shape_convex(&o[4]) && !shape_convex(&open) && !shape_convex(&inv));
	int mism = 0, self = 0, tested = 0, hits = 0;
	for (int pass = 0; pass < 2; pass++) {
		int n = pass ? NO + 1 : 6; /* 5 bounded leaves and the plane: by their boxes */
		if (!pass)
			top[5] = &o[NO];
		else
			top[5] = &o[5];
		struct bvh *b = bvh_build(top, n);
		for (int i = 0; i < 20000; i++) {
			const struct object *s = i % 8 ? top[(int)(rnd() * (n - 1)) % (n - 1)] : &o[NO]; /* or the plane */
			struct ray in = {v_scale(rnd_dir(), 30), v3(0, 0, 0)};
			struct bbox bx = s->kind == OBJ_PLANE ? (struct bbox){v3(-5, -5, -5), v3(5, 5, 5)} : shape_bounds(s);
			in.d = v_sub(v_add(v_scale(v_add(bx.lo, bx.hi), 0.5), rnd_vec(-1, 1)), in.o);
			struct hit h;
			if (!shape_intersect(s, &in, 0, INFINITY, &h))
				continue;
			struct vec3 d = rnd_dir();
			if (i % 4 == 0) /* grazing: nearly in the tangent plane */
				d = v_norm(v_madd(d, h.n, -v_dot(d, h.n) + 1e-9));
			if (v_dot(d, h.n) < 0)
				d = v_madd(d, h.n, -2 * v_dot(d, h.n));
			double eps = 1e-7 * (1 + fmax(fabs(h.p.x), fmax(fabs(h.p.y), fabs(h.p.z))));
			struct ray r = {v_madd(h.p, h.n, eps), d};
			double tmax = i % 2 ? INFINITY : rndr(0.1, 40);
			const struct object *from = shape_convex(s) ? s : NULL;
			struct hit hs, hf, ho;
			if (from && shape_intersect(s, &r, 0, tmax, &ho))
				self++;
			bool gs = bvh_intersect_skip(b, &r, 0, tmax, 0, &hs);
			bool gf = bvh_intersect_from(b, &r, 0, tmax, 0, from, &hf);
			bool os = bvh_occluded_skip(b, &r, 0, tmax, 0), of = bvh_occluded_from(b, &r, 0, tmax, 0, from);
			tested += from != NULL;
			hits += gs;
			mism += gs != gf || os != of || (gs && (hs.t != hf.t || hs.obj != hf.obj || hs.n.x != hf.n.x));
		}
		bvh_free(b);
	}
	printf("# %d rays leaving convex objects, %d hit something, %d hit their own object, %d mismatches\n",
	       tested, hits, self, mism);
	CHECK(self == 0 && mism == 0);
	CHECK(tested > 5000 && hits > 1000);
}

/* bvh_intersect_in answers bit for bit as bvh_intersect_skip, in a scene of
 * a few leaves (by their boxes), some far apart, two overlapping, a plane
 * through some: for rays refracted into a leaf or reflected inside it (as
 * the eye pass asks), rays from anywhere in its box, and rays given the
 * wrong leaf. */
static void t_inside_leaf(void)
{
	enum { NO = 7 };
	static struct object o[NO + 1];
	struct object *top[NO + 1];
	const enum object_kind kind[NO] = {OBJ_SPHERE, OBJ_BOX, OBJ_CYLINDER, OBJ_CONE, OBJ_TORUS, OBJ_SPHERE, OBJ_BOX};
	const struct vec3 at[NO] = {{-9, 0, 0}, {0, 0, 0}, {9, 0, 0}, {0, 9, 0}, {0, -9, 0}, {0.2, 0.1, 0}, {0, 0, 9}};
	rng_seed(27);
	for (int i = 0; i < NO; i++) {
		o[i] = rnd_prim(kind[i], false);
		o[i].xf = xf_keep(xf_then(rnd_xform(i % 2, true), xf_translate(at[i])));
		top[i] = &o[i];
	}
	o[NO] = mk_obj(OBJ_PLANE);
	o[NO].g.plane.n = v3(0.1, 1, 0), o[NO].g.plane.d = 0.3;
	top[NO] = &o[NO];
	struct bvh *b = bvh_build(top, NO + 1);
	int mism = 0, hits = 0, inside = 0;
	for (int i = 0; i < 30000; i++) {
		const struct object *s = top[i % NO];
		struct bbox bx = shape_bounds(s);
		struct vec3 c = v_scale(v_add(bx.lo, bx.hi), 0.5);
		struct ray r = {v_madd(c, rnd_dir(), 30), v3(0, 0, 0)};
		r.d = v_sub(v_add(c, rnd_vec(-0.5, 0.5)), r.o);
		struct hit h;
		if (!shape_intersect(s, &r, 0, INFINITY, &h))
			continue;
		double eps = 1e-7 * (1 + fmax(fabs(h.p.x), fmax(fabs(h.p.y), fabs(h.p.z))));
		struct vec3 n = h.entering ? h.n : v_neg(h.n), d = rnd_dir(); /* n: outward */
		if (v_dot(d, n) > 0)
			d = v_neg(d);
		struct ray q = {v_madd(h.p, n, -eps), d}; /* into it */
		if (i % 5 == 3 || (i % NO == 1 && i % 2)) /* anywhere in its box (often in the two that overlap) */
			q.o = v3(bx.lo.x + rnd() * (bx.hi.x - bx.lo.x), bx.lo.y + rnd() * (bx.hi.y - bx.lo.y),
			         bx.lo.z + rnd() * (bx.hi.z - bx.lo.z));
		const struct object *in = i % 7 == 6 ? top[(i + 3) % NO] : s;
		double tmax = i % 3 ? INFINITY : rndr(0.1, 5);
		unsigned skip = i % 11 == 10 ? OF_NO_IMAGE : 0;
		struct hit hs, hi;
		bool gs = bvh_intersect_skip(b, &q, 0, tmax, skip | BVH_NO_UV, &hs);
		bool gi = bvh_intersect_in(b, &q, 0, tmax, skip | BVH_NO_UV | (i % 2 ? BVH_UV_UNREAD : 0), in, &hi);
		hits += gs;
		inside += gs && hs.obj == s;
		mism += gs != gi || (gs && (memcmp(&hs.t, &hi.t, sizeof hs.t) || hs.obj != hi.obj ||
		                            memcmp(&hs.p, &hi.p, sizeof hs.p) || memcmp(&hs.n, &hi.n, sizeof hs.n)));
	}
	bvh_free(b);
	printf("# %d hits, %d on the leaf they start in, %d mismatches\n", hits, inside, mism);
	CHECK(mism == 0);
	CHECK(hits > 10000 && inside > hits / 2);
}

int main(void)
{
	RUN(t_same_as_brute_force);
	RUN(t_occluded_and_skip);
	RUN(t_degenerate_and_empty);
	RUN(t_axis_rays);
	RUN(t_from_surfaces);
	RUN(t_small_scenes);
	RUN(t_lazy);
	RUN(t_occluded_packet);
	RUN(t_intersect_packet);
	RUN(t_ties_collection_order);
	RUN(t_tangent_packet);
	RUN(t_leafbox);
	RUN(t_leaving_convex);
	RUN(t_inside_leaf);
	return test_done();
}
