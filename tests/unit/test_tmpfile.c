/* SPDX-License-Identifier: MIT */
/* test_tmpfile.c: temp file + rename (tracer/output/tmpfile.c) and the
 * diag's status idiom (common/diag.c). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../../common/diag.h"
#include "../../tracer/output/tmpfile.h"
#include "test.h"

static char dir[64];

static const char *in_dir(const char *name)
{
	static char p[128];
	snprintf(p, sizeof p, "%s/%s", dir, name);
	return p;
}

static int exists(const char *path) { return access(path, F_OK) == 0; }

static char *slurp(const char *path)
{
	static char buf[64];
	FILE *f = fopen(path, "r");
	size_t n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
	if (f)
		fclose(f);
	buf[n] = '\0';
	return buf;
}

/* A committed temp file replaces the target; its name is gone. */
static void t_commit(void)
{
	char tmp[256], target[128];
	snprintf(target, sizeof target, "%s", in_dir("a.exr"));
	int fd = out_tmp_create(target, tmp, sizeof tmp);
	CHECK(fd >= 0);
	CHECK(strncmp(tmp, target, strlen(target)) == 0 && strstr(tmp, ".tmp.") != NULL);
	CHECK(write(fd, "new", 3) == 3);
	close(fd);
	CHECK(!exists(target) && exists(tmp));
	CHECK(out_tmp_finish(tmp, target, 1) == 0);
	CHECK(exists(target) && !exists(tmp));
	CHECK_STR(slurp(target), "new");
}

/* An abandoned temp file is removed and the earlier target kept. */
static void t_abandon(void)
{
	char tmp[256], target[128];
	snprintf(target, sizeof target, "%s", in_dir("b.exr"));
	FILE *f = fopen(target, "w");
	fputs("old", f);
	fclose(f);
	int fd = out_tmp_create(target, tmp, sizeof tmp);
	CHECK(fd >= 0 && write(fd, "half", 4) == 4);
	close(fd);
	CHECK(out_tmp_finish(tmp, target, 0) == 0);
	CHECK(!exists(tmp));
	CHECK_STR(slurp(target), "old");
}

/* out_tmp_remove_all (what the signal handler calls) removes every open
 * temporary and nothing else. */
static void t_remove_all(void)
{
	char t1[256], t2[256], target[128];
	snprintf(target, sizeof target, "%s", in_dir("c.exr"));
	int a = out_tmp_create(target, t1, sizeof t1), b = out_tmp_create(in_dir("d.png"), t2, sizeof t2);
	CHECK(a >= 0 && b >= 0);
	close(a), close(b);
	CHECK(exists(t1) && exists(t2) && exists(in_dir("b.exr")));
	out_tmp_remove_all();
	CHECK(!exists(t1) && !exists(t2) && exists(in_dir("b.exr")));
	CHECK(out_tmp_finish(t1, target, 0) == 0 && out_tmp_finish(t2, in_dir("d.png"), 0) == 0);
	out_tmp_remove_all(); /* the slots were freed: nothing left to do */
}

/* A temp file in a missing directory fails with errno set; nothing is registered. */
static void t_no_dir(void)
{
	char tmp[256];
	errno = 0;
	CHECK(out_tmp_create(in_dir("no/such/e.exr"), tmp, sizeof tmp) == -1 && errno == ENOENT);
	char small[8];
	CHECK(out_tmp_create(in_dir("f.exr"), small, sizeof small) == -1 && errno == ENAMETOOLONG);
}

/* diag_fail reports, counts, keeps the text and returns the status. */
static void t_diag_fail(void)
{
	struct diag dg;
	diag_init(&dg, NULL);
	CHECK(diag_fail(&dg, FAIL_WRITE, srcloc_none(), "cannot write '%s': %s", "x.exr", "disk full") == 74);
	CHECK(dg.errors == 1);
	CHECK_STR(dg.last, "cannot write 'x.exr': disk full");
	diag_warning(&dg, srcloc_none(), "w %d", 3);
	CHECK(dg.warnings == 1 && dg.errors == 1);
	CHECK_STR(dg.last, "w 3");
	CHECK(FAIL_INPUT == 66 && FAIL_CREATE == 73 && FAIL_USAGE == 64);
}

int main(void)
{
	snprintf(dir, sizeof dir, "%s/arvo-tmpfile.XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
	if (!mkdtemp(dir)) {
		perror("mkdtemp");
		return 1;
	}
	RUN(t_commit);
	RUN(t_abandon);
	RUN(t_remove_all);
	RUN(t_no_dir);
	RUN(t_diag_fail);
	const char *names[] = {"a.exr", "b.exr", "c.exr", "d.png"};
	for (int i = 0; i < 4; i++)
		remove(in_dir(names[i]));
	rmdir(dir);
	return test_done();
}
