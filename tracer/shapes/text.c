/* SPDX-License-Identifier: MIT */
/* text.c: text { ttf "font" "string" thickness, offset }: the glyph outlines
 * of a TrueType font (read by eval/font.c) in the x-y plane, baseline at
 * y = 0, one unit per em, extruded from z = 0 to z = thickness.
 *
 * Everything but the dump is the extruded outline of prism.c, in the sweep
 * frame (a,h,b) = (x, z, −y), with one outline part per glyph (rays skip a
 * glyph by its box) and TrueType's nonzero fill rule. So (u,v) is prism's:
 * v ∈ [0,⅓] the front face (z = 0), [⅓,⅔] the side walls, [⅔,1] the back
 * face (z = thickness); docs/parametrisations.md. */
#include "extrude.h"

static void tx_dump(const struct object *o, FILE *out)
{
	const struct extrusion *e = o->g.text.e;
	fprintf(out, "glyphs %d pieces %d thickness %.6g bounds <%.6g, %.6g>-<%.6g, %.6g>", e->nparts,
	        e->nseg, e->h1 - e->h0, e->lo[0] + 0.0, -e->hi[1] + 0.0, e->hi[0] + 0.0,
	        -e->lo[1] + 0.0);
}

const struct prim_ops shape_text_ops = {
	ext_intersect, ext_inside, ext_bounds, ext_uv_point, ext_uv_range, ext_cell_area, tx_dump, NULL,
};
