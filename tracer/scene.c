/* SPDX-License-Identifier: MIT */
/* scene.c: scene defaults (POV-Ray 3.7's), list growth, and --dump-scene. */
#include "scene.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "shape.h"

void scene_init(struct scene *s)
{
	memset(s, 0, sizeof *s);
	arena_init_large(&s->arena); /* its objects: a million spheres fill ~100 MB */
	s->version = 3.7;
	s->camera = scene_default_camera();
	s->background = (struct colour){0, 0, 0, 0, 0};
	s->gs.assumed_gamma = 1.0;
	s->gs.max_trace_level = 5;
	s->gs.adc_bailout = 1.0 / 255;
	s->gs.ambient_light = c_rgb(1, 1, 1);
	s->gs.noise_generator = 2;
	s->gs.number_of_waves = 10;
	s->gs.illum.method = ILLUM_SHAFT; /* light shafts: smooth caustics, no point noise */
	s->gs.illum.passes = PASSES_RGB;
}

/* POV-Ray's default finish, which every texture without a finish shares. */
static const struct finish default_finish = {
	.ambient = {0.1, 0.1, 0.1, 0, 0}, .diffuse = 0.6, .brilliance = 1, .roughness = 0.05,
	.phong_size = 40, .refl_falloff = 1,
};

static const struct pattern default_pattern = {
	.axis = {0, 1, 0}, .frequency = 1, .exponent = 1, .brick_size = {8, 3, 4.5}, .mortar = 0.5,
	.agate_turb = 1, .metric = 2, .form = {-1, 1, 0}, .control0 = 1, .control1 = 1,
};

const struct pattern *pig_pattern(const struct pigment *p)
{
	return p->pat ? p->pat : &default_pattern;
}

struct colour pig_colour(const struct pigment *p, int k)
{
	return k == 0 ? p->c[0] : pig_pattern(p)->more[k - 1];
}

struct texture scene_default_texture(void)
{
	struct texture t;
	memset(&t, 0, sizeof t);
	t.pigment.kind = PIG_SOLID;
	t.pigment.xf = NULL;
	t.ext = NULL; /* tex_ext_none */
	return t;
}

const struct tex_ext tex_ext_none = {.finish = &default_finish, .loc = {-1, 0, 0}};

struct interior scene_default_interior(void)
{
	return (struct interior){.ior = 1, .dispersion = 1, .dispersion_samples = 7, .fade_power = 0,
	                         .fade_color = {0, 0, 0, 0, 0}};
}

struct camera scene_default_camera(void)
{
	struct camera c;
	memset(&c, 0, sizeof c);
	c.kind = CAM_PERSPECTIVE;
	c.direction = v3(0, 0, 1);
	c.up = v3(0, 1, 0);
	c.right = v3(1.33, 0, 0);
	c.sky = v3(0, 1, 0);
	c.look_at = v3(0, 0, 1);
	c.blur_samples = 0;
	c.loc = (struct srcloc){-1, 0, 0};
	return c;
}

struct light scene_default_light(void)
{
	struct light l;
	memset(&l, 0, sizeof l);
	l.kind = LIGHT_POINT;
	l.colour = c_rgb(1, 1, 1);
	l.point_at = v3(0, 0, 1);
	l.radius = 30;
	l.falloff = 45;
	l.size1 = l.size2 = 1;
	l.photons_refraction = l.photons_reflection = true;
	return l;
}

/* Appends to an arena-backed array whose capacity is the next power of two. */
static void *grow(struct arena *a, void *arr, int n, size_t elem)
{
	if (n && (n & (n - 1)))
		return arr;
	void *b = arena_alloc(a, elem * (size_t)(n ? n * 2 : 4));
	if (n)
		memcpy(b, arr, elem * (size_t)n);
	return b;
}

size_t obj_size(enum object_kind k)
{
	static const struct object o;
	size_t g;
	switch (k) {
	case OBJ_SPHERE: g = sizeof o.g.sphere; break;
	case OBJ_PLANE: g = sizeof o.g.plane; break;
	case OBJ_BOX: g = sizeof o.g.box; break;
	case OBJ_TORUS: g = sizeof o.g.torus; break;
	case OBJ_SUPERELLIPSOID: g = sizeof o.g.superellipsoid; break;
	case OBJ_BLOB: case OBJ_MESH: case OBJ_TEXT: case OBJ_PRISM: case OBJ_POLYGON: case OBJ_LATHE:
	case OBJ_SOR: case OBJ_ISOSURFACE: g = sizeof(void *); break;
	case OBJ_UNION: case OBJ_INTERSECTION: case OBJ_DIFFERENCE: case OBJ_MERGE: case OBJ_CLIP:
		g = sizeof o.g.csg;
		break;
	default: return sizeof o; /* disc, cylinder, cone, triangle, poly */
	}
	return offsetof(struct object, g) + g;
}

struct object *obj_new(struct arena *a, enum object_kind k)
{
	struct object *o = arena_alloc8(a, obj_size(k));
	o->kind = (uint8_t)k;
	return o;
}

struct object *obj_copy(struct arena *a, const struct object *o)
{
	size_t n = obj_size(o->kind);
	struct object *c = arena_alloc8(a, n);
	memcpy(c, o, n);
	return c;
}

struct obj_extra *obj_extra_w(struct arena *a, struct object *o)
{
	struct obj_extra *x = arena_alloc8(a, sizeof *x);
	*x = o->ext ? *o->ext : (struct obj_extra){0};
	o->ext = x;
	return x;
}

/* The top-level list is one malloc'd array (freed by scene_free), not an
 * arena one: doubling in the arena would keep every smaller copy, 8 MB more
 * at a million objects. */
void scene_add_object(struct scene *s, struct object *o)
{
	int n = s->nobjects;
	if (n >= 4 && (n & (n - 1)) == 0)
		s->objects = mem_realloc(s->objects, sizeof *s->objects * (size_t)n * 2);
	else if (n == 0)
		s->objects = mem_alloc(sizeof *s->objects * 4);
	s->objects[s->nobjects++] = o;
}

void scene_add_light(struct scene *s, const struct light *l)
{
	s->lights = grow(&s->arena, s->lights, s->nlights, sizeof *s->lights);
	s->lights[s->nlights++] = *l;
}

void scene_free(struct scene *s)
{
	free(s->objects);
	s->objects = NULL;
	arena_free(&s->arena);
}

const char *scene_pov_view(const struct scene *s)
{
	if (!s->legacy_lights)
		return NULL;
	bool srgb = s->gs.gamma_given ? s->gs.assumed_gamma < 1.6 : s->version >= 3.7;
	return srgb ? "Standard" : "Raw";
}

/* ==== --dump-scene ======================================================== */

static const char *const kind_names[OBJ_KIND_COUNT] = {
#define PRIM(n, w) [OBJ_##n] = #w,
#define CSG(n, w) [OBJ_##n] = #w,
#define NODE(n, w) [OBJ_##n] = #w,
#include "objects.def"
};

const char *scene_object_kind_name(enum object_kind k) { return kind_names[k]; }

static void pv(FILE *o, struct vec3 v) { fprintf(o, "<%.6g, %.6g, %.6g>", v.x + 0.0, v.y + 0.0, v.z + 0.0); }

static void pc(FILE *o, struct colour c)
{
	fprintf(o, "rgbft <%.6g, %.6g, %.6g, %.6g, %.6g>", c.r + 0.0, c.g + 0.0, c.b + 0.0, c.f + 0.0, c.t + 0.0);
}

static void indent(FILE *o, int d) { fprintf(o, "%*s", d * 2, ""); }

static void dump_xform(FILE *o, const struct xform *x, int d)
{
	if (xf_is_identity(x))
		return;
	indent(o, d);
	fputs("matrix", o);
	for (int i = 0; i < 3; i++)
		fprintf(o, " [%.6g %.6g %.6g %.6g]", x->m[i][0] + 0.0, x->m[i][1] + 0.0, x->m[i][2] + 0.0, x->m[i][3] + 0.0);
	fputc('\n', o);
}

static void dump_pigment(FILE *o, const struct pigment *p, int d);

/* A pattern's warps (in the order they act), noise settings and pigments. */
static void dump_pattern_extras(FILE *o, const struct pigment *p, int d)
{
	const struct pattern *pt = pig_pattern(p);
	for (int i = 0; i < pt->nwarps; i++) {
		const struct warp *w = &pt->warps[i];
		indent(o, d);
		switch (w->kind) {
		case WARP_TURB:
			fprintf(o, "%s ", w->classic ? "turbulence" : "warp turbulence"), pv(o, w->turb);
			fprintf(o, " octaves %d omega %.6g lambda %.6g\n", w->octaves, w->omega, w->lambda);
			break;
		case WARP_REPEAT:
			fprintf(o, "warp repeat axis %d width %.6g offset ", w->axis, w->width), pv(o, w->offset);
			fputs(" flip ", o), pv(o, w->flip), fputc('\n', o);
			break;
		case WARP_BLACK_HOLE:
			fputs("warp black_hole ", o), pv(o, w->center);
			fprintf(o, " radius %.6g falloff %.6g strength %.6g%s\n", w->radius, w->falloff, w->strength,
			        w->inverse ? " inverse" : "");
			break;
		case WARP_XF:
			fputs("warp transform\n", o);
			dump_xform(o, w->xf, d + 1);
			break;
		}
	}
	if (p->kind == PIG_PATTERN && pt->pattern >= PAT_BOZO && pt->pattern < PAT_PIGMENT) {
		indent(o, d);
		fprintf(o, "noise_generator %d", pt->noise_gen);
		if (pt->pattern == PAT_CRACKLE)
			fprintf(o, " metric %.6g offset %.6g solid %d form ", pt->metric, pt->offset, pt->solid), pv(o, pt->form);
		if (pt->pattern == PAT_AGATE)
			fprintf(o, " agate_turb %.6g", pt->agate_turb);
		if (pt->pattern == PAT_QUILTED)
			fprintf(o, " control0 %.6g control1 %.6g", pt->control0, pt->control1);
		if (pt->pattern == PAT_SPIRAL1 || pt->pattern == PAT_SPIRAL2)
			fprintf(o, " arms %d", pt->arms);
		fputc('\n', o);
	}
	if (pt->sub)
		dump_pigment(o, pt->sub, d);
	for (int i = 0; i < pt->npmap; i++) {
		indent(o, d);
		fprintf(o, "[%.6g\n", pt->pmap[i].pos);
		dump_pigment(o, pt->pmap[i].pig, d + 1);
	}
}

static void dump_pigment(FILE *o, const struct pigment *p, int d)
{
	static const char *const kinds[] = {"solid", "checker", "gradient", "image_map", "pattern", "hexagon", "brick"};
	static const char *const pats[] = {"radial", "onion", "spherical", "cylindrical", "boxed", "planar", "leopard",
		"bozo", "spotted", "bumps", "dents", "granite", "marble", "wood", "agate", "wrinkles", "ripples", "waves",
		"crackle", "quilted", "spiral1", "spiral2", "cells", "mandel", "pigment_pattern", "average", "function"};
	_Static_assert(sizeof pats / sizeof *pats == PAT_KIND_COUNT, "a name for every pattern kind");
	static const char *const waves[] = {"ramp", "triangle", "sine", "scallop", "cubic", "poly"};
	indent(o, d);
	fprintf(o, "pigment %s ", kinds[p->kind]);
	switch (p->kind) {
	case PIG_SOLID: pc(o, p->c[0]); break;
	case PIG_CHECKER: pc(o, p->c[0]), fputc(' ', o), pc(o, pig_colour(p, 1)); break;
	case PIG_GRADIENT: pv(o, pig_pattern(p)->axis); break;
	case PIG_IMAGE: fprintf(o, "\"%s\" interpolate %d once %d", pig_pattern(p)->image, pig_pattern(p)->interpolate, pig_pattern(p)->once); break;
	case PIG_PATTERN: fputs(pats[pig_pattern(p)->pattern], o); break;
	case PIG_HEXAGON: pc(o, p->c[0]), fputc(' ', o), pc(o, pig_colour(p, 1)), fputc(' ', o), pc(o, pig_colour(p, 2)); break;
	case PIG_BRICK:
		pc(o, p->c[0]), fputc(' ', o), pc(o, pig_colour(p, 1)), fputs(" brick_size ", o), pv(o, pig_pattern(p)->brick_size);
		fprintf(o, " mortar %.6g", pig_pattern(p)->mortar);
		break;
	}
	if ((p->kind == PIG_GRADIENT || p->kind == PIG_PATTERN) &&
	    (pig_pattern(p)->wave != WAVE_RAMP || pig_pattern(p)->frequency != 1 || pig_pattern(p)->phase != 0))
		fprintf(o, " %s_wave %.6g frequency %.6g phase %.6g", waves[pig_pattern(p)->wave], pig_pattern(p)->exponent, pig_pattern(p)->frequency, pig_pattern(p)->phase);
	fputc('\n', o);
	for (int i = 0; i < pig_pattern(p)->nmap; i++) {
		indent(o, d + 1);
		fprintf(o, "[%.6g ", pig_pattern(p)->map[i].pos);
		pc(o, pig_pattern(p)->map[i].c);
		fputs("]\n", o);
	}
	dump_xform(o, p->xf ? p->xf : &xf_ident, d + 1);
	dump_pattern_extras(o, p, d + 1);
}

static void dump_normal(FILE *o, const struct tnormal *t, int d)
{
	indent(o, d);
	fprintf(o, "normal amount %.6g\n", t->amount);
	dump_pigment(o, &t->pat, d + 1);
	for (int i = 0; i < t->nmap; i++) {
		indent(o, d + 1);
		fprintf(o, "[%.6g\n", t->map[i].pos);
		if (t->map[i].n)
			dump_normal(o, t->map[i].n, d + 2);
	}
}

static void dump_finish(FILE *o, const struct finish *f, int d)
{
	indent(o, d);
	fputs("finish ambient ", o);
	pc(o, f->ambient);
	fprintf(o, " diffuse %.6g brilliance %.6g specular %.6g roughness %.6g phong %.6g phong_size %.6g\n",
	        f->diffuse, f->brilliance, f->specular, f->roughness, f->phong, f->phong_size);
	indent(o, d + 1);
	fputs("reflection ", o);
	pc(o, f->refl_min);
	fputc(' ', o);
	pc(o, f->refl_max);
	fprintf(o, " falloff %.6g fresnel %d metallic %d conserve_energy %d emission ", f->refl_falloff,
	        f->refl_fresnel, f->refl_metallic, f->conserve_energy);
	pc(o, f->emission);
	fputc('\n', o);
}

static void dump_object(FILE *o, const struct object *ob, int d);

static void dump_geometry(FILE *o, const struct object *ob, int d)
{
	indent(o, d);
	if (!shape_dump(ob, o))
		fprintf(o, "children %d", ob->g.csg.n);
	fputc('\n', o);
}

static void dump_object(FILE *o, const struct object *ob, int d)
{
	static const char *const flags[] = {"no_shadow", "no_image", "no_reflection", "hollow", "inverse",
		"open", "sturm", "double_illuminate"};
	indent(o, d);
	fprintf(o, "object %s @%d:%d\n", kind_names[ob->kind], ob->loc.line, ob->loc.col);
	dump_geometry(o, ob, d + 1);
	dump_xform(o, obj_xf(ob), d + 1);
	if (ob->flags) {
		indent(o, d + 1);
		fputs("flags", o);
		for (int i = 0; i < 8; i++)
			if (ob->flags & (1u << i))
				fprintf(o, " %s", flags[i]);
		fputc('\n', o);
	}
	if (ob->tex) {
		indent(o, d + 1);
		const struct tex_ext *x = tex_x(ob->tex);
		fprintf(o, "texture @%d:%d\n", x->loc.line, x->loc.col);
		dump_pigment(o, &ob->tex->pigment, d + 2);
		dump_finish(o, x->finish, d + 2);
		if (x->normal)
			dump_normal(o, x->normal, d + 2);
		for (int i = 0; i < x->nmap; i++) {
			const struct texture *k = x->map[i].tex;
			indent(o, d + 2);
			fprintf(o, "[%.6g texture\n", x->map[i].pos);
			dump_pigment(o, &k->pigment, d + 3);
			dump_finish(o, tex_finish(k), d + 3);
			if (tex_normal(k))
				dump_normal(o, tex_normal(k), d + 3);
		}
	}
	if (obj_interior(ob)) {
		const struct interior *in = obj_interior(ob);
		indent(o, d + 1);
		fprintf(o, "interior ior %.6g dispersion %.6g dispersion_samples %d fade_distance %.6g fade_power %.6g fade_color ",
		        in->ior, in->dispersion, in->dispersion_samples, in->fade_distance, in->fade_power);
		pc(o, in->fade_color);
		fputc('\n', o);
	}
	struct illum_spec il = obj_illum(ob);
	if (il.resolution || il.cell) {
		indent(o, d + 1);
		fprintf(o, "illum_map resolution %d cell %.6g\n", il.resolution, il.cell);
	}
	if (obj_photons(ob)) {
		const struct photon_spec *p = obj_photons(ob);
		indent(o, d + 1);
		fprintf(o, "photons target %d spacing %.6g refraction %d reflection %d collect %d pass_through %d\n",
		        p->target, p->spacing, p->refraction, p->reflection, p->collect, p->pass_through);
	}
	if (ob->kind >= OBJ_FIRST_CSG)
		for (int i = 0; i < ob->g.csg.n; i++)
			dump_object(o, ob->g.csg.kids[i], d + 1);
}

static void dump_light(FILE *o, const struct light *l)
{
	static const char *const kinds[] = {"point", "spotlight", "parallel"};
	fprintf(o, "light %s @%d:%d\n  position ", kinds[l->kind], l->loc.line, l->loc.col);
	pv(o, l->pos);
	fputs(" colour ", o);
	pc(o, l->colour);
	fputc('\n', o);
	if (l->kind != LIGHT_POINT) {
		fputs("  point_at ", o);
		pv(o, l->point_at);
		fprintf(o, " radius %.6g falloff %.6g tightness %.6g\n", l->radius, l->falloff, l->tightness);
	}
	if (l->area) {
		fputs("  area_light ", o);
		pv(o, l->axis1);
		fputc(' ', o);
		pv(o, l->axis2);
		fprintf(o, " %d %d adaptive %d jitter %d circular %d orient %d\n", l->size1, l->size2, l->adaptive,
		        l->jitter, l->circular, l->orient);
	}
	if (l->fade_distance > 0 || l->fade_power > 0)
		fprintf(o, "  fade_distance %.6g fade_power %.6g\n", l->fade_distance, l->fade_power);
	if (l->shadowless)
		fputs("  shadowless\n", o);
	if (!l->photons_refraction || !l->photons_reflection)
		fprintf(o, "  photons refraction %d reflection %d\n", l->photons_refraction, l->photons_reflection);
}

void scene_dump(FILE *o, const struct scene *s)
{
	const struct camera *c = &s->camera;
	const struct global_settings *g = &s->gs;
	fprintf(o, "scene \"%s\" version %.6g legacy_lights %d\n", s->name ? s->name : "", s->version, s->legacy_lights);
	fprintf(o, "global_settings assumed_gamma %.6g max_trace_level %d adc_bailout %.6g ambient_light ",
	        g->assumed_gamma, g->max_trace_level, g->adc_bailout);
	pc(o, g->ambient_light);
	fprintf(o, "\n  illumination rays %ld method %s passes %s max_depth %d photon_spacing %.6g photon_count %ld\n",
	        g->illum.rays, g->illum.method == ILLUM_SHAFT ? "shaft" : "point",
	        g->illum.passes == PASSES_SPECTRAL ? "spectral" : "rgb", g->illum.max_depth, g->illum.spacing, g->illum.count);
	if (g->illum.tolerance > 0)
		fprintf(o, "  illumination tolerance %.6g\n", g->illum.tolerance);
	fputs("background ", o);
	pc(o, s->background);
	if (s->nsky > 0) {
		fprintf(o, "\nsky_sphere %d\n", s->nsky);
		for (int i = 0; i < s->nsky; i++)
			dump_pigment(o, &s->sky[i], 1);
		if (s->sky_xf)
			dump_xform(o, s->sky_xf, 1);
		fputs("end sky_sphere", o);
	}
	if (s->fog.type) {
		const struct fog *f = &s->fog;
		fprintf(o, "\nfog type %d distance %.6g offset %.6g alt %.6g up ", f->type, f->distance, f->offset, f->alt);
		pv(o, f->up);
		fputc(' ', o);
		pc(o, f->c);
	}
	static const char *const kinds[] = {"perspective", "orthographic", "fisheye", "ultra_wide_angle", "panoramic",
	                                    "cylinder 1", "cylinder 2", "cylinder 3", "cylinder 4", "spherical",
	                                    "omnimax"};
	fprintf(o, "\ncamera %s @%d:%d\n  location ", kinds[c->kind],
	        c->loc.line, c->loc.col);
	pv(o, c->location);
	fputs(" direction ", o);
	pv(o, c->direction);
	fputs("\n  up ", o);
	pv(o, c->up);
	fputs(" right ", o);
	pv(o, c->right);
	fputs(" sky ", o);
	pv(o, c->sky);
	fprintf(o, "\n  angle %.6g aperture %.6g blur_samples %d focal_point ", c->angle, c->aperture, c->blur_samples);
	pv(o, c->focal_point);
	fputc('\n', o);
	for (int i = 0; i < s->nlights; i++)
		dump_light(o, &s->lights[i]);
	for (int i = 0; i < s->nobjects; i++)
		dump_object(o, s->objects[i], 0);
}
