/* SPDX-License-Identifier: MIT */
/* test_progress.c: the plain progress lines (common/progress.c): a line for
 * every tenth passed, once and in order, even when one step passes several
 * tenths (two threads finishing tiles at once), and no bar or line when
 * quiet. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../../common/progress.h"
#include "test.h"

/* The percentages of the "arvo: progress: what N% (...)" lines in f, as
 * "10 20 …", and the count of "done" lines in *done. */
static void percents(FILE *f, char *out, size_t n, int *done)
{
	char line[256];
	size_t k = 0;
	*done = 0;
	out[0] = '\0';
	rewind(f);
	while (fgets(line, sizeof line, f)) {
		int pc;
		if (sscanf(line, "arvo: progress: eye pass %d%%", &pc) == 1)
			k += (size_t)snprintf(out + k, n - k, "%s%d", k ? " " : "", pc);
		else if (strstr(line, "arvo: progress: eye pass done ("))
			++*done;
	}
}

static void t_every_tenth(void)
{
	/* 16 tiles whose completions arrive 1, then 4 at once (1 -> 5: 10 %
	 * to 30 %), then 11 at once (5 -> 16: to the end) */
	FILE *f = tmpfile();
	struct progress p;
	char got[128];
	int done;
	progress_init(&p, PROGRESS_LINES, f);
	progress_begin(&p, "eye pass", 16);
	progress_step(&p, 1);
	progress_step(&p, 4);
	percents(f, got, sizeof got, &done);
	CHECK_STR(got, "10 20 30");
	progress_step(&p, 11);
	progress_end(&p);
	percents(f, got, sizeof got, &done);
	CHECK_STR(got, "10 20 30 40 50 60 70 80 90");
	CHECK(done == 1);
	progress_destroy(&p);
	fclose(f);
}

static void t_quiet(void)
{
	FILE *f = tmpfile();
	struct progress p;
	progress_init(&p, progress_mode_for(1), f);
	progress_begin(&p, "eye pass", 16);
	progress_step(&p, 16);
	progress_end(&p);
	CHECK(ftell(f) == 0);
	progress_destroy(&p);
	fclose(f);
}

int main(void)
{
	RUN(t_every_tenth);
	RUN(t_quiet);
	return test_done();
}
