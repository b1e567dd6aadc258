/* SPDX-License-Identifier: MIT */
/* arena.c: allocation wrapper (with fault injection) and bump arenas. */
#include "arena.h"

#include <errno.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

struct arena_block {
	struct arena_block *next; /* older block */
	size_t size, used;        /* capacity and fill of data[] */
	_Alignas(16) unsigned char data[];
};

static void default_oom(size_t n)
{
	fprintf(stderr, "arvo: error: out of memory (allocating %zu bytes)\n", n);
	exit(70);
}

static void (*oom_handler)(size_t) = default_oom;
static long fail_at = -1; /* from ARVO_FAIL_ALLOC; -1 until read, 0 when off */
static long calls;

void mem_set_oom(void (*handler)(size_t)) { oom_handler = handler ? handler : default_oom; }

/* True when fault injection says this allocation must fail. */
static int inject(void)
{
	if (fail_at < 0) {
		const char *s = getenv("ARVO_FAIL_ALLOC");
		fail_at = s ? atol(s) : 0;
	}
	return fail_at > 0 && ++calls == fail_at;
}

static size_t budget;                     /* bytes; 0: none */
static mem_over_fn budget_over;
static atomic_size_t since_check;         /* bytes requested since the last look */

mem_over_fn mem_set_budget(size_t bytes, mem_over_fn over)
{
	mem_over_fn old = budget_over;
	budget = bytes;
	budget_over = over;
	atomic_store(&since_check, 0);
	return old;
}

size_t mem_parse_size(const char *s)
{
	char *end;
	if (*s < '0' || *s > '9')
		return 0;
	errno = 0;
	unsigned long long v = strtoull(s, &end, 10);
	int shift = 0;
	if (errno)
		return 0;
	if (*end) {
		const char *units = "KMGT", *u = strchr(units, end[0] & ~0x20);
		if (!u || !*u || (end[1] && strcmp(end + 1, "iB") && strcmp(end + 1, "B")))
			return 0;
		shift = 10 * (int)(u - units + 1);
	}
	if (v == 0 || v > (SIZE_MAX >> shift))
		return 0;
	return (size_t)v << shift;
}

void mem_format_size(char *buf, size_t len, size_t bytes)
{
	static const char *const units[] = {"KiB", "MiB", "GiB", "TiB"};
	int u = -1;
	size_t v = bytes;
	while (u < 3 && v >= 1024 && v % 1024 == 0)
		v /= 1024, u++;
	if (u < 0)
		snprintf(buf, len, "%zu bytes", bytes);
	else
		snprintf(buf, len, "%zu %s", v, units[u]);
}

size_t mem_budget(void) { return budget; }

size_t mem_resident(void)
{
	FILE *f = fopen("/proc/self/statm", "r");
	unsigned long size, resident;
	int ok = f && fscanf(f, "%lu %lu", &size, &resident) == 2;
	if (f)
		fclose(f);
	return ok ? (size_t)resident * (size_t)sysconf(_SC_PAGESIZE) : 0;
}

size_t mem_default_budget(void)
{
	long pages = sysconf(_SC_PHYS_PAGES), psize = sysconf(_SC_PAGESIZE);
	size_t total = pages > 0 && psize > 0 ? (size_t)pages * (size_t)psize : (size_t)1 << 32;
	FILE *f = fopen("/sys/fs/cgroup/memory.max", "r"); /* a container's limit, if lower */
	unsigned long long lim;
	if (f) {
		if (fscanf(f, "%llu", &lim) == 1 && lim > 0 && lim < total)
			total = (size_t)lim;
		fclose(f);
	}
	return total / 2;
}

/* Looks at the resident size when due; calls the handler past the budget. */
static void budget_check(size_t n)
{
	if (!budget)
		return;
	size_t seen = atomic_fetch_add_explicit(&since_check, n, memory_order_relaxed) + n;
	if (n < MEM_CHECK_BYTES && seen < MEM_CHECK_BYTES)
		return;
	atomic_store_explicit(&since_check, 0, memory_order_relaxed);
	size_t rss = mem_resident();
	if (n > budget || rss > budget - n)
		budget_over(n);
}

void mem_huge(void *p, size_t n)
{
#ifdef MADV_HUGEPAGE
	const uintptr_t huge = (uintptr_t)2 << 20;
	uintptr_t lo = ((uintptr_t)p + huge - 1) & ~(huge - 1), hi = ((uintptr_t)p + n) & ~(huge - 1);
	if (n >= MEM_HUGE_MIN && lo < hi)
		(void)madvise((void *)lo, hi - lo, MADV_HUGEPAGE); /* advice: a refusal changes nothing */
#else
	(void)p, (void)n;
#endif
}

void *mem_alloc_huge(size_t n)
{
	const size_t huge = (size_t)2 << 20;
	if (n < MEM_HUGE_MIN || n > SIZE_MAX - huge)
		return mem_alloc(n);
	size_t size = (n + huge - 1) & ~(huge - 1); /* aligned_alloc: a multiple of the alignment */
	budget_check(size);
	void *p = inject() ? NULL : aligned_alloc(huge, size);
	if (!p) {
		oom_handler(n);
		abort();
	}
	mem_huge(p, size);
	return p;
}

void *mem_realloc(void *p, size_t n)
{
	budget_check(n);
	void *q = inject() ? NULL : realloc(p, n ? n : 1);
	if (!q) {
		oom_handler(n);
		abort();
	}
	return q;
}

void *mem_alloc(size_t n) { return mem_realloc(NULL, n); }

/* calloc, not malloc + memset: a big zeroed block (a framebuffer plane, an
 * image a header declares) costs no memory until it is written. */
void *mem_calloc(size_t n, size_t size)
{
	if (size && n > SIZE_MAX / size) {
		oom_handler(SIZE_MAX);
		abort();
	}
	budget_check(n * size);
	void *p = inject() ? NULL : calloc(n ? n : 1, size ? size : 1);
	if (!p) {
		oom_handler(n * size);
		abort();
	}
	return p;
}

char *mem_strndup(const char *s, size_t n)
{
	char *p = mem_alloc(n + 1);
	memcpy(p, s, n);
	p[n] = '\0';
	return p;
}

char *mem_strdup(const char *s) { return mem_strndup(s, strlen(s)); }

void arena_init(struct arena *a) { memset(a, 0, sizeof *a); }

void arena_init_large(struct arena *a)
{
	memset(a, 0, sizeof *a);
	a->most = ARENA_LARGE_BLOCK;
}

void arena_init_sized(struct arena *a, size_t first)
{
	memset(a, 0, sizeof *a);
	a->block = first;
}

size_t arena_bytes(const struct arena *a)
{
	size_t n = 0;
	for (const struct arena_block *b = a->head; b; b = b->next)
		n += sizeof *b + b->size;
	return n;
}

/* n bytes aligned to align (8 or 16; n a multiple of it). */
static void *alloc_aligned(struct arena *a, size_t n, size_t align)
{
	struct arena_block *b = a->head;
	size_t at = b ? (b->used + align - 1) & ~(align - 1) : 0; /* past what an 8-aligned one left */
	if (!b || at > b->size || b->size - at < n) {
		size_t want = a->block ? a->block : 65536, size = n > want ? n : want;
		a->block = want < (a->most ? a->most : (size_t)1 << 20) ? 2 * want : want;
		b = mem_alloc_huge(sizeof *b + size); /* (huge pages from MEM_HUGE_MIN on) */
		b->size = size;
		b->used = 0;
		b->next = a->head;
		a->head = b;
		at = 0;
	}
	void *p = b->data + at;
	b->used = at + n;
	a->used += n;
	memset(p, 0, n);
	return p;
}

void *arena_alloc(struct arena *a, size_t n) { return alloc_aligned(a, (n + 15) & ~(size_t)15, 16); }

void *arena_alloc8(struct arena *a, size_t n) { return alloc_aligned(a, (n + 7) & ~(size_t)7, 8); }

char *arena_strndup(struct arena *a, const char *s, size_t n)
{
	char *p = arena_alloc(a, n + 1);
	memcpy(p, s, n);
	p[n] = '\0';
	return p;
}

void arena_adopt(struct arena *dst, struct arena *src)
{
	struct arena_block *tail = src->head;
	if (!tail)
		return;
	while (tail->next)
		tail = tail->next;
	if (dst->head) { /* keep dst's newest block first: it has room to bump */
		tail->next = dst->head->next;
		dst->head->next = src->head;
	} else {
		dst->head = src->head;
	}
	dst->used += src->used;
	src->head = NULL;
	src->used = 0;
}

void arena_reset(struct arena *a)
{
	struct arena_block *b = a->head;
	if (!b)
		return;
	while (b->next) {
		struct arena_block *n = b->next;
		free(b);
		b = n;
	}
	b->used = 0;
	a->head = b;
	a->used = 0;
}

void arena_free(struct arena *a)
{
	for (struct arena_block *b = a->head, *n; b; b = n) {
		n = b->next;
		free(b);
	}
	a->head = NULL;
	a->used = 0;
}
