/* SPDX-License-Identifier: MIT */
/* test_budget.c: the memory budget (common/arena.c): sizes as --max-memory
 * reads and prints them, the resident size, and the handler called before an
 * allocation over the budget is made. */
#include <setjmp.h>
#include <stdint.h>
#include <stdlib.h>

#include "../../common/arena.h"
#include "test.h"

static void t_parse_size(void)
{
	CHECK(mem_parse_size("512M") == (size_t)512 << 20);
	CHECK(mem_parse_size("4G") == (size_t)4 << 30);
	CHECK(mem_parse_size("4GiB") == (size_t)4 << 30);
	CHECK(mem_parse_size("64k") == (size_t)64 << 10);
	CHECK(mem_parse_size("1T") == (size_t)1 << 40);
	CHECK(mem_parse_size("1000000") == 1000000);
	CHECK(mem_parse_size("0") == 0);
	CHECK(mem_parse_size("") == 0);
	CHECK(mem_parse_size("-1G") == 0);
	CHECK(mem_parse_size("12X") == 0);
	CHECK(mem_parse_size("12 M") == 0);
	CHECK(mem_parse_size("1.5G") == 0);
	CHECK(mem_parse_size("99999999999999999999") == 0);
	CHECK(mem_parse_size("17179869184T") == 0); /* 2^64 bytes */
}

static void t_format_size(void)
{
	char b[32];
	mem_format_size(b, sizeof b, (size_t)512 << 20);
	CHECK_STR(b, "512 MiB");
	mem_format_size(b, sizeof b, (size_t)4 << 30);
	CHECK_STR(b, "4 GiB");
	mem_format_size(b, sizeof b, (size_t)1536 << 20);
	CHECK_STR(b, "1536 MiB");
	mem_format_size(b, sizeof b, 1000);
	CHECK_STR(b, "1000 bytes");
}

static void t_resident(void)
{
	size_t before = mem_resident();
	CHECK(before > 0);
	size_t n = (size_t)64 << 20;
	char *p = mem_alloc(n);
	memset(p, 1, n); /* touched: resident */
	size_t after = mem_resident();
	CHECK(after >= before + n - ((size_t)4 << 20));
	free(p);
	CHECK(mem_default_budget() >= ((size_t)64 << 20));
}

static jmp_buf over;
static size_t over_request;
static void on_over(size_t request)
{
	over_request = request;
	longjmp(over, 1);
}

static void t_budget(void)
{
	size_t budget = mem_resident() + ((size_t)32 << 20);
	mem_over_fn old = mem_set_budget(budget, on_over);
	CHECK(mem_budget() == budget);
	/* a request bigger than the budget is refused before it is made */
	over_request = 0;
	if (setjmp(over) == 0) {
		free(mem_alloc((size_t)1 << 40));
		CHECK(!"1 TiB allocated under a 32 MiB budget");
	}
	CHECK(over_request == (size_t)1 << 40);
	/* small allocations are checked every MEM_CHECK_BYTES */
	over_request = 0;
	char *keep[64];
	volatile int k = 0;
	if (setjmp(over) == 0) {
		for (k = 0; k < 64; k++) {
			keep[k] = mem_alloc((size_t)1 << 20);
			memset(keep[k], 1, (size_t)1 << 20);
		}
	}
	CHECK(over_request == (size_t)1 << 20);
	CHECK(k > 16 && k < 64); /* stopped past 32 MiB more, within a check interval */
	for (int i = 0; i < k; i++)
		free(keep[i]);
	mem_set_budget(0, old);
	CHECK(mem_budget() == 0);
	free(mem_alloc((size_t)64 << 20)); /* no budget: allowed */
}

int main(void)
{
	RUN(t_parse_size);
	RUN(t_format_size);
	RUN(t_resident);
	RUN(t_budget);
	return test_done();
}
