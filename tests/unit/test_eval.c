/* SPDX-License-Identifier: MIT */
/* test_eval.c: values and the evaluator through its public entry, on small
 * scenes written to a temporary file: promotion rules, colours, transforms,
 * camera vectors, texture inheritance. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../../common/diag.h"
#include "../../eval/eval.h"
#include "../../eval/value.h"
#include "test.h"

static char *out;    /* #debug output of the last run */
static size_t outlen;
static struct scene sc;

/* Evaluates text as a scene; returns the exit code. */
static int run(const char *text)
{
	char path[] = "/tmp/arvo-test-eval-XXXXXX";
	int fd = mkstemp(path);
	if (fd < 0 || write(fd, text, strlen(text)) != (ssize_t)strlen(text))
		return -1;
	close(fd);
	FILE *dbg = open_memstream(&out, &outlen);
	FILE *err = fopen("/dev/null", "w");
	struct diag dg;
	diag_init(&dg, err);
	struct eval_options o;
	eval_default_options(&o);
	o.debug_out = dbg;
	int rc = eval_scene(path, &o, &dg, &sc);
	fclose(dbg);
	fclose(err);
	unlink(path);
	return rc;
}

static void done(void)
{
	scene_free(&sc);
	free(out);
	out = NULL;
}

static void t_value_constructors(void)
{
	double v[4] = {1, 2, 3, 4};
	struct value a = val_vector(4, v);
	CHECK(a.kind == V_VECTOR && a.n == 4 && a.v[3] == 4);
	struct value c = val_colour((struct colour){0.5, 0.25, 1, 0.1, 0.2});
	struct colour back = val_to_colour(&c);
	CHECK(back.r == 0.5 && back.f == 0.1 && back.t == 0.2);
	CHECK_STR(val_type_name(&c), "a colour");
	CHECK_STR(val_kind_name(V_ARRAY), "an array");
	struct value s = val_string("abc", 3);
	CHECK(s.kind == V_STRING && s.n == 3);
}

static void t_promotion(void)
{
	CHECK(run("#declare V = <1,2,3> * 2 + 1;\n#debug vstr(3, V, \",\", 0, 1)\n"
	          "#declare W = <1,2> + <1,2,3>;\n#debug concat(\" \", str(W.z, 0, 1))\n") == 0);
	CHECK_STR(out, "3.0,5.0,7.0 3.0");
	done();
}

static void t_colours(void)
{
	CHECK(run("#declare A = color 0.5;\n#declare B = rgb 0.5;\n#declare C = rgbft <1,0,0,0.2,0.3>;\n"
	          "#declare D = srgb 0.5;\n"
	          "#debug concat(str(A.filter,0,2), \" \", str(B.filter,0,2), \" \", str(C.transmit,0,2), \" \","
	          " str(D.red,0,4), \" \", str((C*2).red,0,1))\n") == 0);
	CHECK_STR(out, "0.50 0.00 0.30 0.2140 2.0");
	done();
}

static void t_transforms_and_camera(void)
{
	CHECK(run("sphere { 0, 1 translate x rotate y*90 scale 2 }\n"
	          "camera { location <0,0,-5> look_at 0 angle 90 }\n") == 0);
	CHECK(sc.nobjects == 1);
	struct vec3 p = xf_point(obj_xf(sc.objects[0]), v3(0, 0, 0));
	/* translate x, rotate 90° about y takes x to -z, scale 2 */
	CHECK_NEAR(p.x, 0, 1e-12);
	CHECK_NEAR(p.z, -2, 1e-12);
	CHECK_NEAR(v_len(sc.camera.direction), 1.33 / 2, 1e-9);
	CHECK_NEAR(sc.camera.direction.z, 1.33 / 2, 1e-9);
	done();
}

/* POV-Ray applies look_at (and angle) once the block's vectors are known:
 * with up along the view direction, its handedness test flips right, so this
 * camera shows +x on the left (checked against POV-Ray 3.7's render). */
static void t_camera_look_at_deferred(void)
{
	CHECK(run("camera { location <0, 5, 0> sky z look_at <0, 0, 0> right x*4/3 up z }\n") == 0);
	CHECK_NEAR(sc.camera.right.x, -4.0 / 3, 1e-12);
	CHECK_NEAR(sc.camera.direction.y, -1, 1e-12);
	done();
	/* the order of angle, right and look_at does not matter */
	CHECK(run("camera { angle 60 look_at 0 location <0,1,-3> right x*2 }\n") == 0);
	CHECK_NEAR(v_len(sc.camera.direction), 1 / tan(M_PI / 6), 1e-12);
	done();
}

static void t_texture_inheritance(void)
{
	CHECK(run("union { sphere { 0, 1 } sphere { x, 1 pigment { rgb <1,0,0> } } pigment { rgb <0,0,1> } no_shadow }\n") == 0);
	struct object *u = sc.objects[0];
	CHECK(u->kind == OBJ_UNION && u->g.csg.n == 2);
	CHECK(u->g.csg.kids[0]->tex->pigment.c[0].b == 1);
	CHECK(u->g.csg.kids[1]->tex->pigment.c[0].r == 1);
	CHECK(u->g.csg.kids[1]->flags & OF_NO_SHADOW);
	done();
}

/* Objects of a loop that make the same texture share one; a block that
 * writes pigment and finish makes one texture; clipped_by hands the object
 * its own before the clip node takes a pigment of its own. */
static void t_texture_sharing(void)
{
	CHECK(run("#declare I = 0;\n#while (I < 6)\n"
	          "  sphere { x * I, 0.4 pigment { rgb <mod(I, 2), 0, 1> } finish { phong 1 } }\n"
	          "  #declare I = I + 1;\n#end\n"
	          "sphere { 0, 1 pigment { rgb <1, 0, 0> } clipped_by { plane { y, 0 } } pigment { rgb <0, 1, 0> } }\n"
	          "#declare S = sphere { 0, 1 pigment { rgb 0.5 } }\n"
	          "object { S pigment { rgb 0.25 } translate y }\nobject { S }\n") == 0);
	CHECK(sc.nobjects == 9);
	struct object **o = sc.objects;
	CHECK(o[0]->tex == o[2]->tex && o[2]->tex == o[4]->tex);
	CHECK(o[1]->tex == o[3]->tex && o[0]->tex != o[1]->tex);
	CHECK(o[0]->tex->pigment.c[0].r == 0 && o[1]->tex->pigment.c[0].r == 1);
	CHECK(tex_finish(o[0]->tex)->phong == 1 && tex_finish(o[1]->tex) == tex_finish(o[0]->tex));
	struct object *clip = o[6];
	CHECK(clip->kind == OBJ_CLIP && clip->g.csg.kids[0]->tex->pigment.c[0].r == 1);
	CHECK(clip->tex->pigment.c[0].g == 1 && clip->tex->pigment.c[0].r == 0);
	CHECK(o[7]->tex->pigment.c[0].r == 0.25 && o[7]->tex->pigment.xf && o[8]->tex->pigment.c[0].r == 0.5);
	CHECK(o[8]->tex->pigment.xf == NULL);
	done();
}

/* A texture keeps its finish, normal, maps, layers and location in a shared
 * record: the distinct textures of a loop share one, which holds the place
 * they were written; a normal or a layer makes another; a texture is its
 * pigment and that pointer, 72 bytes. */
static void t_texture_records(void)
{
	CHECK(sizeof(struct texture) == 72);
	CHECK(run("#declare I = 0;\n#while (I < 4)\n"
	          "  sphere { x * I, 0.4 pigment { rgb <I / 4, 0, 1> } }\n"
	          "  #declare I = I + 1;\n#end\n"
	          "sphere { 0, 1 pigment { rgb 1 } normal { bumps 0.5 } }\n"
	          "sphere { 0, 1 texture { pigment { rgb 1 } } texture { pigment { rgbt <1, 0, 0, 0.5> } } }\n"
	          "sphere { 0, 1 }\n") == 0);
	CHECK(sc.nobjects == 7);
	struct object **o = sc.objects;
	CHECK(o[0]->tex != o[1]->tex && o[0]->tex->ext && o[0]->tex->ext == o[3]->tex->ext);
	CHECK(tex_loc(o[2]->tex).line == 3 && tex_loc(o[2]->tex).col == 23);
	CHECK(tex_normal(o[2]->tex) == NULL && tex_below(o[2]->tex) == NULL && tex_map(o[2]->tex) == NULL);
	CHECK(tex_normal(o[4]->tex) && tex_loc(o[4]->tex).line == 6 && tex_loc(o[4]->tex).col == 15);
	const struct texture *below = tex_below(o[5]->tex);
	CHECK(below && below->pigment.c[0].r == 1 && below->pigment.c[0].b == 1 && tex_below(below) == NULL);
	CHECK(o[5]->tex->pigment.c[0].t == 0.5 && tex_loc(o[5]->tex).line == 7 && tex_loc(o[5]->tex).col == 45);
	CHECK(o[6]->tex->ext == NULL && tex_loc(o[6]->tex).file == -1 && tex_nmap(o[6]->tex) == 0);
	CHECK(tex_finish(o[6]->tex) == tex_finish(o[0]->tex) && tex_finish(o[0]->tex)->diffuse == 0.6);
	done();
}

/* Objects keep their interior, illum_map and photons in one shared record
 * (struct obj_extra): none for a plain object, one for the children of a
 * CSG that pass the same ones down, and a write copies it. */
static void t_object_records(void)
{
	CHECK(obj_size(OBJ_SPHERE) == 72);
	CHECK(run("#declare U = union { sphere { 0, 1 } sphere { x, 1 } sphere { 2 * x, 1 interior { ior 2 } }\n"
	          "  interior { ior 1.5 } photons { target } }\n"
	          "object { U }\n"
	          "object { U photons { target 0.5 } }\n"
	          "sphere { 0, 1 illum_map { resolution 64 } }\n"
	          "sphere { 0, 1 }\n") == 0);
	CHECK(sc.nobjects == 4);
	struct object **o = sc.objects;
	struct object *const *a = o[0]->g.csg.kids, *const *b = o[1]->g.csg.kids;
	/* the first two children share the record propagate made; the third
	 * keeps its own interior and takes the photons */
	CHECK(a[0]->ext && a[0]->ext == a[1]->ext && a[2]->ext != a[0]->ext);
	CHECK(obj_interior(a[0])->ior == 1.5 && obj_interior(a[2])->ior == 2);
	CHECK(obj_photons(a[0]) && obj_photons(a[0])->target && obj_photons(a[2]) && obj_photons(a[2])->target);
	/* the copy's own photons { } are its own: the first copy keeps spacing 1 */
	CHECK(obj_photons(o[0])->spacing == 1 && obj_photons(o[1])->spacing == 0.5);
	CHECK(obj_interior(o[1])->ior == 1.5 && obj_photons(b[0]) && obj_photons(b[0])->spacing == 0.5);
	CHECK(obj_illum(o[2]).resolution == 64 && obj_interior(o[2]) == NULL && obj_photons(o[2]) == NULL);
	CHECK(o[3]->ext == NULL && obj_illum(o[3]).resolution == 0 && obj_illum(o[3]).cell == 0);
	done();
}

static void t_errors_are_65(void)
{
	CHECK(run("#declare X = 1/0;\n") == 65);
	done();
	CHECK(run("sphere { 0 }\n") == 65);
	done();
	CHECK(run("#error \"stop\"\n") == 65);
	done();
}

int main(void)
{
	RUN(t_value_constructors);
	RUN(t_promotion);
	RUN(t_colours);
	RUN(t_transforms_and_camera);
	RUN(t_camera_look_at_deferred);
	RUN(t_texture_inheritance);
	RUN(t_texture_sharing);
	RUN(t_texture_records);
	RUN(t_object_records);
	RUN(t_errors_are_65);
	srcfile_free_all();
	return test_done();
}
