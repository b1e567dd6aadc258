/* SPDX-License-Identifier: MIT */
/* objects.c: what each block accepts. A sink stands for the block being
 * evaluated; sink_keyword and sink_value dispatch on its kind to the builders
 * of the scene model (tracer/scene.h): geometry.c (objects), textures.c
 * (pigments, colour maps, finishes, interiors) and settings.c (lights,
 * camera, global settings). This file holds the dispatch, the argument
 * helpers they share, and value blocks. Misplaced or unknown keywords are
 * errors. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

void sink_init(struct sink *s, enum sink_kind kind, enum tok kw, struct srcloc loc, void *target)
{
	memset(s, 0, offsetof(struct sink, params)); /* internal.h: the rest is written before read */
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

_Noreturn void misplaced(struct eval *E, const struct sink *s, const struct node *n)
{
	if (n->op == TK_TURBULENCE || n->op == TK_OCTAVES || n->op == TK_OMEGA || n->op == TK_LAMBDA)
		eval_fail(E, n->loc, "%s is not supported", tok_name(n->op));
	eval_fail(E, n->loc, "%s is not valid %s", tok_name(n->op), where(s));
}

/* The single argument of a keyword item like `translate <1,0,0>`. */
struct value arg1(struct eval *E, const struct node *n)
{
	if (n->nkids != 1)
		eval_fail(E, n->loc, "%s takes one value, found %d", tok_name(n->op), n->nkids);
	return eval_expr(E, n->kids[0]);
}

double arg_float(struct eval *E, const struct node *n)
{
	struct value v = arg1(E, n);
	return val_want_float(E, &v, n->kids[0]->loc);
}

struct vec3 arg_vec3(struct eval *E, const struct node *n)
{
	struct value v = arg1(E, n);
	return val_want_vec3(E, &v, n->kids[0]->loc);
}

struct colour arg_colour(struct eval *E, const struct node *n)
{
	struct value v = arg1(E, n);
	return val_want_colour(E, &v, n->kids[0]->loc);
}

/* An optional on/off argument (`fresnel`, `fresnel on`, `hollow off`). */
bool arg_bool(struct eval *E, const struct node *n)
{
	return n->nkids == 0 ? true : arg_float(E, n) != 0;
}

double arg_positive(struct eval *E, const struct node *n)
{
	double f = arg_float(E, n);
	if (!(f > 0))
		eval_fail(E, n->kids[0]->loc, "%s must be positive, found %g", tok_name(n->op), f);
	return f;
}

int arg_int(struct eval *E, const struct node *n, int lo, int hi)
{
	double f = arg_float(E, n);
	if (!(f >= lo && f <= hi))
		eval_fail(E, n->kids[0]->loc, "%s must be %d to %d, found %g", tok_name(n->op), lo, hi, f);
	return (int)f;
}

static bool transform_kind(struct eval *E, const struct node *n, struct xform *out);

/* A transform whose matrix or inverse is not finite (translate 1e308 twice,
 * scale 1e-200 twice) is an error at loc: no infinity reaches the scene. */
static const struct xform *xform_finite(struct eval *E, const struct xform *x, struct srcloc loc)
{
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 4; j++)
			if (!isfinite(x->m[i][j]) || !isfinite(x->inv[i][j]))
				eval_fail(E, loc, "the transform is not finite (it overflows, or is nearly singular)");
	return x;
}

/* translate/rotate/scale/matrix/transform: computes the transform of item n;
 * false when n is not a transform keyword. */
bool transform_of(struct eval *E, const struct node *n, struct xform *out)
{
	if (!transform_kind(E, n, out))
		return false;
	xform_finite(E, out, n->loc);
	return true;
}

static bool transform_kind(struct eval *E, const struct node *n, struct xform *out)
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

struct texture *texture_copy(struct eval *E, const struct texture *t)
{
	struct texture *c = NEW(E, struct texture);
	*c = t ? *t : E->default_tex;
	return c;
}

static bool ext_equal(const struct tex_ext *a, const struct tex_ext *b)
{
	return a->finish == b->finish && a->normal == b->normal && a->map == b->map && a->below == b->below &&
	       a->nmap == b->nmap && a->loc.file == b->loc.file && a->loc.line == b->loc.line && a->loc.col == b->loc.col;
}

void tex_ext_set(struct eval *E, struct texture *t, const struct tex_ext *x)
{
	if (ext_equal(x, &tex_ext_none)) {
		t->ext = NULL;
		return;
	}
	for (int i = 1; i <= EXT_SEEN; i++) { /* the latest first */
		const struct tex_ext *r = E->ext_seen[(E->ext_next + EXT_SEEN - i) % EXT_SEEN];
		if (!r)
			break;
		if (ext_equal(r, x)) {
			t->ext = r;
			return;
		}
	}
	struct tex_ext *c = NEW(E, struct tex_ext);
	*c = *x;
	E->ext_seen[E->ext_next] = t->ext = c;
	E->ext_next = (E->ext_next + 1) % EXT_SEEN;
}

void tex_set_loc(struct eval *E, struct texture *t, struct srcloc loc)
{
	struct tex_ext x = *tex_x(t);
	x.loc = loc;
	tex_ext_set(E, t, &x);
}

void tex_set_finish(struct eval *E, struct texture *t, const struct finish *f)
{
	struct tex_ext x = *tex_x(t);
	x.finish = f;
	tex_ext_set(E, t, &x);
}

void tex_set_normal(struct eval *E, struct texture *t, const struct tnormal *n)
{
	struct tex_ext x = *tex_x(t);
	x.normal = n;
	tex_ext_set(E, t, &x);
}

void tex_set_below(struct eval *E, struct texture *t, const struct texture *below)
{
	struct tex_ext x = *tex_x(t);
	x.below = below;
	tex_ext_set(E, t, &x);
}

void tex_set_map(struct eval *E, struct texture *t, const struct tex_entry *map, int nmap)
{
	struct tex_ext x = *tex_x(t);
	x.map = map;
	x.nmap = nmap;
	tex_ext_set(E, t, &x);
}

/* The fields of a texture as words, bit for bit (padding left out), for
 * sharing. */
#define TEX_WORDS 14

static void tex_key(const struct texture *t, uint64_t k[TEX_WORDS])
{
	const struct colour *c = &t->pigment.c[0];
	const double d[5] = {c->r, c->g, c->b, c->f, c->t};
	memcpy(k, d, sizeof d);
	k[5] = (uint64_t)t->pigment.kind;
	k[6] = (uint64_t)(uintptr_t)t->pigment.pat;
	k[7] = (uint64_t)(uintptr_t)t->pigment.xf;
	const struct tex_ext *x = tex_x(t); /* by content: equal records may be two */
	k[8] = (uint64_t)(uintptr_t)x->normal;
	k[9] = (uint64_t)(uintptr_t)x->finish;
	k[10] = (uint64_t)(uintptr_t)x->map;
	k[11] = (uint64_t)(uintptr_t)x->below;
	k[12] = (uint64_t)(uint32_t)x->loc.file << 32 | (uint32_t)x->loc.line;
	k[13] = (uint64_t)(uint32_t)x->loc.col << 32 | (uint32_t)x->nmap;
}

/* A loop that makes the same texture over and over (a colour of a few, a
 * declared finish) stores it once: up to TEX_SEEN recent textures are
 * looked up by content. Deterministic: it depends on the order of
 * evaluation only. */
struct texture *texture_share(struct eval *E, const struct texture *t)
{
	uint64_t k[TEX_WORDS], h = 0;
	tex_key(t, k);
	for (int i = 0; i < TEX_WORDS; i++)
		h = (h ^ k[i]) * 0x9e3779b97f4a7c15u;
	h ^= h >> 32;
	/* up to 8 slots from the hash's: a match, else the first free one,
	 * else the first of them is given to t */
	size_t at = h % TEX_SEEN;
	for (int i = 0; i < 8; i++) {
		size_t j = (h + (uint64_t)i) % TEX_SEEN;
		if (!E->tex_seen[j]) {
			at = j;
			break;
		}
		uint64_t s[TEX_WORDS];
		if (E->tex_hash[j] != h)
			continue;
		tex_key(E->tex_seen[j], s);
		if (memcmp(s, k, sizeof k) == 0)
			return (struct texture *)E->tex_seen[j];
	}
	struct texture *c = arena_alloc8(&SC(E)->arena, sizeof *c); /* beside 8-aligned objects: no gap */
	*c = *t;
	E->tex_seen[at] = c;
	E->tex_hash[at] = h;
	return c;
}

void texture_transform(struct eval *E, struct texture *t, const struct xform *X)
{
	t->pigment.xf = xform_then(E, t->pigment.xf, X);
	if (!t->ext)
		return;
	struct tex_ext x = *t->ext;
	if (x.below) { /* and the layers under it */
		struct texture *b = texture_copy(E, x.below);
		texture_transform(E, b, X);
		x.below = b;
	}
	if (x.map) { /* a texture_map's textures move with it */
		struct tex_entry *m = ARENA_ARRAY(&SC(E)->arena, struct tex_entry, x.nmap);
		for (int i = 0; i < x.nmap; i++) {
			struct texture *c = texture_copy(E, x.map[i].tex);
			texture_transform(E, c, X);
			m[i] = (struct tex_entry){x.map[i].pos, c};
		}
		x.map = m;
	}
	if (x.normal) {
		struct tnormal *nr = NEW(E, struct tnormal);
		*nr = *x.normal;
		nr->pat.xf = xform_then(E, nr->pat.xf, X);
		x.normal = nr;
	}
	tex_ext_set(E, t, &x);
}

const struct xform *xform_then(struct eval *E, const struct xform *old, const struct xform *X)
{
	struct xform *x = NEW(E, struct xform);
	*x = xf_then(old ? *old : xf_ident, *X);
	xform_finite(E, x, E->stmt);
	return xf_is_identity(x) ? NULL : x;
}

const struct finish *finish_block(struct eval *E, const struct node *n, const struct finish *f)
{
	struct sink sub;
	struct finish c = *f;
	run_block(E, n, SK_FINISH, &c, &sub);
	if (E->last_finish && memcmp(E->last_finish, &c, sizeof c) == 0)
		return E->last_finish; /* a loop writing the same finish shares one */
	struct finish *k = NEW(E, struct finish);
	*k = c;
	return E->last_finish = k;
}

/* Evaluates a block's items into a fresh sink of the given kind. */
void run_block(struct eval *E, const struct node *blk, enum sink_kind kind, void *target, struct sink *out)
{
	sink_init(out, kind, blk->op, blk->loc, target);
	eval_items(E, blk, out);
}

/* POV-Ray's layered texture: top over bottom, as a fresh texture. */
struct texture *texture_layered(struct eval *E, const struct texture *bottom, const struct texture *top)
{
	struct texture *t = texture_copy(E, bottom);
	texture_layer(E, t, top);
	return t;
}

struct value eval_block(struct eval *E, const struct node *blk)
{
	struct value v = {.kind = V_NONE};
	struct sink s;
	if (blk->kind == N_SKIPPED || blk->op == TK_NORMAL) {
		v.kind = V_SKIPPED;
		v.p.nrm = blk->kind == N_SKIPPED ? NULL : normal_block(E, blk);
		return v;
	}
	bool object = is_object_kw(blk->op);
	if (object || blk->op == TK_LIGHT_SOURCE)
		eval_count_object(E, blk->loc);
	if (object)
		return object_block(E, blk);
	switch (blk->op) {
	case TK_TEXTURE:
		v.kind = V_TEXTURE;
		v.p.tex = texture_copy(E, NULL);
		tex_set_loc(E, v.p.tex, blk->loc);
		run_block(E, blk, SK_TEXTURE, v.p.tex, &s);
		if (blk->c) /* texture { A } texture { B }: B layered over A */
			v.p.tex = texture_layered(E, v.p.tex, eval_block(E, blk->c).p.tex);
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
		*v.p.fin = *tex_ext_none.finish;
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
	case TK_SKY_SPHERE: { /* #declare S = sky_sphere { … } (skies.inc): built aside */
		struct scene *sc = SC(E);
		struct pigment *sky0 = sc->sky;
		int n0 = sc->nsky;
		const struct xform *xf0 = sc->sky_xf;
		sc->sky = NULL, sc->nsky = 0, sc->sky_xf = NULL;
		run_block(E, blk, SK_SKY, sc, &s);
		struct sky_value *sv = NEW(E, struct sky_value);
		*sv = (struct sky_value){sc->sky, sc->nsky, sc->sky_xf};
		sc->sky = sky0, sc->nsky = n0, sc->sky_xf = xf0;
		v.kind = V_SKY;
		v.p.sky = sv;
		return v;
	}
	default:
		eval_fail(E, blk->loc, "%s cannot be used as a value", tok_name(blk->op));
	}
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
		propagate(E, o, E->default_shared);
		scene_add_object(sc, o);
		return;
	}
	switch (n->op) {
	case TK_LIGHT_SOURCE: {
		struct light *l = eval_block(E, n).p.light;
		scene_add_light(sc, l);
		if (l->looks_like) { /* the object, moved to the light, casts no shadow */
			struct object *o = obj_copy(&SC(E)->arena, l->looks_like);
			struct xform X = xf_translate(l->pos);
			object_transform(E, o, &X);
			o->flags |= OF_NO_SHADOW;
			if (!E->default_shared)
				E->default_shared = texture_copy(E, &E->default_tex);
			propagate(E, o, E->default_shared);
			scene_add_object(sc, o);
			eval_count_object(E, n->loc);
		}
		return;
	}
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
	case TK_FOG:
		sc->fog = (struct fog){.type = 1, .up = v3(0, 1, 0)};
		run_block(E, n, SK_FOG, &sc->fog, &sub);
		if (!(sc->fog.distance > 0))
			eval_fail(E, n->loc, "fog needs a positive distance: fog { distance 10 color rgb 0.5 }");
		if (sc->fog.type == 2 && !(sc->fog.alt > 0))
			eval_fail(E, n->loc, "a ground fog (fog_type 2) needs a positive fog_alt");
		return;
	case TK_SKY_SPHERE:
		sc->nsky = 0, sc->sky_xf = NULL; /* a later sky_sphere replaces an earlier one */
		run_block(E, n, SK_SKY, sc, &sub);
		if (sc->nsky == 0)
			eval_fail(E, n->loc, "sky_sphere needs a pigment: sky_sphere { pigment { … } }");
		return;
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
		tex_set_finish(E, t, finish_block(E, n, tex_finish(t)));
	else if (n->op == TK_NORMAL) {
		E->in_default++;
		tex_set_normal(E, t, normal_block(E, n));
		E->in_default--;
	} else {
		misplaced(E, s, n);
	}
}

/* sink_keyword's rarer items, each a function of its own so that
 * sink_keyword itself is a dispatch (it runs for every block in a loop). */
static __attribute__((noinline)) void skipped_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	if (s->kind != SK_OBJECT && s->kind != SK_TEXTURE && s->kind != SK_DEFAULT && s->kind != SK_MATERIAL)
		misplaced(E, s, n);
	if (!E->warned_normal++)
		diag_warning(E->diag, n->loc, "'normal' is not supported yet; ignored");
}

static __attribute__((noinline)) void default_block(struct eval *E, struct sink *s, const struct node *n)
{
	struct sink sub;
	if (s->kind != SK_SCENE)
		eval_fail(E, n->loc, "'#default' is only valid at the top level");
	sink_init(&sub, SK_DEFAULT, TK_DIR_DEFAULT, n->loc, NULL);
	eval_items(E, n, &sub);
}

static __attribute__((noinline)) void transform_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct xform X;
	if (n->op == TK_INVERSE) {
		*(struct xform *)s->target = xf_inverse(*(struct xform *)s->target);
		return;
	}
	if (!transform_of(E, n, &X))
		misplaced(E, s, n);
	*(struct xform *)s->target = xf_then(*(struct xform *)s->target, X);
	xform_finite(E, s->target, n->loc);
}

static __attribute__((noinline)) void material_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct xform X;
	struct material *m = s->target;
	if (transform_of(E, n, &X)) {
		if (m->tex) {
			m->tex = texture_copy(E, m->tex);
			texture_transform(E, m->tex, &X);
		}
		return;
	}
	if (n->op == TK_TEXTURE)
		m->tex = eval_block(E, n).p.tex;
	else if (n->op == TK_INTERIOR)
		m->interior = eval_block(E, n).p.in;
	else
		misplaced(E, s, n);
}

static __attribute__((noinline)) void value_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	if (n->kind != N_BLOCK && n->op != TK_TRANSFORM)
		misplaced(E, s, n);
	struct value v = eval_block(E, n);
	sink_value(E, s, &v, n->loc);
}

void sink_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	if (n->kind == N_SKIPPED) {
		skipped_keyword(E, s, n);
		return;
	}
	if (n->kind == N_ENTRY) {
		if (s->kind != SK_COLOUR_MAP)
			eval_fail(E, n->loc, "'[' entries are only valid in colour_map");
		colour_map_entry(E, s->target, n);
		return;
	}
	if (n->kind == N_DEFAULT) {
		default_block(E, s, n);
		return;
	}
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
	case SK_SKY: sky_keyword(E, s, n); return;
	case SK_NORMAL: normal_keyword(E, s, n); return;
	case SK_FOG: fog_keyword(E, s, n); return;
	case SK_WARP: warp_keyword(E, s, n); return;
	case SK_DEFAULT: default_keyword(E, s, n); return;
	case SK_LIST: list_keyword(E, s, n); return;
	case SK_TRANSFORM: transform_keyword(E, s, n); return;
	case SK_MATERIAL: material_keyword(E, s, n); return;
	case SK_VALUE: value_keyword(E, s, n); return;
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
	case SK_NORMAL: normal_value(E, s, v, loc); return;
	case SK_FOG: fog_value(E, s, v, loc); return;
	case SK_SKY: sky_value(E, s, v, loc); return;
	case SK_LIGHT: light_value(E, s, v, loc); return;
	case SK_LIST: list_value(E, s, v, loc); return;
	case SK_ENTRY: case SK_REFLECTION: case SK_BACKGROUND:
		if (s->nparams >= SINK_MAX_PARAMS)
			eval_fail(E, loc, "too many values here");
		s->ploc[s->nparams] = loc;
		s->params[s->nparams++] = *v;
		return;
	case SK_IMAGE_MAP:
		if (v->kind != V_STRING)
			eval_fail(E, loc, "expected an image file name, found %s", val_type_name(v));
		image_set(E, pat_w(E, s->target), loc, v->p.s);
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

void objects_finish(struct eval *E)
{
	struct scene *sc = SC(E);
	if (!sc->has_camera)
		sc->camera = scene_default_camera();
	patterns_finish(E);
}
