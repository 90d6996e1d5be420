/* rd_film.c: DPX (8, 10 filled, 16 bit; either byte order) and Cineon (8, 10 bit) readers, top down. */
#include <stdlib.h>
#include <string.h>
#include "image/imgread_int.h"

/* Code values are scaled to 8 bits as they are (v * 255 / max, rounded): the diff compares what
 * the file holds, not the light a film recorder would make of it. */
typedef struct {
	int le;                         /* little-endian words */
	unsigned bits, nch;             /* bits per sample (8, 10, 16), samples per pixel (1 or 3) */
	int filled;                     /* 10-bit: samples in 32-bit words, left justified */
	size_t stride;                  /* bytes of one row */
	unsigned char *line;
	uint8_t *pix;                   /* planar DPX: the whole picture (R, G, B planes merged) */
	int planar_done;                /* pix holds all of it: rows come from there */
} film_t;

int img_rd_is_dpx(const unsigned char *b, size_t n)
{
	return n >= 4 && (memcmp(b, "SDPX", 4) == 0 || memcmp(b, "XPDS", 4) == 0);
}

int img_rd_is_cineon(const unsigned char *b, size_t n)
{
	return n >= 4 && memcmp(b, "\x80\x2A\x5F\xD7", 4) == 0;
}

static uint32_t rd32(const unsigned char *p, int le)
{
	return le ? (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24
		: (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static unsigned rd16(const unsigned char *p, int le)
{
	return le ? (unsigned)p[0] | (unsigned)p[1] << 8 : (unsigned)p[0] << 8 | p[1];
}

/* Read the first need bytes of the header into h, then skip to the pixels at dataoff. */
static int header(img_reader_t *r, unsigned char *h, size_t need)
{
	long got = img_rd_take(r, h, need);
	if (got < 0)
		return (int)got;
	return (size_t)got < need ? img_rd_bad(r, img_rd_offset(r), "truncated header") : 0;
}

static int setup(img_reader_t *r, film_t *f, uint32_t w, uint32_t ht, uint32_t dataoff, unsigned at_size)
{
	if (w == 0 || ht == 0 || w > DEV_IMAGE_MAX_DIM || ht > DEV_IMAGE_MAX_DIM)
		return img_rd_bad(r, at_size, "bad or too large image size (each side 1 to 65536)");
	r->width = w;
	r->height = ht;
	uint64_t at = img_rd_offset(r);
	if (dataoff < at)
		return img_rd_bad(r, 4, "image data offset inside the header");
	int rc = img_rd_skip(r, dataoff - at, "truncated before the image data");
	if (rc)
		return rc;
	size_t samples = (size_t)w * f->nch;
	if (f->bits == 10)
		f->stride = f->nch == 3 ? 4 * (size_t)w : 4 * ((samples + 2) / 3);
	else
		f->stride = (samples * (f->bits / 8) + 3) / 4 * 4;
	return (f->line = malloc(f->stride)) ? 0 : img_rd_nomem(r);
}

static int film_row(img_reader_t *r, uint8_t *row);

/* Planar DPX: elements R, G and B (descriptors 1, 2, 3), alike, stored one after the other: the
 * planes are decoded into one buffer (bounded as the buffered formats are), then served. */
static int planar(img_reader_t *r, film_t *f, const unsigned char *h, uint32_t w, uint32_t ht)
{
	int le = f->le;
	uint32_t off[3];
	unsigned ch[3];
	for (int k = 0; k < 3; k++) {
		const unsigned char *e = h + 780 + 72 * k;
		unsigned d = e[20];
		if (d < 1 || d > 3 || e[23] != f->bits || rd16(e + 24, le) != rd16(h + 804, le) || rd16(e + 26, le))
			return img_rd_bad(r, 780 + 72 * (unsigned)k, "planar DPX elements must be R, G, B alike");
		ch[k] = d - 1;
		off[k] = rd32(e + 28, le);
		if (k && off[k] <= off[k - 1])
			return img_rd_bad(r, 808 + 72 * (unsigned)k, "planar DPX elements out of order");
	}
	if ((uint64_t)w * ht > IMGR_BUFFERED_MAX)
		return img_rd_bad(r, 772, "planar DPX too large to buffer");
	f->nch = 1;
	int rc = setup(r, f, w, ht, off[0], 772);
	size_t n = (size_t)w * 3;
	uint8_t *row = rc ? NULL : malloc(n);
	if (!rc && !row)
		return img_rd_nomem(r);
	for (int k = 0; k < 3 && !rc; k++) {
		uint64_t at = img_rd_offset(r);
		if (k && (rc = off[k] < at ? img_rd_bad(r, 808 + 72 * (unsigned)k, "planar DPX elements overlap")
				: img_rd_skip(r, off[k] - at, "truncated before an image element")))
			break;
		for (unsigned y = 0; y < ht && !rc; y++) {
			if (!f->pix || (k == 0 && y % 64 == 0)) {   /* grow with the rows decoded */
				size_t rows = (size_t)y + 64 < ht ? (size_t)y + 64 : ht;
				uint8_t *q = realloc(f->pix, rows * n);
				if (!q) {
					rc = img_rd_nomem(r);
					break;
				}
				f->pix = q;
			}
			r->y = y;
			if (!(rc = film_row(r, row)))
				for (unsigned x = 0; x < w; x++)
					f->pix[(size_t)y * n + 3 * x + ch[k]] = row[3 * x];
		}
	}
	r->y = 0;
	free(row);
	f->planar_done = rc == 0;
	return rc;
}

static int dpx_open(img_reader_t *r)
{
	unsigned char h[1024];
	film_t *f = calloc(1, sizeof *f);
	if (!f)
		return img_rd_nomem(r);
	r->st = f;
	int rc = header(r, h, sizeof h);
	if (rc)
		return rc;
	int le = f->le = h[0] == 'X';
	uint32_t dataoff = rd32(h + 4, le);
	unsigned orient = rd16(h + 768, le), nel = rd16(h + 770, le);
	uint32_t w = rd32(h + 772, le), ht = rd32(h + 776, le);
	unsigned desc = h[800], bits = h[803], pack = rd16(h + 804, le), enc = rd16(h + 806, le);
	uint32_t eloff = rd32(h + 808, le);
	if (orient != 0)
		return img_rd_bad(r, 768, "only DPX stored left to right, top to bottom is supported");
	if (nel != 1 && nel != 3)
		return img_rd_bad(r, 770, "only DPX of one image element, or three (planar R, G, B)");
	if (enc != 0)
		return img_rd_bad(r, 806, "run-length encoded DPX is not supported");
	if (desc == 50)
		f->nch = 3;
	else if (desc == 1 || desc == 2 || desc == 3 || desc == 6)
		f->nch = 1;
	else
		return img_rd_bad(r, 800, "unsupported DPX descriptor (RGB, R, G, B or luma)");
	if (bits != 8 && bits != 10 && bits != 16)
		return img_rd_bad(r, 803, "unsupported DPX bit size (8, 10 or 16)");
	if (bits == 10 && pack != 1)
		return img_rd_bad(r, 804, "10-bit DPX must be filled (packing method A)");
	f->bits = bits;
	f->filled = bits == 10;
	if (nel == 3)
		return planar(r, f, h, w, ht);
	return setup(r, f, w, ht, eloff ? eloff : dataoff, 772);
}

static int cin_open(img_reader_t *r)
{
	unsigned char h[692];
	film_t *f = calloc(1, sizeof *f);
	if (!f)
		return img_rd_nomem(r);
	r->st = f;
	int rc = header(r, h, sizeof h);
	if (rc)
		return rc;
	uint32_t dataoff = rd32(h + 4, 0);
	unsigned orient = h[192], nch = h[193];
	if (orient != 0)
		return img_rd_bad(r, 192, "only Cineon stored left to right, top to bottom is supported");
	if (nch != 1 && nch != 3)
		return img_rd_bad(r, 193, "Cineon with 1 or 3 channels only");
	unsigned bits = h[198];
	for (unsigned c = 0; c < nch; c++)
		if (h[196 + 28 * c + 2] != bits || (bits != 8 && bits != 10))
			return img_rd_bad(r, 198 + 28 * c, "only 8 or 10-bit Cineon, the same for each channel");
	if (h[680] != 0 || h[681] != 5)
		return img_rd_bad(r, 680, "only Cineon interleaved by pixel in left-justified 32-bit words");
	f->nch = nch;
	f->bits = bits;
	f->filled = bits == 10;
	return setup(r, f, rd32(h + 200, 0), rd32(h + 204, 0), dataoff, 200);
}

static uint8_t to8(unsigned v, unsigned max)
{
	return (uint8_t)((v * 255u + max / 2) / max);
}

static int film_row(img_reader_t *r, uint8_t *row)
{
	film_t *f = r->st;
	if (f->planar_done) {
		memcpy(row, f->pix + (size_t)r->y * r->width * 3, (size_t)r->width * 3);
		return 0;
	}
	long got = img_rd_take(r, f->line, f->stride);
	if (got < 0)
		return (int)got;
	if ((size_t)got < f->stride)
		return img_rd_bad(r, img_rd_offset(r), "truncated image data");
	const unsigned char *l = f->line;
	for (unsigned x = 0; x < r->width; x++) {
		uint8_t *o = row + 3 * x;
		if (f->bits == 10 && f->nch == 3) {
			uint32_t v = rd32(l + 4 * (size_t)x, f->le);
			o[0] = to8(v >> 22 & 1023, 1023), o[1] = to8(v >> 12 & 1023, 1023), o[2] = to8(v >> 2 & 1023, 1023);
			continue;
		}
		for (unsigned c = 0; c < f->nch; c++) {
			size_t i = (size_t)x * f->nch + c;
			unsigned v;
			if (f->bits == 8)
				v = to8(l[i], 255);
			else if (f->bits == 16)
				v = to8(rd16(l + 2 * i, f->le), 65535);
			else   /* one channel, three samples a word, the first in the low bits (as dev-film) */
				v = to8(rd32(l + 4 * (i / 3), f->le) >> (2 + 10 * (i % 3)) & 1023, 1023);
			o[c] = (uint8_t)v;
		}
		if (f->nch == 1)
			o[1] = o[2] = o[0];
	}
	return 0;
}

static void film_done(img_reader_t *r)
{
	film_t *f = r->st;
	if (f) {
		free(f->line);
		free(f->pix);
		free(f);
	}
	r->st = NULL;
}

const img_rd_fmt_t img_rd_dpx = { dpx_open, film_row, NULL, film_done };
const img_rd_fmt_t img_rd_cineon = { cin_open, film_row, NULL, film_done };
