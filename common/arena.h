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

struct arena_block;

/* A chained bump allocator: one lifetime for everything allocated in it.
 * Blocks start at `block` bytes (64 KiB after arena_init) and double up to
 * 1 MiB, so an arena that holds little costs little. */
struct arena {
	struct arena_block *head; /* newest block */
	size_t used;              /* bytes handed out, all blocks */
	size_t block;             /* size of the next block (0: 64 KiB) */
};

void arena_init(struct arena *a);
/* An arena whose first block holds `first` bytes (for many small arenas). */
void arena_init_sized(struct arena *a, size_t first);
/* Bytes obtained from the allocator, block headers included. */
size_t arena_bytes(const struct arena *a);
/* Zeroed, 16-byte aligned memory that lives until arena_free/arena_reset. */
void *arena_alloc(struct arena *a, size_t n);
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
