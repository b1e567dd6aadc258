/* SPDX-License-Identifier: MIT */
/* exrout.c: scanline EXR writer and reader on OpenEXRCore (docs/design.md §6). */
#include "exrout.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <openexr.h>

#include "../../common/arena.h"
#include "../../common/pool.h"
#include "tmpfile.h"

/* ================= OpenEXRCore plumbing ================= */

/* User data of a context: the output fd and the first detailed message. */
struct io {
	int fd;         /* output file (writer), -1 for the reader */
	char msg[512];  /* first error reported by the library, or "" */
};

/* Error handler: keeps the library's first message for our own report. */
static void on_error(exr_const_context_t ctx, exr_result_t code, const char *msg)
{
	void *ud = NULL;
	if (exr_get_user_data(ctx, &ud) != EXR_ERR_SUCCESS || !ud)
		return;
	struct io *io = ud;
	if (!io->msg[0])
		snprintf(io->msg, sizeof io->msg, "%s", msg ? msg : exr_get_error_code_as_string(code));
}

/* Custom write routine: pwrite to our temp file, retrying short writes. */
static int64_t write_fd(exr_const_context_t ctx, void *ud, const void *buf, uint64_t sz,
                        uint64_t off, exr_stream_error_func_ptr_t ecb)
{
	struct io *io = ud;
	const char *p = buf;
	uint64_t done = 0;
	while (done < sz) {
		ssize_t n = pwrite(io->fd, p + done, (size_t)(sz - done), (off_t)(off + done));
		if (n < 0 && errno == EINTR)
			continue;
		if (n <= 0) {
			ecb(ctx, EXR_ERR_WRITE_IO, "%s", n < 0 ? strerror(errno) : "short write");
			return -1;
		}
		done += (uint64_t)n;
	}
	return (int64_t)sz;
}

/* The message for a failed call: the library's detail, else the code's text. */
static const char *exr_msg(const struct io *io, exr_result_t rv)
{
	return io->msg[0] ? io->msg : exr_get_error_code_as_string(rv);
}

#define TRY(call)                                                                       \
	do {                                                                                \
		if ((rv = (call)) != EXR_ERR_SUCCESS)                                           \
			return rv;                                                                  \
	} while (0)

/* ================= writer ================= */

/* Index in names[] is the enum value (OUT_EXR_ZIP is 0, the default). */
int out_exr_compression_parse(const char *name, enum out_exr_compression *out)
{
	static const char *const names[] = {"zip", "none", "zips", "piz", "rle"};
	for (int i = 0; i < 5; i++)
		if (name && strcmp(name, names[i]) == 0) {
			*out = (enum out_exr_compression)i;
			return 0;
		}
	return -1;
}

/* OpenEXRCore's compression for ours. */
static exr_compression_t core_compression(enum out_exr_compression c)
{
	switch (c) {
	case OUT_EXR_NONE: return EXR_COMPRESSION_NONE;
	case OUT_EXR_ZIPS: return EXR_COMPRESSION_ZIPS;
	case OUT_EXR_PIZ: return EXR_COMPRESSION_PIZ;
	case OUT_EXR_RLE: return EXR_COMPRESSION_RLE;
	case OUT_EXR_ZIP: break;
	}
	return EXR_COMPRESSION_ZIP;
}

void out_meta_add(struct out_exr_meta *m, const char *key, const char *fmt, ...)
{
	if (m->n >= OUT_META_MAX)
		return;
	va_list ap;
	va_start(ap, fmt);
	snprintf(m->key[m->n], sizeof m->key[0], "%s", key);
	vsnprintf(m->val[m->n], sizeof m->val[0], fmt, ap);
	va_end(ap);
	m->n++;
}

/* The matrices and string attributes of m (arvo:scene is written apart). */
static exr_result_t write_meta(exr_context_t ctx, int part, const struct out_exr_meta *m)
{
	exr_result_t rv;
	if (m->has_camera) {
		exr_attr_m44f_t a;
		memcpy(a.m, m->world_to_camera, sizeof a.m);
		TRY(exr_attr_set_m44f(ctx, part, "worldToCamera", &a));
		memcpy(a.m, m->world_to_ndc, sizeof a.m);
		TRY(exr_attr_set_m44f(ctx, part, "worldToNDC", &a));
		memcpy(a.m, m->camera_to_world, sizeof a.m);
		TRY(exr_attr_set_m44f(ctx, part, "arvo:cameraToWorld", &a));
	}
	for (int i = 0; i < m->n; i++)
		if (strcmp(m->key[i], "arvo:scene") != 0)
			TRY(exr_attr_set_string(ctx, part, m->key[i], m->val[i]));
	return EXR_ERR_SUCCESS;
}

/* Declares the part: size, compression, one channel per plane, attributes. */
static exr_result_t write_header(exr_context_t ctx, const struct framebuffer *fb,
                                 const struct out_exr_opts *o)
{
	static const exr_attr_chromaticities_t rec709 = {0.64f,  0.33f,  0.30f,   0.60f,
	                                                 0.15f,  0.06f,  0.3127f, 0.3290f};
	exr_result_t rv;
	int part;
	TRY(exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part));
	exr_attr_box2i_t disp, data;
	exr_attr_v2f_t centre;
	disp.min.x = 0, disp.min.y = 0, disp.max.x = fb->full_w - 1, disp.max.y = fb->full_h - 1;
	data.min.x = fb->x0, data.min.y = fb->y0;
	data.max.x = fb->x0 + fb->w - 1, data.max.y = fb->y0 + fb->h - 1;
	centre.x = 0, centre.y = 0;
	TRY(exr_initialize_required_attr(ctx, part, &disp, &data, 1.0f, &centre, 1.0f,
	                                 EXR_LINEORDER_INCREASING_Y, core_compression(o->compression)));
	/* zlib level 4, OpenEXR's default since 3.2 (3.1 uses 6): a 1280x960
	 * render's 27 layers compress in 28 % less time, 2.6 % larger */
	if (o->compression == OUT_EXR_ZIP || o->compression == OUT_EXR_ZIPS)
		TRY(exr_set_zip_compression_level(ctx, part, EXR_ZIP_LEVEL));
	for (int i = 0; i < fb->count; i++) {
		const char *name = fb->planes[i].name;
		int half = o->half && strcmp(name, "Z") != 0;
		TRY(exr_add_channel(ctx, part, name, half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT,
		                    EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1));
	}
	TRY(exr_attr_set_chromaticities(ctx, part, "chromaticities", &rec709));
	TRY(exr_attr_set_string(ctx, part, "software", "arvo " ARVO_VERSION));
	if (o->scene)
		TRY(exr_attr_set_string(ctx, part, "arvo:scene", o->scene));
	if (o->meta)
		TRY(write_meta(ctx, part, o->meta));
	return exr_write_header(ctx);
}

/* Points each channel of the encoder at rows [y, ...) of its plane, found by
 * NAME: the file stores channels sorted, not in the framebuffer's order. */
static exr_result_t bind_planes(exr_encode_pipeline_t *enc, const struct framebuffer *fb, int y)
{
	for (int i = 0; i < enc->channel_count; i++) {
		exr_coding_channel_info_t *ch = &enc->channels[i];
		const float *p = fb_find(fb, ch->channel_name);
		if (!p)
			return EXR_ERR_INVALID_ARGUMENT;
		ch->user_data_type = EXR_PIXEL_FLOAT;
		ch->user_bytes_per_element = 4;
		ch->user_pixel_stride = 4;
		ch->user_line_stride = 4 * fb->w;
		ch->encode_from_ptr = (const uint8_t *)(p + (size_t)y * (size_t)fb->w);
	}
	return EXR_ERR_SUCCESS;
}

/* One encoder per worker thread: its pipeline, the library's compress
 * routine (wrapped by compress_fixed), and the chunk it encodes now. */
struct encoder {
	exr_encode_pipeline_t enc;
	bool inited;  /* enc was initialised (and is to be destroyed) */
	bool ready;   /* its routines are chosen: keep_chunk writes nothing itself */
	exr_result_t (*core_compress)(exr_encode_pipeline_t *);
	struct chunk *out;
};

/* A chunk encoded, waiting its turn to be written. */
struct chunk {
	int y;              /* its first row, in the file's coordinates */
	exr_chunk_info_t ci;
	void *data;         /* the bytes to write (malloc'd) */
	uint64_t size;
	exr_result_t rv;
};

/* OpenEXRCore 3.1.5 stores the compressed bytes when they are exactly as
 * long as the raw data, but readers take a chunk of raw length as raw
 * (openexr issue #2306, fixed upstream in 2026): a 2x4 float ZIP image came
 * back as garbage. Whenever compression does not shrink a chunk, store it
 * raw, as the file format requires. */
static exr_result_t compress_fixed(exr_encode_pipeline_t *enc)
{
	const struct encoder *e = enc->encoding_user_data;
	exr_result_t rv = e->core_compress(enc);
	if (rv == EXR_ERR_SUCCESS && enc->compressed_bytes >= enc->packed_bytes &&
	    enc->compressed_buffer != enc->packed_buffer &&
	    enc->compressed_alloc_size >= enc->packed_bytes) {
		memcpy(enc->compressed_buffer, enc->packed_buffer, enc->packed_bytes);
		enc->compressed_bytes = enc->packed_bytes;
	}
	return rv;
}

/* In place of the library's write: keeps the chunk's bytes for write_pixels
 * to write in order. */
static exr_result_t keep_chunk(exr_encode_pipeline_t *enc)
{
	struct chunk *c = ((struct encoder *)enc->encoding_user_data)->out;
	c->data = malloc(enc->compressed_bytes ? enc->compressed_bytes : 1);
	if (!c->data)
		return EXR_ERR_OUT_OF_MEMORY;
	memcpy(c->data, enc->compressed_buffer, enc->compressed_bytes);
	c->size = enc->compressed_bytes;
	return EXR_ERR_SUCCESS;
}

/* No waiting for the chunks before: they are written in order afterwards. */
static exr_result_t no_wait(exr_encode_pipeline_t *enc)
{
	(void)enc;
	return EXR_ERR_SUCCESS;
}

/* The encoding of a batch of chunks, one parallel_for item each. */
struct encode_job {
	exr_context_t ctx;
	const struct framebuffer *fb;
	struct encoder *workers;
	struct chunk *chunks;
};

static void encode_chunk(void *arg, long k, int worker)
{
	struct encode_job *J = arg;
	struct encoder *e = &J->workers[worker];
	struct chunk *c = &J->chunks[k];
	exr_result_t rv;
	if (e->inited) { /* routines chosen on the worker's first chunk stay */
		rv = e->ready ? exr_encoding_update(J->ctx, 0, &c->ci, &e->enc) : EXR_ERR_INVALID_ARGUMENT;
	} else {
		rv = exr_encoding_initialize(J->ctx, 0, &c->ci, &e->enc);
		e->inited = rv == EXR_ERR_SUCCESS; /* write_pixels destroys it */
	}
	if (rv == EXR_ERR_SUCCESS) {
		e->enc.encoding_user_data = e;
		rv = bind_planes(&e->enc, J->fb, c->y - J->fb->y0);
	}
	if (rv == EXR_ERR_SUCCESS && !e->ready) { /* after bind: packing follows the channels' types */
		rv = exr_encoding_choose_default_routines(J->ctx, 0, &e->enc);
		if (rv == EXR_ERR_SUCCESS && e->enc.compress_fn) {
			e->core_compress = e->enc.compress_fn;
			e->enc.compress_fn = compress_fixed;
		}
		e->enc.write_fn = keep_chunk;
		e->enc.yield_until_ready_fn = no_wait;
		e->ready = rv == EXR_ERR_SUCCESS;
	}
	e->out = c;
	if (rv == EXR_ERR_SUCCESS)
		rv = exr_encoding_run(J->ctx, 0, &e->enc);
	c->rv = rv;
}

/* Encodes every scanline chunk on the given threads, a batch at a time,
 * and writes the batch's chunks in order: the same file for any number of
 * threads (each chunk is compressed alone). */
static exr_result_t write_pixels(exr_context_t ctx, const struct framebuffer *fb, int threads)
{
	exr_result_t rv = EXR_ERR_SUCCESS;
	int lpc = 1;
	if ((rv = exr_get_scanlines_per_chunk(ctx, 0, &lpc)) != EXR_ERR_SUCCESS)
		return rv;
	int nt = pool_threads(threads);
	long n = (fb->h + lpc - 1) / lpc, batch = 8L * nt;
	struct encode_job J = {ctx, fb, mem_calloc((size_t)nt, sizeof *J.workers),
	                       mem_calloc((size_t)batch, sizeof *J.chunks)};
	for (int w = 0; w < nt; w++)
		J.workers[w].enc = (exr_encode_pipeline_t)EXR_ENCODE_PIPELINE_INITIALIZER;
	for (long k0 = 0; k0 < n && rv == EXR_ERR_SUCCESS; k0 += batch) {
		long m = n - k0 < batch ? n - k0 : batch;
		for (long k = 0; k < m && rv == EXR_ERR_SUCCESS; k++) {
			struct chunk *c = &J.chunks[k];
			*c = (struct chunk){.y = fb->y0 + (int)((k0 + k) * lpc)};
			rv = exr_write_scanline_chunk_info(ctx, 0, c->y, &c->ci);
		}
		if (rv == EXR_ERR_SUCCESS)
			parallel_for(m, nt, encode_chunk, &J);
		for (long k = 0; k < m; k++) {
			struct chunk *c = &J.chunks[k];
			if (rv == EXR_ERR_SUCCESS)
				rv = c->rv;
			if (rv == EXR_ERR_SUCCESS)
				rv = exr_write_scanline_chunk(ctx, 0, c->y, c->data, c->size);
			free(c->data);
			c->data = NULL;
		}
	}
	for (int w = 0; w < nt; w++) {
		exr_result_t rd = J.workers[w].inited ? exr_encoding_destroy(ctx, &J.workers[w].enc) : EXR_ERR_SUCCESS;
		if (rv == EXR_ERR_SUCCESS)
			rv = rd;
	}
	free(J.workers);
	free(J.chunks);
	return rv;
}

/* Writes the whole file through io->fd; returns 0 or FAIL_WRITE (reported). */
static int write_file(struct io *io, const char *path, const struct framebuffer *fb,
                      const struct out_exr_opts *o, struct diag *dg)
{
	exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
	exr_context_t ctx = NULL;
	init.user_data = io;
	init.write_fn = write_fd;
	init.error_handler_fn = on_error;
	exr_result_t rv = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
	if (rv == EXR_ERR_SUCCESS)
		rv = write_header(ctx, fb, o);
	if (rv == EXR_ERR_SUCCESS)
		rv = write_pixels(ctx, fb, o->threads);
	if (ctx) {
		exr_result_t rf = exr_finish(&ctx);
		if (rv == EXR_ERR_SUCCESS)
			rv = rf;
	}
	if (rv == EXR_ERR_SUCCESS)
		return 0;
	return diag_fail(dg, FAIL_WRITE, srcloc_none(), "cannot write '%s': %s", path, exr_msg(io, rv));
}

/* Validates, writes to a temp file through our fd, then renames or removes it. */
int out_exr_write(const struct framebuffer *fb, const char *path, const struct out_exr_opts *opts,
                  struct diag *dg)
{
	static const struct out_exr_opts defaults = {0, OUT_EXR_ZIP, NULL, NULL, 0};
	const struct out_exr_opts *o = opts ? opts : &defaults;
	struct srcloc none = srcloc_none();
	if (!fb || fb->count == 0)
		return diag_fail(dg, FAIL_INTERNAL, none, "cannot write '%s': the image has no channels", path);
	if ((unsigned)o->compression > OUT_EXR_RLE)
		return diag_fail(dg, FAIL_INTERNAL, none, "cannot write '%s': unknown compression %d", path,
		                 (int)o->compression);
	char tmp[4096];
	struct io io = {.fd = out_tmp_create(path, tmp, sizeof tmp)};
	if (io.fd < 0)
		return diag_fail(dg, FAIL_CREATE, none, "cannot create '%s': %s", path, strerror(errno));
	int rc = write_file(&io, path, fb, o, dg);
	if (close(io.fd) != 0 && !rc)
		rc = diag_fail(dg, FAIL_WRITE, none, "cannot write '%s': %s", path, strerror(errno));
	if (out_tmp_finish(tmp, path, rc == 0) != 0)
		rc = diag_fail(dg, FAIL_WRITE, none, "cannot write '%s': rename: %s", path, strerror(errno));
	return rc;
}

/* ================= reader ================= */

/* The matrices and the "arvo:…" string attributes of part 0. */
static void read_meta(exr_const_context_t ctx, struct out_exr_meta *m)
{
	exr_attr_m44f_t a[3];
	if (exr_attr_get_m44f(ctx, 0, "worldToCamera", &a[0]) == EXR_ERR_SUCCESS &&
	    exr_attr_get_m44f(ctx, 0, "worldToNDC", &a[1]) == EXR_ERR_SUCCESS &&
	    exr_attr_get_m44f(ctx, 0, "arvo:cameraToWorld", &a[2]) == EXR_ERR_SUCCESS) {
		m->has_camera = 1;
		memcpy(m->world_to_camera, a[0].m, sizeof a[0].m);
		memcpy(m->world_to_ndc, a[1].m, sizeof a[1].m);
		memcpy(m->camera_to_world, a[2].m, sizeof a[2].m);
	}
	int32_t count = 0;
	if (exr_get_attribute_count(ctx, 0, &count) != EXR_ERR_SUCCESS)
		return;
	for (int32_t i = 0; i < count; i++) {
		const exr_attribute_t *at = NULL;
		if (exr_get_attribute_by_index(ctx, 0, EXR_ATTR_LIST_FILE_ORDER, i, &at) != EXR_ERR_SUCCESS ||
		    !at || at->type != EXR_ATTR_STRING || strncmp(at->name, "arvo:", 5) != 0)
			continue;
		out_meta_add(m, at->name, "%.*s", (int)at->string->length, at->string->str);
	}
}

/* Copies the header facts the caller asked for into info. */
static void read_info(exr_const_context_t ctx, const exr_attr_chlist_t *cl,
                      struct out_exr_info *info)
{
	exr_attr_chromaticities_t c;
	const char *s;
	int32_t len;
	memset(info, 0, sizeof *info);
	if (exr_attr_get_chromaticities(ctx, 0, "chromaticities", &c) == EXR_ERR_SUCCESS) {
		const float v[8] = {c.red_x,  c.red_y,  c.green_x, c.green_y,
		                    c.blue_x, c.blue_y, c.white_x, c.white_y};
		memcpy(info->chroma, v, sizeof v);
		info->has_chroma = 1;
	}
	if (exr_attr_get_string(ctx, 0, "software", &len, &s) == EXR_ERR_SUCCESS)
		snprintf(info->software, sizeof info->software, "%.*s", (int)len, s);
	if (exr_attr_get_string(ctx, 0, "arvo:scene", &len, &s) == EXR_ERR_SUCCESS)
		snprintf(info->scene, sizeof info->scene, "%.*s", (int)len, s);
	read_meta(ctx, &info->meta);
	exr_compression_t comp;
	static const exr_compression_t ours[] = {EXR_COMPRESSION_ZIP, EXR_COMPRESSION_NONE, EXR_COMPRESSION_ZIPS,
	                                         EXR_COMPRESSION_PIZ, EXR_COMPRESSION_RLE};
	if (exr_get_compression(ctx, 0, &comp) == EXR_ERR_SUCCESS)
		for (int i = 0; i < 5; i++)
			if (ours[i] == comp)
				info->compression = (enum out_exr_compression)i;
	info->half = info->half_but_z = 1;
	for (int i = 0; i < cl->num_channels; i++)
		if (cl->entries[i].pixel_type != EXR_PIXEL_HALF) {
			info->half = 0;
			if (strcmp(cl->entries[i].name.str, "Z") != 0)
				info->half_but_z = 0;
		}
}

/* Points every channel of the decoder at its plane (ALL channels: decoding a
 * subset crashes the core on 3-channel half files, docs/design.md §6, library facts).
 * UINT channels are decoded as uint32 into the float plane, converted later. */
static exr_result_t bind_decode(exr_decode_pipeline_t *dec, struct framebuffer *fb, int row)
{
	for (int i = 0; i < dec->channel_count; i++) {
		exr_coding_channel_info_t *ch = &dec->channels[i];
		float *p = fb_find(fb, ch->channel_name);
		if (!p)
			return EXR_ERR_INVALID_ARGUMENT;
		ch->user_data_type = ch->data_type == EXR_PIXEL_UINT ? EXR_PIXEL_UINT : EXR_PIXEL_FLOAT;
		ch->user_bytes_per_element = 4;
		ch->user_pixel_stride = 4;
		ch->user_line_stride = 4 * fb->w;
		ch->decode_to_ptr = (uint8_t *)(p + (size_t)row * (size_t)fb->w);
	}
	return EXR_ERR_SUCCESS;
}

/* Reads and decodes every chunk of part 0 into fb. */
static exr_result_t read_pixels(exr_const_context_t ctx, struct framebuffer *fb, int ymin)
{
	exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
	exr_result_t rv = EXR_ERR_SUCCESS;
	int lpc = 1, inited = 0;
	if ((rv = exr_get_scanlines_per_chunk(ctx, 0, &lpc)) != EXR_ERR_SUCCESS)
		return rv;
	for (int y = ymin; y < ymin + fb->h && rv == EXR_ERR_SUCCESS; y += lpc) {
		exr_chunk_info_t ci;
		rv = exr_read_scanline_chunk_info(ctx, 0, y, &ci);
		if (rv == EXR_ERR_SUCCESS)
			rv = inited ? exr_decoding_update(ctx, 0, &ci, &dec)
			            : exr_decoding_initialize(ctx, 0, &ci, &dec);
		if (rv != EXR_ERR_SUCCESS)
			break;
		rv = bind_decode(&dec, fb, ci.start_y - ymin);
		if (rv == EXR_ERR_SUCCESS && !inited)
			rv = exr_decoding_choose_default_routines(ctx, 0, &dec);
		inited = 1;
		if (rv == EXR_ERR_SUCCESS)
			rv = exr_decoding_run(ctx, 0, &dec);
	}
	if (inited) {
		exr_result_t rd = exr_decoding_destroy(ctx, &dec);
		if (rv == EXR_ERR_SUCCESS)
			rv = rd;
	}
	return rv;
}

/* Converts planes that were decoded as uint32 into floats, in place. */
static void uint_to_float(struct framebuffer *fb, const exr_attr_chlist_t *cl)
{
	size_t n = (size_t)fb->w * (size_t)fb->h;
	for (int i = 0; i < cl->num_channels; i++) {
		if (cl->entries[i].pixel_type != EXR_PIXEL_UINT)
			continue;
		float *p = fb_find(fb, cl->entries[i].name.str);
		for (size_t k = 0; k < n; k++) {
			uint32_t u;
			memcpy(&u, p + k, 4);
			p[k] = (float)u;
		}
	}
}

/* Checks part 0 is a readable scanline image; sets *w *h *ymin, *cl and the
 * display and data windows. Returns 0 or FAIL_INPUT (reported). */
static int check_part(exr_const_context_t ctx, const char *path, int *w, int *h, int *ymin,
                      const exr_attr_chlist_t **cl, exr_attr_box2i_t *disp, exr_attr_box2i_t *data,
                      struct diag *dg)
{
	struct srcloc none = srcloc_none();
	exr_storage_t st;
	exr_attr_box2i_t dw;
	if (exr_get_storage(ctx, 0, &st) != EXR_ERR_SUCCESS || st != EXR_STORAGE_SCANLINE)
		return diag_fail(dg, FAIL_INPUT, none, "cannot read '%s': only scanline EXR images are supported", path);
	if (exr_get_data_window(ctx, 0, &dw) != EXR_ERR_SUCCESS ||
	    exr_get_channels(ctx, 0, cl) != EXR_ERR_SUCCESS || !*cl || (*cl)->num_channels < 1)
		return diag_fail(dg, FAIL_INPUT, none, "cannot read '%s': bad header", path);
	int64_t ww = (int64_t)dw.max.x - dw.min.x + 1, hh = (int64_t)dw.max.y - dw.min.y + 1;
	if (ww < 1 || hh < 1 || ww * hh * (*cl)->num_channels > ((int64_t)1 << 28)) /* 1 GiB of floats */
		return diag_fail(dg, FAIL_INPUT, none, "cannot read '%s': unsupported size %lldx%lld", path,
		                 (long long)ww, (long long)hh);
	for (int i = 0; i < (*cl)->num_channels; i++)
		if ((*cl)->entries[i].x_sampling != 1 || (*cl)->entries[i].y_sampling != 1)
			return diag_fail(dg, FAIL_INPUT, none, "cannot read '%s': subsampled channel '%s' is not supported",
			                 path, (*cl)->entries[i].name.str);
	*w = (int)ww, *h = (int)hh, *ymin = dw.min.y, *data = dw;
	if (exr_get_display_window(ctx, 0, disp) != EXR_ERR_SUCCESS)
		*disp = dw;
	/* a display window too large or too far for int sizes and offsets (a
	 * damaged or hostile header): take the data window as the frame */
	const int64_t lim = (int64_t)1 << 24;
	int64_t fw = (int64_t)disp->max.x - disp->min.x + 1, fh = (int64_t)disp->max.y - disp->min.y + 1;
	int64_t ox = (int64_t)dw.min.x - disp->min.x, oy = (int64_t)dw.min.y - disp->min.y;
	if (fw < 1 || fh < 1 || fw > lim || fh > lim || ox < -lim || ox > lim || oy < -lim || oy > lim)
		*disp = dw;
	return 0;
}

/* Opens, checks the header, decodes all channels; on error nothing leaks and *out stays NULL. */
int out_exr_read(const char *path, struct framebuffer **out, struct out_exr_info *info, struct diag *dg)
{
	exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
	exr_context_t ctx = NULL;
	struct io io = {.fd = -1};
	*out = NULL;
	init.user_data = &io;
	init.error_handler_fn = on_error;
	exr_result_t rv = exr_start_read(&ctx, path, &init);
	if (rv != EXR_ERR_SUCCESS) {
		int e = diag_fail(dg, FAIL_INPUT, srcloc_none(), "cannot read '%s': %s", path, exr_msg(&io, rv));
		if (ctx)
			exr_finish(&ctx);
		return e;
	}
	const exr_attr_chlist_t *cl = NULL;
	int w = 0, h = 0, ymin = 0;
	exr_attr_box2i_t disp = {0}, data = {0};
	int err = check_part(ctx, path, &w, &h, &ymin, &cl, &disp, &data, dg);
	struct framebuffer *fb = NULL;
	if (!err) {
		fb = fb_new(w, h);
		fb->x0 = data.min.x - disp.min.x, fb->y0 = data.min.y - disp.min.y;
		fb->full_w = disp.max.x - disp.min.x + 1, fb->full_h = disp.max.y - disp.min.y + 1;
		for (int i = 0; i < cl->num_channels; i++)
			fb_plane(fb, cl->entries[i].name.str);
		if ((rv = read_pixels(ctx, fb, ymin)) != EXR_ERR_SUCCESS)
			err = diag_fail(dg, FAIL_INPUT, srcloc_none(), "cannot read '%s': %s", path, exr_msg(&io, rv));
	}
	if (!err) {
		uint_to_float(fb, cl);
		if (info)
			read_info(ctx, cl, info);
		*out = fb;
	} else {
		fb_free(fb);
	}
	exr_finish(&ctx);
	return err;
}
