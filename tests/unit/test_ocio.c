/* SPDX-License-Identifier: MIT */
/* test_ocio.c: the OCIO shim and config resolution with the shipped config:
 * known linear values through each view give the reference values of docs/design.md §6 (1e-3). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../../tracer/output/ocio_shim.h"
#include "../../tracer/output/pngout.h"
#include "test.h"

static struct ocio_config *cfg; /* the shipped config, loaded once */

/* One row of docs/design.md §6's reference table: linear in, Standard out, ACES SDR out. */
struct row {
	float in[3], standard[3], aces[3];
};

static const struct row table[] = {
    {{0.18f, 0.18f, 0.18f}, {0.4614f, 0.4614f, 0.4614f}, {0.3560f, 0.3560f, 0.3560f}},
    {{1, 1, 1}, {1, 1, 1}, {0.8120f, 0.8120f, 0.8120f}},
    {{0.5f, 0.2f, 0.1f}, {0.7354f, 0.4845f, 0.3492f}, {0.6234f, 0.3941f, 0.2512f}},
    {{50, 5, 1}, {5.3296f, 2.0080f, 1.0000f}, {1.0236f, 0.9844f, 0.9288f}},
    {{1000, 100, 10}, {18.7058f, 7.1326f, 2.6987f}, {1.0377f, 1.0249f, 1.0127f}},
    {{10, 0.5f, 0.05f}, {2.6987f, 0.7354f, 0.2478f}, {1.0490f, 0.8354f, 0.5295f}},
    {{100, 2, 0.1f}, {7.1326f, 1.3533f, 0.3492f}, {1.0329f, 0.9878f, 0.9332f}},
};
#define NROWS ((int)(sizeof table / sizeof table[0]))

static void t_default_config_found(void)
{
	const char *p = out_default_ocio_config();
	CHECK(p != NULL);
	if (p) {
		printf("# shipped config: %s\n", p);
		CHECK(strstr(p, "ocio/config.ocio") != NULL);
		CHECK(access(p, R_OK) == 0);
	}
	char err[256] = "";
	cfg = p ? ocio_config_load(p, err, sizeof err) : NULL;
	CHECK(cfg != NULL);
	if (!cfg)
		printf("# %s\n", err);
	const char *v = ocio_version();
	CHECK(v && strncmp(v, "2.", 2) == 0);
}

static void t_displays_views(void)
{
	if (!cfg)
		return;
	CHECK(ocio_display_count(cfg) == 1);
	CHECK_STR(ocio_display_name(cfg, 0), "sRGB - Display");
	CHECK(ocio_display_name(cfg, 1) == NULL);
	CHECK_STR(ocio_default_display(cfg), "sRGB - Display");
	CHECK(ocio_view_count(cfg, "sRGB - Display") == 3);
	CHECK_STR(ocio_view_name(cfg, "sRGB - Display", 0), "Standard");
	CHECK_STR(ocio_view_name(cfg, "sRGB - Display", 1), "ACES 1.0 - SDR Video");
	CHECK_STR(ocio_view_name(cfg, "sRGB - Display", 2), "Raw");
	CHECK(ocio_view_count(cfg, "nope") == 0);
	CHECK(ocio_view_name(cfg, "nope", 0) == NULL);
	CHECK(ocio_has_colorspace(cfg, "sRGB - Texture"));
	CHECK(ocio_has_colorspace(cfg, "scene_linear"));
	CHECK(!ocio_has_colorspace(cfg, "nope"));
	char buf[256];
	size_t n = ocio_describe_views(cfg, buf, sizeof buf);
	CHECK_STR(buf, "\"sRGB - Display\": \"Standard\", \"ACES 1.0 - SDR Video\", \"Raw\"\n");
	CHECK(n == strlen(buf));
	const char *d = NULL, *v = NULL;
	CHECK(MSG(out_ocio_pick_view(cfg, NULL, NULL, &d, &v, TDG)) == NULL);
	CHECK_STR(d, "sRGB - Display");
	CHECK_STR(v, "ACES 1.0 - SDR Video");
	const char *err = MSG(out_ocio_pick_view(cfg, NULL, "Filmic", &d, &v, TDG));
	CHECK(err && strstr(err, "'Filmic'") && strstr(err, "\"ACES 1.0 - SDR Video\""));
	if (err)
		printf("# expected error: %.*s\n", (int)strcspn(err, "\n"), err);
	err = MSG(out_ocio_pick_view(cfg, "P3", NULL, &d, &v, TDG));
	CHECK(err && strstr(err, "display 'P3'") && strstr(err, "\"Standard\""));
}

/* Runs the table through one view; col picks the expected column. */
static void check_view(const char *view, int col)
{
	char err[256] = "";
	struct ocio_proc *p = ocio_proc_display(cfg, NULL, "sRGB - Display", view, err, sizeof err);
	CHECK(p != NULL);
	if (!p) {
		printf("# %s\n", err);
		return;
	}
	float rgb[NROWS * 3];
	for (int i = 0; i < NROWS; i++)
		memcpy(rgb + 3 * i, table[i].in, sizeof table[i].in);
	CHECK(ocio_proc_apply_rgb(p, rgb, NROWS, err, sizeof err) == 0);
	for (int i = 0; i < NROWS; i++)
		for (int c = 0; c < 3; c++) {
			const float *want = col == 0 ? table[i].standard : col == 1 ? table[i].aces : table[i].in;
			CHECK_NEAR(rgb[3 * i + c], want[c], 1e-3);
		}
	ocio_proc_free(p);
}

static void t_view_standard(void)
{
	if (cfg)
		check_view("Standard", 0);
}

static void t_view_aces(void)
{
	if (cfg)
		check_view("ACES 1.0 - SDR Video", 1);
}

static void t_view_raw(void)
{
	if (cfg)
		check_view("Raw", 2);
}

/* An explicit source space: ACEScg (AP1) input through the Standard view. */
static void t_source_space(void)
{
	if (!cfg)
		return;
	char err[256];
	struct ocio_proc *p = ocio_proc_display(cfg, "Linear Rec.709 (sRGB)", "sRGB - Display",
	                                        "Standard", err, sizeof err);
	float g[3] = {0.18f, 0.18f, 0.18f};
	CHECK(p && ocio_proc_apply_rgb(p, g, 1, err, sizeof err) == 0);
	CHECK_NEAR(g[1], 0.4614, 1e-3);
	ocio_proc_free(p);
	p = ocio_proc_display(cfg, "nope", "sRGB - Display", "Standard", err, sizeof err);
	CHECK(p == NULL && strstr(err, "nope") != NULL);
}

/* sRGB - Texture → scene_linear is the sRGB EOTF (texture decoding). */
static void t_texture_to_linear(void)
{
	if (!cfg)
		return;
	char err[256];
	struct ocio_proc *p = ocio_proc_convert(cfg, "sRGB - Texture", "scene_linear", err, sizeof err);
	CHECK(p != NULL);
	if (!p)
		return;
	float v[6] = {0.5f, 1.0f, 0.0f, 0.04045f, 0.2f, 0.8f};
	CHECK(ocio_proc_apply_rgb(p, v, 2, err, sizeof err) == 0);
	CHECK_NEAR(v[0], 0.2140411, 1e-4);
	CHECK_NEAR(v[1], 1.0, 1e-4);
	CHECK_NEAR(v[2], 0.0, 1e-4);
	CHECK_NEAR(v[3], 0.0031308, 1e-4);
	CHECK_NEAR(v[4], 0.0331048, 1e-4);
	CHECK_NEAR(v[5], 0.6038273, 1e-4);
	ocio_proc_free(p);
	CHECK(ocio_proc_convert(cfg, "sRGB - Texture", "nope", err, sizeof err) == NULL);
}

/* Explicit path > $OCIO > shipped; bad paths give messages, not crashes. */
static void t_config_resolution(void)
{
	const char *shipped = out_default_ocio_config();
	unsetenv("OCIO");
	CHECK(out_ocio_config_path(NULL) == shipped);
	CHECK(out_ocio_config_path("") == shipped);
	CHECK_STR(out_ocio_config_path("/x/y.ocio"), "/x/y.ocio");
	setenv("OCIO", "/env/config.ocio", 1);
	CHECK_STR(out_ocio_config_path(NULL), "/env/config.ocio");
	CHECK_STR(out_ocio_config_path("/x/y.ocio"), "/x/y.ocio");
	struct ocio_config *c = NULL;
	const char *err = MSG(out_ocio_load(NULL, &c, TDG));
	CHECK(c == NULL && err && strstr(err, "/env/config.ocio"));
	if (err)
		printf("# expected error: %s\n", err);
	unsetenv("OCIO");
	char e[256];
	CHECK(ocio_config_load(NULL, e, sizeof e) == NULL && strstr(e, "$OCIO"));
	CHECK(ocio_config_load("/nonexistent.ocio", e, sizeof e) == NULL && e[0]);
	char list[256];
	CHECK(MSG(out_ocio_list_views(NULL, list, sizeof list, TDG)) == NULL);
	CHECK(strstr(list, "\"Raw\"") != NULL);
}

/* $ARVO_DATA_DIR wins over the executable's neighbourhood; a directory
 * without ocio/config.ocio falls through. Runs this binary again with
 * --print-default, since the search result is cached per process. */
static void t_data_dir_env(void)
{
	char dir[64] = "/tmp/arvo-ocio-XXXXXX", cmd[512], out[512] = "";
	if (!mkdtemp(dir)) {
		CHECK(0);
		return;
	}
	snprintf(cmd, sizeof cmd, "mkdir -p %s/ocio && cp '%s' %s/ocio/config.ocio", dir,
	         out_default_ocio_config(), dir);
	CHECK(system(cmd) == 0);
	snprintf(cmd, sizeof cmd, "ARVO_DATA_DIR=%s /proc/%d/exe --print-default", dir, (int)getpid());
	FILE *p = popen(cmd, "r");
	if (p && fgets(out, sizeof out, p))
		out[strcspn(out, "\n")] = '\0';
	if (p)
		pclose(p);
	snprintf(cmd, sizeof cmd, "%s/ocio/config.ocio", dir);
	CHECK_STR(out, cmd);
	snprintf(cmd, sizeof cmd, "ARVO_DATA_DIR=/nonexistent /proc/%d/exe --print-default", (int)getpid());
	p = popen(cmd, "r");
	out[0] = '\0';
	if (p && fgets(out, sizeof out, p))
		out[strcspn(out, "\n")] = '\0';
	if (p)
		pclose(p);
	CHECK_STR(out, out_default_ocio_config());
	snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
	CHECK(system(cmd) == 0);
}

int main(int argc, char **argv)
{
	if (argc > 1 && strcmp(argv[1], "--print-default") == 0) {
		const char *p = out_default_ocio_config();
		printf("%s\n", p ? p : "(none)");
		return 0;
	}
	RUN(t_default_config_found);
	RUN(t_displays_views);
	RUN(t_view_standard);
	RUN(t_view_aces);
	RUN(t_view_raw);
	RUN(t_source_space);
	RUN(t_texture_to_linear);
	RUN(t_config_resolution);
	RUN(t_data_dir_env);
	ocio_config_free(cfg);
	return test_done();
}
