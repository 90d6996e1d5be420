/* rd_pcx.c: ZSoft PCX reader (1-bit mono, 16-colour planes, 8-bit palette, 24-bit RGB planes). */
#include <stdlib.h>
#include <string.h>
#include "image/imgread_int.h"

#define PCX_HEADER 128

typedef struct {
	unsigned bpp, planes, bpl;      /* bits per pixel per plane, planes, bytes per plane line */
	unsigned char pal16[48];
	unsigned char pal256[768];
	unsigned char *line;            /* one decoded scan line (planes * bpl bytes) */
	unsigned runleft, runval;       /* a run that crosses a scan line */
	uint8_t *idx;                   /* 8-bit palette files: every index, the palette is at the end */
	size_t nidx;
} pcx_t;

int img_rd_is_pcx(const unsigned char *b, size_t n)
{
	return n >= 4 && b[0] == 0x0A && b[1] <= 5 && b[2] == 1 &&
		(b[3] == 1 || b[3] == 2 || b[3] == 4 || b[3] == 8);
}

static unsigned le16(const unsigned char *p)
{
	return (unsigned)p[0] | (unsigned)p[1] << 8;
}

/* Decode one scan line of planes * bpl bytes. */
static int pcx_line(img_reader_t *r, pcx_t *p)
{
	size_t n = (size_t)p->planes * p->bpl, k = 0;
	while (k < n) {
		if (p->runleft) {
			p->line[k++] = (unsigned char)p->runval;
			p->runleft--;
			continue;
		}
		unsigned char c;
		long got = img_rd_take(r, &c, 1);
		if (got < 0)
			return (int)got;
		if (got == 0)
			return img_rd_bad(r, img_rd_offset(r), "truncated PCX data");
		if ((c & 0xC0) == 0xC0) {
			unsigned char v;
			got = img_rd_take(r, &v, 1);
			if (got < 0)
				return (int)got;
			if (got == 0)
				return img_rd_bad(r, img_rd_offset(r), "truncated PCX run");
			p->runleft = c & 0x3F;
			p->runval = v;
		} else {
			p->line[k++] = c;
		}
	}
	return 0;
}

static int pcx_open(img_reader_t *r)
{
	unsigned char h[PCX_HEADER];
	long got = img_rd_take(r, h, sizeof h);
	if (got < 0)
		return (int)got;
	if ((size_t)got < sizeof h)
		return img_rd_bad(r, img_rd_offset(r), "truncated PCX header");
	unsigned x0 = le16(h + 4), y0 = le16(h + 6), x1 = le16(h + 8), y1 = le16(h + 10);
	if (x1 < x0 || y1 < y0)
		return img_rd_bad(r, 4, "bad PCX window (xmax < xmin or ymax < ymin)");
	pcx_t *p = calloc(1, sizeof *p);
	if (!p)
		return img_rd_nomem(r);
	r->st = p;
	p->bpp = h[3];
	p->planes = h[65];
	p->bpl = le16(h + 66);
	memcpy(p->pal16, h + 16, 48);
	r->width = x1 - x0 + 1;
	r->height = y1 - y0 + 1;
	int ok = (p->bpp == 8 && (p->planes == 1 || p->planes == 3 || p->planes == 4)) ||
		(p->bpp == 1 && (p->planes == 1 || p->planes == 4)) || (p->bpp == 4 && p->planes == 1) ||
		(p->bpp == 2 && p->planes == 1);
	if (!ok)
		return img_rd_bad(r, 3, "unsupported PCX depth (bits per pixel x planes)");
	if (p->bpl == 0 || p->bpl & 1 || (uint64_t)p->bpl * 8 < (uint64_t)r->width * p->bpp)
		return img_rd_bad(r, 66, "bad PCX bytes per line (even, and enough for the width)");
	if (!(p->line = malloc((size_t)p->planes * p->bpl)))
		return img_rd_nomem(r);
	if (p->bpp == 8 && p->planes == 1) {
		/* the palette follows the pixels: decode them all first, growing with the data */
		if ((uint64_t)r->width * r->height > IMGR_BUFFERED_MAX)
			return img_rd_bad(r, 4, "PCX with its palette at the end is too large to buffer");
		size_t cap = 0;
		for (unsigned y = 0; y < r->height; y++) {
			int rc = pcx_line(r, p);
			if (rc)
				return rc;
			if (p->nidx + r->width > cap) {
				size_t ncap = cap ? cap * 2 : (size_t)r->width * 16;
				uint8_t *q = realloc(p->idx, ncap);
				if (!q)
					return img_rd_nomem(r);
				p->idx = q;
				cap = ncap;
			}
			memcpy(p->idx + p->nidx, p->line, r->width);
			p->nidx += r->width;
		}
		unsigned char m;
		uint64_t at = img_rd_offset(r);
		got = img_rd_take(r, &m, 1);
		if (got < 0)
			return (int)got;
		if (got == 0 || m != 0x0C)
			return img_rd_bad(r, at, "expected the 256-colour PCX palette (byte 12) after the pixels");
		got = img_rd_take(r, p->pal256, 768);
		if (got < 0)
			return (int)got;
		if (got < 768)
			return img_rd_bad(r, img_rd_offset(r), "truncated PCX palette");
	}
	return 0;
}

static int pcx_row(img_reader_t *r, uint8_t *row)
{
	pcx_t *p = r->st;
	unsigned w = r->width;
	if (p->idx) {
		const uint8_t *s = p->idx + (size_t)r->y * w;
		for (unsigned x = 0; x < w; x++)
			memcpy(row + 3 * x, p->pal256 + 3 * s[x], 3);
		return 0;
	}
	int rc = pcx_line(r, p);
	if (rc)
		return rc;
	const unsigned char *l = p->line;
	for (unsigned x = 0; x < w; x++) {
		uint8_t *o = row + 3 * x;
		if (p->bpp == 8) {   /* 3 or 4 planes: R, G, B (and alpha, ignored) */
			o[0] = l[x], o[1] = l[p->bpl + x], o[2] = l[2 * p->bpl + x];
			continue;
		}
		unsigned v = 0;
		if (p->planes == 4) {   /* 1 bit in each of 4 planes: a 16-colour index */
			for (unsigned k = 0; k < 4; k++)
				v |= (unsigned)(l[k * p->bpl + x / 8] >> (7 - x % 8) & 1) << k;
			memcpy(o, p->pal16 + 3 * v, 3);
			continue;
		}
		unsigned per = 8 / p->bpp;
		v = l[x / per] >> (8 - p->bpp * (x % per + 1)) & ((1u << p->bpp) - 1);
		if (p->bpp == 1)
			memset(o, v ? 255 : 0, 3);
		else
			memcpy(o, p->pal16 + 3 * v, 3);
	}
	return 0;
}

static void pcx_done(img_reader_t *r)
{
	pcx_t *p = r->st;
	if (p) {
		free(p->line);
		free(p->idx);
		free(p);
	}
	r->st = NULL;
}

const img_rd_fmt_t img_rd_pcx = { pcx_open, pcx_row, NULL, pcx_done };
