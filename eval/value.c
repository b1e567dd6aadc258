/* SPDX-License-Identifier: MIT */
/* value.c: value constructors, names and printing. */
#include "value.h"

#include <string.h>

struct value val_vector(int n, const double *v)
{
	struct value r = {.kind = V_VECTOR, .n = n};
	memcpy(r.v, v, sizeof(double) * (size_t)n);
	return r;
}

struct value val_vec3(struct vec3 v) { return (struct value){.kind = V_VECTOR, .n = 3, .v = {v.x, v.y, v.z}}; }

struct value val_colour(struct colour c)
{
	return (struct value){.kind = V_COLOUR, .n = 5, .v = {c.r, c.g, c.b, c.f, c.t}};
}

struct value val_string(const char *s, int len)
{
	struct value r = {.kind = V_STRING, .n = len};
	r.p.s = s;
	return r;
}

static const char *const kind_names[V_KIND_COUNT] = {
	"nothing", "a float", "a vector", "a colour", "a string", "an array",
	"an object", "a light", "a camera", "a texture", "a pigment", "a finish",
	"an interior", "a material", "a transform", "a colour map", "a normal",
	"a function", "a sky_sphere",
};

const char *val_kind_name(enum val_kind k) { return kind_names[k]; }
const char *val_type_name(const struct value *v) { return kind_names[v->kind]; }

struct colour val_to_colour(const struct value *v)
{
	return (struct colour){v->v[0], v->v[1], v->v[2], v->v[3], v->v[4]};
}

void val_print(FILE *out, const struct value *v)
{
	switch (v->kind) {
	case V_FLOAT: fprintf(out, "%.6g", v->v[0]); break;
	case V_STRING: fprintf(out, "%.*s", v->n, v->p.s); break;
	case V_VECTOR: case V_COLOUR: {
		int n = v->kind == V_COLOUR ? 5 : v->n;
		fputs(v->kind == V_COLOUR ? "rgbft <" : "<", out);
		for (int i = 0; i < n; i++)
			fprintf(out, "%s%.6g", i ? ", " : "", v->v[i]);
		fputc('>', out);
		break;
	}
	default: fprintf(out, "(%s)", val_type_name(v)); break;
	}
}
