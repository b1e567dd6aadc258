/* SPDX-License-Identifier: MIT */
/* xform.h: 4x4 affine transforms with their inverses (column-vector convention). */
#ifndef ARVO_XFORM_H
#define ARVO_XFORM_H

#include <stdbool.h>

#include "vec.h"

/* p' = m·p for points (bottom row implied 0 0 0 1); inv is m's inverse. */
struct xform {
	double m[3][4];   /* object → world */
	double inv[3][4]; /* world → object */
};

struct xform xf_identity(void);
/* The identity, for frames that need no transform. */
extern const struct xform xf_ident;
struct xform xf_translate(struct vec3 t);
struct xform xf_scale(struct vec3 s);
/* POV-Ray's rotate <a,b,c>: degrees about x, then y, then z. */
struct xform xf_rotate(struct vec3 deg);
/* Rotation by deg degrees about an arbitrary axis (POV-Ray vaxis_rotate's sense). */
struct xform xf_axis_rotate(struct vec3 axis, double deg);
/* POV-Ray's matrix <…12 values…> (row-vector layout, last row the translation).
 * Returns false when the matrix is singular. */
bool xf_from_pov_matrix(const double v[12], struct xform *out);
/* Applies a, then b: the result maps p to b(a(p)). */
struct xform xf_then(struct xform a, struct xform b);
struct xform xf_inverse(struct xform a);
bool xf_is_identity(const struct xform *a);

struct vec3 xf_point(const struct xform *a, struct vec3 p);
struct vec3 xf_vector(const struct xform *a, struct vec3 v);
/* Transforms a normal by the inverse transpose (result not normalised). */
struct vec3 xf_normal(const struct xform *a, struct vec3 n);
struct vec3 xf_inv_point(const struct xform *a, struct vec3 p);
struct vec3 xf_inv_vector(const struct xform *a, struct vec3 v);
/* Bounds of a transformed box. */
struct bbox xf_bbox(const struct xform *a, struct bbox b);

#endif
