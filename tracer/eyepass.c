/* SPDX-License-Identifier: MIT */
/* eyepass.c: Whitted ray tracing from the camera (see eyepass.h). */
#include "eyepass.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define EYE_SIMD 1
#endif
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "optics.h"
#include "pattern.h"
#include "sampler.h"
#include "spectrum.h"
#include "surface.h"
#include "scatter.h"

/* The state of one camera sample's tree of rays. */
struct path {
	const struct eye_ctx *ctx; /* shared context */
	struct smp_stream rng;     /* this sample's random numbers */
	long long rays;            /* rays traced so far */
	struct band band;          /* BAND_ALL, or the channel or wavelength of a
	                              path split off at dispersive glass */
	const struct hit *pre;     /* the camera ray's hit, traced beforehand in a
	                              packet (eye_pixels); used by the first trace */
	int pre_state;             /* 1: pre holds it, -1: it missed, 0: none */
	const struct shadow_memo *memo; /* per light (EYE_MEMO first ones): the
	                              shadow ray of the camera hit, tested
	                              beforehand in a packet (eye_pixels), or NULL */
	const struct object *from; /* the next trace's ray leaves this convex object
	                              outward (surf.out), or NULL */
	const struct object *in;   /* or enters this convex object, or is reflected
	                              inside it: it meets it first (bvh_intersect_in) */
	const struct pre_geo *geo; /* for the hit pre: its directions, worked out
	                              beforehand (eye_pixels), or NULL */
};

/* The unit directions the shading of a camera hit h along d begins with,
 * worked out for a whole packet at once (geo16): v = -v_norm(d), and the
 * direction L and distance dist from h->p towards light (the scene's
 * first, a point or spot light without an area), as towards() gives them;
 * light NULL: v alone. The same bits as the scalar steps. */
struct pre_geo {
	struct vec3 v, L;
	double dist;
	const struct light *light;
};

/* A shadow ray of a light point towards l->pos, and whether it is blocked,
 * answered beforehand; shadow() uses it for exactly this ray (the same bits
 * of origin, direction and end), which gets the same answer alone. */
#define EYE_MEMO 4
struct shadow_memo {
	bool set;    /* the entry holds a ray */
	bool blocked;
	struct ray r;
	double tmax;
};

/* The AOVs of the first visible point (filled at depth 1 only). The
 * radiance leaving it splits as
 *   beauty = albedo/π · (direct + caustic) + specular + emission
 * (eyepass.h): lambert is the first term; diffuse is the diffuse radiance
 * the shading computed, which differs from lambert where the surface is
 * not Lambertian (brilliance ≠ 1, the legacy light model, the fade of a
 * medium the camera sits in): that difference counts as specular. */
struct aov {
	bool hit;           /* the camera ray hit something */
	struct vec3 direct; /* irradiance from shadow rays */
	struct vec3 albedo; /* pigment × diffuse × opacity */
	struct vec3 n;      /* facing normal */
	struct vec3 p;      /* world position */
	double z;           /* hit distance (+inf on a miss) */
	struct vec3 caustic;/* irradiance from the illumination maps */
	struct vec3 emis;   /* ambient and emission (the background on a miss) */
	struct vec3 diffuse;/* diffuse radiance from the lights and the maps */
	struct vec3 spec;   /* highlights, reflected and refracted radiance */
};

/* What the shading of one hit needs to know about the surface. */
struct surf {
	const struct hit *h;        /* the hit */
	const struct texture *tex;  /* its texture */
	struct colour pc;           /* pigment colour there */
	struct vec3 nf;             /* unit normal facing the incoming ray */
	struct vec3 v;              /* unit vector towards the viewer */
	double opacity;             /* 1 - filter - transmit, clamped */
	const struct object *out;   /* h's object when convex and nf is its outward
	                               normal (not flipped, not perturbed): rays
	                               leaving along d·nf >= 0 cannot hit it (bvh.h) */
	const struct object *back;  /* h's object when convex and nf is its inward
	                               normal (flipped, not perturbed): the
	                               transmitted ray, offset along -nf, leaves it
	                               when it goes along d·n >= 0 */
	const struct pre_geo *geo;  /* h's directions worked out beforehand, or NULL */
};

static struct vec3 col3(struct colour c) { return v3(c.r, c.g, c.b); }
static bool no_colour(struct colour c) { return c.r == 0 && c.g == 0 && c.b == 0; }
static double v_maxc(struct vec3 a) { return d_max(a.x, d_max(a.y, a.z)); }

/* The query flags for hits shaded here: (u,v) and the partials are looked
 * at only to read illumination maps (caustic_at). */
static unsigned no_uv(const struct eye_ctx *ctx) { return ctx->ncaustics ? 0 : BVH_NO_UV | BVH_UV_UNREAD; }

/* Inlined where it is called: the shading steps of a hit, which GCC
 * otherwise leaves as calls, passing each vector argument through the
 * stack (three doubles); the prims scene (bench/eye) spent a twentieth of
 * its eye pass on those calls. */
#define HOT static inline __attribute__((always_inline))

/* An offset for spawned rays, relative to the size of the coordinates. */
static double eps_at(struct vec3 p)
{
	return 1e-7 * (1 + d_max(fabs(p.x), d_max(fabs(p.y), fabs(p.z))));
}

/* ==== lights ============================================================= */

/* The position of sample i of n along an area light's edge, in [-½, ½]:
 * evenly spaced with the end samples on the edge's ends, as POV-Ray places
 * them; jitter moves a sample anywhere in its cell. */
static double edge_pos(struct path *pa, bool jitter, int i, int n)
{
	if (n <= 1)
		return jitter ? smp_next(&pa->rng) - 0.5 : 0;
	double o = jitter ? smp_next(&pa->rng) - 0.5 : 0;
	return (i + o) / (n - 1) - 0.5;
}

/* Where sample (i, j) of light l sits, jittered from the path's numbers when
 * the area light asks for it. */
static struct vec3 light_point(struct path *pa, const struct light *l, int i, int j)
{
	if (!l->area)
		return l->pos;
	double a = edge_pos(pa, l->jitter, i, l->size1);
	double b = edge_pos(pa, l->jitter, j, l->size2);
	if (l->circular && (a != 0 || b != 0)) { /* square → disc, keeping the rim */
		double r = fmax(fabs(a), fabs(b)), s = sqrt(a * a + b * b);
		a *= r / s;
		b *= r / s;
	}
	return v_add(l->pos, v_add(v_scale(l->axis1, a), v_scale(l->axis2, b)));
}

/* The radiometric quantity arriving at p from a light point q along unit L
 * (before cosθ): I/d² (physical), I·fade (legacy), I for parallel lights. */
static struct vec3 arriving(const struct scene *s, const struct light *l, double d)
{
	struct vec3 I = col3(l->colour);
	if (l->kind == LIGHT_PARALLEL)
		return I;
	if (!s->legacy_lights)
		return v_scale(I, 1 / (d * d));
	if (l->fade_distance > 0) {
		double fp = l->fade_power > 0 ? l->fade_power : 1;
		return v_scale(I, 2 / (1 + pow(d / l->fade_distance, fp)));
	}
	return I;
}

/* The share of light from the light that reaches p (on the side of nf)
 * along unit L over dist: 0 behind an opaque object or one whose
 * transmitted light the light pass carries (a caustic), else the product of
 * what each straight transmitter passes (surface.h) and of the absorption
 * inside it. */
static struct vec3 shadow_through(struct path *pa, struct ray r, double tmax);

HOT struct vec3 shadow(struct path *pa, const struct light *l, const struct object *from, struct vec3 p,
                       struct vec3 nf, struct vec3 L, double dist)
{
	if (l->shadowless)
		return v3(1, 1, 1);
	const struct eye_ctx *ctx = pa->ctx;
	struct ray r = {v_madd(p, nf, eps_at(p)), L};
	double tmax = dist * (1 - 1e-9);
	pa->rays++;
	if (ctx->see_through)
		return shadow_through(pa, r, tmax);
	ptrdiff_t li = l - ctx->scene->lights;
	const struct shadow_memo *m = pa->memo && li < EYE_MEMO ? &pa->memo[li] : NULL;
	bool blocked;
	if (m && m->set && !memcmp(&m->r, &r, sizeof r) && !memcmp(&m->tmax, &tmax, sizeof tmax))
		blocked = m->blocked;
	else
		blocked = bvh_occluded_from(ctx->bvh, &r, 0, tmax, OF_NO_SHADOW, from);
	return blocked ? v3(0, 0, 0) : v3(1, 1, 1);
}

/* shadow() where some object passes light straight through (see_through):
 * the shadow ray r over (0, tmax) walks from surface to surface. Out of
 * line, so that the usual case above is inline in its callers. */
static struct vec3 shadow_through(struct path *pa, struct ray r, double tmax)
{
	const struct eye_ctx *ctx = pa->ctx;
	struct vec3 L = r.d, pass = v3(1, 1, 1);
	double t0 = 0;
	for (int n = 0; n < 64; n++) {
		struct hit h;
		if (!bvh_intersect_skip(ctx->bvh, &r, t0, tmax, OF_NO_SHADOW | BVH_NO_UV, &h))
			return pass;
		struct surf_in si;
		struct surf_out so;
		surf_prepare(ctx->scene, ctx->mats, &h, L, &si);
		if (!si.straight)
			return v3(0, 0, 0);
		surf_scatter(&si, pa->band, &so);
		pass = v_mul(pass, so.T);
		if (!h.entering)
			pass = v_mul(pass, opt_fade(si.in, h.t - t0));
		if (v_maxc(pass) <= 0)
			return pass;
		t0 = h.t + eps_at(h.p);
		pa->rays++;
	}
	return v3(0, 0, 0);
}

/* Phong and Blinn highlights for light direction L (unit), per unit of
 * arriving light. */
HOT double highlight(const struct finish *f, struct vec3 nf, struct vec3 v, struct vec3 L)
{
	double k = 0;
	if (f->specular > 0) {
		struct vec3 hv = v_norm(v_add(L, v));
		double c = v_dot(nf, hv);
		if (c > 0)
			k += f->specular * pow(c, 1 / (f->roughness > 1e-6 ? f->roughness : 1e-6)); /* fmax, inline */
	}
	if (f->phong > 0) {
		struct vec3 rv = v_sub(v_scale(nf, 2 * v_dot(nf, v)), v);
		double c = v_dot(rv, L);
		if (c > 0)
			k += f->phong * pow(c, f->phong_size);
	}
	return k;
}

/* The direction (unit, into *L) and distance from the surface point to the
 * light point q; parallel lights shine from infinitely far along -point_at. */
static double towards(const struct light *l, struct vec3 p, struct vec3 q, struct vec3 *L)
{
	if (l->kind == LIGHT_PARALLEL) {
		*L = v_norm(v_sub(l->pos, l->point_at));
		return INFINITY;
	}
	*L = v_sub(q, p);
	double dist = v_len(*L);
	*L = v_scale(*L, 1 / dist);
	return dist;
}

/* The light from point q of l (weighted by w) reflected at sf: diffuse and
 * highlights; adds the irradiance to *E and the highlights' radiance to *H.
 * Tests the shadow ray when asked.
 * As in POV-Ray, the diffuse term is scaled by the surface's opacity
 * (1 - filter - transmit) but highlights are not, so clear glass shows them. */
HOT struct vec3 from_point(struct path *pa, const struct light *l, const struct surf *sf, struct vec3 q,
                           double w, bool test, struct vec3 *E, struct vec3 *H)
{
	const struct scene *s = pa->ctx->scene;
	const struct finish *f = tex_finish(sf->tex);
	struct vec3 L;
	double dist;
	if (sf->geo && sf->geo->light == l && !l->area) /* q is l->pos (light_one) */
		L = sf->geo->L, dist = sf->geo->dist;
	else
		dist = towards(l, sf->h->p, q, &L);
	double c = v_dot(sf->nf, L);
	if (c <= 0)
		return v3(0, 0, 0);
	struct vec3 Li = v_scale(arriving(s, l, dist), w);
	if (l->kind == LIGHT_SPOT)
		Li = v_scale(Li, opt_spot(l, v_neg(L)));
	if (test && v_maxc(Li) > 0)
		Li = v_mul(Li, shadow(pa, l, sf->out, sf->h->p, sf->nf, L, dist));
	if (v_maxc(Li) <= 0)
		return v3(0, 0, 0);
	*E = v_madd(*E, Li, c);
	double k = s->legacy_lights ? 1 : 1 / M_PI;
	double cb = f->brilliance != 1 ? pow(c, f->brilliance) : c;
	struct vec3 rho = v_scale(col3(sf->pc), f->diffuse);
	struct vec3 hl = v_scale(Li, highlight(f, sf->nf, sf->v, L) * k);
	if (f->refl_metallic)
		hl = v_mul(hl, col3(sf->pc));
	*H = v_add(*H, hl);
	return v_add(v_scale(v_mul(rho, Li), cb * k * sf->opacity), hl);
}

/* Direct light from l at surface sf: returns the reflected radiance and adds
 * the irradiance (W/m², before albedo) to *E, the highlights to *H. Physical model: an area light
 * is size1×size2 point lights of 1/(size1·size2) the intensity, each with
 * its own shadow ray. Legacy model (POV-Ray): the area only softens the
 * shadow; shading uses the centre, scaled by the fraction of samples seen. */
static struct vec3 light_one(struct path *pa, const struct light *l, const struct surf *sf,
                             struct vec3 *E, struct vec3 *H)
{
	if (!l->area) /* the loop below once, at l->pos with w = 1 (its sum's +0 aside: shade_tex adds it to one) */
		return from_point(pa, l, sf, l->pos, 1, true, E, H);
	bool area = l->area && (l->size1 > 1 || l->size2 > 1);
	int n1 = area && l->size1 > 0 ? l->size1 : 1, n2 = area && l->size2 > 0 ? l->size2 : 1;
	double w = 1.0 / (n1 * n2), seen = 0;
	bool legacy = pa->ctx->scene->legacy_lights && area;
	struct vec3 out = v3(0, 0, 0), L;
	for (int i = 0; i < n1; i++)
		for (int j = 0; j < n2; j++) {
			struct vec3 q = light_point(pa, l, i, j);
			if (!legacy) {
				out = v_add(out, from_point(pa, l, sf, q, w, true, E, H));
				continue;
			}
			double dist = towards(l, sf->h->p, q, &L);
			if (v_dot(sf->nf, L) > 0) { /* the mean share passed, as a scalar */
				struct vec3 k = shadow(pa, l, sf->out, sf->h->p, sf->nf, L, dist);
				seen += w * (k.x + k.y + k.z) / 3;
			}
		}
	return legacy && seen > 0 ? from_point(pa, l, sf, l->pos, seen, false, E, H) : out;
}

/* ==== reflection and refraction ========================================== */

static struct vec3 trace(struct path *pa, const struct ray *r, int depth, double weight, unsigned skip,
                         struct aov *aov);

HOT struct vec3 specular(struct path *pa, const struct surf *sf, struct vec3 d, int depth,
                         double weight, unsigned skip);

/* A full-colour path at dispersive glass splits, each part refracting with
 * its own index: into one path per channel (passes rgb: chromatic
 * aberration), or into N = dispersion_samples wavelengths stratified over
 * the spectrum as the light pass draws them (spectrum.h), each weighted by
 * its factors f(λ), whose mean is white: so the glass seen directly and the
 * spectrum it casts on a wall agree. */
static struct vec3 disperse(struct path *pa, const struct surf *sf, const struct interior *in,
                            struct vec3 d, int depth, double weight, unsigned skip)
{
	struct vec3 out = v3(0, 0, 0);
	if (!pa->ctx->spectral) {
		double o[3];
		for (int c = 0; c < 3; c++) {
			pa->band = (struct band){c, 0};
			o[c] = v_comp(specular(pa, sf, d, depth, weight, skip), c);
		}
		out = v3(o[0], o[1], o[2]);
	} else {
		int n = in->dispersion_samples > 0 ? in->dispersion_samples : 7;
		for (int j = 0; j < n; j++) {
			double f[3];
			pa->band = (struct band){-1, spec_sample((j + smp_next(&pa->rng)) / n, f)};
			out = v_add(out, v_mul(v3(f[0], f[1], f[2]), specular(pa, sf, d, depth, weight, skip)));
		}
		out = v_scale(out, 1.0 / n);
	}
	pa->band = BAND_ALL;
	return out;
}

/* Whether the surface reflects or transmits at all: else specular() gives 0
 * (asked first: most surfaces do neither). */
static bool scatters(const struct surf *sf)
{
	const struct finish *f = tex_finish(sf->tex);
	return sf->pc.f > 0 || sf->pc.t > 0 || !no_colour(f->refl_min) || !no_colour(f->refl_max);
}

/* The reflected and transmitted light at a hit, as the surface step
 * (surface.h) splits it; dispersive glass splits a full-colour path first. */
HOT struct vec3 specular(struct path *pa, const struct surf *sf, struct vec3 d, int depth,
                         double weight, unsigned skip)
{
	bool clear = sf->pc.f > 0 || sf->pc.t > 0;
	const struct finish *f = tex_finish(sf->tex);
	if (!clear && no_colour(f->refl_min) && no_colour(f->refl_max))
		return v3(0, 0, 0); /* neither reflects nor transmits: R = T = 0 */
	const struct interior *in = mat_interior(sf->h->obj);
	bool disperses = in->dispersion > 0 && in->dispersion != 1;
	if (disperses && clear && pa->band.channel < 0 && !(pa->band.lambda > 0))
		return disperse(pa, sf, in, d, depth, weight, skip);
	struct surf_in si = {sf->h, tex_finish(sf->tex), sf->pc, in, d, sf->nf,
	                     pa->ctx->scene->legacy_lights, false};
	struct surf_out so;
	surf_scatter_at(&si, pa->band, &so); /* inline (scatter.h) */
	struct vec3 out = v3(0, 0, 0);
	if (v_maxc(so.T) > 0) {
		pa->from = sf->back && v_dot(so.trans.d, sf->h->n) >= 0 ? sf->back : NULL;
		pa->in = sf->out; /* refracted into it */
		out = v_mul(so.T, trace(pa, &so.trans, depth + 1, weight * v_maxc(so.T), skip, NULL));
	}
	if (v_maxc(so.R) > 0) {
		pa->from = sf->out; /* so.refl.d·nf = -d·nf >= 0 */
		pa->in = sf->back;  /* reflected inside (nf inward) */
		out = v_add(out, v_mul(so.R, trace(pa, &so.refl, depth + 1, weight * v_maxc(so.R), OF_NO_REFLECTION, NULL)));
	}
	return out;
}

/* ==== shading ============================================================ */

/* The radiance leaving hit h back along ray direction d. */
/* Irradiance the light pass left at a hit (summed over the channel passes). */
static struct vec3 caustic_at(const struct eye_ctx *ctx, const struct hit *h)
{
	struct vec3 E = v3(0, 0, 0);
	for (int i = 0; i < ctx->ncaustics; i++) {
		double e[3];
		lp_lookup(ctx->caustics[i], h->obj, h->u, h->v, e);
		E = v_add(E, v3(e[0], e[1], e[2]));
	}
	return E;
}

/* The radiance leaving hit h along -d under texture tex (not a map). An
 * upper layer of a layered texture reflects and refracts nothing: what its
 * filter and transmit let through is the layer below (shade_map). */
static struct vec3 shade_tex(struct path *pa, const struct hit *h, const struct texture *tex, struct vec3 d,
                             int depth, double weight, unsigned skip, struct aov *aov, bool upper)
{
	const struct scene *s = pa->ctx->scene;
	const struct pre_geo *g = pa->geo && h == pa->pre ? pa->geo : NULL; /* the camera hit's, in hand */
	struct surf sf = {h, tex, {0, 0, 0, 0, 0}, h->n, g ? g->v : v_neg(v_norm(d)), 1, NULL, NULL, g};
	sf.pc = tex->pigment.kind == PIG_SOLID ? tex->pigment.c[0] /* as mat_pigment, without the calls */
	                                       : mat_pigment(pa->ctx->mats, &tex->pigment, h->p);
	if (v_dot(sf.nf, sf.v) < 0) { /* decided by the true normal */
		sf.nf = v_neg(sf.nf);
		if (!tex_normal(sf.tex) && shape_convex(h->obj))
			sf.back = h->obj;
	} else if (!tex_normal(sf.tex) && shape_convex(h->obj)) {
		sf.out = h->obj;
	}
	if (tex_normal(sf.tex)) /* as POV-Ray: the normal facing the eye is perturbed */
		sf.nf = pattern_perturb(tex_normal(sf.tex), h->p, sf.nf);
	sf.opacity = 1 - sf.pc.f - sf.pc.t;
	if (!s->legacy_lights) /* POV-Ray does not clamp: transmit 100 amplifies contrast */
		sf.opacity = sf.opacity > 0 ? d_min(sf.opacity, 1) : 0; /* NaN → 0; never -0 */
	const struct finish *f = tex_finish(sf.tex);
	struct vec3 pc = col3(sf.pc), E = v3(0, 0, 0), H = v3(0, 0, 0), lit = v3(0, 0, 0);
	struct vec3 emis = v_mul(pc, v_add(v_mul(col3(f->ambient), col3(s->gs.ambient_light)),
	                                   col3(f->emission)));
	emis = v_scale(emis, sf.opacity);
	for (int i = 0; i < s->nlights; i++)
		lit = v_add(lit, light_one(pa, &s->lights[i], &sf, &E, &H));
	struct vec3 diffuse = v_sub(lit, H);
	struct vec3 Ec = caustic_at(pa->ctx, h);
	if (f->diffuse > 0 && v_maxc(Ec) > 0) /* the maps as one more diffuse light: ρ·E/π */
		diffuse = v_add(diffuse, v_scale(v_mul(v_scale(pc, f->diffuse), Ec),
		                                 (s->legacy_lights ? 1 : 1 / M_PI) * sf.opacity));
	struct vec3 spec = upper || !scatters(&sf) ? v3(0, 0, 0)
	                                          : specular(pa, &sf, v_neg(sf.v), depth, weight, skip); /* v_norm(d) */
	if (aov) {
		aov->hit = true;
		aov->caustic = Ec;
		aov->direct = E;
		aov->albedo = v_scale(pc, f->diffuse * sf.opacity);
		aov->n = sf.nf;
		aov->p = h->p;
		aov->emis = emis;
		aov->diffuse = diffuse;
		aov->spec = v_add(H, spec);
	}
	return v_add(v_add(emis, diffuse), v_add(H, spec));
}

/* a·wa + b·wb for every layer of two AOV records (the normal renormalised). */
static void aov_blend(struct aov *a, const struct aov *b, double wa, double wb)
{
	a->direct = v_add(v_scale(a->direct, wa), v_scale(b->direct, wb));
	a->albedo = v_add(v_scale(a->albedo, wa), v_scale(b->albedo, wb));
	a->n = v_norm(v_add(v_scale(a->n, wa), v_scale(b->n, wb)));
	a->caustic = v_add(v_scale(a->caustic, wa), v_scale(b->caustic, wb));
	a->emis = v_add(v_scale(a->emis, wa), v_scale(b->emis, wb));
	a->diffuse = v_add(v_scale(a->diffuse, wa), v_scale(b->diffuse, wb));
	a->spec = v_add(v_scale(a->spec, wa), v_scale(b->spec, wb));
}

static struct vec3 shade_map(struct path *pa, const struct hit *h, const struct texture *t, struct vec3 d,
                             int depth, double weight, unsigned skip, struct aov *aov, int level, bool upper);

/* average texture_map { [w texture] … }: every texture shaded, their light
 * and their AOV layers weighted by w. */
static struct vec3 shade_average(struct path *pa, const struct hit *h, const struct texture *t, struct vec3 d,
                                 int depth, double weight, unsigned skip, struct aov *aov, int level, bool upper)
{
	const struct tex_entry *m = tex_map(t);
	int nmap = tex_nmap(t);
	double total = 0;
	for (int i = 0; i < nmap; i++)
		total += m[i].pos;
	struct vec3 out = v3(0, 0, 0);
	if (total == 0)
		return out;
	struct aov start = aov ? *aov : (struct aov){0}, sum = start;
	for (int i = 0; i < nmap; i++) {
		double w = m[i].pos / total;
		struct aov a = start;
		struct vec3 c = shade_map(pa, h, m[i].tex, d, depth, weight * fabs(w), skip, aov ? &a : NULL,
		                          level + 1, upper);
		out = v_madd(out, c, w);
		if (aov) {
			if (i == 0)
				sum = a;
			aov_blend(&sum, &a, i == 0 ? w : 1, i == 0 ? 0 : w);
		}
	}
	if (aov)
		*aov = sum;
	return out;
}

/* The radiance leaving hit h under texture t: a texture_map blends the
 * light of its two textures at h, each shaded in full, as POV-Ray does. */
static struct vec3 shade_map(struct path *pa, const struct hit *h, const struct texture *t, struct vec3 d,
                             int depth, double weight, unsigned skip, struct aov *aov, int level, bool upper)
{
	if (tex_below(t) && level <= 16) { /* layered: this layer, then what shows through it */
		struct colour pc = mat_pigment(pa->ctx->mats, &t->pigment, h->p);
		struct vec3 through = v_add(v_scale(col3(pc), pc.f), v3(pc.t, pc.t, pc.t));
		struct texture self = *t; /* the layer alone */
		struct tex_ext alone = *t->ext;
		alone.below = NULL;
		self.ext = &alone;
		struct vec3 out = shade_map(pa, h, &self, d, depth, weight, skip, aov, level + 1, true);
		if (v_maxc(through) <= 0)
			return out;
		struct aov under;
		if (aov)
			under = *aov;
		struct vec3 b = shade_map(pa, h, tex_below(t), d, depth, weight * v_maxc(through), skip, aov ? &under : NULL,
		                          level + 1, false);
		if (aov)
			aov_blend(aov, &under, 1, v_maxc(through));
		return v_add(out, v_mul(through, b));
	}
	if (!tex_map(t) || level > 16)
		return shade_tex(pa, h, t, d, depth, weight, skip, aov, upper);
	if (t->pigment.kind == PIG_PATTERN && pig_pattern(&t->pigment)->pattern == PAT_AVERAGE)
		return shade_average(pa, h, t, d, depth, weight, skip, aov, level, upper);
	const struct texture *k[2];
	double w[2];
	struct aov a[2];
	int n = mat_texture_pick(pa->ctx->mats, t, h->p, k, w);
	struct vec3 out = v3(0, 0, 0);
	for (int i = 0; i < n; i++) {
		if (aov)
			a[i] = *aov;
		struct vec3 c = shade_map(pa, h, k[i], d, depth, weight * w[i], skip, aov ? &a[i] : NULL, level + 1, upper);
		out = v_madd(out, c, w[i]);
	}
	if (aov) {
		*aov = a[0];
		if (n == 2)
			aov_blend(aov, &a[1], w[0], w[1]);
	}
	return out;
}

static struct vec3 shade(struct path *pa, const struct hit *h, struct vec3 d, int depth,
                         double weight, unsigned skip, struct aov *aov)
{
	return shade_map(pa, h, mat_texture(h->obj), d, depth, weight, skip, aov, 0, false);
}

/* POV-Ray's sky_sphere along unit d: the pigments at d in the sky's
 * frame, composited from the top one down through their filter and
 * transmit; the background shows through what remains. */
static struct vec3 sky(const struct eye_ctx *ctx, struct vec3 d)
{
	const struct scene *s = ctx->scene;
	struct vec3 p = s->sky_xf ? v_norm(xf_inv_vector(s->sky_xf, d)) : d, out = v3(0, 0, 0);
	double pass = 1;
	for (int i = s->nsky - 1; i >= 0 && pass > 0; i--) {
		struct colour c = mat_pigment(ctx->mats, &s->sky[i], p);
		double through = c.f + c.t;
		out = v_madd(out, col3(c), pass * (1 - through));
		pass *= through;
	}
	return v_madd(out, col3(s->background), pass);
}

/* POV-Ray's fog over a ray segment from o along unit d of length len
 * (a miss: far away): the share k = e^(-len·density/distance) of c passes,
 * never less than the fog's transmit, tinted by the fog's filter; the fog's
 * colour fills 1 - k. A
 * ground fog's density is 1 below fog_offset and 1/(1 + (h/fog_alt)²) at
 * height h above it, averaged exactly along the segment. */
static struct vec3 fog(const struct fog *f, struct vec3 o, struct vec3 d, double len, struct vec3 c)
{
	double density = 1;
	if (f->type == 2) {
		double y1 = v_dot(o, f->up) - f->offset, dy = v_dot(d, f->up) * len, a = f->alt;
		/* ∫ density dy: y below 0 counts fully, above a·atan(y/a) */
		double lo = fmin(y1, y1 + dy), hi = fmax(y1, y1 + dy);
		if (hi - lo < 1e-9) {
			density = lo <= 0 ? 1 : 1 / (1 + (lo / a) * (lo / a));
		} else {
			double below = fmin(hi, 0) - fmin(lo, 0);
			double above = a * (atan(fmax(hi, 0) / a) - atan(fmax(lo, 0) / a));
			density = (below + above) / (hi - lo);
		}
	}
	double k = fmax(exp(-len * density / f->distance), f->c.t);
	struct vec3 fc = col3(f->c);
	/* as POV-Ray: what passes is also filtered by the fog's colour
	 * (1 - filter + filter·colour); the fog's colour fills the rest */
	double fl = f->c.f;
	struct vec3 pass = v_add(v3(1 - fl, 1 - fl, 1 - fl), v_scale(fc, fl));
	return v_add(v_scale(v_mul(pass, c), k), v_scale(fc, 1 - k));
}

/* The radiance arriving along r: the background on a miss, else the shaded
 * hit, attenuated by the medium when the ray travelled inside an object. */
static struct vec3 trace(struct path *pa, const struct ray *r, int depth, double weight, unsigned skip,
                         struct aov *aov)
{
	const struct scene *s = pa->ctx->scene;
	int maxd = s->gs.max_trace_level > 0 ? s->gs.max_trace_level : 5, pre = pa->pre_state;
	const struct object *from = pa->from, *in = pa->in;
	pa->pre_state = 0, pa->from = NULL, pa->in = NULL;
	if (depth > maxd || weight < s->gs.adc_bailout)
		return v3(0, 0, 0);
	struct hit hit;
	const struct hit *hp = pre > 0 ? pa->pre : &hit; /* the packet's hit is used in place */
	pa->rays++;
	if (pre < 0 || (!pre && !(in ? bvh_intersect_in(pa->ctx->bvh, r, 0, INFINITY, skip | no_uv(pa->ctx), in, &hit)
	                             : bvh_intersect_from(pa->ctx->bvh, r, 0, INFINITY, skip | no_uv(pa->ctx), from, &hit)))) {
		struct vec3 bg = s->nsky ? sky(pa->ctx, v_norm(r->d)) : col3(s->background);
		if (s->fog.type)
			bg = fog(&s->fog, r->o, v_norm(r->d), 1e7, bg);
		if (aov)
			aov->emis = bg;
		return bg;
	}
	if (aov)
		aov->z = hp->t * v_len(r->d);
	struct vec3 c = shade(pa, hp, r->d, depth, weight, skip, aov);
	if (!hp->entering && mat_interior(hp->obj)->fade_distance > 0) { /* else the fade is 1 */
		struct vec3 fade = opt_fade(mat_interior(hp->obj), hp->t * v_len(r->d));
		c = v_mul(c, fade);
		if (aov) {
			aov->emis = v_mul(aov->emis, fade);
			aov->diffuse = v_mul(aov->diffuse, fade);
			aov->spec = v_mul(aov->spec, fade);
		}
	}
	if (s->fog.type) /* the layers keep their unfogged values */
		c = fog(&s->fog, r->o, v_norm(r->d), hp->t * v_len(r->d), c);
	return c;
}

/* The specular layer of a sample: highlights, reflection and refraction,
 * plus what the diffuse radiance holds beyond albedo/π · (direct + caustic). */
static struct vec3 aov_specular(const struct aov *a)
{
	struct vec3 lambert = v_scale(v_mul(a->albedo, v_add(a->direct, a->caustic)), 1 / M_PI);
	return v_add(a->spec, v_sub(a->diffuse, lambert));
}

/* ==== pixels ============================================================= */

void eye_setup(struct eye_ctx *ctx, const struct scene *s, const struct bvh *b,
               const struct mat_cache *m, int w, int h, int spp)
{
	memset(ctx, 0, sizeof *ctx);
	ctx->scene = s;
	ctx->bvh = b;
	ctx->mats = m;
	ctx->w = w;
	ctx->h = h;
	cam_setup(&ctx->cam, &s->camera);
	ctx->see_through = surf_any_straight(s);
#ifdef EYE_SIMD
	ctx->simd16 = __builtin_cpu_supports("avx512f");
#endif
	ctx->spp = spp > 0 ? spp : 1;
	if (cam_has_dof(&ctx->cam) && ctx->cam.blur_samples > ctx->spp)
		ctx->spp = ctx->cam.blur_samples;
}

static void put3(float *dst, struct vec3 v, double k)
{
	dst[0] = (float)(v.x * k);
	dst[1] = (float)(v.y * k);
	dst[2] = (float)(v.z * k);
}

/* Starts sample i of pixel (x, y): its path (random numbers drawn so far)
 * and its camera ray, stratified over an m×m grid of the pixel (m =
 * ⌊√spp⌋, remaining samples uniform). */
/* Sample i of pixel (x, y)'s path as it starts: its random numbers, and
 * nothing traced yet. */
static inline struct path path_start(const struct eye_ctx *ctx, int x, int y, uint32_t i)
{
	uint64_t pixel = ((uint64_t)y * (uint64_t)ctx->w + (uint64_t)x) ^ ctx->seed_key;
	return (struct path){.ctx = ctx, .rng = smp_start(pixel, i), .band = BAND_ALL};
}

static void camera_sample_to(const struct eye_ctx *ctx, int x, int y, int i, struct path *pa, struct ray *r)
{
	bool jitter = ctx->spp > 1;
	*pa = path_start(ctx, x, y, (uint32_t)i);
	double jx = 0.5, jy = 0.5;
	if (jitter) {
		int m = (int)sqrt((double)ctx->spp); /* m×m strata, the rest at random */
		jx = smp_next(&pa->rng), jy = smp_next(&pa->rng);
		if (i < m * m) {
			jx = (i % m + jx) / m;
			jy = (i / m + jy) / m;
		}
	}
	double l1 = 0, l2 = 0; /* the lens sample, drawn only for a lens */
	if (ctx->cam.aperture > 0)
		l1 = smp_next(&pa->rng), l2 = smp_next(&pa->rng);
	else
		pa->rng.dim += 2; /* the numbers after it stay the same */
	cam_ray_to(&ctx->cam, (x + jx) / ctx->w, (y + jy) / ctx->h, l1, l2, r);
}

static struct ray camera_sample(const struct eye_ctx *ctx, int x, int y, int i, struct path *pa)
{
	struct ray r;
	camera_sample_to(ctx, x, y, i, pa, &r);
	return r;
}

/* Sample i's path and camera ray: sample 0's as eye_pixels started and
 * traced it (pa0, r0 and its hit pre), when it did. */
static struct ray sample_start(const struct eye_ctx *ctx, int x, int y, int i, const struct path *pa0,
                               const struct ray *r0, const struct hit *pre, int pre_state, struct path *pa)
{
	if (i > 0 || !pa0)
		return camera_sample(ctx, x, y, i, pa);
	*pa = *pa0;
	pa->pre = pre, pa->pre_state = pre_state;
	return *r0;
}

/* Shades one pixel: spp camera samples averaged with equal weights. The
 * radiance and irradiance layers are means over the samples; A is the
 * share of samples that hit; Z, N, P and albedo are the nearest sample's
 * (the first of equals), so they describe one surface. pre_state (1: hit,
 * -1: miss) and pre give sample 0's camera hit when it was traced
 * beforehand. */
static void pixel(const struct eye_ctx *ctx, int x, int y, struct eye_px *out, long long *rays,
                  struct path *pa0, const struct ray *r0, const struct hit *pre, int pre_state)
{
	struct vec3 sum = v3(0, 0, 0);
	if (ctx->beauty_only) { /* the same radiance, without the layers (left unset) */
		for (int i = 0; i < ctx->spp; i++) {
			struct path own, *pa = &own;
			struct ray r;
			if (i == 0 && pa0) { /* sample 0's path, used in place */
				pa = pa0;
				pa->pre = pre, pa->pre_state = pre_state;
				r = *r0;
			} else {
				r = camera_sample(ctx, x, y, i, pa);
			}
			if (v_dot(r.d, r.d) > 0)
				sum = v_add(sum, trace(pa, &r, 1, 1, OF_NO_IMAGE, NULL));
			*rays += pa->rays;
		}
		put3(out->rgb, sum, 1.0 / ctx->spp);
		return;
	}
	struct vec3 E = v3(0, 0, 0), C = v3(0, 0, 0), S = v3(0, 0, 0), M = v3(0, 0, 0);
	struct aov near = {.z = INFINITY};
	int hits = 0;
	for (int i = 0; i < ctx->spp; i++) {
		struct path pa;
		struct ray r = sample_start(ctx, x, y, i, pa0, r0, pre, pre_state, &pa);
		struct aov aov = {.z = INFINITY};
		if (v_dot(r.d, r.d) > 0) /* else the camera shoots no ray here */
			sum = v_add(sum, trace(&pa, &r, 1, 1, OF_NO_IMAGE, &aov));
		E = v_add(E, aov.direct);
		C = v_add(C, aov.caustic);
		S = v_add(S, aov_specular(&aov));
		M = v_add(M, aov.emis);
		hits += aov.hit;
		if (aov.z < near.z)
			near = aov;
		*rays += pa.rays;
	}
	double k = 1.0 / ctx->spp;
	put3(out->rgb, sum, k);
	put3(out->direct, E, k);
	put3(out->caustic, C, k);
	put3(out->specular, S, k);
	put3(out->emission, M, k);
	put3(out->albedo, near.albedo, 1);
	put3(out->n, near.n, 1);
	put3(out->p, near.p, 1);
	out->z = (float)near.z;
	out->a = (float)(hits * k);
}

void eye_pixel(const struct eye_ctx *ctx, int x, int y, struct eye_px *out, long long *rays)
{
	pixel(ctx, x, y, out, rays, NULL, NULL, NULL, 0);
}

/* Whether the camera hits h of a packet (found[i]: ray i hit) are close
 * enough for their shadow rays to walk the hierarchy together: within 5%
 * in depth and on at most two objects. Elsewhere (the random cloud, or
 * spheres a pixel or two across) a packet of shadow rays was measured
 * slower than the rays one by one. */
#define EYE_COHERENT 1.05
#define EYE_FEW 2
static bool coherent(int n, const struct hit *h, const bool *found)
{
	const struct object *seen[EYE_FEW];
	int nseen = 0;
	double t0 = INFINITY, t1 = 0;
	for (int i = 0; i < n; i++) {
		if (!found[i])
			continue;
		t0 = d_min(t0, h[i].t), t1 = d_max(t1, h[i].t); /* hits: finite, > 0 */
		int k = 0;
		while (k < nseen && seen[k] != h[i].obj)
			k++;
		if (k == nseen && nseen == EYE_FEW)
			return false;
		if (k == nseen)
			seen[nseen++] = h[i].obj;
	}
	return !(t1 > t0 * EYE_COHERENT);
}

/* The shadow rays shadow() will ask for at the camera hits h of a packet
 * (found[i]: ray r[i] hit), towards each point or spot light among the
 * first EYE_MEMO, built as shade_tex, from_point and shadow build them,
 * tested as one packet per light when the hits are coherent; the answers
 * go to memo[i], which pa[i] points to. Hits under a textured normal or a
 * layered or mapped texture get none (their facing normal is known only
 * in the shading). */
static void shadow_packets(const struct eye_ctx *ctx, int n, const struct ray *r, const struct hit *h,
                           const bool *found, struct path *pa, struct shadow_memo memo[][EYE_MEMO])
{
	const struct scene *s = ctx->scene;
	struct vec3 nf[BVH_PACKET];
	bool ok[BVH_PACKET];
	if (!coherent(n, h, found))
		return;
	for (int i = 0; i < n; i++) {
		for (int k = 0; k < EYE_MEMO; k++)
			memo[i][k].set = false;
		pa[i].memo = memo[i];
		ok[i] = found[i];
		if (!ok[i])
			continue;
		const struct texture *t = mat_texture(h[i].obj);
		if (tex_normal(t) || tex_map(t) || tex_below(t)) {
			ok[i] = false;
			continue;
		}
		nf[i] = h[i].n;
		if (v_dot(nf[i], v_neg(v_norm(r[i].d))) < 0)
			nf[i] = v_neg(nf[i]);
	}
	for (int k = 0; k < s->nlights && k < EYE_MEMO; k++) {
		const struct light *l = &s->lights[k];
		if (l->area || l->shadowless || l->kind == LIGHT_PARALLEL)
			continue;
		struct ray sr[BVH_PACKET];
		double tmax[BVH_PACKET];
		bool blocked[BVH_PACKET];
		int lane[BVH_PACKET], m = 0;
		for (int i = 0; i < n; i++) {
			if (!ok[i])
				continue;
			struct vec3 L;
			double dist = towards(l, h[i].p, l->pos, &L);
			if (v_dot(nf[i], L) <= 0)
				continue; /* from_point tests no shadow */
			sr[m] = (struct ray){v_madd(h[i].p, nf[i], eps_at(h[i].p)), L};
			tmax[m] = dist * (1 - 1e-9);
			lane[m++] = i;
		}
		if (m == 0)
			continue;
		bvh_occluded_packet(ctx->bvh, m, sr, tmax, OF_NO_SHADOW, blocked);
		for (int j = 0; j < m; j++)
			memo[lane[j]][k] = (struct shadow_memo){true, blocked[j], sr[j], tmax[j]};
	}
}

/* pixel() for one sample without AOVs (ctx->beauty_only, spp 1): sample
 * 0's path pa, camera ray r and its hit h (found: it hit), in place. With
 * bg (plain_miss), a miss is the background, as trace() would return it. */
static void pixel_one(const struct eye_ctx *ctx, struct eye_px *out, long long *rays, struct path *pa,
                      const struct ray *r, const struct hit *h, bool found, bool bg)
{
	struct vec3 c = v3(0, 0, 0);
	if (!(v_dot(r->d, r->d) > 0)) { /* the camera shoots no ray here */
	} else if (bg && !found) {
		c = col3(ctx->scene->background);
		*rays += 1;
	} else {
		pa->pre = h, pa->pre_state = found ? 1 : -1;
		c = trace(pa, r, 1, 1, OF_NO_IMAGE, NULL);
		*rays += pa->rays;
	}
	put3(out->rgb, v_add(v3(0, 0, 0), c), 1.0);
}

/* Whether a camera ray that misses everything gives its pixel the plain
 * background, with nothing else to compute: one sample and no AOVs, no sky
 * or fog, and trace() lets a camera ray through (depth 1, weight 1). */
static bool plain_miss(const struct eye_ctx *ctx)
{
	const struct scene *s = ctx->scene;
	int maxd = s->gs.max_trace_level > 0 ? s->gs.max_trace_level : 5;
	return ctx->beauty_only && ctx->spp == 1 && !s->nsky && !s->fog.type && 1 <= maxd &&
	       !(1 < s->gs.adc_bailout);
}

#ifdef EYE_SIMD
/* Whether camera16 may start the packet's samples: one sample a pixel (no
 * jitter) through a perspective camera without a lens (cam_ray_to's
 * inline case). */
static bool camera16_fits(const struct eye_ctx *ctx)
{
	return ctx->simd16 && ctx->spp == 1 && ctx->cam.kind == CAM_PERSPECTIVE && !(ctx->cam.aperture > 0);
}

/* camera_sample_to for sample 0 of the n pixels (x[i], y[i]) (n <= 16)
 * where camera16_fits: each path as it starts it, and the film coordinates
 * and ray directions of all sixteen lanes at once (AVX-512), the same
 * operations on the same doubles as cam_ray_to's. */
__attribute__((target("avx512f"))) static void camera16(const struct eye_ctx *ctx, int n, const int *x,
                                                       const int *y, struct path *pa, struct ray *r)
{
	_Alignas(64) int xi[BVH_PACKET], yi[BVH_PACKET];
	_Alignas(64) double d[3][BVH_PACKET];
	for (int i = 0; i < BVH_PACKET; i++) {
		xi[i] = x[i < n ? i : 0], yi[i] = y[i < n ? i : 0];
		if (i >= n)
			continue;
		pa[i] = path_start(ctx, x[i], y[i], 0);
		pa[i].rng.dim += 2; /* no lens sample: the numbers after it stay the same */
	}
	const struct cam *c = &ctx->cam;
	const __m512d half = _mm512_set1_pd(0.5), w = _mm512_set1_pd((double)ctx->w);
	const __m512d h = _mm512_set1_pd((double)ctx->h);
	const double dir[3] = {c->dir.x, c->dir.y, c->dir.z}, right[3] = {c->right.x, c->right.y, c->right.z};
	const double up[3] = {c->up.x, c->up.y, c->up.z};
	for (int k = 0; k < 2; k++) {
		__m512d sx = _mm512_div_pd(_mm512_add_pd(_mm512_cvtepi32_pd(_mm256_load_si256((const __m256i *)(xi + 8 * k))),
		                                         half), w);
		__m512d sy = _mm512_div_pd(_mm512_add_pd(_mm512_cvtepi32_pd(_mm256_load_si256((const __m256i *)(yi + 8 * k))),
		                                         half), h);
		__m512d fx = _mm512_sub_pd(sx, half), fy = _mm512_sub_pd(half, sy); /* cam_ray_to's x, y */
		for (int a = 0; a < 3; a++)
			_mm512_store_pd(d[a] + 8 * k,
			                _mm512_add_pd(_mm512_set1_pd(dir[a]),
			                              _mm512_add_pd(_mm512_mul_pd(_mm512_set1_pd(right[a]), fx),
			                                            _mm512_mul_pd(_mm512_set1_pd(up[a]), fy))));
	}
	for (int i = 0; i < n; i++) {
		r[i].o = c->loc;
		r[i].d = v3(d[0][i], d[1][i], d[2][i]);
	}
}

/* The pre_geo of the camera hits h of rays r (lanes of m, n <= 16) into
 * g[i], towards light l (or NULL), sixteen lanes at a time: v_norm, v_neg
 * and towards' subtraction, length and scaling, the same operations on
 * the same doubles (AVX-512). One lane after another in the shading, their
 * square roots and divisions were a tenth of shade_map's samples (perf,
 * bench/eye/grid.scn). */
__attribute__((target("avx512f"))) static void geo16(unsigned m, const struct ray *r, const struct hit *h,
                                                    const struct light *l, struct pre_geo *g)
{
	_Alignas(64) double in[6][BVH_PACKET], out[7][BVH_PACKET];
	for (int i = 0; i < BVH_PACKET; i++) {
		bool on = m >> i & 1;
		in[0][i] = on ? r[i].d.x : 0, in[1][i] = on ? r[i].d.y : 0, in[2][i] = on ? r[i].d.z : 0;
		in[3][i] = on ? h[i].p.x : 0, in[4][i] = on ? h[i].p.y : 0, in[5][i] = on ? h[i].p.z : 0;
	}
	const __m512d one = _mm512_set1_pd(1), zero = _mm512_setzero_pd();
	const __m512i sign = _mm512_set1_epi64((long long)0x8000000000000000ull);
	for (int k = 0; k < 2; k++) {
		__m512d dx = _mm512_load_pd(in[0] + 8 * k), dy = _mm512_load_pd(in[1] + 8 * k);
		__m512d dz = _mm512_load_pd(in[2] + 8 * k);
		__m512d len = _mm512_sqrt_pd(_mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)),
		                                           _mm512_mul_pd(dz, dz)));
		__mmask8 pos = _mm512_cmp_pd_mask(len, zero, _CMP_GT_OQ);
		__m512d inv = _mm512_div_pd(one, len);
		dx = _mm512_mask_blend_pd(pos, dx, _mm512_mul_pd(dx, inv));
		dy = _mm512_mask_blend_pd(pos, dy, _mm512_mul_pd(dy, inv));
		dz = _mm512_mask_blend_pd(pos, dz, _mm512_mul_pd(dz, inv));
		_mm512_store_pd(out[0] + 8 * k, _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(dx), sign)));
		_mm512_store_pd(out[1] + 8 * k, _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(dy), sign)));
		_mm512_store_pd(out[2] + 8 * k, _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(dz), sign)));
		if (!l)
			continue;
		__m512d lx = _mm512_sub_pd(_mm512_set1_pd(l->pos.x), _mm512_load_pd(in[3] + 8 * k));
		__m512d ly = _mm512_sub_pd(_mm512_set1_pd(l->pos.y), _mm512_load_pd(in[4] + 8 * k));
		__m512d lz = _mm512_sub_pd(_mm512_set1_pd(l->pos.z), _mm512_load_pd(in[5] + 8 * k));
		__m512d dist = _mm512_sqrt_pd(_mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(lx, lx), _mm512_mul_pd(ly, ly)),
		                                            _mm512_mul_pd(lz, lz)));
		__m512d id = _mm512_div_pd(one, dist);
		_mm512_store_pd(out[3] + 8 * k, _mm512_mul_pd(lx, id));
		_mm512_store_pd(out[4] + 8 * k, _mm512_mul_pd(ly, id));
		_mm512_store_pd(out[5] + 8 * k, _mm512_mul_pd(lz, id));
		_mm512_store_pd(out[6] + 8 * k, dist);
	}
	for (; m; m &= m - 1) {
		int i = __builtin_ctz(m);
		g[i].v = v3(out[0][i], out[1][i], out[2][i]);
		g[i].light = l;
		if (l)
			g[i].L = v3(out[3][i], out[4][i], out[5][i]), g[i].dist = out[6][i];
	}
}
#endif

void eye_pixels(const struct eye_ctx *ctx, int n, const int *x, const int *y, struct eye_px *out,
                long long *rays)
{
	struct ray r[BVH_PACKET]; /* lanes 0..n-1 are set and read */
	struct hit h[BVH_PACKET];
	struct path pa[BVH_PACKET];
	bool found[BVH_PACKET];
#ifdef EYE_SIMD
	if (camera16_fits(ctx))
		camera16(ctx, n, x, y, pa, r);
	else
#endif
		for (int i = 0; i < n; i++)
			camera_sample_to(ctx, x[i], y[i], 0, &pa[i], &r[i]);
	bvh_intersect_packet(ctx->bvh, n, r, 0, INFINITY, OF_NO_IMAGE | no_uv(ctx), h, found);
	struct shadow_memo memo[BVH_PACKET][EYE_MEMO];
	if (!ctx->see_through && ctx->scene->nlights > 0 && bvh_walks(ctx->bvh))
		shadow_packets(ctx, n, r, h, found, pa, memo);
	bool one = ctx->beauty_only && ctx->spp == 1, bg = plain_miss(ctx);
#ifdef EYE_SIMD
	struct pre_geo geo[BVH_PACKET];
	if (ctx->simd16) {
		unsigned m = 0;
		for (int i = 0; i < n; i++)
			m |= (unsigned)found[i] << i;
		const struct scene *s = ctx->scene;
		const struct light *l = s->nlights > 0 ? &s->lights[0] : NULL;
		if (l && (l->area || l->kind == LIGHT_PARALLEL))
			l = NULL; /* towards() for a point or spot light's centre only */
		if (m) {
			geo16(m, r, h, l, geo);
			for (int i = 0; i < n; i++)
				pa[i].geo = found[i] ? &geo[i] : NULL;
		}
	}
#endif
	for (int i = 0; i < n; i++) {
		if (one)
			pixel_one(ctx, &out[i], rays, &pa[i], &r[i], &h[i], found[i], bg);
		else
			pixel(ctx, x[i], y[i], &out[i], rays, &pa[i], &r[i], &h[i], found[i] ? 1 : -1);
	}
}
