/* SPDX-License-Identifier: MIT */
/* patterns.c: the noise patterns, turbulence, warps and maps of pigments,
 * normals and textures (tracer/noisepat.c evaluates them).
 *
 * Warps are kept in the order they act. As in POV-Ray, a new warp acts
 * before everything written so far: the transforms written before it move
 * into the list after it, and transforms written after it act first (they
 * go to the pigment's own transform). A pattern's `turbulence`, `octaves`,
 * `omega` and `lambda` set its own turbulence warp, which acts last. */
#include <string.h>

#include "internal.h"

/* ==== warps =============================================================== */

/* The warp list of p made its own (pigments share lists), with room for
 * `extra` more at the front; returns the first slot. */
static struct warp *warps_grow(struct eval *E, struct pigment *p, int extra)
{
	struct pattern *pt = pat_w(E, p);
	struct warp *w = ARENA_ARRAY(&SC(E)->arena, struct warp, pt->nwarps + extra);
	memset(w, 0, sizeof *w * (size_t)extra);
	if (pt->nwarps)
		memcpy(w + extra, pt->warps, sizeof *w * (size_t)pt->nwarps);
	pt->warps = w;
	pt->nwarps += extra;
	return w;
}

/* A new warp acting first: the pigment's transform so far moves after it. */
static struct warp *warp_push(struct eval *E, struct pigment *p)
{
	if (pig_pattern(p)->nwarps >= 64)
		eval_fail(E, E->stmt, "more than 64 warps in one pattern");
	if (!p->xf)
		return warps_grow(E, p, 1);
	struct warp *w = warps_grow(E, p, 2);
	w[1] = (struct warp){.kind = WARP_XF, .xf = p->xf};
	p->xf = NULL;
	return w;
}

static void turb_defaults(struct warp *w)
{
	*w = (struct warp){.kind = WARP_TURB, .octaves = 6, .omega = 0.5, .lambda = 2};
}

/* The pattern's own turbulence: the last warp to act, added there unless
 * the last already is it (POV-Ray's order, measured against its renders:
 * it acts after every transform, wherever it was written). */
static struct warp *own_turb(struct eval *E, struct pigment *p)
{
	const struct pattern *pt = pig_pattern(p);
	int n = pt->nwarps;
	if (n > 0 && pt->warps[n - 1].kind == WARP_TURB && pt->warps[n - 1].classic)
		return warps_grow(E, p, 0) + n - 1;
	if (n >= 64)
		eval_fail(E, E->stmt, "more than 64 warps in one pattern");
	struct pattern *w = pat_w(E, p);
	struct warp *arr = ARENA_ARRAY(&SC(E)->arena, struct warp, n + 1);
	if (n)
		memcpy(arr, w->warps, sizeof *arr * (size_t)n);
	turb_defaults(&arr[n]);
	arr[n].classic = true;
	w->warps = arr;
	w->nwarps = n + 1;
	return &arr[n];
}

/* turbulence, octaves, omega, lambda into warp w; false for other words. */
static bool turb_keyword(struct eval *E, struct warp *w, const struct node *n)
{
	switch (n->op) {
	case TK_TURBULENCE: w->turb = arg_vec3(E, n); return true;
	case TK_OCTAVES: w->octaves = arg_int(E, n, 1, 10); return true;
	case TK_OMEGA: w->omega = arg_float(E, n); return true;
	case TK_LAMBDA: w->lambda = arg_float(E, n); return true;
	default: return false;
	}
}

/* repeat <v>: the axis of v's one non-zero component, the width its value. */
static void repeat_axis(struct eval *E, struct warp *w, const struct node *n)
{
	struct vec3 v = arg_vec3(E, n);
	int nz = (v.x != 0) + (v.y != 0) + (v.z != 0);
	if (nz != 1)
		eval_fail(E, n->kids[0]->loc, "repeat needs a vector along one axis, such as 2*x");
	w->axis = v.x != 0 ? 0 : v.y != 0 ? 1 : 2;
	w->width = fabs(v.x + v.y + v.z);
}

/* One item of warp { }: turbulence, repeat, black_hole and their modifiers. */
void warp_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct warp *w = s->target;
	if (turb_keyword(E, w, n)) {
		if (w->kind != WARP_TURB)
			eval_fail(E, n->loc, "%s belongs to a turbulence warp, not this one", tok_name(n->op));
		s->nparams |= 1;
		return;
	}
	switch (n->op) {
	case TK_REPEAT:
		w->kind = WARP_REPEAT;
		repeat_axis(E, w, n);
		s->nparams |= 2;
		return;
	case TK_OFFSET: w->offset = arg_vec3(E, n); return;
	case TK_FLIP: {
		struct vec3 f = arg_vec3(E, n);
		w->flip = v3(f.x != 0 ? -1 : 1, f.y != 0 ? -1 : 1, f.z != 0 ? -1 : 1);
		return;
	}
	case TK_BLACK_HOLE:
		if (n->nkids != 2)
			eval_fail(E, n->loc, "black_hole needs a centre and a radius: black_hole <0,0,0>, 1");
		w->kind = WARP_BLACK_HOLE;
		w->center = eval_vec3(E, n->kids[0]);
		w->radius = eval_float(E, n->kids[1]);
		if (!(w->radius > 0))
			eval_fail(E, n->kids[1]->loc, "black_hole radius must be positive");
		s->nparams |= 4;
		return;
	case TK_FALLOFF: w->falloff = arg_float(E, n); return;
	case TK_STRENGTH: w->strength = arg_float(E, n); return;
	case TK_INVERSE: w->inverse = true; return;
	default: misplaced(E, s, n);
	}
}

/* warp { … } on pigment p. */
static void warp_block(struct eval *E, struct pigment *p, const struct node *n)
{
	struct warp w;
	struct sink s;
	turb_defaults(&w);
	w.flip = v3(1, 1, 1);
	w.strength = 1;
	w.falloff = 2;
	run_block(E, n, SK_WARP, &w, &s);
	if (s.nparams == 0)
		eval_fail(E, n->loc, "warp needs turbulence, repeat or black_hole");
	if (s.nparams & (s.nparams - 1))
		eval_fail(E, n->loc, "one kind of warp per warp { }: turbulence, repeat or black_hole");
	if (w.kind == WARP_REPEAT && !(w.width > 0))
		eval_fail(E, n->loc, "repeat width must be positive");
	*warp_push(E, p) = w;
}

/* ==== maps ================================================================ */

/* The position of map entry n: its first item when that is a number (the
 * body then starts at *first = 1); else 1, as POV-Ray's average takes
 * [texture-body] without a weight (*first = 0). */
static double entry_pos(struct eval *E, const struct node *n, int *first)
{
	const struct node *k = n->kids[0];
	*first = 0;
	if (k->kind == N_BLOCK || k->kind == N_MOD || k->kind == N_WORD || k->kind == N_SKIPPED || k->kind == N_FUNC)
		return 1;
	struct value v = eval_expr(E, k);
	if (v.kind != V_FLOAT)
		return 1;
	*first = 1;
	return v.v[0];
}

/* [position pigment-body] of a pigment_map. */
static void pigment_entry(struct eval *E, struct pig_entry *e, const struct node *n)
{
	int first;
	if (n->kind != N_ENTRY || n->nkids < 1)
		eval_fail(E, n->loc, "a pigment_map entry is [position pigment]");
	e->pos = entry_pos(E, n, &first);
	struct pigment *pg = NEW(E, struct pigment);
	*pg = scene_default_texture().pigment;
	struct sink s;
	sink_init(&s, SK_PIGMENT, TK_PIGMENT_MAP, n->loc, pg);
	for (int i = first; i < n->nkids; i++)
		eval_item(E, n->kids[i], &s);
	e->pig = pg;
}

/* The entries [v …] of a map block, in order, each through one(). */
static int map_entries(struct eval *E, const struct node *blk, size_t size, void **out,
                       void (*one)(struct eval *, void *, const struct node *), const char *what)
{
	int n = 0;
	char *arr = NULL;
	for (int i = 0; i < blk->nkids; i++) {
		const struct node *k = blk->kids[i];
		if (k->kind != N_ENTRY)
			eval_fail(E, k->loc, "a %s holds entries [position …]", what);
		if (n >= 256)
			eval_fail(E, k->loc, "%s has more than 256 entries", what);
		char *grown = arena_alloc(&SC(E)->arena, size * (size_t)(n + 1));
		if (n)
			memcpy(grown, arr, size * (size_t)n);
		arr = grown;
		one(E, arr + size * (size_t)n, k);
		n++;
	}
	if (n == 0)
		eval_fail(E, blk->loc, "%s needs at least one entry", what);
	*out = arr;
	return n;
}

static void pig_entry_cb(struct eval *E, void *e, const struct node *n) { pigment_entry(E, e, n); }

static void pigment_map_block(struct eval *E, struct pigment *p, const struct node *n)
{
	void *arr;
	int k = map_entries(E, n, sizeof(struct pig_entry), &arr, pig_entry_cb, "pigment_map");
	struct pattern *pt = pat_w(E, p);
	pt->pmap = arr;
	pt->npmap = k;
}

/* ==== patterns ============================================================ */

static enum pattern_kind noise_kind(enum tok t)
{
	switch (t) {
	case TK_BOZO: return PAT_BOZO;
	case TK_SPOTTED: return PAT_SPOTTED;
	case TK_BUMPS: return PAT_BUMPS;
	case TK_DENTS: return PAT_DENTS;
	case TK_GRANITE: return PAT_GRANITE;
	case TK_MARBLE: return PAT_MARBLE;
	case TK_WOOD: return PAT_WOOD;
	case TK_AGATE: return PAT_AGATE;
	case TK_WRINKLES: return PAT_WRINKLES;
	case TK_RIPPLES: return PAT_RIPPLES;
	case TK_WAVES: return PAT_WAVES;
	case TK_CRACKLE: return PAT_CRACKLE;
	case TK_QUILTED: return PAT_QUILTED;
	case TK_SPIRAL1: return PAT_SPIRAL1;
	case TK_SPIRAL2: return PAT_SPIRAL2;
	case TK_CELLS: return PAT_CELLS;
	case TK_MANDEL: return PAT_MANDEL;
	case TK_AVERAGE: return PAT_AVERAGE;
	default: return PAT_KIND_COUNT;
	}
}

/* A noise pattern keyword: the kind, and what POV-Ray sets with it (marble,
 * wood and the spirals take the triangle wave, agate its own turbulence). */
static void noise_pattern(struct eval *E, struct pigment *p, const struct node *n)
{
	p->kind = PIG_PATTERN;
	struct pattern *pt = pat_w(E, p);
	pt->pattern = noise_kind(n->op);
	if (n->op == TK_MARBLE || n->op == TK_WOOD || n->op == TK_SPIRAL1 || n->op == TK_SPIRAL2)
		pt->wave = WAVE_TRIANGLE;
	if (n->op == TK_SPIRAL1 || n->op == TK_SPIRAL2) {
		if (n->nkids < 1)
			eval_fail(E, n->loc, "%s needs its number of arms: %s 5", tok_name(n->op), tok_name(n->op));
		double a = eval_float(E, n->kids[0]);
		if (!(a >= -1e6 && a <= 1e6))
			eval_fail(E, n->kids[0]->loc, "%s arms must be -1e6 to 1e6", tok_name(n->op));
		pt->arms = (int)a;
	}
	if (n->op == TK_AGATE)
		own_turb(E, p);
	if (n->op == TK_MANDEL) {
		pt->arms = arg_int(E, n, 1, 1000000); /* the iterations */
		pt->exponent_i = 2;
	}
}

bool pattern_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct pigment *p = s->target;
	if (noise_kind(n->op) != PAT_KIND_COUNT) {
		noise_pattern(E, p, n);
		return true;
	}
	if (n->op == TK_TURBULENCE || n->op == TK_OCTAVES || n->op == TK_OMEGA || n->op == TK_LAMBDA) {
		struct warp *w = own_turb(E, p);
		turb_keyword(E, w, n);
		return true;
	}
	switch (n->op) {
	case TK_AGATE_TURB: pat_w(E, p)->agate_turb = arg_float(E, n); return true;
	case TK_EXPONENT: pat_w(E, p)->exponent_i = arg_int(E, n, 2, 4); return true;
	case TK_METRIC: pat_w(E, p)->metric = arg_positive(E, n); return true;
	case TK_FORM: pat_w(E, p)->form = arg_vec3(E, n); return true;
	case TK_OFFSET: pat_w(E, p)->offset = arg_float(E, n); return true;
	case TK_SOLID: pat_w(E, p)->solid = true; return true;
	case TK_CONTROL0: pat_w(E, p)->control0 = arg_float(E, n); return true;
	case TK_CONTROL1: pat_w(E, p)->control1 = arg_float(E, n); return true;
	case TK_NOISE_GENERATOR: pat_w(E, p)->noise_gen = arg_int(E, n, 1, 3); return true;
	case TK_WARP: warp_block(E, p, n); return true;
	case TK_PIGMENT_MAP: pigment_map_block(E, p, n); return true;
	case TK_PIGMENT_PATTERN: {
		struct pigment *sub = NEW(E, struct pigment);
		struct sink ss;
		*sub = scene_default_texture().pigment;
		run_block(E, n, SK_PIGMENT, sub, &ss);
		p->kind = PIG_PATTERN;
		pat_w(E, p)->pattern = PAT_PIGMENT;
		pat_w(E, p)->sub = sub;
		return true;
	}
	default: return false;
	}
}

/* `checker pigment { … } pigment { … }`: pigments in place of colours. */
void pattern_sub_pigment(struct eval *E, struct sink *s, const struct pigment *sub, struct srcloc loc)
{
	struct pigment *p = s->target;
	struct pattern *pt = pat_w(E, p);
	int most = p->kind == PIG_HEXAGON ? 3 : 2;
	if (s->nparams >= most)
		eval_fail(E, loc, "%s takes %d pigments, found more", p->kind == PIG_HEXAGON ? "hexagon" : p->kind == PIG_BRICK ? "brick" : "checker", most);
	struct pig_entry *e = ARENA_ARRAY(&SC(E)->arena, struct pig_entry, most);
	for (int i = 0; i < most; i++) { /* the entries not given yet: the colours so far */
		struct pigment *c = NEW(E, struct pigment);
		*c = scene_default_texture().pigment;
		c->c[0] = pig_colour(p, i);
		e[i] = i < pt->npmap ? pt->pmap[i] : (struct pig_entry){i, c};
	}
	e[s->nparams].pig = sub;
	pt->pmap = e;
	pt->npmap = most;
	s->nparams++;
}

void patterns_finish(struct eval *E)
{
	int g = SC(E)->gs.noise_generator;
	for (int i = 0; i < E->npats; i++) {
		if (E->pats[i]->noise_gen == 0)
			E->pats[i]->noise_gen = g;
		E->pats[i]->nwaves = SC(E)->gs.number_of_waves;
	}
}

/* ==== texture_map and normal_map ========================================= */

/* [position texture-body] of a texture_map: a declared texture or pigment,
 * finish and normal blocks. */
static void tex_entry_cb(struct eval *E, void *out, const struct node *n)
{
	struct tex_entry *e = out;
	int first;
	if (n->nkids < 1)
		eval_fail(E, n->loc, "a texture_map entry is [position texture]");
	e->pos = entry_pos(E, n, &first);
	struct texture *t = texture_copy(E, NULL);
	tex_set_loc(E, t, n->loc);
	struct sink s;
	sink_init(&s, SK_TEXTURE, TK_TEXTURE_MAP, n->loc, t);
	for (int i = first; i < n->nkids; i++)
		eval_item(E, n->kids[i], &s);
	e->tex = t;
}

/* [position normal-body] of a normal_map. */
static void nrm_entry_cb(struct eval *E, void *out, const struct node *n)
{
	struct nrm_entry *e = out;
	int first;
	if (n->nkids < 1)
		eval_fail(E, n->loc, "a normal_map entry is [position normal]");
	e->pos = entry_pos(E, n, &first);
	struct tnormal *t = NEW(E, struct tnormal);
	t->pat = scene_default_texture().pigment;
	t->pat.kind = PIG_SOLID;
	t->amount = E->default_bump > 0 ? E->default_bump : 0.5;
	struct sink s;
	sink_init(&s, SK_NORMAL, TK_NORMAL_MAP, n->loc, t);
	for (int i = first; i < n->nkids; i++)
		eval_item(E, n->kids[i], &s);
	e->n = s.pending || t->pat.kind == PIG_SOLID || t->pat.kind == PIG_IMAGE ? NULL : t;
}

void texture_map_block(struct eval *E, struct texture *t, const struct node *n)
{
	void *arr;
	int k = map_entries(E, n, sizeof(struct tex_entry), &arr, tex_entry_cb, "texture_map");
	tex_set_map(E, t, arr, k);
}

void normal_map_block(struct eval *E, struct tnormal *t, const struct node *n)
{
	void *arr;
	int k = map_entries(E, n, sizeof(struct nrm_entry), &arr, nrm_entry_cb, "normal_map");
	t->map = arr;
	t->nmap = k;
}

bool is_pattern_kw(enum tok k)
{
	switch (k) {
	case TK_CHECKER: case TK_HEXAGON: case TK_BRICK: case TK_GRADIENT: case TK_RADIAL: case TK_ONION:
	case TK_SPHERICAL: case TK_CYLINDRICAL: case TK_BOXED: case TK_PLANAR: case TK_LEOPARD:
	case TK_BRICK_SIZE: case TK_MORTAR: case TK_FREQUENCY: case TK_PHASE: case TK_RAMP_WAVE:
	case TK_TRIANGLE_WAVE: case TK_SINE_WAVE: case TK_SCALLOP_WAVE: case TK_CUBIC_WAVE: case TK_POLY_WAVE:
	case TK_TURBULENCE: case TK_OCTAVES: case TK_OMEGA: case TK_LAMBDA: case TK_WARP: case TK_AGATE_TURB:
	case TK_METRIC: case TK_FORM: case TK_OFFSET: case TK_SOLID: case TK_CONTROL0: case TK_CONTROL1:
	case TK_NOISE_GENERATOR: case TK_PIGMENT_PATTERN: case TK_EXPONENT:
		return true;
	default: return noise_kind(k) != PAT_KIND_COUNT;
	}
}

/* tiles { texture { … } … tile2 texture { … } … }: POV-Ray's old checker of
 * (layered) textures. */
void tiles_block(struct eval *E, struct texture *t, const struct node *n)
{
	struct texture *tile[2] = {NULL, NULL};
	int k = 0;
	for (int i = 0; i < n->nkids; i++) {
		const struct node *it = n->kids[i];
		if (it->kind == N_MOD && it->op == TK_TILE2) {
			k = 1;
			continue;
		}
		if (it->kind != N_BLOCK || it->op != TK_TEXTURE)
			eval_fail(E, it->loc, "tiles holds textures, then tile2 and more textures");
		const struct texture *x = eval_block(E, it).p.tex;
		if (!tile[k]) {
			tile[k] = texture_copy(E, x);
		} else {
			texture_layer(E, tile[k], x);
		}
	}
	if (!tile[0] || !tile[1])
		eval_fail(E, n->loc, "tiles needs a texture on each side of tile2");
	struct tex_entry *m = ARENA_ARRAY(&SC(E)->arena, struct tex_entry, 2);
	m[0] = (struct tex_entry){0, tile[1]}; /* POV-Ray's tile2 on the checker's first colour */
	m[1] = (struct tex_entry){1, tile[0]};
	t->pigment = scene_default_texture().pigment;
	t->pigment.kind = PIG_CHECKER;
	tex_set_map(E, t, m, 2);
}
