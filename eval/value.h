/* SPDX-License-Identifier: MIT */
/* value.h: the evaluator's tagged values (after clox's Value and Lua's TValue). */
#ifndef ARVO_VALUE_H
#define ARVO_VALUE_H

#include <stdbool.h>
#include <stdio.h>

#include "../tracer/scene.h"

enum val_kind {
	V_NONE,      /* no value (an unset array element, a macro that yields nothing) */
	V_FLOAT, V_VECTOR, V_COLOUR, V_STRING, V_ARRAY,
	V_OBJECT, V_LIGHT, V_CAMERA, V_TEXTURE, V_PIGMENT, V_FINISH, V_INTERIOR,
	V_MATERIAL, V_TRANSFORM, V_COLOUR_MAP, V_SKIPPED,
	V_FUNCTION,  /* function { … } (tracer/fn.h) */
	V_SKY,       /* a declared sky_sphere { … } */
	V_KIND_COUNT
};

struct value;

struct array {
	int ndims;           /* 1..5 */
	int dims[5];         /* size of each dimension */
	long n;              /* total elements */
	struct value *items; /* row-major; V_NONE until assigned */
};

struct material {
	struct texture *tex;       /* NULL: not given */
	struct interior *interior; /* NULL: not given */
};

struct colour_map {
	struct map_entry *e; /* entries, ascending positions */
	int n;
};

/* A declared sky_sphere: its pigments (bottom first) and transform. */
struct sky_value {
	struct pigment *pig;
	int n;
	const struct xform *xf;
};

struct value {
	enum val_kind kind;
	int n;       /* V_VECTOR: components (2..5); V_STRING: length */
	double v[5]; /* V_FLOAT: v[0]; V_VECTOR: components; V_COLOUR: r g b filter transmit */
	union {
		const char *s;
		struct array *arr;
		struct object *obj;
		struct light *light;
		struct camera *cam;
		struct texture *tex;
		struct pigment *pig;
		struct finish *fin;
		struct interior *in;
		struct material *mat;
		struct xform *xf;
		struct colour_map *cmap;
		struct tnormal *nrm; /* V_SKIPPED (a normal): NULL when ignored */
		struct sky_value *sky;
		const struct fn *fn; /* V_FUNCTION */
	} p;
};

#define IS_FLOAT(x) ((x).kind == V_FLOAT)
#define AS_FLOAT(x) ((x).v[0])

static inline struct value val_float(double f) { return (struct value){.kind = V_FLOAT, .v = {f}}; }
static inline struct value val_none(void) { return (struct value){.kind = V_NONE}; }
struct value val_vector(int n, const double *v);
struct value val_vec3(struct vec3 v);
struct value val_colour(struct colour c);
struct value val_string(const char *s, int len);

/* "a float", "a vector", "a colour", … for messages. */
const char *val_kind_name(enum val_kind k);
const char *val_type_name(const struct value *v);
/* Writes a readable rendering (for #debug of non-strings and dumps). */
void val_print(FILE *out, const struct value *v);
struct colour val_to_colour(const struct value *v);

#endif
