/* SPDX-License-Identifier: MIT */
/* test_outlines.c: text, prism, polygon, lathe and sor, built by the
 * evaluator from small scenes: known hits, normals, (u,v) and inside tests
 * on shapes whose answers are exact (a square ring, a pyramid, cylinders),
 * total areas, (u,v) → point → hit → (u,v) round trips with outward
 * orientation under random transforms, partials against finite
 * differences, and text's placement rules (offsets, thickness, the first
 * glyph at x = 0) and errors on POV-Ray's own fonts (povray-includes). */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../../common/diag.h"
#include "../../eval/eval.h"
#include "../../tracer/shape.h"
#include "geo_rand.h"
#include "test.h"

#ifndef POVRAY_INCLUDE_DIR
#define POVRAY_INCLUDE_DIR "/usr/share/povray-3.7/include" /* Debian's povray-includes */
#endif

static struct scene sc;
static char *errs; /* the diagnostics of the last run */
static size_t errlen;

/* Evaluates text as a scene (in /tmp, with POV-Ray's include directory);
 * returns the exit code. */
static int run(const char *text)
{
	char path[] = "/tmp/arvo-test-outl-XXXXXX";
	int fd = mkstemp(path);
	if (fd < 0 || write(fd, text, strlen(text)) != (ssize_t)strlen(text))
		return -1;
	close(fd);
	free(errs);
	errs = NULL;
	FILE *err = open_memstream(&errs, &errlen);
	struct diag dg;
	diag_init(&dg, err);
	struct eval_options o;
	eval_default_options(&o);
	o.pov_include_dir = POVRAY_INCLUDE_DIR;
	int rc = eval_scene(path, &o, &dg, &sc);
	fclose(err);
	unlink(path);
	return rc;
}

/* The first object of a scene that must evaluate. */
static const struct object *first(const char *text)
{
	int rc = run(text);
	if (rc != 0 || sc.nobjects < 1) {
		printf("#   scene failed (%d): %s", rc, errs ? errs : "");
		return NULL;
	}
	return sc.objects[0];
}

static double dist(struct vec3 a, struct vec3 b) { return v_len(v_sub(a, b)); }

static bool hit(const struct object *o, struct vec3 from, struct vec3 dir, double tmin, struct hit *h)
{
	struct ray r = {from, dir};
	return shape_intersect(o, &r, tmin, INFINITY, h);
}

#define CHECK_VEC(a, b, tol) CHECK(dist((a), (b)) < (tol))

static const char *ring =
	"prism { linear_spline 0, 2, 10, <-2,-2>, <2,-2>, <2,2>, <-2,2>, <-2,-2>,"
	" <-1,-1>, <1,-1>, <1,1>, <-1,1>, <-1,-1> }\n";

static void t_prism_ring(void)
{
	const struct object *o = first(ring);
	struct hit h;
	if (!o)
		return;
	CHECK(hit(o, v3(1.5, 5, 0), v3(0, -1, 0), 0, &h));
	CHECK_NEAR(h.t, 3, 1e-12);
	CHECK_VEC(h.n, v3(0, 1, 0), 1e-12);
	CHECK(h.entering);
	CHECK_NEAR(h.u, 0.875, 1e-12);          /* (1.5 − A0)/ΔA */
	CHECK_NEAR(h.v, 5.0 / 6, 1e-12);        /* top cap: ⅔ + (B1 − 0)/ΔB/3 */
	CHECK(!hit(o, v3(0, 5, 0), v3(0, -1, 0), 0, &h)); /* down the hole */
	CHECK(hit(o, v3(-5, 1, 0.3), v3(1, 0, 0), 0, &h));
	CHECK_NEAR(h.t, 3, 1e-12);
	CHECK_VEC(h.n, v3(-1, 0, 0), 1e-12);
	CHECK_NEAR(h.v, 0.5, 1e-12);           /* half way up the wall */
	CHECK(hit(o, v3(-5, 1, 0.3), v3(1, 0, 0), 3.5, &h));
	CHECK_NEAR(h.t, 4, 1e-12);             /* the hole's wall, leaving the solid */
	CHECK_VEC(h.n, v3(1, 0, 0), 1e-12);
	CHECK(!h.entering);
	CHECK(shape_inside(o, v3(1.5, 1, 0)));
	CHECK(!shape_inside(o, v3(0, 1, 0)));
	CHECK(!shape_inside(o, v3(1.5, 2.5, 0)));
	CHECK_NEAR(shape_area(o), 2 * 12 + 2 * (16 + 8), 1e-9);
	struct bbox b = shape_bounds(o);
	CHECK_VEC(b.lo, v3(-2, 0, -2), 1e-15);
	CHECK_VEC(b.hi, v3(2, 2, 2), 1e-15);
	scene_free(&sc);
}

static void t_prism_conic_and_splines(void)
{
	/* a pyramid: the square at y = 1, shrinking to the apex at the origin */
	const struct object *o =
		first("prism { conic_sweep linear_spline 0, 1, 5, <-1,-1>, <1,-1>, <1,1>, <-1,1>, <-1,-1> }\n");
	struct hit h;
	if (!o)
		return;
	CHECK(hit(o, v3(5, 0.5, 0), v3(-1, 0, 0), 0, &h));
	CHECK_NEAR(h.t, 4.5, 1e-12);
	CHECK_VEC(h.n, v3(M_SQRT1_2, -M_SQRT1_2, 0), 1e-12);
	CHECK(hit(o, v3(0.3, 5, 0.2), v3(0, -1, 0), 0, &h));
	CHECK_NEAR(h.t, 4, 1e-12);
	CHECK(shape_inside(o, v3(0.2, 0.5, 0.2)));
	CHECK(!shape_inside(o, v3(0.6, 0.5, 0)));
	/* base 4 + four triangles of base 2 and slant height √(1 + 1) */
	CHECK_NEAR(shape_area(o), 4 + 4 * sqrt(2), 1e-9);
	scene_free(&sc);
	/* a Bézier circle quadrant stays within its control polygon; the closing
	 * line makes a quarter disc of radius 1 (area ≈ π/4) */
	o = first("prism { bezier_spline 0, 1, 8, <1,0>, <1,0.5523>, <0.5523,1>, <0,1>,"
	          " <0,1>, <0,0.5>, <0,0.5>, <1,0> }\n");
	if (!o)
		return;
	CHECK(hit(o, v3(0.5, 5, 0.5), v3(0, -1, 0), 0, &h));
	CHECK(!hit(o, v3(0.75, 5, 0.75), v3(0, -1, 0), 0, &h)); /* outside the arc (r ≈ 1.06) */
	CHECK(hit(o, v3(5, 0.5, 0.7071), v3(-1, 0, 0), 0, &h));
	CHECK_NEAR(h.p.x, 0.7071, 2e-3);  /* on the arc, near the circle */
	scene_free(&sc);
	/* the POV-Ray Catmull–Rom piece passes through its inner points */
	o = first("prism { cubic_spline 0, 1, 7, <-1,-1>, <1,-1>, <1,1>, <-1,1>, <-1,-1>, <1,-1>, <1,1> }\n");
	if (!o)
		return;
	CHECK(hit(o, v3(5, 0.5, -1), v3(-1, 0, 0), 0, &h));
	CHECK_NEAR(h.p.x, 1, 1e-9); /* the corner <1,-1> is on the curve */
	scene_free(&sc);
}

static void t_polygon(void)
{
	const struct object *o = first("polygon { 10, <0,0>, <2,0>, <2,2>, <0,2>, <0,0>,"
	                               " <0.5,0.5>, <1.5,0.5>, <1.5,1.5>, <0.5,1.5>, <0.5,0.5> }\n");
	struct hit h;
	if (!o)
		return;
	CHECK(hit(o, v3(1.75, 1, -5), v3(0, 0, 1), 0, &h));
	CHECK_NEAR(h.t, 5, 1e-12);
	CHECK_NEAR(fabs(h.n.z), 1, 1e-12);
	CHECK(!hit(o, v3(1, 1, -5), v3(0, 0, 1), 0, &h));
	CHECK(!shape_inside(o, v3(1.75, 1, 0)));
	CHECK_NEAR(shape_area(o), 3, 1e-12);
	scene_free(&sc);
	/* a tilted triangle in 3D: the plane through its points */
	o = first("polygon { 4, <0,0,0>, <1,0,1>, <0,1,1>, <0,0,0> }\n");
	if (!o)
		return;
	CHECK(hit(o, v3(0.25, 0.25, 5), v3(0, 0, -1), 0, &h));
	CHECK_NEAR(h.p.z, 0.5, 1e-12);
	CHECK_NEAR(shape_area(o), 0.5 * sqrt(3), 1e-12);
	scene_free(&sc);
}

static void t_lathe(void)
{
	const struct object *o = first("lathe { linear_spline 5, <0,0>, <1,0>, <1,1>, <0,1>, <0,0> }\n");
	struct hit h;
	if (!o)
		return;
	CHECK(hit(o, v3(0.5, 5, 0), v3(0, -1, 0), 0, &h));
	CHECK_NEAR(h.t, 4, 1e-12);
	CHECK_VEC(h.n, v3(0, 1, 0), 1e-12);
	CHECK(hit(o, v3(5, 0.5, 0), v3(-1, 0, 0), 0, &h));
	CHECK_NEAR(h.t, 4, 1e-12);
	CHECK_VEC(h.n, v3(1, 0, 0), 1e-12);
	CHECK(shape_inside(o, v3(0.5, 0.5, 0.3)));
	CHECK(!shape_inside(o, v3(0.9, 0.5, 0.9)));
	CHECK_NEAR(shape_area(o), 4 * M_PI, 1e-8);
	scene_free(&sc);
	/* a quadratic spline through collinear points: the cylinder r = 1 */
	o = first("lathe { quadratic_spline 4, <1,-1>, <1,0>, <1,1>, <1,2> }\n");
	if (!o)
		return;
	CHECK(hit(o, v3(5, 0.5, 0), v3(-1, 0, 0), 0, &h)); /* perpendicular to the axis */
	CHECK_NEAR(h.t, 4, 1e-12);
	CHECK(hit(o, v3(5, 1.5, 0), v3(-1, -0.25, 0), 0, &h)); /* oblique: the degree-6 solve */
	CHECK_NEAR(h.t, 4, 1e-9);
	CHECK_NEAR(h.p.y, 0.5, 1e-9);
	CHECK(hit(o, v3(0, 0.5, 0), v3(0.6, 0.3, 0.8), 0, &h)); /* from inside */
	CHECK_NEAR(h.t, 1, 1e-9);
	CHECK(!h.entering);
	scene_free(&sc);
}

static void t_sor(void)
{
	const struct object *o = first("sor { 4, <1,-1>, <1,0>, <1,1>, <1,2> }\n");
	struct hit h;
	if (!o)
		return;
	CHECK(hit(o, v3(5, 0.5, 0), v3(-1, 0, 0), 0, &h));
	CHECK_NEAR(h.t, 4, 1e-12);
	CHECK_VEC(h.n, v3(1, 0, 0), 1e-12);
	CHECK(hit(o, v3(0.5, 5, 0), v3(0, -1, 0), 0, &h));
	CHECK_NEAR(h.t, 4, 1e-12);
	CHECK_VEC(h.n, v3(0, 1, 0), 1e-12);
	CHECK(shape_inside(o, v3(0.5, 0.5, 0.5)));
	CHECK_NEAR(shape_area(o), 4 * M_PI, 1e-8);
	scene_free(&sc);
	/* the squared radius interpolates the points exactly */
	o = first("sor { 5, <0.5,-1>, <0.7,0>, <1.2,1>, <0.9,2>, <0.6,3> }\n");
	if (!o)
		return;
	CHECK(hit(o, v3(5, 1, 0), v3(-1, 0, 0), 0, &h));
	CHECK_NEAR(h.p.x, 1.2, 1e-9);
	CHECK(hit(o, v3(0, 0, 5), v3(0, 0, -1), 0, &h));
	CHECK_NEAR(h.p.z, 0.7, 1e-9);
	scene_free(&sc);
}

/* Round trips and partials on every primitive of the scene below, each
 * under random transforms (mirrored too). Cap points outside the outline
 * and points where the Jacobian vanishes are skipped. */
static const char *shapes =
	"prism { linear_spline 0, 2, 10, <-2,-2>, <2,-2>, <2,2>, <-2,2>, <-2,-2>,"
	" <-1,-1>, <1,-1>, <1,1>, <-1,1>, <-1,-1> }\n"
	"prism { conic_sweep quadratic_spline 0.25, 1, 12, <0.2,-1>, <0.2,0.2>, <1,-0.2>, <1,0.2>,"
	" <0.2,1>, <-0.2,1>, <-1,0.2>, <-1,-0.2>, <-0.2,0.2>, <-0.2,-1>, <0.2,-1>, <0.2,0.2> }\n"
	"prism { cubic_spline 0, 1, 6, <3,-5>, <3,5>, <-5,0>, <3,-5>, <3,5>, <-5,0> }\n"
	"polygon { 5, <0,0,0>, <2,0,1>, <2,2,0>, <0,2,1>, <0,0,0> }\n"
	"lathe { cubic_spline 8, <0,0>, <0.5,0>, <1,0.3>, <0.6,1>, <0.9,1.5>, <0.3,2>, <0,2.1>, <0,2.2> }\n"
	"lathe { bezier_spline 8, <0,0>, <1,0>, <1,1>, <0.5,1>, <0.5,1>, <0.2,1.5>, <0.4,2>, <0,2> }\n"
	"sor { 7, <0,0>, <0.5,0.1>, <0.8,0.5>, <0.4,1>, <0.6,1.5>, <0.3,2>, <0.2,2.5> }\n"
	"sor { 6, <0,-0.1>, <0.6,0>, <0.5,0.5>, <0.7,1>, <0.2,1.5>, <0,2> open }\n";

/* Round trips and partials of one object under 400 random transforms. */
static void round_trips(const struct object *src)
{
	int bad = 0, tried = 0;
	double worst = 0;
	for (int i = 0; i < 400; i++) {
		struct object o;
		memcpy(&o, src, obj_size(src->kind));
		o.xf = xf_keep(rnd_xform(i % 4 == 0, true));
		double u = rndr(0.01, 0.99), v = rndr(0.01, 0.99), s = 1e-6;
		struct vec3 p, du, dv, p1, p0;
		CHECK(shape_uv_point(&o, u, v, &p, &du, &dv));
		struct vec3 cr = v_cross(du, dv), n = v_norm(cr);
		double J = v_len(cr), size = v_len(v_sub(shape_bounds(&o).hi, shape_bounds(&o).lo));
		if (!(J > 1e-6 * size * size))
			continue;
		/* partials against central differences */
		shape_uv_point(&o, u + s, v, &p1, NULL, NULL);
		shape_uv_point(&o, u - s, v, &p0, NULL, NULL);
		double e1 = dist(v_scale(v_sub(p1, p0), 0.5 / s), du) / v_len(du);
		shape_uv_point(&o, u, v + s, &p1, NULL, NULL);
		shape_uv_point(&o, u, v - s, &p0, NULL, NULL);
		double e2 = dist(v_scale(v_sub(p1, p0), 0.5 / s), dv) / v_len(dv);
		struct ray r = {v_madd(p, n, 1e-5 * size), v_neg(n)};
		struct hit h;
		if (!shape_intersect(&o, &r, 0, INFINITY, &h) || dist(h.p, p) > 1e-7 * size)
			continue; /* a cap point off the outline, or hidden behind another part */
		tried++;
		worst = fmax(worst, fmax(e1, e2));
		double orient = v_dot(h.n, cr) * xf_det(obj_xf(&o));
		bool ok = fabs(h.u - u) < 1e-7 && fabs(h.v - v) < 1e-7 && orient > 0;
		if (!ok && bad < 3)
			printf("#   uv (%.9f, %.9f) -> (%.9f, %.9f), orient %g\n", u, v, h.u, h.v, orient);
		bad += !ok;
	}
	printf("# %s: %d round trips, worst partial error %.2g\n", scene_object_kind_name(src->kind),
	       tried, worst);
	CHECK(bad == 0);
	CHECK(tried > 100);
	CHECK(worst < 1e-4);
}

static void t_round_trips(void)
{
	if (run(shapes) != 0) {
		CHECK(!"scene failed");
		return;
	}
	rng_seed(12);
	for (int k = 0; k < sc.nobjects; k++)
		round_trips(sc.objects[k]);
	scene_free(&sc);
}

static bool have_fonts(void) { return access(POVRAY_INCLUDE_DIR "/timrom.ttf", R_OK) == 0; }

static struct bbox text_bounds(const char *scene)
{
	const struct object *o = first(scene);
	struct bbox b = o ? shape_bounds(o) : bbox_empty();
	scene_free(&sc);
	return b;
}

static void t_text_placement(void)
{
	if (!have_fonts()) {
		printf("# skipped: POV-Ray's fonts are not installed (make deps installs povray-includes)\n");
		return;
	}
	struct bbox one = text_bounds("text { ttf \"timrom.ttf\" \"I\" 0.25, 0 }\n");
	CHECK_NEAR(one.lo.x, 0, 1e-12); /* the first glyph's left edge at x = 0 */
	CHECK_NEAR(one.lo.z, 0, 0);
	CHECK_NEAR(one.hi.z, 0.25, 1e-15);
	CHECK(one.hi.y > 0.5 && one.hi.y < 1 && one.lo.y > -0.01); /* a capital on the baseline */
	struct bbox two = text_bounds("text { ttf \"timrom.ttf\" \"II\" 0.25, 0 }\n");
	struct bbox twox = text_bounds("text { ttf \"timrom.ttf\" \"II\" 0.25, <0.5, 0, 0> }\n");
	struct bbox twoy = text_bounds("text { ttf \"timrom.ttf\", \"II\", 0.25, <0, 0.25, 7> }\n");
	CHECK_NEAR(twox.hi.x - two.hi.x, 0.5, 1e-12); /* the offset moves the next glyph */
	CHECK_NEAR(twoy.hi.y - two.hi.y, 0.25, 1e-12);
	CHECK_NEAR(twoy.hi.z, 0.25, 1e-15);            /* and its z is ignored (POV-Ray) */
	CHECK(two.hi.x - one.hi.x > 0.3);              /* one advance of 'I' */
	/* a ray through the middle of the 'I' meets the front face at z = 0 */
	const struct object *o = first("text { ttf \"timrom.ttf\" \"I\" 0.25, 0 }\n");
	struct hit h;
	if (!o)
		return;
	struct vec3 mid = v_scale(v_add(one.lo, one.hi), 0.5);
	CHECK(hit(o, v3(mid.x, mid.y, -5), v3(0, 0, 1), 0, &h));
	CHECK_NEAR(h.t, 5, 1e-12);
	CHECK_VEC(h.n, v3(0, 0, -1), 1e-12);
	CHECK(hit(o, v3(mid.x, mid.y, -5), v3(0, 0, 1), 5.1, &h));
	CHECK_NEAR(h.t, 5.25, 1e-12);
	CHECK_VEC(h.n, v3(0, 0, 1), 1e-12);
	CHECK(shape_inside(o, v3(mid.x, mid.y, 0.1)));
	CHECK(!shape_inside(o, v3(mid.x, mid.y, 0.3)));
	CHECK(hit(o, v3(-1, mid.y, 0.1), v3(1, 0, 0), 0, &h)); /* the stem's side wall (inside the serifs) */
	CHECK(h.p.x > one.lo.x && h.p.x < mid.x);
	CHECK_NEAR(h.n.x, -1, 1e-6);
	scene_free(&sc);
	/* quadratic pieces, several glyphs, holes ('g', 'e', 'o') */
	o = first("text { ttf \"timrom.ttf\" \"Ego\" 0.3, 0.05 }\n");
	if (o)
		round_trips(o);
	scene_free(&sc);
}

static void t_text_errors(void)
{
	if (!have_fonts())
		return;
	CHECK(run("text { ttf \"no_such_font.ttf\" \"A\" 1, 0 }\n") == 66);
	CHECK(errs && strstr(errs, "cannot find font file 'no_such_font.ttf'"));
	scene_free(&sc);
	char dir[] = "/tmp/arvo-test-font-XXXXXX";
	if (!mkdtemp(dir))
		return;
	char font[64], scene[64];
	snprintf(font, sizeof font, "%s/broken.ttf", dir);
	snprintf(scene, sizeof scene, "%s/s.scn", dir);
	FILE *f = fopen(font, "w"), *s = fopen(scene, "w");
	if (f && s) {
		fputs("this is not a font\n", f);
		fputs("text { ttf \"broken.ttf\" \"A\" 1, 0 }\n", s);
	}
	if (f)
		fclose(f);
	if (s)
		fclose(s);
	struct diag dg;
	FILE *err = open_memstream(&errs, &errlen);
	diag_init(&dg, err);
	struct eval_options o;
	eval_default_options(&o);
	int rc = eval_scene(scene, &o, &dg, &sc);
	fclose(err);
	CHECK(rc == 66);
	CHECK(errs && strstr(errs, "s.scn:1:12: error: not a font file: 'broken.ttf'"));
	scene_free(&sc);
	unlink(font);
	unlink(scene);
	rmdir(dir);
	/* a character the font lacks: a warning, and the scene still renders */
	CHECK(run("text { ttf \"timrom.ttf\" \"A\\u4E2DB\" 1, 0 }\n") == 0);
	CHECK(errs && strstr(errs, "warning: character U+4E2D is not in font 'timrom.ttf'"));
	scene_free(&sc);
}

int main(void)
{
	RUN(t_prism_ring);
	RUN(t_prism_conic_and_splines);
	RUN(t_polygon);
	RUN(t_lathe);
	RUN(t_sor);
	RUN(t_round_trips);
	RUN(t_text_placement);
	RUN(t_text_errors);
	free(errs);
	return test_done();
}
