/* SPDX-License-Identifier: MIT */
/* geometry.c: objects. An object block collects its parameters and
 * modifiers; when it ends, the primitive's geom_ function (one per PRIM of
 * tracer/objects.def) checks the parameters and fixes the geometry. */
#include <string.h>

#include "internal.h"

/* Applies X to an object, its texture and its children (POV-Ray moves the
 * texture with the object when the texture came first). */
void object_transform(struct eval *E, struct object *o, const struct xform *X)
{
	o->xf = xform_then(E, o->xf, X);
	if (o->tex) {
		o->tex = texture_copy(E, o->tex);
		texture_transform(E, o->tex, X);
	}
	if (o->kind >= OBJ_FIRST_CSG)
		for (int i = 0; i < o->g.csg.n; i++)
			object_transform(E, o->g.csg.kids[i], X);
}

static struct object *object_copy(struct eval *E, const struct object *o)
{
	eval_count_object(E, E->stmt); /* copies of declared CSGs count too */
	struct object *c = NEW(E, struct object);
	*c = *o;
	if (o->kind >= OBJ_FIRST_CSG) {
		c->g.csg.kids = ARENA_ARRAY(&SC(E)->arena, struct object *, o->g.csg.n);
		for (int i = 0; i < o->g.csg.n; i++)
			c->g.csg.kids[i] = object_copy(E, o->g.csg.kids[i]);
	}
	return c;
}

static enum object_kind object_kind_of(enum tok kw)
{
	switch (kw) {
#define PRIM(n, w) case TK_##n: return OBJ_##n;
#define CSG(n, w) case TK_##n: return OBJ_##n;
#include "../tracer/objects.def"
	default: return OBJ_KIND_COUNT;
	}
}

bool is_object_kw(enum tok kw) { return object_kind_of(kw) != OBJ_KIND_COUNT || kw == TK_OBJECT; }

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
	if (n->op == TK_PIGMENT || n->op == TK_FINISH || n->op == TK_NORMAL) {
		o->tex = texture_copy(E, o->tex);
		if (o->tex->loc.file < 0)
			o->tex->loc = n->loc;
		if (n->op == TK_PIGMENT)
			run_block(E, n, SK_PIGMENT, &o->tex->pigment, &sub);
		else if (n->op == TK_NORMAL)
			o->tex->normal = normal_block(E, n);
		else
			finish_block(E, n, &o->tex->finish);
	} else if (n->op == TK_INTERIOR) {
		struct interior *in = NEW(E, struct interior);
		*in = o->interior ? *o->interior : scene_default_interior();
		run_block(E, n, SK_INTERIOR, in, &sub);
		o->interior = in;
	} else if (n->op == TK_TEXTURE) {
		struct value v = eval_block(E, n);
		if (s->pending & 1) { /* a second texture in the block: a layer on top */
			struct texture *t = texture_copy(E, o->tex);
			texture_layer(E, t, v.p.tex);
			o->tex = t;
		} else {
			o->tex = v.p.tex;
		}
		s->pending |= 1;
	} else {
		struct value v = eval_block(E, n);
		if (v.p.mat->tex)
			o->tex = v.p.mat->tex;
		if (v.p.mat->interior)
			o->interior = v.p.mat->interior;
	}
	(void)s;
}

static void object_geometry(struct eval *E, struct sink *s, struct object *o);

/* object { … clipped_by { A B … } … }: from here on the sink builds a clip
 * node whose first child is the object so far (its geometry fixed now) and
 * whose others are A, B …; later modifiers apply to the whole (csg.c). */
static void clip(struct eval *E, struct sink *s, struct object *o, const struct node *n)
{
	if (s->kw != TK_OBJECT && o->kind < OBJ_FIRST_CSG)
		object_geometry(E, s, o);
	struct object tmp = {.kind = OBJ_UNION, .loc = n->loc};
	struct sink sub;
	sink_init(&sub, SK_OBJECT, TK_UNION, n->loc, &tmp);
	eval_items(E, n, &sub);
	if (tmp.g.csg.n == 0)
		eval_fail(E, n->loc, "clipped_by needs an object: clipped_by { plane { y, 0 } }");
	struct object *c = NEW(E, struct object);
	c->kind = OBJ_CLIP;
	c->loc = o->loc;
	csg_add(E, c, o);
	for (int i = 0; i < tmp.g.csg.n; i++)
		csg_add(E, c, tmp.g.csg.kids[i]);
	s->target = c;
}

void object_keyword(struct eval *E, struct sink *s, const struct node *n)
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
	case TK_TEXTURE: case TK_PIGMENT: case TK_FINISH: case TK_INTERIOR: case TK_MATERIAL: case TK_NORMAL:
		object_material_block(E, s, o, n);
		return;
	case TK_BOUNDED_BY: return; /* POV-Ray's bounding hint: arvo bounds every object itself */
	case TK_CLIPPED_BY: clip(E, s, o, n); return;
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
			if (o->kind < OBJ_FIRST_CSG)
				eval_fail(E, n->loc, "%s cannot contain other objects; use union { } to group them", tok_name(s->kw));
			csg_add(E, o, eval_block(E, n).p.obj);
			return;
		}
		misplaced(E, s, n);
	}
}

void object_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc)
{
	if (s->kw == TK_OBJECT && !s->target) {
		if (v->kind != V_OBJECT)
			eval_fail(E, loc, "expected a declared object in 'object', found %s", val_type_name(v));
		s->target = object_copy(E, v->p.obj);
		return;
	}
	struct object *o = object_target(E, s, loc);
	if (o->kind >= OBJ_FIRST_CSG || s->kw == TK_OBJECT) {
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

static void geom_sphere(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "a centre and a radius: sphere { <x,y,z>, r }", 2, 2);
	o->g.sphere.c = PV(0);
	o->g.sphere.r = positive_param(E, s, 1, "sphere radius");
}

static void geom_plane(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "a normal and a distance: plane { <nx,ny,nz>, d }", 2, 2);
	struct vec3 n = PV(0);
	if (v_len(n) == 0)
		eval_fail(E, s->ploc[0], "plane normal has zero length");
	o->g.plane.n = v_norm(n);
	o->g.plane.d = PF(1);
}

static void geom_box(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "two corners: box { <x1,y1,z1>, <x2,y2,z2> }", 2, 2);
	o->g.box.lo = v_min(PV(0), PV(1));
	o->g.box.hi = v_max(PV(0), PV(1));
	/* a flat box has no inside and faces of no area (its map's nodes) */
	for (int k = 0; k < 3; k++)
		if (!(v_comp(o->g.box.hi, k) > v_comp(o->g.box.lo, k)))
			eval_fail(E, s->ploc[1], "box has zero volume (both corners have %c = %g)", "xyz"[k],
			          v_comp(o->g.box.lo, k));
}

static void geom_disc(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "a centre, a normal and a radius: disc { <c>, <n>, r [, hole] }", 3, 4);
	o->g.disc.c = PV(0);
	if (v_len(PV(1)) == 0)
		eval_fail(E, s->ploc[1], "disc normal has zero length");
	o->g.disc.n = v_norm(PV(1));
	o->g.disc.r = positive_param(E, s, 2, "disc radius");
	o->g.disc.hole = s->nparams > 3 ? PF(3) : 0;
	if (o->g.disc.hole < 0 || o->g.disc.hole >= o->g.disc.r)
		eval_fail(E, s->ploc[3], "disc hole radius must be 0 to less than the radius");
}

static void geom_cylinder(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "two end points and a radius: cylinder { <a>, <b>, r }", 3, 3);
	o->g.cylinder.a = PV(0);
	o->g.cylinder.b = PV(1);
	if (v_len(v_sub(PV(1), PV(0))) == 0)
		eval_fail(E, s->ploc[1], "cylinder end points coincide");
	o->g.cylinder.r = positive_param(E, s, 2, "cylinder radius");
}

static void geom_cone(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "two end points with radii: cone { <a>, ra, <b>, rb }", 4, 4);
	o->g.cone.a = PV(0);
	o->g.cone.ra = PF(1);
	o->g.cone.b = PV(2);
	o->g.cone.rb = PF(3);
	if (v_len(v_sub(o->g.cone.b, o->g.cone.a)) == 0)
		eval_fail(E, s->ploc[2], "cone end points coincide");
	if (o->g.cone.ra < 0 || o->g.cone.rb < 0 || (o->g.cone.ra == 0 && o->g.cone.rb == 0))
		eval_fail(E, s->ploc[1], "cone radii must not be negative, and not both zero");
}

static void geom_torus(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "two radii: torus { major, minor }", 2, 2);
	o->g.torus.major = positive_param(E, s, 0, "torus major radius");
	o->g.torus.minor = positive_param(E, s, 1, "torus minor radius");
}

static void geom_triangle(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "three corners: triangle { <a>, <b>, <c> }", 3, 3);
	for (int i = 0; i < 3; i++)
		o->g.triangle.p[i] = PV(i);
	if (v_len(v_cross(v_sub(PV(1), PV(0)), v_sub(PV(2), PV(0)))) == 0)
		eval_fail(E, s->loc, "degenerate triangle (its corners are collinear)");
}

/* The geometry builder of each primitive, indexed by enum object_kind. */
typedef void geom_fn(struct eval *E, struct sink *s, struct object *o);
static geom_fn *const geom_of[OBJ_KIND_COUNT] = {
#define PRIM(n, w) [OBJ_##n] = geom_##w,
#include "../tracer/objects.def"
};

/* Turns the collected parameters into the primitive's geometry. */
static void object_geometry(struct eval *E, struct sink *s, struct object *o)
{
	if (geom_of[o->kind]) {
		geom_of[o->kind](E, s, o);
		return;
	}
	if (o->g.csg.n == 0)
		eval_fail(E, s->loc, "%s needs at least one object", tok_name(s->kw));
}

struct value object_block(struct eval *E, const struct node *blk)
{
	struct sink s;
	struct object *o = NULL;
	if (blk->op != TK_OBJECT) {
		o = NEW(E, struct object);
		o->kind = object_kind_of(blk->op);
		o->loc = blk->loc;
		o->xf = NULL; /* the identity until a transform comes */
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

/* Children without their own texture, interior or photons { } take the
 * parent's; the visibility flags pass down too. */
void propagate(struct object *o, struct texture *tex, struct interior *in, unsigned flags,
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
	if (o->kind >= OBJ_FIRST_CSG)
		for (int i = 0; i < o->g.csg.n; i++)
			propagate(o->g.csg.kids[i], o->tex, o->interior, o->flags, o);
}
