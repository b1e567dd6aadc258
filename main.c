/* SPDX-License-Identifier: MIT */
/* main.c: the command line. Reads like the pipeline:
 *   lex → parse (AST) → eval (scene) → render (light pass, eye pass) → output
 * and maps each stage's result to an exit code (docs/design.md §8). */
#include <errno.h>
#include <signal.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common/arena.h"
#include "common/diag.h"
#include "eval/eval.h"
#include "lexer/lexer.h"
#include "parser/parser.h"
#include "tracer/output/exrout.h"
#include "tracer/output/ocio_shim.h"
#include "tracer/output/pngout.h"
#include "tracer/output/tmpfile.h"
#include "tools/tools.h"
#include "tracer/camera.h"
#include "tracer/render.h"
#include "tracer/scene.h"

#ifndef ARVO_VERSION
#define ARVO_VERSION "0.1.0"
#endif

enum { EX_OK = 0, EX_USAGE = 64, EX_DATAERR = 65, EX_NOINPUT = 66, EX_SOFTWARE = 70,
       EX_CANTCREAT = 73, EX_IOERR = 74 };

#define MAX_PIXELS (16384LL * 16384) /* width x height */

enum action { ACT_RENDER, ACT_CHECK, ACT_TOKENS, ACT_AST, ACT_SCENE };

struct options {
	enum action action;
	const char *scene;           /* input file */
	const char *outputs[16];     /* -o (several: one render, several files) */
	int noutputs;
	const char *depfile;         /* -M / --depfile */
	const char *includes[64];    /* -I */
	int ninclude;
	const char *allow_read[64];  /* --allow-read */
	int nallow;
	const char *defines[256];    /* -D */
	int ndefines;
	int width, height, spp, threads;
	double clock;
	int frame;
	int clock_given;             /* --clock, +K or --frame given: clock_on */
	int anim;                    /* --frames or +KFF: the internal animation loop */
	long first_frame, last_frame;   /* --frames A:B (+KFI, +KFF; default 1:1) */
	double first_clock, last_clock; /* +KI, +KF (default 0, 1) */
	long sub_first, sub_last;       /* --subset C:D (+SF, +EF; -1: the whole range) */
	long max_iterations, max_calls, max_objects, max_steps; /* --max-iterations, -calls, -objects, -steps */
	size_t max_memory;                           /* --max-memory (0: not given) */
	int quiet, stats;
	const char *display;         /* --display (PNG) */
	const char *view;            /* --view (PNG) */
	const char *ocio_config;     /* --ocio-config */
	int half;                    /* --half: 16-bit EXR */
	enum out_exr_compression compression; /* --compression */
	long rays;                   /* --rays: light-pass rays per light (-1: not given, 0: off) */
	int method;                  /* --method: 0 not given, else enum illum_method + 1 */
	double tolerance;            /* --tolerance (0: not given) */
	const char *dump_maps;       /* --dump-maps DIR */
	const char *save_maps;       /* --save-maps FILE */
	const char *load_maps;       /* --load-maps FILE */
	int passes;                  /* --passes: 0 not given, else enum illum_passes + 1 */
	int region[4];               /* --region x0:x1,y0:y1 (x1 == 0: not given) */
	int tile_i, tile_n;          /* --tile i/n (tile_n == 0: not given) */
	long seed;                   /* --seed */
	int png_depth;               /* --png-depth 8|16 (0: 8) */
	char data_dir[PATH_MAX * 2];     /* stdlib-scenes (or share/arvo) */
	char stdlib_dir[PATH_MAX * 2 + 16];   /* data_dir/include */
};

static void usage(FILE *out)
{
	fputs("usage: arvo [options] scene.scn\n"
	      "  -o FILE            output image (.exr or .png; default: scene name .exr); repeat\n"
	      "                     -o to write several files from one render\n"
	      "  --width W, --height H   image size (default 320x240); also +WW +HH\n"
	      "  --spp N            samples per pixel (+A: 4);  --threads N  render threads (+WTN)\n"
	      "  --half             16-bit half EXR (default float)\n"
	      "  --compression C    EXR compression: zip (default), none, zips, piz, rle\n"
	      "  --display NAME, --view NAME   OCIO display and view for PNG output\n"
	      "  --ocio-config FILE OCIO config (default: $OCIO, else the shipped one)\n"
	      "  --rays N           light-pass rays per light (default: the scene's, else 1000000; 0: off)\n"
	      "  --method M         light pass: point (deposits) or shaft (light shafts)\n"
	      "  --tolerance T      shoot light rays until the maps' estimated error is below T\n"
	      "  --dump-maps DIR    write every illumination map as an EXR into DIR\n"
	      "  --save-maps FILE, --load-maps FILE   keep a light pass for later renders\n"
	      "  --passes rgb|spectral   dispersion by colour channel or by wavelength\n"
	      "  --region x0:x1,y0:y1  render columns x0..x1-1, rows y0..y1-1 (an EXR of that part)\n"
	      "  --tile i/n         render the i-th of n bands of rows (1 <= i <= n), as --region\n"
	      "  --seed N           another set of random numbers (default 0)\n"
	      "  --png-depth 8|16   bits per PNG channel (default 8)\n"
	      "  -D NAME=VALUE      declare a float (or \"string\") before the scene is read\n"
	      "  -I DIR             add an include directory (also +LDIR)\n"
	      "  --allow-read DIR   let the scene read files below DIR too\n"
	      "  --clock F          value of clock;  --frame N  value of frame_number\n"
	      "  --frames A:B       render frames A to B in turn (+KFIA +KFFB); clock runs from\n"
	      "                     0 to 1 (+KIx +KFy: from x to y); -o name.%04d.exr numbers them\n"
	      "  --subset C:D       only frames C to D of the range (+SFC +EFD)\n"
	      "  --max-iterations N limit on #while/#for iterations (default 10000000)\n"
	      "  --max-calls N      limit on macro calls (default 1000000)\n"
	      "  --max-objects N    limit on objects and lights (default 1000000)\n"
	      "  --max-steps N      limit on evaluation steps (default 1000000000)\n"
	      "  --max-memory SIZE  memory budget, e.g. 512M or 4G (default: half the machine's)\n"
	      "  -M, --depfile FILE write Make dependencies: every file the render reads\n"
	      "  --check            parse and evaluate only (errors and #debug output)\n"
	      "  --dump-tokens | --dump-ast | --dump-scene   print a stage's text and stop\n"
	      "  --quiet, --stats, --help, --version\n"
	      "  arvo compare A.exr B.exr [options]   arvo merge -o FULL.exr PARTS.exr...\n"
	      "exit status: 0 ok, 64 usage, 65 bad scene, 66 missing input, 70 internal error,\n"
	      "             73 cannot create output, 74 output I/O error\n",
	      out);
}

__attribute__((format(printf, 1, 2)))
static int usage_error(const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	fprintf(stderr, "arvo: error: ");
	vfprintf(stderr, fmt, ap);
	fprintf(stderr, "\n(see 'arvo --help')\n");
	va_end(ap);
	return EX_USAGE;
}

/* Parses a whole-string integer in [lo, hi]; false when it is not one. */
static int parse_int(const char *s, long lo, long hi, long *out)
{
	char *end;
	errno = 0;
	long v = strtol(s, &end, 10);
	if (errno || end == s || *end || v < lo || v > hi)
		return 0;
	*out = v;
	return 1;
}

static int parse_double(const char *s, double *out)
{
	char *end;
	errno = 0;
	double v = strtod(s, &end); /* (ERANGE on a finite result: a tiny number, as the language reads it) */
	if ((errno && errno != ERANGE) || end == s || *end || !isfinite(v))
		return 0;
	*out = v;
	return 1;
}

/* -D NAME=VALUE: NAME an identifier, VALUE a number or a quoted string. */
static int valid_define(const char *d)
{
	const char *eq = strchr(d, '=');
	if (!eq || eq == d)
		return 0;
	for (const char *p = d; p < eq; p++)
		if (!(p[0] == '_' || (p[0] >= 'a' && p[0] <= 'z') || (p[0] >= 'A' && p[0] <= 'Z') ||
		      (p > d && p[0] >= '0' && p[0] <= '9')))
			return 0;
	double f;
	size_t vl = strlen(eq + 1);
	return parse_double(eq + 1, &f) || (vl >= 2 && eq[1] == '"' && eq[vl] == '"');
}

/* Finds the data directory (stdlib-scenes or share/arvo) next to the binary. */
static void find_data_dir(struct options *o)
{
	const char *env = getenv("ARVO_DATA_DIR");
	char exe[PATH_MAX], cand[PATH_MAX + 64];
	if (env && *env) {
		snprintf(o->data_dir, sizeof o->data_dir, "%s", env);
		goto done;
	}
#ifdef ARVO_DATA_DIR
	snprintf(cand, sizeof cand, "%s/include", ARVO_DATA_DIR);
	if (access(cand, R_OK) == 0) {
		snprintf(o->data_dir, sizeof o->data_dir, "%s", ARVO_DATA_DIR);
		goto done;
	}
#endif
	ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
	if (n > 0) {
		exe[n] = '\0';
		for (int up = 0; up < 4; up++) {
			char *slash = strrchr(exe, '/');
			if (!slash)
				break;
			*slash = '\0';
			const char *subs[] = {"stdlib-scenes", "share/arvo"};
			for (int i = 0; i < 2; i++) {
				snprintf(cand, sizeof cand, "%s/%s/include", exe, subs[i]);
				if (access(cand, R_OK) == 0) {
					snprintf(o->data_dir, sizeof o->data_dir, "%s/%s", exe, subs[i]);
					goto done;
				}
			}
		}
	}
	o->data_dir[0] = '\0';
done:
	if (o->data_dir[0])
		snprintf(o->stdlib_dir, sizeof o->stdlib_dir, "%s/include", o->data_dir);
}

/* -o and +O: one more output file (at most 16). */
static int add_output(struct options *o, const char *path)
{
	if (o->noutputs >= 16)
		return 0;
	o->outputs[o->noutputs++] = path;
	return 1;
}

/* POV-Ray's animation switches (s after the sign): +KFIn +KFFn (first and
 * last frame), +KIn.n +KFn.n (clock at them), +SFn +EFn (a subset). */
static int pov_anim_switch(struct options *o, const char *s)
{
	long v;
	double f;
	if (s[0] != 'K' && s[0] != 'S' && s[0] != 'E')
		return 0;
	if (!strncmp(s, "KFI", 3) && parse_int(s + 3, 0, 999999999, &v))
		return o->first_frame = v, 1;
	if (!strncmp(s, "KFF", 3) && parse_int(s + 3, 0, 999999999, &v))
		return o->last_frame = v, o->anim = 1, 1;
	if (!strncmp(s, "KI", 2) && parse_double(s + 2, &f))
		return o->first_clock = f, 1;
	if (!strncmp(s, "KF", 2) && parse_double(s + 2, &f))
		return o->last_clock = f, 1;
	if (!strncmp(s, "SF", 2) && parse_int(s + 2, 0, 999999999, &v))
		return o->sub_first = v, 1;
	if (!strncmp(s, "EF", 2) && parse_int(s + 2, 0, 999999999, &v))
		return o->sub_last = v, 1;
	return 0;
}

/* "A:B" with 0 <= A <= B: the frames of --frames and --subset. */
static int parse_range(const char *s, long *a, long *b)
{
	char buf[64];
	const char *colon = strchr(s, ':');
	if (!colon || colon - s >= (long)sizeof buf)
		return 0;
	snprintf(buf, sizeof buf, "%.*s", (int)(colon - s), s);
	return parse_int(buf, 0, 999999999, a) && parse_int(colon + 1, 0, 999999999, b) && *a <= *b;
}

#ifndef POVRAY_INCLUDE_DIR
#define POVRAY_INCLUDE_DIR "/usr/share/povray-3.7/include" /* Debian's povray-includes */
#endif

/* POV-Ray's include directory: $ARVO_POVRAY_INCLUDE (empty: none), else
 * POVRAY_INCLUDE_DIR when it exists. */
static const char *pov_include_dir(void)
{
	const char *env = getenv("ARVO_POVRAY_INCLUDE");
	if (env)
		return *env ? env : NULL;
	return access(POVRAY_INCLUDE_DIR, R_OK) == 0 ? POVRAY_INCLUDE_DIR : NULL;
}

/* POV-Ray switches arvo does not implement: the message naming what to
 * use instead, or NULL. */
static const char *pov_unsupported(const char *a)
{
	const char *s = a + 1;
	if (!strncasecmp(s, "SR", 2) || !strncasecmp(s, "ER", 2) || !strncasecmp(s, "SC", 2) || !strncasecmp(s, "EC", 2))
		return "POV-Ray's partial render switches (+SR +ER +SC +EC) are not supported: arvo renders the whole image";
	return NULL;
}

/* The POV-Ray switches arvo accepts: +W +H +O +I +L +A -A +D -D +WT +K
 * +KFI +KFF +KI +KF +SF +EF. */
static int pov_switch(struct options *o, const char *a)
{
	long v;
	double f;
	char sign = a[0];
	const char *s = a + 1;
	if (s[0] == 'W' && s[1] == 'T' && parse_int(s + 2, 1, 1024, &v))
		return o->threads = (int)v, 1;
	if ((s[0] == 'W' || s[0] == 'w') && parse_int(s + 1, 1, 65536, &v))
		return o->width = (int)v, 1;
	if ((s[0] == 'H' || s[0] == 'h') && parse_int(s + 1, 1, 65536, &v))
		return o->height = (int)v, 1;
	if ((s[0] == 'O' || s[0] == 'o') && s[1] && sign == '+')
		return add_output(o, s + 1);
	if ((s[0] == 'I' || s[0] == 'i') && s[1] && sign == '+')
		return o->scene = s + 1, 1;
	if ((s[0] == 'L' || s[0] == 'l') && s[1] && sign == '+' && o->ninclude < 64)
		return o->includes[o->ninclude++] = s + 1, 1;
	if (pov_anim_switch(o, s))
		return 1;
	if ((s[0] == 'K' || s[0] == 'k') && parse_double(s + 1, &f))
		return o->clock = f, o->clock_given = 1, 1;
	if ((s[0] == 'A' || s[0] == 'a') && (s[1] == '\0' || parse_double(s + 1, &f)))
		return o->spp = sign == '+' ? (o->spp > 1 ? o->spp : 4) : 1, 1;
	if ((s[0] == 'D' || s[0] == 'd') && s[1] == '\0' && sign == '+')
		return 1; /* +D display on: arvo has no preview window */
	return 0;
}

/* The animation options agree: a subset inside the range, no --clock or
 * --frame with --frames (the loop sets them). Returns -1 or EX_USAGE. */
static int check_animation(struct options *o)
{
	if (!o->anim && (o->sub_first >= 0 || o->sub_last >= 0))
		return usage_error("--subset (+SF, +EF) needs a frame range (--frames or +KFF)");
	if (!o->anim)
		return -1;
	if (o->first_frame > o->last_frame)
		return usage_error("the first frame (%ld) is after the last (%ld)", o->first_frame, o->last_frame);
	if (o->clock_given)
		return usage_error("--clock and --frame cannot be combined with a frame range (--frames, +KFF): "
		                   "the range sets clock and frame_number");
	if (o->sub_first < 0)
		o->sub_first = o->first_frame;
	if (o->sub_last < 0)
		o->sub_last = o->last_frame;
	if (o->sub_first < o->first_frame || o->sub_last > o->last_frame || o->sub_first > o->sub_last)
		return usage_error("--subset %ld:%ld is not inside --frames %ld:%ld", o->sub_first, o->sub_last,
		                   o->first_frame, o->last_frame);
	return -1;
}

/* --region, --tile, --seed, --png-depth (value v): returns -1, or an exit code. */
static int pipeline_option(struct options *o, const char *a, const char *v)
{
	int n = 0;
	long x;
	if (!strcmp(a, "--region")) {
		int *r = o->region;
		if (sscanf(v, "%d:%d,%d:%d%n", &r[0], &r[1], &r[2], &r[3], &n) != 4 || v[n] ||
		    r[0] < 0 || r[2] < 0 || r[1] <= r[0] || r[3] <= r[2])
			return usage_error("bad value for --region: '%s' (expected x0:x1,y0:y1 with "
			                   "0 <= x0 < x1 and 0 <= y0 < y1)", v);
	} else if (!strcmp(a, "--tile")) {
		if (sscanf(v, "%d/%d%n", &o->tile_i, &o->tile_n, &n) != 2 || v[n] || o->tile_n < 1 ||
		    o->tile_i < 1 || o->tile_i > o->tile_n)
			return usage_error("bad value for --tile: '%s' (expected i/n with 1 <= i <= n)", v);
	} else if (!strcmp(a, "--seed")) {
		if (!parse_int(v, 0, 2147483647L, &x))
			return usage_error("bad value for --seed: '%s' (expected 0 to 2147483647)", v);
		o->seed = x;
	} else if (strcmp(v, "8") && strcmp(v, "16")) {
		return usage_error("bad value for --png-depth: '%s' (expected 8 or 16)", v);
	} else {
		o->png_depth = atoi(v);
	}
	return -1;
}

/* Reads argv into o; returns -1 to go on, else an exit code. */
static int parse_args(int argc, char **argv, struct options *o)
{
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i];
		const char *next = i + 1 < argc ? argv[i + 1] : NULL;
		long v;
#define NEED_ARG()                                                   \
	do {                                                             \
		if (!next)                                                   \
			return usage_error("option '%s' needs a value", a);      \
		i++;                                                         \
	} while (0)
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			usage(stdout);
			return EX_OK;
		} else if (!strcmp(a, "--version")) {
			printf("arvo %s\n", ARVO_VERSION);
			return EX_OK;
		} else if (!strcmp(a, "--check")) {
			o->action = ACT_CHECK;
		} else if (!strcmp(a, "--dump-tokens")) {
			o->action = ACT_TOKENS;
		} else if (!strcmp(a, "--dump-ast")) {
			o->action = ACT_AST;
		} else if (!strcmp(a, "--dump-scene")) {
			o->action = ACT_SCENE;
		} else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
			o->quiet = 1;
		} else if (!strcmp(a, "--stats")) {
			o->stats = 1;
		} else if (!strcmp(a, "--rays")) {
			NEED_ARG();
			if (!parse_int(next, 0, 1000000000000L, &v))
				return usage_error("bad value for --rays: '%s' (expected 0 to 1e12)", next);
			o->rays = v;
		} else if (!strcmp(a, "--tolerance")) {
			NEED_ARG();
			double t;
			if (!parse_double(next, &t) || !(t >= 1e-5 && t <= 0.5))
				return usage_error("bad value for --tolerance: '%s' (expected 1e-5 to 0.5)", next);
			o->tolerance = t;
		} else if (!strcmp(a, "--method")) {
			NEED_ARG();
			if (strcmp(next, "point") && strcmp(next, "shaft"))
				return usage_error("bad value for --method: '%s' (expected point or shaft)", next);
			o->method = (strcmp(next, "point") ? ILLUM_SHAFT : ILLUM_POINT) + 1;
		} else if (!strcmp(a, "--dump-maps")) {
			NEED_ARG();
			o->dump_maps = next;
		} else if (!strcmp(a, "--save-maps") || !strcmp(a, "--load-maps")) {
			NEED_ARG();
			*(a[2] == 's' ? &o->save_maps : &o->load_maps) = next;
		} else if (!strcmp(a, "--passes")) {
			NEED_ARG();
			if (strcmp(next, "rgb") && strcmp(next, "spectral"))
				return usage_error("bad value for --passes: '%s' (expected rgb or spectral)", next);
			o->passes = (strcmp(next, "rgb") ? PASSES_SPECTRAL : PASSES_RGB) + 1;
		} else if (!strcmp(a, "--region") || !strcmp(a, "--tile") || !strcmp(a, "--seed") ||
		           !strcmp(a, "--png-depth")) {
			NEED_ARG();
			int rc = pipeline_option(o, a, next);
			if (rc >= 0)
				return rc;
		} else if (!strcmp(a, "--half")) {
			o->half = 1;
		} else if (!strcmp(a, "--display") || !strcmp(a, "--view") || !strcmp(a, "--ocio-config")) {
			NEED_ARG();
			*(a[2] == 'd' ? &o->display : a[2] == 'v' ? &o->view : &o->ocio_config) = next;
		} else if (!strcmp(a, "--compression")) {
			NEED_ARG();
			if (out_exr_compression_parse(next, &o->compression) != 0)
				return usage_error("unknown compression '%s' (expected none, zip, zips, piz or rle)", next);
		} else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
			NEED_ARG();
			if (!add_output(o, next))
				return usage_error("too many output files (at most %s)", "16");
		} else if (!strcmp(a, "--frames") || !strcmp(a, "--subset")) {
			NEED_ARG();
			long fa, fb;
			if (!parse_range(next, &fa, &fb))
				return usage_error("bad value for %s: '%s' (expected FIRST:LAST, 0 <= FIRST <= LAST)", a, next);
			if (a[2] == 'f')
				o->first_frame = fa, o->last_frame = fb, o->anim = 1;
			else
				o->sub_first = fa, o->sub_last = fb;
		} else if (!strcmp(a, "-M") || !strcmp(a, "--depfile")) {
			NEED_ARG();
			o->depfile = next;
		} else if (!strcmp(a, "--allow-read")) {
			NEED_ARG();
			struct stat sb;
			if (stat(next, &sb) != 0 || !S_ISDIR(sb.st_mode))
				return usage_error("bad value for --allow-read: '%s' is not a directory", next);
			if (o->nallow >= 64)
				return usage_error("too many --allow-read directories (at most %s)", "64");
			o->allow_read[o->nallow++] = next;
		} else if (!strcmp(a, "-I")) {
			NEED_ARG();
			if (o->ninclude >= 64)
				return usage_error("too many -I directories (at most %s)", "64");
			o->includes[o->ninclude++] = next;
		} else if (!strncmp(a, "-I", 2)) {
			if (o->ninclude >= 64)
				return usage_error("too many -I directories (at most %s)", "64");
			o->includes[o->ninclude++] = a + 2;
		} else if (!strcmp(a, "-D") && !(next && strchr(next, '='))) {
			continue; /* POV-Ray's -D: display off (arvo has no preview window) */
		} else if (!strcmp(a, "-D") || !strncmp(a, "Declare=", 8) || !strncmp(a, "-D", 2)) {
			if (!strcmp(a, "-D"))
				NEED_ARG();
			const char *d = !strcmp(a, "-D") ? next : a[0] == 'D' ? a + 8 : a + 2;
			if (!valid_define(d))
				return usage_error("bad declaration '%s' (expected NAME=number or NAME=\"string\")", d);
			int nlen = (int)(strchr(d, '=') - d); /* (valid_define: there is one) */
			const char *why = eval_undeclarable(d, nlen);
			if (why)
				return usage_error("bad declaration '%s': '%.*s' is %s and cannot be declared%s", d, nlen, d,
				                   why, !strncmp(d, "clock=", 6) ? " (see --clock)" : "");
			if (o->ndefines >= 256)
				return usage_error("too many -D declarations (at most %s)", "256");
			o->defines[o->ndefines++] = d;
		} else if (!strcmp(a, "--width") || !strcmp(a, "--height") || !strcmp(a, "--spp") ||
		           !strcmp(a, "--threads") || !strcmp(a, "--frame")) {
			NEED_ARG();
			if (!parse_int(next, a[2] == 'f' ? -1000000000L : 1, a[2] == 't' ? 1024 : 1000000000L, &v))
				return usage_error("bad value for %s: '%s' (expected a positive whole number)", a, next);
			int *dst = a[2] == 'w' ? &o->width : a[2] == 'h' ? &o->height : a[3] == 'p' ? &o->spp
			         : a[2] == 't' ? &o->threads : &o->frame;
			if ((a[2] == 'w' || a[2] == 'h') && v > 65536)
				return usage_error("image size too large: '%s' (at most 65536)", next);
			*dst = (int)v;
			o->clock_given |= dst == &o->frame;
		} else if (!strcmp(a, "--clock")) {
			NEED_ARG();
			if (!parse_double(next, &o->clock))
				return usage_error("bad value for --clock: '%s'", next);
			o->clock_given = 1;
		} else if (!strcmp(a, "--max-iterations") || !strcmp(a, "--max-calls") || !strcmp(a, "--max-objects") ||
		           !strcmp(a, "--max-steps")) {
			NEED_ARG();
			if (!parse_int(next, 1, 1L << 50, &v))
				return usage_error("bad value for %s: '%s'", a, next);
			*(a[6] == 'i' ? &o->max_iterations : a[6] == 'c' ? &o->max_calls : a[6] == 'o' ? &o->max_objects
			  : &o->max_steps) = v;
		} else if (!strcmp(a, "--max-memory")) {
			NEED_ARG();
			o->max_memory = mem_parse_size(next);
			if (o->max_memory < ((size_t)16 << 20))
				return usage_error("bad value for --max-memory: '%s' (expected a size of at least 16M, e.g. 512M or 4G)",
				                   next);
		} else if ((a[0] == '+' || a[0] == '-') && a[1] && a[1] != '-' && pov_switch(o, a)) {
			continue;
		} else if (a[0] == '-' && a[1] && !pov_unsupported(a)) {
			return usage_error("unknown option '%s'", a);
		} else if ((a[0] == '+' || a[0] == '-') && pov_unsupported(a)) {
			return usage_error("%s", pov_unsupported(a));
		} else if (a[0] == '+' && a[1]) {
			return usage_error("unknown or malformed POV-Ray switch '%s'", a);
		} else if (strlen(a) > 4 && !strcasecmp(a + strlen(a) - 4, ".ini")) {
			return usage_error("POV-Ray INI files are not read ('%s'): give its settings as options, e.g. "
			                   "Width=640 Height=480 Antialias=on as --width 640 --height 480 --spp 4", a);
		} else {
			if (o->scene)
				return usage_error("more than one scene file given ('%s')", a);
			o->scene = a;
		}
#undef NEED_ARG
	}
	if (!o->scene)
		return usage_error("no scene file given");
	if ((long long)o->width * o->height > MAX_PIXELS)
		return usage_error("image too large: %dx%d is %lld pixels (at most %lld)", o->width, o->height,
		                   (long long)o->width * o->height, (long long)MAX_PIXELS);
	return check_animation(o);
}

/* -M: collects the files a scene reads. */
struct deps {
	char **files;
	int n;
};

static void dep_add(const char *path, void *ctx)
{
	struct deps *d = ctx;
	for (int i = 0; i < d->n; i++)
		if (strcmp(d->files[i], path) == 0)
			return;
	d->files = mem_realloc(d->files, sizeof *d->files * (size_t)(d->n + 1));
	d->files[d->n++] = mem_strdup(path);
}

/* Writes a path for make: spaces and '#' escaped with '\\', '$' doubled. */
static void put_make_path(FILE *f, const char *p)
{
	for (; *p; p++) {
		if (*p == ' ' || *p == '#' || *p == '\t')
			fputc('\\', f);
		else if (*p == '$')
			fputc('$', f);
		fputc(*p, f);
	}
}

/* The depfile, like gcc -MMD -MP: "targets: the scene and every file it
 * read", then an empty rule for each file but the scene, so make does not
 * fail when one disappears. */
static int write_depfile(const struct options *o, const struct deps *d, const struct deps *targets)
{
	char tmp[PATH_MAX + 32];
	int fd = out_tmp_create(o->depfile, tmp, sizeof tmp);
	FILE *f = fd < 0 ? NULL : fdopen(fd, "w");
	if (!f) {
		int e = errno;
		if (fd >= 0)
			close(fd), out_tmp_finish(tmp, o->depfile, 0);
		fprintf(stderr, "arvo: error: cannot create '%s': %s\n", o->depfile, strerror(e));
		return EX_CANTCREAT;
	}
	for (int i = 0; i < targets->n; i++) {
		if (i)
			fputc(' ', f);
		put_make_path(f, targets->files[i]);
	}
	fputc(':', f);
	for (int i = 0; i < d->n; i++) {
		fputs(i % 4 == 3 ? " \\\n " : " ", f);
		put_make_path(f, d->files[i]);
	}
	fputc('\n', f);
	for (int i = 1; i < d->n; i++) {
		fputc('\n', f);
		put_make_path(f, d->files[i]);
		fputs(":\n", f);
	}
	int bad = fflush(f) != 0 || ferror(f), e = errno;
	if (fclose(f) != 0 && !bad)
		bad = 1, e = errno;
	if (out_tmp_finish(tmp, o->depfile, !bad) != 0)
		bad = 1, e = errno;
	if (bad) {
		fprintf(stderr, "arvo: error: cannot write '%s': %s\n", o->depfile, strerror(e));
		return EX_IOERR;
	}
	return EX_OK;
}

/* --dump-tokens and --dump-ast work on the scene file alone. */
static int dump_front(const struct options *o, struct diag *dg)
{
	size_t len;
	char *text = srcfile_read(o->scene, &len);
	if (!text) {
		fprintf(stderr, "arvo: error: cannot open '%s': %s\n", o->scene, strerror(errno));
		return EX_NOINPUT;
	}
	int file = srcfile_add(mem_strdup(o->scene), text, len);
	struct arena a;
	arena_init(&a);
	if (o->action == ACT_TOKENS) {
		struct lexer lx;
		lex_init(&lx, file, dg, &a);
		lex_dump(stdout, &lx);
	} else {
		struct node *root = parse_file(file, dg, &a);
		if (dg->errors == 0)
			ast_dump(stdout, root);
	}
	arena_free(&a);
	return dg->errors ? EX_DATAERR : EX_OK;
}

/* The default output name: the scene's base name with .exr. */
static const char *default_output(const char *scene, char *buf, size_t size)
{
	const char *base = strrchr(scene, '/');
	base = base ? base + 1 : scene;
	const char *dot = strrchr(base, '.');
	int n = dot ? (int)(dot - base) : (int)strlen(base);
	snprintf(buf, size, "%.*s.exr", n, base);
	return buf;
}

/* The output format from the file name: 'e' (.exr), 'p' (.png), 0 (other). */
static int output_kind(const char *path)
{
	const char *dot = strrchr(path, '.');
	if (dot && strchr(dot, '/') == NULL) {
		if (!strcasecmp(dot, ".exr"))
			return 'e';
		if (!strcasecmp(dot, ".png"))
			return 'p';
	}
	return 0;
}

/* Can path be written? Creates and removes a temporary beside it, as the
 * writers will, so every reason (no directory, no permission, read-only
 * file system) shows before any work. Reports and returns 73 if not. */
static int check_creatable(const char *path)
{
	char tmp[PATH_MAX + 32];
	struct stat sb;
	if (stat(path, &sb) == 0 && !S_ISREG(sb.st_mode)) { /* a rename would replace a device or a directory */
		fprintf(stderr, "arvo: error: cannot create '%s': %s\n", path,
		        S_ISDIR(sb.st_mode) ? strerror(EISDIR) : "not a regular file");
		return EX_CANTCREAT;
	}
	int fd = out_tmp_create(path, tmp, sizeof tmp);
	if (fd < 0) {
		fprintf(stderr, "arvo: error: cannot create '%s': %s\n", path, strerror(errno));
		return EX_CANTCREAT;
	}
	close(fd);
	out_tmp_finish(tmp, path, 0);
	return EX_OK;
}

/* --tile i/n becomes a region (the i-th band of rows); checks the region
 * lies in the frame and goes to an EXR. Returns -1, or an exit code. */
static int resolve_region(struct options *o, int kind)
{
	int *r = o->region;
	if (o->tile_n > 0 && r[1] > 0)
		return usage_error("--region and --tile cannot be used together");
	if (o->tile_n > o->height)
		return usage_error("--tile %d/%d: more tiles than the image has rows (%d)", o->tile_i,
		                   o->tile_n, o->height);
	if (o->tile_n > 0) {
		r[0] = 0, r[1] = o->width;
		r[2] = (int)((long)(o->tile_i - 1) * o->height / o->tile_n);
		r[3] = (int)((long)o->tile_i * o->height / o->tile_n);
	}
	if (r[1] > 0 && (r[1] > o->width || r[3] > o->height))
		return usage_error("--region %d:%d,%d:%d lies outside the %dx%d image", r[0], r[1], r[2],
		                   r[3], o->width, o->height);
	if (r[1] > 0 && kind != 'e')
		return usage_error("a partial render (--region, --tile) needs an .exr output");
	return -1;
}

/* The EXR header's record of the render: camera, settings, scene, version. */
static void exr_meta(const struct options *o, const struct scene *scene, struct out_exr_meta *m)
{
	struct cam c;
	double c2w[16], w2c[16], ndc[16];
	cam_setup(&c, &scene->camera);
	cam_matrices(&c, c2w, w2c, ndc);
	m->has_camera = 1;
	for (int i = 0; i < 16; i++) {
		m->camera_to_world[i] = (float)c2w[i];
		m->world_to_camera[i] = (float)w2c[i];
		m->world_to_ndc[i] = (float)ndc[i];
	}
	const struct illum_settings *il = &scene->gs.illum;
	int method = o->method ? o->method - 1 : (int)il->method, passes = o->passes ? o->passes - 1 : (int)il->passes;
	out_meta_add(m, "arvo:version", "%s", ARVO_VERSION);
	out_meta_add(m, "arvo:spp", "%d", o->spp > 0 ? o->spp : 1);
	if (o->rays == 0 || (o->rays < 0 && scene->nlights == 0))
		out_meta_add(m, "arvo:rays", "off");
	else if (o->load_maps)
		out_meta_add(m, "arvo:rays", "loaded from %s", o->load_maps);
	else
		out_meta_add(m, "arvo:rays", "%ld", o->rays > 0 ? o->rays : il->rays > 0 ? il->rays
		             : il->count > 0 ? il->count : 1000000);
	out_meta_add(m, "arvo:method", "%s", method == ILLUM_SHAFT ? "shaft" : "point");
	out_meta_add(m, "arvo:passes", "%s", passes == PASSES_SPECTRAL ? "spectral" : "rgb");
	if (o->tolerance > 0 || il->tolerance > 0)
		out_meta_add(m, "arvo:tolerance", "%g", o->tolerance > 0 ? o->tolerance : il->tolerance);
	out_meta_add(m, "arvo:seed", "%ld", o->seed);
}

/* What runs outside the evaluator, for out-of-memory messages. */
static const char *volatile mem_phase = "reading the scene";

/* Over the --max-memory budget outside the evaluator (which reports at the
 * statement it was running): reading the scene file, or rendering (the
 * light pass's maps, the acceleration structure, the framebuffer). Exit 70. */
static void over_budget(size_t request)
{
	static atomic_int once;
	char size[32];
	if (atomic_exchange(&once, 1)) /* another thread is reporting it */
		for (;;)
			pause();
	mem_format_size(size, sizeof size, mem_budget());
	(void)request;
	fprintf(stderr, "arvo: error: out of memory: %s needs more than the %s that --max-memory allows\n", mem_phase, size);
	out_tmp_remove_all();
	exit(EX_SOFTWARE);
}

/* Expands a frame pattern in a file name: %d, %Nd or %0Nd become the frame
 * number, %% a '%'. In an animation (digits > 0) a name without a pattern
 * gets POV-Ray's numbering: the number, zero-padded to digits, before the
 * extension. Returns 0 for any other '%' or a name too long. */
static int frame_name(const char *pat, long frame, int digits, char *buf, size_t size)
{
	size_t k = 0;
	int pattern = 0;
	for (const char *p = pat; *p; p++) {
		char piece[32];
		if (*p != '%') {
			piece[0] = *p, piece[1] = '\0';
		} else if (p[1] == '%') {
			strcpy(piece, "%"), p++;
		} else {
			int zero = p[1] == '0', width = 0;
			const char *q = p + 1 + zero;
			while (*q >= '0' && *q <= '9' && width < 100)
				width = width * 10 + (*q++ - '0');
			if (*q != 'd')
				return 0;
			snprintf(piece, sizeof piece, zero ? "%0*ld" : "%*ld", width, frame);
			p = q, pattern = 1;
		}
		size_t n = strlen(piece);
		if (k + n >= size)
			return 0;
		memcpy(buf + k, piece, n + 1), k += n;
	}
	if (pattern || digits == 0)
		return 1;
	const char *slash = strrchr(buf, '/'), *dot = strrchr(buf, '.');
	size_t stem = dot && (!slash || dot > slash) ? (size_t)(dot - buf) : k;
	char tail[PATH_MAX];
	snprintf(tail, sizeof tail, "%s", buf + stem);
	int n = snprintf(buf + stem, size - stem, "%0*ld%s", digits, frame, tail);
	return n > 0 && (size_t)n < size - stem;
}

/* The digits of POV-Ray's frame numbering (those of the last frame), or 0
 * when there is no animation. */
static int frame_digits(const struct options *o)
{
	int d = 1;
	if (!o->anim)
		return 0;
	for (long f = o->last_frame; f >= 10; f /= 10)
		d++;
	return d;
}

/* Checks the output names before any work: a known format, a valid frame
 * pattern, and a pattern in --save-maps when several frames are rendered. */
static int check_outputs(const struct options *o)
{
	char name[PATH_MAX], def[PATH_MAX];
	int n = o->noutputs ? o->noutputs : 1;
	for (int i = 0; i < n; i++) {
		const char *pat = o->noutputs ? o->outputs[i] : default_output(o->scene, def, sizeof def);
		if (!frame_name(pat, 0, frame_digits(o), name, sizeof name))
			return usage_error("bad frame pattern in '%s' (expected %%d, %%4d or %%04d; %%%% for a '%%')", pat);
		if (o->action == ACT_RENDER && !output_kind(name))
			return usage_error("unknown output format '%s' (expected a .exr or .png name)", pat);
	}
	const char *maps[2] = {o->save_maps, o->load_maps};
	for (int i = 0; i < 2; i++)
		if (maps[i] && !frame_name(maps[i], 0, 0, name, sizeof name))
			return usage_error("bad frame pattern in '%s' (expected %%d, %%4d or %%04d; %%%% for a '%%')", maps[i]);
	if (o->anim && o->sub_last > o->sub_first && o->save_maps && !strchr(o->save_maps, '%'))
		return usage_error("--save-maps '%s' would be overwritten by every frame: give it a frame "
		                   "pattern such as %%04d", o->save_maps);
	return EX_OK;
}

/* Are all the outputs EXRs (a partial render needs it)? */
static int all_exr(const struct options *o)
{
	char def[PATH_MAX];
	for (int i = 0; i < (o->noutputs ? o->noutputs : 1); i++)
		if (output_kind(o->noutputs ? o->outputs[i] : default_output(o->scene, def, sizeof def)) != 'e')
			return 0;
	return 1;
}

/* Sets clock, frame_number and the animation constants for one frame, as
 * POV-Ray 3.7 does: clock runs linearly from the first clock at the first
 * frame to the last clock at the last frame, and clock_on is true in every
 * frame of an animation (and whenever --clock or --frame is given). */
static void set_frame(const struct options *o, struct eval_options *eo, long frame)
{
	eo->clock = o->clock;
	eo->frame = o->frame;
	eo->clock_on = o->clock_given;
	if (!o->anim)
		return;
	long span = o->last_frame - o->first_frame;
	eo->clock_on = 1;
	eo->frame = (int)frame;
	eo->initial_frame = (int)o->first_frame, eo->final_frame = (int)o->last_frame;
	eo->initial_clock = o->first_clock, eo->final_clock = o->last_clock;
	eo->clock_delta = span > 0 ? (o->last_clock - o->first_clock) / (double)span : 0;
	eo->clock = o->first_clock + eo->clock_delta * (double)(frame - o->first_frame);
}

/* Render: the light pass and the eye pass into one framebuffer, then each
 * output: the EXR, or the PNG through OCIO. */
static int render_and_write(const struct options *o, const struct scene *scene, char (*outputs)[PATH_MAX],
                            int noutputs, const char *save_maps, const char *load_maps, struct diag *dg)
{
	int rc = EX_OK;
	for (int i = 0; i < noutputs && !rc; i++) /* each frame's names (the first were checked before any work) */
		rc = check_creatable(outputs[i]);
	if (!rc && save_maps)
		rc = check_creatable(save_maps);
	if (rc)
		return rc;
	struct render_opts ro = {o->width, o->height, o->spp > 0 ? o->spp : 1, o->threads, o->quiet,
	                         o->ocio_config, o->rays < 0 ? 0 : o->rays == 0 ? -1 : o->rays, o->dump_maps,
	                         save_maps, load_maps, o->method, o->tolerance, o->passes,
	                         {o->region[0], o->region[1], o->region[2], o->region[3]}, o->seed, true};
	for (int i = 0; i < noutputs; i++) /* PNG outputs read R G B alone */
		ro.beauty_only &= output_kind(outputs[i]) != 'e';
	struct render_stats st;
	struct framebuffer *fb;
	if ((rc = render(scene, &ro, dg, &fb, &st)) != 0)
		return rc;
	for (int i = 0; i < noutputs && !rc; i++) {
		if (output_kind(outputs[i]) == 'e') {
			static struct out_exr_meta meta;
			exr_meta(o, scene, &meta);
			struct out_exr_opts eo = {o->half, o->compression, scene->name, &meta, o->threads};
			rc = out_exr_write(fb, outputs[i], &eo, dg);
		} else {
			struct out_png_opts po = {o->ocio_config, o->display, o->view, NULL, scene_pov_view(scene),
			                          o->png_depth, o->threads};
			rc = out_png_write(fb, outputs[i], &po, dg);
		}
	}
	fb_free(fb);
	if (!rc && o->stats)
		render_print_stats(stderr, &st);
	return rc;
}

/* One frame: evaluates the scene with this frame's clock, then dumps it or
 * renders it into every output. The output names, with the frame number
 * filled in, are added to targets (the depfile's targets). */
static int run_frame(const struct options *o, struct eval_options *eo, struct diag *dg, long frame,
                     struct deps *targets)
{
	char names[16][PATH_MAX], def[PATH_MAX], save[PATH_MAX], load[PATH_MAX];
	int n = o->noutputs ? o->noutputs : 1, digits = frame_digits(o);
	for (int i = 0; i < n; i++) {
		frame_name(o->noutputs ? o->outputs[i] : default_output(o->scene, def, sizeof def), frame, digits,
		           names[i], sizeof names[i]);
		dep_add(names[i], targets);
	}
	if (o->save_maps)
		frame_name(o->save_maps, frame, 0, save, sizeof save);
	if (o->load_maps)
		frame_name(o->load_maps, frame, 0, load, sizeof load);
	set_frame(o, eo, frame);
	if (o->anim && !o->quiet && o->action == ACT_RENDER)
		fprintf(stderr, "arvo: frame %ld (%ld to %ld), clock %g: %s\n", frame, o->sub_first, o->sub_last,
		        eo->clock, names[0]);
	struct scene scene;
	mem_phase = "reading the scene";
	int rc = eval_scene(o->scene, eo, dg, &scene);
	if (o->load_maps && eo->on_file) /* after the scene: the depfile lists the scene first */
		eo->on_file(load, eo->on_file_ctx);
	if (rc == EX_OK) {
		if (o->action == ACT_SCENE)
			scene_dump(stdout, &scene);
		else if (o->action == ACT_RENDER) {
			mem_phase = "rendering";
			rc = render_and_write(o, &scene, names, n, o->save_maps ? save : NULL,
			                      o->load_maps ? load : NULL, dg);
		}
	}
	scene_free(&scene);
	return rc;
}

/* -M also names the OCIO config when the render reads it: for a PNG output
 * or a PNG image_map. */
static void dep_add_ocio(const struct options *o, const struct deps *targets, struct deps *deps)
{
	int png = 0;
	for (int i = 0; i < targets->n; i++)
		png |= output_kind(targets->files[i]) == 'p' && o->action == ACT_RENDER;
	for (int i = 0; i < deps->n; i++)
		png |= output_kind(deps->files[i]) == 'p';
	const char *cfg = png ? out_ocio_config_path(o->ocio_config) : NULL;
	if (cfg) {
		char real[PATH_MAX];
		dep_add(realpath(cfg, real) ? real : cfg, deps);
	}
}

/* Checks before any work what a render will write or read besides the
 * scene: the OCIO config (66) and display/view (64) when a PNG is written
 * or an OCIO option is given; every output of the first frame, the
 * --save-maps file, a --dump-maps file and the depfile can be created (73);
 * the --load-maps file can be read (66). */
static int check_before_work(const struct options *o, struct diag *dg)
{
	char name[PATH_MAX], def[PATH_MAX];
	int n = o->noutputs ? o->noutputs : 1, png = o->ocio_config || o->display || o->view, rc = EX_OK;
	long frame = o->anim ? o->sub_first : 0;
	for (int i = 0; i < n; i++) {
		frame_name(o->noutputs ? o->outputs[i] : default_output(o->scene, def, sizeof def), frame,
		           frame_digits(o), name, sizeof name);
		png |= output_kind(name) == 'p';
		if (!rc)
			rc = check_creatable(name);
	}
	if (png) {
		struct ocio_config *cfg;
		const char *disp, *view;
		int r = out_ocio_load(o->ocio_config, &cfg, dg);
		if (r)
			return r;
		r = out_ocio_pick_view(cfg, o->display, o->view, &disp, &view, dg);
		ocio_config_free(cfg);
		if (r)
			return r;
	}
	struct stat sb;
	if (!rc && o->dump_maps && (stat(o->dump_maps, &sb) != 0 || !S_ISDIR(sb.st_mode))) {
		fprintf(stderr, "arvo: error: cannot write maps into '%s': not a directory\n", o->dump_maps);
		return EX_CANTCREAT;
	}
	if (!rc && o->dump_maps) {
		snprintf(name, sizeof name, "%s/map", o->dump_maps);
		rc = check_creatable(name);
	}
	if (!rc && o->save_maps && frame_name(o->save_maps, frame, 0, name, sizeof name))
		rc = check_creatable(name);
	if (!rc && o->depfile)
		rc = check_creatable(o->depfile);
	if (!rc && o->load_maps && frame_name(o->load_maps, frame, 0, name, sizeof name) &&
	    access(name, R_OK) != 0) {
		fprintf(stderr, "arvo: error: cannot open '%s': %s\n", name, strerror(errno));
		return EX_NOINPUT;
	}
	return rc;
}

/* SIGINT, SIGTERM, SIGHUP: remove the temporaries being written (the files
 * they would replace stay untouched) and exit 128 + the signal. */
static void on_signal(int sig)
{
	out_tmp_remove_all();
	_exit(128 + sig);
}

static void install_signals(void)
{
	struct sigaction sa;
	memset(&sa, 0, sizeof sa);
	sa.sa_handler = on_signal;
	sigemptyset(&sa.sa_mask);
	const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
	for (int i = 0; i < 3; i++)
		sigaction(sigs[i], &sa, NULL);
	signal(SIGXFSZ, SIG_IGN); /* past ulimit -f: write fails with EFBIG, exit 74 */
}

int main(int argc, char **argv)
{
	if (argc > 1 && (!strcmp(argv[1], "compare") || !strcmp(argv[1], "merge")))
		return argv[1][0] == 'c' ? tool_compare(argc - 1, argv + 1) : tool_merge(argc - 1, argv + 1);
	struct options o;
	memset(&o, 0, sizeof o);
	o.width = 320, o.height = 240, o.spp = 1, o.threads = 0, o.rays = -1;
	o.max_iterations = 10000000, o.max_calls = 1000000, o.max_objects = 1000000, o.max_steps = 1000000000;
	o.first_frame = o.last_frame = 1, o.first_clock = 0, o.last_clock = 1, o.sub_first = o.sub_last = -1;
	int rc = parse_args(argc, argv, &o);
	if (rc >= 0)
		return rc;
	mem_set_budget(o.max_memory ? o.max_memory : mem_default_budget(), over_budget);
	struct diag dg;
	diag_init(&dg, stderr);
	install_signals();
	if (o.action == ACT_TOKENS || o.action == ACT_AST) {
		rc = dump_front(&o, &dg);
		srcfile_free_all();
		return rc;
	}
	if ((rc = check_outputs(&o)) != EX_OK)
		return rc;
	if (o.action == ACT_RENDER && (rc = resolve_region(&o, all_exr(&o) ? 'e' : 'p')) >= 0)
		return rc;
	if (o.action == ACT_RENDER && (rc = check_before_work(&o, &dg)) != EX_OK)
		return rc;
	rc = EX_OK;
	find_data_dir(&o);

	struct eval_options eo;
	eval_default_options(&eo);
	eo.include_dirs = o.includes;
	eo.ninclude = o.ninclude;
	eo.stdlib_dir = o.stdlib_dir[0] ? o.stdlib_dir : NULL;
	eo.pov_include_dir = pov_include_dir();
	eo.allow_read = o.allow_read;
	eo.nallow = o.nallow;
	eo.defines = o.defines;
	eo.ndefines = o.ndefines;
	eo.width = o.width;
	eo.height = o.height;
	eo.max_iterations = o.max_iterations;
	eo.max_calls = o.max_calls;
	eo.max_objects = o.max_objects;
	eo.max_steps = o.max_steps;
	struct deps deps = {NULL, 0}, targets = {NULL, 0};
	if (o.depfile) {
		eo.on_file = dep_add;
		eo.on_file_ctx = &deps;
	}
	long first = o.anim ? o.sub_first : 0, last = o.anim ? o.sub_last : 0;
	for (long f = first; f <= last && rc == EX_OK; f++)
		rc = run_frame(&o, &eo, &dg, f, &targets);
	if (rc == EX_OK && o.depfile) {
		dep_add_ocio(&o, &targets, &deps);
		rc = write_depfile(&o, &deps, &targets);
	}
	if (fflush(stdout) != 0 && rc == EX_OK)
		rc = EX_IOERR;
	for (int i = 0; i < deps.n; i++)
		free(deps.files[i]);
	for (int i = 0; i < targets.n; i++)
		free(targets.files[i]);
	free(deps.files);
	free(targets.files);
	srcfile_free_all();
	return rc;
}
