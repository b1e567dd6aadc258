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

/* Walks an object tree, loading the image_map of every texture. */
static int load_tree(struct mat_cache *c, const struct object *o, const char *ocio, struct diag *dg)
{
	if (o->tex && o->tex->pigment.kind == PIG_IMAGE) {
		int err = cache_add(c, pig_pattern(&o->tex->pigment), ocio, dg);
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
	return o->interior ? o->interior : &def;
}

/* ==== patterns =========================================================== */

static struct colour c_lerp(struct colour a, struct colour b, double t)
{
	return (struct colour){a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t,
	                       a.f + (b.f - a.f) * t, a.t + (b.t - a.t) * t};
}

/* The colour_map at v ∈ [0,1]: linear between entries, clamped at the ends;
 * without a map, black to white. */
static struct colour colour_map(const struct pigment *pg, double v)
{
	if (!pig_pattern(pg)->map || pig_pattern(pg)->nmap == 0)
		return c_rgb(v, v, v);
	const struct map_entry *m = pig_pattern(pg)->map;
	if (v <= m[0].pos)
		return m[0].c;
	for (int i = 1; i < pig_pattern(pg)->nmap; i++)
		if (v <= m[i].pos) {
			double span = m[i].pos - m[i - 1].pos;
			return span > 0 ? c_lerp(m[i - 1].c, m[i].c, (v - m[i - 1].pos) / span) : m[i].c;
		}
	return m[pig_pattern(pg)->nmap - 1].c;
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
	const struct img *im = cache_find(c, pig_pattern(pg)->image ? pig_pattern(pg)->image : "");
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

struct colour mat_pigment(const struct mat_cache *c, const struct pigment *pg, struct vec3 p)
{
	if (pg->kind == PIG_SOLID)
		return pg->c[0];
	struct vec3 q = xf_inv_point(pg->xf ? pg->xf : &xf_ident, p);
	switch (pg->kind) {
	case PIG_CHECKER: case PIG_HEXAGON: case PIG_BRICK: return pig_colour(pg, pattern_block(pg, q));
	case PIG_GRADIENT: case PIG_PATTERN: return colour_map(pg, pattern_value(pg, q));
	case PIG_IMAGE: return image_map(c, pg, q);
	default: return pg->c[0];
	}
}
