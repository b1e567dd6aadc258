/* SPDX-License-Identifier: MIT */
/* xform.c: affine transforms. */
#include "xform.h"

#include <string.h>

static void mat_identity(double m[3][4])
{
	memset(m, 0, sizeof(double) * 12);
	m[0][0] = m[1][1] = m[2][2] = 1;
}

/* r = a·b, both affine 3x4 with implied bottom row. */
static void mat_mul(double r[3][4], double a[3][4], double b[3][4])
{
	double t[3][4];
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 4; j++) {
			double s = j == 3 ? a[i][3] : 0;
			for (int k = 0; k < 3; k++)
				s += a[i][k] * b[k][j];
			t[i][j] = s;
		}
	}
	memcpy(r, t, sizeof t);
}

/* Inverts an affine matrix; returns false when singular. */
static bool mat_inverse(double r[3][4], double a[3][4])
{
	double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
	double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
	double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
	double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
	if (!(fabs(det) > 1e-300))
		return false;
	double id = 1.0 / det, t[3][4];
	t[0][0] = c00 * id;
	t[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) * id;
	t[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) * id;
	t[1][0] = c01 * id;
	t[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) * id;
	t[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) * id;
	t[2][0] = c02 * id;
	t[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) * id;
	t[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) * id;
	for (int i = 0; i < 3; i++)
		t[i][3] = -(t[i][0] * a[0][3] + t[i][1] * a[1][3] + t[i][2] * a[2][3]);
	memcpy(r, t, sizeof t);
	return true;
}

const struct xform xf_ident = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}},
                                {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};

struct xform xf_identity(void)
{
	struct xform x;
	mat_identity(x.m);
	mat_identity(x.inv);
	return x;
}

struct xform xf_translate(struct vec3 t)
{
	struct xform x = xf_identity();
	x.m[0][3] = t.x, x.m[1][3] = t.y, x.m[2][3] = t.z;
	x.inv[0][3] = -t.x, x.inv[1][3] = -t.y, x.inv[2][3] = -t.z;
	return x;
}

struct xform xf_scale(struct vec3 s)
{
	struct xform x = xf_identity();
	x.m[0][0] = s.x, x.m[1][1] = s.y, x.m[2][2] = s.z;
	x.inv[0][0] = 1 / s.x, x.inv[1][1] = 1 / s.y, x.inv[2][2] = 1 / s.z;
	return x;
}

/* Rotation by deg degrees about coordinate axis k, as POV-Ray computes it. */
static struct xform rot_axis(int k, double deg)
{
	struct xform x = xf_identity();
	double a = deg * M_PI / 180.0, c = cos(a), s = sin(a);
	/* exact values at multiples of 90 degrees (no 6e-17 residues) */
	if (fmod(deg, 90.0) == 0) {
		long q = ((long)(fmod(deg, 360.0) / 90.0) + 4) % 4; /* (an angle past 2^63 quarter turns, too) */
		c = q == 0 ? 1 : q == 2 ? -1 : 0;
		s = q == 1 ? 1 : q == 3 ? -1 : 0;
	}
	int i = (k + 1) % 3, j = (k + 2) % 3;
	x.m[i][i] = c, x.m[i][j] = -s, x.m[j][i] = s, x.m[j][j] = c;
	x.inv[i][i] = c, x.inv[i][j] = s, x.inv[j][i] = -s, x.inv[j][j] = c;
	return x;
}

struct xform xf_rotate(struct vec3 deg)
{
	struct xform r = xf_identity();
	if (deg.x != 0)
		r = xf_then(r, rot_axis(0, deg.x));
	if (deg.y != 0)
		r = xf_then(r, rot_axis(1, deg.y));
	if (deg.z != 0)
		r = xf_then(r, rot_axis(2, deg.z));
	return r;
}

struct xform xf_axis_rotate(struct vec3 axis, double deg)
{
	struct vec3 u = v_norm(axis);
	double a = deg * M_PI / 180.0, c = cos(a), s = sin(a), t = 1 - c;
	struct xform x = xf_identity();
	double m[3][3] = {
		{t * u.x * u.x + c, t * u.x * u.y - s * u.z, t * u.x * u.z + s * u.y},
		{t * u.x * u.y + s * u.z, t * u.y * u.y + c, t * u.y * u.z - s * u.x},
		{t * u.x * u.z - s * u.y, t * u.y * u.z + s * u.x, t * u.z * u.z + c},
	};
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			x.m[i][j] = m[i][j], x.inv[j][i] = m[i][j];
	return x;
}

bool xf_from_pov_matrix(const double v[12], struct xform *out)
{
	struct xform x = xf_identity();
	for (int r = 0; r < 4; r++)
		for (int c = 0; c < 3; c++)
			x.m[c][r] = v[r * 3 + c];
	if (!mat_inverse(x.inv, x.m))
		return false;
	*out = x;
	return true;
}

struct xform xf_then(struct xform a, struct xform b)
{
	struct xform r;
	mat_mul(r.m, b.m, a.m);
	mat_mul(r.inv, a.inv, b.inv);
	return r;
}

struct xform xf_inverse(struct xform a)
{
	struct xform r;
	memcpy(r.m, a.inv, sizeof r.m);
	memcpy(r.inv, a.m, sizeof r.inv);
	return r;
}

bool xf_is_identity(const struct xform *a)
{
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 4; j++)
			if (a->m[i][j] != (i == j ? 1.0 : 0.0))
				return false;
	return true;
}

static struct vec3 apply_p(double m[3][4], struct vec3 p)
{
	return v3(m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
	          m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
	          m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]);
}

static struct vec3 apply_v(double m[3][4], struct vec3 p)
{
	return v3(m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z,
	          m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z,
	          m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z);
}

struct vec3 xf_point(const struct xform *a, struct vec3 p) { return apply_p((double (*)[4])a->m, p); }
struct vec3 xf_vector(const struct xform *a, struct vec3 v) { return apply_v((double (*)[4])a->m, v); }
struct vec3 xf_inv_point(const struct xform *a, struct vec3 p) { return apply_p((double (*)[4])a->inv, p); }
struct vec3 xf_inv_vector(const struct xform *a, struct vec3 v) { return apply_v((double (*)[4])a->inv, v); }

struct vec3 xf_normal(const struct xform *a, struct vec3 n)
{
	const double (*m)[4] = a->inv;
	return v3(m[0][0] * n.x + m[1][0] * n.y + m[2][0] * n.z,
	          m[0][1] * n.x + m[1][1] * n.y + m[2][1] * n.z,
	          m[0][2] * n.x + m[1][2] * n.y + m[2][2] * n.z);
}

struct bbox xf_bbox(const struct xform *a, struct bbox b)
{
	struct bbox r = bbox_empty();
	if (b.lo.x > b.hi.x)
		return r;
	for (int i = 0; i < 8; i++) {
		struct vec3 p = v3(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
		r = bbox_add(r, xf_point(a, p));
	}
	return r;
}
