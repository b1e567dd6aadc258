/* SPDX-License-Identifier: MIT */
/* textures.c: pigments, colour maps, image maps, finishes, interiors and
 * textures, built into the scene model by the sinks of objects.c. */
#include <stdlib.h>
#include <string.h>

#include "internal.h"

struct colour_map *colour_map_block(struct eval *E, const struct node *blk)
{
	struct colour_map *m = NEW(E, struct colour_map);
	struct sink s;
	run_block(E, blk, SK_COLOUR_MAP, m, &s);
	if (m->n == 0)
		eval_fail(E, blk->loc, "colour_map needs at least one entry [position colour]");
	return m;
}

static void colour_map_push(struct eval *E, struct colour_map *m, const struct node *n, struct sink *sk, int ip, int ic);

/* [position colour] of a colour_map. */
void colour_map_entry(struct eval *E, struct colour_map *m, const struct node *n)
{
	struct sink s;
	sink_init(&s, SK_ENTRY, TK_COLOR_MAP, n->loc, NULL);
	eval_items(E, n, &s);
	if (s.nparams == 4) { /* POV-Ray's old [from, to colour_from colour_to] */
		colour_map_push(E, m, n, &s, 0, 2);
		colour_map_push(E, m, n, &s, 1, 3);
		return;
	}
	if (s.nparams != 2)
		eval_fail(E, n->loc, "a colour_map entry is [position colour] or [from, to colour colour], found %d value%s",
		          s.nparams, s.nparams == 1 ? "" : "s");
	colour_map_push(E, m, n, &s, 0, 1);
}

/* Appends the entry (params[ip], params[ic]) of the sink to the map. */
static void colour_map_push(struct eval *E, struct colour_map *m, const struct node *n, struct sink *sk, int ip, int ic)
{
	/* any position, in any order, as POV-Ray takes them (its own woods.inc
	 * has 1.001 and a step back); the search finds the first entry at or
	 * above the value */
	double pos = val_want_float(E, &sk->params[ip], sk->ploc[ip]);
	if (m->n >= 256)
		eval_fail(E, n->loc, "colour_map has more than 256 entries");
	struct map_entry *e = ARENA_ARRAY(&SC(E)->arena, struct map_entry, m->n + 1);
	if (m->n)
		memcpy(e, m->e, sizeof *e * (size_t)m->n);
	e[m->n++] = (struct map_entry){pos, val_want_colour(E, &sk->params[ic], sk->ploc[ic])};
	m->e = e;
}

/* Resolves an image file like an include (only allowed directories) into
 * the pigment, keeping the name as written and where, for the tracer's
 * messages. */
void image_set(struct eval *E, struct pattern *p, struct srcloc loc, const char *name)
{
	char *real = eval_find_file(E, name, loc, "image file", NULL);
	if (E->opt->on_file) /* -M: the image is a dependency */
		E->opt->on_file(real, E->opt->on_file_ctx);
	p->image = arena_strndup(&SC(E)->arena, real, strlen(real));
	p->image_name = arena_strndup(&SC(E)->arena, name, strlen(name));
	p->image_loc = loc;
	free(real);
}

void image_map_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct pigment *p = s->target;
	switch (n->op) {
	case TK_PNG: case TK_EXR: {
		struct value v = arg1(E, n);
		if (v.kind != V_STRING)
			eval_fail(E, n->kids[0]->loc, "expected a file name string, found %s", val_type_name(&v));
		image_set(E, pat_w(E, p), n->loc, v.p.s);
		return;
	}
	case TK_INTERPOLATE: pat_w(E, p)->interpolate = arg_int(E, n, 0, 4); return;
	case TK_ONCE: pat_w(E, p)->once = true; return;
	case TK_MAP_TYPE:
		if (arg_int(E, n, 0, 7) != 0)
			eval_fail(E, n->kids[0]->loc, "only map_type 0 (planar) is supported");
		return;
	default: misplaced(E, s, n);
	}
}

struct pattern *pat_w(struct eval *E, struct pigment *p)
{
	struct pattern *c = NEW(E, struct pattern);
	*c = *pig_pattern(p);
	p->pat = c;
	if (E->npats == E->cappats) {
		int cap = E->cappats ? E->cappats * 2 : 64;
		struct pattern **g = ARENA_ARRAY(&E->arena, struct pattern *, cap);
		if (E->npats)
			memcpy(g, E->pats, sizeof *g * (size_t)E->npats);
		E->pats = g;
		E->cappats = cap;
	}
	E->pats[E->npats++] = c;
	return c;
}

void pigment_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct pigment *p = s->target;
	struct xform X;
	s->modified = 1;
	if (transform_of(E, n, &X)) {
		p->xf = xform_then(E, p->xf, &X);
		return;
	}
	switch (n->op) {
	case TK_CHECKER: case TK_HEXAGON: case TK_BRICK: {
		/* POV-Ray's default colours: checker blue, green; hexagon blue,
		 * green, red; brick grey mortar, red brick */
		p->kind = n->op == TK_CHECKER ? PIG_CHECKER : n->op == TK_HEXAGON ? PIG_HEXAGON : PIG_BRICK;
		p->c[0] = n->op == TK_BRICK ? c_rgb(0.5, 0.5, 0.5) : c_rgb(0, 0, 1);
		struct pattern *pt = pat_w(E, p);
		pt->more[0] = n->op == TK_BRICK ? c_rgb(0.6, 0.15, 0.15) : c_rgb(0, 1, 0);
		pt->more[1] = c_rgb(1, 0, 0);
		s->nparams = 0;
		s->modified = 0;
		return;
	}
	case TK_RADIAL: case TK_ONION: case TK_SPHERICAL: case TK_CYLINDRICAL: case TK_BOXED:
	case TK_PLANAR: case TK_LEOPARD:
		p->kind = PIG_PATTERN;
		pat_w(E, p)->pattern = n->op == TK_RADIAL ? PAT_RADIAL : n->op == TK_ONION ? PAT_ONION
		           : n->op == TK_SPHERICAL ? PAT_SPHERICAL : n->op == TK_CYLINDRICAL ? PAT_CYLINDRICAL
		           : n->op == TK_BOXED ? PAT_BOXED : n->op == TK_PLANAR ? PAT_PLANAR : PAT_LEOPARD;
		return;
	case TK_QUICK_COLOR: case TK_QUICK_COLOUR: /* POV-Ray's preview colour (quality below 6): not used */
		arg_colour(E, n);
		return;
	case TK_FILTER: case TK_TRANSMIT: /* pigment { White filter 0.5 }: the colour's component */
		if (p->kind != PIG_SOLID)
			misplaced(E, s, n);
		if (n->op == TK_FILTER)
			p->c[0].f = arg_float(E, n);
		else
			p->c[0].t = arg_float(E, n);
		return;
	case TK_FREQUENCY: pat_w(E, p)->frequency = arg_float(E, n); return;
	case TK_PHASE: pat_w(E, p)->phase = arg_float(E, n); return;
	case TK_RAMP_WAVE: pat_w(E, p)->wave = WAVE_RAMP; return;
	case TK_TRIANGLE_WAVE: pat_w(E, p)->wave = WAVE_TRIANGLE; return;
	case TK_SINE_WAVE: pat_w(E, p)->wave = WAVE_SINE; return;
	case TK_SCALLOP_WAVE: pat_w(E, p)->wave = WAVE_SCALLOP; return;
	case TK_CUBIC_WAVE: pat_w(E, p)->wave = WAVE_CUBIC; return;
	case TK_POLY_WAVE:
		pat_w(E, p)->wave = WAVE_POLY;
		pat_w(E, p)->exponent = n->nkids ? arg_float(E, n) : 1;
		return;
	case TK_BRICK_SIZE: {
		struct vec3 b = arg_vec3(E, n);
		if (!(b.x > 0 && b.y > 0 && b.z > 0))
			eval_fail(E, n->kids[0]->loc, "brick_size must be positive in x, y and z");
		pat_w(E, p)->brick_size = b;
		return;
	}
	case TK_MORTAR: pat_w(E, p)->mortar = arg_float(E, n); return;
	case TK_GRADIENT: {
		struct vec3 a = arg_vec3(E, n);
		if (v_len(a) == 0)
			eval_fail(E, n->kids[0]->loc, "gradient direction has zero length");
		p->kind = PIG_GRADIENT;
		pat_w(E, p)->axis = a;
		return;
	}
	case TK_COLOR_MAP: case TK_COLOUR_MAP: {
		struct colour_map *m = colour_map_block(E, n);
		pat_w(E, p)->map = m->e;
		pat_w(E, p)->nmap = m->n;
		return;
	}
	case TK_IMAGE_MAP: {
		struct sink sub;
		p->kind = PIG_IMAGE;
		pat_w(E, p)->interpolate = 0;
		run_block(E, n, SK_IMAGE_MAP, p, &sub);
		if (!pig_pattern(p)->image)
			eval_fail(E, n->loc, "image_map needs a file: image_map { png \"file.png\" }");
		return;
	}
	case TK_PIGMENT:
		if (p->kind == PIG_CHECKER || p->kind == PIG_HEXAGON || p->kind == PIG_BRICK) {
			struct pigment *sub = NEW(E, struct pigment);
			struct sink ss;
			*sub = scene_default_texture().pigment;
			run_block(E, n, SK_PIGMENT, sub, &ss);
			s->modified = 0;
			pattern_sub_pigment(E, s, sub, n->loc);
			return;
		}
		misplaced(E, s, n);
	default:
		if (!pattern_keyword(E, s, n))
			misplaced(E, s, n);
	}
}

void function_pattern(struct eval *E, struct pigment *p, const struct value *v, struct srcloc loc)
{
	const struct fn *f = function_usable(E, v, loc);
	p->kind = PIG_PATTERN;
	struct pattern *pt = pat_w(E, p);
	pt->pattern = PAT_FUNCTION;
	pt->fn = f;
}

void pigment_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc)
{
	struct pigment *p = s->target;
	bool block = p->kind == PIG_CHECKER || p->kind == PIG_HEXAGON || p->kind == PIG_BRICK;
	if (v->kind == V_PIGMENT && block && !s->modified) {
		pattern_sub_pigment(E, s, v->p.pig, loc);
		return;
	}
	if (v->kind == V_PIGMENT && s->nparams == 0 && !s->modified) {
		*p = *v->p.pig;
		s->modified = 1;
		return;
	}
	if (v->kind == V_FUNCTION) { /* pigment { function { … } colour_map { … } } */
		function_pattern(E, p, v, loc);
		s->modified = 1;
		return;
	}
	if (v->kind == V_COLOUR_MAP && (p->kind == PIG_GRADIENT || p->kind == PIG_PATTERN)) {
		pat_w(E, p)->map = v->p.cmap->e;
		pat_w(E, p)->nmap = v->p.cmap->n;
		return;
	}
	if (v->kind != V_COLOUR && v->kind != V_FLOAT && v->kind != V_VECTOR)
		eval_fail(E, loc, "expected a colour in pigment, found %s", val_type_name(v));
	struct colour c = val_want_colour(E, v, loc);
	if (p->kind == PIG_CHECKER || p->kind == PIG_HEXAGON || p->kind == PIG_BRICK) {
		int most = p->kind == PIG_HEXAGON ? 3 : 2;
		if (s->nparams >= most)
			eval_fail(E, loc, "%s takes %s colours, found more", p->kind == PIG_HEXAGON ? "hexagon" :
			          p->kind == PIG_BRICK ? "brick" : "checker", most == 3 ? "three" : "two");
		if (s->nparams == 0)
			p->c[0] = c;
		else
			pat_w(E, p)->more[s->nparams - 1] = c;
		if (pig_pattern(p)->pmap) { /* after a pigment: this one a plain colour too */
			struct pigment *solid = NEW(E, struct pigment);
			*solid = scene_default_texture().pigment;
			solid->c[0] = c;
			pattern_sub_pigment(E, s, solid, loc);
			return;
		}
		s->nparams++;
		return;
	}
	if (s->modified)
		eval_fail(E, loc, "a colour must come first in a pigment");
	p->kind = PIG_SOLID;
	p->c[0] = c;
	s->modified = 1;
}

void reflection_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct finish *f = s->target;
	switch (n->op) {
	case TK_FRESNEL: f->refl_fresnel = arg_bool(E, n); return;
	case TK_FALLOFF: f->refl_falloff = arg_positive(E, n); return;
	case TK_METALLIC: f->refl_metallic = arg_bool(E, n); return;
	default: misplaced(E, s, n);
	}
}

void finish_keyword(struct eval *E, struct sink *s, const struct node *n)
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
	case TK_CRAND: /* POV-Ray's grain: noise arvo does not add */
		arg_float(E, n);
		if (!E->warned_crand)
			diag_warning(E->diag, n->loc, "'crand' is not supported; ignored (here and in every finish)");
		E->warned_crand = true;
		return;
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

void interior_keyword(struct eval *E, struct sink *s, const struct node *n)
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

void texture_layer(struct eval *E, struct texture *t, const struct texture *top)
{
	struct texture *below = texture_copy(E, t);
	const struct texture *bottom = top;
	int depth = 0;
	while (tex_below(bottom) && depth++ < 64) /* top may be layered itself */
		bottom = tex_below(bottom);
	if (depth >= 64)
		eval_fail(E, E->stmt, "more than 64 texture layers");
	if (bottom == top) {
		*t = *top;
		tex_set_below(E, t, below);
		return;
	}
	/* copy top's chain, its last layer resting on below */
	struct texture *k = t;
	*t = *top;
	while (tex_below(k)) {
		struct texture *next = texture_copy(E, tex_below(k));
		tex_set_below(E, k, next);
		k = next;
	}
	tex_set_below(E, k, below);
}

/* The next texture of checker, hexagon or brick texture t. */
static void texture_entry(struct eval *E, struct texture *t, const struct texture *k, struct srcloc loc)
{
	enum pigment_kind pk = t->pigment.kind;
	int most = pk == PIG_HEXAGON ? 3 : 2, n = tex_nmap(t);
	if (n >= most)
		eval_fail(E, loc, "%s takes %d textures, found more",
		          pk == PIG_HEXAGON ? "hexagon" : pk == PIG_BRICK ? "brick" : "checker", most);
	struct tex_entry *m = ARENA_ARRAY(&SC(E)->arena, struct tex_entry, n + 1);
	if (n)
		memcpy(m, tex_map(t), sizeof *m * (size_t)n);
	m[n] = (struct tex_entry){n, k};
	tex_set_map(E, t, m, n + 1);
}

void texture_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct texture *t = s->target;
	struct xform X;
	struct sink sub;
	s->modified = 1;
	if (transform_of(E, n, &X)) {
		texture_transform(E, t, &X);
		return;
	}
	if (n->op == TK_TEXTURE_MAP) {
		texture_map_block(E, t, n);
		return;
	}
	if (n->op == TK_TILES) {
		tiles_block(E, t, n);
		return;
	}
	if (n->op == TK_TEXTURE) {
		enum pigment_kind pk = t->pigment.kind;
		if (pk == PIG_CHECKER || pk == PIG_HEXAGON || pk == PIG_BRICK) {
			/* checker texture { } texture { }: the parser links textures in a
			 * row as layers (n->c); here each is one of the pattern's */
			for (const struct node *k = n; k; k = k->c) {
				struct node one = *k;
				one.c = NULL;
				texture_entry(E, t, eval_block(E, &one).p.tex, k->loc);
			}
			return;
		}
		texture_layer(E, t, eval_block(E, n).p.tex); /* a layer on top of what t is so far */
		return;
	}
	if (is_pattern_kw(n->op)) { /* texture { gradient x texture_map { … } } */
		sink_init(&sub, SK_PIGMENT, TK_TEXTURE, s->loc, &t->pigment);
		pigment_keyword(E, &sub, n);
		return;
	}
	if (n->op == TK_NORMAL)
		tex_set_normal(E, t, normal_block(E, n));
	else if (n->op == TK_PIGMENT)
		run_block(E, n, SK_PIGMENT, &t->pigment, &sub);
	else if (n->op == TK_FINISH)
		tex_set_finish(E, t, finish_block(E, n, tex_finish(t)));
	else
		misplaced(E, s, n);
}

/* ==== normal ============================================================== */

struct tnormal *normal_block(struct eval *E, const struct node *blk)
{
	struct tnormal *t = NEW(E, struct tnormal);
	struct sink s;
	t->pat = scene_default_texture().pigment;
	t->pat.kind = PIG_SOLID; /* no pattern yet */
	t->amount = E->default_bump > 0 ? E->default_bump : 0.5; /* #default { normal { bump_size … } } */
	run_block(E, blk, SK_NORMAL, t, &s);
	if (s.pending)
		return NULL;
	if (blk->kind == N_BLOCK && E->in_default && t->pat.kind == PIG_SOLID) {
		E->default_bump = t->amount; /* a default bump size alone: no warning */
		return NULL;
	}
	if (t->pat.kind == PIG_SOLID || t->pat.kind == PIG_IMAGE) {
		if (!E->warned_normal++)
			diag_warning(E->diag, blk->loc, "'normal' without a pattern arvo supports is ignored");
		return NULL;
	}
	return t;
}

/* The pattern keywords of pigment, a bump size after the pattern (also
 * `gradient x, 0.5`), transforms. */
void normal_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct tnormal *t = s->target;
	struct sink sub;
	sink_init(&sub, SK_PIGMENT, TK_NORMAL, s->loc, &t->pat);
	if (n->op == TK_GRADIENT && n->nkids == 2) {
		struct node one = *n;
		one.nkids = 1;
		t->amount = eval_float(E, n->kids[1]);
		pigment_keyword(E, &sub, &one);
		return;
	}
	switch (n->op) {
	case TK_COLOR_MAP: case TK_COLOUR_MAP: case TK_IMAGE_MAP: case TK_PIGMENT_MAP: misplaced(E, s, n);
	case TK_BUMP_SIZE: t->amount = arg_float(E, n); return;
	case TK_NORMAL_MAP: normal_map_block(E, t, n); return;
	case TK_NORMAL: { /* checker normal { } normal { }, or normal_map { [v normal { … }] } */
		const struct tnormal *k = normal_block(E, n);
		enum pigment_kind pk = t->pat.kind;
		if (pk == PIG_CHECKER || pk == PIG_HEXAGON || pk == PIG_BRICK) {
			int most = pk == PIG_HEXAGON ? 3 : 2;
			if (t->nmap >= most)
				eval_fail(E, n->loc, "this pattern takes %d normals, found more", most);
			struct nrm_entry *m = ARENA_ARRAY(&SC(E)->arena, struct nrm_entry, t->nmap + 1);
			if (t->nmap)
				memcpy(m, t->map, sizeof *m * (size_t)t->nmap);
			m[t->nmap] = (struct nrm_entry){t->nmap, k};
			t->map = m;
			t->nmap++;
		} else if (k) {
			*t = *k;
		} else {
			s->pending = 1;
		}
		return;
	}
	case TK_SPIRAL1: case TK_SPIRAL2: case TK_MANDEL:
		if (n->nkids == 2) { /* spiral1 arms, bump size */
			struct node one = *n;
			one.nkids = 1;
			t->amount = eval_float(E, n->kids[1]);
			pigment_keyword(E, &sub, &one);
			return;
		}
		pigment_keyword(E, &sub, n);
		return;
	default: pigment_keyword(E, &sub, n);
	}
}

void normal_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc)
{
	struct tnormal *t = s->target;
	if (v->kind == V_FUNCTION) { /* normal { function { … } [amount] } */
		function_pattern(E, &t->pat, v, loc);
		return;
	}
	if (v->kind == V_SKIPPED) { /* a declared normal first */
		if (v->p.nrm)
			*t = *v->p.nrm;
		else
			s->pending = 1;
		return;
	}
	t->amount = val_want_float(E, v, loc);
}
