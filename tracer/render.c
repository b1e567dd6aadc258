/* SPDX-License-Identifier: MIT */
/* render.c: the driver: setup, light pass (to come), eye pass over tiles. */
#include "render.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include "../common/arena.h"
#include "../common/diag.h"
#include "../common/pool.h"
#include "../common/progress.h"
#include "bvh.h"
#include "eyepass.h"
#include "light/lightpass.h"
#include "material.h"
#include "sampler.h"
#include "shape.h"

#define TILE 16 /* tile edge in pixels */
#define NPLANES 27

/* The eye pass's shared state: tiles are handed out by parallel_for_shares and
 * each pixel's result goes to its own slot, so scheduling cannot change the
 * image. */
struct eye_job {
	const struct eye_ctx *ctx; /* shading context */
	struct framebuffer *fb;    /* output planes */
	float *pl[NPLANES];        /* the planes, in plane_names' order */
	int nplanes;               /* planes stored: the first three (R G B) or all */
	int x0, y0, w, h;          /* the region rendered (fb holds just it) */
	int tx, ty;                /* tiles across and down */
	atomic_int done;           /* tiles finished */
	long long *rays;           /* rays traced, per worker */
	struct progress *progress; /* tiles done (common/progress.h) */
};

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* CPU seconds of the whole process so far (every thread). */
static double cpu_now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
	return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* Channel names as Nuke and OpenImageIO group them into layers. */
static const char *const plane_names[NPLANES] = {
	"R", "G", "B", "A", "direct.R", "direct.G", "direct.B", "caustic.R", "caustic.G",
	"caustic.B", "specular.R", "specular.G", "specular.B", "emission.R", "emission.G",
	"emission.B", "albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z",
	"Z", NULL};

/* Where each plane (in plane_names' order) is in a struct eye_px read as
 * floats. */
static const unsigned char plane_at[NPLANES - 1] = {
	0, 1, 2, 25, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24};

/* Stores the results of n pixels (at indices at[i] of the planes), plane by
 * plane: neighbours land in the same cache lines one after another. */
static void store(struct eye_job *j, int n, const size_t *at, const struct eye_px *px)
{
	_Static_assert(sizeof(struct eye_px) == (NPLANES - 1) * sizeof(float), "eye_px is floats");
	for (int k = 0; k < j->nplanes; k++) {
		float *pl = j->pl[k];
		for (int i = 0; i < n; i++)
			pl[at[i]] = ((const float *)&px[i])[plane_at[k]];
	}
}

/* Renders tile t (a parallel_for item). */
static void do_tile(void *arg, long t, int worker)
{
	struct eye_job *j = arg;
	int x0 = (int)(t % j->tx) * TILE, y0 = (int)(t / j->tx) * TILE;
	long long rays = 0; /* a local count: the workers' slots share a cache line */
	/* blocks of 4×4 pixels, whose camera rays Embree traces as one packet */
	for (int by = y0; by < y0 + TILE && by < j->h; by += 4)
		for (int bx = x0; bx < x0 + TILE && bx < j->w; bx += 4) {
			/* each pixel's image coordinates and plane index in one loop:
			 * a second loop over xs[] read them back as vectors just
			 * after they were stored one by one, which the CPU cannot
			 * forward (a third of do_tile's time, perf, grid 100k) */
			int ax[BVH_PACKET], ay[BVH_PACKET], n = 0;
			size_t at[BVH_PACKET];
			for (int y = by; y < by + 4 && y < j->h; y++)
				for (int x = bx; x < bx + 4 && x < j->w; x++, n++)
					ax[n] = j->x0 + x, ay[n] = j->y0 + y, at[n] = (size_t)y * (size_t)j->w + (size_t)x;
			struct eye_px px[BVH_PACKET];
			eye_pixels(j->ctx, n, ax, ay, px, &rays);
			store(j, n, at, px);
		}
	j->rays[worker] += rays;
	atomic_fetch_add(&j->done, 1);
	progress_step(j->progress, 1);
}

/* Runs the eye pass on nthreads threads (the caller's thread included). */
static void eye_pass(const struct eye_ctx *ctx, struct framebuffer *fb, int nplanes, int nthreads,
                     struct progress *show, long long *rays)
{
	struct eye_job j;
	memset(&j, 0, sizeof j);
	j.ctx = ctx;
	j.fb = fb;
	j.nplanes = nplanes;
	for (int k = 0; k < nplanes; k++)
		j.pl[k] = fb_plane(fb, plane_names[k]);
	j.x0 = fb->x0, j.y0 = fb->y0, j.w = fb->w, j.h = fb->h;
	j.tx = (j.w + TILE - 1) / TILE;
	j.ty = (j.h + TILE - 1) / TILE;
	atomic_init(&j.done, 0);
	j.rays = mem_calloc((size_t)nthreads, sizeof *j.rays);
	j.progress = show;
	progress_begin(show, "eye pass", (long)j.tx * j.ty);
	parallel_for_shares((long)j.tx * j.ty, nthreads, do_tile, &j);
	progress_end(show);
	*rays = 0;
	for (int i = 0; i < nthreads; i++)
		*rays += j.rays[i];
	free(j.rays);
}

/* The passes in force: --passes, else the scene's illumination { passes }. */
static enum illum_passes passes_of(const struct scene *s, const struct render_opts *o)
{
	return o->passes > 0 ? (enum illum_passes)(o->passes - 1) : s->gs.illum.passes;
}

/* The light pass (docs/design.md §4): one pass, or, when a material
 * disperses, one per colour channel (passes rgb: chromatic aberration) or
 * one spectral pass whose rays each carry a wavelength (passes spectral),
 * shooting as many rays as the three channel passes; it deposits points
 * (a shaft's corners would part ways). With a tolerance each pass is
 * progressive (lp_run). Returns the number of results. */
/* POV-Ray's photons { spacing S }: photons S apart where they reach a
 * target, pi r^2 / (S s)^2 of them for spacing multiplier s and r the
 * radius of the sphere the light pass aims at (shape_bsphere), so its rays
 * arrive S·s apart; the light pass shoots as many rays per light (at least
 * 10^4, at most 10^7); without spacing (or a target) 10^6, the default. */
static long photon_rays(const struct scene *s)
{
	double S = s->gs.illum.spacing, n = 0;
	if (!(S > 0))
		return 1000000;
	for (int i = 0; i < s->nobjects; i++) {
		const struct object *o = s->objects[i];
		const struct photon_spec *ph = obj_photons(o);
		struct vec3 c;
		double r;
		if (!ph || !ph->target || !shape_bsphere(o, &c, &r)) /* (false when unbounded) */
			continue;
		double sp = S * ph->spacing;
		n += M_PI * r * r / (sp * sp);
	}
	return n > 0 ? (long)fmin(fmax(n, 1e4), 1e7) : 1000000;
}

static int light_pass(const struct scene *s, const struct bvh *b, const struct mat_cache *mats,
                      const struct render_opts *o, int threads, struct progress *prog, struct lp_result *out[3],
                      struct render_stats *st, struct diag *dg)
{
	if (s->nlights == 0 || o->rays < 0)
		return 0;
	/* POV-Ray casts no caustics unless the scene asks for photons */
	if (s->legacy_lights && !s->gs.illum.given && o->rays == 0)
		return 0;
	struct lp_opts lo = {
		/* --rays, else illumination { rays }, else POV-Ray's photons { count },
		 * else its photons { spacing }, else 1e6 */
		.rays = o->rays > 0 ? o->rays : s->gs.illum.rays > 0 ? s->gs.illum.rays
		      : s->gs.illum.count > 0 ? s->gs.illum.count
		      : photon_rays(s),
		.max_depth = s->gs.illum.max_depth > 0 ? s->gs.illum.max_depth
		           : s->gs.max_trace_level > 0 ? s->gs.max_trace_level : 5,
		.min_weight = 1e-4, .threads = threads, .discard_isolated = true, .channel = -1, .progress = prog,
		.shafts = (o->method > 0 ? (enum illum_method)(o->method - 1) : s->gs.illum.method) == ILLUM_SHAFT,
		.seed_key = render_seed_key(o->seed),
	};
	/* the image's pixel, so the maps need not be finer than it */
	struct cam cm;
	cam_setup(&cm, &s->camera);
	lo.eye = cm.loc;
	if (cm.kind == CAM_ORTHOGRAPHIC)
		lo.pixel_width = v_len(cm.right) / (o->width > 0 ? o->width : 1);
	else
		lo.pixel_angle = 2 * atan(0.5 * v_len(cm.right) / v_len(cm.dir)) / (o->width > 0 ? o->width : 1);
	bool dispersive = lp_dispersive(s);
	lo.spectral = dispersive && passes_of(s, o) == PASSES_SPECTRAL;
	int passes = dispersive && !lo.spectral ? 3 : 1, n = 0;
	if (lo.spectral)
		lo.rays *= 3;
	if (lo.spectral && lo.shafts && !(o->method > 0 || s->gs.illum.method_set)) {
		lo.shafts = false; /* the default method: points, silently */
	} else if (lo.spectral && lo.shafts) {
		diag_warning(dg, srcloc_none(), "passes spectral: light rays of different wavelengths part "
		             "ways, so the dispersive light pass deposits points, not shafts");
		lo.shafts = false;
	}
	/* --tolerance, else the scene's unless --rays was given */
	lo.tolerance = o->tolerance > 0 ? o->tolerance : o->rays > 0 ? 0 : s->gs.illum.tolerance;
	st->tolerance = lo.tolerance;
	for (int c = 0; c < passes; c++) {
		struct lp_stats ls;
		lo.channel = passes == 3 ? c : -1;
		struct lp_result *r = lp_run(s, b, mats, &lo, &ls);
		if (!r)
			continue;
		out[n++] = r;
		st->light_rays += ls.rays;
		st->light_segments += ls.segments;
		st->tol_estimate = fmax(st->tol_estimate, ls.tol_estimate);
		st->tol_rounds = ls.tol_rounds > st->tol_rounds ? ls.tol_rounds : st->tol_rounds;
		st->tol_rays = ls.tol_rays > st->tol_rays ? ls.tol_rays : st->tol_rays;
		st->maps += ls.maps;
		st->map_bytes += ls.map_bytes;
		double fc = lp_finest_cell(r);
		st->finest_cell = st->finest_cell > 0 && fc > 0 ? fmin(st->finest_cell, fc) : fmax(st->finest_cell, fc);
		for (int k = 0; k < 3; k++) {
			st->e_emitted += ls.emitted[k];
			st->e_deposited += ls.landed[k];
			st->e_direct += ls.direct[k];
			st->e_absorbed += ls.absorbed[k];
			st->e_escaped += ls.escaped[k];
			st->e_cut += ls.cut[k];
			st->e_held += ls.deposited[k];
		}
		struct uv_range ur;
		if (ls.nomap && c == 0 && !shape_uv_range(ls.nomap, &ur)) {
			diag_warning(dg, ls.nomap->loc, "an %s has no (u,v) map: the caustic on it is not drawn",
			             scene_object_kind_name(ls.nomap->kind));
		} else if (ls.nomap && c == 0) {
			diag_warning(dg, ls.nomap->loc, "this %s's illumination map would have too many nodes; "
			             "it gets no caustic (give illum_map a coarser cell or resolution)",
			             scene_object_kind_name(ls.nomap->kind));
		}
		if (ls.clipped && c == 0) {
			diag_warning(dg, ls.clipped->loc,
			             "under a parallel light this unbounded %s casts caustics only around the "
			             "finite objects and the camera", scene_object_kind_name(ls.clipped->kind));
		}
	}
	if (lo.tolerance > 0 && st->tol_estimate > lo.tolerance)
		diag_warning(dg, srcloc_none(), "tolerance %g not reached: the light pass's error estimate is %.3g "
		             "after %ld rays per light", lo.tolerance, st->tol_estimate, st->tol_rays);
	return n;
}

struct dump_ctx {
	const char *dir;  /* --dump-maps directory */
	int pass;         /* which channel pass */
	struct diag *dg;  /* where errors go */
	int err;          /* first error's status */
};

static void dump_one(void *ctx, const struct object *o, int level, const struct illum_map *m)
{
	struct dump_ctx *d = ctx;
	char path[4096], lv[16] = "";
	if (level > 0)
		snprintf(lv, sizeof lv, "-L%d", level);
	snprintf(path, sizeof path, "%s/map-%s-%d-%d%s%s.exr", d->dir, scene_object_kind_name(o->kind),
	         o->loc.line, o->loc.col, d->pass < 0 ? "" : d->pass == 0 ? "-R" : d->pass == 1 ? "-G" : "-B", lv);
	if (!d->err)
		d->err = illum_write_exr(m, path, d->dg);
}

/* --dump-maps DIR: every map as an EXR named after its object and source line. */
static int dump_maps(struct lp_result *const *maps, int n, const char *dir, struct diag *dg)
{
	struct dump_ctx d = {dir, -1, dg, 0};
	for (int i = 0; i < n && !d.err; i++) {
		d.pass = n == 3 ? i : -1;
		lp_each_map(maps[i], dump_one, &d);
	}
	return d.err;
}

uint64_t render_seed_key(long seed)
{
	return seed ? smp_mix((uint64_t)seed * 0x9E3779B97F4A7C15ull) : 0;
}

/* The framebuffer for the frame, or for the region of it asked for (the
 * caller checked the region lies inside the frame). */
static struct framebuffer *new_film(const struct render_opts *o)
{
	const int *r = o->region;
	if (r[1] <= 0)
		return fb_new(o->width, o->height);
	struct framebuffer *fb = fb_new(r[1] - r[0], r[3] - r[2]);
	fb->x0 = r[0], fb->y0 = r[2];
	fb->full_w = o->width, fb->full_h = o->height;
	return fb;
}

int render(const struct scene *s, const struct render_opts *o, struct diag *dg, struct framebuffer **out,
           struct render_stats *stats)
{
	struct render_stats st;
	memset(&st, 0, sizeof st);
	*out = NULL;
	double t0 = now();
	struct mat_cache mats;
	memset(&mats, 0, sizeof mats);
	int err = mat_cache_load(&mats, s, o->ocio_config, dg);
	if (err) {
		mat_cache_free(&mats);
		return err;
	}
	struct bvh *b = bvh_build(s->objects, s->nobjects);
	struct framebuffer *fb = new_film(o);
	/* the image's planes, made and written once here (fb_reserve): their
	 * pages fault in while the image is set up, not one by one under the
	 * eye pass */
	int nplanes = o->beauty_only ? 3 : NPLANES - 1;
	fb_reserve(fb, nplanes);
	for (int k = 0; k < nplanes; k++)
		fb_plane(fb, plane_names[k]);
	st.threads = pool_threads(o->threads);
	/* the eye pass's set-up (camera, and a scan of every object for one
	 * that passes light straight through) is part of the scene's: 11 ms
	 * at a million spheres, counted here, not as tracing */
	struct eye_ctx ctx;
	eye_setup(&ctx, s, b, &mats, o->width, o->height, o->spp);
	double t1 = now();
	st.t_setup = t1 - t0;

	struct lp_result *maps[3] = {NULL, NULL, NULL};
	int nmaps = 0;
	struct progress prog; /* the light pass's and the eye pass's report */
	progress_init(&prog, progress_mode_for(o->quiet), stderr);
	if (o->load_maps) {
		nmaps = lp_load(maps, s, o->load_maps, false, dg); /* isolated nodes were not saved */
		if (nmaps < 0)
			err = -nmaps, nmaps = 0;
	} else {
		nmaps = light_pass(s, b, &mats, o, st.threads, &prog, maps, &st, dg);
	}
	if (!err && o->save_maps)
		err = lp_save(maps, nmaps, s, o->save_maps, dg);
	if (!err && nmaps > 0 && o->dump_maps)
		err = dump_maps(maps, nmaps, o->dump_maps, dg);
	double t2 = now();
	st.t_light = t2 - t1;

	ctx.beauty_only = nplanes == 3;
	ctx.caustics = maps;
	ctx.ncaustics = nmaps;
	ctx.spectral = passes_of(s, o) == PASSES_SPECTRAL;
	ctx.seed_key = render_seed_key(o->seed);
	double c2 = cpu_now();
	if (!err)
		eye_pass(&ctx, fb, nplanes, st.threads, &prog, &st.rays);
	st.t_eye = now() - t2;
	st.cpu_eye = cpu_now() - c2;
	for (int i = 0; i < nmaps; i++)
		lp_free(maps[i]);

	progress_destroy(&prog);
	bvh_free(b);
	mat_cache_free(&mats);
	struct rusage ru;
	if (getrusage(RUSAGE_SELF, &ru) == 0)
		st.peak_rss_kb = ru.ru_maxrss;
	if (stats)
		*stats = st;
	if (err) {
		fb_free(fb);
		return err;
	}
	*out = fb;
	return 0;
}

void render_print_stats(FILE *f, const struct render_stats *st)
{
	double total = st->t_setup + st->t_light + st->t_eye;
	fprintf(f, "arvo: threads          %d\n", st->threads);
	fprintf(f, "arvo: rays traced      %lld\n", st->rays);
	fprintf(f, "arvo: setup            %.3f s (BVH, images)\n", st->t_setup);
	fprintf(f, "arvo: light pass       %.3f s (%lld light rays, %lld segments, %ld maps, %.1f MiB)\n",
	        st->t_light, st->light_rays, st->light_segments, st->maps, st->map_bytes / 1048576.0);
	if (st->tolerance > 0)
		fprintf(f, "arvo: tolerance        %.3g asked, %.3g estimated (%d rounds, last %ld rays per light, "
		        "finest map cell %.3g)\n", st->tolerance, st->tol_estimate, st->tol_rounds, st->tol_rays,
		        st->finest_cell);
	if (st->e_emitted > 0) {
		fprintf(f, "arvo: light energy     emitted %.6g W = deposited %.6g + direct %.6g + absorbed %.6g"
		        " + escaped %.6g + cut %.6g\n", st->e_emitted, st->e_deposited, st->e_direct,
		        st->e_absorbed, st->e_escaped, st->e_cut);
		fprintf(f, "arvo: maps hold        %.6g W (irradiance × area of the light that landed)\n",
		        st->e_held);
	}
	fprintf(f, "arvo: eye pass         %.3f s (%.3g rays/s, %.3f s CPU)\n", st->t_eye,
	        st->t_eye > 0 ? (double)st->rays / st->t_eye : 0.0, st->cpu_eye);
	fprintf(f, "arvo: total            %.3f s\n", total);
	fprintf(f, "arvo: peak memory      %.1f MiB\n", st->peak_rss_kb / 1024.0);
}
