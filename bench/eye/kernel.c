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
 * Each is run REPS times (5); the best time counts. Prints one line of
 * key=value pairs: rays, spheres, {arvo,points,user}_rays_per_s (camera
 * rays per second on one core), {arvo,points,user}_hits and agree (pixels
 * where the points kernel and arvo hit the same sphere, or both miss).
 * Exit status 0; 1 when the scene cannot be evaluated or holds anything
 * but spheres without a transform. */
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

/* A float ray-sphere test for the user-geometry kernel. */
static void sphere_cb(const struct RTCIntersectFunctionNArguments *a)
{
	const struct cloud *c = a->geometryUserPtr;
	const float *s = c->p + 4 * a->primID;
	float *rh = (float *)a->rayhit;
	unsigned N = a->N;
	for (unsigned i = 0; i < N; i++) {
		if (!a->valid[i])
			continue;
		float ox = rh[0 * N + i] - s[0], oy = rh[1 * N + i] - s[1], oz = rh[2 * N + i] - s[2];
		float dx = rh[4 * N + i], dy = rh[5 * N + i], dz = rh[6 * N + i];
		float A = dx * dx + dy * dy + dz * dz, B = ox * dx + oy * dy + oz * dz;
		float C = ox * ox + oy * oy + oz * oz - s[3] * s[3], D = B * B - A * C;
		if (D < 0)
			continue;
		float q = sqrtf(D), t = (-B - q) / A;
		if (t < rh[3 * N + i])
			t = (-B + q) / A;
		if (t < rh[3 * N + i] || t > rh[8 * N + i])
			continue;
		rh[8 * N + i] = t;
		((unsigned *)rh)[17 * N + i] = a->primID;
		((unsigned *)rh)[18 * N + i] = a->geomID;
	}
}

static void bounds_cb(const struct RTCBoundsFunctionArguments *a)
{
	const struct cloud *c = a->geometryUserPtr;
	const float *s = c->p + 4 * a->primID;
	*a->bounds_o = (struct RTCBounds){s[0] - s[3], s[1] - s[3], s[2] - s[3], 0,
	                                  s[0] + s[3], s[1] + s[3], s[2] + s[3], 0};
}

/* Embree's own kernel over the cloud: native points or user geometry.
 * Returns the best seconds of REPS runs and the hit sphere of each ray
 * (-1: none) in prim. */
static double embree_run(RTCDevice dev, const struct cloud *c, bool user, const struct ray *rays, int w,
                         int h, int *prim)
{
	RTCScene sc = rtcNewScene(dev);
	RTCGeometry g;
	if (user) {
		g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
		rtcSetGeometryUserPrimitiveCount(g, (unsigned)c->n);
		rtcSetGeometryUserData(g, (void *)c);
		rtcSetGeometryBoundsFunction(g, bounds_cb, (void *)c);
		rtcSetGeometryIntersectFunction(g, sphere_cb);
	} else {
		g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_SPHERE_POINT);
		rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, c->p, 0,
		                           4 * sizeof(float), (size_t)c->n);
	}
	rtcCommitGeometry(g);
	rtcAttachGeometry(sc, g);
	rtcReleaseGeometry(g);
	rtcCommitScene(sc);
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
	rtcReleaseScene(sc);
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
	struct bvh *b = bvh_build(s.objects, s.nobjects);
	struct eye_ctx ctx;
	eye_setup(&ctx, &s, b, NULL, w, h, 1);
	struct ray *rays = malloc(sizeof *rays * (size_t)w * (size_t)h);
	const struct object **pa = malloc(sizeof *pa * (size_t)w * (size_t)h);
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
					pa[at[i]] = found[i] ? hit[i].obj : NULL;
			}
		double t = now() - t0;
		if (t < best)
			best = t;
	}
	double t_arvo = best;
	long hits_arvo = 0;
	for (long i = 0; i < (long)w * h; i++)
		hits_arvo += pa[i] != NULL;

	RTCDevice dev = rtcNewDevice("verbose=0");
	double t_points = embree_run(dev, &c, false, rays, w, h, pp);
	long hits_points = 0, agree = 0;
	for (long i = 0; i < (long)w * h; i++)
		hits_points += pp[i] >= 0, agree += (pp[i] >= 0 ? s.objects[pp[i]] : NULL) == pa[i];
	double t_user = embree_run(dev, &c, true, rays, w, h, pp);
	long hits_user = 0;
	for (long i = 0; i < (long)w * h; i++)
		hits_user += pp[i] >= 0;
	rtcReleaseDevice(dev);

	double n = (double)w * h;
	printf("rays=%.0f spheres=%d arvo_rays_per_s=%.0f points_rays_per_s=%.0f user_rays_per_s=%.0f "
	       "arvo_hits=%ld points_hits=%ld user_hits=%ld agree=%ld\n",
	       n, s.nobjects, n / t_arvo, n / t_points, n / t_user, hits_arvo, hits_points, hits_user, agree);
	bvh_free(b);
	scene_free(&s);
	free(rays), free((void *)pa), free(pp), free(c.p);
	return 0;
}
