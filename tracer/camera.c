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
