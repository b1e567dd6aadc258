/* SPDX-License-Identifier: MIT */
/* geometry.c: objects. An object block collects its parameters and
 * modifiers; when it ends, the primitive's geom_ function (one per PRIM of
 * tracer/objects.def) checks the parameters and fixes the geometry. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "../tracer/polysolve.h"
#include "../tracer/output/imageio.h"
#include "../tracer/shape.h"

/* Applies X to an object, its texture and its children (POV-Ray moves the
 * texture with the object when the texture came first). */
void object_transform(struct eval *E, struct object *o, const struct xform *X)
{
	object_transform_own(E, o, X, NULL);
}

void object_transform_own(struct eval *E, struct object *o, const struct xform *X, const struct texture *own)
{
	o->xf = xform_then(E, o->xf, X);
	if (o->tex) {
		if (o->tex != own) /* textures are shared: a copy moves */
			o->tex = texture_copy(E, o->tex);
		texture_transform(E, o->tex, X);
	}
	if (o->kind >= OBJ_FIRST_CSG)
		for (int i = 0; i < o->g.csg.n; i++)
			object_transform(E, o->g.csg.kids[i], X);
}

static struct object *object_copy(struct eval *E, const struct object *o)
{
	eval_count_object(E, E->stmt); /* copies of declared CSGs count too */
	struct object *c = obj_copy(&SC(E)->arena, o);
	if (o->kind >= OBJ_FIRST_CSG) {
		c->g.csg.kids = ARENA_ARRAY(&SC(E)->arena, struct object *, o->g.csg.n);
		for (int i = 0; i < o->g.csg.n; i++)
			c->g.csg.kids[i] = object_copy(E, o->g.csg.kids[i]);
	}
	return c;
}

static enum object_kind object_kind_of(enum tok kw)
{
	switch (kw) {
#define PRIM(n, w) case TK_##n: return OBJ_##n;
#define CSG(n, w) case TK_##n: return OBJ_##n;
#include "../tracer/objects.def"
	case TK_QUARTIC: case TK_CUBIC: case TK_QUADRIC: return OBJ_POLY;
	case TK_MESH2: case TK_SMOOTH_TRIANGLE: case TK_HEIGHT_FIELD: return OBJ_MESH;
	default: return OBJ_KIND_COUNT;
	}
}

bool is_object_kw(enum tok kw) { return object_kind_of(kw) != OBJ_KIND_COUNT || kw == TK_OBJECT; }

static void csg_add(struct eval *E, struct object *o, struct object *kid)
{
	int n = o->g.csg.n;
	if ((n & (n - 1)) == 0) {
		struct object **k = ARENA_ARRAY(&SC(E)->arena, struct object *, n ? n * 2 : 2);
		if (n)
			memcpy(k, o->g.csg.kids, sizeof *k * (size_t)n);
		o->g.csg.kids = k;
	}
	o->g.csg.kids[o->g.csg.n++] = kid;
}

/* The object a sink is building; `object { }` must name one first. */
static struct object *object_target(struct eval *E, struct sink *s, struct srcloc loc)
{
	if (!s->target)
		eval_fail(E, loc, "'object' needs a declared object first: object { Name … }");
	return s->target;
}

/* The object whose texture is sink s's scratch (object_block) gets a scene
 * texture in its place: the block ends, or the scratch is wanted for another
 * object (the clip node clipped_by makes). */
static void unscratch(struct eval *E, struct sink *s)
{
	if (s->own_obj && s->own_obj->tex == s->own_tex)
		s->own_obj->tex = texture_share(E, s->own_tex);
	s->own_obj = NULL;
}

/* pigment/finish/interior blocks inside an object modify what it has. */
static void object_material_block(struct eval *E, struct sink *s, struct object *o, const struct node *n)
{
	struct sink sub;
	if (n->op == TK_PIGMENT || n->op == TK_FINISH || n->op == TK_NORMAL) {
		if (!s->own_tex) { /* a sink without a scratch texture: a copy */
			o->tex = texture_copy(E, o->tex);
		} else if (o->tex != s->own_tex) { /* the first change: into the block's scratch */
			unscratch(E, s);
			*s->own_tex = o->tex ? *o->tex : E->default_tex;
			o->tex = s->own_tex;
			s->own_obj = o;
		}
		if (tex_loc(o->tex).file < 0)
			tex_set_loc(E, o->tex, n->loc);
		if (n->op == TK_PIGMENT)
			run_block(E, n, SK_PIGMENT, &o->tex->pigment, &sub);
		else if (n->op == TK_NORMAL)
			tex_set_normal(E, o->tex, normal_block(E, n));
		else
			tex_set_finish(E, o->tex, finish_block(E, n, tex_finish(o->tex)));
	} else if (n->op == TK_INTERIOR) {
		struct interior *in = NEW(E, struct interior);
		*in = obj_interior(o) ? *obj_interior(o) : scene_default_interior();
		run_block(E, n, SK_INTERIOR, in, &sub);
		obj_extra_w(&SC(E)->arena, o)->interior = in;
	} else if (n->op == TK_TEXTURE) {
		struct value v = eval_block(E, n);
		if (s->pending & 1) { /* a second texture in the block: a layer on top */
			struct texture *t = texture_copy(E, o->tex);
			texture_layer(E, t, v.p.tex);
			o->tex = t;
		} else {
			o->tex = v.p.tex;
		}
		s->pending |= 1;
	} else {
		struct value v = eval_block(E, n);
		if (v.p.mat->tex)
			o->tex = v.p.mat->tex;
		if (v.p.mat->interior)
			obj_extra_w(&SC(E)->arena, o)->interior = v.p.mat->interior;
	}
	(void)s;
}

static void object_geometry(struct eval *E, struct sink *s, struct object *o);

/* object { … clipped_by { A B … } … }: from here on the sink builds a clip
 * node whose first child is the object so far (its geometry fixed now) and
 * whose others are A, B …; later modifiers apply to the whole (csg.c). */
static void clip(struct eval *E, struct sink *s, struct object *o, const struct node *n)
{
	if (s->kw != TK_OBJECT && o->kind < OBJ_FIRST_CSG)
		object_geometry(E, s, o);
	struct object tmp = {.kind = OBJ_UNION, .loc = n->loc};
	struct sink sub;
	sink_init(&sub, SK_OBJECT, TK_UNION, n->loc, &tmp);
	eval_items(E, n, &sub);
	if (tmp.g.csg.n == 0)
		eval_fail(E, n->loc, "clipped_by needs an object: clipped_by { plane { y, 0 } }");
	struct object *c = obj_new(&SC(E)->arena, OBJ_CLIP);
	c->loc = o->loc;
	csg_add(E, c, o);
	for (int i = 0; i < tmp.g.csg.n; i++)
		csg_add(E, c, tmp.g.csg.kids[i]);
	s->target = c;
}

#define SINK_BLOB_PART 1u /* sink.pending: a blob's sphere or cylinder */

/* The blob o is building (made on first use). */
static struct blob *blob_of(struct eval *E, struct object *o)
{
	if (!o->g.blob.b) {
		struct blob *b = NEW(E, struct blob);
		b->threshold = 1; /* POV-Ray's default */
		o->g.blob.b = b;
	}
	return (struct blob *)o->g.blob.b;
}

static void blob_add(struct eval *E, struct object *o, struct blob_comp c)
{
	struct blob *b = blob_of(E, o);
	if ((b->n & (b->n - 1)) == 0) {
		struct blob_comp *more = ARENA_ARRAY(&SC(E)->arena, struct blob_comp, b->n ? 2 * b->n : 1);
		if (b->n)
			memcpy(more, b->c, sizeof *more * (size_t)b->n);
		b->c = more;
	}
	b->c[b->n++] = c;
}

/* A blob's sphere { c, r, [strength] s } or cylinder { a, b, r, [strength] s },
 * with its own transforms (its texture is not used). */
static void blob_component(struct eval *E, struct object *o, const struct node *n)
{
	struct object tmp = {.kind = n->op == TK_SPHERE ? OBJ_SPHERE : OBJ_CYLINDER, .loc = n->loc};
	struct sink sub;
	sink_init(&sub, SK_OBJECT, n->op, n->loc, &tmp);
	sub.pending = SINK_BLOB_PART;
	eval_items(E, n, &sub);
	bool cyl = n->op == TK_CYLINDER;
	int k = cyl ? 4 : 3;
	if (sub.nparams != k)
		eval_fail(E, n->loc, "%s", cyl ? "a blob cylinder expects two end points, a radius and a strength: cylinder { <a>, <b>, r, strength s }"
		                                : "a blob sphere expects a centre, a radius and a strength: sphere { <c>, r, strength s }");
	struct blob_comp c = {.cylinder = cyl, .xf = tmp.xf};
	c.a = val_want_vec3(E, &sub.params[0], sub.ploc[0]);
	if (cyl) {
		c.b = val_want_vec3(E, &sub.params[1], sub.ploc[1]);
		if (!(v_len(v_sub(c.b, c.a)) > 0))
			eval_fail(E, sub.ploc[1], "blob cylinder end points coincide");
	}
	c.r = val_want_float(E, &sub.params[k - 2], sub.ploc[k - 2]);
	c.s = val_want_float(E, &sub.params[k - 1], sub.ploc[k - 1]);
	if (!(c.r > 0))
		eval_fail(E, sub.ploc[k - 2], "blob component radius must be positive, found %g", c.r);
	blob_add(E, o, c);
}

/* component s, r, <c>: POV-Ray's old spelling of a blob sphere. */
static void blob_old_component(struct eval *E, struct object *o, const struct node *n)
{
	if (n->nkids != 3)
		eval_fail(E, n->loc, "component expects a strength, a radius and a centre: component s, r, <c>");
	struct blob_comp c = {.s = eval_float(E, n->kids[0]), .r = eval_float(E, n->kids[1])};
	struct value v = eval_expr(E, n->kids[2]);
	c.a = val_want_vec3(E, &v, n->kids[2]->loc);
	if (!(c.r > 0))
		eval_fail(E, n->kids[1]->loc, "blob component radius must be positive, found %g", c.r);
	blob_add(E, o, c);
}


/* ---- meshes ---------------------------------------------------------------- */

/* Room for one more element in an arena array of n (doubling at powers of two). */
static void *grow(struct eval *E, void *arr, int n, size_t size)
{
	if (n & (n - 1))
		return arr;
	void *more = arena_alloc(&SC(E)->arena, size * (size_t)(n ? 2 * n : 4));
	if (n)
		memcpy(more, arr, size * (size_t)n);
	return more;
}

/* The mesh o is building (made on first use). */
static struct mesh *mesh_of(struct eval *E, struct object *o)
{
	if (!o->g.mesh.m)
		o->g.mesh.m = NEW(E, struct mesh);
	return (struct mesh *)o->g.mesh.m;
}

static int mesh_vertex(struct eval *E, struct mesh *m, struct vec3 p)
{
	m->vert = grow(E, m->vert, m->nv, sizeof *m->vert);
	m->vert[m->nv] = p;
	return m->nv++;
}

static int mesh_normal(struct eval *E, struct mesh *m, struct vec3 n)
{
	m->norm = grow(E, m->norm, m->nn, sizeof *m->norm);
	m->norm[m->nn] = n;
	return m->nn++;
}

static void mesh_add(struct eval *E, struct mesh *m, struct mesh_tri t)
{
	m->tri = grow(E, m->tri, m->nt, sizeof *m->tri);
	m->tri[m->nt++] = t;
}

/* triangle { a, b, c } or smooth_triangle { a, na, b, nb, c, nc } from the
 * collected parameters; degenerate triangles are dropped, as POV-Ray does. */
static void mesh_triangle_params(struct eval *E, struct mesh *m, struct sink *s, bool smooth)
{
	int k = smooth ? 6 : 3;
	if (s->nparams != k)
		eval_fail(E, s->nparams > k ? s->ploc[k] : s->loc, "%s", smooth
		          ? "smooth_triangle expects three corners, each with a normal: smooth_triangle { <a>, <na>, <b>, <nb>, <c>, <nc> }"
		          : "triangle expects three corners: triangle { <a>, <b>, <c> }");
	struct vec3 p[3], nv[3];
	for (int i = 0; i < 3; i++) {
		p[i] = val_want_vec3(E, &s->params[smooth ? 2 * i : i], s->ploc[smooth ? 2 * i : i]);
		if (smooth)
			nv[i] = val_want_vec3(E, &s->params[2 * i + 1], s->ploc[2 * i + 1]);
	}
	if (!(v_len(v_cross(v_sub(p[1], p[0]), v_sub(p[2], p[0]))) > 0))
		return;
	struct mesh_tri t = {{0, 0, 0}, {-1, -1, -1}};
	for (int i = 0; i < 3; i++) {
		t.v[i] = mesh_vertex(E, m, p[i]);
		if (smooth)
			t.n[i] = mesh_normal(E, m, nv[i]);
	}
	mesh_add(E, m, t);
}

/* A mesh's triangle { … } or smooth_triangle { … } (its texture unused). */
static void mesh_triangle(struct eval *E, struct object *o, const struct node *n)
{
	struct object tmp = {.kind = OBJ_TRIANGLE, .loc = n->loc};
	struct sink sub;
	sink_init(&sub, SK_OBJECT, n->op, n->loc, &tmp);
	eval_items(E, n, &sub);
	if (tmp.xf)
		eval_fail(E, n->loc, "a mesh's triangles cannot be transformed one by one; transform the mesh");
	if (tmp.tex && !E->warned_mesh_tex++)
		diag_warning(E->diag, n->loc, "textures of single mesh triangles are not supported; the mesh's texture is used");
	mesh_triangle_params(E, mesh_of(E, o), &sub, n->op == TK_SMOOTH_TRIANGLE);
}

/* What a mesh2 list block collects. */
struct vlist {
	struct value *v;
	struct srcloc *loc;
	int n;
	int textures; /* texture_list: texture { } blocks */
};

void list_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct vlist *L = s->target;
	if (s->kw == TK_TEXTURE_LIST && n->op == TK_TEXTURE && n->kind == N_BLOCK) {
		eval_block(E, n);
		L->textures++;
		return;
	}
	misplaced(E, s, n);
}

void list_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc)
{
	struct vlist *L = s->target;
	if (v->kind != V_FLOAT && v->kind != V_VECTOR)
		eval_fail(E, loc, "expected a number or a vector in %s, found %s", tok_name(s->kw), val_type_name(v));
	L->v = grow(E, L->v, L->n, sizeof *L->v);
	L->loc = grow(E, L->loc, L->n, sizeof *L->loc);
	L->v[L->n] = *v;
	L->loc[L->n++] = loc;
}

/* The vectors of a mesh2 list `kw { count, v, v, … }`, written to *out (NULL
 * when absent); checks the count. Face lists may follow a face's vector by
 * one or three texture indices, which are skipped. */
static int mesh2_vectors(struct eval *E, const struct node *n, struct vec3 **out)
{
	struct vlist L = {0};
	struct sink sub;
	sink_init(&sub, SK_LIST, n->op, n->loc, &L);
	eval_items(E, n, &sub);
	if (n->op == TK_TEXTURE_LIST || n->op == TK_UV_VECTORS || n->op == TK_UV_INDICES)
		return 0;
	if (L.n == 0 || L.v[0].kind != V_FLOAT)
		eval_fail(E, n->loc, "%s starts with its count: %s { n, <…>, … }", tok_name(n->op), tok_name(n->op));
	double cnt = L.v[0].v[0];
	int k = 0;
	*out = ARENA_ARRAY(&SC(E)->arena, struct vec3, L.n);
	for (int i = 1; i < L.n; i++) {
		if (L.v[i].kind == V_FLOAT) {
			if (n->op != TK_FACE_INDICES || k == 0)
				eval_fail(E, L.loc[i], "expected a vector in %s, found a number", tok_name(n->op));
			continue; /* a texture index */
		}
		(*out)[k++] = val_want_vec3(E, &L.v[i], L.loc[i]);
	}
	if (cnt != k)
		eval_fail(E, n->loc, "%s says %g entries, found %d", tok_name(n->op), cnt, k);
	return k;
}

/* An index of a mesh2 face, checked against the count it indexes. */
static int mesh2_index(struct eval *E, double x, int count, const char *what, struct srcloc loc)
{
	if (!(x >= 0 && x < count && x == floor(x)))
		eval_fail(E, loc, "%s index %g is out of range (0 to %d)", what, x, count - 1);
	return (int)x;
}

/* mesh2 { vertex_vectors { … } [normal_vectors { … }] face_indices { … }
 * [normal_indices { … }] … }: the lists are kept in the sink's params
 * slots as they come and joined at the end (geom_mesh). */
static void mesh2_block(struct eval *E, struct object *o, const struct node *n)
{
	struct mesh *m = mesh_of(E, o);
	struct vec3 *vs = NULL;
	switch (n->op) {
	case TK_VERTEX_VECTORS:
		if (m->nv)
			eval_fail(E, n->loc, "mesh2 has vertex_vectors already");
		m->nv = mesh2_vectors(E, n, &m->vert);
		return;
	case TK_NORMAL_VECTORS:
		if (m->nn)
			eval_fail(E, n->loc, "mesh2 has normal_vectors already");
		m->nn = mesh2_vectors(E, n, &m->norm);
		return;
	case TK_FACE_INDICES: {
		if (!m->nv)
			eval_fail(E, n->loc, "mesh2's face_indices must come after its vertex_vectors");
		int k = mesh2_vectors(E, n, &vs);
		for (int i = 0; i < k; i++) {
			struct mesh_tri t = {{0, 0, 0}, {-1, -1, -1}};
			t.v[0] = mesh2_index(E, vs[i].x, m->nv, "vertex", n->loc);
			t.v[1] = mesh2_index(E, vs[i].y, m->nv, "vertex", n->loc);
			t.v[2] = mesh2_index(E, vs[i].z, m->nv, "vertex", n->loc);
			if (m->nn == m->nv) /* normals follow the vertices unless normal_indices says */
				for (int j = 0; j < 3; j++)
					t.n[j] = t.v[j];
			mesh_add(E, m, t);
		}
		return;
	}
	case TK_NORMAL_INDICES: {
		if (!m->nn || !m->nt)
			eval_fail(E, n->loc, "mesh2's normal_indices must come after its normal_vectors and face_indices");
		int k = mesh2_vectors(E, n, &vs);
		if (k != m->nt)
			eval_fail(E, n->loc, "normal_indices has %d entries for %d faces", k, m->nt);
		for (int i = 0; i < k; i++) {
			m->tri[i].n[0] = mesh2_index(E, vs[i].x, m->nn, "normal", n->loc);
			m->tri[i].n[1] = mesh2_index(E, vs[i].y, m->nn, "normal", n->loc);
			m->tri[i].n[2] = mesh2_index(E, vs[i].z, m->nn, "normal", n->loc);
		}
		return;
	}
	default: /* uv_vectors, uv_indices, texture_list: read, not used */
		if (n->op == TK_TEXTURE_LIST && !E->warned_mesh_tex++)
			diag_warning(E->diag, n->loc, "textures of single mesh triangles are not supported; the mesh's texture is used");
		mesh2_vectors(E, n, &vs);
		return;
	}
}
static struct isosurface *iso_w(struct eval *E, struct object *o);
static void isosurface_keyword(struct eval *E, struct object *o, const struct node *n);

/* height_field { png "file" … }: the image's heights as POV-Ray reads them
 * (a palette image's index·256, a grey image's value, an 8-bit colour
 * image's red·256 + green, a 16-bit one's grey), over 65536; the grid
 * x = i/(w−1), z = j/(h−1), the image's bottom row at z = 0; each cell two
 * triangles split along the diagonal from (i+1, j) to (i, j+1). */
static void height_field_image(struct eval *E, struct object *o, const struct node *n)
{
	struct mesh *m = mesh_of(E, o);
	if (m->hf_w)
		eval_fail(E, n->loc, "height_field has its image already");
	struct value v = arg1(E, n);
	if (v.kind != V_STRING)
		eval_fail(E, n->kids[0]->loc, "expected a file name string, found %s", val_type_name(&v));
	char *real = eval_find_file(E, v.p.s, n->loc, "image file", NULL);
	if (E->opt->on_file) /* -M: the image is a dependency */
		E->opt->on_file(real, E->opt->on_file_ctx);
	struct img im;
	struct img_opts io = {NULL, NULL, 1, 1};
	int err = img_load(real, &io, &im, E->diag, n->loc, v.p.s);
	free(real);
	if (err) {
		E->missing = 1;
		longjmp(*E->fail, 1);
	}
	if (im.w < 2 || im.h < 2) {
		img_free(&im);
		eval_fail(E, n->loc, "a height_field image needs at least 2 x 2 pixels");
	}
	int w = im.w, h = im.h;
	m->hf_w = w;
	m->hf_h = h;
	m->nv = w * h;
	m->vert = ARENA_ARRAY(&SC(E)->arena, struct vec3, m->nv);
	for (int j = 0; j < h; j++)
		for (int i = 0; i < w; i++) {
			const float *px = im.px + ((size_t)(h - 1 - j) * (size_t)w + (size_t)i) * (size_t)im.nch;
			double hv;
			if (im.indexed)
				hv = floor(px[0] * 255.0f + 0.5f) * 256;
			else if (im.depth > 8)
				hv = floor((0.297f * px[0] + 0.589f * px[1] + 0.114f * px[2]) * 65535.0f);
			else
				hv = floor(px[0] * 255.0f + 0.5f) * 256 + floor(px[1] * 255.0f + 0.5f);
			m->vert[j * w + i] = v3((double)i / (w - 1), hv / 65536, (double)j / (h - 1));
		}
	img_free(&im);
	m->nt = 2 * (w - 1) * (h - 1);
	m->tri = ARENA_ARRAY(&SC(E)->arena, struct mesh_tri, m->nt);
	int k = 0;
	for (int j = 0; j + 1 < h; j++)
		for (int i = 0; i + 1 < w; i++) {
			int a = j * w + i, b = a + 1, c = a + w, d = c + 1;
			m->tri[k++] = (struct mesh_tri){{a, c, b}, {-1, -1, -1}}; /* normal up */
			m->tri[k++] = (struct mesh_tri){{d, b, c}, {-1, -1, -1}};
		}
	m->has_inside = true;
	m->inside_dir = v3(0, 1, 0);
}

/* height_field smooth: each grid point's normal from its neighbours'
 * heights (one-sided at the edges). */
static void height_field_normals(struct eval *E, struct mesh *m)
{
	int w = m->hf_w, h = m->hf_h;
	m->nn = w * h;
	m->norm = ARENA_ARRAY(&SC(E)->arena, struct vec3, m->nn);
	for (int j = 0; j < h; j++)
		for (int i = 0; i < w; i++) {
			int i0 = i > 0 ? i - 1 : i, i1 = i + 1 < w ? i + 1 : i;
			int j0 = j > 0 ? j - 1 : j, j1 = j + 1 < h ? j + 1 : j;
			struct vec3 dx = v_sub(m->vert[j * w + i1], m->vert[j * w + i0]);
			struct vec3 dz = v_sub(m->vert[j1 * w + i], m->vert[j0 * w + i]);
			m->norm[j * w + i] = v_norm(v_cross(dz, dx));
		}
	for (int t = 0; t < m->nt; t++)
		for (int k = 0; k < 3; k++)
			m->tri[t].n[k] = m->tri[t].v[k];
}

void object_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct xform X;
	if (n->op == TK_STRENGTH && (s->pending & SINK_BLOB_PART)) {
		struct value v = arg1(E, n);
		object_value(E, s, &v, n->loc);
		return;
	}
	if (s->kw == TK_OBJECT && !s->target && is_object_kw(n->op) && n->kind == N_BLOCK) {
		s->target = eval_block(E, n).p.obj; /* object { Macro() } with a macro yielding an object */
		return;
	}
	if (transform_of(E, n, &X)) {
		object_transform_own(E, object_target(E, s, n->loc), &X, s->own_tex);
		s->modified = 1;
		return;
	}
	struct object *o = object_target(E, s, n->loc);
	if (!s->modified && is_outline_kind(o->kind) && outline_keyword(E, s, o, n))
		return;
	s->modified = 1;
	switch (n->op) {
	case TK_TEXTURE: case TK_PIGMENT: case TK_FINISH: case TK_INTERIOR: case TK_MATERIAL: case TK_NORMAL:
		object_material_block(E, s, o, n);
		return;
	case TK_BOUNDED_BY:
		/* POV-Ray's bounding hint: arvo bounds every object itself, but an
		 * unbounded polynomial surface is only seen inside its bound */
		if (o->kind == OBJ_POLY && !(n->nkids == 1 && n->kids[0]->op == TK_CLIPPED_BY))
			clip(E, s, o, n);
		return;
	case TK_CLIPPED_BY:
		if (n->kind != N_BLOCK)
			misplaced(E, s, n); /* the word form belongs in bounded_by */
		clip(E, s, o, n);
		return;
	case TK_NO_SHADOW: o->flags |= OF_NO_SHADOW; return;
	case TK_NO_IMAGE: o->flags |= OF_NO_IMAGE; return;
	case TK_NO_REFLECTION: o->flags |= OF_NO_REFLECTION; return;
	case TK_DOUBLE_ILLUMINATE: o->flags |= OF_DOUBLE_ILLUM; return;
	case TK_INVERSE: o->flags ^= OF_INVERSE; return;
	case TK_HOLLOW:
		if (arg_bool(E, n))
			o->flags |= OF_HOLLOW;
		else
			o->flags &= ~(unsigned)OF_HOLLOW;
		return;
	case TK_CONTAINED_BY: case TK_MAX_GRADIENT: case TK_ACCURACY: case TK_MAX_TRACE:
	case TK_ALL_INTERSECTIONS: case TK_EVALUATE:
		if (o->kind != OBJ_ISOSURFACE)
			misplaced(E, s, n);
		isosurface_keyword(E, o, n);
		return;
	case TK_OPEN:
		if (o->kind != OBJ_CYLINDER && o->kind != OBJ_CONE && o->kind != OBJ_PRISM && o->kind != OBJ_SOR &&
		    o->kind != OBJ_ISOSURFACE)
			misplaced(E, s, n);
		o->flags |= OF_OPEN;
		return;
	case TK_THRESHOLD: /* blob and isosurface */
		if (o->kind == OBJ_ISOSURFACE) {
			isosurface_keyword(E, o, n);
			return;
		}
		if (o->kind != OBJ_BLOB)
			misplaced(E, s, n);
		blob_of(E, o)->threshold = arg_float(E, n);
		if (!(blob_of(E, o)->threshold > 0))
			eval_fail(E, n->kids[0]->loc, "blob threshold must be positive");
		return;
	case TK_PNG:
		if (s->kw != TK_HEIGHT_FIELD)
			misplaced(E, s, n);
		height_field_image(E, o, n);
		return;
	case TK_WATER_LEVEL:
		if (s->kw != TK_HEIGHT_FIELD)
			misplaced(E, s, n);
		mesh_of(E, o)->clip_y = arg_float(E, n); /* a fraction of the full height */
		mesh_of(E, o)->clipped = true;
		return;
	case TK_SMOOTH:
		if (s->kw != TK_HEIGHT_FIELD)
			misplaced(E, s, n);
		mesh_of(E, o)->hf_smooth = true;
		return;
	case TK_INSIDE_VECTOR:
		if (o->kind != OBJ_MESH || s->kw == TK_SMOOTH_TRIANGLE)
			misplaced(E, s, n);
		mesh_of(E, o)->inside_dir = arg_vec3(E, n);
		mesh_of(E, o)->has_inside = v_len(mesh_of(E, o)->inside_dir) > 0;
		return;
	case TK_VERTEX_VECTORS: case TK_NORMAL_VECTORS: case TK_UV_VECTORS: case TK_TEXTURE_LIST:
	case TK_FACE_INDICES: case TK_NORMAL_INDICES: case TK_UV_INDICES:
		if (s->kw != TK_MESH2)
			misplaced(E, s, n);
		mesh2_block(E, o, n);
		return;
	case TK_COMPONENT:
		if (o->kind != OBJ_BLOB)
			misplaced(E, s, n);
		blob_old_component(E, o, n);
		return;
	case TK_HIERARCHY:
		if (o->kind != OBJ_BLOB && o->kind != OBJ_MESH)
			misplaced(E, s, n);
		arg_bool(E, n); /* POV-Ray's bounding hint */
		return;
	case TK_STURM:
		if (o->kind != OBJ_TORUS && o->kind != OBJ_POLY && o->kind != OBJ_BLOB && o->kind != OBJ_PRISM &&
		    o->kind != OBJ_LATHE && o->kind != OBJ_SOR)
			misplaced(E, s, n);
		arg_bool(E, n);
		o->flags |= OF_STURM;
		return;
	case TK_PHOTONS: {
		struct sink sub;
		struct obj_extra *x = obj_extra_w(&SC(E)->arena, o);
		x->has_photons = true;
		x->photons = (struct photon_spec){.spacing = 1, .collect = true};
		sink_init(&sub, SK_PHOTONS, TK_OBJECT, n->loc, &x->photons);
		eval_items(E, n, &sub);
		return;
	}
	case TK_ILLUM_MAP: {
		struct sink sub;
		struct obj_extra *x = obj_extra_w(&SC(E)->arena, o);
		run_block(E, n, SK_ILLUM_MAP, &x->illum, &sub);
		if (x->illum.resolution && x->illum.cell)
			eval_fail(E, n->loc, "illum_map takes 'resolution' or 'cell', not both");
		return;
	}
	default:
		if (s->kw == TK_MESH && (n->op == TK_TRIANGLE || n->op == TK_SMOOTH_TRIANGLE) && n->kind == N_BLOCK) {
			mesh_triangle(E, o, n);
			return;
		}
		if (o->kind == OBJ_BLOB && (n->op == TK_SPHERE || n->op == TK_CYLINDER) && n->kind == N_BLOCK) {
			blob_component(E, o, n);
			return;
		}
		if (is_object_kw(n->op) && n->kind == N_BLOCK) {
			if (o->kind < OBJ_FIRST_CSG)
				eval_fail(E, n->loc, "%s cannot contain other objects; use union { } to group them", tok_name(s->kw));
			csg_add(E, o, eval_block(E, n).p.obj);
			return;
		}
		misplaced(E, s, n);
	}
}

void object_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc)
{
	if (s->kw == TK_OBJECT && !s->target) {
		if (v->kind != V_OBJECT)
			eval_fail(E, loc, "expected a declared object in 'object', found %s", val_type_name(v));
		s->target = object_copy(E, v->p.obj);
		return;
	}
	struct object *o = object_target(E, s, loc);
	if (o->kind == OBJ_ISOSURFACE && v->kind == V_FUNCTION) { /* isosurface { function { … } … } */
		iso_w(E, o)->fn = function_usable(E, v, loc);
		return;
	}
	if (o->kind >= OBJ_FIRST_CSG || s->kw == TK_OBJECT) {
		if (v->kind == V_OBJECT)
			eval_fail(E, loc, "use object { Name } to place a declared object");
		eval_fail(E, loc, "unexpected %s in %s", val_type_name(v), tok_name(s->kw));
	}
	if (s->modified)
		eval_fail(E, loc, "%s parameters must come before its modifiers", tok_name(s->kw));
	if (is_outline_kind(o->kind) && outline_value(E, s, o, v, loc))
		return;
	if (v->kind != V_FLOAT && v->kind != V_VECTOR)
		eval_fail(E, loc, "expected a float or vector parameter in %s, found %s", tok_name(s->kw), val_type_name(v));
	if (s->nparams >= SINK_MAX_PARAMS)
		eval_fail(E, loc, "too many parameters in %s", tok_name(s->kw));
	s->ploc[s->nparams] = loc;
	s->params[s->nparams++] = *v;
}

/* Checks a primitive's parameter list against its signature. */
static void want_params(struct eval *E, struct sink *s, const char *sig, int min, int max)
{
	if (s->nparams < min || s->nparams > max)
		eval_fail(E, s->nparams > max ? s->ploc[max] : s->loc, "%s expects %s, found %d value%s", tok_name(s->kw), sig,
		          s->nparams, s->nparams == 1 ? "" : "s");
}

#define PV(i) val_want_vec3(E, &s->params[i], s->ploc[i])
#define PF(i) val_want_float(E, &s->params[i], s->ploc[i])

static double positive_param(struct eval *E, struct sink *s, int i, const char *what)
{
	double f = PF(i);
	if (!(f > 0))
		eval_fail(E, s->ploc[i], "%s must be positive, found %g", what, f);
	return f;
}

static void geom_sphere(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "a centre and a radius: sphere { <x,y,z>, r }", 2, 2);
	o->g.sphere.c = PV(0);
	o->g.sphere.r = positive_param(E, s, 1, "sphere radius");
}

static void geom_plane(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "a normal and a distance: plane { <nx,ny,nz>, d }", 2, 2);
	struct vec3 n = PV(0);
	if (v_len(n) == 0)
		eval_fail(E, s->ploc[0], "plane normal has zero length");
	o->g.plane.n = v_norm(n);
	o->g.plane.d = PF(1);
}

static void geom_box(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "two corners: box { <x1,y1,z1>, <x2,y2,z2> }", 2, 2);
	o->g.box.lo = v_min(PV(0), PV(1));
	o->g.box.hi = v_max(PV(0), PV(1));
	/* a flat box has no inside and faces of no area (its map's nodes) */
	for (int k = 0; k < 3; k++)
		if (!(v_comp(o->g.box.hi, k) > v_comp(o->g.box.lo, k)))
			eval_fail(E, s->ploc[1], "box has zero volume (both corners have %c = %g)", "xyz"[k],
			          v_comp(o->g.box.lo, k));
}

static void geom_disc(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "a centre, a normal and a radius: disc { <c>, <n>, r [, hole] }", 3, 4);
	o->g.disc.c = PV(0);
	if (v_len(PV(1)) == 0)
		eval_fail(E, s->ploc[1], "disc normal has zero length");
	o->g.disc.n = v_norm(PV(1));
	o->g.disc.r = positive_param(E, s, 2, "disc radius");
	o->g.disc.hole = s->nparams > 3 ? PF(3) : 0;
	if (o->g.disc.hole < 0 || o->g.disc.hole >= o->g.disc.r)
		eval_fail(E, s->ploc[3], "disc hole radius must be 0 to less than the radius");
}

static void geom_cylinder(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "two end points and a radius: cylinder { <a>, <b>, r }", 3, 3);
	o->g.cylinder.a = PV(0);
	o->g.cylinder.b = PV(1);
	if (v_len(v_sub(PV(1), PV(0))) == 0)
		eval_fail(E, s->ploc[1], "cylinder end points coincide");
	o->g.cylinder.r = positive_param(E, s, 2, "cylinder radius");
}

static void geom_cone(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "two end points with radii: cone { <a>, ra, <b>, rb }", 4, 4);
	o->g.cone.a = PV(0);
	o->g.cone.ra = PF(1);
	o->g.cone.b = PV(2);
	o->g.cone.rb = PF(3);
	if (v_len(v_sub(o->g.cone.b, o->g.cone.a)) == 0)
		eval_fail(E, s->ploc[2], "cone end points coincide");
	if (o->g.cone.ra < 0 || o->g.cone.rb < 0 || (o->g.cone.ra == 0 && o->g.cone.rb == 0))
		eval_fail(E, s->ploc[1], "cone radii must not be negative, and not both zero");
}

static void geom_torus(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "two radii: torus { major, minor }", 2, 2);
	o->g.torus.major = positive_param(E, s, 0, "torus major radius");
	o->g.torus.minor = positive_param(E, s, 1, "torus minor radius");
}

static void geom_triangle(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "three corners: triangle { <a>, <b>, <c> }", 3, 3);
	for (int i = 0; i < 3; i++)
		o->g.triangle.p[i] = PV(i);
	if (v_len(v_cross(v_sub(PV(1), PV(0)), v_sub(PV(2), PV(0)))) == 0)
		eval_fail(E, s->loc, "degenerate triangle (its corners are collinear)");
}

bool object_long_vector(struct eval *E, struct sink *s, const struct node *n)
{
	if (n->nkids <= 5 || (s->kw != TK_POLY && s->kw != TK_QUARTIC && s->kw != TK_CUBIC))
		return false;
	struct object *o = s->target; /* kept in the object, not the sink: sinks are on the stack */
	if (o->g.poly.list)
		eval_fail(E, n->loc, "%s takes one coefficient vector", tok_name(s->kw));
	if (s->modified)
		eval_fail(E, n->loc, "%s parameters must come before its modifiers", tok_name(s->kw));
	double *c = ARENA_ARRAY(&E->arena, double, n->nkids);
	for (int i = 0; i < n->nkids; i++)
		c[i] = eval_float(E, n->kids[i]);
	o->g.poly.list = c;
	o->g.poly.nlist = n->nkids;
	o->g.poly.list_loc = n->loc;
	return true;
}

/* The polynomial of order n from POV-Ray's coefficient list: xⁿ first, the
 * power of x falling slowest, then of y, then of z (a constant last). */
static void poly_from_list(struct eval *E, struct object *o, int n, const double *c)
{
	struct polynomial *P = NEW(E, struct polynomial);
	int count = (n + 1) * (n + 2) * (n + 3) / 6, k = 0;
	P->order = n;
	P->t = ARENA_ARRAY(&SC(E)->arena, struct poly_term, count);
	for (int i = n; i >= 0; i--)
		for (int j = n - i; j >= 0; j--)
			for (int l = n - i - j; l >= 0; l--, k++)
				if (c[k] != 0)
					P->t[P->nterms++] = (struct poly_term){c[k], {i, j, l}};
	o->g.poly.p = P;
}

/* poly { N, <…> }, quartic { <35> }, cubic { <20> }, quadric { <A,B,C>,
 * <D,E,F>, <G,H,I>, J }: A x² + B y² + C z² + D xy + E xz + F yz + G x +
 * H y + I z + J. */
static void geom_poly(struct eval *E, struct sink *s, struct object *o)
{
	int n = s->kw == TK_QUARTIC ? 4 : s->kw == TK_CUBIC ? 3 : 2;
	if (s->kw == TK_QUADRIC) {
		want_params(E, s, "four values: quadric { <A,B,C>, <D,E,F>, <G,H,I>, J }", 4, 4);
		struct vec3 a = PV(0), b = PV(1), c = PV(2);
		/* the list order of poly 2: x² xy xz x y² yz y z² z 1 */
		double l[10] = {a.x, b.x, b.y, c.x, a.y, b.z, c.y, a.z, c.z, PF(3)};
		poly_from_list(E, o, 2, l);
	} else {
		if (s->kw == TK_POLY) {
			want_params(E, s, "an order and its coefficients: poly { N, <a, b, …> }", 1, 1);
			double f = PF(0);
			if (!(f >= 2 && f <= POLY_MAX_DEGREE && f == floor(f)))
				eval_fail(E, s->ploc[0], "poly order must be an integer from 2 to %d, found %g", POLY_MAX_DEGREE, f);
			n = (int)f;
		} else {
			want_params(E, s, n == 4 ? "35 coefficients: quartic { <a, b, …> }" : "20 coefficients: cubic { <a, b, …> }", 0, 0);
		}
		int count = (n + 1) * (n + 2) * (n + 3) / 6;
		if (!o->g.poly.list)
			eval_fail(E, s->loc, "%s expects a vector of %d coefficients", tok_name(s->kw), count);
		if (o->g.poly.nlist != count)
			eval_fail(E, o->g.poly.list_loc, "%s of order %d expects %d coefficients, found %d", tok_name(s->kw), n, count,
			          o->g.poly.nlist);
		poly_from_list(E, o, n, o->g.poly.list);
	}
	if (o->g.poly.p->nterms == 0)
		eval_fail(E, s->loc, "%s has no non-zero coefficient", tok_name(s->kw));
}

static void geom_superellipsoid(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "two exponents: superellipsoid { <e, n> }", 1, 1);
	struct value *v = &s->params[0];
	if (v->kind != V_VECTOR || v->n != 2)
		eval_fail(E, s->ploc[0], "superellipsoid expects a 2-component vector <e, n>");
	for (int i = 0; i < 2; i++)
		if (!(v->v[i] >= 1e-3 && v->v[i] <= 1e3))
			eval_fail(E, s->ploc[0], "superellipsoid exponents must be from 0.001 to 1000, found %g", v->v[i]);
	o->g.superellipsoid.e = v->v[0];
	o->g.superellipsoid.n = v->v[1];
}

static void geom_blob(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "components: blob { threshold T sphere { <c>, r, strength s } … }", 0, 0);
	struct blob *b = blob_of(E, o);
	if (b->n == 0)
		eval_fail(E, s->loc, "blob needs at least one sphere or cylinder component");
	struct bbox all = shape_bounds(&(struct object){.kind = OBJ_BLOB, .g.blob.b = b});
	b->centre = v_scale(v_add(all.lo, all.hi), 0.5);
}

/* mesh { triangles }, mesh2 { lists }, or a lone smooth_triangle { … }. */
static void geom_mesh(struct eval *E, struct sink *s, struct object *o)
{
	struct mesh *m = mesh_of(E, o);
	if (s->kw == TK_SMOOTH_TRIANGLE) {
		mesh_triangle_params(E, m, s, true);
		if (m->nt == 0)
			eval_fail(E, s->loc, "degenerate smooth_triangle (its corners are collinear)");
	} else if (s->kw == TK_HEIGHT_FIELD) {
		want_params(E, s, "an image: height_field { png \"file.png\" }", 0, 0);
		if (!m->hf_w)
			eval_fail(E, s->loc, "height_field needs an image: height_field { png \"file.png\" }");
		if (m->hf_smooth)
			height_field_normals(E, m);
	} else {
		want_params(E, s, s->kw == TK_MESH ? "triangles: mesh { triangle { <a>, <b>, <c> } … }"
		                                   : "lists: mesh2 { vertex_vectors { … } face_indices { … } }", 0, 0);
	}
	int bad = -1;
	if (!mesh_finish(m, &SC(E)->arena, &bad)) {
		if (bad >= 0)
			eval_fail(E, s->loc, "%s face %d has a normal index out of range", tok_name(s->kw), bad);
		eval_fail(E, s->loc, "%s has no triangle", tok_name(s->kw));
	}
}

/* The isosurface's settings, made its own to be written. */
static struct isosurface *iso_w(struct eval *E, struct object *o)
{
	struct isosurface *s = NEW(E, struct isosurface);
	if (o->g.isosurface.iso) {
		*s = *o->g.isosurface.iso;
	} else { /* POV-Ray's defaults */
		s->lo = v3(-1, -1, -1), s->hi = v3(1, 1, 1);
		s->max_gradient = 1.1;
		s->accuracy = 0.001;
	}
	o->g.isosurface.iso = s;
	return s;
}

/* contained_by { box { … } | sphere { … } }, threshold, max_gradient,
 * accuracy; max_trace, all_intersections and evaluate are accepted (the
 * nearest root is always found). */
static void isosurface_keyword(struct eval *E, struct object *o, const struct node *n)
{
	switch (n->op) {
	case TK_CONTAINED_BY: {
		struct isosurface *s = iso_w(E, o);
		if (n->nkids != 1 || !n->kids[0] || n->kids[0]->kind != N_BLOCK ||
		    (n->kids[0]->op != TK_BOX && n->kids[0]->op != TK_SPHERE))
			eval_fail(E, n->loc, "contained_by needs a box { } or a sphere { }");
		struct value v = eval_block(E, n->kids[0]);
		const struct object *c = v.p.obj;
		if (c->xf)
			eval_fail(E, n->kids[0]->loc, "the container cannot be transformed: transform the isosurface");
		s->sphere = c->kind == OBJ_SPHERE;
		if (s->sphere)
			s->c = c->g.sphere.c, s->r = c->g.sphere.r;
		else
			s->lo = c->g.box.lo, s->hi = c->g.box.hi;
		return;
	}
	case TK_THRESHOLD: iso_w(E, o)->threshold = arg_float(E, n); return;
	case TK_MAX_GRADIENT: iso_w(E, o)->max_gradient = arg_positive(E, n); return;
	case TK_ACCURACY: {
		double a = arg_positive(E, n);
		if (a < 1e-6)
			eval_fail(E, n->kids[0]->loc, "accuracy must be at least 1e-6, found %g", a);
		iso_w(E, o)->accuracy = a;
		return;
	}
	case TK_MAX_TRACE: arg_int(E, n, 1, 1000000); return;
	case TK_EVALUATE:
		for (int i = 0; i < n->nkids; i++)
			eval_float(E, n->kids[i]);
		return;
	default: return; /* all_intersections */
	}
}

static void geom_isosurface(struct eval *E, struct sink *s, struct object *o)
{
	want_params(E, s, "a function: isosurface { function { … } contained_by { box { … } } }", 0, 0);
	if (!o->g.isosurface.iso || !o->g.isosurface.iso->fn)
		eval_fail(E, s->loc, "isosurface needs a function: isosurface { function { … } }");
}

/* The geometry builder of each primitive, indexed by enum object_kind. */
typedef void geom_fn(struct eval *E, struct sink *s, struct object *o);
static geom_fn *const geom_of[OBJ_KIND_COUNT] = {
#define PRIM(n, w) [OBJ_##n] = geom_##w,
#include "../tracer/objects.def"
};

/* Turns the collected parameters into the primitive's geometry. */
static void object_geometry(struct eval *E, struct sink *s, struct object *o)
{
	if (geom_of[o->kind]) {
		geom_of[o->kind](E, s, o);
		return;
	}
	if (o->g.csg.n == 0)
		eval_fail(E, s->loc, "%s needs at least one object", tok_name(s->kw));
}

struct value object_block(struct eval *E, const struct node *blk)
{
	struct sink s;
	struct object *o = NULL;
	struct texture scratch; /* the object's own texture while the block runs */
	if (blk->op != TK_OBJECT) {
		o = obj_new(&SC(E)->arena, object_kind_of(blk->op));
		o->loc = blk->loc;
		o->xf = NULL; /* the identity until a transform comes */
	}
	sink_init(&s, SK_OBJECT, blk->op, blk->loc, o);
	s.own_tex = &scratch;
	eval_items(E, blk, &s);
	o = object_target(E, &s, blk->loc);
	unscratch(E, &s);
	if (blk->op != TK_OBJECT) {
		/* geometry is fixed when the block ends; transforms composed already */
		object_geometry(E, &s, o);
	}
	struct value v = {.kind = V_OBJECT};
	v.p.obj = o;
	return v;
}

/* The last extra record propagate made: siblings that had the same one
 * (none, mostly) share its result instead of a copy each. */
struct prop_memo {
	const struct obj_extra *from, *parent_ext, *to;
	const struct interior *in;
};

static void prop(struct eval *E, struct object *o, struct texture *tex, struct interior *in, unsigned flags,
                 const struct obj_extra *pext, struct prop_memo *m)
{
	const unsigned inherit = OF_NO_SHADOW | OF_NO_IMAGE | OF_NO_REFLECTION | OF_DOUBLE_ILLUM;
	if (!o->tex)
		o->tex = tex;
	o->flags |= flags & inherit;
	bool need_in = in && !obj_interior(o);
	bool need_ph = pext && pext->has_photons && !obj_photons(o);
	if (need_in || need_ph) {
		if (m->to && m->from == o->ext && m->in == in && m->parent_ext == pext) {
			o->ext = m->to;
		} else {
			const struct obj_extra *from = o->ext;
			struct obj_extra *x = obj_extra_w(&SC(E)->arena, o);
			if (need_in)
				x->interior = in;
			if (need_ph) {
				x->photons = pext->photons;
				x->has_photons = true;
			}
			*m = (struct prop_memo){from, pext, x, in};
		}
	}
	if (o->kind >= OBJ_FIRST_CSG)
		for (int i = 0; i < o->g.csg.n; i++)
			prop(E, o->g.csg.kids[i], o->tex, obj_interior(o), o->flags, o->ext, m);
}

/* Children without their own texture, interior or photons { } take the
 * parent's; the visibility flags pass down too. */
void propagate(struct eval *E, struct object *o, struct texture *tex)
{
	struct prop_memo m = {0};
	prop(E, o, tex, NULL, 0, NULL, &m);
}
