/* SPDX-License-Identifier: MIT */
/* test.h: a tiny TAP-producing unit test harness (one binary per module).
 *
 *   static void t_something(void) { CHECK(x == 1); CHECK_NEAR(a, b, 1e-9); }
 *   int main(void) { RUN(t_something); return test_done(); }
 *
 * Each RUN prints "ok N - name" or "not ok N - name" with the failed checks. */
#ifndef ARVO_TEST_H
#define ARVO_TEST_H

#include <math.h>
#include <stdio.h>
#include <string.h>

static int test_n, test_failed, test_cur_failed;

#define CHECK(cond)                                                                     \
	do {                                                                                \
		if (!(cond)) {                                                                  \
			printf("#   %s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);         \
			test_cur_failed++;                                                          \
		}                                                                               \
	} while (0)

/* |a-b| <= tol, printing both values when not. */
#define CHECK_NEAR(a, b, tol)                                                           \
	do {                                                                                \
		double a_ = (a), b_ = (b);                                                      \
		if (!(fabs(a_ - b_) <= (tol))) {                                                \
			printf("#   %s:%d: %s = %.17g, expected %s = %.17g (tol %g)\n", __FILE__,    \
			       __LINE__, #a, a_, #b, b_, (double)(tol));                            \
			test_cur_failed++;                                                          \
		}                                                                               \
	} while (0)

#define CHECK_STR(a, b)                                                                 \
	do {                                                                                \
		const char *a_ = (a), *b_ = (b);                                                \
		if (!a_ || !b_ || strcmp(a_, b_) != 0) {                                        \
			printf("#   %s:%d: %s = \"%s\", expected \"%s\"\n", __FILE__, __LINE__, #a,  \
			       a_ ? a_ : "(null)", b_ ? b_ : "(null)");                             \
			test_cur_failed++;                                                          \
		}                                                                               \
	} while (0)

#define RUN(fn)                                                                         \
	do {                                                                                \
		test_cur_failed = 0;                                                            \
		fn();                                                                           \
		test_n++;                                                                       \
		if (test_cur_failed)                                                            \
			test_failed++;                                                              \
		printf("%sok %d - %s\n", test_cur_failed ? "not " : "", test_n, #fn);           \
	} while (0)

#ifdef ARVO_DIAG_H
/* A diag that prints nothing and keeps the last message, for library calls
 * whose errors a test inspects: MSG(call) is NULL when call returns 0, else
 * the message it reported to TDG. */
static struct diag test_dg __attribute__((unused));
#define TDG (&test_dg)
#define MSG(call) ((call) ? (const char *)test_dg.last : (const char *)NULL)
#endif

static inline int test_done(void)
{
	printf("1..%d\n", test_n);
	return test_failed ? 1 : 0;
}

#endif
