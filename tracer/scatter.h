/* SPDX-License-Identifier: MIT */
/* scatter.h: the surface step's body (surf_scatter, surface.h), inline for
 * the eye pass, which takes it at every hit that reflects or transmits:
 * surface.c's surf_scatter is this, so both passes keep one physics and
 * the same numbers; the light pass takes surf_scatter_rt with the weights
 * of a surface made once. Include it only from tracer/ sources built with
 * the same arithmetic (the Makefile's -ffp-contract=off and no fast-math,
 * at -O2 or at HOT_C's -O3). */
#ifndef ARVO_SCATTER_H
#define ARVO_SCATTER_H

#include "optics.h"
#include "surface.h"

static inline double sc_clamp01(double x) { return x > 0 ? (x < 1 ? x : 1) : 0; }

static inline struct vec3 sc_clamp3(struct vec3 a) { return v3(sc_clamp01(a.x), sc_clamp01(a.y), sc_clamp01(a.z)); }

/* min and max of numbers that are not NaN, inline (fmin and fmax are libm
 * calls) */
static inline double sc_dmin(double a, double b) { return a < b ? a : b; }
static inline double sc_maxc(struct vec3 a) { return a.x > a.y ? (a.x > a.z ? a.x : a.z) : (a.y > a.z ? a.y : a.z); }

/* Is f's reflection one constant colour (no Fresnel, no metallic: t = 1),
 * whatever the angle and the indices? */
static inline bool sc_refl_fixed(const struct finish *f)
{
	return !f->refl_fresnel && !f->refl_metallic && f->refl_min.r == f->refl_max.r &&
	       f->refl_min.g == f->refl_max.g && f->refl_min.b == f->refl_max.b;
}

/* sc_clamp3(opt_reflection(…)), its common case (sc_refl_fixed) inline,
 * with the same numbers. */
static inline struct vec3 sc_reflection(const struct finish *f, struct colour pc, double ci, double n1, double n2)
{
	if (sc_refl_fixed(f))
		return sc_clamp3(v_add(opt_rgb(f->refl_min), v_sub(opt_rgb(f->refl_max), opt_rgb(f->refl_min))));
	return sc_clamp3(opt_reflection(f, pc, ci, n1, n2));
}

/* surf_ior(in, b), its common case (no dispersion: the index itself) inline. */
static inline double sc_ior(const struct interior *in, struct band b)
{
	if (!(in->dispersion > 0 && in->dispersion != 1))
		return in->ior > 0 ? in->ior : 1;
	return surf_ior(in, b);
}

/* The reflected and transmitted weights before refraction is tried, for
 * cosine ci between indices n1 and n2: R (sc_reflection) and T, the
 * pigment's transmission clamped (docs/design.md §3). Under
 * sc_refl_fixed(si->f), for a solid pigment, they depend on the surface
 * alone: surf_scatter_rt takes them made once. */
struct sc_weights {
	struct vec3 R, T;
};

__attribute__((always_inline)) static inline struct sc_weights surf_weights(const struct surf_in *si, double ci,
                                                                           double n1, double n2)
{
	struct vec3 R = sc_reflection(si->f, si->pc, ci, n1, n2);
	struct vec3 T = opt_transmission(si->pc), one = v3(1, 1, 1);
	if (!si->legacy || sc_maxc(T) <= 1) { /* POV-Ray's model lets transmit > 1 amplify */
		T = sc_clamp3(T);
		if (si->f->refl_fresnel || si->f->conserve_energy)
			T = v_mul(T, v_sub(one, R));
		T = v3(sc_dmin(T.x, 1 - R.x), sc_dmin(T.y, 1 - R.y), sc_dmin(T.z, 1 - R.z)); /* never more out than in */
	}
	return (struct sc_weights){R, T};
}

/* The indices on the incoming side (n1) and the far side (n2) of hit
 * si->h in band b. */
static inline void sc_sides(const struct surf_in *si, struct band b, double *n1, double *n2)
{
	double ior = sc_ior(si->in, b);
	*n1 = si->h->entering ? 1 : ior, *n2 = si->h->entering ? ior : 1;
}

/* The rest of the surface step, given sc_sides' n1 and n2 and
 * surf_weights. */
__attribute__((always_inline)) static inline void surf_scatter_rt(const struct surf_in *si, double n1, double n2,
                                                                 struct sc_weights w, struct surf_out *out)
{
	const struct hit *h = si->h;
	struct vec3 R = w.R, T = w.T;
	double eps = surf_eps(h->p); /* the offset of spawned rays */
	struct vec3 one = v3(1, 1, 1);
	out->tir = false;
	if (sc_maxc(T) > 0) {
		out->trans = (struct ray){v_madd(h->p, si->nf, -eps), si->d};
		if (!si->straight && !opt_refract(si->d, si->nf, n1 / n2, &out->trans.d)) {
			/* total internal reflection: the share that would pass is
			 * reflected (POV-Ray's legacy model reflects everything, as
			 * POV-Ray does) */
			out->tir = true;
			R = si->legacy ? one : v_add(R, T);
			T = v3(0, 0, 0);
		}
	}
	out->R = R;
	out->T = T;
	if (sc_maxc(R) > 0)
		out->refl = (struct ray){v_madd(h->p, si->nf, eps), opt_reflect(si->d, si->nf)};
}

__attribute__((always_inline)) static inline void surf_scatter_at(const struct surf_in *si, struct band b,
                                                                 struct surf_out *out)
{
	double n1, n2;
	sc_sides(si, b, &n1, &n2);
	surf_scatter_rt(si, n1, n2, surf_weights(si, -v_dot(si->d, si->nf), n1, n2), out);
}

#endif
