/* SPDX-License-Identifier: MIT */
/* outlines.c: the primitives built from 2D outlines: text, prism, polygon,
 * lathe and sor. Their blocks take a leading keyword or two (the spline,
 * the sweep, the font) and a list of values of any length, so they collect
 * into s->ob rather than the sink's few parameters; each geom_ function
 * then turns POV-Ray's points into the curve pieces of tracer/shapes/
 * outline.h (the spline formulas are POV-Ray's, docs/parametrisations.md). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../tracer/shapes/outline.h"
#include "internal.h"

enum spline { SP_LINEAR, SP_QUADRATIC, SP_CUBIC, SP_BEZIER };

struct outline_build {
	struct value *v;      /* the positional values, in order */
	struct srcloc *loc;   /* where each came from */
	int n, cap;
	enum spline spline;   /* linear_spline (default) … bezier_spline */
	struct srcloc spline_loc;
	bool spline_given;
	bool conic;           /* conic_sweep */
	const char *font;     /* ttf "file" */
	struct srcloc font_loc;
};

/* Growable list of pieces, in the evaluator's arena until copied out. */
struct pieces {
	struct curve2 *c;
	int n, cap;
};

static struct outline_build *build_of(struct eval *E, struct sink *s)
{
	if (!s->ob)
		s->ob = ARENA_NEW(&E->arena, struct outline_build);
	return s->ob;
}

bool outline_keyword(struct eval *E, struct sink *s, struct object *o, const struct node *n)
{
	if (!is_outline_kind(o->kind))
		return false;
	struct outline_build *b = build_of(E, s);
	bool splines = o->kind == OBJ_PRISM || o->kind == OBJ_LATHE;
	switch (n->op) {
	case TK_LINEAR_SPLINE: case TK_QUADRATIC_SPLINE: case TK_CUBIC_SPLINE: case TK_BEZIER_SPLINE:
		if (!splines || b->n)
			return false;
		b->spline = n->op == TK_LINEAR_SPLINE ? SP_LINEAR : n->op == TK_QUADRATIC_SPLINE ? SP_QUADRATIC
		          : n->op == TK_CUBIC_SPLINE ? SP_CUBIC : SP_BEZIER;
		b->spline_loc = n->loc;
		b->spline_given = true;
		return true;
	case TK_LINEAR_SWEEP: case TK_CONIC_SWEEP:
		if (o->kind != OBJ_PRISM || b->n)
			return false;
		b->conic = n->op == TK_CONIC_SWEEP;
		return true;
	case TK_TTF: {
		/* ttf "file" "string" t, o — or, with commas, ttf "file", "string", t, o */
		if (o->kind != OBJ_TEXT || b->n || n->nkids < 1)
			return false;
		struct value v = eval_expr(E, n->kids[0]);
		if (v.kind != V_STRING)
			eval_fail(E, n->kids[0]->loc, "expected a font file name string after 'ttf', found %s",
			          val_type_name(&v));
		b->font = v.p.s;
		b->font_loc = n->kids[0]->loc;
		for (int i = 1; i < n->nkids; i++) {
			struct value w = eval_expr(E, n->kids[i]);
			outline_value(E, s, o, &w, n->kids[i]->loc);
		}
		return true;
	}
	default:
		return false;
	}
}

bool outline_value(struct eval *E, struct sink *s, struct object *o, const struct value *v, struct srcloc loc)
{
	if (!is_outline_kind(o->kind))
		return false;
	struct outline_build *b = build_of(E, s);
	if (v->kind != V_FLOAT && v->kind != V_VECTOR && !(v->kind == V_STRING && o->kind == OBJ_TEXT))
		eval_fail(E, loc, "expected a float or vector parameter in %s, found %s", tok_name(s->kw),
		          val_type_name(v));
	if (b->n == b->cap) {
		int cap = b->cap ? 2 * b->cap : 16;
		struct value *nv = ARENA_ARRAY(&E->arena, struct value, cap);
		struct srcloc *nl = ARENA_ARRAY(&E->arena, struct srcloc, cap);
		if (b->n) {
			memcpy(nv, b->v, sizeof *nv * (size_t)b->n);
			memcpy(nl, b->loc, sizeof *nl * (size_t)b->n);
		}
		b->v = nv, b->loc = nl, b->cap = cap;
	}
	b->v[b->n] = *v;
	b->loc[b->n++] = loc;
	return true;
}

/* ---- values ------------------------------------------------------------- */

static double want_float(struct eval *E, const struct outline_build *b, int i)
{
	return val_want_float(E, &b->v[i], b->loc[i]);
}

/* The point count n that leads a point list, checked against what follows. */
static int want_count(struct eval *E, struct sink *s, const struct outline_build *b, int i, int min,
                      const char *usage)
{
	if (b->n <= i)
		eval_fail(E, s->loc, "%s expects %s", tok_name(s->kw), usage);
	double f = want_float(E, b, i);
	if (f != floor(f) || f < min || f > 1e7)
		eval_fail(E, b->loc[i], "%s needs a whole number of at least %d points, found %g", tok_name(s->kw),
		          min, f);
	int n = (int)f;
	if (b->n - i - 1 != n)
		eval_fail(E, b->n - i - 1 > n ? b->loc[i + 1 + n] : s->loc,
		          "%s says %d points but %d follow", tok_name(s->kw), n, b->n - i - 1);
	return n;
}

/* A 2D point <u,v> (the first two components of a vector). */
static void want_uv(struct eval *E, const struct outline_build *b, int i, double out[2])
{
	const struct value *v = &b->v[i];
	if (v->kind != V_VECTOR)
		eval_fail(E, b->loc[i], "expected a 2D point <u, v>, found %s", val_type_name(v));
	out[0] = v->v[0];
	out[1] = v->v[1];
	if (!isfinite(out[0]) || !isfinite(out[1]))
		eval_fail(E, b->loc[i], "point is not finite");
}

/* ---- pieces --------------------------------------------------------------- */

static void add_piece(struct eval *E, struct pieces *p, const double cx[4], const double cy[4],
                      const double p0[2], const double p1[2])
{
	if (p->n == p->cap) {
		int cap = p->cap ? 2 * p->cap : 32;
		struct curve2 *c = ARENA_ARRAY(&E->arena, struct curve2, cap);
		if (p->n)
			memcpy(c, p->c, sizeof *c * (size_t)p->n);
		p->c = c, p->cap = cap;
	}
	p->c[p->n++] = curve2_make(cx, cy, p0, p1);
}

static void add_line(struct eval *E, struct pieces *p, const double a[2], const double b[2])
{
	double cx[4] = {a[0], b[0] - a[0], 0, 0}, cy[4] = {a[1], b[1] - a[1], 0, 0};
	add_piece(E, p, cx, cy, a, b);
}

/* The piece of a spline over points P[i…] (POV-Ray's formulas): linear
 * P[i]→P[i+1]; quadratic P[i+1]→P[i+2] led by P[i]; cubic (Catmull–Rom)
 * P[i+1]→P[i+2] between P[i] and P[i+3]; Bézier P[i]…P[i+3]. */
static void add_spline(struct eval *E, struct pieces *p, enum spline sp, double (*P)[2], int i)
{
	double cx[4] = {0}, cy[4] = {0};
	const double *s = P[i], *e = P[i + 1];
	for (int k = 0; k < 2; k++) {
		double *c = k ? cy : cx;
		double p0 = P[i][k], p1 = P[i + 1][k];
		double p2 = sp >= SP_QUADRATIC ? P[i + 2][k] : 0, p3 = sp >= SP_CUBIC ? P[i + 3][k] : 0;
		switch (sp) {
		case SP_LINEAR: c[0] = p0, c[1] = p1 - p0; break;
		case SP_QUADRATIC: c[0] = p1, c[1] = 0.5 * (p2 - p0), c[2] = 0.5 * p0 - p1 + 0.5 * p2; break;
		case SP_CUBIC:
			c[0] = p1, c[1] = 0.5 * (p2 - p0), c[2] = p0 - 2.5 * p1 + 2 * p2 - 0.5 * p3;
			c[3] = -0.5 * p0 + 1.5 * p1 - 1.5 * p2 + 0.5 * p3;
			break;
		case SP_BEZIER:
			c[0] = p0, c[1] = 3 * (p1 - p0), c[2] = 3 * (p0 - 2 * p1 + p2);
			c[3] = -p0 + 3 * p1 - 3 * p2 + p3;
			break;
		}
	}
	if (sp == SP_QUADRATIC || sp == SP_CUBIC)
		s = P[i + 1], e = P[i + 2];
	else if (sp == SP_BEZIER)
		e = P[i + 3];
	add_piece(E, p, cx, cy, s, e);
}

/* Points each piece of a spline reaches past i, and where its last
 * on-curve point is. */
static int spline_span(enum spline sp) { return sp == SP_LINEAR ? 1 : sp == SP_QUADRATIC ? 2 : 3; }
static int spline_end(enum spline sp) { return sp == SP_LINEAR ? 1 : sp == SP_BEZIER ? 3 : 2; }

static bool same_point(const double a[2], const double b[2])
{
	return fabs(a[0] - b[0]) < 1e-10 && fabs(a[1] - b[1]) < 1e-10;
}

static const char *spline_name(enum spline sp)
{
	static const char *const names[] = {"linear_spline", "quadratic_spline", "cubic_spline", "bezier_spline"};
	return names[sp];
}

/* POV-Ray's closed sub-outlines: a sub-outline ends where a piece returns
 * to its first on-curve point, and the next starts after it. A last one
 * left open is closed with a straight line (warned). */
static void closed_splines(struct eval *E, struct sink *s, const struct outline_build *b, double (*P)[2],
                           int n, int first_idx, struct pieces *out)
{
	enum spline sp = b->spline;
	int lead = sp == SP_QUADRATIC || sp == SP_CUBIC ? 1 : 0;
	const double *first = P[lead];
	int start_pieces = out->n;
	for (int i = 0; i < n - 1; i++) {
		if (i + spline_span(sp) >= n)
			eval_fail(E, b->loc[first_idx + n - 1], "too few points in %s for its %s (a sub-outline "
			          "is not closed, or control points are missing)", tok_name(s->kw), spline_name(sp));
		add_spline(E, out, sp, P, i);
		const double *end = P[i + spline_end(sp)];
		if (sp == SP_BEZIER) {
			i += 3;
			if (same_point(end, first)) {
				start_pieces = out->n;
				if (i + 1 < n)
					first = P[i + 1];
			}
		} else if (same_point(end, first)) {
			i += spline_span(sp);
			start_pieces = out->n;
			if (i + 1 + lead < n)
				first = P[i + 1 + lead];
		}
	}
	if (out->n > start_pieces) {
		const double *last = out->c[out->n - 1].p1;
		diag_warning(E->diag, b->loc[first_idx + n - 1], "%s outline is not closed; closing it with a "
		             "straight line", tok_name(s->kw));
		add_line(E, out, last, out->c[start_pieces].p0);
	}
}

/* The spline pieces of a lathe profile: no closing, every piece in turn. */
static void open_splines(struct eval *E, struct sink *s, const struct outline_build *b, double (*P)[2],
                         int n, struct pieces *out)
{
	enum spline sp = b->spline;
	int need = spline_span(sp) + 1;
	if (n < need || (sp == SP_BEZIER && n % 4 != 0))
		eval_fail(E, s->loc, "lathe with %s needs %s, found %d points", spline_name(sp),
		          sp == SP_BEZIER ? "a multiple of 4 points" : sp == SP_LINEAR ? "at least 2 points"
		          : sp == SP_QUADRATIC ? "at least 3 points" : "at least 4 points", n);
	for (int i = 0; i + spline_span(sp) < n; i += sp == SP_BEZIER ? 4 : 1)
		add_spline(E, out, sp, P, i);
}

static void to_outline(struct eval *E, const struct pieces *p, bool nonzero, struct outline *ol)
{
	ol->seg = ARENA_ARRAY(&SC(E)->arena, struct curve2, p->n);
	memcpy(ol->seg, p->c, sizeof *p->c * (size_t)p->n);
	ol->n = p->n;
	ol->nonzero = nonzero;
	outline_finish(ol);
}

/* The n points after the count at index i. */
static double (*points_after(struct eval *E, const struct outline_build *b, int i, int n))[2]
{
	double (*P)[2] = (double(*)[2])arena_alloc(&E->arena, sizeof(double[2]) * (size_t)n);
	for (int k = 0; k < n; k++)
		want_uv(E, b, i + 1 + k, P[k]);
	return P;
}

/* ---- the primitives --------------------------------------------------------- */

void geom_prism(struct eval *E, struct sink *s, struct object *o)
{
	struct outline_build *b = build_of(E, s);
	const char *usage = "two heights, a point count and the points: prism { h1, h2, n, <a,b>, … }";
	if (b->n < 3)
		eval_fail(E, s->loc, "prism expects %s", usage);
	double h0 = want_float(E, b, 0), h1 = want_float(E, b, 1);
	int n = want_count(E, s, b, 2, 3, usage);
	if (h0 == h1)
		eval_fail(E, b->loc[1], "prism has zero height (both heights are %g)", h0);
	double (*P)[2] = points_after(E, b, 2, n);
	struct pieces pc = {0};
	closed_splines(E, s, b, P, n, 3, &pc);
	struct extrusion *e = NEW(E, struct extrusion);
	e->part = NEW(E, struct outline);
	e->nparts = 1;
	to_outline(E, &pc, false, e->part);
	e->nseg = pc.n;
	e->h0 = fmin(h0, h1), e->h1 = fmax(h0, h1);
	e->conic = b->conic;
	e->open = (o->flags & OF_OPEN) != 0;
	memcpy(e->lo, e->part->lo, sizeof e->lo);
	memcpy(e->hi, e->part->hi, sizeof e->hi);
	o->g.prism.e = e;
}

void geom_lathe(struct eval *E, struct sink *s, struct object *o)
{
	struct outline_build *b = build_of(E, s);
	int n = want_count(E, s, b, 0, 2, "a point count and the points: lathe { n, <r,y>, … }");
	double (*P)[2] = points_after(E, b, 0, n);
	struct pieces pc = {0};
	open_splines(E, s, b, P, n, &pc);
	struct revolution *r = NEW(E, struct revolution);
	to_outline(E, &pc, false, &r->ol);
	if (!(r->ol.hi[1] > r->ol.lo[1]))
		eval_fail(E, s->loc, "lathe profile has no height (every point has y = %g)", r->ol.lo[1]);
	o->g.lathe.r = r;
}

void geom_polygon(struct eval *E, struct sink *s, struct object *o)
{
	struct outline_build *b = build_of(E, s);
	int n = want_count(E, s, b, 0, 3, "a point count and the points: polygon { n, <p0>, <p1>, … }");
	struct vec3 *P = ARENA_ARRAY(&E->arena, struct vec3, n);
	for (int k = 0; k < n; k++) {
		const struct value *v = &b->v[1 + k];
		if (v->kind != V_VECTOR)
			eval_fail(E, b->loc[1 + k], "expected a point, found %s", val_type_name(v));
		P[k] = v3(v->v[0], v->v[1], v->n > 2 ? v->v[2] : 0);
	}
	/* Newell's normal of the sub-polygons (its length: twice the area) */
	struct vec3 nrm = v3(0, 0, 0);
	for (int k = 0; k < n; k++) {
		struct vec3 a = P[k], c = P[(k + 1) % n];
		nrm = v_add(nrm, v3((a.y - c.y) * (a.z + c.z), (a.z - c.z) * (a.x + c.x), (a.x - c.x) * (a.y + c.y)));
	}
	if (!(v_len(nrm) > 0))
		eval_fail(E, s->loc, "degenerate polygon (its points are collinear)");
	nrm = v_norm(nrm);
	struct vec3 e1 = fabs(nrm.x) < 0.9 ? v3(1, 0, 0) : v3(0, 0, 1);
	e1 = v_norm(v_sub(e1, v_scale(nrm, v_dot(e1, nrm))));
	struct vec3 e2 = v_cross(nrm, e1);
	double (*Q)[2] = (double(*)[2])arena_alloc(&E->arena, sizeof(double[2]) * (size_t)n);
	for (int k = 0; k < n; k++) {
		struct vec3 d = v_sub(P[k], P[0]);
		Q[k][0] = v_dot(d, e1);
		Q[k][1] = v_dot(d, e2);
	}
	struct pieces pc = {0};
	struct outline_build lin = *b;
	lin.spline = SP_LINEAR;
	closed_splines(E, s, &lin, Q, n, 1, &pc);
	struct flat_outline *f = NEW(E, struct flat_outline);
	to_outline(E, &pc, false, &f->ol);
	double *dst[4] = {f->o, f->e1, f->e2, f->n};
	struct vec3 src[4] = {P[0], e1, e2, nrm};
	for (int k = 0; k < 4; k++)
		dst[k][0] = src[k].x, dst[k][1] = src[k].y, dst[k][2] = src[k].z;
	o->g.polygon.f = f;
}

/* POV-Ray's sor piece between points i+1 and i+2: the cubic in y through
 * both squared radii, with the slopes of the squared radius estimated from
 * the neighbours. */
static void sor_piece(double (*P)[2], int i, struct sor_piece *pc)
{
	double w0 = P[i + 1][1], w1 = P[i + 2][1], h = w1 - w0;
	double k0 = P[i + 1][0] * P[i + 1][0], k1 = P[i + 2][0] * P[i + 2][0];
	double m0 = 2 * P[i + 1][0] * (P[i + 2][0] - P[i][0]) / (P[i + 2][1] - P[i][1]);
	double m1 = 2 * P[i + 2][0] * (P[i + 3][0] - P[i + 1][0]) / (P[i + 3][1] - P[i + 1][1]);
	double c2 = (3 * (k1 - k0) / h - 2 * m0 - m1) / h, c3 = (m0 + m1 - 2 * (k1 - k0) / h) / (h * h);
	pc->A = c3;
	pc->B = c2 - 3 * c3 * w0;
	pc->C = m0 - 2 * c2 * w0 + 3 * c3 * w0 * w0;
	pc->D = k0 - m0 * w0 + c2 * w0 * w0 - c3 * w0 * w0 * w0;
	pc->y0 = w0;
	pc->y1 = w1;
	/* the largest radius: at the ends or where r² turns */
	double d[3] = {pc->C, 2 * pc->B, 3 * pc->A}, r[2], best = fmax(k0, k1);
	int m = outline_roots(d, 2, w0, w1, r);
	for (int j = 0; j < m; j++)
		best = fmax(best, ((pc->A * r[j] + pc->B) * r[j] + pc->C) * r[j] + pc->D);
	pc->rmax = sqrt(fmax(best, 0));
}

void geom_sor(struct eval *E, struct sink *s, struct object *o)
{
	struct outline_build *b = build_of(E, s);
	int n = want_count(E, s, b, 0, 4, "a point count and the points: sor { n, <r,y>, … }");
	double (*P)[2] = points_after(E, b, 0, n);
	/* the heights rise along the curve (P[1] … P[n-2]); the two end points,
	 * which only set slopes, may repeat their neighbour's height */
	for (int k = 1; k < n; k++) {
		bool curve = k >= 2 && k <= n - 2;
		if (curve ? !(P[k][1] > P[k - 1][1]) : !(P[k][1] >= P[k - 1][1]))
			eval_fail(E, b->loc[1 + k], "sor points must rise: y = %g after %g", P[k][1], P[k - 1][1]);
	}
	struct sor_shape *S = NEW(E, struct sor_shape);
	S->n = n - 3;
	S->p = ARENA_ARRAY(&SC(E)->arena, struct sor_piece, S->n);
	for (int i = 0; i < S->n; i++) {
		sor_piece(P, i, &S->p[i]);
		S->rmax = fmax(S->rmax, S->p[i].rmax);
	}
	S->ylo = S->p[0].y0;
	S->yhi = S->p[S->n - 1].y1;
	S->rbase = fabs(P[1][0]);
	S->rcap = fabs(P[n - 2][0]);
	o->g.sor.s = S;
}

void geom_text(struct eval *E, struct sink *s, struct object *o)
{
	struct outline_build *b = build_of(E, s);
	const char *usage = "ttf \"font.ttf\" \"string\" thickness, offset";
	if (!b->font)
		eval_fail(E, s->loc, "text expects %s (only TrueType fonts are supported)", usage);
	if (b->n != 3 || b->v[0].kind != V_STRING)
		eval_fail(E, b->n ? b->loc[0] : s->loc, "text expects %s", usage);
	double th = want_float(E, b, 1);
	struct vec3 off = b->v[2].kind == V_FLOAT ? v3(b->v[2].v[0], b->v[2].v[0], b->v[2].v[0])
	                                          : val_want_vec3(E, &b->v[2], b->loc[2]);
	if (th == 0)
		eval_fail(E, b->loc[1], "text thickness must not be 0");
	/* POV-Ray adds ".ttf" to a name it cannot find */
	const char *name = b->font;
	size_t nl = strlen(name);
	if (nl < 4 || strcmp(name + nl - 4, ".ttf") != 0) {
		char *withext = ARENA_ARRAY(&E->arena, char, nl + 5);
		memcpy(withext, name, nl);
		memcpy(withext + nl, ".ttf", 5);
		char *plain = eval_try_file(E, name, b->font_loc), *with = plain ? NULL : eval_try_file(E, withext, b->font_loc);
		if (with)
			name = withext;
		free(plain);
		free(with);
	}
	char *found = eval_find_file(E, name, b->font_loc, "font file", NULL);
	if (E->opt->on_file)
		E->opt->on_file(found, E->opt->on_file_ctx);
	char *path = eval_strdup(E, found, (int)strlen(found)); /* font_text may fail: nothing to free then */
	free(found);
	struct extrusion *e = font_text(E, path, b->font, b->font_loc, b->v[0].p.s, b->v[0].n, b->loc[0], th, off);
	e->open = false;
	o->g.text.e = e;
}
