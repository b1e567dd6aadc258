/* SPDX-License-Identifier: MIT */
/* optics.h: the specular optics the light pass and the eye pass share:
 * unpolarised Fresnel reflectance, Snell refraction, mirror reflection, and
 * a surface's reflected and transmitted colours (POV-Ray's finish reflection
 * and pigment filter/transmit, docs/design.md §3). */
#ifndef ARVO_OPTICS_H
#define ARVO_OPTICS_H

#include <stdbool.h>
#include <string.h>

#include "scene.h"

/* Unpolarised Fresnel reflectance R = (Rs+Rp)/2 for cosine ci (> 0, on the
 * incident side) going from index n1 into n2; 1 under total internal reflection. */
static inline double opt_fresnel(double ci, double n1, double n2)
{
	double eta = n1 / n2, s2 = eta * eta * (1 - ci * ci);
	if (s2 >= 1)
		return 1;
	double ct = sqrt(1 - s2);
	double rs = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct);
	double rp = (n1 * ct - n2 * ci) / (n1 * ct + n2 * ci);
	return 0.5 * (rs * rs + rp * rp);
}

/* Refracted unit direction of unit d through the facing unit normal nf with
 * eta = n1/n2; false under total internal reflection. */
static inline bool opt_refract(struct vec3 d, struct vec3 nf, double eta, struct vec3 *out)
{
	double ci = -v_dot(d, nf), s2 = eta * eta * (1 - ci * ci);
	if (s2 > 1)
		return false;
	*out = v_norm(v_add(v_scale(d, eta), v_scale(nf, eta * ci - sqrt(1 - s2))));
	return true;
}

static inline struct vec3 opt_reflect(struct vec3 d, struct vec3 nf)
{
	return v_sub(d, v_scale(nf, 2 * v_dot(d, nf)));
}

static inline struct vec3 opt_rgb(struct colour c) { return v3(c.r, c.g, c.b); }

/* The finish's reflection colour at cosine ci: constant, POV's variable
 * reflection (falloff), or Fresnel between refl_min and refl_max; metallic
 * tints it by the pigment colour pc. */
static inline struct vec3 opt_reflection(const struct finish *f, struct colour pc, double ci, double n1, double n2)
{
	struct vec3 lo = opt_rgb(f->refl_min), hi = opt_rgb(f->refl_max);
	double t = 1;
	if (f->refl_fresnel)
		t = opt_fresnel(ci, n1, n2);
	else if (memcmp(&lo, &hi, sizeof lo) != 0)
		t = pow(1 - ci, f->refl_falloff);
	struct vec3 r = v_add(lo, v_scale(v_sub(hi, lo), t));
	return f->refl_metallic ? v_mul(r, opt_rgb(pc)) : r;
}

/* The transmitted colour of a pigment: filter tints by its colour, transmit
 * passes light unchanged. */
static inline struct vec3 opt_transmission(struct colour pc)
{
	return v_add(v_scale(opt_rgb(pc), pc.f), v3(pc.t, pc.t, pc.t));
}

/* POV-Ray's spotlight cone for the unit direction d from the light: 1 inside
 * radius, a smooth cubic to 0 at falloff, times cos^tightness (both passes). */
static inline double opt_spot(const struct light *l, struct vec3 d)
{
	struct vec3 axis = v_norm(v_sub(l->point_at, l->pos));
	double c = v_dot(d, axis);
	double cf = cos(l->falloff * M_PI / 180), cr = cos(l->radius * M_PI / 180);
	if (c <= cf)
		return 0;
	double k = l->tightness > 0 ? pow(c, l->tightness) : 1;
	if (c < cr && cr > cf) {
		double t = (c - cf) / (cr - cf);
		k *= t * t * (3 - 2 * t);
	}
	return k;
}

/* POV-Ray's absorption over a distance dist inside interior in:
 * fade_color + (1 − fade_color)/(1 + (dist/fade_distance)^fade_power), or
 * exponential for fade_power >= 1000 (both passes). */
static inline struct vec3 opt_fade(const struct interior *in, double dist)
{
	if (!(in->fade_distance > 0))
		return v3(1, 1, 1);
	struct vec3 fc = opt_rgb(in->fade_color);
	if (in->fade_power >= 1000)
		return v3(exp(-(1 - fc.x) * dist / in->fade_distance), exp(-(1 - fc.y) * dist / in->fade_distance),
		          exp(-(1 - fc.z) * dist / in->fade_distance));
	double fp = in->fade_power > 0 ? in->fade_power : 2;
	double a = 1 / (1 + pow(dist / in->fade_distance, fp));
	return v_add(v_scale(v3(1, 1, 1), a), v_scale(fc, 1 - a));
}

#endif
