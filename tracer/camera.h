/* SPDX-License-Identifier: MIT */
/* camera.h: primary rays from POV-Ray's camera vectors.
 *
 * The image spans right × up at distance |direction| from location: a pixel
 * at film coordinates (sx, sy) ∈ [0,1)² (sx left→right, sy top→bottom) looks
 * through location + direction + (sx-½)·right + (½-sy)·up (perspective). An
 * orthographic camera shoots parallel rays along direction from location +
 * (sx-½)·right + (½-sy)·up, so the view is as wide and high as right and up
 * are long. Depth of field (aperture > 0) moves the ray origin over a disc of
 * diameter aperture in the right/up plane and aims it at the point the
 * pinhole ray meets the focal plane (through focal_point, normal to
 * direction). */
#ifndef ARVO_CAMERA_H
#define ARVO_CAMERA_H

#include <stdbool.h>

#include "../common/vec.h"
#include "scene.h"

struct cam {
	enum camera_kind kind; /* perspective or orthographic */
	struct vec3 loc;       /* location */
	struct vec3 dir;       /* direction (its length is the film distance) */
	struct vec3 right, up; /* film edges */
	struct vec3 fwd;       /* unit direction */
	struct vec3 lu, lv;    /* unit lens axes (along right and up) */
	double aperture;       /* lens diameter (0: pinhole) */
	double focal;          /* distance of the focal plane along fwd */
	int blur_samples;      /* POV blur_samples (minimum samples per pixel) */
	double angle, v_angle; /* fisheye, ultra_wide_angle, cylinder, spherical: radians */
	double len_right, len_up; /* |right| and |up| before they were normalised */
};

/* Prepares c from the scene's resolved camera. */
void cam_setup(struct cam *c, const struct camera *sc);
/* Does the camera have depth of field? */
bool cam_has_dof(const struct cam *c);
/* The primary ray through film point (sx, sy); (l1, l2) ∈ [0,1)² pick the
 * lens point (ignored for a pinhole). The direction is not normalised; it
 * is zero where the camera shoots no ray (outside a fisheye's circle), and
 * such a sample is black and uncovered, as in POV-Ray. */
struct ray cam_ray(const struct cam *c, double sx, double sy, double l1, double l2);
/* cam_ray into *r, inline for a perspective camera without a lens (the
 * camera rays of most scenes, one per pixel): the same arithmetic, the
 * same bits. Written field by field: a ray returned by value went through
 * a temporary on the stack, copied at once with loads of other widths
 * than its stores, which the CPU cannot forward (a third of eye_pixels'
 * own time, perf, bench/eye/grid.scn). */
static inline void cam_ray_to(const struct cam *c, double sx, double sy, double l1, double l2, struct ray *r)
{
	if (c->kind != CAM_PERSPECTIVE || c->aperture > 0) {
		*r = cam_ray(c, sx, sy, l1, l2);
		return;
	}
	double x = sx - 0.5, y = 0.5 - sy;
	r->o = c->loc;
	r->d = v_add(c->dir, v_add(v_scale(c->right, x), v_scale(c->up, y)));
}

/* The camera as matrices for row vectors (p' = p·M, translation in the last
 * row, as OpenEXR's m44f attributes and Imath take them), row-major:
 * c2w maps camera space (x right, y up, z along direction: left-handed,
 * OpenEXR's and RenderMan's convention; unit axes) to world space, w2c
 * back; ndc maps a world point, after division by w, to film coordinates
 * (0,0) top left, (1,1) bottom right (OpenEXR's worldToNDC; z/w is 1 for
 * perspective, the depth along direction for orthographic). */
void cam_matrices(const struct cam *c, double c2w[16], double w2c[16], double ndc[16]);

#endif
