/* SPDX-License-Identifier: MIT */
/* extrude.h: the operations of an extruded outline (prism.c), shared by
 * prism and text, whose objects hold a struct extrusion (outline.h). */
#ifndef ARVO_EXTRUDE_H
#define ARVO_EXTRUDE_H

#include "outline.h"
#include "prim.h"

bool ext_intersect(const struct object *o, const struct ray *r, double tmin, double tmax,
                   struct local_hit *lh);
bool ext_inside(const struct object *o, struct vec3 p);
struct bbox ext_bounds(const struct object *o);
bool ext_uv_point(const struct object *o, double u, double v, struct vec3 *p, struct vec3 *dpdu,
                  struct vec3 *dpdv);
struct uv_range ext_uv_range(const struct object *o);
double ext_cell_area(const struct object *o, double u0, double u1, double v0, double v1);

#endif
