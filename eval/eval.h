/* SPDX-License-Identifier: MIT */
/* eval.h: runs a parsed scene file and builds the scene model. */
#ifndef ARVO_EVAL_H
#define ARVO_EVAL_H

#include <stdbool.h>

#include "../common/diag.h"
#include "../tracer/scene.h"

/* What the command line gives the evaluator. */
struct eval_options {
	const char *const *include_dirs; /* -I directories, in order */
	int ninclude;
	const char *stdlib_dir;          /* stdlib-scenes/include (NULL: none) */
	const char *pov_include_dir;     /* POV-Ray's include files (NULL: none) */
	const char *const *allow_read;   /* --allow-read directories: more a scene may read */
	int nallow;
	const char *const *defines;      /* -D NAME=VALUE strings */
	int ndefines;
	double clock;                    /* clock */
	int frame;                       /* frame_number */
	/* animation (all 0 without one, as POV-Ray): clock_on, clock_delta,
	 * initial_clock, final_clock, initial_frame, final_frame */
	int clock_on;
	double clock_delta, initial_clock, final_clock;
	int initial_frame, final_frame;
	int width, height;               /* image_width, image_height */
	long max_iterations;             /* #while/#for iterations in total */
	long max_calls;                  /* macro calls in total */
	long max_steps;                  /* evaluation steps (item lists and expressions) in total */
	long max_objects;                /* objects and lights in the scene */
	FILE *debug_out;                 /* where #debug writes (stdout) */
	/* Called for each file read (the scene, every include and image_map), for -M. */
	void (*on_file)(const char *path, void *ctx);
	void *on_file_ctx;
};

void eval_default_options(struct eval_options *o);
/* Why name[0..len) cannot be declared (by -D or #declare): "a reserved
 * word" or "a built-in name"; NULL when it can. */
const char *eval_undeclarable(const char *name, int len);
/* Reads, parses and evaluates the scene file at path into *out (which
 * eval_scene initialises). Returns 0 on success, 65 when the scene has errors
 * (reported to diag), 66 when the file itself, or a file it includes or
 * names, is missing or cannot be read. */
int eval_scene(const char *path, const struct eval_options *opt, struct diag *diag, struct scene *out);

#endif
