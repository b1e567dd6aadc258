/* SPDX-License-Identifier: MIT */
/* surface.h: the one surface-interaction step. Both passes call it where a
 * ray meets a surface, so the energy the light pass carries and the radiance
 * the eye pass gathers follow the same physics by construction: how much is
 * reflected and transmitted (finish reflection, Fresnel, conserve_energy,
 * metallic, pigment filter and transmit), total internal reflection, the
 * index for the path's channel or wavelength, the spawned rays and their
 * offset, and which transmitters the eye pass's shadow rays see through.
 *
 * The rule that keeps energy (docs/design.md §3): the reflected weight R is
 * clamped to [0,1] and the transmitted weight T to [0, 1−R] per channel, so
 * a surface never returns more than it receives; with fresnel or
 * conserve_energy T is first scaled by 1−R. Under total internal reflection
 * the share that would have passed is reflected (R+T, at most 1); POV-Ray's
 * legacy model (#version 3.x) reflects everything there, as POV-Ray does. */
#ifndef ARVO_SURFACE_H
#define ARVO_SURFACE_H

#include <stdbool.h>

#include "material.h"
#include "scene.h"
#include "shape.h"

/* Which light a path carries. */
struct band {
	int channel;   /* -1: all three RGB channels; 0, 1, 2: that channel only */
	double lambda; /* > 0: a single wavelength in nm (spectral passes) */
};

#define BAND_ALL ((struct band){-1, 0})

/* The index of refraction of interior in for band b: ior itself for all
 * channels; with dispersion D (the ratio of blue's index to red's) red uses
 * ior/√D, green ior and blue ior·√D; a wavelength follows Cauchy's law,
 * fitted so that each channel's light refracts on average as that channel
 * does (spec_ior, spectrum.h). */
double surf_ior(const struct interior *in, struct band b);

/* A ray meeting a surface. */
struct surf_in {
	const struct hit *h;         /* the hit */
	const struct finish *f;      /* its finish */
	struct colour pc;            /* the pigment colour there (filter, transmit) */
	const struct interior *in;   /* its interior */
	struct vec3 d;               /* unit direction of the incoming ray */
	struct vec3 nf;              /* unit normal on the incoming side (nf·d < 0) */
	bool legacy;                 /* POV-Ray's legacy model (#version 3.x) */
	bool straight;               /* transmission does not bend (surf_straight) */
};

/* What leaves the surface: weights per channel and the rays to follow. */
struct surf_out {
	struct vec3 R, T;            /* reflected and transmitted weights, R+T ≤ 1 */
	struct ray refl, trans;      /* the spawned rays (offset off the surface); refl is
	                                set only where some R > 0, trans where some T > 0 */
	bool tir;                    /* total internal reflection took T into R */
};

/* The surface step: fills out for a ray meeting a surface in band b. */
void surf_scatter(const struct surf_in *si, struct band b, struct surf_out *out);

/* Does light transmitted through o reach what lies behind it in a straight
 * line, attenuated, by the eye pass's shadow rays (true), or bent by the
 * light pass as a caustic (false)? Never both, never neither: straight when
 * o does not bend light (ior 1, no dispersion) or, in POV-Ray's legacy model,
 * unless o is a photons { target } whose refraction is on. Only meaningful
 * for surfaces that transmit. */
bool surf_straight(const struct scene *s, const struct object *o);

/* Does some object of s (or part of one) transmit light straight? */
bool surf_any_straight(const struct scene *s);

/* Fills si for ray direction d (unit) meeting hit h: texture, pigment at
 * the point, interior, facing normal, the scene's model and surf_straight. */
void surf_prepare(const struct scene *s, const struct mat_cache *mc, const struct hit *h, struct vec3 d,
                  struct surf_in *si);

/* What surf_prepare fills for any hit on o, when that is all but the hit,
 * the direction and the facing normal (surf_prepare_hit): o's texture is
 * one texture (no texture_map) of a solid pigment. False otherwise, si
 * then unset. A caller that meets o often (the light pass) makes it once. */
bool surf_prepare_obj(const struct scene *s, const struct object *o, struct surf_in *si);

/* The rest of surf_prepare, for ray direction d (unit) meeting hit h. */
static inline void surf_prepare_hit(const struct hit *h, struct vec3 d, struct surf_in *si)
{
	si->h = h;
	si->d = d;
	si->nf = v_dot(h->n, d) < 0 ? h->n : v_neg(h->n);
}

/* An offset for spawned rays, relative to the size of the coordinates. */
static inline double surf_eps(struct vec3 p)
{
	double x = fabs(p.x), y = fabs(p.y), z = fabs(p.z), m = y > z || z != z ? y : z;
	return 1e-7 * (1 + (x > m || m != m ? x : m)); /* fmax's numbers, without its libm calls */
}

#endif
