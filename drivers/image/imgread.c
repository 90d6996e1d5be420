/* imgread.c: streaming PNG (libpng), PPM (P6) and RLE image readers (PCX, BMP, DPX, Cineon in rd_*.c). */
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "image/image.h"
#include "image/imgread_int.h"

#define INBUF ((size_t)1 << 16)

/* ---- PPM ---- */

static int ppm_number(img_reader_t *r, unsigned *v)
{
	int rc;
	for (;;) {
		if ((rc = img_rd_fill(r)) <= 0)
			return rc < 0 ? rc : img_rd_bad(r, img_rd_offset(r), "truncated PPM header");
		unsigned char c = r->buf[r->pos];
		if (c == '#') {
			while ((rc = img_rd_fill(r)) > 0 && r->buf[r->pos] != '\n')
				r->pos++;
			if (rc < 0)
				return rc;
		} else if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
			r->pos++;
		} else {
			break;
		}
	}
	if (r->buf[r->pos] < '0' || r->buf[r->pos] > '9')
		return img_rd_bad(r, img_rd_offset(r), "expected a number in the PPM header");
	uint64_t at = img_rd_offset(r);
	unsigned long x = 0;
	while ((rc = img_rd_fill(r)) > 0 && r->buf[r->pos] >= '0' && r->buf[r->pos] <= '9') {
		if (x > 1000000)
			return img_rd_bad(r, at, "number too large in the PPM header");
		x = x * 10 + (unsigned)(r->buf[r->pos++] - '0');
	}
	if (rc < 0)
		return rc;
	*v = (unsigned)x;
	return 0;
}

static int ppm_open(img_reader_t *r)
{
	unsigned v[3];
	r->pos += 2;
	for (int k = 0; k < 3; k++) {
		int rc = ppm_number(r, &v[k]);
		if (rc)
			return rc;
		if (k == 1 && (v[0] == 0 || v[1] == 0 || v[0] > DEV_IMAGE_MAX_DIM || v[1] > DEV_IMAGE_MAX_DIM))
			return img_rd_bad(r, 3, "bad or too large PPM size (each side 1 to 65536)");
	}
	if (v[2] != 255)
		return img_rd_bad(r, img_rd_offset(r), "only PPM with maxval 255 is supported");
	int rc = img_rd_fill(r);
	if (rc <= 0)
		return rc < 0 ? rc : img_rd_bad(r, img_rd_offset(r), "truncated PPM header");
	r->pos++;   /* the single whitespace byte before the pixels */
	r->width = v[0];
	r->height = v[1];
	return 0;
}

static int ppm_row(img_reader_t *r, uint8_t *row)
{
	size_t n = (size_t)r->width * 3;
	long got = img_rd_take(r, row, n);
	if (got < 0)
		return (int)got;
	return (size_t)got < n ? img_rd_bad(r, img_rd_offset(r), "truncated PPM pixel data") : 0;
}

/* ---- RLE (docs/rle-format.md) ---- */

static uint32_t be32(const unsigned char *p)
{
	return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static int rle_open(img_reader_t *r)
{
	unsigned char h[DEV_RLE_HEADER];
	long got = img_rd_take(r, h, sizeof h);
	if (got < 0)
		return (int)got;
	if ((size_t)got < sizeof h)
		return img_rd_bad(r, img_rd_offset(r), "truncated RLE header");
	if (h[4] != DEV_RLE_VERSION)
		return img_rd_bad(r, 4, "unsupported RLE version");
	uint32_t w = be32(h + 5), ht = be32(h + 9);
	if (w == 0 || ht == 0 || w > DEV_IMAGE_MAX_DIM || ht > DEV_IMAGE_MAX_DIM)
		return img_rd_bad(r, 5, "bad or too large RLE size (each side 1 to 65536)");
	r->width = w;
	r->height = ht;
	return 0;
}

static int rle_row(img_reader_t *r, uint8_t *row)
{
	unsigned x = 0;
	while (x < r->width) {
		unsigned char q[4];
		uint64_t at = img_rd_offset(r);
		long got = img_rd_take(r, q, 4);
		if (got < 0)
			return (int)got;
		if (got < 4)
			return img_rd_bad(r, at, "truncated RLE data");
		unsigned c = (unsigned)q[0] + 1;
		if (x + c > r->width)
			return img_rd_bad(r, at, "RLE run crosses the end of its row");
		for (unsigned k = 0; k < c; k++)
			memcpy(row + 3 * (x + k), q + 1, 3);
		x += c;
	}
	return 0;
}

/* ---- PNG ---- */

static void png_in(png_structp png, png_bytep data, size_t n)
{
	img_reader_t *r = png_get_io_ptr(png);
	long got = img_rd_take(r, data, n);
	if (got < 0)
		png_error(png, "read error");
	if ((size_t)got < n)
		png_error(png, "truncated PNG data");
}

static void png_rerr(png_structp png, png_const_charp msg)
{
	img_reader_t *r = png_get_error_ptr(png);
	if (!r->ioerr)
		snprintf(r->err, sizeof r->err, "%s: byte %llu: bad PNG: %s", r->name,
			(unsigned long long)img_rd_offset(r), msg);
	png_longjmp(png, 1);
}

static void png_rwarn(png_structp png, png_const_charp msg)
{
	(void)png;
	(void)msg;
}

static int png_fail(img_reader_t *r)
{
	return r->ioerr ? -74 : -65;
}

static int png_open(img_reader_t *r)
{
	r->png = png_create_read_struct(PNG_LIBPNG_VER_STRING, r, png_rerr, png_rwarn);
	if (!r->png || !(r->info = png_create_info_struct(r->png))) {
		snprintf(r->err, sizeof r->err, "%s: out of memory", r->name);
		return -70;
	}
	if (setjmp(png_jmpbuf(r->png)))
		return png_fail(r);
	png_set_read_fn(r->png, r, png_in);
	png_set_user_limits(r->png, DEV_IMAGE_MAX_DIM, DEV_IMAGE_MAX_DIM);
	png_set_chunk_malloc_max(r->png, (png_alloc_size_t)8 << 20);
	png_read_info(r->png, r->info);
	png_uint_32 w, h;
	int depth, type, interlace;
	png_get_IHDR(r->png, r->info, &w, &h, &depth, &type, &interlace, NULL, NULL);
	if (interlace != PNG_INTERLACE_NONE)
		return img_rd_bad(r, 28, "interlaced PNG is not supported (it cannot be read a row at a time)");
	png_set_expand(r->png);
	png_set_scale_16(r->png);
	png_set_gray_to_rgb(r->png);
	png_read_update_info(r->png, r->info);
	r->channels = png_get_channels(r->png, r->info);
	if (r->channels != 3 && r->channels != 4)
		return img_rd_bad(r, 16, "unexpected PNG channel count");
	r->width = w;
	r->height = h;
	r->prow = malloc((size_t)w * r->channels);
	if (!r->prow) {
		snprintf(r->err, sizeof r->err, "%s: out of memory", r->name);
		return -70;
	}
	return 0;
}

static int png_row(img_reader_t *r, uint8_t *row)
{
	if (setjmp(png_jmpbuf(r->png)))
		return png_fail(r);
	png_read_row(r->png, r->channels == 3 ? row : r->prow, NULL);
	if (r->channels == 4)   /* composed on black */
		for (unsigned x = 0; x < r->width; x++)
			for (int c = 0; c < 3; c++)
				row[3 * x + c] = (uint8_t)((r->prow[4 * x + c] * r->prow[4 * x + 3] + 127) / 255);
	return 0;
}

static int png_finish(img_reader_t *r)
{
	if (setjmp(png_jmpbuf(r->png)))
		return png_fail(r);
	png_read_end(r->png, NULL);
	return 0;
}

/* ---- the reader ---- */

/* Open, the format told by the magic, or forced (a dump of fsize bytes). */
static int open_as(img_source_fn fn, void *user, const void *head, size_t nhead, const char *name,
		const img_rd_fmt_t *force, uint64_t fsize, img_reader_t **out, char *err, size_t errlen)
{
	*out = NULL;
	img_reader_t *r = calloc(1, sizeof *r);
	size_t cap = nhead > INBUF ? nhead : INBUF;
	if (!r || !(r->buf = malloc(cap))) {
		free(r);
		snprintf(err, errlen, "%s: out of memory", name);
		return -70;
	}
	r->fn = fn;
	r->user = user;
	r->cap = cap;
	snprintf(r->name, sizeof r->name, "%s", name);
	if (nhead)
		memcpy(r->buf, head, nhead);
	r->len = nhead;
	/* sniff: at least 8 bytes, as far as the stream has them */
	while (r->len < 8 && !r->eof) {
		long n = fn(user, r->buf + r->len, r->cap - r->len);
		if (n < 0) {
			r->ioerr = 1;
			snprintf(r->err, sizeof r->err, "%s: read error", name);
			break;
		}
		if (n == 0)
			r->eof = 1;
		r->len += (size_t)n;
	}
	int rc = r->ioerr ? -74 : 0;
	r->fsize = fsize;
	if (rc == 0 && force) {
		r->ops = force;
		r->fmt = IMG_FMT_UNKNOWN;
		rc = force->open(r);
	} else if (rc == 0) {
		const unsigned char *b = r->buf;
		if (r->len >= 8 && memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0)
			r->fmt = IMG_FMT_PNG, rc = png_open(r);
		else if (r->len >= 2 && b[0] == 'P' && b[1] == '6')
			r->fmt = IMG_FMT_PPM, rc = ppm_open(r);
		else if (r->len >= 4 && memcmp(b, DEV_RLE_MAGIC, 4) == 0)
			r->fmt = IMG_FMT_RLE, rc = rle_open(r);
		else if (img_rd_is_pcx(b, r->len))
			r->ops = &img_rd_pcx;
		else if (img_rd_is_bmp(b, r->len))
			r->ops = &img_rd_bmp;
		else if (img_rd_is_dpx(b, r->len))
			r->ops = &img_rd_dpx;
		else if (img_rd_is_cineon(b, r->len))
			r->ops = &img_rd_cineon;
		else
			rc = img_rd_bad(r, 0, "not a PNG, PPM (P6), Locus RLE, PCX, BMP, DPX or Cineon image");
		if (r->ops)
			r->fmt = IMG_FMT_UNKNOWN, rc = r->ops->open(r);
	}
	if (rc) {
		snprintf(err, errlen, "%s", r->err);
		img_reader_free(r);
		return rc;
	}
	*out = r;
	return 0;
}

int img_reader_open(img_source_fn fn, void *user, const void *head, size_t nhead, const char *name,
		img_reader_t **out, char *err, size_t errlen)
{
	return open_as(fn, user, head, nhead, name, NULL, 0, out, err, errlen);
}

int img_reader_sniff(const unsigned char *b, size_t n)
{
	return (n >= 8 && memcmp(b, "\x89PNG", 4) == 0) || (n >= 2 && b[0] == 'P' && b[1] == '6') ||
		(n >= 4 && memcmp(b, DEV_RLE_MAGIC, 4) == 0) || img_rd_is_pcx(b, n) || img_rd_is_bmp(b, n) ||
		img_rd_is_dpx(b, n) || img_rd_is_cineon(b, n);
}

int img_rd_open_fbdump(img_source_fn fn, void *user, const void *head, size_t nhead, const char *name,
		uint64_t size, img_reader_t **out, char *err, size_t errlen)
{
	return open_as(fn, user, head, nhead, name, &img_rd_fbdump, size, out, err, errlen);
}

unsigned img_reader_width(const img_reader_t *r)
{
	return r->width;
}

unsigned img_reader_height(const img_reader_t *r)
{
	return r->height;
}

int img_reader_row(img_reader_t *r, uint8_t *row)
{
	if (r->y >= r->height) {
		snprintf(r->err, sizeof r->err, "%s: read past the last row", r->name);
		return -70;
	}
	int rc = r->ops ? r->ops->row(r, row) : r->fmt == IMG_FMT_PNG ? png_row(r, row) : r->fmt == IMG_FMT_PPM ? ppm_row(r, row)
		: rle_row(r, row);
	if (rc == 0)
		r->y++;
	return rc;
}

int img_reader_end(img_reader_t *r)
{
	if (r->ops)
		return r->ops->end ? r->ops->end(r) : 0;
	if (r->fmt == IMG_FMT_PNG)
		return png_finish(r);
	if (r->fmt == IMG_FMT_RLE) {
		int rc = img_rd_fill(r);
		if (rc)
			return rc < 0 ? rc : img_rd_bad(r, img_rd_offset(r), "trailing bytes after the RLE image");
	}
	return 0;
}

const char *img_reader_error(const img_reader_t *r)
{
	return r->err;
}

void img_reader_free(img_reader_t *r)
{
	if (!r)
		return;
	if (r->ops && r->ops->done)
		r->ops->done(r);
	if (r->png)
		png_destroy_read_struct(&r->png, r->info ? &r->info : NULL, NULL);
	free(r->prow);
	free(r->buf);
	free(r);
}

/* ---- whole images from memory ---- */

typedef struct {
	const unsigned char *b;
	size_t n, at;
} membuf_t;

static long mem_read(void *user, void *buf, size_t n)
{
	membuf_t *m = user;
	size_t k = m->n - m->at < n ? m->n - m->at : n;
	memcpy(buf, m->b + m->at, k);
	m->at += k;
	return (long)k;
}

void img_free(img_t *img)
{
	free(img->pix);
	img->pix = NULL;
	img->width = img->height = 0;
}

int img_decode(const unsigned char *buf, size_t n, const char *name, img_t *img,
		char *err, size_t errlen)
{
	memset(img, 0, sizeof *img);
	membuf_t m = { buf, n, 0 };
	img_reader_t *r;
	int rc = img_reader_open(mem_read, &m, NULL, 0, name, &r, err, errlen);
	if (rc)
		return rc;
	size_t row = (size_t)r->width * 3, cap = 0;
	for (unsigned y = 0; y < r->height && rc == 0; y++) {
		if (y == cap) {   /* grow with the rows decoded, never from the header alone */
			size_t ncap = cap ? cap * 2 : 16;
			if (ncap > r->height)
				ncap = r->height;
			uint8_t *p = realloc(img->pix, ncap * row);
			if (!p) {
				snprintf(r->err, sizeof r->err, "%s: out of memory", r->name);
				rc = -70;
				break;
			}
			img->pix = p;
			cap = ncap;
		}
		rc = img_reader_row(r, img->pix + y * row);
	}
	if (rc == 0)
		rc = img_reader_end(r);
	if (rc) {
		snprintf(err, errlen, "%s", r->err);
		img_free(img);
	} else {
		img->width = r->width;
		img->height = r->height;
	}
	img_reader_free(r);
	return rc;
}
