/* fbout.c: write a framebuffer picture as a video memory dump, indexed PNG, PCX or BMP. */
#include <errno.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fb/fbout.h"

int fbout_format_by_name(const char *name)
{
	static const char *const names[] = { "dump", "png", "pcx", "bmp" };
	for (int k = 0; k < 4; k++)
		if (strcmp(name, names[k]) == 0)
			return k;
	return FBOUT_UNKNOWN;
}

int fbout_format_by_suffix(const char *path)
{
	const char *dot = strrchr(path, '.');
	if (!dot || strchr(dot, '/'))
		return FBOUT_UNKNOWN;
	dot++;
	char s[8];
	size_t n = strlen(dot);
	if (n >= sizeof s)
		return FBOUT_UNKNOWN;
	for (size_t k = 0; k <= n; k++)
		s[k] = (char)(dot[k] >= 'A' && dot[k] <= 'Z' ? dot[k] + 32 : dot[k]);
	return fbout_format_by_name(s);
}

/* The 8-bit colour of pixel k (any layout). */
static void rgb_of(const fbout_picture_t *p, size_t k, uint8_t *c)
{
	if (p->layout == FBOUT_DIRECT565) {
		unsigned v = p->pix[k], r = v >> 11, g = v >> 5 & 63, b = v & 31;
		c[0] = (uint8_t)(r << 3 | r >> 2), c[1] = (uint8_t)(g << 2 | g >> 4), c[2] = (uint8_t)(b << 3 | b >> 2);
	} else {
		const uint8_t *d = p->pal->dac[p->idx[k]];
		for (int i = 0; i < 3; i++)
			c[i] = (uint8_t)quant_show(p->pal, d[i]);
	}
}

/* Pixel density in some unit for x and y, in the ratio of the pixel shape (y fixed at base). */
static unsigned density_x(const fbout_picture_t *p, unsigned base)
{
	double a = p->pixel_aspect > 0 ? p->pixel_aspect : 1;
	return (unsigned)(base / a + 0.5);
}

typedef struct {
	io_transport_t *t;
	char *err;
	size_t errlen;
	uint8_t buf[4096];
	size_t n;
	int failed;
	int code;           /* the failure's errno, set where it is raised (fbout_write returns -code) */
} wbuf_t;

static void put(wbuf_t *w, const void *data, size_t n)
{
	if (w->failed)
		return;
	if (io_write(w->t, data, n)) {
		snprintf(w->err, w->errlen, "%s", io_error(w->t));
		w->code = io_errno(w->t);
		w->failed = 1;
	}
}

static void put_byte(wbuf_t *w, unsigned v)
{
	w->buf[w->n++] = (uint8_t)v;
	if (w->n == sizeof w->buf) {
		put(w, w->buf, w->n);
		w->n = 0;
	}
}

static void put_le(wbuf_t *w, uint32_t v, int bytes)
{
	for (int k = 0; k < bytes; k++)
		put_byte(w, v >> (8 * k) & 0xff);
}

static void drain(wbuf_t *w)
{
	if (w->n)
		put(w, w->buf, w->n);
	w->n = 0;
}

/* ---- dump --------------------------------------------------------------------------- */

static void write_dump(wbuf_t *w, const fbout_picture_t *p)
{
	size_t px = (size_t)p->width * p->height;
	if (p->layout == FBOUT_DIRECT565) {
		for (size_t k = 0; k < px; k++)
			put_le(w, p->pix[k], 2);
		return;
	}
	unsigned ncol = 256;
	if (p->layout == FBOUT_PLANAR4) {
		unsigned bpl = (p->width + 7) / 8;
		for (int plane = 0; plane < 4; plane++)
			for (unsigned y = 0; y < p->height; y++)
				for (unsigned xb = 0; xb < bpl; xb++) {
					unsigned v = 0;
					for (unsigned bit = 0; bit < 8; bit++) {
						unsigned x = xb * 8 + bit;
						if (x < p->width && (p->idx[(size_t)y * p->width + x] >> plane & 1))
							v |= 0x80u >> bit;
					}
					put_byte(w, v);
				}
		ncol = 16;
	} else {
		drain(w);
		put(w, p->idx, px);
	}
	for (unsigned k = 0; k < ncol; k++)
		for (int c = 0; c < 3; c++)
			put_byte(w, k < p->pal->n ? p->pal->dac[k][c] : 0);
}

/* ---- PNG (libpng) ------------------------------------------------------------------- */

static void png_out(png_structp png, png_bytep data, size_t n)
{
	wbuf_t *w = png_get_io_ptr(png);
	put(w, data, n);
	if (w->failed)
		png_error(png, "write failed");
}

static void png_noflush(png_structp png) { (void)png; }

static void png_err(png_structp png, png_const_charp msg)
{
	wbuf_t *w = png_get_error_ptr(png);
	if (!w->failed) {   /* libpng's handler gets only the text: its out-of-memory errors become the code */
		w->code = strstr(msg, "memory") ? ENOMEM : EIO;
		snprintf(w->err, w->errlen, "png: %s", w->code == ENOMEM ? "out of memory" : msg);
	}
	w->failed = 1;
	png_longjmp(png, 1);
}

static void png_warn(png_structp png, png_const_charp msg) { (void)png; (void)msg; }

static int write_png(wbuf_t *w, const fbout_picture_t *p)
{
	png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, w, png_err, png_warn);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	uint8_t *row = malloc((size_t)p->width * 3 + 1);
	int rc = -1;
	if (!png || !info || !row) {
		snprintf(w->err, w->errlen, "png: out of memory");
		w->code = ENOMEM;
		goto done;
	}
	if (setjmp(png_jmpbuf(png)))
		goto done;
	png_set_write_fn(png, w, png_out, png_noflush);
	int direct = p->layout == FBOUT_DIRECT565, depth = p->layout == FBOUT_PLANAR4 ? 4 : 8;
	png_set_IHDR(png, info, p->width, p->height, depth, direct ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_PALETTE,
		PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	if (!direct) {
		png_color plte[QUANT_MAX];
		unsigned n = p->pal->n ? p->pal->n : 1;
		if (depth == 4 && n > 16)
			n = 16;
		memset(plte, 0, sizeof plte);
		for (unsigned k = 0; k < p->pal->n && k < n; k++) {
			plte[k].red = (png_byte)quant_show(p->pal, p->pal->dac[k][0]);
			plte[k].green = (png_byte)quant_show(p->pal, p->pal->dac[k][1]);
			plte[k].blue = (png_byte)quant_show(p->pal, p->pal->dac[k][2]);
		}
		png_set_PLTE(png, info, plte, (int)n);
	}
	png_set_pHYs(png, info, density_x(p, 1000), 1000, PNG_RESOLUTION_UNKNOWN);
	/* no filters for indices (the PNG book's advice for palette images), zlib level 3: measured
	 * on the benchmark pictures, much faster than the defaults for a few per cent more bytes */
	png_set_compression_level(png, 3);
	png_set_filter(png, PNG_FILTER_TYPE_BASE, direct ? PNG_FILTER_SUB : PNG_FILTER_NONE);
	png_write_info(png, info);
	for (unsigned y = 0; y < p->height; y++) {
		size_t base = (size_t)y * p->width;
		if (direct) {
			for (unsigned x = 0; x < p->width; x++)
				rgb_of(p, base + x, row + 3 * x);
		} else if (depth == 4) {
			memset(row, 0, (p->width + 1) / 2);
			for (unsigned x = 0; x < p->width; x++)
				row[x / 2] |= (uint8_t)((p->idx[base + x] & 15) << (x & 1 ? 0 : 4));
		} else {
			memcpy(row, p->idx + base, p->width);
		}
		png_write_row(png, row);
		if (y + 1 < p->height && p->wait_row && p->wait_row(p->wait_ctx, y + 1)) {
			snprintf(w->err, w->errlen, "png: the picture was not finished");
			goto done;
		}
	}
	png_write_end(png, info);
	rc = 0;
done:
	png_destroy_write_struct(&png, &info);
	free(row);
	return rc;
}

/* ---- PCX (version 5, RLE) ----------------------------------------------------------- */

static void pcx_line(wbuf_t *w, const uint8_t *b, unsigned n)
{
	for (unsigned x = 0; x < n;) {
		unsigned run = 1;
		while (x + run < n && run < 63 && b[x + run] == b[x])
			run++;
		if (run > 1 || b[x] >= 0xc0)
			put_byte(w, 0xc0 | run);
		put_byte(w, b[x]);
		x += run;
	}
}

/* 256-colour and direct modes: one plane of 8-bit indices, the palette after 0x0C at the end
 * (24-bit: three planes of R, G, B). The 16-colour planar mode as PCX 16-colour files are
 * (the EGA's own layout): four planes of 1 bit, plane k holding bit k of each index, the most
 * significant bit the leftmost pixel, and the 16-colour palette in the header. */
static int write_pcx(wbuf_t *w, const fbout_picture_t *p)
{
	int direct = p->layout == FBOUT_DIRECT565, planar = p->layout == FBOUT_PLANAR4;
	unsigned planes = direct ? 3 : planar ? 4 : 1;
	unsigned bpl = planar ? ((p->width + 7) / 8 + 1) & ~1u : (p->width + 1) & ~1u;
	uint8_t *line = calloc(bpl, 1);
	if (!line) {
		snprintf(w->err, w->errlen, "pcx: out of memory");
		w->code = ENOMEM;
		return -1;
	}
	uint8_t hdr[128];
	memset(hdr, 0, sizeof hdr);
	hdr[0] = 10, hdr[1] = 5, hdr[2] = 1, hdr[3] = planar ? 1 : 8;
	unsigned v[8] = { 0, 0, p->width - 1, p->height - 1, density_x(p, 300), 300 };
	for (int k = 0; k < 6; k++)
		hdr[4 + 2 * k] = (uint8_t)v[k], hdr[5 + 2 * k] = (uint8_t)(v[k] >> 8);
	if (planar)                  /* the 16-colour palette: bytes 16..63 */
		for (unsigned k = 0; k < 16; k++)
			for (int c = 0; c < 3; c++)
				hdr[16 + 3 * k + c] = (uint8_t)(k < p->pal->n ? quant_show(p->pal, p->pal->dac[k][c]) : 0);
	hdr[65] = (uint8_t)planes;
	hdr[66] = (uint8_t)bpl, hdr[67] = (uint8_t)(bpl >> 8);
	hdr[68] = 1;                 /* palette info: colour */
	hdr[70] = (uint8_t)p->width, hdr[71] = (uint8_t)(p->width >> 8);
	hdr[72] = (uint8_t)p->height, hdr[73] = (uint8_t)(p->height >> 8);
	put(w, hdr, sizeof hdr);
	for (unsigned y = 0; y < p->height; y++) {
		size_t base = (size_t)y * p->width;
		for (unsigned plane = 0; plane < planes; plane++) {
			if (planar) {
				memset(line, 0, bpl);
				for (unsigned x = 0; x < p->width; x++)
					if (p->idx[base + x] >> plane & 1)
						line[x / 8] |= (uint8_t)(0x80 >> (x & 7));
			} else {
				for (unsigned x = 0; x < p->width; x++) {
					if (direct) {
						uint8_t c[3];
						rgb_of(p, base + x, c);
						line[x] = c[plane];
					} else {
						line[x] = p->idx[base + x];
					}
				}
			}
			pcx_line(w, line, bpl);
		}
	}
	if (!direct && !planar) {
		put_byte(w, 0x0c);
		for (unsigned k = 0; k < 256; k++)
			for (int c = 0; c < 3; c++)
				put_byte(w, k < p->pal->n ? quant_show(p->pal, p->pal->dac[k][c]) : 0);
	}
	free(line);
	return 0;
}

/* ---- BMP (BI_RGB, bottom-up) -------------------------------------------------------- */

static int write_bmp(wbuf_t *w, const fbout_picture_t *p)
{
	int bits = p->layout == FBOUT_DIRECT565 ? 24 : p->layout == FBOUT_PLANAR4 ? 4 : 8;
	unsigned ncol = bits == 24 ? 0 : 1u << bits;
	size_t rowbytes = (((size_t)p->width * bits + 31) / 32) * 4;
	size_t off = 14 + 40 + 4 * (size_t)ncol, total = off + rowbytes * p->height;
	if (total > 0xffffffffu) {
		snprintf(w->err, w->errlen, "bmp: picture too large");
		return -1;
	}
	put_byte(w, 'B'), put_byte(w, 'M');
	put_le(w, (uint32_t)total, 4), put_le(w, 0, 4), put_le(w, (uint32_t)off, 4);
	put_le(w, 40, 4), put_le(w, p->width, 4), put_le(w, p->height, 4);   /* height > 0: bottom-up */
	put_le(w, 1, 2), put_le(w, (uint32_t)bits, 2), put_le(w, 0, 4);      /* BI_RGB */
	put_le(w, (uint32_t)(rowbytes * p->height), 4);
	put_le(w, density_x(p, 2835), 4), put_le(w, 2835, 4);                /* 72 dpi high */
	put_le(w, ncol, 4), put_le(w, 0, 4);
	for (unsigned k = 0; k < ncol; k++) {
		const uint8_t *d = k < p->pal->n ? p->pal->dac[k] : (const uint8_t *)"\0\0\0";
		put_byte(w, quant_show(p->pal, d[2])), put_byte(w, quant_show(p->pal, d[1])), put_byte(w, quant_show(p->pal, d[0]));
		put_byte(w, 0);
	}
	for (unsigned yy = p->height; yy-- > 0;) {
		size_t base = (size_t)yy * p->width, done = 0;
		for (unsigned x = 0; x < p->width;) {
			if (bits == 24) {
				uint8_t c[3];
				rgb_of(p, base + x, c);
				put_byte(w, c[2]), put_byte(w, c[1]), put_byte(w, c[0]);
				x++, done += 3;
			} else if (bits == 8) {
				put_byte(w, p->idx[base + x]);
				x++, done++;
			} else {
				unsigned hi = p->idx[base + x] & 15, lo = x + 1 < p->width ? p->idx[base + x + 1] & 15 : 0;
				put_byte(w, hi << 4 | lo);
				x += 2, done++;
			}
		}
		for (; done < rowbytes; done++)
			put_byte(w, 0);
	}
	return 0;
}

int fbout_write(io_transport_t *t, int format, const fbout_picture_t *p, char *err, size_t errlen)
{
	wbuf_t *w = calloc(1, sizeof *w);
	if (!w) {
		snprintf(err, errlen, "out of memory");
		return -ENOMEM;
	}
	w->t = t, w->err = err, w->errlen = errlen;
	int rc;
	/* rows still being mapped: a PNG waits row by row, the other formats for the whole */
	for (unsigned y = 0; p->wait_row && y < (format == FBOUT_PNG ? 1 : p->height); y++)
		if (p->wait_row(p->wait_ctx, y)) {
			snprintf(err, errlen, "the picture was not finished");
			free(w);
			return -EIO;
		}
	switch (format) {
	case FBOUT_DUMP: write_dump(w, p); rc = 0; break;
	case FBOUT_PNG: drain(w); rc = write_png(w, p); break;
	case FBOUT_PCX: rc = write_pcx(w, p); break;
	case FBOUT_BMP: rc = write_bmp(w, p); break;
	default:
		snprintf(err, errlen, "unknown output format %d", format);
		rc = -1;
	}
	drain(w);
	if (w->failed || rc)
		rc = -(w->code ? w->code : EIO);
	free(w);
	return rc;
}
