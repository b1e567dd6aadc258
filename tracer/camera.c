/* SPDX-License-Identifier: MIT */
/* camera.c: POV-Ray's camera types, with depth of field.
 *
 * With x = sx − ½ and y = ½ − sy (each in [−½, ½]), R, U, D the camera's
 * right, up and direction, and R̂, Û, D̂ them normalised (POV-Ray 3.7's
 * projections, written out in docs/design.md §5):
 *   perspective       D + x·R + y·U
 *   orthographic      D from location + x·R + y·U
 *   fisheye           (a, b) = (2x|R|, 2y|U|), r = |(a,b)|: no ray past
 *                     r = 1; φ = the angle of (a,b), θ = r·angle/2:
 *                     cosφ sinθ R̂ + sinφ sinθ Û + cosθ D̂
 *   ultra_wide_angle  α = x·angle, β = y·angle·|U|/|R|:
 *                     sinα R̂ + sinβ Û + cosα cosβ D̂
 *   panoramic         α = (½ − x)·π, β = y·π: cosα R + tanβ U + sinα D
 *   cylinder 1        α = x·angle: sinα R̂ + y|U| Û + cosα D̂
 *   cylinder 2        β = y·angle: x|R| R̂ + sinβ Û + cosβ D̂
 *   cylinder 3        as 1 without the Û term, from location + y|U| Û
 *   cylinder 4        as 2 without the R̂ term, from location + x|R| R̂
 *   spherical         D turned by y·v_angle about R (upwards), then by
 *                     x·angle about U (to the right)
 *   omnimax           (a, b) = (2x, 2y) fitted to the dome's 1.283458
 *                     aspect; no ray past r = 1 or more than 45° below D;
 *                     θ = 1.411269 r − 0.09439 r³ + 0.25674 r⁵, then as
 *                     fisheye */
#include "camera.h"

#include <math.h>

void cam_setup(struct cam *c, const struct camera *sc)
{
	c->kind = sc->kind;
	c->loc = sc->location;
	c->dir = sc->direction;
	c->right = sc->right;
	c->up = sc->up;
	c->fwd = v_norm(sc->direction);
	c->lu = v_norm(sc->right);
	c->lv = v_norm(sc->up);
	c->aperture = sc->aperture > 0 ? sc->aperture : 0;
	c->blur_samples = sc->blur_samples;
	c->focal = v_dot(v_sub(sc->focal_point, sc->location), c->fwd);
	if (!(c->focal > 1e-9))
		c->focal = v_len(sc->direction);
	c->len_right = v_len(sc->right);
	c->len_up = v_len(sc->up);
	double deg = sc->angle > 0 ? sc->angle : sc->kind == CAM_SPHERICAL ? 360 : 90;
	c->angle = deg * M_PI / 180;
	c->v_angle = (sc->v_angle > 0 ? sc->v_angle : deg / 2) * M_PI / 180;
	if (sc->kind != CAM_PERSPECTIVE && sc->kind != CAM_ORTHOGRAPHIC && sc->kind != CAM_PANORAMIC && /* the rest use unit vectors */
	    sc->kind != CAM_SPHERICAL) {
		c->right = c->lu;
		c->up = c->lv;
		c->dir = c->fwd;
	}
}

/* v turned by angle a about the unit axis k (Rodrigues). */
static struct vec3 turn(struct vec3 v, struct vec3 k, double a)
{
	double ca = cos(a), sa = sin(a);
	return v_add(v_add(v_scale(v, ca), v_scale(v_cross(k, v), sa)), v_scale(k, v_dot(k, v) * (1 - ca)));
}

/* The direction (and origin) of the pinhole ray at (x, y) ∈ [−½, ½]². */
static struct ray pinhole(const struct cam *c, double x, double y)
{
	struct ray r = {c->loc, v3(0, 0, 0)};
	struct vec3 R = c->right, U = c->up, D = c->dir;
	switch (c->kind) {
	case CAM_ORTHOGRAPHIC:
		r.o = v_add(c->loc, v_add(v_scale(R, x), v_scale(U, y)));
		r.d = D;
		break;
	case CAM_FISHEYE: {
		double a = 2 * x * c->len_right, b = 2 * y * c->len_up, rad = sqrt(a * a + b * b);
		if (rad > 1)
			break; /* no ray */
		double phi = rad > 0 ? atan2(b, a) : 0, th = rad * c->angle / 2;
		r.d = v_add(v_add(v_scale(R, cos(phi) * sin(th)), v_scale(U, sin(phi) * sin(th))), v_scale(D, cos(th)));
		break;
	}
	case CAM_ULTRA_WIDE: {
		double a = x * c->angle, b = y * c->angle * c->len_up / c->len_right;
		r.d = v_add(v_add(v_scale(R, sin(a)), v_scale(U, sin(b))), v_scale(D, cos(a) * cos(b)));
		break;
	}
	case CAM_PANORAMIC: {
		double a = (0.5 - x) * M_PI, b = y * M_PI;
		double tb = fabs(b) > M_PI / 2 - 1e-10 ? copysign(1e10, b) : tan(b);
		r.d = v_add(v_add(v_scale(R, cos(a)), v_scale(U, tb)), v_scale(D, sin(a)));
		break;
	}
	case CAM_CYL1: case CAM_CYL3: {
		double a = x * c->angle;
		r.d = v_add(v_scale(R, sin(a)), v_scale(D, cos(a)));
		if (c->kind == CAM_CYL1)
			r.d = v_madd(r.d, U, y * c->len_up);
		else
			r.o = v_madd(c->loc, U, y * c->len_up);
		break;
	}
	case CAM_CYL2: case CAM_CYL4: {
		double b = y * c->angle;
		r.d = v_add(v_scale(U, sin(b)), v_scale(D, cos(b)));
		if (c->kind == CAM_CYL2)
			r.d = v_madd(r.d, R, x * c->len_right);
		else
			r.o = v_madd(c->loc, R, x * c->len_right);
		break;
	}
	case CAM_OMNIMAX: {
		double a = 2 * x, b = 2 * y, asp = c->len_right / c->len_up;
		if (asp > 1.283458) {
			a *= asp / 1.283458;
			b = (b - 1) / 1.283458 + 1;
		} else if (asp > 1) {
			b = (b - 1) / asp + 1;
		} else {
			b /= asp;
		}
		double rad = sqrt(a * a + b * b);
		if (rad > 1)
			break;
		double phi = rad > 0 ? atan2(b, a) : 0;
		double th = rad * (1.411269 + rad * rad * (-0.09439 + rad * rad * 0.25674));
		if (sin(phi) * sin(th) < -cos(th)) /* tan 135° = −1: below 45° under the axis */
			break;
		r.d = v_add(v_add(v_scale(R, cos(phi) * sin(th)), v_scale(U, sin(phi) * sin(th))), v_scale(D, cos(th)));
		break;
	}
	case CAM_SPHERICAL:
		r.d = turn(turn(D, c->lu, -y * c->v_angle), c->lv, x * c->angle);
		break;
	default:
		r.d = v_add(D, v_add(v_scale(R, x), v_scale(U, y)));
	}
	return r;
}

bool cam_has_dof(const struct cam *c)
{
	return c->aperture > 0;
}

/* A uniform point on the unit disc from two numbers in [0,1) (concentric map,
 * so stratified inputs stay stratified). */
static void disc_point(double a, double b, double *x, double *y)
{
	double u = 2 * a - 1, v = 2 * b - 1, r, phi;
	if (u == 0 && v == 0) {
		*x = *y = 0;
		return;
	}
	if (fabs(u) > fabs(v)) {
		r = u;
		phi = (M_PI / 4) * (v / u);
	} else {
		r = v;
		phi = M_PI / 2 - (M_PI / 4) * (u / v);
	}
	*x = r * cos(phi);
	*y = r * sin(phi);
}

struct ray cam_ray(const struct cam *c, double sx, double sy, double l1, double l2)
{
	struct ray r = pinhole(c, sx - 0.5, 0.5 - sy);
	if (c->aperture > 0 && v_dot(r.d, r.d) > 0) {
		double cosd = v_dot(r.d, c->fwd);
		struct vec3 focus = v_madd(r.o, r.d, c->focal / cosd);
		double x, y;
		disc_point(l1, l2, &x, &y);
		double rad = 0.5 * c->aperture;
		r.o = v_add(r.o, v_add(v_scale(c->lu, x * rad), v_scale(c->lv, y * rad)));
		r.d = v_sub(focus, r.o);
	}
	return r;
}

/* The rows of the inverse of the 3×3 matrix whose rows are a, b, c, laid out
 * for row vectors: q = x·a + y·b + z·c gives x = q·ia, y = q·ib, z = q·ic. */
static void inverse_rows(struct vec3 a, struct vec3 b, struct vec3 c, struct vec3 *ia,
                         struct vec3 *ib, struct vec3 *ic)
{
	double det = v_dot(a, v_cross(b, c));
	*ia = v_scale(v_cross(b, c), 1 / det);
	*ib = v_scale(v_cross(c, a), 1 / det);
	*ic = v_scale(v_cross(a, b), 1 / det);
}

/* Fills column col of the row-vector matrix m with p ↦ p·v + k. */
static void set_col(double m[16], int col, struct vec3 v, double k)
{
	m[col] = v.x, m[4 + col] = v.y, m[8 + col] = v.z, m[12 + col] = k;
}

void cam_matrices(const struct cam *c, double c2w[16], double w2c[16], double ndc[16])
{
	struct vec3 r = v_norm(c->right), u = v_norm(c->up), d = c->fwd, ia, ib, ic;
	const struct vec3 rows[4] = {r, u, d, c->loc};
	for (int i = 0; i < 4; i++) {
		c2w[4 * i] = rows[i].x, c2w[4 * i + 1] = rows[i].y, c2w[4 * i + 2] = rows[i].z;
		c2w[4 * i + 3] = i == 3;
	}
	inverse_rows(r, u, d, &ia, &ib, &ic);
	set_col(w2c, 0, ia, -v_dot(c->loc, ia));
	set_col(w2c, 1, ib, -v_dot(c->loc, ib));
	set_col(w2c, 2, ic, -v_dot(c->loc, ic));
	set_col(w2c, 3, v3(0, 0, 0), 1);
	/* film coordinates: q - loc = a·right + b·up + c·direction; the film point
	 * is (½ + a/c, ½ - b/c) (perspective) or (½ + a, ½ - b) (orthographic) */
	inverse_rows(c->right, c->up, c->dir, &ia, &ib, &ic);
	double a0 = -v_dot(c->loc, ia), b0 = -v_dot(c->loc, ib), c0 = -v_dot(c->loc, ic);
	if (c->kind == CAM_ORTHOGRAPHIC) {
		set_col(ndc, 0, ia, a0 + 0.5);
		set_col(ndc, 1, v_neg(ib), 0.5 - b0);
		set_col(ndc, 2, ic, c0);
		set_col(ndc, 3, v3(0, 0, 0), 1);
	} else {
		set_col(ndc, 0, v_madd(ia, ic, 0.5), a0 + 0.5 * c0);
		set_col(ndc, 1, v_madd(v_neg(ib), ic, 0.5), 0.5 * c0 - b0);
		set_col(ndc, 2, ic, c0);
		set_col(ndc, 3, ic, c0);
	}
}
