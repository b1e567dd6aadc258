/* SPDX-License-Identifier: MIT */
/* polygon.c: clipping, moments and self-crossing splits of plane polygons
 * (see polygon.h). */
#include "polygon.h"

#include <math.h>
#include <stdlib.h>

#include "../../common/arena.h"

double poly_area(const struct pt2 *p, int n)
{
	double s = 0;
	for (int i = 1; i + 1 < n; i++) /* a fan about p[0]: small cross products */
		s += (p[i].x - p[0].x) * (p[i + 1].y - p[0].y) - (p[i + 1].x - p[0].x) * (p[i].y - p[0].y);
	return 0.5 * s;
}

/* Green's theorem over the edges, corners taken relative to p[0]:
 *   2∫1 = Σ c_k,  6∫x = Σ (x_k + x_k+1) c_k,  6∫y = Σ (y_k + y_k+1) c_k,
 *   24∫xy = Σ (x_k y_k+1 + 2 x_k y_k + 2 x_k+1 y_k+1 + x_k+1 y_k) c_k,
 * with c_k = x_k y_k+1 − x_k+1 y_k. Dividing by 2, 6 and 24 (rather than
 * multiplying by reciprocals) keeps results exact for small integer corners. */
struct moments poly_moments(const struct pt2 *p, int n, struct pt2 o)
{
	double a = 0, sx = 0, sy = 0, sxy = 0;
	/* the two edges at p[0] are left out: a corner there is (0, 0) exactly,
	 * so their c_k is ±0 and all they would add to a sum is ±0, which
	 * leaves it as it is (a sum that starts at +0 is never −0) for finite
	 * corners */
	double x1 = n > 1 ? p[1].x - p[0].x : 0, y1 = n > 1 ? p[1].y - p[0].y : 0;
	for (int k = 1; k + 1 < n; k++) {
		double x0 = x1, y0 = y1; /* p[k] − p[0], as the previous edge's end */
		x1 = p[k + 1].x - p[0].x, y1 = p[k + 1].y - p[0].y;
		double c = x0 * y1 - x1 * y0;
		a += c;
		sx += (x0 + x1) * c;
		sy += (y0 + y1) * c;
		sxy += (x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0) * c;
	}
	struct moments m = {a / 2, sx / 6, sy / 6, sxy / 24};
	double dx = p[0].x - o.x, dy = p[0].y - o.y; /* shift the origin: x → x + dx */
	return (struct moments){m.a, m.x + dx * m.a, m.y + dy * m.a, m.xy + dx * m.y + dy * m.x + dx * dy * m.a};
}

#define ALWAYS_INLINE __attribute__((always_inline)) static inline

ALWAYS_INLINE double coord(struct pt2 p, int axis) { return axis ? p.y : p.x; }

/* The point where edge p→q meets coordinate b: exactly b on the axis, the
 * other coordinate interpolated from p (the same edge clipped from either
 * side gives the same point). */
ALWAYS_INLINE struct pt2 cross_at(struct pt2 p, struct pt2 q, int axis, double b)
{
	double t = (b - coord(p, axis)) / (coord(q, axis) - coord(p, axis));
	if (axis)
		return (struct pt2){p.x + t * (q.x - p.x), b};
	return (struct pt2){b, p.y + t * (q.y - p.y)};
}

/* One Sutherland–Hodgman pass: keeps coordinate ≥ b (above) or ≤ b. Each
 * edge emits at most two corners, so out needs room for 2n. Inlined where
 * axis and above are constants (clip_slab): a copy for each. */
ALWAYS_INLINE int clip_side(const struct pt2 *p, int n, int axis, double b, bool above, struct pt2 *out)
{
	int k = 0;
	struct pt2 a = p[n - 1];
	bool ina = above ? coord(a, axis) >= b : coord(a, axis) <= b; /* each corner's side, worked out once */
	for (int i = 0; i < n; i++) {
		struct pt2 c = p[i];
		bool inc = above ? coord(c, axis) >= b : coord(c, axis) <= b;
		if (ina != inc)
			out[k++] = cross_at(a, c, axis, b);
		if (inc)
			out[k++] = c;
		a = c, ina = inc;
	}
	return k;
}

/* poly_clip_slab on a constant axis, the corners' least and greatest
 * coordinate on it given (mn, mx). */
ALWAYS_INLINE int clip_range(const struct pt2 *p, int n, int axis, double lo, double hi, double mn, double mx,
                             struct pt2 *out, struct pt2 *tmp)
{
	if (mx < lo || mn > hi) /* wholly outside; a bound only touched still clips */
		return 0;
	bool cut_lo = mn < lo, cut_hi = mx > hi; /* the sides that cut anything */
	if (cut_lo && cut_hi) {
		n = clip_side(p, n, axis, lo, true, tmp);
		return n < 3 ? 0 : clip_side(tmp, n, axis, hi, false, out);
	}
	if (cut_lo)
		return clip_side(p, n, axis, lo, true, out);
	if (cut_hi)
		return clip_side(p, n, axis, hi, false, out);
	for (int i = 0; i < n; i++)
		out[i] = p[i];
	return n;
}

/* poly_clip_slab on a constant axis. */
ALWAYS_INLINE int clip_slab(const struct pt2 *p, int n, int axis, double lo, double hi, struct pt2 *out,
                            struct pt2 *tmp)
{
	double mn = coord(p[0], axis), mx = mn;
	for (int i = 1; i < n; i++) {
		double c = coord(p[i], axis); /* finite: no fmin/fmax (libm calls) needed */
		mn = c < mn ? c : mn;
		mx = c > mx ? c : mx;
	}
	return clip_range(p, n, axis, lo, hi, mn, mx, out, tmp);
}

int poly_clip_slab(const struct pt2 *p, int n, int axis, double lo, double hi, struct pt2 *out,
                   struct pt2 *tmp)
{
	return axis ? clip_slab(p, n, 1, lo, hi, out, tmp) : clip_slab(p, n, 0, lo, hi, out, tmp);
}

int poly_clip_range(const struct pt2 *p, int n, int axis, double lo, double hi, double mn, double mx,
                    struct pt2 *out, struct pt2 *tmp)
{
	return axis ? clip_range(p, n, 1, lo, hi, mn, mx, out, tmp) : clip_range(p, n, 0, lo, hi, mn, mx, out, tmp);
}

static double orient(struct pt2 a, struct pt2 b, struct pt2 c)
{
	return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool poly_crossing(const struct pt2 *p, int n, int *a, int *b, struct pt2 *x)
{
	for (int i = 0; i < n; i++) {
		struct pt2 p0 = p[i], p1 = p[i + 1 < n ? i + 1 : 0];
		for (int j = i + 2; j < n; j++) {
			if (i == 0 && j == n - 1) /* adjacent through the closing edge */
				continue;
			struct pt2 q0 = p[j], q1 = p[j + 1 < n ? j + 1 : 0];
			double o0 = orient(q0, q1, p0), o1 = orient(q0, q1, p1);
			if (!((o0 < 0 && o1 > 0) || (o0 > 0 && o1 < 0)))
				continue;
			double o2 = orient(p0, p1, q0), o3 = orient(p0, p1, q1);
			if (!((o2 < 0 && o3 > 0) || (o2 > 0 && o3 < 0)))
				continue;
			double t = o0 / (o0 - o1);
			*a = i;
			*b = j;
			*x = (struct pt2){p0.x + t * (p1.x - p0.x), p0.y + t * (p1.y - p0.y)};
			return true;
		}
	}
	return false;
}

/* Room for `more` corners and one more loop. */
static void loops_reserve(struct loops *l, int more)
{
	if (l->npt + more > l->cap_pt) {
		int cap = l->cap_pt ? 2 * l->cap_pt : 64;
		while (cap < l->npt + more)
			cap *= 2;
		l->pt = mem_realloc(l->pt, (size_t)cap * sizeof *l->pt);
		l->cap_pt = cap;
	}
	if (l->n + 1 > l->cap_loop) {
		int cap = l->cap_loop ? 2 * l->cap_loop : 8;
		l->start = mem_realloc(l->start, (size_t)cap * sizeof *l->start);
		l->len = mem_realloc(l->len, (size_t)cap * sizeof *l->len);
		l->cap_loop = cap;
	}
}

/* Writes the loop x, src[from], src[from+1], … (count corners after x,
 * indices modulo n) as loop k (k == l->n appends); the room is reserved. */
static void loop_put(struct loops *l, int k, struct pt2 x, const struct pt2 *src, int n, int from, int count)
{
	int s = l->npt;
	l->pt[l->npt++] = x;
	for (int i = 0; i < count; i++)
		l->pt[l->npt++] = src[(from + i) % n];
	l->start[k] = s;
	l->len[k] = count + 1;
	if (k == l->n)
		l->n++;
}

void poly_split(struct loops *l, const struct pt2 *p, int n)
{
	l->n = l->npt = 0;
	loops_reserve(l, n);
	l->start[0] = 0;
	l->len[0] = n;
	for (int i = 0; i < n; i++)
		l->pt[i] = p[i];
	l->n = 1;
	l->npt = n;
	for (int k = n > POLY_SPLIT_MAX; k < l->n;) {
		int a, b;
		struct pt2 x;
		if (!poly_crossing(l->pt + l->start[k], l->len[k], &a, &b, &x)) {
			k++;
			continue;
		}
		int len = l->len[k];
		loops_reserve(l, 2 * len + 4); /* parent copy + both children */
		struct pt2 *par = l->pt + l->npt; /* a stable copy of the parent */
		for (int i = 0; i < len; i++)
			par[i] = l->pt[l->start[k] + i];
		l->npt += len;
		loop_put(l, k, x, par, len, a + 1, b - a);           /* x, p[a+1..b] */
		loop_put(l, l->n, x, par, len, b + 1, len - b + a); /* x, p[b+1..], p[..a] */
	}
}

size_t loops_bytes(const struct loops *l)
{
	return (size_t)l->cap_pt * sizeof *l->pt + (size_t)l->cap_loop * (sizeof *l->start + sizeof *l->len);
}

void loops_free(struct loops *l)
{
	free(l->pt);
	free(l->start);
	free(l->len);
	*l = (struct loops){0};
}
