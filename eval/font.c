/* SPDX-License-Identifier: MIT */
/* font.c: the glyph outlines of text { ttf "font" "string" … } through
 * FreeType, placed as POV-Ray places them (docs/design.md §2, "Outline
 * primitives").
 *
 * Glyphs are read unscaled and unhinted, so their quadratic (TrueType) or
 * cubic (CFF) pieces are the font's own, in font units; one unit of the
 * scene is one em (font units / units_per_EM). The pen follows POV-Ray: the
 * first glyph is moved so that its left edge is at x = 0 and the pen then
 * stands at advance − left bearing; every later glyph is drawn at the pen
 * plus the pair's kerning, and the pen moves on by advance + kerning; after
 * each glyph the pen also moves by the offset's x and y (POV-Ray ignores its
 * z). The outlines go into the text object's sweep frame (a,b) = (x, −y)
 * (tracer/shapes/text.c). */
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H

#include <math.h>
#include <string.h>

#include "../tracer/shapes/outline.h"
#include "internal.h"

/* The pieces of one glyph as FreeType walks its outline. */
struct walk {
	struct eval *E;
	struct curve2 *c;
	int n, cap;
	double scale, dx, dy;   /* font units → em, and the glyph's position */
	double start[2], at[2]; /* the contour's first point, the current point */
	bool open;              /* a contour is being drawn */
};

static void to_ab(const struct walk *w, const FT_Vector *v, double out[2])
{
	out[0] = (double)v->x * w->scale + w->dx;
	out[1] = -((double)v->y * w->scale + w->dy);
}

static void push(struct walk *w, const double cx[4], const double cy[4], const double p1[2])
{
	if (w->n == w->cap) {
		int cap = w->cap ? 2 * w->cap : 64;
		struct curve2 *c = ARENA_ARRAY(&w->E->arena, struct curve2, cap);
		if (w->n)
			memcpy(c, w->c, sizeof *c * (size_t)w->n);
		w->c = c, w->cap = cap;
	}
	w->c[w->n++] = curve2_make(cx, cy, w->at, p1);
	w->at[0] = p1[0], w->at[1] = p1[1];
}

static void line(struct walk *w, const double p[2])
{
	if (p[0] == w->at[0] && p[1] == w->at[1])
		return; /* a repeated point: no piece */
	double cx[4] = {w->at[0], p[0] - w->at[0], 0, 0}, cy[4] = {w->at[1], p[1] - w->at[1], 0, 0};
	push(w, cx, cy, p);
}

static void close_contour(struct walk *w)
{
	if (w->open)
		line(w, w->start);
	w->open = false;
}

static int move_to(const FT_Vector *to, void *user)
{
	struct walk *w = user;
	close_contour(w);
	to_ab(w, to, w->start);
	w->at[0] = w->start[0], w->at[1] = w->start[1];
	w->open = true;
	return 0;
}

static int line_to(const FT_Vector *to, void *user)
{
	struct walk *w = user;
	double p[2];
	to_ab(w, to, p);
	line(w, p);
	return 0;
}

static int conic_to(const FT_Vector *ctl, const FT_Vector *to, void *user)
{
	struct walk *w = user;
	double c[2], p[2], cx[4] = {0}, cy[4] = {0};
	to_ab(w, ctl, c);
	to_ab(w, to, p);
	for (int k = 0; k < 2; k++) {
		double *q = k ? cy : cx, a = w->at[k];
		q[0] = a, q[1] = 2 * (c[k] - a), q[2] = a - 2 * c[k] + p[k];
	}
	push(w, cx, cy, p);
	return 0;
}

static int cubic_to(const FT_Vector *c1, const FT_Vector *c2, const FT_Vector *to, void *user)
{
	struct walk *w = user;
	double b[2], c[2], p[2], cx[4], cy[4];
	to_ab(w, c1, b);
	to_ab(w, c2, c);
	to_ab(w, to, p);
	for (int k = 0; k < 2; k++) {
		double *q = k ? cy : cx, a = w->at[k];
		q[0] = a, q[1] = 3 * (b[k] - a), q[2] = 3 * (a - 2 * b[k] + c[k]);
		q[3] = -a + 3 * b[k] - 3 * c[k] + p[k];
	}
	push(w, cx, cy, p);
	return 0;
}

/* The next character of a UTF-8 string (a byte that is not UTF-8 stands
 * for itself, as Latin-1). */
static unsigned next_char(const unsigned char *s, int len, int *i)
{
	unsigned c = s[*i];
	int extra = c >= 0xF0 && c < 0xF8 ? 3 : c >= 0xE0 ? 2 : c >= 0xC0 ? 1 : 0;
	if (c < 0x80 || extra == 0 || *i + extra >= len) {
		(*i)++;
		return c;
	}
	unsigned v = c & (0x3F >> extra);
	for (int k = 1; k <= extra; k++) {
		if ((s[*i + k] & 0xC0) != 0x80) {
			(*i)++;
			return c;
		}
		v = v << 6 | (s[*i + k] & 0x3F);
	}
	*i += extra + 1;
	return v;
}

/* The glyph of character ch: Unicode first; a symbol font (POV-Ray's
 * povlogo.ttf) maps its characters at U+F000 + ch. 0 when absent. */
static FT_UInt glyph_of(FT_Face face, unsigned ch)
{
	FT_UInt g = FT_Get_Char_Index(face, ch);
	if (g == 0 && face->charmap && face->charmap->encoding == FT_ENCODING_MS_SYMBOL)
		g = FT_Get_Char_Index(face, 0xF000 + ch);
	return g;
}

struct font_job {
	FT_Library lib;
	FT_Face face;
};

static _Noreturn void font_fail(struct eval *E, struct font_job *j, struct srcloc loc, bool missing,
                                const char *msg, const char *name, int err)
{
	if (j->face)
		FT_Done_Face(j->face);
	if (j->lib)
		FT_Done_FreeType(j->lib);
	if (missing)
		E->missing = 1;
	eval_fail(E, loc, "%s '%s' (FreeType error %d)", msg, name, err);
}

struct extrusion *font_text(struct eval *E, const char *path, const char *name, struct srcloc floc,
                            const char *text, int len, struct srcloc tloc, double thickness,
                            struct vec3 offset)
{
	struct font_job j = {0};
	int err = FT_Init_FreeType(&j.lib);
	if (err)
		font_fail(E, &j, floc, false, "cannot start FreeType for font file", name, err);
	err = FT_New_Face(j.lib, path, 0, &j.face);
	if (err)
		font_fail(E, &j, floc, true, err == FT_Err_Unknown_File_Format ? "not a font file:"
		          : "cannot read font file", name, err);
	if (!FT_IS_SCALABLE(j.face) || j.face->units_per_EM == 0)
		font_fail(E, &j, floc, true, "font file has no outlines:", name, 0);
	if (FT_Select_Charmap(j.face, FT_ENCODING_UNICODE) != 0 && j.face->num_charmaps > 0)
		FT_Set_Charmap(j.face, j.face->charmaps[0]);
	double scale = 1.0 / j.face->units_per_EM, pen_x = 0, pen_y = 0;
	struct extrusion *e = NEW(E, struct extrusion);
	e->part = ARENA_ARRAY(&SC(E)->arena, struct outline, len > 0 ? len : 1);
	FT_Outline_Funcs funcs = {move_to, line_to, conic_to, cubic_to, 0, 0};
	FT_UInt prev = 0;
	for (int i = 0, k = 0; i < len; k++) {
		unsigned ch = next_char((const unsigned char *)text, len, &i);
		FT_UInt g = glyph_of(j.face, ch);
		if (g == 0)
			diag_warning(E->diag, tloc, "character U+%04X is not in font '%s'; its missing-glyph "
			             "shape is used", ch, name);
		err = FT_Load_Glyph(j.face, g, FT_LOAD_NO_SCALE | FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP);
		if (err || j.face->glyph->format != FT_GLYPH_FORMAT_OUTLINE)
			font_fail(E, &j, floc, true, "broken glyph in font file", name, err);
		double adv = (double)j.face->glyph->metrics.horiAdvance, lsb = (double)j.face->glyph->metrics.horiBearingX;
		struct walk w = {.E = E, .scale = scale, .dy = pen_y};
		if (k == 0) {
			w.dx = -lsb * scale;
			pen_x = (adv - lsb) * scale;
		} else {
			FT_Vector kern = {0, 0};
			if (FT_HAS_KERNING(j.face) && FT_Get_Kerning(j.face, prev, g, FT_KERNING_UNSCALED, &kern) == 0)
				kern.x = kern.x < -(FT_Pos)j.face->units_per_EM ? -(FT_Pos)j.face->units_per_EM : kern.x;
			w.dx = pen_x + (double)kern.x * scale;
			pen_x += (adv + (double)kern.x) * scale;
		}
		err = FT_Outline_Decompose(&j.face->glyph->outline, &funcs, &w);
		if (err)
			font_fail(E, &j, floc, true, "broken glyph outline in font file", name, err);
		close_contour(&w);
		pen_x += offset.x;
		pen_y += offset.y;
		prev = g;
		if (w.n == 0)
			continue; /* a space */
		struct outline *ol = &e->part[e->nparts++];
		ol->seg = ARENA_ARRAY(&SC(E)->arena, struct curve2, w.n);
		memcpy(ol->seg, w.c, sizeof *w.c * (size_t)w.n);
		ol->n = w.n;
		ol->nonzero = true;
		ol->first = e->nseg;
		e->nseg += w.n;
		outline_finish(ol);
	}
	FT_Done_Face(j.face);
	FT_Done_FreeType(j.lib);
	if (e->nparts == 0) {
		diag_warning(E->diag, tloc, "text has no visible glyphs (the string is empty or only spaces)");
		e->lo[0] = e->lo[1] = e->hi[0] = e->hi[1] = 0;
	} else {
		e->lo[0] = e->lo[1] = INFINITY;
	e->hi[0] = e->hi[1] = -INFINITY;
	for (int i = 0; i < e->nparts; i++)
		for (int a = 0; a < 2; a++) {
			e->lo[a] = fmin(e->lo[a], e->part[i].lo[a]);
			e->hi[a] = fmax(e->hi[a], e->part[i].hi[a]);
		}
	}
	e->h0 = fmin(0, thickness);
	e->h1 = fmax(0, thickness);
	e->zaxis = true;
	return e;
}
