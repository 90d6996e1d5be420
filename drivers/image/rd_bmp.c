/* rd_bmp.c: Windows BMP reader (1/4/8-bit palettes, 16/24/32-bit, bit fields; top-down or bottom-up). */
#include <stdlib.h>
#include <string.h>
#include "image/imgread_int.h"

typedef struct {
	unsigned bpp, topdown, npal;
	unsigned char pal[256][3];
	uint32_t mask[3];
	size_t stride;                  /* bytes of one stored row (padded to 4) */
	unsigned char *line;
	uint8_t *pix;                   /* bottom-up files: the whole picture, top row first */
} bmp_t;

int img_rd_is_bmp(const unsigned char *b, size_t n)
{
	return n >= 2 && b[0] == 'B' && b[1] == 'M';
}

static uint32_t le32(const unsigned char *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* The 8-bit value of the field of v under mask m. */
static uint8_t field(uint32_t v, uint32_t m)
{
	if (!m)
		return 0;
	unsigned sh = 0, bits = 0;
	while (!(m >> sh & 1))
		sh++;
	while (sh + bits < 32 && (m >> (sh + bits) & 1))
		bits++;
	uint32_t f = (v & m) >> sh, max = bits >= 32 ? 0xFFFFFFFFu : (1u << bits) - 1;
	return (uint8_t)((f * 255u + max / 2) / max);
}

/* Decode one stored row into out (width * 3). */
static int bmp_line(img_reader_t *r, bmp_t *b, uint8_t *out)
{
	long got = img_rd_take(r, b->line, b->stride);
	if (got < 0)
		return (int)got;
	if ((size_t)got < b->stride)
		return img_rd_bad(r, img_rd_offset(r), "truncated BMP pixel data");
	const unsigned char *l = b->line;
	for (unsigned x = 0; x < r->width; x++) {
		uint8_t *o = out + 3 * x;
		if (b->bpp <= 8) {
			unsigned per = 8 / b->bpp;
			unsigned v = l[x / per] >> (8 - b->bpp * (x % per + 1)) & ((1u << b->bpp) - 1);
			if (v >= b->npal)
				return img_rd_bad(r, img_rd_offset(r), "BMP colour index past the palette");
			memcpy(o, b->pal[v], 3);
		} else if (b->bpp == 24) {
			o[0] = l[3 * x + 2], o[1] = l[3 * x + 1], o[2] = l[3 * x];
		} else {
			uint32_t v = b->bpp == 16 ? (uint32_t)l[2 * x] | (uint32_t)l[2 * x + 1] << 8 : le32(l + 4 * x);
			for (int c = 0; c < 3; c++)
				o[c] = field(v, b->mask[c]);
		}
	}
	return 0;
}

static int bmp_open(img_reader_t *r)
{
	unsigned char h[14 + 124];
	long got = img_rd_take(r, h, 18);
	if (got < 0)
		return (int)got;
	if (got < 18)
		return img_rd_bad(r, img_rd_offset(r), "truncated BMP header");
	uint32_t dataoff = le32(h + 10), hsize = le32(h + 14);
	if (hsize != 12 && hsize != 40 && hsize != 52 && hsize != 56 && hsize != 108 && hsize != 124)
		return img_rd_bad(r, 14, "unsupported BMP header size");
	got = img_rd_take(r, h + 18, hsize - 4);
	if (got < 0)
		return (int)got;
	if ((uint32_t)got < hsize - 4)
		return img_rd_bad(r, img_rd_offset(r), "truncated BMP header");
	bmp_t *b = calloc(1, sizeof *b);
	if (!b)
		return img_rd_nomem(r);
	r->st = b;
	int32_t w, ht;
	uint32_t comp = 0, ncol = 0;
	if (hsize == 12) {
		w = (int16_t)(h[18] | h[19] << 8);
		ht = (int16_t)(h[20] | h[21] << 8);
		b->bpp = h[24] | h[25] << 8;
	} else {
		w = (int32_t)le32(h + 18);
		ht = (int32_t)le32(h + 22);
		b->bpp = h[28] | h[29] << 8;
		comp = le32(h + 30);
		ncol = le32(h + 46);
	}
	b->topdown = ht < 0;
	if (ht < 0)
		ht = ht == INT32_MIN ? 0 : -ht;
	if (w <= 0 || ht <= 0 || w > DEV_IMAGE_MAX_DIM || ht > DEV_IMAGE_MAX_DIM)
		return img_rd_bad(r, 18, "bad or too large BMP size (each side 1 to 65536)");
	r->width = (unsigned)w;
	r->height = (unsigned)ht;
	unsigned bpp = b->bpp;
	if (bpp != 1 && bpp != 4 && bpp != 8 && bpp != 16 && bpp != 24 && bpp != 32)
		return img_rd_bad(r, 28, "unsupported BMP bits per pixel");
	if (comp != 0 && !(comp == 3 && (bpp == 16 || bpp == 32)))
		return img_rd_bad(r, 30, "compressed BMP (RLE, JPEG, PNG) is not supported");
	if (comp == 3) {
		if (hsize == 40) {   /* the masks follow the header */
			got = img_rd_take(r, h + 54, 12);
			if (got < 0)
				return (int)got;
			if (got < 12)
				return img_rd_bad(r, img_rd_offset(r), "truncated BMP bit fields");
		}
		for (int c = 0; c < 3; c++)
			b->mask[c] = le32(h + 54 + 4 * c);
	} else if (bpp == 16) {
		b->mask[0] = 0x7C00, b->mask[1] = 0x03E0, b->mask[2] = 0x001F;
	} else if (bpp == 32) {
		b->mask[0] = 0xFF0000, b->mask[1] = 0xFF00, b->mask[2] = 0xFF;
	}
	if (bpp <= 8) {
		unsigned esz = hsize == 12 ? 3 : 4;
		b->npal = ncol && ncol <= (1u << bpp) ? ncol : 1u << bpp;
		for (unsigned k = 0; k < b->npal; k++) {
			unsigned char e[4];
			got = img_rd_take(r, e, esz);
			if (got < 0)
				return (int)got;
			if ((unsigned)got < esz)
				return img_rd_bad(r, img_rd_offset(r), "truncated BMP palette");
			b->pal[k][0] = e[2], b->pal[k][1] = e[1], b->pal[k][2] = e[0];
		}
	}
	uint64_t at = img_rd_offset(r);
	if (dataoff < at)
		return img_rd_bad(r, 10, "BMP pixel data offset inside the header");
	int rc = img_rd_skip(r, dataoff - at, "truncated BMP before its pixel data");
	if (rc)
		return rc;
	b->stride = (((size_t)r->width * bpp + 31) / 32) * 4;
	if (!(b->line = malloc(b->stride)))
		return img_rd_nomem(r);
	if (!b->topdown) {
		/* stored bottom row first: decode it all, the buffer growing with the rows read */
		if ((uint64_t)r->width * r->height > IMGR_BUFFERED_MAX)
			return img_rd_bad(r, 22, "bottom-up BMP too large to buffer");
		size_t row = (size_t)r->width * 3, cap = 0;
		for (unsigned k = 0; k < r->height; k++) {
			if (k == cap) {
				size_t ncap = cap ? cap * 2 : 16;
				if (ncap > r->height)
					ncap = r->height;
				uint8_t *q = realloc(b->pix, ncap * row);
				if (!q)
					return img_rd_nomem(r);
				b->pix = q;
				cap = ncap;
			}
			if ((rc = bmp_line(r, b, b->pix + (size_t)k * row)))
				return rc;
		}
	}
	return 0;
}

static int bmp_row(img_reader_t *r, uint8_t *row)
{
	bmp_t *b = r->st;
	if (b->topdown)
		return bmp_line(r, b, row);
	size_t n = (size_t)r->width * 3;
	memcpy(row, b->pix + (size_t)(r->height - 1 - r->y) * n, n);
	return 0;
}

static void bmp_done(img_reader_t *r)
{
	bmp_t *b = r->st;
	if (b) {
		free(b->line);
		free(b->pix);
		free(b);
	}
	r->st = NULL;
}

const img_rd_fmt_t img_rd_bmp = { bmp_open, bmp_row, NULL, bmp_done };
