/* SPDX-License-Identifier: MIT */
/* surface.c: the one surface-interaction step (see surface.h). */
#include "surface.h"

#include "optics.h"
#include "scatter.h"
#include "spectrum.h"

double surf_ior(const struct interior *in, struct band b)
{
	double ior = in->ior > 0 ? in->ior : 1, D = in->dispersion > 0 ? in->dispersion : 1;
	if (D == 1)
		return ior;
	if (b.lambda > 0)
		return spec_ior(ior, D, b.lambda);
	if (b.channel < 0)
		return ior;
	return ior * pow(D, (b.channel - 1) / 2.0);
}

void surf_scatter(const struct surf_in *si, struct band b, struct surf_out *out)
{
	surf_scatter_at(si, b, out);
}

/* surf_straight, given o's interior in. */
static inline bool straight(const struct scene *s, const struct object *o, const struct interior *in)
{
	if (!s->legacy_lights)
		return !(in->ior > 0 && in->ior != 1) && !(in->dispersion > 0 && in->dispersion != 1);
	const struct photon_spec *ph = obj_photons(o);
	return !(ph && ph->target && ph->refraction);
}

bool surf_straight(const struct scene *s, const struct object *o)
{
	return straight(s, o, mat_interior(o));
}

/* What surf_prepare fills for o under texture t of pigment colour pc
 * (all but the hit's own fields). */
static void fill_obj(const struct scene *s, const struct object *o, const struct texture *t, struct colour pc,
                     struct surf_in *si)
{
	si->f = tex_finish(t);
	si->pc = pc;
	si->in = mat_interior(o);
	si->legacy = s->legacy_lights;
	si->straight = straight(s, o, si->in);
}

void surf_prepare(const struct scene *s, const struct mat_cache *mc, const struct hit *h, struct vec3 d,
                  struct surf_in *si)
{
	const struct texture *t = mat_texture(h->obj);
	if (tex_map(t)) /* a texture_map: the texture at the point */
		t = mat_texture_leaf(mc, t, h->p);
	fill_obj(s, h->obj, t, t->pigment.kind == PIG_SOLID ? t->pigment.c[0] : mat_pigment(mc, &t->pigment, h->p), si);
	surf_prepare_hit(h, d, si);
}

bool surf_prepare_obj(const struct scene *s, const struct object *o, struct surf_in *si)
{
	const struct texture *t = mat_texture(o);
	if (tex_map(t) || t->pigment.kind != PIG_SOLID)
		return false; /* (the texture or the pigment at the point) */
	*si = (struct surf_in){.f = NULL};
	fill_obj(s, o, t, t->pigment.c[0], si);
	return true;
}

static bool opaque(struct colour c) { return c.f == 0 && c.t == 0; }

/* Can pattern pigment p give a colour with filter or transmit anywhere?
 * False only when every colour it can give, or blend from, has neither
 * (a checker of two plain colours, a colour_map without them): then an
 * object of it passes no light (opt_transmission is 0). Image maps (alpha)
 * and pigments nested deeper than pigment_at looks always may. */
static bool may_pass(const struct pigment *p, int depth)
{
	if (p->kind == PIG_SOLID)
		return !opaque(p->c[0]);
	const struct pattern *pt = pig_pattern(p);
	if (p->kind == PIG_IMAGE || depth > 32)
		return true;
	for (int i = 0; pt->pmap && i < pt->npmap; i++)
		if (may_pass(pt->pmap[i].pig, depth + 1))
			return true;
	if (p->kind == PIG_CHECKER || p->kind == PIG_HEXAGON || p->kind == PIG_BRICK)
		return !opaque(p->c[0]) || !opaque(pt->more[0]) || (p->kind == PIG_HEXAGON && !opaque(pt->more[1]));
	for (int i = 0; pt->map && i < pt->nmap; i++) /* else a default map: opaque */
		if (!opaque(pt->map[i].c))
			return true;
	return false;
}

/* Can o, or a part of it, pass light straight through? A texture_map, a
 * layered texture or an interior that fades (whose fade a shadow ray
 * multiplies in) counts as clear unless its pigment is a plain opaque
 * colour. */
static bool straight_in(const struct scene *s, const struct object *o)
{
	if (o->kind >= OBJ_FIRST_CSG) {
		for (int i = 0; i < o->g.csg.n; i++)
			if (straight_in(s, o->g.csg.kids[i]))
				return true;
		return false;
	}
	const struct texture *t = mat_texture(o);
	const struct pigment *p = &t->pigment;
	bool clear = p->kind == PIG_SOLID ? p->c[0].f + p->c[0].t > 0
	                                  : tex_map(t) || tex_below(t) || mat_interior(o)->fade_distance > 0 ||
	                                        may_pass(p, 0);
	return clear && surf_straight(s, o);
}

bool surf_any_straight(const struct scene *s)
{
	for (int i = 0; i < s->nobjects; i++)
		if (straight_in(s, s->objects[i]))
			return true;
	return false;
}
