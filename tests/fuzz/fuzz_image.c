/* SPDX-License-Identifier: MIT */
/* fuzz_image.c: the image_map readers (PNG and EXR, chosen by their magic
 * bytes in img_load) and the --load-maps map-file loader (inputs that start
 * with its magic, "ARVOMAP1"), on a file holding the input. Map files are
 * loaded for tests/fuzz/maps.scn, the scene fuzz.sh saves its seed from. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../../common/arena.h"
#include "../../common/diag.h"
#include "../../eval/eval.h"
#include "../../tracer/light/lightpass.h"
#include "../../tracer/output/imageio.h"
#include "../../tracer/scene.h"
#include "fuzz.h"

static void over_budget(size_t request) { (void)request; }

static uint64_t be32(const uint8_t *p)
{
	return (uint64_t)p[0] << 24 | (uint64_t)p[1] << 16 | (uint64_t)p[2] << 8 | p[3];
}

/* The scene map files are loaded for; NULL when it cannot be read. */
static struct scene *maps_scene(void)
{
	static struct scene sc;
	static int state; /* 0 not tried, 1 ready, 2 unavailable */
	if (state == 0) {
		FILE *null = fopen("/dev/null", "w");
		struct diag dg;
		diag_init(&dg, null);
		struct eval_options eo;
		eval_default_options(&eo);
		eo.debug_out = null;
		state = eval_scene("tests/fuzz/maps.scn", &eo, &dg, &sc) == 0 ? 1 : 2;
		fclose(null);
	}
	return state == 1 ? &sc : NULL;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static int init;
	if (!init) {
		init = 1;
		mem_set_budget((size_t)1536 << 20, over_budget);
	}
	if (size >= 8 && memcmp(data, "ARVOMAP1", 8) == 0) {
		const struct scene *sc = maps_scene();
		if (!sc)
			return 0;
		const char *path = fuzz_file("fuzz.map", data, size);
		struct lp_result *r[3] = {NULL, NULL, NULL};
		struct diag quiet; /* no stream: the message is only kept */
		diag_init(&quiet, NULL);
		int n = lp_load(r, sc, path, false, &quiet);
		for (int i = 0; i < n; i++)
			lp_free(r[i]);
		return 0;
	}
	/* A PNG header may declare up to 32768 x 32768 pixels, which the reader
	 * allocates before reading them: arvo refuses it at its memory budget
	 * (exit 70); here such inputs are skipped, as libFuzzer's malloc limit
	 * would report them. */
	if (size >= 24 && memcmp(data, "\x89PNG", 4) == 0 && be32(data + 16) * be32(data + 20) > ((uint64_t)1 << 24))
		return 0;
	const char *path = fuzz_file("fuzz.img", data, size);
	struct img_opts opts = {NULL, NULL, 1, 0}; /* raw: the readers, not OCIO */
	struct img im;
	struct diag quiet;
	diag_init(&quiet, NULL);
	if (!img_load(path, &opts, &im, &quiet, srcloc_none(), NULL))
		img_free(&im);
	return 0;
}
