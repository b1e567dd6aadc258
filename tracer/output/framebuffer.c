/* SPDX-License-Identifier: MIT */
/* framebuffer.c: named float planes kept in a stable, canonical order. */
#include "framebuffer.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "../../common/arena.h"

/* Sizes below 1 are raised to 1 so every plane has storage. */
struct framebuffer *fb_new(int w, int h)
{
	struct framebuffer *fb = mem_calloc(1, sizeof *fb);
	fb->w = w > 0 ? w : 1;
	fb->h = h > 0 ? h : 1;
	fb->full_w = fb->w;
	fb->full_h = fb->h;
	return fb;
}

/* Rank of a channel suffix inside its layer: R G B A X Y Z, then the rest. */
static int chan_rank(const char *c)
{
	static const char *const order[] = {"R", "G", "B", "A", "X", "Y", "Z"};
	for (int i = 0; i < 7; i++)
		if (strcmp(c, order[i]) == 0)
			return i;
	return 7;
}

/* Orders two plane names: beauty channels (no '.') first, then by layer name,
 * then by channel rank, then by name. A total order, so iteration is stable. */
static int name_cmp(const char *a, const char *b)
{
	const char *da = strrchr(a, '.'), *db = strrchr(b, '.');
	if (!da != !db)
		return da ? 1 : -1;
	if (da) {
		size_t la = (size_t)(da - a), lb = (size_t)(db - b);
		int c = strncmp(a, b, la < lb ? la : lb);
		if (c)
			return c;
		if (la != lb)
			return la < lb ? -1 : 1;
	}
	const char *ca = da ? da + 1 : a, *cb = db ? db + 1 : b;
	int ra = chan_rank(ca), rb = chan_rank(cb);
	if (ra != rb)
		return ra < rb ? -1 : 1;
	return strcmp(ca, cb);
}

float *fb_find(const struct framebuffer *fb, const char *name)
{
	for (int i = 0; i < fb->count; i++)
		if (strcmp(fb->planes[i].name, name) == 0)
			return fb->planes[i].data;
	return NULL;
}

/* Finds or inserts a plane, keeping planes[] sorted by name_cmp. */
float *fb_plane(struct framebuffer *fb, const char *name)
{
	float *p = fb_find(fb, name);
	if (p)
		return p;
	if (fb->count == fb->cap) {
		fb->cap = fb->cap ? 2 * fb->cap : 8;
		fb->planes = mem_realloc(fb->planes, (size_t)fb->cap * sizeof *fb->planes);
	}
	int at = fb->count;
	while (at > 0 && name_cmp(name, fb->planes[at - 1].name) < 0)
		at--;
	memmove(fb->planes + at + 1, fb->planes + at, (size_t)(fb->count - at) * sizeof *fb->planes);
	fb->planes[at].name = mem_strdup(name);
	size_t n = (size_t)fb->w * (size_t)fb->h;
	if (fb->spare > 0)
		fb->planes[at].data = fb->block + n * (size_t)fb->given++, fb->spare--;
	else
		fb->planes[at].data = mem_calloc(n, sizeof(float));
	fb->count++;
	return fb->planes[at].data;
}

void fb_reserve(struct framebuffer *fb, int n)
{
	if (fb->block || n <= 0)
		return;
	size_t bytes = (size_t)fb->w * (size_t)fb->h * sizeof(float) * (size_t)n;
	fb->block = memset(mem_alloc_huge(bytes), 0, bytes);
	fb->spare = n;
}

/* Whether p is one of the planes carved from fb's block. */
static bool in_block(const struct framebuffer *fb, const float *p)
{
	return fb->block && p >= fb->block && p < fb->block + (size_t)fb->w * (size_t)fb->h * (size_t)fb->given;
}

int fb_count(const struct framebuffer *fb) { return fb->count; }

const char *fb_name(const struct framebuffer *fb, int i)
{
	return i >= 0 && i < fb->count ? fb->planes[i].name : NULL;
}

float *fb_data(const struct framebuffer *fb, int i)
{
	return i >= 0 && i < fb->count ? fb->planes[i].data : NULL;
}

/* Frees every plane, its name, and fb itself; NULL is allowed. */
void fb_free(struct framebuffer *fb)
{
	if (!fb)
		return;
	for (int i = 0; i < fb->count; i++) {
		free(fb->planes[i].name);
		if (!in_block(fb, fb->planes[i].data))
			free(fb->planes[i].data);
	}
	free(fb->planes), free(fb->block);
	free(fb);
}
