/* SPDX-License-Identifier: MIT */
/* illum.h: the illumination map of one surface (Arvo 1986; docs/design.md §4).
 *
 * A map is a grid of NODES (map points) over a primitive's (u,v) domain
 * (tracer/shape.h). The light pass deposits ray energy at (u,v) hits, split
 * bilinearly among the four surrounding nodes; illum_finish turns energy into
 * irradiance (W/m²); the eye pass reads it back with illum_lookup.
 *
 * Grid convention (per axis; `step` is the node spacing in parameter units):
 *   - resolution R (bounded surfaces): step = 1/R. A wrapping axis (sphere,
 *     cylinder, cone, disc, torus u; torus v) has R nodes at i/R, with no
 *     duplicate seam node. A non-wrapping axis has R+1 nodes at i/R, both
 *     domain edges included (so R a multiple of 6 puts nodes on the box
 *     atlas's face boundaries). Poles, apexes and disc centres are edge rows.
 *   - cell S on a bounded surface: per axis, the number of intervals is
 *     ceil(Lmax/S), Lmax the longest world length of a constant-v (resp.
 *     constant-u) curve, so nodes are at most ~S apart everywhere; box maps
 *     round u up to a multiple of 3 and v to a multiple of 2 (atlas faces).
 *   - cell S on the unbounded plane: nodes at (i·du, j·dv), i, j any integers,
 *     du = S/|∂T/∂u| and dv = S/|∂T/∂v| (S in world units under xf).
 *   Points outside a bounded, non-wrapping axis are clamped to its edge.
 *
 * Node area: a node's irradiance is energy / A_node with
 *   A_node = ∫ φ_node dA,  φ_node(u,v) = tent(u)·tent(v) (its bilinear weight),
 * integrated with shape_cell_area (Gauss–Legendre over the half-widths of
 * centred cells, see illum.c). This is the paper's eq. 1 with the area
 * integrated rather than evaluated at the point: finite at poles and apexes,
 * and exactly unbiased for uniform irradiance on any parametrisation (a plain
 * box cell [u±du/2]×[v±dv/2] would read a pole 33 % high, because bilinear
 * splats reach a full spacing from the pole but the box only half of it).
 *
 * Accumulation is in 128-bit fixed point (quantum 2^-96 W, capacity 2^32 W
 * per node and channel), so sums are exact and independent of order:
 * partial maps merged in any order, or deposits made in any order, give
 * bit-identical energies and irradiances. When the energy deposited into a
 * map could exceed 2^31 W (a scene at 1e6 scale), the map's quantum and
 * capacity grow by a power of two first, so nothing saturates. Σw² (for
 * σ²) is a float.
 *
 * Footprints: illum_deposit_poly spreads a light shaft's energy over its
 * polygon on the map, the integral of point deposits over it.
 *
 * Threads: one map per thread while depositing (illum_new_like), merged with
 * illum_merge; after illum_finish, illum_lookup may be called concurrently. */
#ifndef ARVO_ILLUM_H
#define ARVO_ILLUM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "../../common/diag.h"
#include "../scene.h"

#define ILLUM_TILE 2            /* nodes per tile side: small, since most tiles of a
                                   sparse caustic hold one ray's splat */
#define ILLUM_RAYS_PER_NODE 16  /* illum_auto_cell's default ray density */
#define ILLUM_POLY_MAX_CELLS 65536 /* grid cells a polygon deposit may visit (see illum_deposit_poly) */

struct illum_map;

/* One node as illum_each reports it. */
struct illum_node {
	long i, j;          /* node indices (u = u0 + i·du, v = v0 + j·dv) */
	double u, v;        /* its (u,v) */
	double energy[3];   /* deposited energy per channel (W) */
	double sumsq[3];    /* Σ (w·e)² per channel: the variance estimate of energy */
	uint64_t count;     /* deposits that gave this node a nonzero weight */
	double area;        /* A_node (m²); 0 before illum_finish */
	double irr[3];      /* irradiance (W/m²) after illum_finish, 0 if isolated */
	bool isolated;      /* removed by the isolated-sample rule */
};

/* A map for primitive o (not CSG) with the grid of spec: resolution R > 0
 * (bounded surfaces only) or cell S > 0; resolution wins when both are given.
 * Returns NULL for CSG nodes, for a plane without cell, and for absurd sizes. */
struct illum_map *illum_new(const struct object *o, const struct illum_spec *spec);
/* An empty map with the same object and grid as m (a per-thread partial). */
struct illum_map *illum_new_like(const struct illum_map *m);
void illum_free(struct illum_map *m);

/* Grid queries: node counts (0 on an unbounded axis), spacings, node (u,v). */
void illum_grid(const struct illum_map *m, long *nu, long *nv, double *du, double *dv);
void illum_node_uv(const struct illum_map *m, long i, long j, double *u, double *v);

/* Adds energy (per channel, W, ≥ 0; negative or NaN components count as 0)
 * at (u,v), split bilinearly among the four surrounding nodes. Non-finite
 * (u,v) are dropped (counted, see illum_dropped). Not thread-safe. */
void illum_deposit(struct illum_map *m, double u, double v, const double energy[3]);

/* One deposit for illum_deposit_all. */
struct illum_splat {
	double u, v;
	double e[3];
};

/* illum_deposit for s[0..n), on up to `threads` threads (each takes the
 * nodes of its own stripes of rows). The result is the same as depositing
 * them one by one, for any thread count. */
void illum_deposit_all(struct illum_map *m, const struct illum_splat *s, long n, int threads);

/* A white splat (the same energy e in the three channels) in 24 bytes. */
struct illum_gsplat {
	double u, v;
	double e;
};

/* The illum_splat of white splat g: e in each channel. */
static inline struct illum_splat illum_gsplat_splat(const struct illum_gsplat *g)
{
	return (struct illum_splat){g->u, g->v, {g->e, g->e, g->e}};
}

/* Splats s, s + stride, …, n of them, somewhere in the caller's memory (a
 * struct whose first member is the illum_splat, say; or the illum_gsplat
 * when grey). */
struct illum_run {
	const void *s;
	long n;
	size_t stride; /* bytes from one splat to the next */
	bool grey;     /* the splats are struct illum_gsplat */
};

/* illum_deposit_all over the runs r[0..nr) in order, as if they were one
 * array: the same result, without copying them into one. */
void illum_deposit_runs(struct illum_map *m, const struct illum_run *r, long nr, int threads);

/* Spreads energy (per channel, W; negative or NaN components count as 0)
 * uniformly per unit (u,v) area over the polygon uv[0..n) — the footprint of
 * a light shaft — giving node k the share ∫_poly φ_k du dv / area(poly), φ_k
 * the bilinear weight illum_deposit gives node k at each point, wrapped and
 * clamped as there. So a polygon deposit is the limit of point deposits
 * spread evenly over it: a cell-sized square on a cell gives each corner
 * node ¼, and a tiny polygon gives what a point at its centroid gives. The
 * integrals are exact (the polygon is clipped to the grid cells its bounding
 * box touches, and 1, u, v, uv are integrated with Green's theorem). The
 * shares are rounded to the fixed-point quantum cumulatively, so that the
 * map gains exactly the energy rounded once (what illum_deposit adds when
 * the point is on a node): the flux is conserved to the last quantum, for
 * any polygon; each share is right to a quantum plus ~2^-53 of the energy.
 *   Shape: n ≥ 3 corners in (u,v) parameter units, either winding, convex
 *     or not. A self-intersecting polygon is split at its crossings into
 *     simple loops, each covered with positive density: the "bow-tie" a fold
 *     makes of a shaft's quadrilateral becomes its two triangles, which share
 *     the flux in proportion to their areas (crossings are looked for up to
 *     64 corners; a larger self-crossing polygon is spread with its winding
 *     number, nodes whose net share comes out negative getting none). The
 *     density is uniform in (u,v), which is uniform in area for footprints
 *     over which the surface's Jacobian barely changes. A polygon lives in
 *     one chart: on the box's atlas, split shafts at face edges.
 *   Wrapping axes: each corner is taken within half a period of the one
 *     before, so a polygon across the seam lands on both sides. A polygon
 *     around a pole (its corners circling the axis) has no faithful (u,v)
 *     polygon: it is deposited as unwrapped, conserving but smeared; callers
 *     should split such shafts. (One wider than a period reaches some nodes
 *     twice, and counts them twice.)
 *   Clamped axes (bounded non-wrapping axes; the plane beyond ±2^30 nodes):
 *     the part outside the domain lands on the edge nodes, as the points of a
 *     point deposit there do (no energy is lost). Corners more than 2^31
 *     nodes beyond the edge are pulled in to that distance first.
 *   Corners within 1e-9 spacings of a grid line are snapped onto it, as
 *     illum_deposit snaps points.
 *   Degenerate: zero area (below 1e-13 × the squared bounding-box diagonal,
 *     or n < 3) → a point deposit at the mean of the corners, with the same
 *     exact total. A NaN or infinite corner (or n < 1) → dropped, counted by
 *     illum_dropped.
 *   Huge: when the bounding box spans more than ILLUM_POLY_MAX_CELLS cells,
 *     the polygon is spread with the tents of every s-th node (s the least
 *     power of two under the cap) onto those nodes only: exact in total and
 *     right at spacing s, but a comb at the map's own spacing. Time and
 *     memory stay bounded (the cap's worth of nodes); such a polygon means
 *     the shafts are far coarser than the map.
 *   Bookkeeping: a polygon deposit is one sample: each node it gives a
 *     nonzero share gets count + 1 and Σw² += (share·energy)², as the four
 *     nodes of a point deposit do with their bilinear weights.
 * Cost (x86-64, -O2): ~1.0·10^4 instructions for a polygon of about one cell
 * (seven point deposits), ~1.8·10^5 for one of 100 cells: linear in the
 * cells beyond that.
 * Not thread-safe: one map per thread, as for illum_deposit. */
void illum_deposit_poly(struct illum_map *m, const double (*uv)[2], int n, const double energy[3]);

/* One polygon for illum_deposit_poly_all. */
struct illum_poly {
	const double (*uv)[2]; /* corners (the caller's memory) */
	int n;                 /* corner count */
	double e[3];           /* energy per channel */
};

/* illum_deposit_poly for *p[0..n) (pointers: the footprints stay where
 * their maker keeps them), on up to `threads` threads (each writes the
 * nodes of its own stripes of rows). The result is the same, bit for bit,
 * as depositing them one by one, for any thread count. */
void illum_deposit_poly_all(struct illum_map *m, const struct illum_poly *const *p, long n, int threads);

/* About how many grid cells (du × dv) polygon uv[0..n) touches: its area in
 * cells plus its perimeter in cells (the cells its edges cross) plus one.
 * A thin slanted sliver whose bounding box spans thousands of cells touches
 * only those along it; its bounding box would overcount it by far. */
double illum_footprint_cells(const double (*uv)[2], int n, double du, double dv);

/* Adds src's energies, Σw² and counts into dst (same object and grid, else
 * false and dst untouched). dst must not be finished afterwards until
 * illum_finish is called again. */
bool illum_merge(struct illum_map *dst, const struct illum_map *src);

/* Converts energy to irradiance at every node that received any, applying
 * the isolated-sample rule when discard_isolated is set (see illum.c for the
 * rule). Energies are kept, so finishing again (e.g. after a merge) is fine.
 * removed (may be NULL) receives the energy the rule discarded. */
void illum_finish(struct illum_map *m, bool discard_isolated, double removed[3]);
/* illum_finish on up to `threads` threads; the same result. */
void illum_finish_mt(struct illum_map *m, bool discard_isolated, double removed[3], int threads);

/* Bilinearly interpolated irradiance (W/m²) at (u,v); 0 where no tile is
 * allocated and before illum_finish. Thread-safe after illum_finish. */
void illum_lookup(const struct illum_map *m, double u, double v, double out[3]);

/* Total energy held (exact sum of the fixed-point accumulators). */
void illum_total(const struct illum_map *m, double out[3]);
/* Deposits dropped because (u,v) was not finite. */
long illum_dropped(const struct illum_map *m);
/* Bytes the map holds (header, tile table, the tiles' share of their
 * arena's blocks, polygon scratch). */
size_t illum_memory(const struct illum_map *m);
/* Allocated tiles. */
long illum_tiles(const struct illum_map *m);

/* Calls fn for every node with count > 0, tiles in (tile v, tile u) order and
 * nodes row by row inside each tile: a deterministic order. */
void illum_each(const struct illum_map *m, void (*fn)(void *ctx, const struct illum_node *n),
                void *ctx);

/* Pitfall 1 (ray density): the world node spacing S such that `rays` rays
 * landing uniformly on `area` m² give on average `rays_per_node` (≤ 0: the
 * default ILLUM_RAYS_PER_NODE) rays per node: S = sqrt(rays_per_node·area /
 * rays). Returns 0 when rays ≤ 0 or area is not finite and positive. */
double illum_auto_cell(double rays, double area, double rays_per_node);

/* Writes the irradiance of the allocated extent as R,G,B (one pixel per node,
 * top row = largest v) to an EXR at path. Returns 0 (also when the extent is
 * too large to dump: a warning), or out_exr_write's status. */
int illum_write_exr(const struct illum_map *m, const char *path, struct diag *dg);

#endif
