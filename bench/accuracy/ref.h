/* SPDX-License-Identifier: MIT */
/* ref.h: the analytic caustic references (the CSVs in tests/accuracy) as bins on
 * the floor y = 0, shared by accuracy.c (arvo's maps) and povbin.c
 * (POV-Ray's images). A reference is named by a spec:
 *
 *   annuli:CSV:COL       rows r_lo,r_hi,…: annuli around the y axis, column
 *                        COL (0-based) holds each annulus's flux (W)
 *   cells:CSV:COL:XMAX   rows x0,x1,z0,z1,…: a regular grid of floor cells,
 *                        column COL their mean irradiance Ebar (W/m²), so a
 *                        cell's flux is Ebar·(x1−x0)·(z1−z0); cells that
 *                        reach past x = XMAX are left out of the metric
 *
 * The metric is the flux-weighted relative L1 of the references' README:
 * Σ_k |Φ̂_k − Φ_k| / Σ_k Φ_k over the bins kept. Header-only (static inline), so
 * each tool compiles alone. */
#ifndef ARVO_BENCH_REF_H
#define ARVO_BENCH_REF_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct ref {
	int radial;      /* 1: annuli; 0: grid cells */
	double w;        /* annulus width, or cell side */
	double x0, z0;   /* grid origin (cells) */
	int nx, nz;      /* grid size (cells); radial: nx annuli, nz = 1 */
	int n;           /* bins: nx·nz */
	double *flux;    /* per bin: the exact flux (W) */
	unsigned char *keep; /* per bin: 1 when it counts in the metric */
	double area_sum; /* Σ bin areas kept (m²) */
};

/* Splits line into at most max comma-separated numbers; returns the count. */
static inline int ref_fields(char *line, double *out, int max)
{
	int k = 0;
	char *p = line;
	while (k < max && p && *p && *p != '\n') {
		char *end;
		out[k++] = strtod(p, &end);
		p = strchr(end, ',');
		if (p)
			p++;
	}
	return k;
}

/* Reads the reference named by spec into R; 0 on success, else prints why
 * on stderr and returns 1. */
static inline int ref_load(const char *spec, struct ref *R)
{
	char kind[16], path[4096];
	int col = -1;
	double xmax = HUGE_VAL;
	memset(R, 0, sizeof *R);
	const char *c1 = strchr(spec, ':');
	if (!c1 || (size_t)(c1 - spec) >= sizeof kind) {
		fprintf(stderr, "ref: %s: expected annuli:CSV:COL or cells:CSV:COL:XMAX\n", spec);
		return 1;
	}
	memcpy(kind, spec, (size_t)(c1 - spec));
	kind[c1 - spec] = 0;
	const char *c2 = strchr(c1 + 1, ':');
	if (!c2 || (size_t)(c2 - c1 - 1) >= sizeof path) {
		fprintf(stderr, "ref: %s: no column\n", spec);
		return 1;
	}
	memcpy(path, c1 + 1, (size_t)(c2 - c1 - 1));
	path[c2 - c1 - 1] = 0;
	col = atoi(c2 + 1);
	const char *c3 = strchr(c2 + 1, ':');
	if (c3)
		xmax = strtod(c3 + 1, NULL);
	R->radial = !strcmp(kind, "annuli");
	if (!R->radial && strcmp(kind, "cells")) {
		fprintf(stderr, "ref: %s: unknown kind %s\n", spec, kind);
		return 1;
	}
	if (col < 0 || col >= 32) {
		fprintf(stderr, "ref: %s: bad column\n", spec);
		return 1;
	}
	FILE *f = fopen(path, "r");
	if (!f) {
		fprintf(stderr, "ref: cannot open %s\n", path);
		return 1;
	}
	char line[2048];
	double v[32];
	long rows = 0, cap = 0;
	double *rowv = NULL; /* per row: x0, x1, z0, z1 (or r_lo, r_hi), value */
	if (!fgets(line, sizeof line, f)) { /* header */
		fclose(f);
		return 1;
	}
	while (fgets(line, sizeof line, f)) {
		int k = ref_fields(line, v, 32);
		if (k <= col || k < (R->radial ? 2 : 4))
			continue;
		if (rows == cap) {
			cap = cap ? 2 * cap : 256;
			rowv = realloc(rowv, sizeof *rowv * 5 * (size_t)cap);
			if (!rowv) {
				fclose(f);
				return 1;
			}
		}
		double *r = rowv + 5 * rows++;
		if (R->radial)
			r[0] = v[0], r[1] = v[1], r[2] = 0, r[3] = 0;
		else
			r[0] = v[0], r[1] = v[1], r[2] = v[2], r[3] = v[3];
		r[4] = v[col];
	}
	fclose(f);
	if (rows == 0) {
		fprintf(stderr, "ref: %s: no rows\n", path);
		free(rowv);
		return 1;
	}
	R->w = rowv[1] - rowv[0];
	if (R->radial) {
		R->nx = (int)rows, R->nz = 1;
	} else {
		double xlo = HUGE_VAL, xhi = -HUGE_VAL, zlo = HUGE_VAL, zhi = -HUGE_VAL;
		for (long i = 0; i < rows; i++) {
			double *r = rowv + 5 * i;
			xlo = fmin(xlo, r[0]), xhi = fmax(xhi, r[1]);
			zlo = fmin(zlo, r[2]), zhi = fmax(zhi, r[3]);
		}
		R->x0 = xlo, R->z0 = zlo;
		R->nx = (int)floor((xhi - xlo) / R->w + 0.5);
		R->nz = (int)floor((zhi - zlo) / R->w + 0.5);
	}
	R->n = R->nx * R->nz;
	R->flux = calloc((size_t)R->n, sizeof *R->flux);
	R->keep = calloc((size_t)R->n, 1);
	if (!R->flux || !R->keep) {
		free(rowv);
		return 1;
	}
	for (long i = 0; i < rows; i++) {
		double *r = rowv + 5 * i;
		int k;
		double area;
		if (R->radial) {
			k = (int)floor(r[0] / R->w + 0.5);
			area = M_PI * (r[1] * r[1] - r[0] * r[0]);
		} else {
			int ix = (int)floor((r[0] - R->x0) / R->w + 0.5), iz = (int)floor((r[2] - R->z0) / R->w + 0.5);
			if (ix < 0 || ix >= R->nx || iz < 0 || iz >= R->nz)
				continue;
			k = ix * R->nz + iz;
			area = (r[1] - r[0]) * (r[3] - r[2]);
		}
		if (k < 0 || k >= R->n)
			continue;
		R->flux[k] = R->radial ? r[4] : r[4] * area;
		R->keep[k] = R->radial || r[1] <= xmax + 1e-9;
		if (R->keep[k])
			R->area_sum += area;
	}
	free(rowv);
	return 0;
}

/* The bin of floor point (x, z), or -1 outside the reference's bins. */
static inline int ref_bin(const struct ref *R, double x, double z)
{
	if (R->radial) {
		int k = (int)(sqrt(x * x + z * z) / R->w);
		return k < R->nx ? k : -1;
	}
	int i = (int)floor((x - R->x0) / R->w), j = (int)floor((z - R->z0) / R->w);
	return i >= 0 && i < R->nx && j >= 0 && j < R->nz ? i * R->nz + j : -1;
}

/* The area of bin k (m²). */
static inline double ref_area(const struct ref *R, int k)
{
	if (!R->radial)
		return R->w * R->w;
	double lo = k * R->w, hi = lo + R->w;
	return M_PI * (hi * hi - lo * lo);
}

/* Σ exact flux over the bins kept. */
static inline double ref_total(const struct ref *R)
{
	double t = 0;
	for (int k = 0; k < R->n; k++)
		if (R->keep[k])
			t += R->flux[k];
	return t;
}

/* Flux-weighted relative L1 of got[] (scaled by s) over the bins kept. */
static inline double ref_l1(const struct ref *R, const double *got, double s)
{
	double d = 0;
	for (int k = 0; k < R->n; k++)
		if (R->keep[k])
			d += fabs(s * got[k] - R->flux[k]);
	return d / ref_total(R);
}

/* The L1 that photon noise alone gives with N box-binned photons of energy
 * w each: √(2/π)·Σ√(wΦ_k)/ΣΦ_k (the references' README). */
static inline double ref_l1_noise(const struct ref *R, double w)
{
	double s = 0;
	for (int k = 0; k < R->n; k++)
		if (R->keep[k])
			s += sqrt(w * R->flux[k]);
	return sqrt(2 / M_PI) * s / ref_total(R);
}

static inline void ref_free(struct ref *R)
{
	free(R->flux);
	free(R->keep);
}

#endif
