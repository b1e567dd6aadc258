/* SPDX-License-Identifier: MIT */
/* illum.c: sparse, tiled illumination maps (see illum.h for the conventions).
 *
 * Storage: nodes live in ILLUM_TILE² tiles allocated on first deposit and found
 * through the window (an array of tile indices over the rectangle where most
 * deposits land, win_fit) or, outside it, an open-addressing hash table keyed
 * by tile coordinates. Both serve bounded domains and the unbounded plane, so
 * memory grows with the number of tiles light reached, never with the
 * surface (docs/design.md §4). A map of white light only is GREY: its tiles
 * hold one channel (struct gacc), until a deposit that needs three makes
 * it colour (ungrey). */
#include "illum.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../../common/arena.h"
#include "../../common/pool.h"
#include "../output/exrout.h"
#include "../output/framebuffer.h"
#include "polygon.h"
#include "../shape.h"

#define TN (ILLUM_TILE * ILLUM_TILE) /* nodes per tile */
#define PLANE_LIMIT 1073741824.0     /* |node index| bound on the plane (2^30) */
#define MAX_NODES (1L << 26)         /* node count bound per bounded axis */
#define SNAP 1e-9                    /* points this close to a node (in spacings) are on it */

/* ==== 128-bit fixed point: value = (hi·2^64 + lo)·2^-96 =================== */

struct fx {
	uint64_t lo, hi; /* low and high 64 bits of the unsigned 128-bit integer */
};

/* Rounds d (≥ 0) to the nearest quantum; saturates at 2^32. */
static inline struct fx fx_from(double d)
{
	struct fx r = {0, 0};
	double m = d * 0x1p96; /* scaling by powers of two is exact here */
	if (m < 0x1p52) /* rint, inline: below 2^52 adding 2^52 rounds to an integer (to even,
	                   as rint does); from 2^52 on a double is one already */
		m = (m + 0x1p52) - 0x1p52;
	if (!(m > 0))
		return r;
	if (!(m < 0x1p128))
		return (struct fx){UINT64_MAX, UINT64_MAX};
	r.hi = (uint64_t)(m * 0x1p-64); /* truncation is floor here (m ≥ 0), and no libm call */
	r.lo = (uint64_t)(m - (double)r.hi * 0x1p64);
	return r;
}

static double fx_to_double(struct fx a) { return (double)a.hi * 0x1p-32 + (double)a.lo * 0x1p-96; }

/* a >> k (k ≥ 0), the bits shifted out dropped. */
static struct fx fx_shr(struct fx a, int k)
{
	if (k <= 0)
		return a;
	if (k >= 128)
		return (struct fx){0, 0};
	if (k >= 64)
		return (struct fx){a.hi >> (k - 64), 0};
	return (struct fx){(a.lo >> k) | (a.hi << (64 - k)), a.hi >> k};
}

/* *a += b, saturating. */
static void fx_add(struct fx *a, struct fx b)
{
	uint64_t lo = a->lo + b.lo, carry = lo < a->lo;
	uint64_t hi = a->hi + b.hi, hi2 = hi + carry;
	if (hi < a->hi || hi2 < hi) {
		a->lo = a->hi = UINT64_MAX;
		return;
	}
	a->lo = lo;
	a->hi = hi2;
}

/* *a += b where the sum cannot pass 2^128 (a map whose energy bound is
 * finite: map_reserve keeps every sum under 2^32 units). */
static void fx_add_fast(struct fx *a, struct fx b)
{
	uint64_t lo = a->lo + b.lo;
	a->hi += b.hi + (lo < b.lo);
	a->lo = lo;
}

/* a − b, given a ≥ b. */
static struct fx fx_sub(struct fx a, struct fx b)
{
	return (struct fx){a.lo - b.lo, a.hi - b.hi - (a.lo < b.lo)};
}

/* ==== the map ============================================================= */

struct acc {
	struct fx e[3];  /* energy per channel */
	float sq[3];     /* Σ (w·e)² per channel (a variance estimate: float is plenty) */
	uint32_t count;  /* deposits with nonzero weight here (saturating) */
};

/* The accumulator of a GREY map's node: its three channels are the same
 * numbers (every deposit so far was white light, as most are), held once. */
struct gacc {
	struct fx e;
	float sq;
	uint32_t count;
};

/* Irradiance is not stored: illum_finish records each node's area (planes:
 * one area for all, m->flat_area) and the isolated ones, and readers divide
 * energy by area, which gives the same numbers for less memory. */
struct tile {
	int32_t ti, tj;    /* tile coordinates (node i = ti·ILLUM_TILE + k) */
	uint32_t iso;      /* bit q: node q is isolated (illum_finish) */
	double *area;      /* TN node areas after illum_finish; NULL on planes */
	union {            /* accumulators, row-major (j then i inside the tile) */
		struct acc n[TN]; /* a colour map's */
		struct gacc g[TN];/* a grey map's: such a tile is allocated only this far (GREY_TILE) */
	};
};

#define GREY_TILE (offsetof(struct tile, g) + sizeof(struct gacc) * TN) /* bytes of a grey tile */

struct axis {
	double lo, hi; /* parameter interval (bounded axes) */
	double step;   /* node spacing in parameter units */
	long n;        /* node count (0: unbounded) */
	bool wraps;    /* periodic: node n ≡ node 0 */
	bool bounded;  /* false on the plane */
};

struct illum_map {
	const struct object *obj; /* the primitive (world space via its xf) */
	struct axis ax[2];        /* u and v */
	struct arena pool;        /* tiles and their finished values */
	struct tile **tiles;      /* allocated tiles, in order of allocation */
	long ntiles, cap;         /* used and allocated entries of tiles[] */
	long *slots;              /* hash of the tiles outside the window: tile index + 1, 0 = empty */
	long nslots;              /* power of two, > 2·nhashed */
	long nhashed;             /* tiles in the hash */
	int32_t *win;             /* the window: tile index + 1 (0 = none) of tile (wti + a, wtj + b)
	                             at win[b·wnu + a]; NULL when there is none */
	long wti, wtj, wnu, wnv;  /* the window's first tile and its size in tiles */
	long last;                /* tile index of the last deposit (cache), -1 */
	bool finished;            /* irradiance is current */
	bool grey;                /* tiles hold one channel (struct gacc): every deposit so far had
	                             three equal channels; the first that does not (or a polygon or
	                             single deposit) makes the map colour first (ungrey) */
	int32_t rti[2], rtj[2];   /* while finished: the least and greatest tile indices held */
	long dropped;             /* deposits with non-finite (u,v) */
	size_t bytes;             /* memory held */
	double flat_area;         /* plane: the node area, the same everywhere (0 until known) */
	struct fx total[3];       /* the energy held, summed by illum_finish (while finished) */
	int shift;                /* accumulators count units of 2^(shift−96) W (see map_reserve) */
	double unit, inv_unit;    /* 2^shift and 2^−shift */
	double bound;             /* energy deposited so far (per channel, at most): bounds every node's sum */
	struct loops loops;       /* polygon deposits: the current polygon's simple loops */
	struct pt2 *pts;          /* polygon deposits: corners and clip buffers (scratch) */
	double *rows;             /* polygon deposits: row shares and node weights (scratch) */
	long *spans;              /* polygon deposits: each weight row's written columns (scratch) */
	size_t cap_pts, cap_rows, cap_spans; /* allocated lengths of pts, rows and spans */
};

_Static_assert((ILLUM_TILE & (ILLUM_TILE - 1)) == 0, "ILLUM_TILE: a power of two");

/* The tile of node index a (floor(a / ILLUM_TILE)), and a's place in it
 * (a − ILLUM_TILE·floordiv(a), in [0, ILLUM_TILE)): masks, the tile a power
 * of two (two's complement, as C11's intN_t are). */
static inline long tile_rem(long a) { return (long)((unsigned long)a & (ILLUM_TILE - 1)); }
static inline long floordiv(long a) { return (a - tile_rem(a)) / ILLUM_TILE; }

static uint64_t tile_hash(int32_t ti, int32_t tj)
{
	uint64_t z = ((uint64_t)(uint32_t)ti << 32) | (uint32_t)tj;
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	return z ^ (z >> 31);
}

/* Where tile (ti,tj) sits in the window, or NULL when outside it. */
static int32_t *win_slot(const struct illum_map *m, long ti, long tj)
{
	unsigned long a = (unsigned long)(ti - m->wti), b = (unsigned long)(tj - m->wtj);
	if (!m->win || a >= (unsigned long)m->wnu || b >= (unsigned long)m->wnv)
		return NULL;
	return &m->win[b * (unsigned long)m->wnu + a];
}

/* Index of tile (ti,tj) in m->tiles, or -1: the window's array, else the
 * hash. */
static long tile_find(const struct illum_map *m, int32_t ti, int32_t tj)
{
	const int32_t *w = win_slot(m, ti, tj);
	if (w)
		return (long)*w - 1;
	if (!m->nslots)
		return -1;
	for (uint64_t h = tile_hash(ti, tj);; h++) {
		long s = m->slots[h & (uint64_t)(m->nslots - 1)];
		if (!s)
			return -1;
		if (m->tiles[s - 1]->ti == ti && m->tiles[s - 1]->tj == tj)
			return s - 1;
	}
}

static void slot_insert(struct illum_map *m, long idx)
{
	const struct tile *t = m->tiles[idx];
	uint64_t h = tile_hash(t->ti, t->tj);
	while (m->slots[h & (uint64_t)(m->nslots - 1)])
		h++;
	m->slots[h & (uint64_t)(m->nslots - 1)] = idx + 1;
}

/* Enters tile idx into the window or, outside it, the hash (growing it). */
static void tile_index(struct illum_map *m, long idx)
{
	int32_t *w = win_slot(m, m->tiles[idx]->ti, m->tiles[idx]->tj);
	if (w) {
		*w = (int32_t)(idx + 1);
		return;
	}
	if (2 * ++m->nhashed >= m->nslots) {
		/* the hashed tiles move to a table twice the size, taken from the
		 * old table (not by looking at every tile: those in the window are
		 * most, and cold) */
		long ns = m->nslots ? 2 * m->nslots : 16, old = m->nslots;
		long *was = m->slots;
		m->bytes -= (size_t)old * sizeof *m->slots;
		m->slots = mem_calloc((size_t)ns, sizeof *m->slots);
		m->bytes += (size_t)ns * sizeof *m->slots;
		m->nslots = ns;
		for (long k = 0; k < old; k++)
			if (was[k])
				slot_insert(m, was[k] - 1);
		free(was);
	}
	slot_insert(m, idx);
}

/* Appends tile t (not yet in the map), growing the table; returns its index. */
static long tile_insert(struct illum_map *m, struct tile *t)
{
	if (m->ntiles == m->cap) {
		long cap = m->cap ? 2 * m->cap : 8;
		m->tiles = mem_realloc(m->tiles, (size_t)cap * sizeof *m->tiles);
		m->bytes += (size_t)(cap - m->cap) * sizeof *m->tiles;
		m->cap = cap;
	}
	m->tiles[m->ntiles++] = t;
	tile_index(m, m->ntiles - 1);
	return m->ntiles - 1;
}

#define WIN_MIN 65536L         /* a window of this many tiles is always allowed */
#define WIN_MAX (1L << 26)     /* and none beyond this (256 MiB of int32) */

/* Gives m an empty window of nu × nv tiles from tile (ti0, tj0), in place
 * of any it had (whose entries the caller puts back). */
static void win_new(struct illum_map *m, long ti0, long tj0, long nu, long nv)
{
	free(m->win);
	m->bytes -= (size_t)(m->wnu * m->wnv) * sizeof *m->win;
	m->wti = ti0, m->wtj = tj0, m->wnu = nu, m->wnv = nv;
	m->win = mem_calloc((size_t)(nu * nv), sizeof *m->win);
	mem_huge(m->win, (size_t)(nu * nv) * sizeof *m->win); /* (a large one: fewer page faults) */
	m->bytes += (size_t)(nu * nv) * sizeof *m->win;
}

/* Widens the window to hold tiles [ti0, ti1] × [tj0, tj1] (and the window
 * it had), when that costs at most WIN_MIN + 8·(tiles + more) entries: so a
 * map's tiles are found by indexing an array, and the window costs at most
 * 32 bytes per tile (a tile holds ~280). Tiles inside it leave the hash.
 * more: tiles about to be added. */
static bool win_grow(struct illum_map *m, long ti0, long ti1, long tj0, long tj1, long more)
{
	if (ti0 > ti1 || tj0 > tj1)
		return true;
	if (m->win) {
		ti0 = ti0 < m->wti ? ti0 : m->wti, tj0 = tj0 < m->wtj ? tj0 : m->wtj;
		ti1 = ti1 > m->wti + m->wnu - 1 ? ti1 : m->wti + m->wnu - 1;
		tj1 = tj1 > m->wtj + m->wnv - 1 ? tj1 : m->wtj + m->wnv - 1;
		if (ti0 == m->wti && tj0 == m->wtj && ti1 - ti0 + 1 == m->wnu && tj1 - tj0 + 1 == m->wnv)
			return true;
	}
	double nu = (double)(ti1 - ti0) + 1, nv = (double)(tj1 - tj0) + 1;
	if (nu * nv > (double)WIN_MAX || nu * nv > (double)WIN_MIN + 8 * ((double)m->ntiles + (double)more))
		return false;
	win_new(m, ti0, tj0, (long)nu, (long)nv);
	if (m->slots)
		memset(m->slots, 0, sizeof *m->slots * (size_t)m->nslots);
	m->nhashed = 0;
	for (long k = 0; k < m->ntiles; k++) {
		int32_t *w = win_slot(m, m->tiles[k]->ti, m->tiles[k]->tj);
		if (w)
			*w = (int32_t)(k + 1);
		else
			m->nhashed++, slot_insert(m, k);
	}
	return true;
}

/* Sorts a[0..n) ascending: by counting when the values span less than
 * 2^16 (tile coordinates, the usual case), else a radix sort, two passes
 * of 16 bits (qsort's comparisons cost ~25 times more on the window's
 * samples). */
static void sort_i32(int32_t *a, long n)
{
	if (n <= 0)
		return;
	int32_t lo = a[0], hi = a[0];
	for (long i = 1; i < n; i++)
		lo = a[i] < lo ? a[i] : lo, hi = a[i] > hi ? a[i] : hi;
	if ((int64_t)hi - lo < 65536) { /* tile coordinates span little: count them */
		long span = (long)((int64_t)hi - lo) + 1, *cnt = mem_calloc((size_t)span, sizeof *cnt);
		for (long i = 0; i < n; i++)
			cnt[a[i] - lo]++;
		for (long v = 0, at = 0; v < span; v++)
			for (long c = cnt[v]; c > 0; c--)
				a[at++] = (int32_t)(lo + v);
		free(cnt);
		return;
	}
	uint32_t *x = (uint32_t *)a, *tmp = mem_alloc(sizeof *tmp * (size_t)(n ? n : 1));
	long *cnt = mem_alloc(sizeof *cnt * 65536);
	for (long i = 0; i < n; i++)
		x[i] ^= 0x80000000u; /* signed order as unsigned */
	for (int pass = 0; pass < 2; pass++) {
		uint32_t *src = pass ? tmp : x, *dst = pass ? x : tmp;
		int sh = 16 * pass;
		memset(cnt, 0, sizeof *cnt * 65536);
		for (long i = 0; i < n; i++)
			cnt[(src[i] >> sh) & 0xffff]++;
		long at = 0;
		for (long d = 0; d < 65536; d++) {
			long c = cnt[d];
			cnt[d] = at;
			at += c;
		}
		for (long i = 0; i < n; i++)
			dst[cnt[(src[i] >> sh) & 0xffff]++] = src[i];
	}
	for (long i = 0; i < n; i++)
		x[i] ^= 0x80000000u;
	free(tmp), free(cnt);
}

#define WIN_SAMPLE 32768 /* tile coordinates looked at to place the window */

/* Places the window over where most of n tiles (coordinates ti[k·stride],
 * tj[k·stride] of a sample) are: over all of them when the window may be
 * that large, else over the central 99.8 %, 99 %, 96 % or 90 % on each axis
 * (a few grazing rays land far away; their tiles stay in the hash).
 * Returns the quantile used (0: all), or -1 when no window was made. */
static double win_fit(struct illum_map *m, int32_t *ti, int32_t *tj, long ns, long more)
{
	static const double q[] = {0, 0.001, 0.005, 0.02, 0.05};
	if (ns <= 0)
		return 0;
	sort_i32(ti, ns);
	sort_i32(tj, ns);
	for (int k = 0; k < 5; k++) {
		long lo = (long)(q[k] * (double)(ns - 1)), hi = ns - 1 - lo;
		if (win_grow(m, ti[lo], ti[hi], tj[lo], tj[hi], more))
			return q[k];
	}
	return -1;
}

/* A zeroed tile for a map that is grey or not, from arena a. */
static struct tile *tile_new(struct arena *a, bool grey)
{
	return grey ? arena_alloc8(a, GREY_TILE) : ARENA_NEW(a, struct tile);
}

/* Node q of tile t of m: its deposit count, and its energy in channel c. */
static inline uint32_t node_count(const struct illum_map *m, const struct tile *t, int q)
{
	return m->grey ? t->g[q].count : t->n[q].count;
}

static inline struct fx node_e(const struct illum_map *m, const struct tile *t, int q, int c)
{
	return m->grey ? t->g[q].e : t->n[q].e[c];
}

/* Appends a zeroed tile (ti,tj); returns its index. */
static long tile_add(struct illum_map *m, int32_t ti, int32_t tj)
{
	struct tile *t = tile_new(&m->pool, m->grey);
	t->ti = ti;
	t->tj = tj;
	return tile_insert(m, t);
}

/* The tile of node (i,j), or NULL when it is absent and create is false.
 * Indices must already be wrapped/clamped (axis_node). */
static struct tile *tile_of(struct illum_map *m, long i, long j, bool create)
{
	long ti = floordiv(i), tj = floordiv(j), k;
	if (m->last >= 0 && m->tiles[m->last]->ti == ti && m->tiles[m->last]->tj == tj)
		k = m->last;
	else if ((k = tile_find(m, (int32_t)ti, (int32_t)tj)) < 0) {
		if (!create)
			return NULL;
		k = tile_add(m, (int32_t)ti, (int32_t)tj);
	}
	m->last = k;
	return m->tiles[k];
}

/* The accumulator of node (i,j) of a colour map (the callers ungrey), as
 * tile_of finds its tile. */
static struct acc *node_acc(struct illum_map *m, long i, long j, bool create)
{
	struct tile *t = tile_of(m, i, j, create);
	return t ? &t->n[tile_rem(j) * ILLUM_TILE + tile_rem(i)] : NULL;
}

/* Read-only lookup of node (i,j): its tile and slot, or NULL. */
static const struct tile *node_tile(const struct illum_map *m, long i, long j, int *slot)
{
	long ti = floordiv(i), tj = floordiv(j);
	long k = tile_find(m, (int32_t)ti, (int32_t)tj);
	if (k < 0)
		return NULL;
	*slot = (int)(tile_rem(j) * ILLUM_TILE + tile_rem(i));
	return m->tiles[k];
}

/* ==== axes: parameter ↔ node indices ====================================== */

/* t (in node spacings) snapped onto the nearest node when within SNAP. */
static double snap(double t)
{
	double r = t; /* nearbyint(t), inline: below 2^52 adding 2^52 rounds to an integer
	                 (to even, as nearbyint does, symmetrically); from 2^52 on t is one */
	if (fabs(t) < 0x1p52)
		r = t >= 0 ? (t + 0x1p52) - 0x1p52 : -((-t + 0x1p52) - 0x1p52);
	return fabs(t - r) < SNAP ? r : t;
}

/* Splits parameter x between nodes *i0 (weight 1 − *f) and *i1 (weight *f):
 * wrapped on periodic axes, clamped to the edges of bounded ones. A point
 * within SNAP spacings of a node is snapped onto it (then *f = 0). */
static inline void axis_split(const struct axis *a, double x, long *i0, long *i1, double *f)
{
	double t = snap((x - a->lo) / a->step);
	if (a->wraps) {
		t = fmod(t, (double)a->n);
		if (t < 0)
			t += (double)a->n;
		long i = (long)floor(t);
		if (i >= a->n)
			i -= a->n;
		*f = t - floor(t);
		*i0 = i;
		*i1 = i + 1 == a->n ? 0 : i + 1;
		return;
	}
	double lo = a->bounded ? 0 : -PLANE_LIMIT, hi = a->bounded ? (double)(a->n - 1) : PLANE_LIMIT;
	t = !(t >= lo) ? lo : t > hi ? hi : t; /* fmin(fmax(t, lo), hi), inline */
	long i = (long)t; /* floor: |t| <= 2^30 */
	if ((double)i > t)
		i--;
	if (a->bounded && i > a->n - 2)
		i = a->n - 2;
	*f = t - (double)i;
	*i0 = i;
	*i1 = i + 1;
}

/* Node index i + d on axis a: wrapped, or -1 past a bounded edge. */
static long axis_step(const struct axis *a, long i, long d)
{
	if (a->wraps)
		return ((i + d) % a->n + a->n) % a->n;
	if (a->bounded && (i + d < 0 || i + d >= a->n))
		return -1;
	return i + d;
}

static double axis_node(const struct axis *a, long i)
{
	if (a->bounded && !a->wraps && i == a->n - 1)
		return a->hi;
	return a->lo + (double)i * a->step;
}

/* Sets up a bounded axis [lo,hi] with `intervals` spacings. */
static void axis_bounded(struct axis *a, double lo, double hi, bool wraps, long intervals)
{
	a->lo = lo;
	a->hi = hi;
	a->wraps = wraps;
	a->bounded = true;
	if (wraps && intervals < 3)
		intervals = 3;
	a->n = wraps ? intervals : intervals + 1;
	a->step = (hi - lo) / (double)intervals;
}

/* The longest world length of the curves along parameter `axis` (0: u, 1: v)
 * at 33 values of the other parameter, each as a 64-segment polyline. */
static double max_curve_length(const struct object *o, const struct uv_range *r, int axis)
{
	double best = 0;
	for (int k = 0; k <= 32; k++) {
		double len = 0;
		struct vec3 prev = {0, 0, 0}, p;
		for (int s = 0; s <= 64; s++) {
			double a = axis ? r->v0 + (r->v1 - r->v0) * s / 64.0 : r->u0 + (r->u1 - r->u0) * s / 64.0;
			double b = axis ? r->u0 + (r->u1 - r->u0) * k / 32.0 : r->v0 + (r->v1 - r->v0) * k / 32.0;
			if (!shape_uv_point(o, axis ? b : a, axis ? a : b, &p, NULL, NULL))
				return 0;
			if (s)
				len += v_len(v_sub(p, prev));
			prev = p;
		}
		best = fmax_(best, len);
	}
	return best;
}

/* ==== construction ======================================================== */

/* A map's arena: small blocks at first (most maps are small), doubling to
 * ARENA_LARGE_BLOCK, so the tiles of a large map lie in huge pages (a page
 * fault per 2 MiB, not per 4 KiB; with 1 MiB blocks, the faults of a
 * shaft pass's 70 MB of tiles were a tenth of its time). */
static void map_pool(struct arena *a)
{
	arena_init_sized(a, 4096);
	a->most = ARENA_LARGE_BLOCK;
}

struct illum_map *illum_new(const struct object *o, const struct illum_spec *spec)
{
	struct uv_range r;
	if (!o || !spec || !shape_uv_range(o, &r))
		return NULL;
	struct illum_map *m = mem_calloc(1, sizeof *m);
	m->obj = o;
	m->last = -1;
	m->grey = true;
	m->unit = m->inv_unit = 1;
	map_pool(&m->pool);
	m->bytes = sizeof *m;
	if (!r.bounded) {
		struct vec3 p, pu, pv;
		if (!(spec->cell > 0) || !shape_uv_point(o, 0, 0, &p, &pu, &pv) || !(v_len(pu) > 0) ||
		    !(v_len(pv) > 0))
			goto fail;
		m->ax[0] = (struct axis){0, 0, spec->cell / v_len(pu), 0, false, false};
		m->ax[1] = (struct axis){0, 0, spec->cell / v_len(pv), 0, false, false};
		return m;
	}
	long n[2];
	if (spec->resolution > 0) {
		n[0] = n[1] = spec->resolution;
	} else if (spec->cell > 0) {
		for (int a = 0; a < 2; a++) {
			double q = ceil(max_curve_length(o, &r, a) / spec->cell * (1 - 1e-9));
			if (!(q <= (double)MAX_NODES))
				goto fail;
			n[a] = q < 1 ? 1 : (long)q;
		}
		if (o->kind == OBJ_BOX) { /* nodes on the atlas's face boundaries */
			n[0] = (n[0] + 2) / 3 * 3;
			n[1] = (n[1] + 1) / 2 * 2;
		}
	} else {
		goto fail;
	}
	if (n[0] > MAX_NODES || n[1] > MAX_NODES)
		goto fail;
	axis_bounded(&m->ax[0], r.u0, r.u1, r.u_wraps, n[0]);
	axis_bounded(&m->ax[1], r.v0, r.v1, r.v_wraps, n[1]);
	return m;
fail:
	free(m);
	return NULL;
}

struct illum_map *illum_new_like(const struct illum_map *src)
{
	struct illum_map *m = mem_calloc(1, sizeof *m);
	m->obj = src->obj;
	m->ax[0] = src->ax[0];
	m->ax[1] = src->ax[1];
	m->last = -1;
	m->grey = src->grey;
	m->shift = src->shift;
	m->unit = src->unit;
	m->inv_unit = src->inv_unit;
	map_pool(&m->pool);
	m->bytes = sizeof *m;
	return m;
}

void illum_free(struct illum_map *m)
{
	if (!m)
		return;
	arena_free(&m->pool);
	free(m->tiles);
	free(m->slots);
	free(m->win);
	loops_free(&m->loops);
	free(m->pts);
	free(m->rows);
	free(m->spans);
	free(m);
}

void illum_grid(const struct illum_map *m, long *nu, long *nv, double *du, double *dv)
{
	if (nu)
		*nu = m->ax[0].n;
	if (nv)
		*nv = m->ax[1].n;
	if (du)
		*du = m->ax[0].step;
	if (dv)
		*dv = m->ax[1].step;
}

void illum_node_uv(const struct illum_map *m, long i, long j, double *u, double *v)
{
	*u = axis_node(&m->ax[0], i);
	*v = axis_node(&m->ax[1], j);
}

/* ==== deposit and merge =================================================== */

/* Makes the accumulators count units of 2^(shift−96) W, shift > m->shift,
 * dropping the bits that fall below the new unit. */
static void map_rescale(struct illum_map *m, int shift)
{
	int k = shift - m->shift;
	for (long t = 0; t < m->ntiles; t++)
		for (int q = 0; q < TN; q++) {
			if (m->grey) {
				m->tiles[t]->g[q].e = fx_shr(m->tiles[t]->g[q].e, k);
				continue;
			}
			for (int c = 0; c < 3; c++)
				m->tiles[t]->n[q].e[c] = fx_shr(m->tiles[t]->n[q].e[c], k);
		}
	m->shift = shift;
	m->unit = ldexp(1, shift);
	m->inv_unit = ldexp(1, -shift);
	m->finished = false;
}

/* Range: no node's sum can exceed the energy deposited into the whole map
 * (per channel), so keeping that bound under 2^31 units (a bit of headroom
 * below the 2^32 capacity) means no accumulator ever saturates. Before
 * `more` W more arrive, raises the unit when the bound needs it. Scenes in
 * everyday units keep shift 0 (the plain 2^−96 W quantum); a scene at 1e6
 * scale, whose rays carry ~1e9 W, does not. An infinite bound is left to
 * saturate. */
static void map_reserve(struct illum_map *m, double more)
{
	double b = m->bound + more;
	int e;
	if (!isfinite(b))
		return;
	m->bound = b;
	frexp(b, &e); /* b < 2^e */
	if (e - 31 > m->shift)
		map_rescale(m, e - 31);
}

/* Makes a grey map a colour one: each tile anew with its one channel
 * copied to the three (the same numbers; the grey tiles stay in the arena
 * until the map is freed). The window and hash keep their indices. */
static void ungrey(struct illum_map *m)
{
	if (!m->grey)
		return;
	for (long k = 0; k < m->ntiles; k++) {
		const struct tile *g = m->tiles[k];
		struct tile *t = ARENA_NEW(&m->pool, struct tile);
		t->ti = g->ti, t->tj = g->tj, t->iso = g->iso, t->area = g->area;
		for (int q = 0; q < TN; q++) {
			for (int c = 0; c < 3; c++)
				t->n[q].e[c] = g->g[q].e, t->n[q].sq[c] = g->g[q].sq;
			t->n[q].count = g->g[q].count;
		}
		m->tiles[k] = t;
	}
	m->grey = false;
}

/* The largest channel of a deposit's energy, as deposit_band counts it. */
static double energy_max(const double e[3])
{
	double x = 0;
	for (int c = 0; c < 3; c++)
		x = e[c] > x ? e[c] : x; /* NaN and negatives → 0 */
	return x;
}

static inline void acc_add(struct acc *n, double w, const double e[3], double inv_unit)
{
	double x = w * e[0];
	struct fx f = fx_from(x * inv_unit);
	float q = (float)(x * x);
	fx_add(&n->e[0], f);
	n->sq[0] += q;
	for (int c = 1; c < 3; c++) {
		if (e[c] != e[c - 1]) { /* white light: the same numbers thrice */
			x = w * e[c];
			f = fx_from(x * inv_unit);
			q = (float)(x * x);
		}
		fx_add(&n->e[c], f);
		n->sq[c] += q;
	}
	n->count += n->count < UINT32_MAX;
}

/* acc_add where no sum can saturate (fx_add_fast), white light (e[0] =
 * e[1] = e[2]) taken once: the same result. */
__attribute__((always_inline)) static inline void acc_add_fast(struct acc *n, double w, const double e[3], bool white,
                                                               double inv_unit)
{
	if (!white) {
		for (int c = 0; c < 3; c++) {
			double x = w * e[c];
			fx_add_fast(&n->e[c], fx_from(x * inv_unit));
			n->sq[c] += (float)(x * x);
		}
	} else { /* written out: GCC does not unroll the loop at -O2 */
		double x = w * e[0];
		struct fx f = fx_from(x * inv_unit);
		float q = (float)(x * x);
		fx_add_fast(&n->e[0], f);
		fx_add_fast(&n->e[1], f);
		fx_add_fast(&n->e[2], f);
		n->sq[0] += q;
		n->sq[1] += q;
		n->sq[2] += q;
	}
	n->count += n->count < UINT32_MAX;
}

/* e = energy with NaN and negative components set to 0; false when all are. */
static bool energy_clean(const double energy[3], double e[3])
{
	for (int c = 0; c < 3; c++)
		e[c] = energy[c] > 0 ? energy[c] : 0;
	return e[0] > 0 || e[1] > 0 || e[2] > 0;
}

/* The band of node row j when the deposits are split among nb threads:
 * stripes of 16 tile rows, dealt round-robin. */
static int band_of(long j, int nb)
{
	long t = floordiv(j), s = t >= 0 ? t / 16 : -((-t + 15) / 16);
	if ((nb & (nb - 1)) == 0) /* the same, without two divisions (unsigned: s modulo 2^64) */
		return (int)((unsigned long)s & (unsigned long)(nb - 1));
	return (int)(((s % nb) + nb) % nb);
}

/* illum_deposit, restricted to the nodes of band `band` of nb. */
static void deposit_band(struct illum_map *m, double u, double v, const double energy[3], int band, int nb)
{
	if (!isfinite(u) || !isfinite(v)) {
		if (band == 0)
			m->dropped++;
		return;
	}
	double e[3];
	if (!energy_clean(energy, e))
		return;
	long iu[2], iv[2];
	double fu, fv;
	axis_split(&m->ax[0], u, &iu[0], &iu[1], &fu);
	axis_split(&m->ax[1], v, &iv[0], &iv[1], &fv);
	double wu[2] = {1 - fu, fu}, wv[2] = {1 - fv, fv};
	for (int b = 0; b < 2; b++) {
		if (nb > 1 && band_of(iv[b], nb) != band)
			continue;
		for (int a = 0; a < 2; a++) {
			double w = wu[a] * wv[b];
			if (w > 0)
				acc_add(node_acc(m, iu[a], iv[b], true), w, e, m->inv_unit);
		}
	}
	m->finished = false;
}

void illum_deposit(struct illum_map *m, double u, double v, const double energy[3])
{
	ungrey(m); /* (single deposits: tests and loading a map file) */
	map_reserve(m, energy_max(energy));
	deposit_band(m, u, v, energy, 0, 1);
}

/* Adds tile s's accumulators, shifted right by k bits (its map's unit is
 * 2^k times finer), into tile d: both grey (dgrey), or d colour and s grey
 * (sgrey) or colour. */
static void tile_accumulate(struct tile *d, bool dgrey, const struct tile *s, bool sgrey, int k)
{
	for (int q = 0; q < TN; q++) {
		uint32_t *dc = dgrey ? &d->g[q].count : &d->n[q].count;
		uint32_t sc = sgrey ? s->g[q].count : s->n[q].count, sum = *dc + sc;
		*dc = sum < *dc ? UINT32_MAX : sum;
		if (dgrey) {
			fx_add(&d->g[q].e, fx_shr(s->g[q].e, k));
			d->g[q].sq += s->g[q].sq;
			continue;
		}
		for (int c = 0; c < 3; c++) {
			fx_add(&d->n[q].e[c], fx_shr(sgrey ? s->g[q].e : s->n[q].e[c], k));
			d->n[q].sq[c] += sgrey ? s->g[q].sq : s->n[q].sq[c];
		}
	}
}

/* Moves src's tiles into dst (same grid), adding where dst has the tile
 * already, and frees src. */
static void adopt(struct illum_map *dst, struct illum_map *src)
{
	for (long k = 0; k < src->ntiles; k++) {
		struct tile *t = src->tiles[k];
		long d = tile_find(dst, t->ti, t->tj);
		if (d >= 0) { /* (src is a band's part of dst: as grey as it) */
			tile_accumulate(dst->tiles[d], dst->grey, t, src->grey, 0);
		} else {
			t->area = NULL;
			t->iso = 0;
			tile_insert(dst, t);
		}
	}
	arena_adopt(&dst->pool, &src->pool);
	dst->dropped += src->dropped;
	dst->finished = false;
	illum_free(src);
}

/* ---- batched point deposits (illum_deposit_all) ----
 * Four steps, none of which hashes per deposit once the window holds the
 * deposits' tiles, and none of which writes anything per splat when there
 * are many (a splat's nodes are worked out where they are needed: an array
 * of them would be memory the kernel zeroes, written and read back):
 *   1. the splats are scanned in parallel chunks: the valid ones counted,
 *      the largest energy and whether all are white; up to PREP_MAX splats,
 *      which the sample would nearly all split again, and any number into a
 *      map already in colour (whose step 3 has more to do per splat than
 *      splitting it again saves: shaft maps, coloured light; not a larger
 *      first coloured batch, which turns a grey map to colour while it is
 *      scanned), are split here onto their nodes (axis_split) once, into a
 *      `prep` each;
 *   2. one thread places the window over a sample of their tiles (every
 *      stride-th valid splat);
 *   3. the accumulators are added band by band, one thread per band of
 *      tile rows (band_of), each band's deposits in splat order, making the
 *      tiles it needs from its own arena: a node receives the same
 *      additions in the same order for any thread count, so even its float
 *      Σw² is bit-identical;
 *   4. the bands' new tiles join the map's list (pointers only). */
#define PREP_MAX 65536 /* splats split once in step 1 (the sample takes every first or second) */

struct prep {
	int32_t i, j;       /* the lower nodes of the split (axis_split's i0), INT32_MIN: no deposit */
	double fu, fv;      /* the weights of the upper ones */
};

struct deposit_job {
	struct illum_map *m;
	const struct illum_run *runs;
	const long *off;    /* run k's splats are [off[k], off[k+1]) */
	long nruns;
	struct prep *p;     /* step 1's splits (up to PREP_MAX splats), else NULL */
	long n, chunk;
	int nb;
	long dropped;       /* per chunk: non-finite (u,v) */
	long valid;         /* per chunk: splats that deposit */
	long c0;            /* per chunk: the valid splats before it */
	int32_t *ti, *tj;   /* the window's sample (step 2) */
	long stride;        /* of the sample: every stride-th valid splat */
	double emax;        /* per chunk: the largest energy_max of its splats */
	bool white;         /* per chunk: its valid splats' three channels are equal */
	struct arena pool;  /* per band: the tiles it made in the window */
	struct tile **made; /* per band: those tiles, in order */
	long *where;        /* per band: their window entries */
	long nmade, cap;
	long first;         /* per band: where its tiles go in the map's list */
	struct illum_map *part; /* per band: tiles it made outside the window */
};

/* Splat i of run r (an illum_splat, or an illum_gsplat in a grey run). */
__attribute__((always_inline)) static inline struct illum_splat run_at(const struct illum_run *r, long i)
{
	const void *p = (const char *)r->s + (size_t)i * r->stride;
	return r->grey ? illum_gsplat_splat(p) : *(const struct illum_splat *)p;
}

/* The run holding splat lo (off[r] <= lo < off[r+1]). */
static long run_of(const struct deposit_job *D, long lo)
{
	long r0 = 0, r1 = D->nruns;
	while (r1 - r0 > 1) {
		long mid = (r0 + r1) / 2;
		if (D->off[mid] <= lo)
			r0 = mid;
		else
			r1 = mid;
	}
	return r0;
}

/* Splat q of the job's runs; *r, the run of an earlier splat (or 0), moves
 * on to q's. */
__attribute__((always_inline)) static inline struct illum_splat splat_at(const struct deposit_job *D, long q, long *r)
{
	while (q >= D->off[*r + 1])
		++*r;
	return run_at(&D->runs[*r], q - D->off[*r]);
}

/* Does splat s deposit? (Finite (u,v), some energy; e its energy cleaned.) */
__attribute__((always_inline)) static inline bool splat_valid(const struct illum_splat *s, double e[3])
{
	return isfinite(s->u) && isfinite(s->v) && energy_clean(s->e, e);
}

/* Step 1 for chunk k of the splats, splitting them when prep (D->p). */
__attribute__((always_inline)) static inline void scan_chunk(struct deposit_job *D, long k, bool prep)
{
	struct deposit_job *J = D + k;
	long lo = k * D->chunk, hi = lo + D->chunk < D->n ? lo + D->chunk : D->n;
	J->dropped = 0;
	J->valid = 0;
	J->emax = 0;
	J->white = true;
	long r0 = run_of(D, lo);
	for (long q = lo; q < hi; q++) {
		struct illum_splat sp = splat_at(D, q, &r0);
		double e[3], x = energy_max(sp.e);
		J->emax = x > J->emax ? x : J->emax;
		if (prep)
			D->p[q].i = INT32_MIN;
		if (!isfinite(sp.u) || !isfinite(sp.v)) {
			J->dropped++;
		} else if (energy_clean(sp.e, e)) {
			J->white = J->white && e[0] == e[1] && e[1] == e[2];
			J->valid++;
			if (prep) {
				struct prep *p = &D->p[q];
				long iu[2], iv[2];
				axis_split(&D->m->ax[0], sp.u, &iu[0], &iu[1], &p->fu);
				axis_split(&D->m->ax[1], sp.v, &iv[0], &iv[1], &p->fv);
				p->i = (int32_t)iu[0], p->j = (int32_t)iv[0];
			}
		}
	}
}

/* Step 1 for chunk k (a parallel_for item). */
static void scan_work(void *ctx, long k, int worker)
{
	(void)worker;
	struct deposit_job *D = ctx;
	if (D->p)
		scan_chunk(D, k, true);
	else
		scan_chunk(D, k, false);
}

/* Sample entry c / stride: the tile of splat q, s. */
__attribute__((always_inline)) static inline void sample_put(const struct deposit_job *D, long c, long q,
                                                             const struct illum_splat *s)
{
	long i0 = D->p ? D->p[q].i : 0, i1, j0 = D->p ? D->p[q].j : 0, j1;
	double f;
	if (!D->p) {
		axis_split(&D->m->ax[0], s->u, &i0, &i1, &f);
		axis_split(&D->m->ax[1], s->v, &j0, &j1, &f);
	}
	D->ti[c / D->stride] = (int32_t)floordiv(i0);
	D->tj[c / D->stride] = (int32_t)floordiv(j0);
}

/* Step 2's sample from chunk k (a parallel_for item): the tiles of valid
 * splats c = 0, stride, 2·stride, … counted over all chunks, each at c /
 * stride. */
static void sample_work(void *ctx, long k, int worker)
{
	(void)worker;
	const struct deposit_job *J = (const struct deposit_job *)ctx + k, *D = ctx;
	long lo = k * D->chunk, hi = lo + D->chunk < D->n ? lo + D->chunk : D->n, c = J->c0;
	if (J->valid == hi - lo) { /* every splat valid (the usual case): straight to the sampled ones */
		long q = lo + (D->stride - c % D->stride) % D->stride, r = run_of(D, q);
		for (; q < hi; q += D->stride) {
			struct illum_splat sp = splat_at(D, q, &r);
			sample_put(D, c + q - lo, q, &sp);
		}
		return;
	}
	for (long q = lo, r = run_of(D, lo); q < hi; q++) {
		struct illum_splat sp = splat_at(D, q, &r);
		double e[3];
		if ((D->p ? D->p[q].i != INT32_MIN : splat_valid(&sp, e)) && c++ % D->stride == 0)
			sample_put(D, c - 1, q, &sp);
	}
}

/* Step 2: the window, placed where most deposits land (the sample taken
 * on the threads). Returns the number of valid splats. */
static long prep_window(struct deposit_job *D, long nchunks)
{
	struct illum_map *m = D->m;
	long n = 0;
	for (long k = 0; k < nchunks; k++) {
		m->dropped += D[k].dropped;
		D[k].c0 = n;
		n += D[k].valid;
	}
	D->stride = n / WIN_SAMPLE + 1;
	long ns = (n + D->stride - 1) / D->stride;
	D->ti = mem_alloc(sizeof *D->ti * (size_t)(ns + 1)), D->tj = mem_alloc(sizeof *D->tj * (size_t)(ns + 1));
	parallel_for(nchunks, D->nb, sample_work, D);
	win_fit(m, D->ti, D->tj, ns, n);
	free(D->ti), free(D->tj);
	return n;
}

/* band_tile (below) when the tile is not one the window names yet: w is
 * its window entry (NULL outside the window). */
static __attribute__((noinline)) struct tile *band_tile_new(struct deposit_job *B, struct illum_map *m, long ti, long tj,
                                                             int32_t *w)
{
	if (w) {
		if (B->nmade == B->cap) {
			B->cap = B->cap ? 2 * B->cap : 256;
			B->made = mem_realloc(B->made, sizeof *B->made * (size_t)B->cap);
			B->where = mem_realloc(B->where, sizeof *B->where * (size_t)B->cap);
		}
		struct tile *t = tile_new(&B->pool, m->grey);
		t->ti = (int32_t)ti, t->tj = (int32_t)tj;
		B->where[B->nmade] = w - m->win;
		B->made[B->nmade++] = t;
		*w = (int32_t)(-B->nmade);
		return t;
	}
	long k = tile_find(m, (int32_t)ti, (int32_t)tj);
	if (k >= 0)
		return m->tiles[k];
	if (!B->part)
		B->part = illum_new_like(m);
	long at = tile_find(B->part, (int32_t)ti, (int32_t)tj);
	if (at < 0)
		at = tile_add(B->part, (int32_t)ti, (int32_t)tj);
	return B->part->tiles[at];
}

/* The tile (ti,tj) for band job B, made when missing: in the window, from
 * the band's own arena (the window entry, which only this band touches,
 * holds −1 − its place in B->made until step 4); outside it, in the band's
 * partial map. Tiles the map had are found read-only. The usual case, a
 * window tile made already, inline; band_tile_new the rest. */
__attribute__((always_inline)) static inline struct tile *band_tile(struct deposit_job *B, struct illum_map *m,
                                                                    long ti, long tj)
{
	int32_t *w = win_slot(m, ti, tj);
	if (w && *w > 0)
		return m->tiles[*w - 1];
	if (w && *w < 0)
		return B->made[-*w - 1];
	return band_tile_new(B, m, ti, tj, w);
}

/* Where step 3 is in band k's tiles: the tile of the last node (most
 * splats stay in one), and what every deposit needs. */
struct band_pos {
	struct deposit_job *B;
	struct illum_map *m;
	long ti, tj;       /* the last node's tile, LONG_MIN: none yet */
	struct tile *t;
	double inv;        /* m->inv_unit */
	bool finite;       /* no sum can reach 2^128 (map_reserve) */
	bool grey;         /* m->grey */
};

/* Adds weight w of energy e (white: e[0] = e[1] = e[2]) to node (i,j). */
__attribute__((always_inline)) static inline void band_add(struct band_pos *P, long i, long j, double w,
                                                           const double e[3], bool white)
{
	if (!(w > 0))
		return;
	long ti = floordiv(i), tj = floordiv(j);
	if (ti != P->ti || tj != P->tj)
		P->t = band_tile(P->B, P->m, ti, tj), P->ti = ti, P->tj = tj;
	if (P->grey) { /* acc_add_fast's or acc_add's white light, on the one channel */
		struct gacc *g = &P->t->g[tile_rem(j) * ILLUM_TILE + tile_rem(i)];
		double x = w * e[0];
		if (P->finite)
			fx_add_fast(&g->e, fx_from(x * P->inv));
		else
			fx_add(&g->e, fx_from(x * P->inv));
		g->sq += (float)(x * x);
		g->count += g->count < UINT32_MAX;
		return;
	}
	struct acc *n = &P->t->n[tile_rem(j) * ILLUM_TILE + tile_rem(i)];
	if (P->finite)
		acc_add_fast(n, w, e, white, P->inv);
	else
		acc_add(n, w, e, P->inv);
}

/* fx_from(d) for d·2^96 in [0, 2^128) (a deposit into a map whose sums
 * cannot saturate): the same rounding below 2^52, and above it, where a
 * double is an integer, its bits shifted into place instead of two
 * conversions to unsigned (each a compare and a fix-up on x86-64). */
static inline struct fx fx_from_fast(double d)
{
	double m = d * 0x1p96;
	if (m < 0x1p63) {
		if (m < 0x1p52) /* rint, as fx_from */
			m = (m + 0x1p52) - 0x1p52;
		return (struct fx){m > 0 ? (uint64_t)(int64_t)m : 0, 0};
	}
	uint64_t b;
	memcpy(&b, &m, sizeof b);
	int e = (int)(b >> 52) - 1075; /* m = mant·2^e, e in [11, 75] */
	uint64_t mant = (b & 0xfffffffffffffull) | 0x10000000000000ull;
	if (e < 64)
		return (struct fx){mant << e, mant >> (64 - e)};
	return (struct fx){0, mant << (e - 64)};
}

/* band_add on a grey map whose sums cannot saturate (P->grey, P->finite),
 * e the splat's one channel. */
__attribute__((always_inline)) static inline void grey_add(struct band_pos *P, long i, long j, double w, double e)
{
	if (!(w > 0))
		return;
	long ti = floordiv(i), tj = floordiv(j);
	if (ti != P->ti || tj != P->tj)
		P->t = band_tile(P->B, P->m, ti, tj), P->ti = ti, P->tj = tj;
	struct gacc *g = &P->t->g[tile_rem(j) * ILLUM_TILE + tile_rem(i)];
	double x = w * e;
	fx_add_fast(&g->e, fx_from_fast(x * P->inv));
	g->sq += (float)(x * x);
	g->count += g->count < UINT32_MAX;
}

/* Which splats band k of nb can skip without splitting them: a splat's
 * two node rows lie in the 32-row stripe (band_of) where its row
 * coordinate t = (v − lo) / step lies, when t is half a row or more inside
 * it; x = (v − lo)·(1 / step) is within 10^-6 rows of t (snap moves it by
 * SNAP at most, the product differs from the quotient by a few ulps of
 * |t| <= 2^30). Not on a wrapping axis (fmod), nor within a row and a half
 * of a bounded axis's ends or the plane's limits (clamped), where the
 * splat is split as before. */
struct band_skip {
	double lo, inv, xlo, xhi; /* x's origin and scale; the range where the test holds */
	long k;                   /* the band */
	int nb;
	bool on;
};

static struct band_skip band_skip_for(const struct axis *a, long k, int nb)
{
	struct band_skip b = {a->lo, 1 / a->step, 0, 0, k, nb, nb > 1 && !a->wraps};
	b.xlo = a->bounded ? 1.5 : -PLANE_LIMIT + 1.5;
	b.xhi = a->bounded ? (double)(a->n - 1) - 1.5 : PLANE_LIMIT - 1.5;
	return b;
}

/* Is splat row coordinate v surely none of band b's? (NaN: no.) */
__attribute__((always_inline)) static inline bool band_skips(const struct band_skip *b, double v)
{
	double x = (v - b->lo) * b->inv;
	if (!(x >= b->xlo && x <= b->xhi))
		return false;
	double y = x * (1.0 / 32);
	long st = (long)y; /* the stripe: floor(y), inline (|y| < 2^26) */
	if ((double)st > y)
		st--;
	double r = x - 32 * (double)st; /* x's place in it */
	if (!(r >= 0.5 && r <= 30.5))
		return false;
	int band = (b->nb & (b->nb - 1)) == 0 ? (int)((unsigned long)st & (unsigned long)(b->nb - 1))
	                                       : (int)(((st % b->nb) + b->nb) % b->nb);
	return band != b->k;
}

/* Step 3 for band k of nb: its tiles are made and its nodes accumulated,
 * deposits in order; prep: D->p holds their splits. */
__attribute__((always_inline)) static inline void accumulate_band(struct deposit_job *D, long k, bool prep)
{
	struct illum_map *m = D->m;
	const struct axis *ax = &m->ax[0], *ay = &m->ax[1];
	struct band_pos P = {D + k, m, LONG_MIN, LONG_MIN, NULL, m->inv_unit, m->bound < 0x1p32 * m->unit, m->grey};
	const struct band_skip bs = band_skip_for(ay, k, D->nb);
	for (long q = 0, r = 0; q < D->n; q++) {
		struct illum_splat sp = splat_at(D, q, &r); /* r: the run of splat q */
		if (!prep && bs.on && band_skips(&bs, sp.v))
			continue;
		double e[3];
		/* a grey map's splats are white: the valid ones have e[0] > 0 */
		bool fast = P.grey && P.finite;
		if (prep ? D->p[q].i == INT32_MIN
		         : fast ? !(isfinite(sp.u) && isfinite(sp.v) && sp.e[0] > 0) : !splat_valid(&sp, e))
			continue;
		long j0, j1, i0, i1;
		double fu, fv;
		if (prep) /* split in step 1 */
			j0 = D->p[q].j, j1 = ay->wraps && j0 + 1 == ay->n ? 0 : j0 + 1, fv = D->p[q].fv;
		else
			axis_split(ay, sp.v, &j0, &j1, &fv);
		bool mine0 = true, mine1 = true;
		if (D->nb > 1) {
			mine0 = band_of(j0, D->nb) == (int)k;
			mine1 = band_of(j1, D->nb) == (int)k;
			if (!mine0 && !mine1)
				continue;
		}
		if (prep)
			i0 = D->p[q].i, i1 = ax->wraps && i0 + 1 == ax->n ? 0 : i0 + 1, fu = D->p[q].fu;
		else
			axis_split(ax, sp.u, &i0, &i1, &fu);
		if (fast && i1 != i0 && j1 != j0) {
			/* the usual case: a grey map (so every splat is white, and
			 * valid ones have e[0] > 0) whose sums cannot saturate. The
			 * four nodes are distinct, each takes one addition, so they
			 * may be visited tile by tile: down the columns when the
			 * splat spans two tile columns, else along the rows */
			double e0 = sp.e[0], u0 = 1 - fu, v0 = 1 - fv;
			if (floordiv(i0) != floordiv(i1)) {
				if (mine0)
					grey_add(&P, i0, j0, u0 * v0, e0);
				if (mine1) {
					grey_add(&P, i0, j1, u0 * fv, e0);
					grey_add(&P, i1, j1, fu * fv, e0);
				}
				if (mine0)
					grey_add(&P, i1, j0, fu * v0, e0);
			} else {
				if (mine0) {
					grey_add(&P, i0, j0, u0 * v0, e0);
					grey_add(&P, i1, j0, fu * v0, e0);
				}
				if (mine1) {
					grey_add(&P, i1, j1, fu * fv, e0);
					grey_add(&P, i0, j1, u0 * fv, e0);
				}
			}
			continue;
		}
		if (fast || prep) /* (else splat_valid cleaned it) */
			energy_clean(sp.e, e);
		bool white = e[0] == e[1] && e[1] == e[2];
		double u0 = 1 - fu, v0 = 1 - fv;
		if (mine0) {
			band_add(&P, i0, j0, u0 * v0, e, white);
			band_add(&P, i1, j0, fu * v0, e, white);
		}
		if (mine1) {
			band_add(&P, i0, j1, u0 * fv, e, white);
			band_add(&P, i1, j1, fu * fv, e, white);
		}
	}
}

/* Step 3 for band k of nb (a parallel_for item). */
static void accumulate_work(void *ctx, long k, int worker)
{
	(void)worker;
	struct deposit_job *D = ctx;
	if (D->p)
		accumulate_band(D, k, true);
	else
		accumulate_band(D, k, false);
}

/* Step 4 for band k (a parallel_for item): its window tiles join the map's
 * list at D[k].first. */
static void join_work(void *ctx, long k, int worker)
{
	(void)worker;
	const struct deposit_job *B = (const struct deposit_job *)ctx + k;
	struct illum_map *m = ((const struct deposit_job *)ctx)->m;
	for (long i = 0; i < B->nmade; i++) {
		m->win[B->where[i]] = (int32_t)(B->first + i + 1);
		m->tiles[B->first + i] = B->made[i];
	}
}

#define PREP_CHUNK 16384 /* splats per step-1 item */

void illum_deposit_all(struct illum_map *m, const struct illum_splat *s, long n, int threads)
{
	illum_deposit_runs(m, &(struct illum_run){s, n, sizeof *s, false}, 1, threads);
}

void illum_deposit_runs(struct illum_map *m, const struct illum_run *runs, long nruns, int threads)
{
	int nb = threads < 1 ? 1 : threads > 64 ? 64 : threads;
	long *off = mem_alloc(sizeof *off * (size_t)(nruns + 1)), n = 0;
	off[0] = 0;
	for (long r = 0; r < nruns; r++)
		off[r + 1] = n += runs[r].n > 0 ? runs[r].n : 0;
	if (n <= 0) {
		free(off);
		return;
	}
	if (n < 8192)
		nb = 1;
	long nchunks = (n + PREP_CHUNK - 1) / PREP_CHUNK, nj = nchunks > nb ? nchunks : nb;
	struct deposit_job *D = mem_calloc((size_t)nj, sizeof *D);
	D[0] = (struct deposit_job){.m = m, .runs = runs, .off = off, .nruns = nruns,
	                            .p = n <= PREP_MAX || !m->grey ? mem_alloc_huge(sizeof *D->p * (size_t)n) : NULL, .n = n,
	                            .chunk = PREP_CHUNK, .nb = nb};
	parallel_for(nchunks, nb, scan_work, D);
	double emax = 0; /* n·emax bounds the total whatever the order: the unit is too */
	bool white = true;
	for (long k = 0; k < nchunks; k++)
		emax = D[k].emax > emax ? D[k].emax : emax, white = white && D[k].white;
	if (!white)
		ungrey(m);
	map_reserve(m, (double)n * emax);
	long valid = prep_window(D, nchunks);
	/* each band's tiles in blocks of about what a sparse map of its share
	 * of the splats needs (~128 bytes a splat; a few KiB at least, 16 MiB
	 * at most): large ones are backed by huge pages (mem_huge), so a map of
	 * many tiles takes one page fault per 2 MiB, not one per 4 KiB */
	double guess = 128.0 * (double)valid / nb;
	size_t first = guess < 4096 ? 4096 : guess > (double)(16 << 20) ? (size_t)16 << 20 : (size_t)guess;
	for (int b = 0; b < nb; b++)
		arena_init_sized(&D[b].pool, first), D[b].nmade = D[b].cap = 0, D[b].made = NULL, D[b].where = NULL,
		D[b].part = NULL;
	parallel_for(nb, nb, accumulate_work, D);
	/* step 4: the bands' tiles join the map (bands hold disjoint tiles), by
	 * their window entries (without reading the tiles, which are cold),
	 * each band's into its own range, on the threads; then the tiles the
	 * bands made outside the window (the order of the list is free:
	 * readers sort it) */
	long total = m->ntiles;
	for (int b = 0; b < nb; b++)
		D[b].first = total, total += D[b].nmade;
	if (total > m->cap) {
		long cap = m->cap ? m->cap : 8;
		while (cap < total)
			cap *= 2;
		m->tiles = mem_realloc(m->tiles, (size_t)cap * sizeof *m->tiles);
		m->bytes += (size_t)(cap - m->cap) * sizeof *m->tiles;
		m->cap = cap;
	}
	parallel_for(nb, nb, join_work, D);
	m->ntiles = total;
	for (int b = 0; b < nb; b++) {
		arena_adopt(&m->pool, &D[b].pool);
		free(D[b].made), free(D[b].where);
		if (D[b].part)
			adopt(m, D[b].part);
	}
	m->finished = false;
	free(D->p), free(D), free(off);
}

static bool same_axis(const struct axis *a, const struct axis *b)
{
	return a->lo == b->lo && a->hi == b->hi && a->step == b->step && a->n == b->n &&
	       a->wraps == b->wraps && a->bounded == b->bounded;
}

bool illum_merge(struct illum_map *dst, const struct illum_map *src)
{
	if (dst->obj != src->obj || !same_axis(&dst->ax[0], &src->ax[0]) ||
	    !same_axis(&dst->ax[1], &src->ax[1]))
		return false;
	map_reserve(dst, src->bound);
	if (src->shift > dst->shift)
		map_rescale(dst, src->shift);
	if (!src->grey)
		ungrey(dst);
	for (long k = 0; k < src->ntiles; k++) {
		const struct tile *s = src->tiles[k];
		long di = tile_find(dst, s->ti, s->tj);
		if (di < 0)
			di = tile_add(dst, s->ti, s->tj);
		tile_accumulate(dst->tiles[di], dst->grey, s, src->grey, dst->shift - src->shift);
	}
	dst->dropped += src->dropped;
	dst->finished = false;
	return true;
}

/* ==== polygon deposits (light-shaft footprints) ============================ */

/* illum_deposit_poly integrates the point deposit over the polygon: node k
 * gets ∫ φ_k / area, φ_k the weight axis_split gives k at each point (tents,
 * wrapped and clamped as for points). Inside one grid cell the four weights
 * are bilinear, so a cell needs only the moments ∫1, x, y, xy of the
 * polygon's part in it: the polygon is clipped to each row of cells (a
 * slab), the slab to each cell of that row, and Green's theorem integrates
 * the pieces (polygon.c). The node weights go to a dense array over the
 * bounding box, whose size the cap below bounds.
 *
 * Work is in NODE UNITS (node i at coordinate i, cells are unit squares) and
 * relative to the first corner, for precision. A polygon whose bounding box
 * spans more than ILLUM_POLY_MAX_CELLS cells is rasterised on a VIRTUAL grid
 * of every s-th node (s a power of two), which bounds time and memory.
 *
 * Fixed point: the shares are quantised by CUMULATIVE rounding, node rows in
 * order and nodes left to right inside a row: node k gets
 * fx(e·C_k) − fx(e·C_k−1), C_k the running sum of the weights up to and
 * including it, over their total. The sum telescopes to fx(e·1) = fx(e),
 * whatever the rounding of the C's, each share is ≥ 0 (C never decreases),
 * and each is off by at most a quantum plus ~e·2^-53. The weights are all
 * computed before any is written, so a thread writing only some rows
 * (illum_deposit_poly_all) rounds them exactly as one writing all. */

#define POLY_FAR 2147483648.0 /* corners are pulled in to 2^31 nodes beyond a clamped edge */
#define POLY_FLAT 1e-13       /* area < POLY_FLAT·diameter²: zero area */
#define NODE_EPS 1e-14        /* a node share (of 1) below this is rounding noise */

/* min and max of finite numbers, inline (fmin and fmax are libm calls). */
static double dmin(double a, double b) { return a < b ? a : b; }
static double dmax(double a, double b) { return a > b ? a : b; }

/* One axis of the grid a polygon is rasterised on. Virtual node I is the
 * map's node I·s, cell c is [c, c+1]. On a clamped axis cell L−1 stands for
 * everything below node L and cell H for everything above node H. */
struct vaxis {
	const struct axis *a; /* the map's axis */
	long s;               /* map nodes per virtual node (1 unless huge) */
	bool clamped;         /* bounded and not wrapping, or the plane (±2^30) */
	long L, H;            /* first and last virtual node of a clamped axis */
	long c0, c1;          /* the cells the polygon's bounding box touches */
	long n0, n1;          /* the nodes those cells weight */
};

/* Axis A of the virtual grid with s map nodes per node, for a polygon
 * spanning [lo, hi] virtual units. */
static void vaxis_init(struct vaxis *A, const struct axis *a, long s, double lo, double hi)
{
	A->a = a;
	A->s = s;
	A->clamped = !a->wraps;
	A->L = a->bounded ? 0 : -(long)(PLANE_LIMIT / (double)s);
	A->H = a->bounded ? (a->n - 1 + s - 1) / s : (long)(PLANE_LIMIT / (double)s);
	double c0 = floor(lo), c1 = fmax_(c0, ceil(hi) - 1);
	if (A->clamped) {
		c0 = fmin_(fmax_(c0, (double)A->L - 1), (double)A->H);
		c1 = fmin_(fmax_(c1, (double)A->L - 1), (double)A->H);
	}
	A->c0 = (long)c0;
	A->c1 = (long)c1;
	A->n0 = A->clamped && A->c0 < A->L ? A->L : A->c0;
	A->n1 = A->clamped && A->c1 >= A->H ? A->H : A->c1 + 1;
}

/* The map node of virtual node I. */
static long vnode(const struct vaxis *A, long I)
{
	long i = I * A->s, n = A->a->n;
	if (A->a->wraps)
		return (i % n + n) % n;
	return A->a->bounded && i > n - 1 ? n - 1 : i;
}

/* Cell c of an axis as a clip interval [lo, hi] and the weights it gives its
 * nodes c ([0]) and c+1 ([1]): al + be·x, x measured from org. Coordinates
 * are relative to r, the first corner's. */
struct cellw {
	double lo, hi, org;
	double al[2], be[2];
	bool has[2];
	bool reg;     /* al = {1, 0}, be = {−1, 1}, both nodes (an unclamped cell) */
};

static struct cellw vcell(const struct vaxis *A, long c, double r)
{
	double o = (double)c - r, o1 = (double)(c + 1) - r; /* as the neighbours compute them */
	if (A->clamped && c < A->L) /* all below node L lands on it */
		return (struct cellw){-INFINITY, (double)A->L - r, o, {0, 1}, {0, 0}, {false, true}, false};
	if (A->clamped && c >= A->H)
		return (struct cellw){(double)A->H - r, INFINITY, o, {1, 0}, {0, 0}, {true, false}, false};
	return (struct cellw){o, o1, o, {1, 0}, {-1, 1}, {true, true}, true};
}

/* One polygon deposit in progress. */
struct fp {
	struct illum_map *m;
	double e[3];                   /* energy per channel (W, ≥ 0) */
	int band, nb;                  /* write only the node rows of band `band` of nb */
	struct vaxis ax[2];            /* u and v */
	struct pt2 r;                  /* virtual (u,v) of the first corner (or of the point) */
	bool point;                    /* zero area: a point deposit at r instead */
	int n;                         /* corners */
	const struct loops *l;         /* the polygon as simple loops, relative to r */
	struct pt2 *slab, *cell, *tmp; /* clip buffers */
	double *sc;                    /* per loop: ±1/(total area), the sign of its winding */
	double *ylo, *yhi;             /* per loop: its v range */
	double *w;                     /* node weights: row k's (k from n0 of v) at w[woff[k] + i], i
	                                  its columns (from n0 of u) clo[k]..chi[k], the only ones
	                                  written (the rest are 0; none when clo[k] > chi[k]) */
	long *clo, *chi, *woff;        /* per row */
	bool sparse;                   /* while integrating: rows are zeroed as written (fp_at), not
	                                  all at first */
	long cols;                     /* nodes per row of the box (w's row stride while integrating) */
	double *pre;                   /* per node row: the running sum of the weights before it */
	double total;                  /* the area, then the sum of all weights (1 to rounding) */
};

/* Corner coordinate x (node units) on axis a: unwrapped to within half a
 * period of the previous corner's *prev (the first corner, prev NULL, is
 * reduced to [0, n)), or pulled in to POLY_FAR beyond a clamped edge (only
 * absurd input moves). */
static double corner_coord(const struct axis *a, double x, const double *prev)
{
	double per = (double)a->n;
	if (a->wraps && !prev) {
		x = fmod(x, per);
		return x < 0 ? x + per : x;
	}
	if (a->wraps)
		return *prev + remainder(x - *prev, per);
	double lo = a->bounded ? 0 : -PLANE_LIMIT, hi = a->bounded ? per - 1 : PLANE_LIMIT;
	return fmin_(fmax_(x, lo - POLY_FAR), hi + POLY_FAR);
}

/* The corners in map node units (node i at i), snapped as axis_split snaps
 * points: a polygon across a seam comes out continuous. */
static void corner_nodes(const struct illum_map *m, const double (*uv)[2], int n, struct pt2 *out)
{
	for (int k = 0; k < n; k++) {
		double x = snap((uv[k][0] - m->ax[0].lo) / m->ax[0].step);
		double y = snap((uv[k][1] - m->ax[1].lo) / m->ax[1].step);
		out[k].x = corner_coord(&m->ax[0], x, k ? &out[k - 1].x : NULL);
		out[k].y = corner_coord(&m->ax[1], y, k ? &out[k - 1].y : NULL);
	}
}

/* Sets up the polygon c[0..n) (map node units): the least coarsening s that
 * keeps the bounding box within ILLUM_POLY_MAX_CELLS cells, the corners in
 * virtual units relative to the first (into v), and the simple loops. False
 * when the area is zero to rounding. */
static bool fp_polygon(struct fp *F, const struct pt2 *c, struct pt2 *v)
{
	double lo[2] = {c[0].x, c[0].y}, hi[2] = {c[0].x, c[0].y};
	for (int k = 1; k < F->n; k++) {
		lo[0] = dmin(lo[0], c[k].x), hi[0] = dmax(hi[0], c[k].x);
		lo[1] = dmin(lo[1], c[k].y), hi[1] = dmax(hi[1], c[k].y);
	}
	long s = 1;
	for (;; s *= 2) {
		for (int d = 0; d < 2; d++)
			vaxis_init(&F->ax[d], &F->m->ax[d], s, lo[d] / (double)s, hi[d] / (double)s);
		double cells = (double)(F->ax[0].c1 - F->ax[0].c0 + 1) * (double)(F->ax[1].c1 - F->ax[1].c0 + 1);
		if (cells <= ILLUM_POLY_MAX_CELLS || s > LONG_MAX / 4)
			break;
	}
	F->r = (struct pt2){c[0].x / (double)s, c[0].y / (double)s}; /* s is a power of two: exact */
	for (int k = 0; k < F->n; k++)
		v[k] = (struct pt2){c[k].x / (double)s - F->r.x, c[k].y / (double)s - F->r.y};
	poly_split(&F->m->loops, v, F->n);
	F->l = &F->m->loops;
	double area = 0, du = (hi[0] - lo[0]) / (double)s, dv = (hi[1] - lo[1]) / (double)s;
	for (int k = 0; k < F->l->n; k++)
		area += fabs(poly_area(F->l->pt + F->l->start[k], F->l->len[k]));
	F->total = area; /* until fp_run: the area, for the loop weights */
	return area > POLY_FLAT * (du * du + dv * dv);
}

/* Sets up a point deposit at the mean of c[0..n): the one cell axis_split
 * would use, with the same snapping and clamping. */
static void fp_point(struct fp *F, const struct pt2 *c)
{
	double x = 0, y = 0;
	for (int k = 0; k < F->n; k++) {
		x += c[k].x;
		y += c[k].y;
	}
	x = snap(x / F->n);
	y = snap(y / F->n);
	vaxis_init(&F->ax[0], &F->m->ax[0], 1, x, x);
	vaxis_init(&F->ax[1], &F->m->ax[1], 1, y, y);
	F->r = (struct pt2){x, y};
	F->point = true;
}

/* Grows buf (cap elements of sz bytes) to at least n; kept between deposits. */
static void *grow(void *buf, size_t *cap, size_t n, size_t sz)
{
	if (n <= *cap)
		return buf;
	size_t c = *cap ? *cap : 64;
	while (c < n)
		c *= 2;
	*cap = c;
	return mem_realloc(buf, c * sz);
}

#define FP_DENSE 4096 /* weights of a footprint's box zeroed at once, at most (32 KiB) */

/* The loop weights and ranges and the node weights (zeroed, or each row as
 * it is written: F->sparse), from the map's scratch. */
static void fp_alloc(struct fp *F)
{
	struct illum_map *m = F->m;
	size_t loops = F->point ? 0 : (size_t)F->l->n;
	size_t rows = (size_t)(F->ax[1].n1 - F->ax[1].n0 + 1), cols = (size_t)(F->ax[0].n1 - F->ax[0].n0 + 1);
	size_t need = 3 * loops + rows * cols + rows + 1;
	m->rows = grow(m->rows, &m->cap_rows, need, sizeof *m->rows);
	m->spans = grow(m->spans, &m->cap_spans, 3 * rows, sizeof *m->spans);
	F->sc = m->rows;
	F->ylo = F->sc + loops;
	F->yhi = F->ylo + loops;
	F->pre = F->yhi + loops;
	F->w = F->pre + rows + 1;
	F->cols = (long)cols;
	F->clo = m->spans, F->chi = F->clo + rows, F->woff = F->chi + rows;
	/* a small box zeroed whole, every column of every row taken as written;
	 * a large one row by row as written (fp_at): the box of a thin slanted
	 * footprint is mostly empty, and zeroing and reading it all cost more
	 * than its cells */
	F->sparse = rows * cols > FP_DENSE;
	if (!F->sparse)
		memset(F->w, 0, rows * cols * sizeof *F->w);
	for (size_t k = 0; k < rows; k++)
		F->clo[k] = F->sparse ? (long)cols : 0, F->chi[k] = F->sparse ? -1 : (long)cols - 1,
		F->woff[k] = (long)(k * cols);
	for (size_t k = 0; k < loops; k++) {
		const struct pt2 *p = F->l->pt + F->l->start[k];
		F->sc[k] = copysign(1 / F->total, poly_area(p, F->l->len[k]));
		F->ylo[k] = F->yhi[k] = p[0].y;
		for (int q = 1; q < F->l->len[k]; q++)
			F->ylo[k] = dmin(F->ylo[k], p[q].y), F->yhi[k] = dmax(F->yhi[k], p[q].y);
	}
}

/* Loop l's part in the slab of a cell row (wv), *k corners: the loop itself
 * when it lies inside (most small polygons: clipping would copy it
 * unchanged), else clipped into F->slab. */
static const struct pt2 *fp_slab(struct fp *F, int l, const struct cellw *wv, int *k)
{
	const struct pt2 *p = F->l->pt + F->l->start[l];
	if (F->ylo[l] >= wv->lo && F->yhi[l] <= wv->hi) {
		*k = F->l->len[l];
		return p;
	}
	*k = poly_clip_range(p, F->l->len[l], 1, wv->lo, wv->hi, F->ylo[l], F->yhi[l], F->slab, F->tmp);
	return F->slab;
}

/* The weight of row r, column c (from the box's first node), zeroed on the
 * row's first write there, with the columns between it and those written
 * before (fp_alloc). */
static double *fp_at(struct fp *F, long r, long c)
{
	double *w = F->w + F->woff[r];
	if (F->clo[r] > F->chi[r]) {
		w[c] = 0;
		F->clo[r] = F->chi[r] = c;
	} else if (c < F->clo[r]) {
		memset(w + c, 0, sizeof *w * (size_t)(F->clo[r] - c));
		F->clo[r] = c;
	} else if (c > F->chi[r]) {
		memset(w + F->chi[r] + 1, 0, sizeof *w * (size_t)(c - F->chi[r]));
		F->chi[r] = c;
	}
	return &w[c];
}

/* Adds sc × the weights the moments mo of cell (cu, cv) give its nodes
 * (sparse: F->sparse, a constant where it is inlined). */
__attribute__((always_inline)) static inline void fp_add(struct fp *F, long cu, long cv, const struct cellw *wu,
                                                         const struct cellw *wv, struct moments mo, double sc,
                                                         bool sparse)
{
	if (wu->reg && wv->reg) {
		/* the four weights below with the factors 1, 0 and −1 multiplied
		 * out: the same sums, less the terms that are ±0 (which change a
		 * nonzero sum not at all, and a weight only in the sign of a zero,
		 * which the += leaves at +0: no weight is ever −0) */
		double w[4] = {((mo.a - mo.y) - mo.x) + mo.xy, mo.x - mo.xy, mo.y - mo.xy, mo.xy};
		for (int b = 0; b < 2; b++)
			for (int a = 0; a < 2; a++) {
				long r = cv + b - F->ax[1].n0, c = cu + a - F->ax[0].n0;
				*(sparse ? fp_at(F, r, c) : &F->w[r * F->cols + c]) += sc * w[2 * b + a];
			}
		return;
	}
	for (int b = 0; b < 2; b++)
		for (int a = 0; a < 2; a++) {
			if (!wu->has[a] || !wv->has[b])
				continue;
			double w = wu->al[a] * wv->al[b] * mo.a + wu->al[a] * wv->be[b] * mo.y +
			           wu->be[a] * wv->al[b] * mo.x + wu->be[a] * wv->be[b] * mo.xy;
			long r = cv + b - F->ax[1].n0, c = cu + a - F->ax[0].n0;
			*(sparse ? fp_at(F, r, c) : &F->w[r * F->cols + c]) += sc * w;
		}
}

/* The cell of axis A holding virtual coordinate c (within the box's cells). */
static long cell_of(const struct vaxis *A, double c)
{
	return (long)dmin(dmax(floor(c), (double)A->c0), (double)A->c1);
}

/* The weights cell row cv gives its nodes. Only the cells the row's slab
 * spans are clipped, and a piece inside its cell is not. sparse: F->sparse
 * (a constant: fp_cell_row). */
__attribute__((always_inline)) static inline void fp_cell_row_as(struct fp *F, long cv, bool sparse)
{
	const struct vaxis *U = &F->ax[0];
	struct cellw wv = vcell(&F->ax[1], cv, F->r.y);
	if (F->point) {
		struct cellw wu = vcell(U, U->c0, F->r.x);
		double x = -wu.org, y = -wv.org;
		fp_add(F, U->c0, cv, &wu, &wv, (struct moments){1, x, y, x * y}, 1, sparse);
		return;
	}
	for (int l = 0; l < F->l->n; l++) {
		int k, kc;
		const struct pt2 *p = fp_slab(F, l, &wv, &k), *c;
		if (k < 3)
			continue;
		double lo = p[0].x, hi = lo;
		for (int q = 1; q < k; q++)
			lo = dmin(lo, p[q].x), hi = dmax(hi, p[q].x);
		long c1 = cell_of(U, ceil(hi + F->r.x) - 1);
		for (long cu = cell_of(U, lo + F->r.x); cu <= c1; cu++) {
			struct cellw wu = vcell(U, cu, F->r.x);
			if (lo >= wu.lo && hi <= wu.hi)
				c = p, kc = k;
			else
				c = F->cell, kc = poly_clip_range(p, k, 0, wu.lo, wu.hi, lo, hi, F->cell, F->tmp);
			if (kc >= 3)
				fp_add(F, cu, cv, &wu, &wv, poly_moments(c, kc, (struct pt2){wu.org, wv.org}), F->sc[l],
				       sparse);
		}
	}
}

static void fp_cell_row(struct fp *F, long cv)
{
	if (F->sparse)
		fp_cell_row_as(F, cv, true);
	else
		fp_cell_row_as(F, cv, false);
}

/* Zeroes the weights below NODE_EPS (rounding noise: slivers, degenerate
 * pieces) and keeps the running sum of the weights, node by node in row
 * order, at the start of each row in pre; F->total gets the whole sum. */
static void fp_row_sums(struct fp *F)
{
	long rows = F->ax[1].n1 - F->ax[1].n0 + 1;
	double run = 0;
	for (long k = 0; k < rows; k++) {
		double *w = F->w;
		long o = F->woff[k];
		F->pre[k] = run;
		for (long i = F->clo[k]; i <= F->chi[k]; i++) { /* (the rest are 0: adding them changes no bit) */
			if (!(w[o + i] >= NODE_EPS))
				w[o + i] = 0;
			run += w[o + i];
		}
	}
	F->pre[rows] = F->total = run;
}

/* Advances the cumulative fixed-point energies cum to the first `upto` (of
 * F->total) of the flux; d (may be NULL) gets the increments. Channels
 * 0..nc-1 only: nc = 1 for white light, whose three are the same numbers. */
static void fp_cum(const struct fp *F, int nc, double upto, struct fx cum[3], struct fx d[3])
{
	double q = upto / F->total;
	for (int c = 0; c < nc; c++) {
		struct fx x = F->e[c] > 0 ? fx_from(F->e[c] * q) : (struct fx){0, 0};
		if (d)
			d[c] = fx_sub(x, cum[c]);
		cum[c] = x;
	}
}

/* Adds the quantised shares d (in units of `unit`) to node n: one sample
 * with that weight. White light (fp_cum's nc = 1): d[0] for all three. */
static void acc_add_fx(struct acc *n, const struct fx d[3], double unit, bool white)
{
	if (white) { /* the same numbers as below, worked out once */
		double x = fx_to_double(d[0]) * unit;
		float q = (float)(x * x);
		for (int c = 0; c < 3; c++) {
			fx_add(&n->e[c], d[0]);
			n->sq[c] += q;
		}
	} else {
		for (int c = 0; c < 3; c++) {
			fx_add(&n->e[c], d[c]);
			double x = fx_to_double(d[c]) * unit;
			n->sq[c] += (float)(x * x);
		}
	}
	n->count += n->count < UINT32_MAX;
}

/* acc_add_fx's white light on a grey map's node: its one channel gets what
 * each of the three would. */
static void gacc_add_fx(struct gacc *g, struct fx d, double unit)
{
	double x = fx_to_double(d) * unit;
	fx_add(&g->e, d);
	g->sq += (float)(x * x);
	g->count += g->count < UINT32_MAX;
}

/* fp_emit on a grey map (white light) that cannot saturate: the same
 * numbers, with the conversions that need no saturation (fx_from_fast:
 * the cumulative share never passes F->e[0] < 2^32; fx_add_fast) and each
 * tile looked up once for the nodes of the row it holds. */
static void fp_emit_grey(struct fp *F, long k)
{
	struct illum_map *m = F->m;
	const double *w = F->w;
	long o = F->woff[k], fj = vnode(&F->ax[1], F->ax[1].n0 + k), rem = tile_rem(fj) * ILLUM_TILE, tj = floordiv(fj);
	double C = F->pre[k], e = F->e[0], total = F->total, unit = m->unit;
	struct fx cum = e > 0 ? fx_from_fast(e * (C / total)) : (struct fx){0, 0};
	long lti = LONG_MIN;
	struct gacc *row = NULL; /* tile lti's row fj */
	for (long i = F->clo[k]; i <= F->chi[k]; i++) {
		if (w[o + i] == 0)
			continue;
		C += w[o + i];
		struct fx x = e > 0 ? fx_from_fast(e * (C / total)) : (struct fx){0, 0}, d = fx_sub(x, cum);
		cum = x;
		long fi = vnode(&F->ax[0], F->ax[0].n0 + i), ti = floordiv(fi);
		if (ti != lti) { /* a tile the window holds, straight from it; else tile_of */
			const int32_t *ws = win_slot(m, ti, tj);
			row = (ws && *ws > 0 ? m->tiles[*ws - 1] : tile_of(m, fi, fj, true))->g + rem, lti = ti;
		}
		struct gacc *g = row + tile_rem(fi);
		double xd = fx_to_double(d) * unit;
		fx_add_fast(&g->e, d);
		g->sq += (float)(xd * xd);
		g->count += g->count < UINT32_MAX;
	}
}

/* Quantises node row k (from n0) cumulatively into the map: C repeats the
 * additions of fp_row_sums from pre[k], so the row ends exactly where the
 * next one starts, whoever writes it. */
static void fp_emit(struct fp *F, long k)
{
	if (F->m->grey && F->e[0] < 0x1p31 && F->m->bound < 0x1p31 * F->m->unit) {
		fp_emit_grey(F, k);
		return;
	}
	const double *w = F->w;
	long o = F->woff[k], fj = vnode(&F->ax[1], F->ax[1].n0 + k);
	double C = F->pre[k];
	struct fx cum[3], d[3];
	bool white = F->e[0] == F->e[1] && F->e[1] == F->e[2];
	int nc = white ? 1 : 3;
	fp_cum(F, nc, C, cum, NULL);
	for (long i = F->clo[k]; i <= F->chi[k]; i++) {
		if (w[o + i] == 0)
			continue;
		C += w[o + i];
		fp_cum(F, nc, C, cum, d);
		long fi = vnode(&F->ax[0], F->ax[0].n0 + i);
		if (F->m->grey) /* (white: illum_deposit_poly_all) */
			gacc_add_fx(&tile_of(F->m, fi, fj, true)->g[tile_rem(fj) * ILLUM_TILE + tile_rem(fi)], d[0],
			            F->m->unit);
		else
			acc_add_fx(node_acc(F->m, fi, fj, true), d, F->m->unit, white);
	}
}

/* Node row J is this deposit's to write: in its band. */
static bool row_mine(const struct fp *F, long J)
{
	return F->nb == 1 || band_of(vnode(&F->ax[1], J), F->nb) == F->band;
}

/* Whether any node row of the deposit is in its band. */
static bool fp_any_mine(const struct fp *F)
{
	for (long J = F->ax[1].n0; J <= F->ax[1].n1; J++)
		if (row_mine(F, J))
			return true;
	return false;
}

/* Integrates the node weights and their row sums; false when no node has
 * a share. */
static bool fp_weights(struct fp *F)
{
	fp_alloc(F);
	for (long cv = F->ax[1].c0; cv <= F->ax[1].c1; cv++)
		fp_cell_row(F, cv);
	fp_row_sums(F);
	return F->total > 0;
}

/* Quantises the rows in the band, from the weights. */
static void fp_emit_mine(struct fp *F)
{
	for (long J = F->ax[1].n0; J <= F->ax[1].n1; J++)
		if (row_mine(F, J))
			fp_emit(F, J - F->ax[1].n0);
}

/* Integrates, then quantises the rows in the band; false (nothing written)
 * when no node has a share. The weights are the same whoever computes
 * them, so the rounding of a row never depends on who writes it. */
static bool fp_run(struct fp *F)
{
	if (!fp_weights(F))
		return false;
	fp_emit_mine(F);
	return true;
}

/* No corner is NaN or infinite. */
static bool corners_finite(const double (*uv)[2], int n)
{
	for (int k = 0; k < n; k++)
		if (!isfinite(uv[k][0]) || !isfinite(uv[k][1]))
			return false;
	return true;
}

/* Sets F (on map m: its unit, its scratch) up for the footprint uv[0..n)
 * of energy e: false when it has no energy. Its corners in node units go to *corners (m's scratch, for a
 * retry as a point); *poly says whether it has an area. */
static bool fp_setup(struct fp *F, struct illum_map *m, const double (*uv)[2], int n, const double e[3],
                     struct pt2 **corners, bool *poly)
{
	*F = (struct fp){.m = m, .band = 0, .nb = 1, .n = n};
	if (!energy_clean(e, F->e))
		return false;
	for (int k = 0; k < 3; k++) /* in the map's unit (map_reserve, done by the caller) */
		F->e[k] *= m->inv_unit;
	/* corners, their virtual copy, and clip buffers for loops of ≤ n corners:
	 * slab 4n, cell 16n, tmp 8n (each Sutherland–Hodgman pass at most doubles) */
	m->pts = grow(m->pts, &m->cap_pts, 30 * (size_t)n + 8, sizeof *m->pts);
	struct pt2 *c = m->pts, *v = c + n;
	F->slab = v + n;
	F->cell = F->slab + 4 * n;
	F->tmp = F->cell + 16 * n;
	corner_nodes(m, uv, n, c);
	*poly = n >= 3 && fp_polygon(F, c, v);
	if (!*poly)
		fp_point(F, c);
	*corners = c;
	return true;
}

/* Whether footprint uv[0..n) may have node rows in band k of nb: false only when
 * its corners' v, widened by two rows (snap, the tents), lie in other
 * bands' stripes (a test before fp_setup, the tenth of a footprint's cost
 * that every band would pay for every footprint). */
static bool may_be_mine(const struct illum_map *m, const double (*uv)[2], int n, int k, int nb)
{
	const struct axis *a = &m->ax[1];
	if (a->wraps)
		return true;
	double lo = INFINITY, hi = -INFINITY;
	for (int c = 0; c < n; c++) {
		double y = (uv[c][1] - a->lo) / a->step;
		lo = y < lo ? y : lo, hi = y > hi ? y : hi;
	}
	if (!(lo > -0x1p30 && hi < 0x1p30) || (a->bounded && (lo < 0 || hi > (double)(a->n - 1))))
		return true; /* (beyond an edge: clamped onto it later) */
	long j0 = (long)floor(lo) - 2, j1 = (long)ceil(hi) + 2;
	if (j1 - j0 >= 16 * ILLUM_TILE * nb) /* a stripe of every band */
		return true;
	for (long j = j0; j <= j1; j++)
		if (band_of(j, nb) == k)
			return true;
	return false;
}

/* illum_deposit_poly, one footprint at a time, into the node rows of band
 * `band` of nb alone (m: that band's part of the map; nb = 1: all rows). */
static void poly_in_band(struct illum_map *m, const double (*uv)[2], int n, const double energy[3], int band,
                         int nb)
{
	if (!uv || n < 1 || !corners_finite(uv, n)) {
		m->dropped += band == 0;
		return;
	}
	struct fp F;
	struct pt2 *c;
	bool poly;
	if ((nb > 1 && !may_be_mine(m, uv, n, band, nb)) || !fp_setup(&F, m, uv, n, energy, &c, &poly))
		return;
	F.band = band, F.nb = nb;
	if (nb > 1 && !fp_any_mine(&F))
		return;
	if (!fp_run(&F) && poly) { /* every row below noise: cannot happen for a real area */
		fp_point(&F, c);
		fp_run(&F);
	}
	m->finished = false;
}

static void poly_one(struct illum_map *m, const double (*uv)[2], int n, const double energy[3])
{
	poly_in_band(m, uv, n, energy, 0, 1);
}

void illum_deposit_poly(struct illum_map *m, const double (*uv)[2], int n, const double energy[3])
{
	ungrey(m); /* (footprints write colour maps) */
	map_reserve(m, energy_max(energy));
	poly_one(m, uv, n, energy);
}

/* A footprint of illum_deposit_poly_all with its node weights, integrated
 * once (step 1) for the bands to write (step 2), as poly_one would. */
struct fp_done {
	bool dropped;         /* corners not finite: counted, nothing written */
	bool live;            /* energy to deposit: set up */
	bool ok;              /* weights with a positive sum: the bands write them */
	struct vaxis mine;    /* the v axis by which a band asks whether it has rows (the
	                         polygon's, before any retry as a point) */
	struct vaxis ax[2];   /* the weights' axes */
	double e[3], total;
	long cols;
	double *pre, *w;      /* in the step's arena of its item: pre, and w's written columns row
	                         after row (struct fp) */
	long *clo, *chi, *woff;
};

/* Footprints per round of the two steps at most, and per step-1 item; and
 * the weights a round may hold, about (poly_bytes): footprints of up to
 * FOOTPRINT_MAX_CELLS cells (lightpass.c) hold up to 8 KiB each, and 16384
 * of them held 130 MB, which the kernel zeroed again every round. */
#define POLY_ROUND 16384
#define POLY_ITEM 256
#define POLY_ROUND_BYTES ((double)(16 << 20))

double illum_footprint_cells(const double (*uv)[2], int n, double du, double dv)
{
	double area = 0, edges = 0;
	for (int c = 0; c < n; c++) {
		const double *a = uv[c], *b = uv[c + 1 < n ? c + 1 : 0];
		area += (a[0] - uv[0][0]) * (b[1] - uv[0][1]) - (b[0] - uv[0][0]) * (a[1] - uv[0][1]);
		edges += fabs(b[0] - a[0]) / du + fabs(b[1] - a[1]) / dv;
	}
	return 0.5 * fabs(area) / (du * dv) + edges + 1;
}

/* About the bytes footprint p's weights take in step 1: twice the cells it
 * touches (illum_footprint_cells; the columns written in its rows) and four
 * numbers a row (pre and the row's columns, struct fp). */
static double poly_bytes(const struct illum_map *m, const struct illum_poly *p)
{
	if (!p->uv || p->n < 1)
		return 0;
	double lo = INFINITY, hi = -INFINITY;
	for (int c = 0; c < p->n; c++)
		lo = p->uv[c][1] < lo ? p->uv[c][1] : lo, hi = p->uv[c][1] > hi ? p->uv[c][1] : hi;
	double bytes = 8 * (2 * illum_footprint_cells(p->uv, p->n, m->ax[0].step, m->ax[1].step) +
	                    4 * ((hi - lo) / m->ax[1].step + 3));
	return isfinite(bytes) ? bytes : 0;
}

struct poly_round {
	const struct illum_poly *const *p; /* the round's footprints */
	long n;
	long item;                        /* footprints per step-1 item (POLY_ITEM, fewer in a small
	                                     round: four items a thread at least) */
	struct fp_done *done;             /* one per footprint */
	struct illum_map **scratch;       /* per worker: buffers for step 1 */
	struct arena *keep;               /* per step-1 item: the weights */
	struct illum_map **part;          /* per band: the tiles it writes */
	int nb;
};

/* Step 1 for item k (a parallel_for item): poly_one's set-up and
 * integration for its footprints, on the worker's scratch map, the weights
 * kept in the item's arena. */
static void poly_weigh(void *ctx, long k, int worker)
{
	struct poly_round *R = ctx;
	struct illum_map *m = R->scratch[worker];
	for (long i = k * R->item; i < R->n && i < (k + 1) * R->item; i++) {
		const struct illum_poly *p = R->p[i];
		struct fp_done *d = &R->done[i];
		memset(d, 0, sizeof *d);
		if (!p->uv || p->n < 1 || !corners_finite(p->uv, p->n)) {
			d->dropped = true;
			continue;
		}
		struct fp F;
		struct pt2 *c;
		bool poly;
		if (!fp_setup(&F, m, p->uv, p->n, p->e, &c, &poly))
			continue;
		d->live = true;
		d->mine = F.ax[1];
		d->ok = fp_weights(&F);
		if (!d->ok && poly) { /* as poly_one */
			fp_point(&F, c);
			d->ok = fp_weights(&F);
		}
		if (!d->ok)
			continue;
		size_t rows = (size_t)(F.ax[1].n1 - F.ax[1].n0 + 1), n = 0;
		for (size_t r = 0; r < rows; r++)
			n += F.clo[r] <= F.chi[r] ? (size_t)(F.chi[r] - F.clo[r] + 1) : 0;
		d->pre = arena_alloc8(&R->keep[k], (rows + 1 + n) * sizeof *d->pre);
		d->w = d->pre + rows + 1;
		d->clo = arena_alloc8(&R->keep[k], 3 * rows * sizeof *d->clo);
		d->chi = d->clo + rows, d->woff = d->chi + rows;
		memcpy(d->pre, F.pre, (rows + 1) * sizeof *d->pre);
		for (size_t r = 0, at = 0; r < rows; r++) { /* the written columns alone, row after row */
			long len = F.clo[r] <= F.chi[r] ? F.chi[r] - F.clo[r] + 1 : 0;
			d->clo[r] = F.clo[r], d->chi[r] = F.chi[r], d->woff[r] = (long)at - F.clo[r];
			if (len)
				memcpy(d->w + at, F.w + F.woff[r] + F.clo[r], sizeof *d->w * (size_t)len);
			at += (size_t)len;
		}
		d->ax[0] = F.ax[0], d->ax[1] = F.ax[1];
		memcpy(d->e, F.e, sizeof d->e);
		d->total = F.total, d->cols = F.cols;
	}
}

/* Step 2 for band k (a parallel_for item): the round's footprints in
 * order, each writing its rows in the band. */
static void poly_write(void *ctx, long k, int worker)
{
	(void)worker;
	struct poly_round *R = ctx;
	struct illum_map *part = R->part[k];
	for (long i = 0; i < R->n; i++) {
		const struct fp_done *d = &R->done[i];
		if (d->dropped) {
			if (k == 0)
				part->dropped++;
			continue;
		}
		struct fp F = {.m = part, .band = (int)k, .nb = R->nb, .ax = {d->mine, d->mine}}; /* the band test reads ax[1] */
		if (!d->live) /* no energy */
			continue;
		if (!fp_any_mine(&F))
			continue;
		if (d->ok) {
			F.ax[0] = d->ax[0], F.ax[1] = d->ax[1];
			memcpy(F.e, d->e, sizeof F.e);
			F.total = d->total, F.cols = d->cols, F.pre = d->pre, F.w = d->w;
			F.clo = d->clo, F.chi = d->chi, F.woff = d->woff;
			fp_emit_mine(&F);
		}
		part->finished = false;
	}
}

/* Footprints written band by band (poly_band). */
struct poly_bands {
	const struct illum_poly *const *p;
	long n;
	struct illum_map **part; /* per band: the tiles it writes, and its scratch */
	int nb;
};

/* Band k of the footprints (a parallel_for item): those with node rows in
 * the band integrated and written there (poly_in_band). A footprint
 * across two bands is integrated by both (a few: bands are stripes of 32
 * node rows), but its weights are written where they were made, still in
 * cache. */
static void poly_band(void *ctx, long k, int worker)
{
	(void)worker;
	const struct poly_bands *B = ctx;
	for (long i = 0; i < B->n; i++)
		poly_in_band(B->part[k], B->p[i]->uv, B->p[i]->n, B->p[i]->e, (int)k, B->nb);
}

/* Whether the footprints p[0..n) are shared out evenly enough among nb
 * bands, by the band of each one's first corner (in a sample), to be
 * written band by band (poly_band): no band has more than 60 % of them. */
static bool bands_even(const struct illum_map *m, const struct illum_poly *const *p, long n, int nb)
{
	long cnt[64] = {0}, all = 0, most = 0, stride = n / WIN_SAMPLE + 1;
	for (long k = 0; k < n; k += stride) {
		if (!p[k]->uv || p[k]->n < 1 || !isfinite(p[k]->uv[0][1]))
			continue;
		long j0, j1;
		double f;
		axis_split(&m->ax[1], p[k]->uv[0][1], &j0, &j1, &f);
		int b = band_of(j0, nb);
		cnt[b]++, all++;
		most = cnt[b] > most ? cnt[b] : most;
	}
	return (double)most <= 0.6 * (double)all;
}

/* Places m's window (win_fit) over where the footprints p[0..n) lie, from
 * the first corner of a sample of them: their tiles are then found by
 * indexing an array, not through the hash (which was a tenth of a shaft
 * pass's time, and its growing tables fresh memory). */
static void poly_window(struct illum_map *m, const struct illum_poly *const *p, long n)
{
	long stride = n / WIN_SAMPLE + 1, ns = 0;
	int32_t *ti = mem_alloc(sizeof *ti * (size_t)(n / stride + 1));
	int32_t *tj = mem_alloc(sizeof *tj * (size_t)(n / stride + 1));
	for (long k = 0; k < n; k += stride) {
		if (!p[k]->uv || p[k]->n < 1 || !isfinite(p[k]->uv[0][0]) || !isfinite(p[k]->uv[0][1]))
			continue;
		long i0, i1, j0, j1;
		double f;
		axis_split(&m->ax[0], p[k]->uv[0][0], &i0, &i1, &f);
		axis_split(&m->ax[1], p[k]->uv[0][1], &j0, &j1, &f);
		ti[ns] = (int32_t)floordiv(i0), tj[ns++] = (int32_t)floordiv(j0);
	}
	win_fit(m, ti, tj, ns, n);
	free(ti), free(tj);
}

/* Gives part (a band's share of m, no tiles yet) a window where m has one. */
static void part_window(struct illum_map *part, const struct illum_map *m)
{
	if (m->win)
		win_new(part, m->wti, m->wtj, m->wnu, m->wnv);
}

void illum_deposit_poly_all(struct illum_map *m, const struct illum_poly *const *p, long n, int threads)
{
	int nb = threads < 1 ? 1 : threads > 64 ? 64 : threads;
	double more = 0;
	bool white = true;
	for (long i = 0; i < n; i++) {
		more += energy_max(p[i]->e);
		white = white && p[i]->e[0] == p[i]->e[1] && p[i]->e[1] == p[i]->e[2];
	}
	if (!white) /* (white light, the usual case: a grey map stays grey, its tiles a third the size) */
		ungrey(m);
	map_reserve(m, more); /* the unit for them all, before any of them (order-free) */
	if (n >= 1024)
		poly_window(m, p, n);
	if (nb == 1 || n < 1024) {
		for (long i = 0; i < n; i++)
			poly_one(m, p[i]->uv, p[i]->n, p[i]->e);
		return;
	}
	if (bands_even(m, p, n, nb)) { /* one thread per band of node rows (band_of), each writing its
	                                  rows of every footprint in order: what poly_one does, band by band */
		struct poly_bands B = {p, n, mem_alloc(sizeof *B.part * (size_t)nb), nb};
		for (int b = 0; b < nb; b++)
			B.part[b] = illum_new_like(m), part_window(B.part[b], m);
		parallel_for(nb, nb, poly_band, &B);
		for (int b = 0; b < nb; b++) /* bands hold disjoint tiles: the order is free */
			adopt(m, B.part[b]);
		free(B.part);
		return;
	}
	/* else in rounds: step 1 integrates every footprint once, on all
	 * threads; step 2 writes them, one thread per band, each band's
	 * footprints in order (a caustic in one band does not keep one thread
	 * busy alone) */
	long nround = n < POLY_ROUND ? n : POLY_ROUND, nitems = (nround + POLY_ITEM - 1) / POLY_ITEM;
	nitems = nitems > 4 * nb ? nitems : 4 * nb; /* (see poly_round.item) */
	struct poly_round R = {.nb = nb};
	R.done = mem_alloc(sizeof *R.done * (size_t)nround);
	R.scratch = mem_alloc(sizeof *R.scratch * (size_t)nb);
	R.part = mem_alloc(sizeof *R.part * (size_t)nb);
	R.keep = mem_alloc(sizeof *R.keep * (size_t)nitems);
	for (int b = 0; b < nb; b++)
		R.scratch[b] = illum_new_like(m), R.part[b] = illum_new_like(m), part_window(R.part[b], m);
	for (long k = 0; k < nitems; k++)
		arena_init(&R.keep[k]);
	for (long at = 0; at < n; at += R.n) {
		double bytes = 0;
		R.p = p + at;
		R.n = 0;
		while (R.n < nround && at + R.n < n && (R.n == 0 || bytes < POLY_ROUND_BYTES))
			bytes += poly_bytes(m, p[at + R.n++]);
		R.item = R.n / (4 * nb) + 1 < POLY_ITEM ? R.n / (4 * nb) + 1 : POLY_ITEM;
		parallel_for((R.n + R.item - 1) / R.item, nb, poly_weigh, &R);
		parallel_for(nb, nb, poly_write, &R);
		for (long k = 0; k < nitems; k++)
			arena_reset(&R.keep[k]);
	}
	for (long k = 0; k < nitems; k++)
		arena_free(&R.keep[k]);
	for (int b = 0; b < nb; b++) { /* bands hold disjoint tiles: the order is free */
		adopt(m, R.part[b]);
		illum_free(R.scratch[b]);
	}
	free(R.done), free(R.scratch), free(R.part), free(R.keep);
}

/* ==== finish: energy → irradiance ========================================= */

/* A_node = ∫ φ dA with φ(u,v) = tent(u)·tent(v), the node's bilinear weight.
 * A tent of half-width h is the average of centred boxes of half-width
 * s ∈ [0,h]: tent(x) = (1/h)∫₀ʰ [|x| < s] ds. So
 *   A_node = (1/(hu·hv)) ∫₀^hu ∫₀^hv C(s,t) ds dt,
 *   C(s,t) = shape_cell_area([u−s,u+s]×[v−t,v+t]),
 * which clips at domain edges exactly as the bilinear split does (half tents
 * at edge nodes). C is linear in s and t for planar pieces and smooth for
 * the curved ones (e.g. ∝ s·sin πt at a sphere pole), so 4×4 Gauss–Legendre
 * is exact or close to machine precision; atlas kinks (box faces) fall on
 * nodes when the map follows the box rule. */
static double node_area(const struct illum_map *m, long i, long j)
{
	static const double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
	                            0.8611363115940526};
	static const double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
	                            0.3478548451374538};
	double u = axis_node(&m->ax[0], i), v = axis_node(&m->ax[1], j), a = 0;
	double hu = m->ax[0].step, hv = m->ax[1].step;
	if (m->obj->kind == OBJ_PLANE) { /* constant Jacobian: the tent integrates to |J|·hu·hv */
		struct illum_map *mm = (struct illum_map *)m;
		if (mm->flat_area <= 0)
			mm->flat_area = shape_cell_area(m->obj, u - 0.5 * hu, u + 0.5 * hu, v - 0.5 * hv, v + 0.5 * hv);
		return mm->flat_area;
	}
	for (int k = 0; k < 4; k++) {
		double s = 0.5 * hu * (1 + x[k]);
		for (int l = 0; l < 4; l++) {
			double t = 0.5 * hv * (1 + x[l]);
			a += 0.25 * w[k] * w[l] * shape_cell_area(m->obj, u - s, u + s, v - t, v + t);
		}
	}
	return a;
}

/* The tiles around tile (ti,tj), tile coordinates ±1 (NULL where absent):
 * the 5×5 neighbourhoods of its nodes mostly fall in them. */
_Static_assert(ILLUM_TILE >= 2 && ILLUM_TILE <= 3, "near and the tile-level test in illum_finish assume 2 or 3");

struct near {
	long ti, tj;
	const struct tile *t[3][3];
};

static void near_fill(const struct illum_map *m, struct near *nb, long ti, long tj)
{
	nb->ti = ti;
	nb->tj = tj;
	for (int b = 0; b < 3; b++)
		for (int a = 0; a < 3; a++) {
			const int32_t *w = win_slot(m, ti + a - 1, tj + b - 1); /* tile_find, the window inline */
			long k = w ? (long)*w - 1 : tile_find(m, (int32_t)(ti + a - 1), (int32_t)(tj + b - 1));
			nb->t[b][a] = k < 0 ? NULL : m->tiles[k];
		}
}

/* Pitfall 2, the isolated-sample rule: a node is ISOLATED when the deposit
 * counts of the 5×5 nodes around it (itself and everything within two
 * spacings, wrapping and clipping as the axes do) add up to at most 4, i.e.
 * at most one ray's bilinear splat reached that neighbourhood. Its energy is
 * then left out of the irradiance (and reported). At the density pitfall 1
 * asks for (≥ 16 rays per node, so ~1600 touches per 5×5 block) a converged
 * map has no such node, and the rule removes exactly nothing. */
static bool node_isolated(const struct illum_map *m, const struct near *nb, long i, long j, uint64_t own)
{
	if (own > 4)
		return false;
	long ru = m->ax[0].wraps ? (m->ax[0].n - 1) / 2 : 2, rv = m->ax[1].wraps ? (m->ax[1].n - 1) / 2 : 2;
	ru = ru > 2 ? 2 : ru;
	rv = rv > 2 ? 2 : rv;
	uint64_t sum = 0;
	for (long dj = -rv; dj <= rv; dj++)
		for (long di = -ru; di <= ru; di++) {
			long a = axis_step(&m->ax[0], i, di), b = axis_step(&m->ax[1], j, dj);
			if ((a < 0 && m->ax[0].bounded) || (b < 0 && m->ax[1].bounded))
				continue; /* past a bounded edge (the plane's nodes go negative) */
			long ta = floordiv(a) - nb->ti + 1, tb = floordiv(b) - nb->tj + 1;
			int slot = (int)(tile_rem(b) * ILLUM_TILE + tile_rem(a));
			const struct tile *t = ta >= 0 && ta < 3 && tb >= 0 && tb < 3 ? nb->t[tb][ta]
			                                                              : node_tile(m, a, b, &slot);
			if (t && (sum += node_count(m, t, slot)) > 4)
				return false;
		}
	return true;
}

#define FINISH_CHUNK 2048 /* tiles per illum_finish_mt item */

/* A sum of fixed-point numbers in 192 bits, which no sum of a map's nodes
 * passes: added without saturating, then saturated once (wide_fx), which
 * gives what fx_add gives added one by one (the least of the sum and the
 * largest fx) for less work. */
struct wide {
	uint64_t lo, hi, top;
};

static inline void wide_add(struct wide *a, struct fx b)
{
	uint64_t lo = a->lo + b.lo, c1 = lo < b.lo;
	uint64_t hi = a->hi + b.hi, c2 = hi < b.hi;
	uint64_t hi2 = hi + c1;
	a->lo = lo;
	a->hi = hi2;
	a->top += c2 + (hi2 < c1);
}

static struct fx wide_fx(struct wide a)
{
	return a.top ? (struct fx){UINT64_MAX, UINT64_MAX} : (struct fx){a.lo, a.hi};
}

struct finish_job {
	struct illum_map *m;
	long k0, k1;      /* tiles [k0, k1) */
	bool discard;
	struct fx rem[3]; /* energy the isolated rule removed (exact) */
	struct fx tot[3]; /* energy its tiles hold (exact) */
	int32_t rti[2], rtj[2]; /* the least and greatest tile indices of its tiles */
};

static uint64_t tile_count(const struct illum_map *m, const struct tile *t)
{
	uint64_t c = 0;
	for (int q = 0; q < TN; q++)
		c += node_count(m, t, q);
	return c;
}

/* Do the 5×5 neighbourhoods of tile (ti,tj)'s nodes stay in the 3×3 tiles
 * around it? Not where a wrapping axis's neighbourhood crosses its seam
 * (node_isolated then reaches the tiles on the other side). */
static bool near_closed(const struct illum_map *m, long ti, long tj)
{
	for (int a = 0; a < 2; a++) {
		long lo = (a ? tj : ti) * ILLUM_TILE - 2, hi = (a ? tj : ti) * ILLUM_TILE + ILLUM_TILE - 1 + 2;
		if (m->ax[a].wraps && (lo < 0 || hi > m->ax[a].n - 1))
			return false;
	}
	return true;
}

/* The deposit count of the 3×3 tiles nb holds, stopping past 4. */
static uint64_t near_count(const struct illum_map *m, const struct near *nb)
{
	uint64_t c = 0;
	for (int b = 0; b < 3 && c <= 4; b++)
		for (int a = 0; a < 3; a++)
			if (nb->t[b][a])
				c += tile_count(m, nb->t[b][a]);
	return c;
}

#define NEAR_N (3 * ILLUM_TILE) /* nodes a side of the 3×3 tiles of a struct near */

/* The deposit counts of the 3×3 tiles nb holds, as one array of nodes
 * (zero where a tile is absent: most are, around a sparse map's tiles). */
static void near_counts(const struct illum_map *m, const struct near *nb, uint32_t c[NEAR_N][NEAR_N])
{
	memset(c, 0, sizeof c[0] * NEAR_N);
	for (int b = 0; b < 3; b++)
		for (int a = 0; a < 3; a++) {
			const struct tile *t = nb->t[b][a];
			if (t)
				for (int y = 0; y < ILLUM_TILE; y++)
					for (int x = 0; x < ILLUM_TILE; x++)
						c[b * ILLUM_TILE + y][a * ILLUM_TILE + x] = node_count(m, t, y * ILLUM_TILE + x);
		}
}

/* node_isolated for node q of the middle tile of c (near_counts), when its
 * 5×5 neighbourhood lies inside c (near_closed, two nodes each way): the
 * same sum of counts, read from the array. */
static bool near_isolated(uint32_t c[NEAR_N][NEAR_N], int q)
{
	int x = ILLUM_TILE + q % ILLUM_TILE, y = ILLUM_TILE + q / ILLUM_TILE;
	uint64_t sum = 0;
	for (int j = y - 2; j <= y + 2; j++) { /* the row's five, written out */
		const uint32_t *row = &c[j][x - 2];
		sum += (uint64_t)row[0] + row[1] + row[2] + row[3] + row[4];
	}
	return sum <= 4;
}

/* Widens range r (least, greatest) to hold [lo, hi]. */
static inline void range_join(int32_t r[2], int32_t lo, int32_t hi)
{
	r[0] = lo < r[0] ? lo : r[0];
	r[1] = hi > r[1] ? hi : r[1];
}

/* Job k of the array at ctx (a parallel_for item). */
static void finish_work(void *ctx, long job, int worker)
{
	(void)worker;
	struct finish_job *J = (struct finish_job *)ctx + job;
	const struct illum_map *m = J->m;
	/* node_isolated reaches two nodes each way on both axes (not fewer on
	 * a short wrapping axis) */
	bool reach2 = (!m->ax[0].wraps || (m->ax[0].n - 1) / 2 >= 2) && (!m->ax[1].wraps || (m->ax[1].n - 1) / 2 >= 2);
	struct wide tot[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, rem[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
	int32_t rti[2] = {INT32_MAX, INT32_MIN}, rtj[2] = {INT32_MAX, INT32_MIN};
	for (long k = J->k0; k < J->k1; k++) {
		struct tile *t = m->tiles[k];
		range_join(rti, t->ti, t->ti);
		range_join(rtj, t->tj, t->tj);
		for (int q = 0; q < TN; q++) {
			if (m->grey) { /* the three sums are this one (wide_fx below) */
				wide_add(&tot[0], t->g[q].e);
				continue;
			}
			wide_add(&tot[0], t->n[q].e[0]);
			wide_add(&tot[1], t->n[q].e[1]);
			wide_add(&tot[2], t->n[q].e[2]);
		}
		/* the nodes of a tile are neighbours: more than one ray's splat in
		 * it and none of them is isolated */
		bool check = J->discard && tile_count(m, t) <= 4, all = false, closed = false;
		struct near nb = {.ti = 0};
		uint32_t cnt[NEAR_N][NEAR_N];
		if (check) {
			near_fill(m, &nb, t->ti, t->tj);
			/* at most one splat in the tiles around: every node with a
			 * deposit is isolated (its neighbourhood is among them) */
			closed = near_closed(m, t->ti, t->tj);
			all = closed && near_count(m, &nb) <= 4;
			closed = closed && reach2 && !all;
			if (closed) /* else node_isolated looks the nodes up */
				near_counts(m, &nb, cnt);
		}
		t->iso = 0;
		for (int q = 0; q < TN; q++) {
			if (t->area)
				t->area[q] = 0;
			uint32_t count = node_count(m, t, q);
			if (!count)
				continue;
			long i = (long)t->ti * ILLUM_TILE + q % ILLUM_TILE;
			long j = (long)t->tj * ILLUM_TILE + q / ILLUM_TILE;
			if (t->area)
				t->area[q] = node_area(m, i, j);
			if (check && (all || (closed ? near_isolated(cnt, q) : node_isolated(m, &nb, i, j, count)))) {
				t->iso |= 1u << q;
				for (int c = 0; c < (m->grey ? 1 : 3); c++)
					wide_add(&rem[c], node_e(m, t, q, c));
			}
		}
	}
	for (int c = 0; c < 3; c++) /* (J's sums start at 0; a grey map's are all channel 0's) */
		J->tot[c] = wide_fx(tot[m->grey ? 0 : c]), J->rem[c] = wide_fx(rem[m->grey ? 0 : c]);
	J->rti[0] = rti[0], J->rti[1] = rti[1], J->rtj[0] = rtj[0], J->rtj[1] = rtj[1];
}

void illum_finish_mt(struct illum_map *m, bool discard_isolated, double removed[3], int threads)
{
	bool plane = m->obj->kind == OBJ_PLANE;
	/* readers (the isolated rule, lookups) find a tile faster in the window
	 * than in the hash: it is placed again when it holds too few of them
	 * (none, as after single deposits); not for the few grazing rays' tiles
	 * that batched deposits leave outside it (a sample of every tile, one
	 * thread, for nothing) */
	if (m->nhashed > m->ntiles / 8) {
		long stride = m->ntiles / WIN_SAMPLE + 1, ns = 0;
		int32_t *ti = mem_alloc(sizeof *ti * (size_t)(m->ntiles / stride + 1));
		int32_t *tj = mem_alloc(sizeof *tj * (size_t)(m->ntiles / stride + 1));
		for (long k = 0; k < m->ntiles; k += stride)
			ti[ns] = m->tiles[k]->ti, tj[ns++] = m->tiles[k]->tj;
		win_fit(m, ti, tj, ns, 0);
		free(ti), free(tj);
	}
	for (long k = 0; k < m->ntiles && !plane; k++) /* (a plane's nodes share one area) */
		if (!m->tiles[k]->area)
			m->tiles[k]->area = ARENA_ARRAY(&m->pool, double, TN);
	if (plane && m->ntiles) /* its one area, before threads read it */
		node_area(m, 0, 0);
	/* chunks of FINISH_CHUNK tiles, claimed by the threads as they come
	 * free (one held up elsewhere on a busy machine then holds up nothing);
	 * the sums are exact, so the chunks change no bit */
	long nb = m->ntiles < 4096 || threads <= 1 ? 1 : (m->ntiles + FINISH_CHUNK - 1) / FINISH_CHUNK;
	struct finish_job *jobs = mem_alloc(sizeof *jobs * (size_t)nb);
	for (long b = 0; b < nb; b++)
		jobs[b] = (struct finish_job){m, m->ntiles * b / nb, m->ntiles * (b + 1) / nb, discard_isolated,
		                              {{0, 0}, {0, 0}, {0, 0}}, {{0, 0}, {0, 0}, {0, 0}}, {0, 0}, {0, 0}};
	parallel_for(nb, threads, finish_work, jobs);
	struct fx rem[3] = {{0, 0}, {0, 0}, {0, 0}};
	memset(m->total, 0, sizeof m->total);
	m->rti[0] = m->rtj[0] = INT32_MAX, m->rti[1] = m->rtj[1] = INT32_MIN;
	for (long b = 0; b < nb; b++) {
		for (int c = 0; c < 3; c++)
			fx_add(&rem[c], jobs[b].rem[c]), fx_add(&m->total[c], jobs[b].tot[c]);
		range_join(m->rti, jobs[b].rti[0], jobs[b].rti[1]); /* the tiles held (none: empty) */
		range_join(m->rtj, jobs[b].rtj[0], jobs[b].rtj[1]);
	}
	free(jobs);
	if (removed)
		for (int c = 0; c < 3; c++)
			removed[c] = fx_to_double(rem[c]) * m->unit;
	m->finished = true;
}

void illum_finish(struct illum_map *m, bool discard_isolated, double removed[3])
{
	illum_finish_mt(m, discard_isolated, removed, 1);
}

/* Irradiance of node q of tile t after illum_finish: 0 when isolated or
 * without area. */
static double node_irr(const struct illum_map *m, const struct tile *t, int q, int c)
{
	double a = t->area ? t->area[q] : m->flat_area;
	if ((t->iso >> q) & 1 || !(a > 0))
		return 0;
	return fx_to_double(node_e(m, t, q, c)) * m->unit / a;
}

/* Adds w × node_irr for the three channels to out, its checks made once
 * (out ≥ 0: adding w × 0 changes no bit, so nothing is added then). */
static void add_irr(const struct illum_map *m, const struct tile *t, int q, double w, double out[3])
{
	double a = t->area ? t->area[q] : m->flat_area;
	if ((t->iso >> q) & 1 || !(a > 0))
		return;
	if (m->grey) { /* the same irradiance in the three channels */
		double x = fx_to_double(t->g[q].e) * m->unit / a;
		for (int c = 0; c < 3; c++)
			out[c] += w * x;
		return;
	}
	for (int c = 0; c < 3; c++)
		out[c] += w * (fx_to_double(t->n[q].e[c]) * m->unit / a);
}

/* False only when tiles ta and tb (one axis) both lie below or both above
 * the range r of the tiles a finished map holds (rti, rtj): then neither
 * is held. */
static bool in_range(const int32_t r[2], long ta, long tb)
{
	return (ta >= r[0] || tb >= r[0]) && (ta <= r[1] || tb <= r[1]);
}

void illum_lookup(const struct illum_map *m, double u, double v, double out[3])
{
	out[0] = out[1] = out[2] = 0;
	if (!m->finished || !isfinite(u) || !isfinite(v))
		return;
	long iu[2], iv[2];
	double fu, fv;
	axis_split(&m->ax[0], u, &iu[0], &iu[1], &fu);
	axis_split(&m->ax[1], v, &iv[0], &iv[1], &fv);
	/* most maps (a surface's coarser levels) hold nothing near (u,v) */
	if (!in_range(m->rti, floordiv(iu[0]), floordiv(iu[1])) || !in_range(m->rtj, floordiv(iv[0]), floordiv(iv[1])))
		return;
	double wu[2] = {1 - fu, fu}, wv[2] = {1 - fv, fv};
	for (int b = 0; b < 2; b++)
		for (int a = 0; a < 2; a++) {
			double w = wu[a] * wv[b];
			int slot;
			const struct tile *t = w > 0 ? node_tile(m, iu[a], iv[b], &slot) : NULL;
			if (t)
				add_irr(m, t, slot, w, out);
		}
}

/* ==== queries ============================================================= */

void illum_total(const struct illum_map *m, double out[3])
{
	struct fx s[3] = {{0, 0}, {0, 0}, {0, 0}};
	if (m->finished) /* summed by illum_finish (sums saturate alike in any order) */
		memcpy(s, m->total, sizeof s);
	for (long k = 0; k < m->ntiles && !m->finished; k++)
		for (int q = 0; q < TN; q++)
			for (int c = 0; c < 3; c++)
				fx_add(&s[c], node_e(m, m->tiles[k], q, c));
	for (int c = 0; c < 3; c++)
		out[c] = fx_to_double(s[c]) * m->unit;
}

long illum_dropped(const struct illum_map *m) { return m->dropped; }
size_t illum_memory(const struct illum_map *m)
{
	return m->bytes + m->pool.used + loops_bytes(&m->loops) + m->cap_pts * sizeof *m->pts +
	       m->cap_rows * sizeof *m->rows + m->cap_spans * sizeof *m->spans;
}
long illum_tiles(const struct illum_map *m) { return m->ntiles; }

static int tile_cmp(const void *pa, const void *pb)
{
	const struct tile *a = *(const struct tile *const *)pa, *b = *(const struct tile *const *)pb;
	if (a->tj != b->tj)
		return a->tj < b->tj ? -1 : 1;
	return a->ti < b->ti ? -1 : a->ti > b->ti;
}

/* The tiles sorted by (tj, ti); free the result. */
static struct tile **sorted_tiles(const struct illum_map *m)
{
	struct tile **s = mem_alloc((size_t)(m->ntiles ? m->ntiles : 1) * sizeof *s);
	if (m->ntiles)
		memcpy(s, m->tiles, (size_t)m->ntiles * sizeof *s);
	qsort(s, (size_t)m->ntiles, sizeof *s, tile_cmp);
	return s;
}

void illum_each(const struct illum_map *m, void (*fn)(void *ctx, const struct illum_node *n),
                void *ctx)
{
	struct tile **s = sorted_tiles(m);
	for (long k = 0; k < m->ntiles; k++)
		for (int q = 0; q < TN; q++) {
			uint32_t count = node_count(m, s[k], q);
			if (!count)
				continue;
			struct illum_node n;
			memset(&n, 0, sizeof n);
			n.i = (long)s[k]->ti * ILLUM_TILE + q % ILLUM_TILE;
			n.j = (long)s[k]->tj * ILLUM_TILE + q / ILLUM_TILE;
			illum_node_uv(m, n.i, n.j, &n.u, &n.v);
			for (int c = 0; c < 3; c++) {
				n.energy[c] = fx_to_double(node_e(m, s[k], q, c)) * m->unit;
				n.sumsq[c] = m->grey ? s[k]->g[q].sq : s[k]->n[q].sq[c];
			}
			n.count = count;
			if (m->finished) {
				n.area = s[k]->area ? s[k]->area[q] : m->flat_area;
				n.isolated = (s[k]->iso >> q) & 1;
				for (int c = 0; c < 3; c++)
					n.irr[c] = node_irr(m, s[k], q, c);
			}
			fn(ctx, &n);
		}
	free(s);
}

double illum_auto_cell(double rays, double area, double rays_per_node)
{
	if (!(rays > 0) || !(area > 0) || !isfinite(area))
		return 0;
	if (!(rays_per_node > 0))
		rays_per_node = ILLUM_RAYS_PER_NODE;
	return sqrt(rays_per_node * area / rays);
}

int illum_write_exr(const struct illum_map *m, const char *path, struct diag *dg)
{
	if (!m->finished || !m->ntiles)
		return diag_fail(dg, FAIL_INTERNAL, srcloc_none(), "cannot write '%s': the map is empty or not finished",
		                 path);
	long i0 = LONG_MAX, j0 = LONG_MAX, i1 = LONG_MIN, j1 = LONG_MIN; /* node extent, inclusive */
	for (long k = 0; k < m->ntiles; k++) {
		const struct tile *t = m->tiles[k];
		long ti = (long)t->ti * ILLUM_TILE, tj = (long)t->tj * ILLUM_TILE;
		i0 = ti < i0 ? ti : i0;
		j0 = tj < j0 ? tj : j0;
		i1 = ti + ILLUM_TILE - 1 > i1 ? ti + ILLUM_TILE - 1 : i1;
		j1 = tj + ILLUM_TILE - 1 > j1 ? tj + ILLUM_TILE - 1 : j1;
	}
	for (int a = 0; a < 2; a++) /* bounded axes: clip to the grid */
		if (m->ax[a].bounded) {
			long *hi = a ? &j1 : &i1;
			*hi = *hi > m->ax[a].n - 1 ? m->ax[a].n - 1 : *hi;
		}
	long w = i1 - i0 + 1, h = j1 - j0 + 1;
	if (w * h > (1L << 28)) { /* a few far-flung rays on an unbounded plane */
		diag_warning(dg, srcloc_none(), "cannot write '%s': map extent %ldx%ld too large; not dumped", path, w, h);
		return 0;
	}
	struct framebuffer *fb = fb_new((int)w, (int)h);
	float *pl[3] = {fb_plane(fb, "R"), fb_plane(fb, "G"), fb_plane(fb, "B")};
	for (long k = 0; k < m->ntiles; k++) {
		const struct tile *t = m->tiles[k];
		for (int q = 0; q < TN; q++) {
			long i = (long)t->ti * ILLUM_TILE + q % ILLUM_TILE;
			long j = (long)t->tj * ILLUM_TILE + q / ILLUM_TILE;
			if (i > i1 || j > j1)
				continue;
			for (int c = 0; c < 3; c++)
				pl[c][(j1 - j) * w + (i - i0)] = (float)node_irr(m, t, q, c);
		}
	}
	int err = out_exr_write(fb, path, NULL, dg);
	fb_free(fb);
	return err;
}
