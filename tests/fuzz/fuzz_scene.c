/* SPDX-License-Identifier: MIT */
/* fuzz_scene.c: the lexer, parser and evaluator on scene text. Each input is
 * a scene file; it is evaluated with the standard includes (when run from the
 * repository), lower loop, call and object limits than the defaults (so one
 * input stays well under the per-input timeout) and a memory budget, and the
 * scene it builds is dumped and freed. Messages go to /dev/null. */
#include <stdio.h>
#include <unistd.h>

#include "../../common/arena.h"
#include "../../common/diag.h"
#include "../../eval/eval.h"
#include "../../tracer/scene.h"
#include "fuzz.h"

/* The budget outside the evaluator: let the allocation go ahead. */
static void over_budget(size_t request) { (void)request; }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static FILE *null;
	if (!null) {
		null = fopen("/dev/null", "w");
		mem_set_budget((size_t)1536 << 20, over_budget);
	}
	const char *path = fuzz_file("fuzz.scn", data, size);
	struct diag dg;
	diag_init(&dg, null);
	struct eval_options eo;
	eval_default_options(&eo);
	eo.debug_out = null;
	eo.max_iterations = 100000;
	eo.max_calls = 100000;
	eo.max_steps = 20000000;
	eo.max_objects = 20000;
	if (access("stdlib-scenes/include", R_OK) == 0)
		eo.stdlib_dir = "stdlib-scenes/include";
	struct scene sc;
	if (eval_scene(path, &eo, &dg, &sc) == 0)
		scene_dump(null, &sc);
	scene_free(&sc);
	srcfile_free_all();
	return 0;
}
