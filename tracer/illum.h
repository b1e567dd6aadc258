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
 * Threads: one map per thread while depositing (illum_new_like), merged with
 * illum_merge; after illum_finish, illum_lookup may be called concurrently. */
#ifndef ARVO_ILLUM_H
#define ARVO_ILLUM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "scene.h"

#define ILLUM_TILE 2            /* nodes per tile side: small, since most tiles of a
                                   sparse caustic hold one ray's splat */
#define ILLUM_RAYS_PER_NODE 16  /* illum_auto_cell's default ray density */

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
/* Bytes allocated by the map (header, tile table, tiles). */
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
 * top row = largest v) to an EXR at path; NULL on success, else a message. */
const char *illum_write_exr(const struct illum_map *m, const char *path);

#endif
