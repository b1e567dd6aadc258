/* SPDX-License-Identifier: MIT */
/* vec.h: 3-vectors, rays and colours as small static inline helpers. */
#ifndef ARVO_VEC_H
#define ARVO_VEC_H

#include <math.h>
#include <stdbool.h>

struct vec3 {
	double x, y, z;
};

struct ray {
	struct vec3 o; /* origin */
	struct vec3 d; /* direction (not necessarily unit length) */
};

/* A linear Rec.709 colour with POV-Ray's filter and transmit channels. */
struct colour {
	double r, g, b; /* scene-linear Rec.709 */
	double f, t;    /* filter, transmit */
};

static inline struct vec3 v3(double x, double y, double z) { return (struct vec3){x, y, z}; }
static inline struct vec3 v_add(struct vec3 a, struct vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline struct vec3 v_sub(struct vec3 a, struct vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline struct vec3 v_mul(struct vec3 a, struct vec3 b) { return v3(a.x * b.x, a.y * b.y, a.z * b.z); }
static inline struct vec3 v_scale(struct vec3 a, double s) { return v3(a.x * s, a.y * s, a.z * s); }
static inline struct vec3 v_neg(struct vec3 a) { return v3(-a.x, -a.y, -a.z); }
static inline double v_dot(struct vec3 a, struct vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline struct vec3 v_cross(struct vec3 a, struct vec3 b)
{
	return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double v_len(struct vec3 a) { return sqrt(v_dot(a, a)); }
static inline struct vec3 v_norm(struct vec3 a)
{
	double l = v_len(a);
	return l > 0 ? v_scale(a, 1.0 / l) : a;
}
static inline struct vec3 v_madd(struct vec3 a, struct vec3 b, double s) { return v3(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s); }
/* min and max of numbers that are not NaN, inline (fmin and fmax are libm
 * calls; on a tie these give b) */
static inline double d_min(double a, double b) { return a < b ? a : b; }
static inline double d_max(double a, double b) { return a > b ? a : b; }
/* fmax and fmin as libm gives them (maxsd and minsd where neither is NaN,
 * the other where one is), inline: from libm they are calls. */
static inline double fmax_(double a, double b) { return a > b || b != b ? a : b; }
static inline double fmin_(double a, double b) { return a < b || b != b ? a : b; }
static inline struct vec3 v_min(struct vec3 a, struct vec3 b) { return v3(fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z)); }
static inline struct vec3 v_max(struct vec3 a, struct vec3 b) { return v3(fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z)); }
static inline double v_comp(struct vec3 a, int i) { return i == 0 ? a.x : i == 1 ? a.y : a.z; }
static inline struct vec3 ray_at(struct ray r, double t) { return v_madd(r.o, r.d, t); }

static inline struct colour c_rgb(double r, double g, double b) { return (struct colour){r, g, b, 0, 0}; }

/* An axis-aligned bounding box; empty when lo > hi. */
struct bbox {
	struct vec3 lo, hi;
};

static inline struct bbox bbox_empty(void) { return (struct bbox){v3(INFINITY, INFINITY, INFINITY), v3(-INFINITY, -INFINITY, -INFINITY)}; }
static inline struct bbox bbox_union(struct bbox a, struct bbox b) { return (struct bbox){v_min(a.lo, b.lo), v_max(a.hi, b.hi)}; }
static inline struct bbox bbox_add(struct bbox a, struct vec3 p) { return (struct bbox){v_min(a.lo, p), v_max(a.hi, p)}; }
/* The centre of b, and the radius of the sphere round b about it (half its diagonal). */
static inline struct vec3 bbox_centre(struct bbox b) { return v_scale(v_add(b.lo, b.hi), 0.5); }
static inline double bbox_radius(struct bbox b) { return 0.5 * v_len(v_sub(b.hi, b.lo)); }
static inline bool bbox_finite(struct bbox b)
{
	return isfinite(b.lo.x) && isfinite(b.lo.y) && isfinite(b.lo.z) && isfinite(b.hi.x) &&
	       isfinite(b.hi.y) && isfinite(b.hi.z);
}

#endif
