/* SPDX-License-Identifier: MIT */
/* internal.h: the evaluator's state, shared by eval.c, env.c, builtins.c and
 * the block builders (objects.c, geometry.c, textures.c, settings.c). */
#ifndef ARVO_EVAL_INTERNAL_H
#define ARVO_EVAL_INTERNAL_H

#include <setjmp.h>
#include <stdint.h>

#include "../parser/ast.h"
#include "eval.h"
#include "value.h"

#define MAX_INCLUDE_DEPTH 64  /* nested #include */
#define MAX_MACRO_DEPTH 200   /* nested macro calls */
#define MAX_STRING 1048576    /* bytes in a string value */
#define MAX_ARRAY 16777216L   /* elements in an array */
#define MAX_SCOPES 512        /* scope stack */
#define MAX_EVAL_DEPTH 2000   /* evaluator recursion: item lists and expressions */
#define TEX_SEEN 1024         /* textures texture_share remembers */
#define EXT_SEEN 8            /* texture records tex_ext_set remembers */

struct scope;
struct entry;
struct inc_cache;
struct builtin;

/* What a block's items are being evaluated into. */
enum sink_kind {
	SK_SCENE, SK_OBJECT, SK_TEXTURE, SK_PIGMENT, SK_FINISH, SK_INTERIOR,
	SK_MATERIAL, SK_CAMERA, SK_LIGHT, SK_TRANSFORM, SK_COLOUR_MAP, SK_ENTRY,
	SK_GLOBAL, SK_PHOTONS, SK_ILLUM, SK_ILLUM_MAP, SK_REFLECTION, SK_IMAGE_MAP,
	SK_BACKGROUND, SK_DEFAULT, SK_SKY, SK_NORMAL, SK_FOG, SK_VALUE, SK_WARP,
	SK_LIST      /* a mesh2 list: vertex_vectors { n, <…>, … } and the like */
};

#define SINK_MAX_PARAMS 8

/* sink_init zeroes the members up to params; the arrays after it are read
 * only as far as they were written (nparams, nresults, pending). */
struct sink {
	enum sink_kind kind;
	enum tok kw;               /* the block's keyword (TK_SPHERE, TK_PIGMENT…) */
	struct srcloc loc;         /* where the block starts */
	void *target;              /* what is being built (struct object *, …) */
	int nparams;
	struct outline_build *ob;  /* SK_OBJECT: text/prism/polygon/lathe/sor's lists (outlines.c) */
	int modified;              /* a modifier was applied (params must come first) */
	unsigned pending;          /* SK_CAMERA: look_at/angle/transforms to apply at the end */
	struct texture *own_tex;   /* SK_OBJECT: object_block's scratch texture, which the
	                            * object's pigment, finish … are written into
	                            * (texture_share makes it a scene texture at the end) */
	struct object *own_obj;    /* the object whose texture the scratch is (NULL: none) */
	int nresults;              /* SK_VALUE: how many values were produced */
	struct value params[SINK_MAX_PARAMS]; /* positional values so far */
	struct srcloc ploc[SINK_MAX_PARAMS];  /* and where each came from */
	struct xform pending_xf;   /* SK_CAMERA: the transforms, in order */
	struct value result;       /* SK_VALUE: the value produced */
};

struct eval {
	struct diag *diag;
	const struct eval_options *opt;
	bool warned_crand;         /* finish { crand } warned about once */
	struct arena arena;        /* ASTs, strings, arrays: lives until eval ends */
	struct scene *scene;       /* what is being built (its arena holds the model) */
	struct scope *scopes[MAX_SCOPES]; /* dynamic scope stack; [0] is global */
	int nscopes;
	int include_depth;
	int macro_depth;
	int depth;                 /* evaluator recursion (eval_items, eval_expr) */
	uintptr_t stack_floor;     /* the lowest stack address enter() allows: 3/4 of the
	                            * stack limit (of 64 MiB at most) below a local of eval_scene */
	long calls;                /* macro calls so far */
	long steps;                /* item lists and expressions evaluated so far */
	long max_steps;            /* opt->max_steps, beside steps (enter() reads both) */
	long objects;              /* objects and lights made so far */
	struct srcloc stmt;        /* the item being evaluated (out-of-memory errors) */
	int out_of_memory;         /* the budget ran out: exit status 70 */
	struct scope *spare_scopes; /* released scopes, for reuse */
	unsigned long env_gen;     /* changes of the scopes so far (from 1): node memos (env.c) */
	struct entry *spare_entries;
	long iterations;           /* loop iterations so far */
	int breaking;              /* a #break is unwinding to its #switch */
	jmp_buf *fail;             /* where a fatal error jumps */
	uint64_t *rng;             /* seed() streams */
	int nrng;
	const char *dir_stack[MAX_INCLUDE_DEPTH + 2]; /* directory of each open file */
	struct texture default_tex; /* #default */
	struct texture *default_shared; /* scene copy of default_tex (NULL after #default) */
	const struct finish *last_finish; /* the last finish { } made, shared when the next is the same */
	int warned_normal;         /* 'normal' ignored warning given */
	struct pattern **pats;     /* every pattern made writable (noise_generator patched at the end) */
	double default_bump;       /* #default { normal { bump_size } } (0: POV-Ray's 0.5) */
	int in_default;            /* evaluating #default { }'s items */
	int npats, cappats;
	int warned_fog_turb;       /* 'turbulence' in fog ignored warning given */
	int warned_mesh_tex;       /* per-triangle mesh textures ignored warning given */
	struct inc_cache *includes; /* files already parsed, by real path */
	const struct texture *tex_seen[TEX_SEEN]; /* texture_share's recent textures, by hash */
	uint64_t tex_hash[TEX_SEEN]; /* and their hashes */
	const struct tex_ext *ext_seen[EXT_SEEN]; /* tex_ext_set's recent records */
	int ext_next;              /* the slot the next new record takes */
	int missing;               /* a file the scene names is missing or unreadable (exit 66) */
};

/* Reports an error at loc and unwinds to eval_scene. */
_Noreturn void eval_fail(struct eval *E, struct srcloc loc, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* ---- eval.c ---- */
struct value eval_expr(struct eval *E, const struct node *n);
double eval_float(struct eval *E, const struct node *n);
struct vec3 eval_vec3(struct eval *E, const struct node *n);
struct colour eval_colour(struct eval *E, const struct node *n);
const char *eval_string(struct eval *E, const struct node *n, int *len);
/* Converts a value, or fails naming what was expected at loc. */
double val_want_float(struct eval *E, const struct value *v, struct srcloc loc);
struct vec3 val_want_vec3(struct eval *E, const struct value *v, struct srcloc loc);
struct colour val_want_colour(struct eval *E, const struct value *v, struct srcloc loc);
/* Evaluates a list of items into a sink. */
void eval_items(struct eval *E, const struct node *list, struct sink *s);
void eval_item(struct eval *E, const struct node *item, struct sink *s);
char *eval_strdup(struct eval *E, const char *s, int len);
/* ---- paths.c ---- */
/* Finds a file a scene names, only in the directories a scene may read. */
char *eval_find_file(struct eval *E, const char *name, struct srcloc loc, const char *what, const char **found_dir);
/* The same, but NULL (and no error) when it is not found or not allowed. */
char *eval_try_file(struct eval *E, const char *name, struct srcloc loc);

/* Counts one object or light made at loc against --max-objects. */
void eval_count_object(struct eval *E, struct srcloc loc);

/* ---- env.c ---- */
struct scope *scope_new(struct eval *E);
void scope_push(struct eval *E, struct scope *sc, struct srcloc loc);
void scope_pop(struct eval *E);
/* Recycles a popped scope nothing refers to any more (macro and include scopes). */
void scope_release(struct eval *E, struct scope *sc);
/* Finds a name, innermost scope first; NULL when undeclared. */
struct value *env_lookup(struct eval *E, const char *name);
const struct node *env_macro(struct eval *E, const char *name);
/* #declare (global unless the name is local somewhere on the stack) and #local. */
struct value *env_declare(struct eval *E, const char *name, bool local);
void env_define_macro(struct eval *E, const char *name, const struct node *def);
/* The same through a node's memo (N_IDENT, N_DECLARE): looked up again only
 * when the scopes changed since (the memo is checked here, inline: a loop's
 * names are read on every pass; env.c looks them up). */
struct value *env_lookup_again(struct eval *E, const struct node *n);
struct value *env_declare_again(struct eval *E, const struct node *n, bool local);
static inline struct value *env_lookup_node(struct eval *E, const struct node *n)
{
	return n->memo_gen == E->env_gen ? n->memo : env_lookup_again(E, n);
}
static inline struct value *env_declare_node(struct eval *E, const struct node *n, bool local)
{
	return n->memo_gen == E->env_gen ? n->memo : env_declare_again(E, n, local);
}
/* N_DECLARE n declared its name already, and the scopes are as they were. */
static inline bool env_declared_before(struct eval *E, const struct node *n)
{
	return n->memo && n->memo_gen == E->env_gen;
}
/* N_CALL n's macro (NULL: none), and else in *var its variable (NULL: none). */
const struct node *env_call_lookup(struct eval *E, const struct node *n, struct value **var);
/* N_CALL n's built-in function (NULL: none): looked up once per node, since
 * built-in names never change. */
const struct builtin *env_call_builtin(struct eval *E, const struct node *n);
/* builtin_float_fn of N_CALL n's built-in, when the name is not a macro or a
 * declared function now; else NULL. */
double (*env_call_float_fn(struct eval *E, const struct node *n))(double);
bool env_undef(struct eval *E, const char *name);

/* ---- builtins.c ---- */
/* A built-in constant (pi, x, clock…); false when name is not one. */
bool builtin_constant(struct eval *E, const char *name, struct value *out);
/* Calls built-in function `name`; false when there is no such function. */
bool builtin_call(struct eval *E, const struct node *call, struct value *out);
bool builtin_is_name(const char *name);
/* The built-in function named name; NULL when there is none. */
const struct builtin *builtin_find(const char *name);
/* b's plain function of one float when b is one (sin, exp …: a float
 * argument, a float result, no check of its own), else NULL. */
double (*builtin_float_fn(const struct builtin *b))(double);

/* ---- function.c: function { } ---- */
/* Compiles a function { } node into a V_FUNCTION value. */
struct value function_value(struct eval *E, const struct node *n);
/* F(args) in an expression: a float, or a pigment function's colour. */
struct value function_call(struct eval *E, const struct node *call, const struct fn *f);
/* The function of v (V_FUNCTION), or a failure at loc when it cannot be used. */
const struct fn *function_usable(struct eval *E, const struct value *v, struct srcloc loc);

/* ---- objects.c: dispatch, and the helpers the builders share ---- */
void sink_init(struct sink *s, enum sink_kind kind, enum tok kw, struct srcloc loc, void *target);
/* "<keyword> is not valid <where s is>" at n. */
_Noreturn void misplaced(struct eval *E, const struct sink *s, const struct node *n);
/* The single argument of a keyword item like `translate <1,0,0>`, converted. */
struct value arg1(struct eval *E, const struct node *n);
double arg_float(struct eval *E, const struct node *n);
struct vec3 arg_vec3(struct eval *E, const struct node *n);
struct colour arg_colour(struct eval *E, const struct node *n);
bool arg_bool(struct eval *E, const struct node *n);     /* `kw`, `kw on`, `kw off` */
double arg_positive(struct eval *E, const struct node *n);
int arg_int(struct eval *E, const struct node *n, int lo, int hi);
/* translate/rotate/scale/matrix/transform item n into *out; false otherwise. */
bool transform_of(struct eval *E, const struct node *n, struct xform *out);
/* Moves a texture's pigment and normal by X (the normal is copied). */
void texture_transform(struct eval *E, struct texture *t, const struct xform *X);
/* A fresh scene copy of t (NULL: the #default texture). */
struct texture *texture_copy(struct eval *E, const struct texture *t);
/* A scene texture equal to *t: one made before when it is among the recent
 * ones (at most TEX_SEEN, by content), else a fresh copy. */
struct texture *texture_share(struct eval *E, const struct texture *t);
/* Gives t the record *x (its normal, map, layer and location): one of the
 * EXT_SEEN recent records when equal, so that the textures a loop writes at
 * one place share one; else a fresh scene copy; NULL when x is
 * tex_ext_none. Records are never written through. */
void tex_ext_set(struct eval *E, struct texture *t, const struct tex_ext *x);
/* One part of t's record changed, by tex_ext_set. */
void tex_set_loc(struct eval *E, struct texture *t, struct srcloc loc);
void tex_set_finish(struct eval *E, struct texture *t, const struct finish *f);
void tex_set_normal(struct eval *E, struct texture *t, const struct tnormal *n);
void tex_set_below(struct eval *E, struct texture *t, const struct texture *below);
void tex_set_map(struct eval *E, struct texture *t, const struct tex_entry *map, int nmap);
/* Evaluates a block's items into a fresh sink of the given kind. */
void run_block(struct eval *E, const struct node *blk, enum sink_kind kind, void *target, struct sink *out);
/* A transform old (NULL: identity) followed by X, in a slot of its own, since
 * copied objects and textures may share old; NULL when it is the identity. */
const struct xform *xform_then(struct eval *E, const struct xform *old, const struct xform *X);
/* A finish { } block n on a texture's finish f: the changed finish, a copy,
 * since textures share finishes (the default one, a declared texture's). */
const struct finish *finish_block(struct eval *E, const struct node *n, const struct finish *f);
/* p's pattern settings, made its own to be written (pigments share them). */
struct pattern *pat_w(struct eval *E, struct pigment *p);
/* A fresh texture: top (and the layers under it) layered over bottom. */
struct texture *texture_layered(struct eval *E, const struct texture *bottom, const struct texture *top);

#define SC(E) ((E)->scene)
#define NEW(E, type) ARENA_NEW(&SC(E)->arena, type)

/* ---- geometry.c: objects ---- */
/* Moves object o (its texture and children too) by X. */
void object_transform(struct eval *E, struct object *o, const struct xform *X);
/* The same, moving texture own in place when o has it (a block's scratch). */
void object_transform_own(struct eval *E, struct object *o, const struct xform *X, const struct texture *own);
bool is_object_kw(enum tok kw); /* sphere … merge, object */
void object_keyword(struct eval *E, struct sink *s, const struct node *n);
void object_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc);
/* A vector of more than 5 components in an object that takes one (poly's
 * coefficients): stored in the sink; false when n is not one. */
bool object_long_vector(struct eval *E, struct sink *s, const struct node *n);
/* The items of a mesh2 list (SK_LIST). */
void list_keyword(struct eval *E, struct sink *s, const struct node *n);
void list_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc);
struct value object_block(struct eval *E, const struct node *blk);
/* Children without their own texture, interior or photons { } take the
 * parent's; the visibility flags pass down too. */
void propagate(struct eval *E, struct object *o, struct texture *tex);

/* ---- outlines.c, font.c: text, prism, polygon, lathe, sor ---- */
/* Whether objects of kind k are built by outlines.c (checked before its
 * calls, which every other object's items would pay for). */
static inline bool is_outline_kind(enum object_kind k)
{
	return k == OBJ_TEXT || k == OBJ_PRISM || k == OBJ_POLYGON || k == OBJ_LATHE || k == OBJ_SOR;
}
/* Takes a positional value or a leading keyword (linear_spline, conic_sweep,
 * ttf …) of those primitives; false when o is not one of them or n is not
 * such a keyword. */
bool outline_value(struct eval *E, struct sink *s, struct object *o, const struct value *v, struct srcloc loc);
bool outline_keyword(struct eval *E, struct sink *s, struct object *o, const struct node *n);
void geom_text(struct eval *E, struct sink *s, struct object *o);
void geom_prism(struct eval *E, struct sink *s, struct object *o);
void geom_polygon(struct eval *E, struct sink *s, struct object *o);
void geom_lathe(struct eval *E, struct sink *s, struct object *o);
void geom_sor(struct eval *E, struct sink *s, struct object *o);
/* The glyph outlines of text in the TrueType font at path (font.c). */
struct extrusion *font_text(struct eval *E, const char *path, const char *name, struct srcloc floc,
                            const char *text, int len, struct srcloc tloc, double thickness,
                            struct vec3 offset);

/* ---- textures.c: pigments, colour maps, finishes, interiors, textures ---- */
struct colour_map *colour_map_block(struct eval *E, const struct node *blk);
void colour_map_entry(struct eval *E, struct colour_map *m, const struct node *n); /* [pos colour] */
/* Resolves an image file like an include: only allowed directories. */
void image_set(struct eval *E, struct pattern *p, struct srcloc loc, const char *name);
void image_map_keyword(struct eval *E, struct sink *s, const struct node *n);
void pigment_keyword(struct eval *E, struct sink *s, const struct node *n);
void pigment_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc);
/* p becomes the pattern of the function v (pigment and normal). */
void function_pattern(struct eval *E, struct pigment *p, const struct value *v, struct srcloc loc);
void reflection_keyword(struct eval *E, struct sink *s, const struct node *n);
void finish_keyword(struct eval *E, struct sink *s, const struct node *n);
void interior_keyword(struct eval *E, struct sink *s, const struct node *n);
void texture_keyword(struct eval *E, struct sink *s, const struct node *n);
/* Puts texture top (and the layers under it) on top of t, as a layer. */
void texture_layer(struct eval *E, struct texture *t, const struct texture *top);
/* normal { }: a fresh perturbation, or NULL when it uses what arvo lacks
 * (warned once: the scene renders with the plain normal). */
struct tnormal *normal_block(struct eval *E, const struct node *blk);
void normal_keyword(struct eval *E, struct sink *s, const struct node *n);
void normal_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc);

/* ---- patterns.c: noise patterns, turbulence, warps, pigment maps ---- */
/* A pattern keyword of pigment s->target (bozo, turbulence, warp,
 * pigment_map …); false when n is not one. */
bool pattern_keyword(struct eval *E, struct sink *s, const struct node *n);
void warp_keyword(struct eval *E, struct sink *s, const struct node *n);
/* A pigment given in place of a colour of checker, hexagon or brick. */
void pattern_sub_pigment(struct eval *E, struct sink *s, const struct pigment *sub, struct srcloc loc);
/* texture_map { } of texture t (its pigment holds the pattern), and
 * normal_map { } of normal t. */
void texture_map_block(struct eval *E, struct texture *t, const struct node *n);
void normal_map_block(struct eval *E, struct tnormal *t, const struct node *n);
/* tiles { textures tile2 textures } of texture t: a checker of the two. */
void tiles_block(struct eval *E, struct texture *t, const struct node *n);
/* A keyword that shapes a pattern (checker, bozo, turbulence, warp …). */
bool is_pattern_kw(enum tok k);
/* Patterns without their own noise_generator take global_settings', and
 * every pattern its number_of_waves. */
void patterns_finish(struct eval *E);

/* ---- settings.c: lights, camera, global settings ---- */
void photons_keyword(struct eval *E, struct sink *s, const struct node *n); /* object, light or global */
void light_keyword(struct eval *E, struct sink *s, const struct node *n);
void light_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc);
/* Applies angle, look_at and the transforms once the camera block ended. */
void camera_finish(struct eval *E, struct sink *s, struct camera *c);
void camera_keyword(struct eval *E, struct sink *s, const struct node *n);
void global_keyword(struct eval *E, struct sink *s, const struct node *n);
void illum_keyword(struct eval *E, struct sink *s, const struct node *n);
void illum_map_keyword(struct eval *E, struct sink *s, const struct node *n);
void sky_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc);
void sky_keyword(struct eval *E, struct sink *s, const struct node *n); /* sky_sphere { } */
void fog_keyword(struct eval *E, struct sink *s, const struct node *n);
void fog_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc);

/* ---- objects.c: entry points ---- */
/* A keyword item (N_BLOCK, N_MOD, N_WORD, N_SKIPPED, N_ENTRY) in a sink. */
void sink_keyword(struct eval *E, struct sink *s, const struct node *item);
/* An expression's value in a sink. */
void sink_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc);
/* Evaluates a value-producing block (sphere {…}, texture {…}, …). */
struct value eval_block(struct eval *E, const struct node *blk);
/* Finishes the scene after the last item (camera defaults, propagation). */
void objects_finish(struct eval *E);

#endif
