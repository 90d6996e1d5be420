/* image.c: streaming PNG (libpng), PPM (P6) and RLE raster writers (readers: imgread.c). */
#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "image/image.h"

struct img_writer {
	int fmt;
	io_transport_t *t;
	img_sink_fn sink;       /* instead of t (img_writer_new_png_fn) */
	void *sink_user;
	unsigned width, height, rows;
	png_structp png;
	png_infop info;
	int io_failed, info_done;
	double wmm, hmm;
	unsigned char *rle;      /* one encoded row */
	int errcode;             /* the failure's errno (img_writer_errno), set where it is raised */
	char err[256];
};

int img_format_by_name(const char *name)
{
	if (!strcmp(name, "png")) return IMG_FMT_PNG;
	if (!strcmp(name, "ppm")) return IMG_FMT_PPM;
	if (!strcmp(name, "rle")) return IMG_FMT_RLE;
	return IMG_FMT_UNKNOWN;
}

int img_format_by_suffix(const char *path)
{
	const char *dot = strrchr(path, '.');
	const char *slash = strrchr(path, '/');
	if (!dot || (slash && dot < slash))
		return IMG_FMT_UNKNOWN;
	return img_format_by_name(dot + 1);
}

static void png_out(png_structp png, png_bytep data, size_t n)
{
	img_writer_t *w = png_get_io_ptr(png);
	if (w->sink ? w->sink(w->sink_user, data, n) : io_write(w->t, data, n)) {
		w->io_failed = 1;   /* the transport's message names the output and the cause */
		w->errcode = w->sink ? EIO : io_errno(w->t);
		snprintf(w->err, sizeof w->err, "%s", w->sink ? "png: write failed" : io_error(w->t));
		png_error(png, "write failed");
	}
}

static void png_flush_cb(png_structp png)
{
	(void)png;
}

static void png_err(png_structp png, png_const_charp msg)
{
	img_writer_t *w = png_get_error_ptr(png);
	/* libpng says "Out of memory", "insufficient memory", ...: one wording, so that the
	 * programs tell it from an I/O error (exit 70, not 74) */
	if (!w->io_failed) {
		/* libpng's error handler gets only the text: its out-of-memory errors become the code */
		w->errcode = strstr(msg, "memory") ? ENOMEM : EIO;
		snprintf(w->err, sizeof w->err, "png: %s", w->errcode == ENOMEM ? "out of memory" : msg);
	}
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

static int png_start(img_writer_t *w)
{
	w->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, w, png_err, png_warn);
	if (!w->png || !(w->info = png_create_info_struct(w->png))) {
		w->errcode = ENOMEM;
		snprintf(w->err, sizeof w->err, "png: out of memory");
		return -1;
	}
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
static int png_header(img_writer_t *w)
{
	if (setjmp(png_jmpbuf(w->png)))
		return -1;
	if (w->wmm > 0 && w->hmm > 0) {
		/* spec §4 `size`: pixels stay square; the pitch is the largest at which the page fits
		 * the size, so one resolution for both axes (the finer of the two) */
		double px = w->width / (w->wmm / 1000.0), py = w->height / (w->hmm / 1000.0);
		png_uint_32 ppm = (png_uint_32)((px > py ? px : py) + 0.5);
		png_set_pHYs(w->png, w->info, ppm, ppm, PNG_RESOLUTION_METER);
	}
	png_write_info(w->png, w->info);
	w->info_done = 1;
	return 0;
}

void img_writer_physical(img_writer_t *w, double width_mm, double height_mm)
{
	w->wmm = width_mm;
	w->hmm = height_mm;
}

img_writer_t *img_writer_new(int fmt, io_transport_t *t, unsigned width, unsigned height, char *err,
		size_t errlen)
{
	img_writer_t *w = calloc(1, sizeof *w);
	if (!w) {
		snprintf(err, errlen, "out of memory");
		errno = ENOMEM;
		return NULL;
	}
	w->fmt = fmt;
	w->t = t;
	w->width = width;
	w->height = height;
	int rc = 0;
	if (fmt == IMG_FMT_PPM) {
		char h[64];
		int n = snprintf(h, sizeof h, "P6\n%u %u\n255\n", width, height);
		rc = io_write(t, h, (size_t)n);
	} else if (fmt == IMG_FMT_RLE) {
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
	if (rc && fmt == IMG_FMT_RLE && !w->rle) {
		snprintf(err, errlen, "out of memory");
		img_writer_abort(w);
		errno = ENOMEM;
		return NULL;
	}
	if (rc) {
		int own = !w->io_failed && fmt == IMG_FMT_PNG, e = own ? w->errcode : io_errno(t);
		snprintf(err, errlen, "%s", own ? w->err : io_error(t));
		img_writer_abort(w);
		errno = e ? e : EIO;
		return NULL;
	}
	return w;
}

img_writer_t *img_writer_new_png_fn(img_sink_fn fn, void *user, int compact, unsigned width,
		unsigned height, char *err, size_t errlen)
{
	img_writer_t *w = calloc(1, sizeof *w);
	if (!w) {
		snprintf(err, errlen, "out of memory");
		return NULL;
	}
	w->fmt = IMG_FMT_PNG;
	w->sink = fn;
	w->sink_user = user;
	w->width = width;
	w->height = height;
	if (png_start(w)) {
		snprintf(err, errlen, "%s", w->err);
		img_writer_abort(w);
		return NULL;
	}
	if (compact) {
		png_set_compression_level(w->png, 9);
		png_set_filter(w->png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
	}
	return w;
}

static int rle_row(img_writer_t *w, const uint8_t *p)
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

static int png_rows(img_writer_t *w, const uint8_t *pix, size_t stride, unsigned n)
{
	if (setjmp(png_jmpbuf(w->png)))
		return -1;
	for (unsigned k = 0; k < n; k++)
		png_write_row(w->png, (png_const_bytep)(pix + k * stride));
	return 0;
}

int img_writer_rows(img_writer_t *w, const uint8_t *pix, size_t stride, unsigned n)
{
	int rc = 0;
	if (w->rows + n > w->height) {
		w->errcode = EINVAL;
		snprintf(w->err, sizeof w->err, "too many rows");
		return -1;
	}
	if (w->fmt == IMG_FMT_PNG) {
		rc = w->info_done ? 0 : png_header(w);
		if (rc == 0)
			rc = png_rows(w, pix, stride, n);
	} else {
		for (unsigned k = 0; k < n && rc == 0; k++)
			rc = w->fmt == IMG_FMT_RLE ? rle_row(w, pix + k * stride)
				: io_write(w->t, pix + k * stride, (size_t)w->width * 3);
		if (rc) {
			w->errcode = io_errno(w->t);
			snprintf(w->err, sizeof w->err, "%s", io_error(w->t));
		}
	}
	w->rows += n;
	return rc;
}

static int png_end(img_writer_t *w)
{
	if (setjmp(png_jmpbuf(w->png)))
		return -1;
	png_write_end(w->png, w->info);
	return 0;
}

int img_writer_finish(img_writer_t *w)
{
	int rc = 0;
	if (w->rows != w->height) {
		w->errcode = EINVAL;
		snprintf(w->err, sizeof w->err, "image incomplete (%u of %u rows)", w->rows, w->height);
		rc = -1;
	} else if (w->fmt == IMG_FMT_PNG) {
		rc = png_end(w);
	}
	if (rc == 0 && !w->sink && (rc = io_flush(w->t)) != 0) {
		w->errcode = io_errno(w->t);
		snprintf(w->err, sizeof w->err, "%s", io_error(w->t));
	}
	if (rc)
		return rc;   /* caller reads the message, then aborts */
	img_writer_abort(w);
	return 0;
}

void img_writer_abort(img_writer_t *w)
{
	if (!w)
		return;
	if (w->png)
		png_destroy_write_struct(&w->png, w->info ? &w->info : NULL);
	free(w->rle);
	free(w);
}

int img_writer_errno(const img_writer_t *w)
{
	return w->errcode ? w->errcode : EIO;
}

const char *img_writer_error(const img_writer_t *w)
{
	return w->err;
}
