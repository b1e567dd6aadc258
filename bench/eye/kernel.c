/* SPDX-License-Identifier: MIT */
/* kernel.c: the ray kernel alone on a bench/eye scene, against Embree's own
 * best on the same camera rays: how far arvo's eye pass is from what the
 * hardware and Embree give, whatever the shading costs.
 *
 *   kernel SCENE N [W H]
 *
 * Evaluates SCENE with -D N=N, sets the camera up as the eye pass does
 * (eye_setup) and makes the W×H (default 640×480) camera rays through the
 * pixel centres. Then, on one thread, in 4×4 blocks as the eye pass does:
 *   arvo      bvh_intersect_packet: arvo's hierarchy (Embree, user
 *             geometry, double-precision callbacks), the nearest hit
 *             without (u,v), as camera rays are traced;
 *   points    Embree alone: the scene's spheres as native sphere points
 *             (RTC_GEOMETRY_TYPE_SPHERE_POINT, float), rtcIntersect16 (or
 *             two rtcIntersect8 without native 16-wide packets);
 *   user      Embree alone with user geometry: the same spheres and a
 *             float ray-sphere test in the callback.
 * Then the shadow rays the eye pass casts from arvo's camera hits towards
 * the scene's first light (a point light), built as the eye pass builds
 * them (from the hit, off the surface on the side facing the camera, up to
 * just short of the light; none where the surface faces away), one at a
 * time, as the eye pass tests them on a cloud:
 *   arvo      bvh_occluded_from (the any-hit query, double-precision
 *             callbacks), the surface the ray leaves not tested;
 *   points    Embree alone, native sphere points, rtcOccluded1;
 *   user      Embree alone, user geometry, a float any-hit sphere test.
 * Each is run REPS times (5); the best time counts. Prints one line of
 * key=value pairs: rays, spheres, {arvo,points,user}_rays_per_s (camera
 * rays per second on one core), {arvo,points,user}_hits and agree (pixels
 * where the points kernel and arvo hit the same sphere, or both miss);
 * shadow_rays, {arvo,points,user}_shadow_per_s and
 * {arvo,points,user}_blocked (shadow rays blocked); and
 * {arvo,points,user}_mix_per_s: camera and shadow rays together per
 * second, the eye pass's ray mix (its "rays traced" counts both).
 * Exit status 0; 1 when the scene cannot be evaluated or holds anything
 * but spheres without a transform, or its first light is not a point
 * light. */
#include <embree3/rtcore.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../../common/diag.h"
#include "../../eval/eval.h"
#include "../../tracer/bvh.h"
#include "../../tracer/camera.h"
#include "../../tracer/eyepass.h"

enum { REPS = 5 };

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The spheres as Embree's float4 points (centre, radius). */
struct cloud {
	float *p;
	int n;
};

/* The roots t0 <= t1 of lane i of Embree's N-wide float rays r (rows:
 * origin, tnear, direction, …) against sphere s (centre, radius); false
 * when the ray's line misses it. */
static bool float_roots(const float *s, const float *r, unsigned N, unsigned i, float *t0, float *t1)
{
	float ox = r[0 * N + i] - s[0], oy = r[1 * N + i] - s[1], oz = r[2 * N + i] - s[2];
	float dx = r[4 * N + i], dy = r[5 * N + i], dz = r[6 * N + i];
	float A = dx * dx + dy * dy + dz * dz, B = ox * dx + oy * dy + oz * dz;
	float C = ox * ox + oy * oy + oz * oz - s[3] * s[3], D = B * B - A * C;
	if (D < 0)
		return false;
	float q = sqrtf(D);
	*t0 = (-B - q) / A, *t1 = (-B + q) / A;
	return true;
}

/* A float ray-sphere test for the user-geometry kernel. */
static void sphere_cb(const struct RTCIntersectFunctionNArguments *a)
{
	const struct cloud *c = a->geometryUserPtr;
	const float *s = c->p + 4 * a->primID;
	float *rh = (float *)a->rayhit;
	unsigned N = a->N;
	for (unsigned i = 0; i < N; i++) {
		float t, t1;
		if (!a->valid[i] || !float_roots(s, rh, N, i, &t, &t1))
			continue;
		if (t < rh[3 * N + i])
			t = t1;
		if (t < rh[3 * N + i] || t > rh[8 * N + i])
			continue;
		rh[8 * N + i] = t;
		((unsigned *)rh)[17 * N + i] = a->primID;
		((unsigned *)rh)[18 * N + i] = a->geomID;
	}
}

/* sphere_cb's test for a shadow ray: any hit in (tnear, tfar) blocks it
 * (tfar becomes -inf). */
static void sphere_occluded_cb(const struct RTCOccludedFunctionNArguments *a)
{
	const struct cloud *c = a->geometryUserPtr;
	const float *s = c->p + 4 * a->primID;
	float *r = (float *)a->ray;
	unsigned N = a->N;
	for (unsigned i = 0; i < N; i++) {
		float t0, t1;
		if (!a->valid[i] || !float_roots(s, r, N, i, &t0, &t1))
			continue;
		float lo = r[3 * N + i], hi = r[8 * N + i];
		if ((t0 > lo && t0 < hi) || (t1 > lo && t1 < hi))
			r[8 * N + i] = -INFINITY;
	}
}

static void bounds_cb(const struct RTCBoundsFunctionArguments *a)
{
	const struct cloud *c = a->geometryUserPtr;
	const float *s = c->p + 4 * a->primID;
	*a->bounds_o = (struct RTCBounds){s[0] - s[3], s[1] - s[3], s[2] - s[3], 0,
	                                  s[0] + s[3], s[1] + s[3], s[2] + s[3], 0};
}

/* Embree's own scene of the cloud: native points or user geometry. */
static RTCScene embree_scene(RTCDevice dev, const struct cloud *c, bool user)
{
	RTCScene sc = rtcNewScene(dev);
	RTCGeometry g;
	if (user) {
		g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
		rtcSetGeometryUserPrimitiveCount(g, (unsigned)c->n);
		rtcSetGeometryUserData(g, (void *)c);
		rtcSetGeometryBoundsFunction(g, bounds_cb, (void *)c);
		rtcSetGeometryIntersectFunction(g, sphere_cb);
		rtcSetGeometryOccludedFunction(g, sphere_occluded_cb);
	} else {
		g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_SPHERE_POINT);
		rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, c->p, 0,
		                           4 * sizeof(float), (size_t)c->n);
	}
	rtcCommitGeometry(g);
	rtcAttachGeometry(sc, g);
	rtcReleaseGeometry(g);
	rtcCommitScene(sc);
	return sc;
}

/* Embree's own kernel over scene sc: the camera rays. Returns the best
 * seconds of REPS runs and the hit sphere of each ray (-1: none) in prim. */
static double embree_run(RTCDevice dev, RTCScene sc, const struct ray *rays, int w, int h, int *prim)
{
	bool native16 = rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED);
	double best = INFINITY;
	for (int rep = 0; rep < REPS; rep++) {
		double t0 = now();
		for (int by = 0; by < h; by += 4)
			for (int bx = 0; bx < w; bx += 4) {
				_Alignas(64) struct RTCRayHit16 rh;
				_Alignas(64) int valid[16];
				int at[16];
				for (int i = 0; i < 16; i++) {
					int x = bx + i % 4, y = by + i / 4;
					valid[i] = x < w && y < h ? -1 : 0;
					at[i] = valid[i] ? y * w + x : 0;
					const struct ray *r = &rays[at[i]];
					rh.ray.org_x[i] = (float)r->o.x, rh.ray.org_y[i] = (float)r->o.y;
					rh.ray.org_z[i] = (float)r->o.z, rh.ray.tnear[i] = 0;
					rh.ray.dir_x[i] = (float)r->d.x, rh.ray.dir_y[i] = (float)r->d.y;
					rh.ray.dir_z[i] = (float)r->d.z, rh.ray.time[i] = 0;
					rh.ray.tfar[i] = INFINITY, rh.ray.mask[i] = ~0u;
					rh.ray.id[i] = 0, rh.ray.flags[i] = 0;
					rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
				}
				struct RTCIntersectContext ctx;
				rtcInitIntersectContext(&ctx);
				ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
				if (native16) {
					rtcIntersect16(valid, sc, &ctx, &rh);
				} else { /* the same rays as two packets of 8 */
					_Alignas(64) struct RTCRayHit8 h8[2];
					for (int k = 0; k < 2; k++) {
						float *dst = (float *)&h8[k];
						const float *src = (const float *)&rh;
						for (int row = 0; row < (int)(sizeof h8[k] / sizeof(float) / 8); row++)
							for (int i = 0; i < 8; i++)
								dst[row * 8 + i] = src[row * 16 + 8 * k + i];
						rtcIntersect8(valid + 8 * k, sc, &ctx, &h8[k]);
						float *back = (float *)&rh;
						for (int row = 0; row < (int)(sizeof h8[k] / sizeof(float) / 8); row++)
							for (int i = 0; i < 8; i++)
								back[row * 16 + 8 * k + i] = dst[row * 8 + i];
					}
				}
				for (int i = 0; i < 16; i++)
					if (valid[i])
						prim[at[i]] = rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID ? -1 : (int)rh.hit.primID[i];
			}
		double t = now() - t0;
		if (t < best)
			best = t;
	}
	return best;
}

/* A shadow ray: from o along unit d over (0, tmax); from, the surface it
 * leaves (arvo's query does not test it). */
struct shadow_ray {
	struct ray r;
	double tmax;
	const struct object *from;
};

/* Embree's own any-hit query on scene sc: the n shadow rays one at a time.
 * Returns the best seconds of REPS runs; *blocked, how many are. */
static double embree_shadows(RTCScene sc, const struct shadow_ray *sr, long n, long *blocked)
{
	double best = INFINITY;
	for (int rep = 0; rep < REPS; rep++) {
		long nb = 0;
		double t0 = now();
		for (long k = 0; k < n; k++) {
			const struct ray *r = &sr[k].r;
			struct RTCRay ray = {(float)r->o.x, (float)r->o.y, (float)r->o.z, 0,
			                     (float)r->d.x, (float)r->d.y, (float)r->d.z, 0,
			                     (float)sr[k].tmax, ~0u, 0, 0};
			struct RTCIntersectContext ctx;
			rtcInitIntersectContext(&ctx);
			rtcOccluded1(sc, &ctx, &ray);
			nb += ray.tfar < 0;
		}
		double t = now() - t0;
		if (t < best)
			best = t;
		*blocked = nb;
	}
	return best;
}

int main(int argc, char **argv)
{
	if (argc != 3 && argc != 5) {
		fprintf(stderr, "usage: kernel SCENE N [W H]\n");
		return 2;
	}
	int w = argc == 5 ? atoi(argv[3]) : 640, h = argc == 5 ? atoi(argv[4]) : 480;
	char def[64];
	snprintf(def, sizeof def, "N=%s", argv[2]);
	const char *defs[] = {def};
	struct diag dg;
	diag_init(&dg, stderr);
	struct eval_options eo;
	eval_default_options(&eo);
	eo.defines = defs, eo.ndefines = 1, eo.max_objects = 10000000;
	eo.width = w, eo.height = h;
	struct scene s;
	if (w < 4 || h < 4 || eval_scene(argv[1], &eo, &dg, &s) != 0)
		return 1;
	struct cloud c = {malloc(sizeof(float) * 4 * (size_t)(s.nobjects ? s.nobjects : 1)), s.nobjects};
	for (int i = 0; i < s.nobjects; i++) {
		const struct object *o = s.objects[i];
		if (o->kind != OBJ_SPHERE || o->xf) {
			fprintf(stderr, "kernel: object %d is not a sphere without a transform\n", i);
			return 1;
		}
		float *p = c.p + 4 * i;
		p[0] = (float)o->g.sphere.c.x, p[1] = (float)o->g.sphere.c.y;
		p[2] = (float)o->g.sphere.c.z, p[3] = (float)o->g.sphere.r;
	}
	if (s.nlights < 1 || s.lights[0].kind != LIGHT_POINT || s.lights[0].area) {
		fprintf(stderr, "kernel: the scene's first light is not a point light\n");
		return 1;
	}
	struct bvh *b = bvh_build(s.objects, s.nobjects);
	struct eye_ctx ctx;
	eye_setup(&ctx, &s, b, NULL, w, h, 1);
	struct ray *rays = malloc(sizeof *rays * (size_t)w * (size_t)h);
	const struct object **pa = malloc(sizeof *pa * (size_t)w * (size_t)h);
	struct vec3 *hp = malloc(sizeof *hp * (size_t)w * (size_t)h), *hn = malloc(sizeof *hn * (size_t)w * (size_t)h);
	int *pp = malloc(sizeof *pp * (size_t)w * (size_t)h);
	for (int y = 0; y < h; y++)
		for (int x = 0; x < w; x++)
			rays[y * w + x] = cam_ray(&ctx.cam, (x + 0.5) / w, (y + 0.5) / h, 0, 0);

	/* arvo's kernel */
	double best = INFINITY;
	for (int rep = 0; rep < REPS; rep++) {
		double t0 = now();
		for (int by = 0; by < h; by += 4)
			for (int bx = 0; bx < w; bx += 4) {
				struct ray r[BVH_PACKET];
				struct hit hit[BVH_PACKET];
				bool found[BVH_PACKET];
				int at[BVH_PACKET], n = 0;
				for (int y = by; y < by + 4 && y < h; y++)
					for (int x = bx; x < bx + 4 && x < w; x++)
						at[n] = y * w + x, r[n++] = rays[y * w + x];
				bvh_intersect_packet(b, n, r, 0, INFINITY, OF_NO_IMAGE | BVH_NO_UV, hit, found);
				for (int i = 0; i < n; i++)
					pa[at[i]] = found[i] ? hit[i].obj : NULL, hp[at[i]] = hit[i].p, hn[at[i]] = hit[i].n;
			}
		double t = now() - t0;
		if (t < best)
			best = t;
	}
	double t_arvo = best;
	long hits_arvo = 0;
	for (long i = 0; i < (long)w * h; i++)
		hits_arvo += pa[i] != NULL;

	/* the shadow rays of the camera hits, as the eye pass makes them */
	struct shadow_ray *sr = malloc(sizeof *sr * (size_t)w * (size_t)h);
	long ns = 0;
	struct vec3 lp = s.lights[0].pos;
	for (long i = 0; i < (long)w * h; i++) {
		if (!pa[i])
			continue;
		struct vec3 nf = hn[i], v = v_neg(v_norm(rays[i].d)), p = hp[i];
		const struct object *from = pa[i]; /* a sphere: convex, left outward */
		if (v_dot(nf, v) < 0)
			nf = v_neg(nf), from = NULL;
		struct vec3 L = v_sub(lp, p);
		double dist = v_len(L);
		L = v_scale(L, 1 / dist);
		if (v_dot(nf, L) <= 0)
			continue;
		double m = fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z))), eps = 1e-7 * (1 + m); /* the eye pass's offset */
		sr[ns++] = (struct shadow_ray){{v_madd(p, nf, eps), L}, dist * (1 - 1e-9), from};
	}
	best = INFINITY;
	long blocked_arvo = 0;
	for (int rep = 0; rep < REPS; rep++) {
		long nb = 0;
		double t0 = now();
		for (long k = 0; k < ns; k++)
			nb += bvh_occluded_from(b, &sr[k].r, 0, sr[k].tmax, OF_NO_SHADOW, sr[k].from);
		double t = now() - t0;
		if (t < best)
			best = t;
		blocked_arvo = nb;
	}
	double ts_arvo = best;

	RTCDevice dev = rtcNewDevice("verbose=0");
	RTCScene sc = embree_scene(dev, &c, false);
	double t_points = embree_run(dev, sc, rays, w, h, pp);
	long hits_points = 0, agree = 0, blocked_points = 0, blocked_user = 0;
	for (long i = 0; i < (long)w * h; i++)
		hits_points += pp[i] >= 0, agree += (pp[i] >= 0 ? s.objects[pp[i]] : NULL) == pa[i];
	double ts_points = embree_shadows(sc, sr, ns, &blocked_points);
	rtcReleaseScene(sc);
	sc = embree_scene(dev, &c, true);
	double t_user = embree_run(dev, sc, rays, w, h, pp);
	long hits_user = 0;
	for (long i = 0; i < (long)w * h; i++)
		hits_user += pp[i] >= 0;
	double ts_user = embree_shadows(sc, sr, ns, &blocked_user);
	rtcReleaseScene(sc);
	rtcReleaseDevice(dev);

	double n = (double)w * h, m = (double)ns;
	printf("rays=%.0f spheres=%d arvo_rays_per_s=%.0f points_rays_per_s=%.0f user_rays_per_s=%.0f "
	       "arvo_hits=%ld points_hits=%ld user_hits=%ld agree=%ld\n",
	       n, s.nobjects, n / t_arvo, n / t_points, n / t_user, hits_arvo, hits_points, hits_user, agree);
	printf("shadow_rays=%ld arvo_shadow_per_s=%.0f points_shadow_per_s=%.0f user_shadow_per_s=%.0f "
	       "arvo_blocked=%ld points_blocked=%ld user_blocked=%ld\n",
	       ns, m / ts_arvo, m / ts_points, m / ts_user, blocked_arvo, blocked_points, blocked_user);
	printf("arvo_mix_per_s=%.0f points_mix_per_s=%.0f user_mix_per_s=%.0f\n", (n + m) / (t_arvo + ts_arvo),
	       (n + m) / (t_points + ts_points), (n + m) / (t_user + ts_user));
	bvh_free(b);
	scene_free(&s);
	free(rays), free((void *)pa), free(pp), free(c.p), free(hp), free(hn), free(sr);
	return 0;
}
