/* rd_fbdump.c: the framebuffer drivers' video-memory dumps (docs/framebuffer.md), told by size. */
#include <stdlib.h>
#include <string.h>
#include "image/imgread_int.h"

/* The modes: size of the dump, raster, layout. */
enum { L_INDEXED, L_PLANAR, L_565 };
static const struct {
	uint64_t bytes;
	unsigned w, h, layout;
} modes[] = {
	{ 64000 + 768, 320, 200, L_INDEXED },           /* 13h */
	{ 4 * 38400 + 48, 640, 480, L_PLANAR },         /* 12h */
	{ 786432 + 768, 1024, 768, L_INDEXED },         /* 1024x768x256 */
	{ 614400, 640, 480, L_565 },                    /* 640x480x565 */
};

typedef struct {
	unsigned layout;
	unsigned char *mem;             /* the video memory (the palette follows it) */
	unsigned char pal[256][3];      /* 8-bit values */
	unsigned char line[1280];
} dump_t;

int img_rd_fbdump_mode(uint64_t size)
{
	for (size_t k = 0; k < sizeof modes / sizeof *modes; k++)
		if (modes[k].bytes == size)
			return (int)k;
	return -1;
}

static unsigned dac8(unsigned v)
{
	return (v << 2) | (v >> 4);
}

static int dump_open(img_reader_t *r)
{
	int m = img_rd_fbdump_mode(r->fsize);
	if (m < 0)
		return img_rd_bad(r, 0, "not a framebuffer dump (its size is no mode's)");
	dump_t *d = calloc(1, sizeof *d);
	if (!d)
		return img_rd_nomem(r);
	r->st = d;
	d->layout = modes[m].layout;
	r->width = modes[m].w;
	r->height = modes[m].h;
	if (d->layout == L_565)
		return 0;
	size_t vm = d->layout == L_PLANAR ? 4 * 38400 : (size_t)r->width * r->height;
	unsigned npal = d->layout == L_PLANAR ? 16 : 256;
	if (!(d->mem = malloc(vm)))
		return img_rd_nomem(r);
	long got = img_rd_take(r, d->mem, vm);
	if (got < 0)
		return (int)got;
	unsigned char p[768];
	long gp = (size_t)got == vm ? img_rd_take(r, p, 3 * npal) : 0;
	if (gp < 0)
		return (int)gp;
	if ((size_t)got < vm || (size_t)gp < 3 * npal)
		return img_rd_bad(r, img_rd_offset(r), "truncated framebuffer dump");
	for (unsigned k = 0; k < 3 * npal; k++) {
		if (p[k] > 63)
			return img_rd_bad(r, vm + k, "DAC value above 63 in the dump's palette");
		d->pal[k / 3][k % 3] = (unsigned char)dac8(p[k]);
	}
	return 0;
}

static int dump_row(img_reader_t *r, uint8_t *row)
{
	dump_t *d = r->st;
	unsigned w = r->width, y = r->y;
	if (d->layout == L_565) {
		long got = img_rd_take(r, d->line, 2 * (size_t)w);
		if (got < 0)
			return (int)got;
		if ((size_t)got < 2 * (size_t)w)
			return img_rd_bad(r, img_rd_offset(r), "truncated framebuffer dump");
		for (unsigned x = 0; x < w; x++) {
			unsigned v = d->line[2 * x] | d->line[2 * x + 1] << 8;
			unsigned rr = v >> 11, g = v >> 5 & 63, b = v & 31;
			row[3 * x] = (uint8_t)(rr << 3 | rr >> 2);
			row[3 * x + 1] = (uint8_t)(g << 2 | g >> 4);
			row[3 * x + 2] = (uint8_t)(b << 3 | b >> 2);
		}
		return 0;
	}
	for (unsigned x = 0; x < w; x++) {
		unsigned v;
		if (d->layout == L_PLANAR) {
			v = 0;
			for (unsigned k = 0; k < 4; k++)
				v |= (unsigned)(d->mem[k * 38400 + y * 80 + x / 8] >> (7 - x % 8) & 1) << k;
		} else {
			v = d->mem[(size_t)y * w + x];
		}
		memcpy(row + 3 * x, d->pal[v], 3);
	}
	return 0;
}

static int dump_end(img_reader_t *r)
{
	int rc = img_rd_fill(r);
	return rc ? (rc < 0 ? rc : img_rd_bad(r, img_rd_offset(r), "trailing bytes after the dump")) : 0;
}

static void dump_done(img_reader_t *r)
{
	dump_t *d = r->st;
	if (d) {
		free(d->mem);
		free(d);
	}
	r->st = NULL;
}

const img_rd_fmt_t img_rd_fbdump = { dump_open, dump_row, dump_end, dump_done };
