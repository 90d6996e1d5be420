/* image.c: streaming PNG (libpng), PPM (P6) and RLE raster writers, and their readers. */
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "image.h"

struct dev_imgw {
	int fmt;
	io_transport_t *t;
	unsigned width, height, rows;
	png_structp png;
	png_infop info;
	int io_failed, info_done;
	double wmm, hmm;
	unsigned char *rle;      /* one encoded row */
	char err[256];
};

int dev_format_by_name(const char *name)
{
	if (!strcmp(name, "png")) return DEV_FMT_PNG;
	if (!strcmp(name, "ppm")) return DEV_FMT_PPM;
	if (!strcmp(name, "rle")) return DEV_FMT_RLE;
	return DEV_FMT_UNKNOWN;
}

int dev_format_by_suffix(const char *path)
{
	const char *dot = strrchr(path, '.');
	const char *slash = strrchr(path, '/');
	if (!dot || (slash && dot < slash))
		return DEV_FMT_UNKNOWN;
	return dev_format_by_name(dot + 1);
}

const char *dev_format_suffix(int fmt)
{
	return fmt == DEV_FMT_PPM ? ".ppm" : fmt == DEV_FMT_RLE ? ".rle" : ".png";
}

static void png_out(png_structp png, png_bytep data, size_t n)
{
	dev_imgw_t *w = png_get_io_ptr(png);
	if (io_write(w->t, data, n)) {
		w->io_failed = 1;
		png_error(png, "write failed");
	}
}

static void png_flush_cb(png_structp png)
{
	(void)png;
}

static void png_err(png_structp png, png_const_charp msg)
{
	dev_imgw_t *w = png_get_error_ptr(png);
	snprintf(w->err, sizeof w->err, "png: %s", msg);
	png_longjmp(png, 1);
}

static void png_warn(png_structp png, png_const_charp msg)
{
	(void)png;
	(void)msg;
}

static void put_be32(unsigned char *p, uint32_t v)
{
	p[0] = (unsigned char)(v >> 24); p[1] = (unsigned char)(v >> 16);
	p[2] = (unsigned char)(v >> 8); p[3] = (unsigned char)v;
}

static int png_start(dev_imgw_t *w)
{
	w->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, w, png_err, png_warn);
	if (!w->png || !(w->info = png_create_info_struct(w->png)))
		return -1;
	if (setjmp(png_jmpbuf(w->png)))
		return -1;
	png_set_write_fn(w->png, w, png_out, png_flush_cb);
	png_set_IHDR(w->png, w->info, w->width, w->height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
		PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	png_set_compression_level(w->png, 3);
	png_set_filter(w->png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
	return 0;
}

/* The PNG header goes out with the first rows, so that the physical size can still be set. */
static int png_header(dev_imgw_t *w)
{
	if (setjmp(png_jmpbuf(w->png)))
		return -1;
	if (w->wmm > 0 && w->hmm > 0)
		png_set_pHYs(w->png, w->info, (png_uint_32)(w->width / (w->wmm / 1000.0) + 0.5),
			(png_uint_32)(w->height / (w->hmm / 1000.0) + 0.5), PNG_RESOLUTION_METER);
	png_write_info(w->png, w->info);
	w->info_done = 1;
	return 0;
}

void dev_imgw_physical(dev_imgw_t *w, double width_mm, double height_mm)
{
	w->wmm = width_mm;
	w->hmm = height_mm;
}

dev_imgw_t *dev_imgw_new(int fmt, io_transport_t *t, unsigned width, unsigned height, char *err,
		size_t errlen)
{
	dev_imgw_t *w = calloc(1, sizeof *w);
	if (!w) {
		snprintf(err, errlen, "out of memory");
		return NULL;
	}
	w->fmt = fmt;
	w->t = t;
	w->width = width;
	w->height = height;
	int rc = 0;
	if (fmt == DEV_FMT_PPM) {
		char h[64];
		int n = snprintf(h, sizeof h, "P6\n%u %u\n255\n", width, height);
		rc = io_write(t, h, (size_t)n);
	} else if (fmt == DEV_FMT_RLE) {
		unsigned char h[DEV_RLE_HEADER];
		memcpy(h, DEV_RLE_MAGIC, 4);
		h[4] = DEV_RLE_VERSION;
		put_be32(h + 5, width);
		put_be32(h + 9, height);
		w->rle = malloc((size_t)width * 4);
		rc = w->rle ? io_write(t, h, sizeof h) : -1;
	} else {
		rc = png_start(w);
	}
	if (rc) {
		snprintf(err, errlen, "%s", w->io_failed || fmt != DEV_FMT_PNG ? io_error(t) : w->err);
		dev_imgw_abort(w);
		return NULL;
	}
	return w;
}

static int rle_row(dev_imgw_t *w, const uint8_t *p)
{
	unsigned char *o = w->rle;
	unsigned x = 0;
	while (x < w->width) {
		unsigned n = 1;
		while (x + n < w->width && n < 256 && memcmp(p + 3 * (x + n), p + 3 * x, 3) == 0)
			n++;
		*o++ = (unsigned char)(n - 1);
		memcpy(o, p + 3 * x, 3);
		o += 3;
		x += n;
	}
	return io_write(w->t, w->rle, (size_t)(o - w->rle));
}

static int png_rows(dev_imgw_t *w, const uint8_t *pix, size_t stride, unsigned n)
{
	if (setjmp(png_jmpbuf(w->png)))
		return -1;
	for (unsigned k = 0; k < n; k++)
		png_write_row(w->png, (png_const_bytep)(pix + k * stride));
	return 0;
}

int dev_imgw_rows(dev_imgw_t *w, const uint8_t *pix, size_t stride, unsigned n)
{
	int rc = 0;
	if (w->rows + n > w->height) {
		snprintf(w->err, sizeof w->err, "too many rows");
		return -1;
	}
	if (w->fmt == DEV_FMT_PNG) {
		rc = w->info_done ? 0 : png_header(w);
		if (rc == 0)
			rc = png_rows(w, pix, stride, n);
	} else {
		for (unsigned k = 0; k < n && rc == 0; k++)
			rc = w->fmt == DEV_FMT_RLE ? rle_row(w, pix + k * stride)
				: io_write(w->t, pix + k * stride, (size_t)w->width * 3);
		if (rc)
			snprintf(w->err, sizeof w->err, "%s", io_error(w->t));
	}
	w->rows += n;
	return rc;
}

static int png_end(dev_imgw_t *w)
{
	if (setjmp(png_jmpbuf(w->png)))
		return -1;
	png_write_end(w->png, w->info);
	return 0;
}

int dev_imgw_finish(dev_imgw_t *w)
{
	int rc = 0;
	if (w->rows != w->height) {
		snprintf(w->err, sizeof w->err, "image incomplete (%u of %u rows)", w->rows, w->height);
		rc = -1;
	} else if (w->fmt == DEV_FMT_PNG) {
		rc = png_end(w);
	}
	if (rc == 0)
		rc = io_flush(w->t);
	if (rc)
		return rc;   /* caller reads the message, then aborts */
	dev_imgw_abort(w);
	return 0;
}

void dev_imgw_abort(dev_imgw_t *w)
{
	if (!w)
		return;
	if (w->png)
		png_destroy_write_struct(&w->png, w->info ? &w->info : NULL);
	free(w->rle);
	free(w);
}

const char *dev_imgw_error(const dev_imgw_t *w)
{
	return w->err;
}

/* ---- readers ---- */

void dev_image_free(dev_image_t *img)
{
	free(img->pix);
	img->pix = NULL;
	img->width = img->height = 0;
}

static int bad(char *err, size_t errlen, const char *name, size_t off, const char *what)
{
	snprintf(err, errlen, "%s: byte %zu: %s", name, off, what);
	return -65;
}

static int alloc_img(dev_image_t *img, unsigned w, unsigned h)
{
	if (w == 0 || h == 0 || w > 65536 || h > 65536)
		return -1;
	img->width = w;
	img->height = h;
	img->pix = malloc((size_t)w * h * 3);
	return img->pix ? 0 : -1;
}

static int load_ppm(const unsigned char *b, size_t n, const char *name, dev_image_t *img, char *err, size_t el)
{
	size_t i = 2;
	unsigned v[3];
	for (int k = 0; k < 3; k++) {
		while (i < n && (b[i] == ' ' || b[i] == '\t' || b[i] == '\n' || b[i] == '\r' || b[i] == '#')) {
			if (b[i] == '#')
				while (i < n && b[i] != '\n')
					i++;
			else
				i++;
		}
		if (i >= n || b[i] < '0' || b[i] > '9')
			return bad(err, el, name, i, "expected a number in the PPM header");
		unsigned long x = 0;
		while (i < n && b[i] >= '0' && b[i] <= '9' && x < 1000000)
			x = x * 10 + (unsigned)(b[i++] - '0');
		v[k] = (unsigned)x;
	}
	if (v[2] != 255)
		return bad(err, el, name, i, "only PPM with maxval 255 is supported");
	if (i >= n)
		return bad(err, el, name, i, "truncated PPM header");
	i++;
	if (alloc_img(img, v[0], v[1]))
		return bad(err, el, name, 3, "bad or too large PPM size");
	size_t need = (size_t)v[0] * v[1] * 3;
	if (n - i < need) {
		dev_image_free(img);
		return bad(err, el, name, n, "truncated PPM pixel data");
	}
	memcpy(img->pix, b + i, need);
	return 0;
}

static uint32_t be32(const unsigned char *p)
{
	return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static int load_rle(const unsigned char *b, size_t n, const char *name, dev_image_t *img, char *err, size_t el)
{
	if (n < DEV_RLE_HEADER)
		return bad(err, el, name, n, "truncated RLE header");
	if (b[4] != DEV_RLE_VERSION)
		return bad(err, el, name, 4, "unsupported RLE version");
	if (alloc_img(img, be32(b + 5), be32(b + 9)))
		return bad(err, el, name, 5, "bad or too large RLE size");
	size_t i = DEV_RLE_HEADER;
	for (unsigned y = 0; y < img->height; y++) {
		unsigned x = 0;
		uint8_t *row = img->pix + (size_t)y * img->width * 3;
		while (x < img->width) {
			if (n - i < 4) {
				dev_image_free(img);
				return bad(err, el, name, i, "truncated RLE data");
			}
			unsigned c = (unsigned)b[i] + 1;
			if (x + c > img->width) {
				dev_image_free(img);
				return bad(err, el, name, i, "RLE run crosses the end of its row");
			}
			for (unsigned k = 0; k < c; k++)
				memcpy(row + 3 * (x + k), b + i + 1, 3);
			x += c;
			i += 4;
		}
	}
	if (i != n) {
		dev_image_free(img);
		return bad(err, el, name, i, "trailing bytes after the RLE image");
	}
	return 0;
}

static int load_png(const unsigned char *b, size_t n, const char *name, dev_image_t *img, char *err, size_t el)
{
	png_image pi;
	memset(&pi, 0, sizeof pi);
	pi.version = PNG_IMAGE_VERSION;
	if (!png_image_begin_read_from_memory(&pi, b, n)) {
		snprintf(err, el, "%s: bad PNG: %s", name, pi.message);
		return -65;
	}
	pi.format = PNG_FORMAT_RGB;
	if (alloc_img(img, pi.width, pi.height)) {
		png_image_free(&pi);
		return bad(err, el, name, 16, "bad or too large PNG size");
	}
	if (!png_image_finish_read(&pi, NULL, img->pix, 0, NULL)) {
		snprintf(err, el, "%s: bad PNG: %s", name, pi.message);
		dev_image_free(img);
		return -65;
	}
	return 0;
}

int dev_image_decode(const unsigned char *b, size_t n, const char *name, dev_image_t *img,
		char *err, size_t errlen)
{
	memset(img, 0, sizeof *img);
	if (n >= 8 && memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0)
		return load_png(b, n, name, img, err, errlen);
	if (n >= 2 && b[0] == 'P' && b[1] == '6')
		return load_ppm(b, n, name, img, err, errlen);
	if (n >= 4 && memcmp(b, DEV_RLE_MAGIC, 4) == 0)
		return load_rle(b, n, name, img, err, errlen);
	return bad(err, errlen, name, 0, "not a PNG, PPM (P6) or Locus RLE image");
}

int dev_image_load(const char *path, dev_image_t *img, char *err, size_t errlen)
{
	io_transport_t *t = io_open_read(path, err, errlen);
	if (!t)
		return -66;
	size_t cap = 1 << 16, n = 0;
	unsigned char *b = malloc(cap);
	long r = 0;
	while (b) {
		if (n == cap) {
			unsigned char *q = realloc(b, cap * 2);
			if (!q)
				break;
			b = q;
			cap *= 2;
		}
		r = io_read(t, b + n, cap - n);
		if (r <= 0)
			break;
		n += (size_t)r;
	}
	if (!b || r < 0) {
		snprintf(err, errlen, "%s", b ? io_error(t) : "out of memory");
		free(b);
		io_close(t, IO_ABORT);
		return -66;
	}
	io_close(t, IO_ABORT);
	int rc = dev_image_decode(b, n, strcmp(path, "-") ? path : "<stdin>", img, err, errlen);
	free(b);
	return rc;
}
