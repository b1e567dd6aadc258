/* SPDX-License-Identifier: MIT */
/* objects.c: what each block accepts. A sink stands for the block being
 * evaluated; sink_keyword and sink_value dispatch on its kind and build the
 * scene model (tracer/scene.h). Misplaced or unknown keywords are errors. */
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* ==== helpers ============================================================= */

void sink_init(struct sink *s, enum sink_kind kind, enum tok kw, struct srcloc loc, void *target)
{
	memset(s, 0, sizeof *s);
	s->kind = kind;
	s->kw = kw;
	s->loc = loc;
	s->target = target;
}

static const char *where(const struct sink *s)
{
	static char buf[64];
	switch (s->kind) {
	case SK_SCENE: return "at the top level of a scene";
	case SK_VALUE: return "where a value is expected";
	case SK_ENTRY: return "in a colour_map entry";
	case SK_DEFAULT: return "in '#default'";
	default: snprintf(buf, sizeof buf, "in %s", tok_name(s->kw)); return buf;
	}
}

static _Noreturn void misplaced(struct eval *E, const struct sink *s, const struct node *n)
{
	eval_fail(E, n->loc, "%s is not valid %s", tok_name(n->op), where(s));
}

/* The single argument of a keyword item like `translate <1,0,0>`. */
static struct value arg1(struct eval *E, const struct node *n)
{
	if (n->nkids != 1)
		eval_fail(E, n->loc, "%s takes one value, found %d", tok_name(n->op), n->nkids);
	return eval_expr(E, n->kids[0]);
}

static double arg_float(struct eval *E, const struct node *n)
{
	struct value v = arg1(E, n);
	return val_want_float(E, &v, n->kids[0]->loc);
}

static struct vec3 arg_vec3(struct eval *E, const struct node *n)
{
	struct value v = arg1(E, n);
	return val_want_vec3(E, &v, n->kids[0]->loc);
}

static struct colour arg_colour(struct eval *E, const struct node *n)
{
	struct value v = arg1(E, n);
	return val_want_colour(E, &v, n->kids[0]->loc);
}

/* An optional on/off argument (`fresnel`, `fresnel on`, `hollow off`). */
static bool arg_bool(struct eval *E, const struct node *n)
{
	return n->nkids == 0 ? true : arg_float(E, n) != 0;
}

static double arg_positive(struct eval *E, const struct node *n)
{
	double f = arg_float(E, n);
	if (!(f > 0))
		eval_fail(E, n->kids[0]->loc, "%s must be positive, found %g", tok_name(n->op), f);
	return f;
}

static int arg_int(struct eval *E, const struct node *n, int lo, int hi)
{
	double f = arg_float(E, n);
	if (!(f >= lo && f <= hi))
		eval_fail(E, n->kids[0]->loc, "%s must be %d to %d, found %g", tok_name(n->op), lo, hi, f);
	return (int)f;
}

static struct scene *SC(struct eval *E) { return E->scene; }

#define NEW(E, type) ARENA_NEW(&SC(E)->arena, type)

/* ==== transforms ========================================================== */

/* translate/rotate/scale/matrix/transform: computes the transform of item n;
 * false when n is not a transform keyword. */
static bool transform_of(struct eval *E, const struct node *n, struct xform *out)
{
	switch (n->op) {
	case TK_TRANSLATE: *out = xf_translate(arg_vec3(E, n)); return true;
	case TK_ROTATE: *out = xf_rotate(arg_vec3(E, n)); return true;
	case TK_SCALE: {
		struct vec3 s = arg_vec3(E, n);
		if (s.x == 0 || s.y == 0 || s.z == 0)
			eval_fail(E, n->kids[0]->loc, "scale by zero");
		*out = xf_scale(s);
		return true;
	}
	case TK_MATRIX: {
		struct value v = arg1(E, n);
		if (v.kind != V_ARRAY || v.p.arr->n != 12)
			eval_fail(E, n->kids[0]->loc, "matrix needs 12 values <a,b,c, d,e,f, g,h,i, x,y,z>");
		double m[12];
		for (int i = 0; i < 12; i++)
			m[i] = v.p.arr->items[i].v[0];
		if (!xf_from_pov_matrix(m, out))
			eval_fail(E, n->kids[0]->loc, "matrix is singular");
		return true;
	}
	case TK_TRANSFORM: {
		struct value v = n->kind == N_BLOCK ? eval_block(E, n) : arg1(E, n);
		if (v.kind != V_TRANSFORM)
			eval_fail(E, n->loc, "expected a transform, found %s", val_type_name(&v));
		*out = *v.p.xf;
		return true;
	}
	default: return false;
	}
}

static struct texture *texture_copy(struct eval *E, const struct texture *t)
{
	struct texture *c = NEW(E, struct texture);
	*c = t ? *t : E->default_tex;
	return c;
}

/* Applies X to an object, its texture and its children (POV-Ray moves the
 * texture with the object when the texture came first). */
static void object_transform(struct eval *E, struct object *o, const struct xform *X)
{
	o->xf = xf_then(o->xf, *X);
	if (o->tex) {
		o->tex = texture_copy(E, o->tex);
		o->tex->pigment.xf = xf_then(o->tex->pigment.xf, *X);
	}
	if (o->kind >= OBJ_UNION)
		for (int i = 0; i < o->g.csg.n; i++)
			object_transform(E, o->g.csg.kids[i], X);
}

static struct object *object_copy(struct eval *E, const struct object *o)
{
	struct object *c = NEW(E, struct object);
	*c = *o;
	if (o->kind >= OBJ_UNION) {
		c->g.csg.kids = ARENA_ARRAY(&SC(E)->arena, struct object *, o->g.csg.n);
		for (int i = 0; i < o->g.csg.n; i++)
			c->g.csg.kids[i] = object_copy(E, o->g.csg.kids[i]);
	}
	return c;
}

static void light_transform(struct light *l, const struct xform *X)
{
	l->pos = xf_point(X, l->pos);
	l->point_at = xf_point(X, l->point_at);
	l->axis1 = xf_vector(X, l->axis1);
	l->axis2 = xf_vector(X, l->axis2);
}

static void camera_transform(struct camera *c, const struct xform *X)
{
	c->location = xf_point(X, c->location);
	c->look_at = xf_point(X, c->look_at);
	c->focal_point = xf_point(X, c->focal_point);
	c->direction = xf_vector(X, c->direction);
	c->up = xf_vector(X, c->up);
	c->right = xf_vector(X, c->right);
	c->sky = xf_vector(X, c->sky);
}

/* ==== pigments, colour maps, finishes, interiors ========================= */

static void pigment_keyword(struct eval *E, struct sink *s, const struct node *n);
static void finish_keyword(struct eval *E, struct sink *s, const struct node *n);

/* Evaluates a block's items into a fresh sink of the given kind. */
static void run_block(struct eval *E, const struct node *blk, enum sink_kind kind, void *target, struct sink *out)
{
	sink_init(out, kind, blk->op, blk->loc, target);
	eval_items(E, blk, out);
}

static struct colour_map *colour_map_block(struct eval *E, const struct node *blk)
{
	struct colour_map *m = NEW(E, struct colour_map);
	struct sink s;
	run_block(E, blk, SK_COLOUR_MAP, m, &s);
	if (m->n == 0)
		eval_fail(E, blk->loc, "colour_map needs at least one entry [position colour]");
	return m;
}

/* [position colour] of a colour_map. */
static void colour_map_entry(struct eval *E, struct colour_map *m, const struct node *n)
{
	struct sink s;
	sink_init(&s, SK_ENTRY, TK_COLOR_MAP, n->loc, NULL);
	eval_items(E, n, &s);
	if (s.nparams != 2)
		eval_fail(E, n->loc, "a colour_map entry is [position colour], found %d value%s", s.nparams, s.nparams == 1 ? "" : "s");
	double pos = val_want_float(E, &s.params[0], s.ploc[0]);
	if (pos < 0 || pos > 1)
		eval_fail(E, s.ploc[0], "colour_map position must be 0 to 1, found %g", pos);
	if (m->n > 0 && pos < m->e[m->n - 1].pos)
		eval_fail(E, s.ploc[0], "colour_map positions must not decrease (%g after %g)", pos, m->e[m->n - 1].pos);
	if (m->n >= 256)
		eval_fail(E, n->loc, "colour_map has more than 256 entries");
	struct map_entry *e = ARENA_ARRAY(&SC(E)->arena, struct map_entry, m->n + 1);
	if (m->n)
		memcpy(e, m->e, sizeof *e * (size_t)m->n);
	e[m->n++] = (struct map_entry){pos, val_want_colour(E, &s.params[1], s.ploc[1])};
	m->e = e;
}

/* Resolves an image file like an include: only allowed directories. */
static void set_image(struct eval *E, struct pigment *p, struct srcloc loc, const char *name)
{
	char *real = eval_find_file(E, name, loc, "image file", NULL);
	p->image = arena_strndup(&SC(E)->arena, real, strlen(real));
	p->image_name = arena_strndup(&SC(E)->arena, name, strlen(name));
	p->image_loc = loc;
	free(real);
}

static void image_map_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct pigment *p = s->target;
	switch (n->op) {
	case TK_PNG: case TK_EXR: {
		struct value v = arg1(E, n);
		if (v.kind != V_STRING)
			eval_fail(E, n->kids[0]->loc, "expected a file name string, found %s", val_type_name(&v));
		set_image(E, p, n->loc, v.p.s);
		return;
	}
	case TK_INTERPOLATE: p->interpolate = arg_int(E, n, 0, 4); return;
	case TK_ONCE: p->once = true; return;
	case TK_MAP_TYPE:
		if (arg_int(E, n, 0, 7) != 0)
			eval_fail(E, n->kids[0]->loc, "only map_type 0 (planar) is supported");
		return;
	default: misplaced(E, s, n);
	}
}

static void pigment_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct pigment *p = s->target;
	struct xform X;
	s->modified = 1;
	if (transform_of(E, n, &X)) {
		p->xf = xf_then(p->xf, X);
		return;
	}
	switch (n->op) {
	case TK_CHECKER:
		p->kind = PIG_CHECKER;
		p->c[0] = c_rgb(0, 0, 1);
		p->c[1] = c_rgb(0, 1, 0);
		s->nparams = 0;
		s->modified = 0;
		return;
	case TK_GRADIENT: {
		struct vec3 a = arg_vec3(E, n);
		if (v_len(a) == 0)
			eval_fail(E, n->kids[0]->loc, "gradient direction has zero length");
		p->kind = PIG_GRADIENT;
		p->axis = a;
		return;
	}
	case TK_COLOR_MAP: case TK_COLOUR_MAP: {
		struct colour_map *m = colour_map_block(E, n);
		p->map = m->e;
		p->nmap = m->n;
		return;
	}
	case TK_IMAGE_MAP: {
		struct sink sub;
		p->kind = PIG_IMAGE;
		p->interpolate = 0;
		run_block(E, n, SK_IMAGE_MAP, p, &sub);
		if (!p->image)
			eval_fail(E, n->loc, "image_map needs a file: image_map { png \"file.png\" }");
		return;
	}
	default: misplaced(E, s, n);
	}
}

static void pigment_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc)
{
	struct pigment *p = s->target;
	if (v->kind == V_PIGMENT && s->nparams == 0 && !s->modified) {
		*p = *v->p.pig;
		s->modified = 1;
		return;
	}
	if (v->kind == V_COLOUR_MAP && p->kind == PIG_GRADIENT) {
		p->map = v->p.cmap->e;
		p->nmap = v->p.cmap->n;
		return;
	}
	if (v->kind != V_COLOUR && v->kind != V_FLOAT && v->kind != V_VECTOR)
		eval_fail(E, loc, "expected a colour in pigment, found %s", val_type_name(v));
	struct colour c = val_want_colour(E, v, loc);
	if (p->kind == PIG_CHECKER) {
		if (s->nparams >= 2)
			eval_fail(E, loc, "checker takes two colours, found a third");
		p->c[s->nparams++] = c;
		return;
	}
	if (s->modified)
		eval_fail(E, loc, "a colour must come first in a pigment");
	p->kind = PIG_SOLID;
	p->c[0] = c;
	s->modified = 1;
}

static void reflection_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct finish *f = s->target;
	switch (n->op) {
	case TK_FRESNEL: f->refl_fresnel = arg_bool(E, n); return;
	case TK_FALLOFF: f->refl_falloff = arg_positive(E, n); return;
	case TK_METALLIC: f->refl_metallic = arg_bool(E, n); return;
	default: misplaced(E, s, n);
	}
}

static void finish_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct finish *f = s->target;
	s->modified = 1;
	switch (n->op) {
	case TK_AMBIENT: f->ambient = arg_colour(E, n); f->ambient.f = f->ambient.t = 0; return;
	case TK_DIFFUSE: f->diffuse = arg_float(E, n); return;
	case TK_BRILLIANCE: f->brilliance = arg_float(E, n); return;
	case TK_SPECULAR: f->specular = arg_float(E, n); return;
	case TK_ROUGHNESS: f->roughness = arg_positive(E, n); return;
	case TK_PHONG: f->phong = arg_float(E, n); return;
	case TK_PHONG_SIZE: f->phong_size = arg_float(E, n); return;
	case TK_METALLIC: arg_bool(E, n); return;
	case TK_CONSERVE_ENERGY: f->conserve_energy = arg_bool(E, n); return;
	case TK_EMISSION: f->emission = arg_colour(E, n); return;
	case TK_REFLECTION:
		if (n->kind == N_BLOCK) {
			struct sink r;
			f->refl_min = f->refl_max = c_rgb(0, 0, 0);
			run_block(E, n, SK_REFLECTION, f, &r);
			if (r.nparams == 0)
				eval_fail(E, n->loc, "reflection { } needs a value: reflection { 0.5 } or { min, max }");
			f->refl_min = val_want_colour(E, &r.params[0], r.ploc[0]);
			f->refl_max = r.nparams > 1 ? val_want_colour(E, &r.params[1], r.ploc[1]) : f->refl_min;
			f->refl_min.f = f->refl_min.t = f->refl_max.f = f->refl_max.t = 0;
		} else {
			f->refl_min = f->refl_max = arg_colour(E, n);
			f->refl_min.f = f->refl_min.t = f->refl_max.f = f->refl_max.t = 0;
		}
		return;
	default: misplaced(E, s, n);
	}
}

static void interior_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct interior *in = s->target;
	s->modified = 1;
	switch (n->op) {
	case TK_IOR: in->ior = arg_positive(E, n); return;
	case TK_DISPERSION: in->dispersion = arg_positive(E, n); return;
	case TK_DISPERSION_SAMPLES: in->dispersion_samples = arg_int(E, n, 2, 1000); return;
	case TK_FADE_DISTANCE: in->fade_distance = arg_float(E, n); return;
	case TK_FADE_POWER: in->fade_power = arg_float(E, n); return;
	case TK_FADE_COLOR: case TK_FADE_COLOUR: in->fade_color = arg_colour(E, n); return;
	case TK_CAUSTICS: in->caustics = arg_float(E, n); return;
	default: misplaced(E, s, n);
	}
}

/* ==== objects ============================================================= */

static enum object_kind object_kind_of(enum tok kw)
{
	switch (kw) {
	case TK_SPHERE: return OBJ_SPHERE;
	case TK_PLANE: return OBJ_PLANE;
	case TK_BOX: return OBJ_BOX;
	case TK_DISC: return OBJ_DISC;
	case TK_CYLINDER: return OBJ_CYLINDER;
	case TK_CONE: return OBJ_CONE;
	case TK_TORUS: return OBJ_TORUS;
	case TK_TRIANGLE: return OBJ_TRIANGLE;
	case TK_UNION: return OBJ_UNION;
	case TK_INTERSECTION: return OBJ_INTERSECTION;
	case TK_DIFFERENCE: return OBJ_DIFFERENCE;
	case TK_MERGE: return OBJ_MERGE;
	default: return OBJ_KIND_COUNT;
	}
}

static bool is_object_kw(enum tok kw) { return object_kind_of(kw) != OBJ_KIND_COUNT || kw == TK_OBJECT; }

static void csg_add(struct eval *E, struct object *o, struct object *kid)
{
	int n = o->g.csg.n;
	if ((n & (n - 1)) == 0) {
		struct object **k = ARENA_ARRAY(&SC(E)->arena, struct object *, n ? n * 2 : 2);
		if (n)
			memcpy(k, o->g.csg.kids, sizeof *k * (size_t)n);
		o->g.csg.kids = k;
	}
	o->g.csg.kids[o->g.csg.n++] = kid;
}

/* The object a sink is building; `object { }` must name one first. */
static struct object *object_target(struct eval *E, struct sink *s, struct srcloc loc)
{
	if (!s->target)
		eval_fail(E, loc, "'object' needs a declared object first: object { Name … }");
	return s->target;
}

/* pigment/finish/interior blocks inside an object modify what it has. */
static void object_material_block(struct eval *E, struct sink *s, struct object *o, const struct node *n)
{
	struct sink sub;
	if (n->op == TK_PIGMENT || n->op == TK_FINISH) {
		o->tex = texture_copy(E, o->tex);
		if (o->tex->loc.file < 0)
			o->tex->loc = n->loc;
		if (n->op == TK_PIGMENT)
			run_block(E, n, SK_PIGMENT, &o->tex->pigment, &sub);
		else
			run_block(E, n, SK_FINISH, &o->tex->finish, &sub);
	} else if (n->op == TK_INTERIOR) {
		struct interior *in = NEW(E, struct interior);
		*in = o->interior ? *o->interior : scene_default_interior();
		run_block(E, n, SK_INTERIOR, in, &sub);
		o->interior = in;
	} else if (n->op == TK_TEXTURE) {
		struct value v = eval_block(E, n);
		o->tex = v.p.tex;
	} else {
		struct value v = eval_block(E, n);
		if (v.p.mat->tex)
			o->tex = v.p.mat->tex;
		if (v.p.mat->interior)
			o->interior = v.p.mat->interior;
	}
	(void)s;
}

static void photons_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	if (s->kw == TK_OBJECT) { /* on an object */
		struct photon_spec *p = s->target;
		switch (n->op) {
		case TK_TARGET: p->target = true; p->spacing = n->nkids ? arg_positive(E, n) : 1; return;
		case TK_REFRACTION: p->refraction = arg_bool(E, n); return;
		case TK_REFLECTION: p->reflection = arg_bool(E, n); return;
		case TK_COLLECT: p->collect = arg_bool(E, n); return;
		case TK_PASS_THROUGH: p->pass_through = arg_bool(E, n); return;
		default: break;
		}
	} else if (s->kw == TK_LIGHT_SOURCE) {
		struct light *l = s->target;
		switch (n->op) {
		case TK_REFRACTION: l->photons_refraction = arg_bool(E, n); return;
		case TK_REFLECTION: l->photons_reflection = arg_bool(E, n); return;
		case TK_AREA_LIGHT: return;
		default: break;
		}
	} else { /* global_settings */
		struct illum_settings *g = s->target;
		g->given = true;
		switch (n->op) {
		case TK_SPACING: g->spacing = arg_positive(E, n); return;
		case TK_COUNT: g->count = (long)arg_positive(E, n); return;
		case TK_MAX_TRACE_LEVEL: g->max_depth = arg_int(E, n, 1, 256); return;
		case TK_GATHER: case TK_MEDIA: case TK_JITTER: case TK_AUTOSTOP: case TK_EXPAND_THRESHOLDS:
		case TK_RADIUS: case TK_ADC_BAILOUT:
			for (int i = 0; i < n->nkids; i++)
				eval_float(E, n->kids[i]);
			return;
		default: break;
		}
	}
	eval_fail(E, n->loc, "%s is not valid in 'photons' here", tok_name(n->op));
}

static void object_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct xform X;
	if (s->kw == TK_OBJECT && !s->target && is_object_kw(n->op) && n->kind == N_BLOCK) {
		s->target = eval_block(E, n).p.obj; /* object { Macro() } with a macro yielding an object */
		return;
	}
	if (transform_of(E, n, &X)) {
		object_transform(E, object_target(E, s, n->loc), &X);
		s->modified = 1;
		return;
	}
	struct object *o = object_target(E, s, n->loc);
	s->modified = 1;
	switch (n->op) {
	case TK_TEXTURE: case TK_PIGMENT: case TK_FINISH: case TK_INTERIOR: case TK_MATERIAL:
		object_material_block(E, s, o, n);
		return;
	case TK_NO_SHADOW: o->flags |= OF_NO_SHADOW; return;
	case TK_NO_IMAGE: o->flags |= OF_NO_IMAGE; return;
	case TK_NO_REFLECTION: o->flags |= OF_NO_REFLECTION; return;
	case TK_DOUBLE_ILLUMINATE: o->flags |= OF_DOUBLE_ILLUM; return;
	case TK_INVERSE: o->flags ^= OF_INVERSE; return;
	case TK_HOLLOW:
		if (arg_bool(E, n))
			o->flags |= OF_HOLLOW;
		else
			o->flags &= ~(unsigned)OF_HOLLOW;
		return;
	case TK_OPEN:
		if (o->kind != OBJ_CYLINDER && o->kind != OBJ_CONE)
			misplaced(E, s, n);
		o->flags |= OF_OPEN;
		return;
	case TK_STURM:
		if (o->kind != OBJ_TORUS)
			misplaced(E, s, n);
		arg_bool(E, n);
		o->flags |= OF_STURM;
		return;
	case TK_PHOTONS: {
		struct sink sub;
		o->has_photons = true;
		o->photons = (struct photon_spec){.spacing = 1, .collect = true};
		sink_init(&sub, SK_PHOTONS, TK_OBJECT, n->loc, &o->photons);
		eval_items(E, n, &sub);
		return;
	}
	case TK_ILLUM_MAP: {
		struct sink sub;
		run_block(E, n, SK_ILLUM_MAP, &o->illum, &sub);
		if (o->illum.resolution && o->illum.cell)
			eval_fail(E, n->loc, "illum_map takes 'resolution' or 'cell', not both");
		return;
	}
	default:
		if (is_object_kw(n->op) && n->kind == N_BLOCK) {
			if (o->kind < OBJ_UNION)
				eval_fail(E, n->loc, "%s cannot contain other objects; use union { } to group them", tok_name(s->kw));
			csg_add(E, o, eval_block(E, n).p.obj);
			return;
		}
		misplaced(E, s, n);
	}
}

static void object_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc)
{
	if (s->kw == TK_OBJECT && !s->target) {
		if (v->kind != V_OBJECT)
			eval_fail(E, loc, "expected a declared object in 'object', found %s", val_type_name(v));
		s->target = object_copy(E, v->p.obj);
		return;
	}
	struct object *o = object_target(E, s, loc);
	if (o->kind >= OBJ_UNION || s->kw == TK_OBJECT) {
		if (v->kind == V_OBJECT)
			eval_fail(E, loc, "use object { Name } to place a declared object");
		eval_fail(E, loc, "unexpected %s in %s", val_type_name(v), tok_name(s->kw));
	}
	if (s->modified)
		eval_fail(E, loc, "%s parameters must come before its modifiers", tok_name(s->kw));
	if (v->kind != V_FLOAT && v->kind != V_VECTOR)
		eval_fail(E, loc, "expected a float or vector parameter in %s, found %s", tok_name(s->kw), val_type_name(v));
	if (s->nparams >= SINK_MAX_PARAMS)
		eval_fail(E, loc, "too many parameters in %s", tok_name(s->kw));
	s->ploc[s->nparams] = loc;
	s->params[s->nparams++] = *v;
}

/* Checks a primitive's parameter list against its signature. */
static void want_params(struct eval *E, struct sink *s, const char *sig, int min, int max)
{
	if (s->nparams < min || s->nparams > max)
		eval_fail(E, s->nparams > max ? s->ploc[max] : s->loc, "%s expects %s, found %d value%s", tok_name(s->kw), sig,
		          s->nparams, s->nparams == 1 ? "" : "s");
}

#define PV(i) val_want_vec3(E, &s->params[i], s->ploc[i])
#define PF(i) val_want_float(E, &s->params[i], s->ploc[i])

static double positive_param(struct eval *E, struct sink *s, int i, const char *what)
{
	double f = PF(i);
	if (!(f > 0))
		eval_fail(E, s->ploc[i], "%s must be positive, found %g", what, f);
	return f;
}

/* Turns the collected parameters into the primitive's geometry. */
static void object_geometry(struct eval *E, struct sink *s, struct object *o)
{
	switch (o->kind) {
	case OBJ_SPHERE:
		want_params(E, s, "a centre and a radius: sphere { <x,y,z>, r }", 2, 2);
		o->g.sphere.c = PV(0);
		o->g.sphere.r = positive_param(E, s, 1, "sphere radius");
		break;
	case OBJ_PLANE: {
		want_params(E, s, "a normal and a distance: plane { <nx,ny,nz>, d }", 2, 2);
		struct vec3 n = PV(0);
		if (v_len(n) == 0)
			eval_fail(E, s->ploc[0], "plane normal has zero length");
		o->g.plane.n = v_norm(n);
		o->g.plane.d = PF(1);
		break;
	}
	case OBJ_BOX:
		want_params(E, s, "two corners: box { <x1,y1,z1>, <x2,y2,z2> }", 2, 2);
		o->g.box.lo = v_min(PV(0), PV(1));
		o->g.box.hi = v_max(PV(0), PV(1));
		/* a flat box has no inside and faces of no area (its map's nodes) */
		for (int k = 0; k < 3; k++)
			if (!(v_comp(o->g.box.hi, k) > v_comp(o->g.box.lo, k)))
				eval_fail(E, s->ploc[1], "box has zero volume (both corners have %c = %g)", "xyz"[k],
				          v_comp(o->g.box.lo, k));
		break;
	case OBJ_DISC:
		want_params(E, s, "a centre, a normal and a radius: disc { <c>, <n>, r [, hole] }", 3, 4);
		o->g.disc.c = PV(0);
		if (v_len(PV(1)) == 0)
			eval_fail(E, s->ploc[1], "disc normal has zero length");
		o->g.disc.n = v_norm(PV(1));
		o->g.disc.r = positive_param(E, s, 2, "disc radius");
		o->g.disc.hole = s->nparams > 3 ? PF(3) : 0;
		if (o->g.disc.hole < 0 || o->g.disc.hole >= o->g.disc.r)
			eval_fail(E, s->ploc[3], "disc hole radius must be 0 to less than the radius");
		break;
	case OBJ_CYLINDER:
		want_params(E, s, "two end points and a radius: cylinder { <a>, <b>, r }", 3, 3);
		o->g.cylinder.a = PV(0);
		o->g.cylinder.b = PV(1);
		if (v_len(v_sub(PV(1), PV(0))) == 0)
			eval_fail(E, s->ploc[1], "cylinder end points coincide");
		o->g.cylinder.r = positive_param(E, s, 2, "cylinder radius");
		break;
	case OBJ_CONE:
		want_params(E, s, "two end points with radii: cone { <a>, ra, <b>, rb }", 4, 4);
		o->g.cone.a = PV(0);
		o->g.cone.ra = PF(1);
		o->g.cone.b = PV(2);
		o->g.cone.rb = PF(3);
		if (v_len(v_sub(o->g.cone.b, o->g.cone.a)) == 0)
			eval_fail(E, s->ploc[2], "cone end points coincide");
		if (o->g.cone.ra < 0 || o->g.cone.rb < 0 || (o->g.cone.ra == 0 && o->g.cone.rb == 0))
			eval_fail(E, s->ploc[1], "cone radii must not be negative, and not both zero");
		break;
	case OBJ_TORUS:
		want_params(E, s, "two radii: torus { major, minor }", 2, 2);
		o->g.torus.major = positive_param(E, s, 0, "torus major radius");
		o->g.torus.minor = positive_param(E, s, 1, "torus minor radius");
		break;
	case OBJ_TRIANGLE:
		want_params(E, s, "three corners: triangle { <a>, <b>, <c> }", 3, 3);
		for (int i = 0; i < 3; i++)
			o->g.triangle.p[i] = PV(i);
		if (v_len(v_cross(v_sub(PV(1), PV(0)), v_sub(PV(2), PV(0)))) == 0)
			eval_fail(E, s->loc, "degenerate triangle (its corners are collinear)");
		break;
	default:
		if (o->g.csg.n == 0)
			eval_fail(E, s->loc, "%s needs at least one object", tok_name(s->kw));
		break;
	}
}

static struct value object_block(struct eval *E, const struct node *blk)
{
	struct sink s;
	struct object *o = NULL;
	if (blk->op != TK_OBJECT) {
		o = NEW(E, struct object);
		o->kind = object_kind_of(blk->op);
		o->loc = blk->loc;
		o->xf = xf_identity();
	}
	sink_init(&s, SK_OBJECT, blk->op, blk->loc, o);
	eval_items(E, blk, &s);
	o = object_target(E, &s, blk->loc);
	if (blk->op != TK_OBJECT) {
		/* geometry is fixed when the block ends; transforms composed already */
		object_geometry(E, &s, o);
	}
	struct value v = {.kind = V_OBJECT};
	v.p.obj = o;
	return v;
}

/* ==== lights and camera =================================================== */

static void light_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct light *l = s->target;
	struct xform X;
	s->modified = 1;
	if (transform_of(E, n, &X)) {
		light_transform(l, &X);
		return;
	}
	switch (n->op) {
	case TK_SPOTLIGHT: l->kind = LIGHT_SPOT; return;
	case TK_PARALLEL: l->kind = LIGHT_PARALLEL; l->point_at = v3(0, 0, 0); return;
	case TK_RADIUS: l->radius = arg_float(E, n); return;
	case TK_FALLOFF: l->falloff = arg_float(E, n); return;
	case TK_TIGHTNESS: l->tightness = arg_float(E, n); return;
	case TK_POINT_AT: l->point_at = arg_vec3(E, n); return;
	case TK_AREA_LIGHT:
		if (n->nkids != 4)
			eval_fail(E, n->loc, "area_light needs <axis1>, <axis2>, size1, size2");
		l->area = true;
		l->axis1 = eval_vec3(E, n->kids[0]);
		l->axis2 = eval_vec3(E, n->kids[1]);
		l->size1 = (int)eval_float(E, n->kids[2]);
		l->size2 = (int)eval_float(E, n->kids[3]);
		if (l->size1 < 1 || l->size2 < 1 || l->size1 > 1024 || l->size2 > 1024)
			eval_fail(E, n->kids[2]->loc, "area_light sizes must be 1 to 1024");
		return;
	case TK_ADAPTIVE: l->adaptive = arg_int(E, n, 0, 16); return;
	case TK_JITTER: l->jitter = arg_bool(E, n); return;
	case TK_CIRCULAR: l->circular = true; return;
	case TK_ORIENT: l->orient = true; return;
	case TK_FADE_DISTANCE: l->fade_distance = arg_float(E, n); return;
	case TK_FADE_POWER: l->fade_power = arg_float(E, n); return;
	case TK_SHADOWLESS: l->shadowless = true; return;
	case TK_PHOTONS: {
		struct sink sub;
		sink_init(&sub, SK_PHOTONS, TK_LIGHT_SOURCE, n->loc, l);
		eval_items(E, n, &sub);
		return;
	}
	default: misplaced(E, s, n);
	}
}

static void light_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc)
{
	struct light *l = s->target;
	if (v->kind == V_LIGHT && s->nparams == 0 && !s->modified) {
		*l = *v->p.light;
		s->nparams = 2; /* a declared light has both */
		return;
	}
	if (s->modified)
		eval_fail(E, loc, "light_source position and colour must come before its modifiers");
	if (s->nparams == 0) {
		l->pos = val_want_vec3(E, v, loc);
	} else if (s->nparams == 1) {
		l->colour = val_want_colour(E, v, loc);
	} else {
		eval_fail(E, loc, "light_source takes a position and a colour, found a third value");
	}
	s->nparams++;
}

/* POV-Ray's look_at: re-aims direction, right and up, keeping their lengths. */
static void camera_look_at(struct eval *E, struct camera *c, struct vec3 at, struct srcloc loc)
{
	double dl = v_len(c->direction), ul = v_len(c->up), rl = v_len(c->right);
	double hand = v_dot(v_cross(c->up, c->direction), c->right);
	c->look_at = at;
	struct vec3 d = v_sub(at, c->location);
	if (v_len(d) < 1e-12)
		eval_fail(E, loc, "camera location and look_at must differ");
	d = v_norm(d);
	struct vec3 r = v_cross(c->sky, d);
	if (v_len(r) < 1e-12)
		eval_fail(E, loc, "camera looks along its sky vector; set sky to something else");
	r = v_norm(r);
	c->up = v_scale(v_norm(v_cross(d, r)), ul);
	c->direction = v_scale(d, dl);
	c->right = v_scale(r, hand > 0 ? rl : -rl);
}

enum { CAM_LOOK_AT = 1, CAM_ANGLE = 2, CAM_XF = 4 };

/* As POV-Ray does, angle and look_at take effect once every vector of the
 * block is known, and the block's transforms after them, whatever the order
 * of the items. */
static void camera_finish(struct eval *E, struct sink *s, struct camera *c)
{
	if ((s->pending & CAM_ANGLE) && c->kind == CAM_PERSPECTIVE)
		c->direction = v_scale(v_norm(c->direction), v_len(c->right) / tan(c->angle * M_PI / 360) / 2);
	if (s->pending & CAM_LOOK_AT)
		camera_look_at(E, c, c->look_at, s->ploc[0]);
	if (s->pending & CAM_XF)
		camera_transform(c, &s->pending_xf);
}

static void camera_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct camera *c = s->target;
	struct xform X;
	if (transform_of(E, n, &X)) {
		s->pending_xf = s->pending & CAM_XF ? xf_then(s->pending_xf, X) : X;
		s->pending |= CAM_XF;
		return;
	}
	switch (n->op) {
	case TK_PERSPECTIVE: c->kind = CAM_PERSPECTIVE; return;
	case TK_ORTHOGRAPHIC: c->kind = CAM_ORTHOGRAPHIC; return;
	case TK_LOCATION: c->location = arg_vec3(E, n); return;
	case TK_DIRECTION: c->direction = arg_vec3(E, n); return;
	case TK_UP: c->up = arg_vec3(E, n); return;
	case TK_RIGHT: c->right = arg_vec3(E, n); return;
	case TK_SKY: c->sky = arg_vec3(E, n); return;
	case TK_LOOK_AT:
		c->look_at = arg_vec3(E, n);
		s->ploc[0] = n->loc; /* for its error */
		s->pending |= CAM_LOOK_AT;
		return;
	case TK_ANGLE: {
		double a = arg_float(E, n);
		if (a <= 0 || (c->kind == CAM_PERSPECTIVE && a >= 180))
			eval_fail(E, n->kids[0]->loc, "camera angle must be between 0 and 180 degrees, found %g", a);
		c->angle = a;
		s->pending |= CAM_ANGLE;
		return;
	}
	case TK_APERTURE: c->aperture = arg_float(E, n); return;
	case TK_FOCAL_POINT: c->focal_point = arg_vec3(E, n); return;
	case TK_BLUR_SAMPLES: c->blur_samples = arg_int(E, n, 1, 65536); return;
	case TK_CONFIDENCE: case TK_VARIANCE: arg_float(E, n); return;
	default: misplaced(E, s, n);
	}
}

/* ==== global settings ===================================================== */

static void global_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct global_settings *g = &SC(E)->gs;
	struct sink sub;
	switch (n->op) {
	case TK_ASSUMED_GAMMA: g->assumed_gamma = arg_positive(E, n); return;
	case TK_MAX_TRACE_LEVEL: g->max_trace_level = arg_int(E, n, 1, 256); return;
	case TK_ADC_BAILOUT: g->adc_bailout = arg_float(E, n); return;
	case TK_AMBIENT_LIGHT: g->ambient_light = arg_colour(E, n); return;
	case TK_PHOTONS:
		g->illum.given = true;
		sink_init(&sub, SK_PHOTONS, TK_GLOBAL_SETTINGS, n->loc, &g->illum);
		eval_items(E, n, &sub);
		return;
	case TK_ILLUMINATION:
		g->illum.given = true;
		run_block(E, n, SK_ILLUM, &g->illum, &sub);
		return;
	default: misplaced(E, s, n);
	}
}

static void illum_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct illum_settings *il = s->target;
	switch (n->op) {
	case TK_RAYS: {
		double r = arg_float(E, n);
		if (!(r >= 1 && r <= 1e12))
			eval_fail(E, n->kids[0]->loc, "rays must be 1 to 1e12, found %g", r);
		il->rays = (long)r;
		return;
	}
	case TK_MAX_DEPTH: il->max_depth = arg_int(E, n, 1, 256); return;
	case TK_TOLERANCE: {
		double t = arg_float(E, n);
		if (!(t >= 1e-5 && t <= 0.5))
			eval_fail(E, n->kids[0]->loc, "tolerance must be 1e-5 to 0.5, found %g", t);
		il->tolerance = t;
		return;
	}
	case TK_METHOD:
		il->method_set = true;
		if (strcmp(n->str, "point") == 0)
			il->method = ILLUM_POINT;
		else if (strcmp(n->str, "shaft") == 0)
			il->method = ILLUM_SHAFT;
		else
			eval_fail(E, n->loc, "method must be 'point' or 'shaft', found '%s'", n->str);
		return;
	case TK_PASSES:
		if (strcmp(n->str, "rgb") == 0)
			il->passes = PASSES_RGB;
		else if (strcmp(n->str, "spectral") == 0)
			il->passes = PASSES_SPECTRAL;
		else
			eval_fail(E, n->loc, "passes must be 'rgb' or 'spectral', found '%s'", n->str);
		return;
	default: misplaced(E, s, n);
	}
}

static void illum_map_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct illum_spec *m = s->target;
	switch (n->op) {
	case TK_RESOLUTION: m->resolution = arg_int(E, n, 2, 65536); return;
	case TK_CELL: m->cell = arg_positive(E, n); return;
	default: misplaced(E, s, n);
	}
}

static void propagate(struct object *o, struct texture *tex, struct interior *in, unsigned flags,
                      const struct object *parent);

/* ==== value blocks ======================================================== */

struct value eval_block(struct eval *E, const struct node *blk)
{
	struct value v = {.kind = V_NONE};
	struct sink s;
	if (blk->kind == N_SKIPPED) {
		v.kind = V_SKIPPED;
		return v;
	}
	if (is_object_kw(blk->op))
		return object_block(E, blk);
	switch (blk->op) {
	case TK_TEXTURE:
		v.kind = V_TEXTURE;
		v.p.tex = texture_copy(E, NULL);
		v.p.tex->loc = blk->loc;
		run_block(E, blk, SK_TEXTURE, v.p.tex, &s);
		return v;
	case TK_PIGMENT:
		v.kind = V_PIGMENT;
		v.p.pig = NEW(E, struct pigment);
		*v.p.pig = scene_default_texture().pigment;
		run_block(E, blk, SK_PIGMENT, v.p.pig, &s);
		return v;
	case TK_FINISH:
		v.kind = V_FINISH;
		v.p.fin = NEW(E, struct finish);
		*v.p.fin = scene_default_texture().finish;
		run_block(E, blk, SK_FINISH, v.p.fin, &s);
		return v;
	case TK_INTERIOR:
		v.kind = V_INTERIOR;
		v.p.in = NEW(E, struct interior);
		*v.p.in = scene_default_interior();
		run_block(E, blk, SK_INTERIOR, v.p.in, &s);
		return v;
	case TK_MATERIAL:
		v.kind = V_MATERIAL;
		v.p.mat = NEW(E, struct material);
		run_block(E, blk, SK_MATERIAL, v.p.mat, &s);
		return v;
	case TK_LIGHT_SOURCE:
		v.kind = V_LIGHT;
		v.p.light = NEW(E, struct light);
		*v.p.light = scene_default_light();
		v.p.light->loc = blk->loc;
		run_block(E, blk, SK_LIGHT, v.p.light, &s);
		if (s.nparams < 2)
			eval_fail(E, blk->loc, "light_source needs a position and a colour: light_source { <x,y,z>, rgb 1 }");
		return v;
	case TK_CAMERA:
		v.kind = V_CAMERA;
		v.p.cam = NEW(E, struct camera);
		*v.p.cam = scene_default_camera();
		v.p.cam->loc = blk->loc;
		run_block(E, blk, SK_CAMERA, v.p.cam, &s);
		camera_finish(E, &s, v.p.cam);
		return v;
	case TK_TRANSFORM:
		v.kind = V_TRANSFORM;
		v.p.xf = NEW(E, struct xform);
		if (blk->kind == N_MOD) {
			struct value t = arg1(E, blk);
			if (t.kind != V_TRANSFORM)
				eval_fail(E, blk->kids[0]->loc, "expected a transform, found %s", val_type_name(&t));
			*v.p.xf = *t.p.xf;
			return v;
		}
		*v.p.xf = xf_identity();
		run_block(E, blk, SK_TRANSFORM, v.p.xf, &s);
		return v;
	case TK_COLOR_MAP: case TK_COLOUR_MAP:
		v.kind = V_COLOUR_MAP;
		v.p.cmap = colour_map_block(E, blk);
		return v;
	default:
		eval_fail(E, blk->loc, "%s cannot be used as a value", tok_name(blk->op));
	}
}

/* ==== dispatch ============================================================ */

static void texture_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct texture *t = s->target;
	struct xform X;
	struct sink sub;
	s->modified = 1;
	if (transform_of(E, n, &X)) {
		t->pigment.xf = xf_then(t->pigment.xf, X);
		return;
	}
	if (n->op == TK_PIGMENT)
		run_block(E, n, SK_PIGMENT, &t->pigment, &sub);
	else if (n->op == TK_FINISH)
		run_block(E, n, SK_FINISH, &t->finish, &sub);
	else
		misplaced(E, s, n);
}

static void scene_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct scene *sc = SC(E);
	struct sink sub;
	if (is_object_kw(n->op) && n->kind == N_BLOCK) {
		struct object *o = eval_block(E, n).p.obj;
		/* the #default in force now is the one this object gets */
		if (!E->default_shared)
			E->default_shared = texture_copy(E, &E->default_tex);
		propagate(o, E->default_shared, NULL, 0, NULL);
		scene_add_object(sc, o);
		return;
	}
	switch (n->op) {
	case TK_LIGHT_SOURCE: scene_add_light(sc, eval_block(E, n).p.light); return;
	case TK_CAMERA:
		sc->camera = *eval_block(E, n).p.cam;
		sc->has_camera = true;
		return;
	case TK_BACKGROUND:
		run_block(E, n, SK_BACKGROUND, sc, &sub);
		if (sub.nparams != 1)
			eval_fail(E, n->loc, "background needs one colour: background { rgb <r,g,b> }");
		sc->background = val_want_colour(E, &sub.params[0], sub.ploc[0]);
		return;
	case TK_GLOBAL_SETTINGS: run_block(E, n, SK_GLOBAL, sc, &sub); return;
	default: misplaced(E, s, n);
	}
}

static void default_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct sink sub;
	struct texture *t = &E->default_tex;
	E->default_shared = NULL;
	if (n->op == TK_TEXTURE)
		*t = *eval_block(E, n).p.tex;
	else if (n->op == TK_PIGMENT)
		run_block(E, n, SK_PIGMENT, &t->pigment, &sub);
	else if (n->op == TK_FINISH)
		run_block(E, n, SK_FINISH, &t->finish, &sub);
	else
		misplaced(E, s, n);
}

void sink_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	if (n->kind == N_SKIPPED) {
		if (s->kind != SK_OBJECT && s->kind != SK_TEXTURE && s->kind != SK_DEFAULT && s->kind != SK_MATERIAL)
			misplaced(E, s, n);
		if (!E->warned_normal++)
			diag_warning(E->diag, n->loc, "'normal' is not supported yet; ignored");
		return;
	}
	if (n->kind == N_ENTRY) {
		if (s->kind != SK_COLOUR_MAP)
			eval_fail(E, n->loc, "'[' entries are only valid in colour_map");
		colour_map_entry(E, s->target, n);
		return;
	}
	if (n->kind == N_DEFAULT) {
		struct sink sub;
		if (s->kind != SK_SCENE)
			eval_fail(E, n->loc, "'#default' is only valid at the top level");
		sink_init(&sub, SK_DEFAULT, TK_DIR_DEFAULT, n->loc, NULL);
		eval_items(E, n, &sub);
		return;
	}
	struct xform X;
	switch (s->kind) {
	case SK_SCENE: scene_keyword(E, s, n); return;
	case SK_OBJECT: object_keyword(E, s, n); return;
	case SK_TEXTURE: texture_keyword(E, s, n); return;
	case SK_PIGMENT: pigment_keyword(E, s, n); return;
	case SK_FINISH: finish_keyword(E, s, n); return;
	case SK_INTERIOR: interior_keyword(E, s, n); return;
	case SK_REFLECTION: reflection_keyword(E, s, n); return;
	case SK_IMAGE_MAP: image_map_keyword(E, s, n); return;
	case SK_CAMERA: camera_keyword(E, s, n); return;
	case SK_LIGHT: light_keyword(E, s, n); return;
	case SK_GLOBAL: global_keyword(E, s, n); return;
	case SK_PHOTONS: photons_keyword(E, s, n); return;
	case SK_ILLUM: illum_keyword(E, s, n); return;
	case SK_ILLUM_MAP: illum_map_keyword(E, s, n); return;
	case SK_DEFAULT: default_keyword(E, s, n); return;
	case SK_TRANSFORM:
		if (n->op == TK_INVERSE) {
			*(struct xform *)s->target = xf_inverse(*(struct xform *)s->target);
			return;
		}
		if (!transform_of(E, n, &X))
			misplaced(E, s, n);
		*(struct xform *)s->target = xf_then(*(struct xform *)s->target, X);
		return;
	case SK_MATERIAL: {
		struct material *m = s->target;
		if (transform_of(E, n, &X)) {
			if (m->tex) {
				m->tex = texture_copy(E, m->tex);
				m->tex->pigment.xf = xf_then(m->tex->pigment.xf, X);
			}
			return;
		}
		if (n->op == TK_TEXTURE)
			m->tex = eval_block(E, n).p.tex;
		else if (n->op == TK_INTERIOR)
			m->interior = eval_block(E, n).p.in;
		else
			misplaced(E, s, n);
		return;
	}
	case SK_VALUE: {
		if (n->kind != N_BLOCK && n->op != TK_TRANSFORM)
			misplaced(E, s, n);
		struct value v = eval_block(E, n);
		sink_value(E, s, &v, n->loc);
		return;
	}
	default: misplaced(E, s, n);
	}
}

void sink_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc)
{
	switch (s->kind) {
	case SK_VALUE:
		if (s->nresults++ > 0)
			eval_fail(E, loc, "a macro used as a value must yield one value, this is the second");
		s->result = *v;
		return;
	case SK_OBJECT: object_value(E, s, v, loc); return;
	case SK_PIGMENT: pigment_value(E, s, v, loc); return;
	case SK_LIGHT: light_value(E, s, v, loc); return;
	case SK_ENTRY: case SK_REFLECTION: case SK_BACKGROUND:
		if (s->nparams >= SINK_MAX_PARAMS)
			eval_fail(E, loc, "too many values here");
		s->ploc[s->nparams] = loc;
		s->params[s->nparams++] = *v;
		return;
	case SK_IMAGE_MAP:
		if (v->kind != V_STRING)
			eval_fail(E, loc, "expected an image file name, found %s", val_type_name(v));
		set_image(E, s->target, loc, v->p.s);
		return;
	default: break;
	}
	/* a declared block of the same kind as the block is its base */
	struct {
		enum sink_kind sk;
		enum val_kind vk;
		size_t size;
	} bases[] = {
		{SK_TEXTURE, V_TEXTURE, sizeof(struct texture)}, {SK_FINISH, V_FINISH, sizeof(struct finish)},
		{SK_INTERIOR, V_INTERIOR, sizeof(struct interior)}, {SK_MATERIAL, V_MATERIAL, sizeof(struct material)},
		{SK_CAMERA, V_CAMERA, sizeof(struct camera)}, {SK_TRANSFORM, V_TRANSFORM, sizeof(struct xform)},
	};
	for (size_t i = 0; i < sizeof bases / sizeof bases[0]; i++) {
		if (s->kind == bases[i].sk && v->kind == bases[i].vk) {
			if (s->modified)
				eval_fail(E, loc, "a declared %s must come first in its block", val_type_name(v) + 2);
			memcpy(s->target, v->p.tex, bases[i].size);
			s->modified = 1;
			return;
		}
	}
	if (s->kind == SK_COLOUR_MAP && v->kind == V_COLOUR_MAP) {
		*(struct colour_map *)s->target = *v->p.cmap;
		return;
	}
	if (s->kind == SK_SCENE)
		eval_fail(E, loc, "expected an object, light, camera or directive, found %s", val_type_name(v));
	eval_fail(E, loc, "unexpected %s %s", val_type_name(v), where(s));
}

/* ==== the end of the scene ================================================ */

/* Children without their own texture, interior or photons { } take the
 * parent's; the visibility flags pass down too. */
static void propagate(struct object *o, struct texture *tex, struct interior *in, unsigned flags,
                      const struct object *parent)
{
	const unsigned inherit = OF_NO_SHADOW | OF_NO_IMAGE | OF_NO_REFLECTION | OF_DOUBLE_ILLUM;
	if (!o->tex)
		o->tex = tex;
	if (!o->interior)
		o->interior = in;
	o->flags |= flags & inherit;
	if (parent && parent->has_photons && !o->has_photons) {
		o->photons = parent->photons;
		o->has_photons = true;
	}
	if (o->kind >= OBJ_UNION)
		for (int i = 0; i < o->g.csg.n; i++)
			propagate(o->g.csg.kids[i], o->tex, o->interior, o->flags, o);
}

void objects_finish(struct eval *E)
{
	struct scene *sc = SC(E);
	if (!sc->has_camera)
		sc->camera = scene_default_camera();
}
