/* SPDX-License-Identifier: MIT */
/* scene.h: the scene model the evaluator builds and the tracer renders.
 *
 * Everything here lives in the scene's arena (scene->arena) until scene_free.
 * Geometry is stored in each primitive's own frame, as the user wrote it; the
 * object's xform maps that frame to the world. Units and colours follow
 * docs/design.md §3: scene-linear Rec.709, point-light colour = intensity in W/sr. */
#ifndef ARVO_SCENE_H
#define ARVO_SCENE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "../common/arena.h"
#include "../common/srcloc.h"
#include "../common/vec.h"
#include "../common/xform.h"

/* ---- materials ---------------------------------------------------------- */

enum pigment_kind {
	PIG_SOLID, PIG_CHECKER, PIG_GRADIENT, PIG_IMAGE,
	PIG_PATTERN,  /* a continuous pattern (enum pattern_kind) through the colour_map */
	PIG_HEXAGON,  /* three colours on hexagons in the x-z plane */
	PIG_BRICK,    /* mortar colour, brick colour */
};

/* POV-Ray's continuous patterns (tracer/pattern.c). */
enum pattern_kind {
	PAT_RADIAL, PAT_ONION, PAT_SPHERICAL, PAT_CYLINDRICAL, PAT_BOXED, PAT_PLANAR,
	PAT_LEOPARD,
	/* the noise patterns (tracer/noise.h) and their kin */
	PAT_BOZO, PAT_SPOTTED, PAT_BUMPS, PAT_DENTS, PAT_GRANITE, PAT_MARBLE, PAT_WOOD,
	PAT_AGATE, PAT_WRINKLES, PAT_RIPPLES, PAT_WAVES, PAT_CRACKLE, PAT_QUILTED,
	PAT_SPIRAL1, PAT_SPIRAL2, PAT_CELLS, PAT_MANDEL,
	PAT_PIGMENT,  /* pigment_pattern: the grey of a pigment */
	PAT_AVERAGE,  /* average: the weighted mean of the map's entries */
	PAT_FUNCTION, /* function { … }: a user-defined function (tracer/fn.h) */
	PAT_KIND_COUNT
};

/* A warp { } or a pattern's own turbulence, in the order they act. */
enum warp_kind { WARP_TURB, WARP_REPEAT, WARP_BLACK_HOLE, WARP_XF };

struct warp {
	enum warp_kind kind;
	bool classic;             /* WARP_TURB: the pattern's own turbulence keyword */
	struct vec3 turb;         /* WARP_TURB: displacement per axis */
	int octaves;              /* WARP_TURB: default 6 */
	double omega, lambda;     /* WARP_TURB: defaults 0.5, 2 */
	int axis;                 /* WARP_REPEAT: 0 x, 1 y, 2 z */
	double width;             /* WARP_REPEAT: the repeat distance */
	struct vec3 offset, flip; /* WARP_REPEAT: per repeat; flip factors (1 or -1) */
	struct vec3 center;       /* WARP_BLACK_HOLE */
	double radius, strength, falloff; /* WARP_BLACK_HOLE: falloff default 2 */
	bool inverse;             /* WARP_BLACK_HOLE: pushes instead of pulling */
	const struct xform *xf;   /* WARP_XF: a transform written before later warps */
};

struct pigment;

/* One entry of a pigment_map (or average): the pigment at position pos. */
struct pig_entry {
	double pos;                  /* position in the pattern (weight for average) */
	const struct pigment *pig;   /* the pigment there */
};

/* The wave a pattern's value goes through before the colour_map. */
enum wave_kind { WAVE_RAMP, WAVE_TRIANGLE, WAVE_SINE, WAVE_SCALLOP, WAVE_CUBIC, WAVE_POLY };

/* One entry of a colour_map: the colour at position pos in [0,1]. */
struct map_entry {
	double pos;       /* position in the pattern, ascending */
	struct colour c;  /* colour there */
};

/* What a pigment other than a plain colour needs: kept apart and shared, so
 * that a scene of many coloured objects stores only their colours. */
struct pattern {
	struct vec3 axis;         /* gradient direction */
	enum pattern_kind pattern; /* PIG_PATTERN: which */
	enum wave_kind wave;      /* gradient, PIG_PATTERN: ramp_wave (default) … */
	double frequency, phase;  /* POV frequency (default 1) and phase (0) */
	double exponent;          /* poly_wave exponent (default 1) */
	struct vec3 brick_size;   /* brick: default <8, 3, 4.5> */
	double mortar;            /* brick: default 0.5 */
	struct map_entry *map;    /* gradient colour_map (NULL: black→white) */
	int nmap;                 /* entries in map */
	const char *image;        /* image_map file, resolved path */
	const char *image_name;   /* image_map file as the scene named it (for messages) */
	struct srcloc image_loc;  /* where the scene named it */
	int interpolate;          /* image_map interpolate (0 none, 2 bilinear) */
	bool once;                /* image_map once */
	struct colour more[2];    /* checker's and brick's second colour, hexagon's second and third */
	int noise_gen;            /* noise_generator 1-3 (0: global_settings') */
	const struct warp *warps; /* turbulence and warp { }, in the order they act */
	int nwarps;
	double agate_turb;        /* agate: default 1 */
	double metric, offset;    /* crackle: defaults 2, 0 */
	struct vec3 form;         /* crackle: default <-1, 1, 0> */
	bool solid;               /* crackle solid */
	double control0, control1; /* quilted: defaults 1, 1 */
	int arms;                 /* spiral1, spiral2: number of arms; mandel: iterations */
	int exponent_i;           /* mandel: exponent 2 (default), 3 or 4 */
	int nwaves;               /* ripples, waves: global_settings' number_of_waves (0: 10) */
	const struct pigment *sub; /* pigment_pattern's pigment */
	const struct pig_entry *pmap; /* pigment_map (or the block patterns' pigments) */
	int npmap;
	const struct fn *fn;      /* PAT_FUNCTION: the function of x, y, z */
};

struct pigment {
	enum pigment_kind kind;   /* which pattern */
	struct colour c[1];       /* solid colour; the first of checker's, brick's, hexagon's */
	const struct pattern *pat; /* NULL: the defaults (pig_pattern) */
	const struct xform *xf;   /* pattern space → world; NULL: identity */
};

/* The pattern settings of p (the defaults when it has none of its own). */
const struct pattern *pig_pattern(const struct pigment *p);
/* Colour k of a checker, brick or hexagon (0: c[0], then the pattern's). */
struct colour pig_colour(const struct pigment *p, int k);

struct finish {
	struct colour ambient; /* ambient colour (rgb) */
	double diffuse;        /* diffuse weight (POV default 0.6) */
	double brilliance;     /* POV brilliance (default 1) */
	double specular;       /* Blinn specular amount */
	double roughness;      /* specular roughness (default 0.05) */
	double phong;          /* Phong amount */
	double phong_size;     /* Phong exponent (default 40) */
	struct colour refl_min; /* reflection at normal incidence (or constant) */
	struct colour refl_max; /* reflection at grazing (variable reflection) */
	double refl_falloff;   /* reflection falloff exponent (default 1) */
	bool refl_fresnel;     /* reflection { … fresnel on } */
	bool refl_metallic;    /* reflection { … metallic } */
	bool conserve_energy;  /* conserve_energy */
	struct colour emission; /* emission colour */
};

struct interior {
	double ior;                /* index of refraction (default 1) */
	double dispersion;         /* violet/red index ratio (default 1: none) */
	int dispersion_samples;    /* POV dispersion_samples (default 7) */
	double fade_distance;      /* absorption distance (0: none) */
	double fade_power;         /* absorption exponent (default 2 when set) */
	struct colour fade_color;  /* colour at fade_distance */
	double caustics;           /* POV's fake caustics value (parsed, unused) */
};

/* normal { pattern [amount] … }: POV-Ray's perturbation of the shading
 * normal by the slope of a pattern (tracer/pattern.h). */
struct tnormal;

/* One entry of a normal_map: the normal at position pos. */
struct nrm_entry {
	double pos;               /* position in the pattern, ascending */
	const struct tnormal *n;  /* the normal there */
};

struct tnormal {
	struct pigment pat; /* the pattern, its wave and its transform */
	double amount;      /* bump size (POV default 0.5) */
	const struct nrm_entry *map; /* normal_map (NULL: none) */
	int nmap;
};

struct texture;

/* One entry of a texture_map: the texture at position pos. */
struct tex_entry {
	double pos;                 /* position in the pattern, ascending */
	const struct texture *tex;  /* the texture there */
};

/* A texture's parts beside its pigment, in a record of their own so that
 * the common texture (a pigment of its own) stays small: shared by every
 * texture that has the same, never written through (a change makes a new
 * record; docs/design.md §1, "A lean scene model"). */
struct tex_ext {
	const struct finish *finish;  /* shared: never NULL, never written through */
	const struct tnormal *normal; /* NULL: none */
	const struct tex_entry *map;  /* texture_map: blended by the pattern (NULL: none) */
	const struct texture *below;  /* layered textures: the layer under this one (NULL: none) */
	struct srcloc loc;            /* where the texture was written */
	int nmap;                     /* entries in map (beside loc: no padding) */
};

struct texture {
	struct pigment pigment;       /* the colour; with a texture_map, the pattern */
	const struct tex_ext *ext;    /* shared: never written through; NULL: tex_ext_none */
};

/* The record of a texture with the default finish, no normal, map or
 * layer and no location. */
extern const struct tex_ext tex_ext_none;

/* The parts of t kept in its record (tex_ext_none when it has none). */
static inline const struct tex_ext *tex_x(const struct texture *t)
{
	return t->ext ? t->ext : &tex_ext_none;
}
static inline const struct finish *tex_finish(const struct texture *t) { return tex_x(t)->finish; }
static inline const struct tnormal *tex_normal(const struct texture *t) { return tex_x(t)->normal; }
static inline const struct tex_entry *tex_map(const struct texture *t) { return tex_x(t)->map; }
static inline int tex_nmap(const struct texture *t) { return tex_x(t)->nmap; }
static inline const struct texture *tex_below(const struct texture *t) { return tex_x(t)->below; }
static inline struct srcloc tex_loc(const struct texture *t) { return tex_x(t)->loc; }

/* ---- objects ------------------------------------------------------------ */

struct extrusion;
struct flat_outline;
struct revolution;
struct sor_shape;

/* The kinds, from objects.def: every primitive, then every CSG kind. */
enum object_kind {
#define PRIM(n, w) OBJ_##n,
#define CSG(n, w) OBJ_##n,
#define NODE(n, w) OBJ_##n,
#include "objects.def"
	OBJ_KIND_COUNT,
	OBJ_FIRST_CSG = OBJ_UNION
};

enum object_flags {
	OF_NO_SHADOW = 1u << 0,     /* casts no shadow */
	OF_NO_IMAGE = 1u << 1,      /* invisible to camera rays */
	OF_NO_REFLECTION = 1u << 2, /* invisible in reflections */
	OF_HOLLOW = 1u << 3,        /* hollow (POV) */
	OF_INVERSE = 1u << 4,       /* inside and outside swapped (CSG) */
	OF_OPEN = 1u << 5,          /* cylinder/cone without caps */
	OF_STURM = 1u << 6,         /* torus: sturm requested */
	OF_DOUBLE_ILLUM = 1u << 7,  /* double_illuminate */
};

/* Illumination map request for a surface (issue: the light pass). */
struct illum_spec {
	int resolution; /* R×R map points over the (u,v) square; 0 = not given */
	double cell;    /* map points this far apart in world units; 0 = not given */
};

/* POV-Ray photons { } on an object, kept for the light pass. */
struct photon_spec {
	double spacing;    /* spacing multiplier (default 1) */
	bool target;       /* target [spacing multiplier] */
	bool refraction;   /* refraction on|off */
	bool reflection;   /* reflection on|off */
	bool collect;      /* collect on|off (default on) */
	bool pass_through; /* pass_through */
};

/* A polynomial surface F(x,y,z) = Σ a·xⁱyʲzᵏ = 0 (poly, quartic, cubic,
 * quadric), inside where F < 0; only its non-zero terms. */
struct poly_term {
	double a;      /* coefficient */
	int e[3];      /* exponents of x, y, z */
};
struct polynomial {
	int order;     /* total degree, 2..7 */
	int nterms;
	struct poly_term *t;
};

/* A blob: components adding s·(1 − d²/r²)² within r of a centre (sphere) or
 * a segment (cylinder), the surface where the sum is threshold. */
struct blob_comp {
	bool cylinder;            /* else a sphere */
	struct vec3 a, b;         /* centre; or the segment's ends */
	double r, s;              /* radius, strength (may be negative) */
	const struct xform *xf;   /* component frame → blob frame; NULL: identity */
};
struct blob {
	double threshold;
	int n;
	struct blob_comp *c;
	struct vec3 centre;       /* of the components' bounds: the (u,v) centre */
};

/* A triangle mesh (mesh, mesh2, smooth_triangle): triangles index the
 * vertex and normal arrays; a bounding volume hierarchy over them is built
 * by mesh_finish (tracer/shape.h). */
struct mesh_tri {
	int v[3];                 /* vertex indices */
	int n[3];                 /* normal indices, or -1 (flat) */
};
struct mesh_node {
	struct bbox b;
	int first, count;         /* leaf: triangles order[first … first+count−1]; count 0: inner,
	                           * children at first and first+1 */
};
struct mesh {
	int nv, nn, nt;
	struct vec3 *vert, *norm;
	struct mesh_tri *tri;
	struct mesh_node *node;   /* node[0] is the root */
	int nnode;
	int *order;               /* triangle indices in leaf order */
	int side;                 /* the (u,v) atlas is side × side cells */
	bool has_inside;          /* inside_vector given: the mesh is a solid */
	struct vec3 inside_dir;   /* inside_vector */
	bool clipped;             /* height_field water_level: no surface below clip_y */
	double clip_y;
	int hf_w, hf_h;           /* height_field: the grid (0: not one) */
	bool hf_smooth;           /* height_field smooth: vertex normals at the end */
};

/* isosurface { function { … } contained_by { box | sphere } … }: the
 * surface f = threshold inside the container; inside is f < threshold
 * (tracer/shapes/isosurface.c). Kept apart: objects stay small. */
struct isosurface {
	const struct fn *fn;       /* f(x, y, z) in the object frame */
	bool sphere;               /* container: sphere (c, r) or box (lo, hi) */
	struct vec3 lo, hi, c;
	double r;
	double threshold;          /* default 0 */
	double max_gradient;       /* Lipschitz bound of f (default 1.1) */
	double accuracy;           /* root tolerance, object units (default 0.001) */
};

/* An object is allocated only as far as its kind's member of the geometry
 * union reaches (obj_size), so the union comes last: a sphere takes 104
 * bytes, not the 144 of the largest member. Copy one with obj_copy, never
 * by assignment. */
/* What few objects set, kept out of struct object (a million spheres carry
 * none): behind one pointer, shared by an object's copies and never written
 * once set (obj_extra_w makes a fresh copy to write). */
struct obj_extra {
	struct interior *interior;   /* NULL: inherit from parent, else default */
	struct illum_spec illum;     /* illum_map { } */
	struct photon_spec photons;  /* photons { } */
	bool has_photons;            /* a photons { } block was given */
};

struct object {
	/* what shading and the light pass read */
	struct texture *tex;         /* NULL: inherit from parent, else default */
	const struct obj_extra *ext; /* NULL: no interior, illum_map or photons */
	struct srcloc loc;           /* where the object was written */
	/* what a ray's candidate test reads, together just before the
	 * geometry: one or two cache lines for a sphere, not two or three */
	uint8_t kind;                /* enum object_kind */
	uint16_t flags;              /* enum object_flags */
	const struct xform *xf;      /* object frame → world; NULL: identity (obj_xf) */
	union {
		struct { struct vec3 c; double r; } sphere;
		struct { struct vec3 n; double d; } plane;        /* n·p = d */
		struct { struct vec3 lo, hi; } box;
		struct { struct vec3 c, n; double r, hole; } disc; /* hole: inner radius */
		struct { struct vec3 a, b; double r; } cylinder;   /* OF_OPEN: no caps */
		struct { struct vec3 a, b; double ra, rb; } cone;  /* radius ra at a, rb at b */
		struct { double major, minor; } torus;             /* about y, centred at origin */
		struct { struct vec3 p[3]; } triangle;
		struct { const struct polynomial *p; const double *list; int nlist; struct srcloc list_loc; } poly;
		/* list…: the coefficient vector while the evaluator builds p */
		struct { double e, n; } superellipsoid;            /* east-west, north-south exponents */
		struct { const struct blob *b; } blob;
		struct { const struct mesh *m; } mesh;
		struct { const struct extrusion *e; } prism, text; /* tracer/shapes/outline.h */
		struct { const struct flat_outline *f; } polygon;
		struct { const struct revolution *r; } lathe;
		struct { const struct sor_shape *s; } sor;
		struct { const struct isosurface *iso; } isosurface; /* OF_OPEN: no container walls */
		struct { struct object **kids; int n; } csg;       /* CSG children */
	} g;                         /* last: see obj_size */
};

/* The bytes an object of kind k takes: up to the end of its geometry. */
size_t obj_size(enum object_kind k);
/* A zeroed object of kind k in arena a (kind set), and a copy of o there. */
struct object *obj_new(struct arena *a, enum object_kind k);
struct object *obj_copy(struct arena *a, const struct object *o);

/* The object's own interior (NULL: none given), photons { } (NULL: none)
 * and illum_map { } (zero: none). */
static inline struct interior *obj_interior(const struct object *o)
{
	return o->ext ? o->ext->interior : NULL;
}
static inline const struct photon_spec *obj_photons(const struct object *o)
{
	return o->ext && o->ext->has_photons ? &o->ext->photons : NULL;
}
static inline struct illum_spec obj_illum(const struct object *o)
{
	return o->ext ? o->ext->illum : (struct illum_spec){0, 0};
}
/* A fresh copy of o's extra record (zero when it has none), made o's, to
 * write: records already set may be shared with o's copies. */
struct obj_extra *obj_extra_w(struct arena *a, struct object *o);

/* The object's frame → world transform (the identity when it has none). */
static inline const struct xform *obj_xf(const struct object *o)
{
	return o->xf ? o->xf : &xf_ident;
}

/* ---- lights and camera -------------------------------------------------- */

enum light_kind { LIGHT_POINT, LIGHT_SPOT, LIGHT_PARALLEL };

struct light {
	enum light_kind kind;
	struct srcloc loc;
	struct vec3 pos;            /* position (after transforms) */
	struct colour colour;       /* radiant intensity, W/sr per channel */
	struct vec3 point_at;       /* spotlight/parallel target */
	double radius, falloff;     /* spotlight cone, degrees */
	double tightness;           /* spotlight tightness */
	bool area;                  /* area_light */
	struct vec3 axis1, axis2;   /* area light edges */
	int size1, size2;           /* area light samples per edge */
	int adaptive;               /* area light adaptive level */
	bool jitter, circular, orient; /* area light options */
	double fade_distance, fade_power; /* POV fading (0: none) */
	bool shadowless;            /* casts no shadows, lights everything */
	bool photons_refraction;    /* photons { refraction on } (default on) */
	bool photons_reflection;    /* photons { reflection on } (default on) */
	struct object *looks_like;  /* looks_like: drawn at the light, casting no shadow (NULL: none) */
};

/* POV-Ray's camera types (tracer/camera.c has their projections). */
enum camera_kind {
	CAM_PERSPECTIVE, CAM_ORTHOGRAPHIC, CAM_FISHEYE, CAM_ULTRA_WIDE, CAM_PANORAMIC,
	CAM_CYL1, CAM_CYL2, CAM_CYL3, CAM_CYL4, CAM_SPHERICAL, CAM_OMNIMAX
};

/* The camera after POV-Ray's rules were applied: location, and the
 * direction/up/right frame that spans the image (right's length is the image
 * width at unit distance along direction, up's its height). */
struct camera {
	enum camera_kind kind;
	struct srcloc loc;
	struct vec3 location, direction, up, right, sky, look_at;
	double angle;          /* horizontal field of view in degrees (0: from vectors;
	                        * POV-Ray's 90 for fisheye, ultra_wide_angle, cylinder) */
	double v_angle;        /* spherical: vertical field of view (0: half of angle) */
	double aperture;       /* depth of field (0: pinhole) */
	struct vec3 focal_point;
	int blur_samples;
};

/* ---- global settings ---------------------------------------------------- */

enum illum_method { ILLUM_POINT, ILLUM_SHAFT };
enum illum_passes { PASSES_RGB, PASSES_SPECTRAL };

struct illum_settings {
	long rays;                 /* light-ray budget per light (0: default) */
	enum illum_method method;  /* default shaft */
	bool method_set;           /* the scene named its method */
	enum illum_passes passes;
	bool given;                /* illumination { } or photons { } was present */
	double spacing;            /* POV photons spacing (0: none) */
	long count;                /* POV photons count (0: none) */
	int max_depth;             /* light ray recursion limit (0: max_trace_level) */
	double tolerance;          /* accuracy target: relative L1 of the maps (0: none) */
};

struct global_settings {
	double assumed_gamma;      /* parsed, recorded (output is linear) */
	bool gamma_given;          /* the scene set assumed_gamma */
	int max_trace_level;       /* default 5 */
	double adc_bailout;        /* default 1/255 */
	struct colour ambient_light; /* default 1 */
	int noise_generator;       /* default 2 (POV-Ray's range-corrected noise) */
	int number_of_waves;       /* ripples and waves: sources (default 10) */
	struct illum_settings illum;
};

struct scene {
	struct arena arena;        /* owns everything below */
	const char *name;          /* the scene file's name */
	double version;            /* #version in force at the end (3.7 default) */
	bool legacy_lights;        /* #version 3.x: POV-Ray's no-falloff light model */
	struct camera camera;
	bool has_camera;
	struct colour background;
	struct pigment *sky;       /* sky_sphere pigments, bottom first (NULL: none) */
	int nsky;
	const struct xform *sky_xf; /* sky_sphere's transforms; NULL: identity */
	struct fog {
		int type;           /* 0: none, 1: constant, 2: ground fog */
		double distance;    /* where a constant fog lets e^-1 through */
		double offset, alt; /* ground fog: full below offset, thinning above over alt */
		struct vec3 up;     /* ground fog: the up direction (unit) */
		struct colour c;    /* its colour; transmit: the least it lets through */
	} fog;
	struct light *lights;
	int nlights;
	struct object **objects;   /* top-level objects */
	int nobjects;
	struct global_settings gs;
};

/* Defaults, as POV-Ray 3.7 has them. */
void scene_init(struct scene *s);
struct texture scene_default_texture(void);
struct interior scene_default_interior(void);
struct camera scene_default_camera(void);
struct light scene_default_light(void);
/* Appends to the scene's lists (arena-backed growth). */
void scene_add_object(struct scene *s, struct object *o);
void scene_add_light(struct scene *s, const struct light *l);
/* Stable text for golden tests (--dump-scene). */
void scene_dump(FILE *out, const struct scene *s);
const char *scene_object_kind_name(enum object_kind k);
/* The OCIO view whose PNG matches POV-Ray's own for a #version 3.x scene
 * (docs/design.md §6): "Standard" (sRGB) for assumed_gamma 1, "Raw" for
 * POV-Ray's un-corrected output (assumed_gamma 2.2, or none before 3.7);
 * NULL for arvo's own scenes. */
const char *scene_pov_view(const struct scene *s);
void scene_free(struct scene *s);

#endif
