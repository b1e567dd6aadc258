/* SPDX-License-Identifier: MIT */
/* material.c: pigments and the image_map cache. */
#include "material.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "../common/arena.h"
#include "pattern.h"

/* ==== the image cache ==================================================== */

static const struct img *cache_find(const struct mat_cache *c, const char *path)
{
	for (int i = 0; i < c->n; i++)
		if (strcmp(c->paths[i], path) == 0)
			return &c->imgs[i];
	return NULL;
}

/* Loads a pigment's image into the cache unless it is there already. */
static int cache_add(struct mat_cache *c, const struct pattern *pg, const char *ocio, struct diag *dg)
{
	const char *path = pg->image;
	if (!path || cache_find(c, path))
		return 0;
	if (c->n == c->cap) {
		c->cap = c->cap ? c->cap * 2 : 4;
		c->paths = mem_realloc(c->paths, sizeof *c->paths * (size_t)c->cap);
		c->imgs = mem_realloc(c->imgs, sizeof *c->imgs * (size_t)c->cap);
	}
	struct img_opts io = {ocio, NULL, 0, 0};
	int err = img_load(path, &io, &c->imgs[c->n], dg, pg->image_loc, pg->image_name);
	if (err)
		return err;
	c->paths[c->n++] = path;
	return 0;
}

/* Loads the image_map of a pigment and of the pigments inside it. */
static int load_pigment(struct mat_cache *c, const struct pigment *pg, const char *ocio, struct diag *dg, int depth)
{
	const struct pattern *pt = pig_pattern(pg);
	int err = 0;
	if (depth > 32)
		return 0;
	if (pg->kind == PIG_IMAGE)
		err = cache_add(c, pt, ocio, dg);
	if (!err && pt->sub)
		err = load_pigment(c, pt->sub, ocio, dg, depth + 1);
	for (int i = 0; !err && i < pt->npmap; i++)
		err = load_pigment(c, pt->pmap[i].pig, ocio, dg, depth + 1);
	return err;
}

/* ... of a texture, its texture_map's textures and the layers under it. */
static int load_texture(struct mat_cache *c, const struct texture *t, const char *ocio, struct diag *dg, int depth)
{
	int err = depth > 32 ? 0 : load_pigment(c, &t->pigment, ocio, dg, depth);
	for (int i = 0; !err && depth <= 32 && i < tex_nmap(t); i++)
		err = load_texture(c, tex_map(t)[i].tex, ocio, dg, depth + 1);
	if (!err && depth <= 32 && tex_below(t))
		err = load_texture(c, tex_below(t), ocio, dg, depth + 1);
	return err;
}

/* Walks an object tree, loading the image_map of every texture. */
static int load_tree(struct mat_cache *c, const struct object *o, const char *ocio, struct diag *dg)
{
	if (o->tex) {
		int err = load_texture(c, o->tex, ocio, dg, 0);
		if (err)
			return err;
	}
	if (o->kind >= OBJ_FIRST_CSG)
		for (int i = 0; i < o->g.csg.n; i++) {
			int err = load_tree(c, o->g.csg.kids[i], ocio, dg);
			if (err)
				return err;
		}
	return 0;
}

int mat_cache_load(struct mat_cache *c, const struct scene *s, const char *ocio_config, struct diag *dg)
{
	for (int i = 0; i < s->nobjects; i++) {
		int err = load_tree(c, s->objects[i], ocio_config, dg);
		if (err)
			return err;
	}
	return 0;
}

void mat_cache_free(struct mat_cache *c)
{
	for (int i = 0; i < c->n; i++)
		img_free(&c->imgs[i]);
	free(c->paths);
	free(c->imgs);
	memset(c, 0, sizeof *c);
}

/* ==== textures =========================================================== */

static struct texture default_tex; /* scene_default_texture(), made once */
static pthread_once_t default_once = PTHREAD_ONCE_INIT;

static void make_default(void)
{
	default_tex = scene_default_texture();
}

const struct texture *mat_texture(const struct object *o)
{
	if (o->tex)
		return o->tex;
	pthread_once(&default_once, make_default);
	return &default_tex;
}

const struct interior *mat_interior(const struct object *o)
{
	static const struct interior def = {1, 1, 7, 0, 0, {0, 0, 0, 0, 0}, 0};
	const struct interior *in = obj_interior(o);
	return in ? in : &def;
}

/* ==== patterns =========================================================== */

static struct colour c_lerp(struct colour a, struct colour b, double t)
{
	return (struct colour){a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t,
	                       a.f + (b.f - a.f) * t, a.t + (b.t - a.t) * t};
}

/* POV-Ray's default colour maps of the patterns that have their own. */
#define E(p, r, g, b) {p, {r, g, b, 0, 0}}
static const struct map_entry map_bozo[] = {E(0.4, 1, 1, 1), E(0.4, 0, 1, 0), E(0.6, 0, 1, 0),
                                            E(0.6, 0, 0, 1), E(0.8, 0, 0, 1), E(0.8, 1, 0, 0)};
static const struct map_entry map_agate[] = {E(0, 1, 1, 1), E(0.5, 0.95, 0.75, 0.5), E(0.5, 0.9, 0.7, 0.5),
                                             E(0.6, 0.9, 0.7, 0.4), E(0.6, 1, 0.7, 0.4), E(1, 0.6, 0.3, 0)};
static const struct map_entry map_marble[] = {E(0, 0.9, 0.8, 0.8), E(0.9, 0.9, 0.08, 0.08), E(0.9, 0, 0, 0)};
static const struct map_entry map_wood[] = {E(0.6, 0.666, 0.312, 0.2), E(0.6, 0.4, 0.1333, 0.066)};
static const struct map_entry map_radial[] = {E(0, 0, 1, 1), E(0.333, 1, 1, 0), E(0.666, 1, 0, 1), E(1, 0, 1, 1)};
static const struct map_entry map_grey[] = {E(0, 0, 0, 0), E(1, 1, 1, 1)};
static const struct map_entry map_mandel[] = {E(0.001, 0, 0, 0), E(0.001, 0, 1, 1), E(0.012, 1, 1, 0),
                                              E(0.015, 1, 0, 1), E(0.1, 0, 1, 1)};
#undef E

/* The colour map a pigment uses: its own, else its pattern's default. */
static const struct map_entry *pig_map(const struct pigment *pg, int *n)
{
	const struct pattern *pt = pig_pattern(pg);
	const struct map_entry *m = map_grey;
	*n = 2;
	if (pt->map && pt->nmap > 0) {
		*n = pt->nmap;
		return pt->map;
	}
	if (pg->kind != PIG_PATTERN)
		return m;
#define USE(a) (*n = (int)(sizeof a / sizeof a[0]), a)
	switch (pt->pattern) {
	case PAT_BOZO: return USE(map_bozo);
	case PAT_AGATE: return USE(map_agate);
	case PAT_MARBLE: return USE(map_marble);
	case PAT_WOOD: return USE(map_wood);
	case PAT_RADIAL: return USE(map_radial);
	case PAT_MANDEL: return USE(map_mandel);
	default: return m;
	}
#undef USE
}

/* The colour_map at v ∈ [0,1]: linear between entries, clamped at the ends. */
static struct colour colour_map(const struct pigment *pg, double v)
{
	int n;
	const struct map_entry *m = pig_map(pg, &n);
	if (v <= m[0].pos)
		return m[0].c;
	for (int i = 1; i < n; i++)
		if (v <= m[i].pos) {
			double span = m[i].pos - m[i - 1].pos;
			return span != 0 ? c_lerp(m[i - 1].c, m[i].c, (v - m[i - 1].pos) / span) : m[i].c;
		}
	return m[n - 1].c;
}

/* One texel (x, y) of im, clamped or wrapped at the edges. */
static struct colour texel(const struct img *im, long x, long y)
{
	x = ((x % im->w) + im->w) % im->w;
	y = ((y % im->h) + im->h) % im->h;
	const float *p = im->px + ((size_t)y * (size_t)im->w + (size_t)x) * (size_t)im->nch;
	struct colour c = c_rgb(p[0], p[1], p[2]);
	if (im->nch == 4)
		c.t = 1 - p[3];
	return c;
}

/* image_map, planar (map_type 0): the unit square of the x-y plane, image
 * bottom-left at the origin, repeating unless `once`. */
static struct colour image_map(const struct mat_cache *c, const struct pigment *pg, struct vec3 q)
{
	const struct img *im = c ? cache_find(c, pig_pattern(pg)->image ? pig_pattern(pg)->image : "") : NULL;
	if (!im || im->w <= 0)
		return c_rgb(1, 0, 1);
	if (pig_pattern(pg)->once && (q.x < 0 || q.x >= 1 || q.y < 0 || q.y >= 1))
		return (struct colour){0, 0, 0, 0, 1};
	double u = q.x - floor(q.x), v = q.y - floor(q.y);
	double fx = u * im->w, fy = (1 - v) * im->h;
	struct colour out;
	if (pig_pattern(pg)->interpolate == 2) {
		double x0 = floor(fx - 0.5), y0 = floor(fy - 0.5), tx = fx - 0.5 - x0, ty = fy - 0.5 - y0;
		struct colour a = c_lerp(texel(im, (long)x0, (long)y0), texel(im, (long)x0 + 1, (long)y0), tx);
		struct colour b = c_lerp(texel(im, (long)x0, (long)y0 + 1), texel(im, (long)x0 + 1, (long)y0 + 1), tx);
		out = c_lerp(a, b, ty);
	} else {
		out = texel(im, (long)floor(fx), (long)floor(fy));
	}
	return out;
}

static struct colour pigment_at(const struct mat_cache *c, const struct pigment *pg, struct vec3 p, int depth);

/* The pattern's value at pattern-space point q (pigment_pattern: the grey
 * of its pigment there). */
static double value_at(const struct mat_cache *c, const struct pigment *pg, struct vec3 q, int depth)
{
	const struct pattern *pt = pig_pattern(pg);
	if (pg->kind == PIG_CHECKER || pg->kind == PIG_HEXAGON || pg->kind == PIG_BRICK)
		return pattern_block(pg, q); /* a map's entry by number */
	if (pg->kind == PIG_PATTERN && pt->pattern == PAT_PIGMENT)
		return pattern_wave(pg, pt->sub ? pattern_grey(pigment_at(c, pt->sub, q, depth + 1)) : 0);
	return pattern_value(pg, q);
}

/* The pigment_map at v: the two entries around v evaluated at the
 * pattern-space point q and blended (POV-Ray's blend map search). */
static struct colour pigment_map(const struct mat_cache *c, const struct pattern *pt, double v, struct vec3 q,
                                 int depth)
{
	const struct pig_entry *m = pt->pmap;
	int n = pt->npmap, i = 0;
	if (v >= m[n - 1].pos)
		return pigment_at(c, m[n - 1].pig, q, depth);
	while (v > m[i].pos)
		i++;
	if (i == 0 || v == m[i].pos)
		return pigment_at(c, m[i].pig, q, depth);
	double w = (m[i].pos - v) / (m[i].pos - m[i - 1].pos);
	return c_lerp(pigment_at(c, m[i].pig, q, depth), pigment_at(c, m[i - 1].pig, q, depth), w);
}

/* average: the entries weighted by their positions. */
static struct colour average(const struct mat_cache *c, const struct pattern *pt, struct vec3 q, int depth)
{
	struct colour sum = {0, 0, 0, 0, 0};
	double total = 0;
	for (int i = 0; i < pt->npmap; i++) {
		struct colour k = pigment_at(c, pt->pmap[i].pig, q, depth);
		double w = pt->pmap[i].pos;
		sum = (struct colour){sum.r + w * k.r, sum.g + w * k.g, sum.b + w * k.b, sum.f + w * k.f, sum.t + w * k.t};
		total += w;
	}
	return total != 0 ? (struct colour){sum.r / total, sum.g / total, sum.b / total, sum.f / total, sum.t / total} : sum;
}

/* A pigment at world point p; depth bounds nested maps (a pigment_map's
 * entry may itself be one). */
static struct colour pigment_at(const struct mat_cache *c, const struct pigment *pg, struct vec3 p, int depth)
{
	if (pg->kind == PIG_SOLID)
		return pg->c[0];
	if (depth > 32)
		return c_rgb(0, 0, 0);
	const struct pattern *pt = pig_pattern(pg);
	struct vec3 q = pattern_point(pg, p);
	switch (pg->kind) {
	case PIG_CHECKER: case PIG_HEXAGON: case PIG_BRICK: {
		int k = pattern_block(pg, q);
		if (pt->pmap && k < pt->npmap)
			return pigment_at(c, pt->pmap[k].pig, q, depth + 1);
		return pig_colour(pg, k);
	}
	case PIG_GRADIENT: case PIG_PATTERN: {
		if (pt->pattern == PAT_AVERAGE && pg->kind == PIG_PATTERN)
			return pt->pmap ? average(c, pt, q, depth + 1) : c_rgb(0, 0, 0);
		double v = value_at(c, pg, q, depth);
		if (pt->pmap && pt->npmap > 0)
			return pigment_map(c, pt, v, q, depth + 1);
		return colour_map(pg, v);
	}
	case PIG_IMAGE: return image_map(c, pg, q);
	default: return pg->c[0];
	}
}

/* A checker of two colours with no transform, warps or pigment_map (a
 * floor's, say) is read here in place: pigment_at's steps for it (p through
 * the identity as x + 0, pattern_block, pig_colour) inline, without their
 * five calls and three of libm's floor. */
struct colour mat_pigment(const struct mat_cache *c, const struct pigment *pg, struct vec3 p)
{
	const struct pattern *pt = pg->pat;
	if (pg->kind == PIG_CHECKER && !pg->xf && pt && pt->nwarps == 0 && !pt->pmap && isfinite(p.x) &&
	    isfinite(p.y) && isfinite(p.z))
		return pattern_checker(v3(p.x + 0.0, p.y + 0.0, p.z + 0.0)) ? pt->more[0] : pg->c[0];
	return pigment_at(c, pg, p, 0);
}

/* ==== texture maps ======================================================== */

int mat_texture_pick(const struct mat_cache *c, const struct texture *t, struct vec3 p,
                     const struct texture *out[2], double w[2])
{
	const struct tex_entry *m = tex_map(t);
	int n = tex_nmap(t), i = 0;
	double v = value_at(c, &t->pigment, pattern_point(&t->pigment, p), 0);
	w[0] = 1, w[1] = 0;
	if (v >= m[n - 1].pos) {
		out[0] = m[n - 1].tex;
		return 1;
	}
	while (v > m[i].pos)
		i++;
	out[0] = m[i].tex;
	if (i == 0 || v == m[i].pos)
		return 1;
	out[1] = m[i - 1].tex;
	w[1] = (m[i].pos - v) / (m[i].pos - m[i - 1].pos);
	w[0] = 1 - w[1];
	return 2;
}

const struct texture *mat_texture_leaf(const struct mat_cache *c, const struct texture *t, struct vec3 p)
{
	for (int depth = 0; tex_map(t) && depth < 16; depth++) {
		const struct texture *k[2];
		double w[2];
		int n = mat_texture_pick(c, t, p, k, w);
		t = n == 2 && w[1] > w[0] ? k[1] : k[0];
	}
	return t;
}
