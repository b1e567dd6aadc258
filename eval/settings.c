/* SPDX-License-Identifier: MIT */
/* settings.c: lights, the camera, global_settings with its photons and
 * illumination blocks, and the illum_map and photons blocks of objects. */
#include <math.h>
#include <string.h>

#include "internal.h"

static void light_transform(struct light *l, const struct xform *X)
{
	l->pos = xf_point(X, l->pos);
	l->point_at = xf_point(X, l->point_at);
	l->axis1 = xf_vector(X, l->axis1);
	l->axis2 = xf_vector(X, l->axis2);
}

static void camera_transform(struct camera *c, const struct xform *X)
{
	c->location = xf_point(X, c->location);
	c->look_at = xf_point(X, c->look_at);
	c->focal_point = xf_point(X, c->focal_point);
	c->direction = xf_vector(X, c->direction);
	c->up = xf_vector(X, c->up);
	c->right = xf_vector(X, c->right);
	c->sky = xf_vector(X, c->sky);
}

void photons_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	if (s->kw == TK_OBJECT) { /* on an object */
		struct photon_spec *p = s->target;
		switch (n->op) {
		case TK_TARGET: p->target = true; p->spacing = n->nkids ? arg_positive(E, n) : 1; return;
		case TK_REFRACTION: p->refraction = arg_bool(E, n); return;
		case TK_REFLECTION: p->reflection = arg_bool(E, n); return;
		case TK_COLLECT: p->collect = arg_bool(E, n); return;
		case TK_PASS_THROUGH: p->pass_through = arg_bool(E, n); return;
		default: break;
		}
	} else if (s->kw == TK_LIGHT_SOURCE) {
		struct light *l = s->target;
		switch (n->op) {
		case TK_REFRACTION: l->photons_refraction = arg_bool(E, n); return;
		case TK_REFLECTION: l->photons_reflection = arg_bool(E, n); return;
		case TK_AREA_LIGHT: return;
		default: break;
		}
	} else { /* global_settings */
		struct illum_settings *g = s->target;
		g->given = true;
		switch (n->op) {
		case TK_SPACING: g->spacing = arg_positive(E, n); return;
		case TK_COUNT: g->count = (long)fmin(arg_positive(E, n), 1e12); return; /* rays are 1e12 at most */
		case TK_MAX_TRACE_LEVEL: g->max_depth = arg_int(E, n, 1, 256); return;
		case TK_GATHER: case TK_MEDIA: case TK_JITTER: case TK_AUTOSTOP: case TK_EXPAND_THRESHOLDS:
		case TK_RADIUS: case TK_ADC_BAILOUT:
			for (int i = 0; i < n->nkids; i++)
				eval_float(E, n->kids[i]);
			return;
		default: break;
		}
	}
	eval_fail(E, n->loc, "%s is not valid in 'photons' here", tok_name(n->op));
}

void light_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct light *l = s->target;
	struct xform X;
	s->modified = 1;
	if (transform_of(E, n, &X)) {
		light_transform(l, &X);
		return;
	}
	switch (n->op) {
	case TK_LOOKS_LIKE: { /* looks_like { object }: an object { } of its items */
		struct node on = *n;
		on.op = TK_OBJECT;
		l->looks_like = object_block(E, &on).p.obj;
		return;
	}
	case TK_SPOTLIGHT: l->kind = LIGHT_SPOT; return;
	case TK_PARALLEL: l->kind = LIGHT_PARALLEL; l->point_at = v3(0, 0, 0); return;
	case TK_RADIUS: l->radius = arg_float(E, n); return;
	case TK_FALLOFF: l->falloff = arg_float(E, n); return;
	case TK_TIGHTNESS: l->tightness = arg_float(E, n); return;
	case TK_POINT_AT: l->point_at = arg_vec3(E, n); return;
	case TK_AREA_LIGHT:
		if (n->nkids != 4)
			eval_fail(E, n->loc, "area_light needs <axis1>, <axis2>, size1, size2");
		l->area = true;
		l->axis1 = eval_vec3(E, n->kids[0]);
		l->axis2 = eval_vec3(E, n->kids[1]);
		double s1 = eval_float(E, n->kids[2]), s2 = eval_float(E, n->kids[3]);
		if (!(s1 >= 1 && s2 >= 1 && s1 < 1025 && s2 < 1025)) /* before converting to int */
			eval_fail(E, n->kids[2]->loc, "area_light sizes must be 1 to 1024");
		l->size1 = (int)s1;
		l->size2 = (int)s2;
		return;
	case TK_ADAPTIVE: l->adaptive = arg_int(E, n, 0, 16); return;
	case TK_JITTER: l->jitter = arg_bool(E, n); return;
	case TK_CIRCULAR: l->circular = true; return;
	case TK_ORIENT: l->orient = true; return;
	case TK_FADE_DISTANCE: l->fade_distance = arg_float(E, n); return;
	case TK_FADE_POWER: l->fade_power = arg_float(E, n); return;
	case TK_SHADOWLESS: l->shadowless = true; return;
	case TK_PHOTONS: {
		struct sink sub;
		sink_init(&sub, SK_PHOTONS, TK_LIGHT_SOURCE, n->loc, l);
		eval_items(E, n, &sub);
		return;
	}
	default: misplaced(E, s, n);
	}
}

void light_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc)
{
	struct light *l = s->target;
	if (v->kind == V_LIGHT && s->nparams == 0 && !s->modified) {
		*l = *v->p.light;
		s->nparams = 2; /* a declared light has both */
		return;
	}
	if (s->modified)
		eval_fail(E, loc, "light_source position and colour must come before its modifiers");
	if (s->nparams == 0) {
		l->pos = val_want_vec3(E, v, loc);
	} else if (s->nparams == 1) {
		l->colour = val_want_colour(E, v, loc);
	} else {
		eval_fail(E, loc, "light_source takes a position and a colour, found a third value");
	}
	s->nparams++;
}

/* POV-Ray's look_at: re-aims direction, right and up, keeping their lengths. */
static void camera_look_at(struct eval *E, struct camera *c, struct vec3 at, struct srcloc loc)
{
	double dl = v_len(c->direction), ul = v_len(c->up), rl = v_len(c->right);
	double hand = v_dot(v_cross(c->up, c->direction), c->right);
	c->look_at = at;
	struct vec3 d = v_sub(at, c->location);
	if (v_len(d) < 1e-12)
		eval_fail(E, loc, "camera location and look_at must differ");
	d = v_norm(d);
	struct vec3 r = v_cross(c->sky, d);
	if (v_len(r) < 1e-12) { /* as POV-Ray: keep the right vector given (or the default) */
		diag_warning(E->diag, loc, "camera looks along its sky vector; the right vector is kept (set sky to choose 'up')");
		r = v_sub(c->right, v_scale(d, v_dot(c->right, d)));
		if (v_len(r) < 1e-12)
			eval_fail(E, loc, "camera looks along its sky vector and its right vector; set sky to something else");
		hand = 1;
	}
	r = v_norm(r);
	c->up = v_scale(v_norm(v_cross(d, r)), ul);
	c->direction = v_scale(d, dl);
	c->right = v_scale(r, hand > 0 ? rl : -rl);
}

enum { CAM_LOOK_AT = 1, CAM_ANGLE = 2, CAM_XF = 4 };

/* As POV-Ray does, angle and look_at take effect once every vector of the
 * block is known, and the block's transforms after them, whatever the order
 * of the items. */
void camera_finish(struct eval *E, struct sink *s, struct camera *c)
{
	if ((s->pending & CAM_ANGLE) && c->kind == CAM_PERSPECTIVE)
		c->direction = v_scale(v_norm(c->direction), v_len(c->right) / tan(c->angle * M_PI / 360) / 2);
	if (s->pending & CAM_LOOK_AT)
		camera_look_at(E, c, c->look_at, s->ploc[0]);
	if ((s->pending & CAM_ANGLE) && c->kind == CAM_ORTHOGRAPHIC) {
		/* POV-Ray 3.7: the view is as wide as a perspective camera's of that
		 * angle at the look_at distance (else at the direction's length) */
		double d = s->pending & CAM_LOOK_AT ? v_len(v_sub(c->look_at, c->location)) : v_len(c->direction);
		double w = 2 * d * tan(c->angle * M_PI / 360), k = w / v_len(c->right);
		c->right = v_scale(c->right, k);
		c->up = v_scale(c->up, k);
	}
	if (s->pending & CAM_XF)
		camera_transform(c, &s->pending_xf);
}

void camera_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct camera *c = s->target;
	struct xform X;
	if (transform_of(E, n, &X)) {
		s->pending_xf = s->pending & CAM_XF ? xf_then(s->pending_xf, X) : X;
		s->pending |= CAM_XF;
		return;
	}
	switch (n->op) {
	case TK_NORMAL: /* POV-Ray's camera ray perturbation */
		diag_warning(E->diag, n->loc, "'normal' in a camera is not supported; ignored");
		return;
	case TK_PERSPECTIVE: c->kind = CAM_PERSPECTIVE; return;
	case TK_ORTHOGRAPHIC: c->kind = CAM_ORTHOGRAPHIC; return;
	case TK_FISHEYE: c->kind = CAM_FISHEYE; return;
	case TK_ULTRA_WIDE_ANGLE: c->kind = CAM_ULTRA_WIDE; return;
	case TK_PANORAMIC: c->kind = CAM_PANORAMIC; return;
	case TK_OMNIMAX: c->kind = CAM_OMNIMAX; return;
	case TK_SPHERICAL: c->kind = CAM_SPHERICAL; return;
	case TK_CYLINDER: {
		if (n->kind == N_BLOCK)
			misplaced(E, s, n);
		int k = arg_int(E, n, 1, 4);
		c->kind = k == 1 ? CAM_CYL1 : k == 2 ? CAM_CYL2 : k == 3 ? CAM_CYL3 : CAM_CYL4;
		return;
	}
	case TK_MESH_CAMERA: eval_fail(E, n->loc, "'mesh_camera' is not supported");
	case TK_LOCATION: c->location = arg_vec3(E, n); return;
	case TK_DIRECTION: c->direction = arg_vec3(E, n); return;
	case TK_UP: c->up = arg_vec3(E, n); return;
	case TK_RIGHT: c->right = arg_vec3(E, n); return;
	case TK_SKY: c->sky = arg_vec3(E, n); return;
	case TK_LOOK_AT:
		c->look_at = arg_vec3(E, n);
		s->ploc[0] = n->loc; /* for its error */
		s->pending |= CAM_LOOK_AT;
		return;
	case TK_ANGLE: {
		struct node first;
		if (c->kind == CAM_SPHERICAL && n->nkids == 2) { /* angle H, V */
			c->v_angle = eval_float(E, n->kids[1]);
			if (!(c->v_angle > 0 && c->v_angle <= 360))
				eval_fail(E, n->kids[1]->loc, "spherical camera angles must be above 0 and at most 360, found %g", c->v_angle);
			first = *n;
			first.nkids = 1;
			n = &first;
		}
		double a = arg_float(E, n);
		if (a <= 0 || (c->kind == CAM_PERSPECTIVE && a >= 180))
			eval_fail(E, n->kids[0]->loc, "camera angle must be between 0 and 180 degrees, found %g", a);
		c->angle = a;
		s->pending |= CAM_ANGLE;
		return;
	}
	case TK_APERTURE: c->aperture = arg_float(E, n); return;
	case TK_FOCAL_POINT: c->focal_point = arg_vec3(E, n); return;
	case TK_BLUR_SAMPLES: c->blur_samples = arg_int(E, n, 1, 65536); return;
	case TK_CONFIDENCE: case TK_VARIANCE: arg_float(E, n); return;
	default: misplaced(E, s, n);
	}
}

void global_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct global_settings *g = &SC(E)->gs;
	struct sink sub;
	switch (n->op) {
	case TK_ASSUMED_GAMMA: g->assumed_gamma = arg_positive(E, n); g->gamma_given = true; return;
	case TK_MAX_TRACE_LEVEL: g->max_trace_level = arg_int(E, n, 1, 256); return;
	case TK_ADC_BAILOUT: g->adc_bailout = arg_float(E, n); return;
	case TK_AMBIENT_LIGHT: g->ambient_light = arg_colour(E, n); return;
	case TK_NOISE_GENERATOR: g->noise_generator = arg_int(E, n, 1, 3); return;
	case TK_NUMBER_OF_WAVES: g->number_of_waves = arg_int(E, n, 1, 256); return;
	case TK_PHOTONS:
		g->illum.given = true;
		sink_init(&sub, SK_PHOTONS, TK_GLOBAL_SETTINGS, n->loc, &g->illum);
		eval_items(E, n, &sub);
		return;
	case TK_ILLUMINATION:
		g->illum.given = true;
		run_block(E, n, SK_ILLUM, &g->illum, &sub);
		return;
	default: misplaced(E, s, n);
	}
}

void illum_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct illum_settings *il = s->target;
	switch (n->op) {
	case TK_RAYS: {
		double r = arg_float(E, n);
		if (!(r >= 1 && r <= 1e12))
			eval_fail(E, n->kids[0]->loc, "rays must be 1 to 1e12, found %g", r);
		il->rays = (long)r;
		return;
	}
	case TK_MAX_DEPTH: il->max_depth = arg_int(E, n, 1, 256); return;
	case TK_TOLERANCE: {
		double t = arg_float(E, n);
		if (!(t >= 1e-5 && t <= 0.5))
			eval_fail(E, n->kids[0]->loc, "tolerance must be 1e-5 to 0.5, found %g", t);
		il->tolerance = t;
		return;
	}
	case TK_METHOD:
		il->method_set = true;
		if (strcmp(n->str, "point") == 0)
			il->method = ILLUM_POINT;
		else if (strcmp(n->str, "shaft") == 0)
			il->method = ILLUM_SHAFT;
		else
			eval_fail(E, n->loc, "method must be 'point' or 'shaft', found '%s'", n->str);
		return;
	case TK_PASSES:
		if (strcmp(n->str, "rgb") == 0)
			il->passes = PASSES_RGB;
		else if (strcmp(n->str, "spectral") == 0)
			il->passes = PASSES_SPECTRAL;
		else
			eval_fail(E, n->loc, "passes must be 'rgb' or 'spectral', found '%s'", n->str);
		return;
	default: misplaced(E, s, n);
	}
}

void illum_map_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct illum_spec *m = s->target;
	switch (n->op) {
	case TK_RESOLUTION: m->resolution = arg_int(E, n, 2, 65536); return;
	case TK_CELL: m->cell = arg_positive(E, n); return;
	default: misplaced(E, s, n);
	}
}

/* sky_sphere { pigment { … } … [transforms] }: the pigments, evaluated at
 * the direction of a ray that leaves the scene, bottom first. */
void sky_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct scene *sc = s->target;
	struct xform X;
	if (transform_of(E, n, &X)) {
		sc->sky_xf = xform_then(E, sc->sky_xf, &X);
		return;
	}
	if (n->op != TK_PIGMENT || n->kind != N_BLOCK)
		misplaced(E, s, n);
	struct value v = eval_block(E, n);
	struct pigment *p = ARENA_ARRAY(&sc->arena, struct pigment, sc->nsky + 1);
	if (sc->nsky)
		memcpy(p, sc->sky, sizeof *p * (size_t)sc->nsky);
	p[sc->nsky++] = *v.p.pig;
	sc->sky = p;
}

/* sky_sphere { S … }: a declared sky_sphere's pigments and transform, then
 * what follows. */
void sky_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc)
{
	struct scene *sc = s->target;
	if (v->kind != V_SKY)
		eval_fail(E, loc, "expected a sky_sphere or a pigment { } in sky_sphere, found %s", val_type_name(v));
	const struct sky_value *sv = v->p.sky;
	struct pigment *p = ARENA_ARRAY(&sc->arena, struct pigment, sc->nsky + sv->n);
	if (sc->nsky)
		memcpy(p, sc->sky, sizeof *p * (size_t)sc->nsky);
	memcpy(p + sc->nsky, sv->pig, sizeof *p * (size_t)sv->n);
	sc->sky = p;
	sc->nsky += sv->n;
	if (sv->xf)
		sc->sky_xf = xform_then(E, sc->sky_xf, sv->xf);
}

/* fog { [fog_type 1|2] distance d colour c [fog_offset h fog_alt a up v] } */
void fog_keyword(struct eval *E, struct sink *s, const struct node *n)
{
	struct fog *f = s->target;
	switch (n->op) {
	case TK_FOG_TYPE: f->type = arg_int(E, n, 1, 2); return;
	case TK_DISTANCE: f->distance = arg_positive(E, n); return;
	case TK_FOG_OFFSET: f->offset = arg_float(E, n); return;
	case TK_FOG_ALT: f->alt = arg_positive(E, n); return;
	case TK_TURBULENCE: case TK_OCTAVES: case TK_OMEGA: case TK_LAMBDA:
		if (!E->warned_fog_turb++)
			diag_warning(E->diag, n->loc, "%s in fog is not supported yet; the fog is even", tok_name(n->op));
		return;
	case TK_UP: {
		struct vec3 u = arg_vec3(E, n);
		if (v_len(u) == 0)
			eval_fail(E, n->kids[0]->loc, "fog up vector has zero length");
		f->up = v_norm(u);
		return;
	}
	default: misplaced(E, s, n);
	}
}

/* The fog's colour. */
void fog_value(struct eval *E, struct sink *s, const struct value *v, struct srcloc loc)
{
	struct fog *f = s->target;
	f->c = val_want_colour(E, v, loc);
}
