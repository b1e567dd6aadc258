/* SPDX-License-Identifier: MIT */
/* arena.h: the single allocation wrapper and chained bump arenas. */
#ifndef ARVO_ARENA_H
#define ARVO_ARENA_H

#include <stddef.h>

/* Every allocation goes through these. On exhaustion they call the handler set
 * by mem_set_oom (main maps it to exit 70); they never return NULL.
 * Setting ARVO_FAIL_ALLOC=N in the environment makes the N-th call fail (tests). */
void *mem_alloc(size_t n);
void *mem_calloc(size_t n, size_t size);
void *mem_realloc(void *p, size_t n);
char *mem_strdup(const char *s);
char *mem_strndup(const char *s, size_t n);
void mem_set_oom(void (*handler)(size_t));
/* Asks that the 2 MiB-aligned stretches inside [p, p+n) be backed by huge
 * pages when first written (Linux's transparent huge pages, madvise
 * MADV_HUGEPAGE; elsewhere, or when the kernel declines, nothing): one page
 * fault per 2 MiB instead of one per 4 KiB for a big buffer filled once.
 * Worth it from MEM_HUGE_MIN bytes (smaller ones have no such stretch, or
 * would hold a whole huge page for a few KiB). Arena blocks that large are
 * advised by the arena. */
#define MEM_HUGE_MIN ((size_t)4 << 20)
void mem_huge(void *p, size_t n);
/* mem_alloc, from MEM_HUGE_MIN bytes on 2 MiB-aligned and advised (mem_huge)
 * whole: every page of it can be a huge one. free() frees it. */
void *mem_alloc_huge(size_t n);

/* The memory budget (--max-memory; docs/design.md §8). With a budget set,
 * every allocation of at least MEM_CHECK_BYTES, and every MEM_CHECK_BYTES
 * allocated in total, compares the process's resident size plus the request
 * with the budget; crossing it calls the handler, which exits or longjmps out
 * of the evaluator (when it returns, the allocation goes ahead).
 * Thread-safe. 0: no budget. */
#define MEM_CHECK_BYTES ((size_t)4 << 20)
typedef void (*mem_over_fn)(size_t request);
/* Sets the budget and its handler; returns the handler it replaces. */
mem_over_fn mem_set_budget(size_t bytes, mem_over_fn over);
size_t mem_budget(void);
/* The process's resident set size in bytes (/proc/self/statm); 0 if unknown. */
size_t mem_resident(void);
/* Half the machine's memory (or of a cgroup limit below it): the default budget. */
size_t mem_default_budget(void);
/* Reads a size: a whole number of bytes with an optional K, M, G or T
 * (binary multiples); 0 when malformed. */
size_t mem_parse_size(const char *s);
/* Writes a size as "512 MiB", "4 GiB" (exact multiples) or "N bytes". */
void mem_format_size(char *buf, size_t len, size_t bytes);

struct arena_block;

/* A chained bump allocator: one lifetime for everything allocated in it.
 * Blocks start at `block` bytes (64 KiB after arena_init) and double up to
 * 1 MiB, so an arena that holds little costs little; an arena made by
 * arena_init_large doubles them up to ARENA_LARGE_BLOCK. */
struct arena {
	struct arena_block *head; /* newest block */
	size_t used;              /* bytes handed out, all blocks */
	size_t block;             /* size of the next block (0: 64 KiB) */
	size_t most;              /* blocks double up to this size (0: 1 MiB) */
};

void arena_init(struct arena *a);
/* An arena that may come to hold a great deal (a scene's objects): its
 * blocks go on doubling to ARENA_LARGE_BLOCK, so that from MEM_HUGE_MIN on
 * they are backed by huge pages: a page fault per 2 MiB while it fills,
 * not one per 4 KiB (docs/design.md §10, Allocation). */
#define ARENA_LARGE_BLOCK ((size_t)16 << 20)
void arena_init_large(struct arena *a);
/* An arena whose first block holds `first` bytes (for many small arenas). */
void arena_init_sized(struct arena *a, size_t first);
/* Bytes obtained from the allocator, block headers included. */
size_t arena_bytes(const struct arena *a);
/* Zeroed, 16-byte aligned memory that lives until arena_free/arena_reset. */
void *arena_alloc(struct arena *a, size_t n);
/* The same, 8-byte aligned: no padding to 16 (a million objects of 104 bytes). */
void *arena_alloc8(struct arena *a, size_t n);
char *arena_strndup(struct arena *a, const char *s, size_t n);
/* Moves everything src holds into dst (same lifetime from now on); src is
 * left empty. */
void arena_adopt(struct arena *dst, struct arena *src);
/* Drops everything but keeps the first block for reuse. */
void arena_reset(struct arena *a);
void arena_free(struct arena *a);

#define ARENA_NEW(a, type) ((type *)arena_alloc((a), sizeof(type)))
#define ARENA_ARRAY(a, type, n) ((type *)arena_alloc((a), sizeof(type) * (size_t)(n)))

#endif
