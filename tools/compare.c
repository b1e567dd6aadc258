/* SPDX-License-Identifier: MIT */
/* compare.c: `arvo compare A.exr B.exr`: per-layer differences of two EXRs,
 * a verdict in the exit status, and optionally a difference image. The
 * figures are those of OpenImageIO's idiff (mean, RMS, peak SNR and maximum
 * absolute error over every value), per layer and over all channels. */
#include "tools.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../common/arena.h"
#include "../tracer/output/exrout.h"

/* The EXR reader and writer report to a diag; the tool prints their message
 * with its own prefix. QUIET(call) is NULL on success, else the message. */
static struct diag quiet;
#define QUIET(call) (diag_init(&quiet, NULL), (call) ? (const char *)quiet.last : (const char *)NULL)

enum { EX_MATCH = 0, EX_DIFFER = 1, EX_TROUBLE = 2, EX_USAGE = 64, EX_IOERR = 74 };

/* The layer a channel belongs to: what comes before its last '.', "" for
 * the beauty R G B A, else the channel itself (Z). Written into buf. */
static const char *layer_of(const char *ch, char *buf, size_t n)
{
	const char *dot = strrchr(ch, '.');
	if (dot)
		snprintf(buf, n, "%.*s", (int)(dot - ch), ch);
	else
		snprintf(buf, n, "%s", strchr("RGBA", ch[0]) && !ch[1] ? "" : ch);
	return buf;
}

/* |a - b|, 0 for equal values (infinities of one sign, NaN with NaN). */
static double diff(float a, float b)
{
	if (a == b || (isnan(a) && isnan(b)))
		return 0;
	double d = fabs((double)a - (double)b);
	return isnan(d) ? INFINITY : d;
}

void cmp_layer(const struct framebuffer *a, const struct framebuffer *b, const char *layer,
               enum cmp_metric m, double tol, struct cmp_figures *f)
{
	size_t n = (size_t)a->w * (size_t)a->h;
	double sum = 0, sum2 = 0;
	long values = 0;
	unsigned char *over = mem_calloc(n ? n : 1, 1);
	memset(f, 0, sizeof *f);
	f->max_ch = "";
	for (int c = 0; c < fb_count(a); c++) {
		char buf[256];
		const char *name = fb_name(a, c);
		const float *pa = fb_data(a, c), *pb = fb_find(b, name);
		if (!pb || (layer && strcmp(layer_of(name, buf, sizeof buf), layer) != 0))
			continue;
		for (size_t i = 0; i < n; i++) {
			double d = diff(pa[i], pb[i]), big = fmax(fabs(pa[i]), fabs(pb[i]));
			double r = d > 0 ? (isinf(d) ? INFINITY : d / big) : 0;
			sum += d, sum2 += d * d, values++;
			if (d > f->max) {
				f->max = d, f->max_ch = name;
				f->max_x = a->x0 + (int)(i % (size_t)a->w), f->max_y = a->y0 + (int)(i / (size_t)a->w);
			}
			f->rel = fmax(f->rel, r);
			if ((m == CMP_REL ? r : d) > tol)
				over[i] = 1;
		}
	}
	for (size_t i = 0; i < n; i++)
		f->over += over[i];
	free(over);
	f->pixels = (long)n;
	f->mean = values ? sum / (double)values : 0;
	f->rmse = values ? sqrt(sum2 / (double)values) : 0;
	f->psnr = f->rmse > 0 ? 20 * log10(1 / f->rmse) : INFINITY;
}

int cmp_match(const struct cmp_figures *f, enum cmp_metric m, double tol, double failpercent)
{
	switch (m) {
	case CMP_MEAN: return f->mean <= tol;
	case CMP_RMSE: return f->rmse <= tol;
	case CMP_PSNR: return f->psnr >= tol;
	case CMP_MAX:
	case CMP_REL: break;
	}
	return 100.0 * (double)f->over <= failpercent * (double)f->pixels;
}

/* ---- the command ---- */

struct cmp_opts {
	const char *a, *b;      /* the images */
	const char *diff;       /* -o: the difference image, or NULL */
	enum cmp_metric metric; /* --metric */
	double tol;             /* --tolerance (default: 0, psnr +inf: exactly) */
	int tol_set;
	double failpercent;     /* --failpercent */
};

__attribute__((format(printf, 1, 2)))
static int usage_err(const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	fprintf(stderr, "arvo compare: error: ");
	vfprintf(stderr, fmt, ap);
	va_end(ap);
	fprintf(stderr, "\nusage: arvo compare A.exr B.exr [--metric rmse|mean|max|psnr|rel] "
	        "[--tolerance T] [--failpercent P] [-o diff.exr]\n");
	return EX_USAGE;
}

static int parse_number(const char *s, double *out)
{
	char *end;
	errno = 0;
	double v = strtod(s, &end);
	if (errno || end == s || *end || !(v >= 0))
		return 0;
	*out = v;
	return 1;
}

static int parse_cmp(int argc, char **argv, struct cmp_opts *o)
{
	static const char *const metrics[] = {"max", "mean", "rmse", "psnr", "rel"};
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
		int takes = !strcmp(a, "--metric") || !strcmp(a, "--tolerance") ||
		            !strcmp(a, "--failpercent") || !strcmp(a, "-o");
		if (takes && !v)
			return usage_err("option '%s' needs a value", a);
		if (takes)
			i++;
		if (!strcmp(a, "--metric")) {
			int k = 0;
			while (k < 5 && strcmp(v, metrics[k]))
				k++;
			if (k == 5)
				return usage_err("unknown metric '%s' (expected rmse, mean, max, psnr or rel)", v);
			o->metric = (enum cmp_metric)k;
		} else if (!strcmp(a, "--tolerance")) {
			if (!parse_number(v, &o->tol))
				return usage_err("bad value for --tolerance: '%s' (expected a number >= 0)", v);
			o->tol_set = 1;
		} else if (!strcmp(a, "--failpercent")) {
			if (!parse_number(v, &o->failpercent) || o->failpercent > 100)
				return usage_err("bad value for --failpercent: '%s' (expected 0 to 100)", v);
		} else if (!strcmp(a, "-o")) {
			o->diff = v;
		} else if (a[0] == '-' && a[1]) {
			return usage_err("unknown option '%s'", a);
		} else if (!o->a || !o->b) {
			*(o->a ? &o->b : &o->a) = a;
		} else {
			return usage_err("more than two images given ('%s')", a);
		}
	}
	if (!o->b)
		return usage_err("%s", "two images are needed");
	if (!o->tol_set && o->metric == CMP_PSNR)
		o->tol = INFINITY;
	return -1;
}

/* Why a and b cannot be compared pixel by pixel, or NULL. */
static const char *mismatch(const struct framebuffer *a, const struct framebuffer *b, char *buf, size_t n)
{
	if (a->w != b->w || a->h != b->h || a->x0 != b->x0 || a->y0 != b->y0 ||
	    a->full_w != b->full_w || a->full_h != b->full_h) {
		snprintf(buf, n, "the images differ in size: %dx%d at (%d,%d) of %dx%d against %dx%d at (%d,%d) of %dx%d",
		         a->w, a->h, a->x0, a->y0, a->full_w, a->full_h, b->w, b->h, b->x0, b->y0, b->full_w, b->full_h);
		return buf;
	}
	for (int k = 0; k < 2; k++) {
		const struct framebuffer *x = k ? b : a, *y = k ? a : b;
		for (int c = 0; c < fb_count(x); c++)
			if (!fb_find(y, fb_name(x, c))) {
				snprintf(buf, n, "channel '%s' is only in %s", fb_name(x, c), k ? "B" : "A");
				return buf;
			}
	}
	return NULL;
}

static void print_row(const char *name, const struct cmp_figures *f, int ok)
{
	printf("%-12s %-12.6g %-12.6g %-12.6g %-9.6g %-12.6g %ld (%.4g%%)%s\n", name, f->mean, f->rmse,
	       f->max, f->psnr, f->rel, f->over, f->pixels ? 100.0 * (double)f->over / (double)f->pixels : 0.0,
	       ok ? "" : "  differs");
}

/* |a - b| for every channel, in a's window: the difference image. */
static const char *write_diff(const struct framebuffer *a, const struct framebuffer *b, const char *path)
{
	struct framebuffer *d = fb_new(a->w, a->h);
	d->x0 = a->x0, d->y0 = a->y0, d->full_w = a->full_w, d->full_h = a->full_h;
	size_t n = (size_t)a->w * (size_t)a->h;
	for (int c = 0; c < fb_count(a); c++) {
		const float *pa = fb_data(a, c), *pb = fb_find(b, fb_name(a, c));
		float *pd = fb_plane(d, fb_name(a, c));
		for (size_t i = 0; i < n; i++)
			pd[i] = (float)diff(pa[i], pb[i]);
	}
	const char *err = QUIET(out_exr_write(d, path, NULL, &quiet));
	fb_free(d);
	return err;
}

/* Compares every layer, prints the table; returns the number that differ. */
static int compare_layers(const struct framebuffer *a, const struct framebuffer *b, const struct cmp_opts *o)
{
	static const char *const names[] = {"max", "mean", "rmse", "psnr", "rel"};
	char seen[64][128];
	int nseen = 0, bad = 0;
	printf("metric %s, tolerance %g, failpercent %g; %dx%d pixels\n", names[o->metric], o->tol,
	       o->failpercent, a->w, a->h);
	printf("%-12s %-12s %-12s %-12s %-9s %-12s %s\n", "layer", "mean", "rmse", "max", "psnr", "rel", "over");
	for (int c = 0; c < fb_count(a) && nseen < 64; c++) {
		char layer[128];
		layer_of(fb_name(a, c), layer, sizeof layer);
		int dup = 0;
		for (int k = 0; k < nseen; k++)
			dup |= !strcmp(seen[k], layer);
		if (dup)
			continue;
		snprintf(seen[nseen++], sizeof seen[0], "%s", layer);
		struct cmp_figures f;
		cmp_layer(a, b, layer, o->metric, o->tol, &f);
		int ok = cmp_match(&f, o->metric, o->tol, o->failpercent);
		bad += !ok;
		print_row(layer[0] ? layer : "RGBA", &f, ok);
	}
	struct cmp_figures all;
	cmp_layer(a, b, NULL, o->metric, o->tol, &all);
	print_row("(all)", &all, cmp_match(&all, o->metric, o->tol, o->failpercent));
	if (all.max > 0)
		printf("largest difference %.6g at (%d, %d) in %s\n", all.max, all.max_x, all.max_y, all.max_ch);
	return bad;
}

int tool_compare(int argc, char **argv)
{
	struct cmp_opts o = {0};
	int rc = parse_cmp(argc, argv, &o);
	if (rc >= 0)
		return rc;
	struct framebuffer *a = NULL, *b = NULL;
	const char *err = QUIET(out_exr_read(o.a, &a, NULL, &quiet));
	if (!err)
		err = QUIET(out_exr_read(o.b, &b, NULL, &quiet));
	if (err) {
		fprintf(stderr, "arvo compare: error: %s\n", err);
		fb_free(a);
		return EX_TROUBLE;
	}
	char why[512];
	if (mismatch(a, b, why, sizeof why)) {
		printf("arvo compare: %s and %s differ: %s\n", o.a, o.b, why);
		rc = EX_DIFFER;
	} else {
		int bad = compare_layers(a, b, &o);
		if (o.diff && (err = write_diff(a, b, o.diff)) != NULL) {
			fprintf(stderr, "arvo compare: error: %s\n", err);
			rc = EX_IOERR;
		} else {
			printf("arvo compare: %s\n", bad ? "the images differ" : "the images match");
			rc = bad ? EX_DIFFER : EX_MATCH;
		}
	}
	fb_free(a);
	fb_free(b);
	return rc;
}
