/* SPDX-License-Identifier: MIT */
/* camera.c: perspective and orthographic cameras with depth of field. */
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
	struct vec3 film = v_add(v_scale(c->right, sx - 0.5), v_scale(c->up, 0.5 - sy));
	struct ray r;
	if (c->kind == CAM_ORTHOGRAPHIC) {
		r.o = v_add(c->loc, film);
		r.d = c->dir;
	} else {
		r.o = c->loc;
		r.d = v_add(c->dir, film);
	}
	if (c->aperture > 0) {
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
