/* imgread_int.h: the streaming image reader's state and helpers, shared by its format files. */
#ifndef LOCUS_IMGREAD_INT_H
#define LOCUS_IMGREAD_INT_H

#include <png.h>
#include <stdint.h>
#include "image/image.h"

/* One format read by a file of its own (rd_*.c): open reads the header (the stream starts at the
 * format's magic), row decodes one row (top first), end checks the rest, done frees st. */
typedef struct {
	int (*open)(img_reader_t *r);
	int (*row)(img_reader_t *r, uint8_t *row);
	int (*end)(img_reader_t *r);
	void (*done)(img_reader_t *r);
} img_rd_fmt_t;

struct img_reader {
	img_source_fn fn;
	void *user;
	char name[256];
	int fmt;
	unsigned width, height, y;
	unsigned char *buf;     /* input bytes buf[pos, len) not consumed yet */
	size_t pos, len, cap;
	uint64_t base;          /* stream offset of buf[0] */
	int eof, ioerr;
	png_structp png;
	png_infop info;
	unsigned char *prow;    /* one PNG row after the transforms (RGB or RGBA, 8 bits) */
	unsigned channels;
	const img_rd_fmt_t *ops;  /* formats of rd_*.c files, else NULL */
	void *st;               /* their state */
	uint64_t fsize;         /* the file's size when known (framebuffer dumps), else 0 */
	char err[512];
};

/* The input buffer (imgread_io.c). Stream offset of the next unconsumed byte. */
uint64_t img_rd_offset(const img_reader_t *r);
/* Set "NAME: byte OFF: what" as the error; returns -65. */
int img_rd_bad(img_reader_t *r, uint64_t off, const char *what);
/* Make at least one unconsumed byte available: 1, 0 at the end of the stream, <0 on error. */
int img_rd_fill(img_reader_t *r);
/* Copy up to n bytes into dst; the count copied (short at the end), or <0 on error. */
long img_rd_take(img_reader_t *r, void *dst, size_t n);
/* Skip n bytes: 0, -65 (truncated: what names it) or <0. */
int img_rd_skip(img_reader_t *r, uint64_t n, const char *what);
/* Set "NAME: out of memory"; returns -70. */
int img_rd_nomem(img_reader_t *r);

/* The formats of the rd_*.c files: sniff (1 when the first n bytes of b are the format's). */
extern const img_rd_fmt_t img_rd_pcx, img_rd_bmp, img_rd_dpx, img_rd_cineon, img_rd_fbdump;
int img_rd_is_pcx(const unsigned char *b, size_t n);
int img_rd_is_bmp(const unsigned char *b, size_t n);
int img_rd_is_dpx(const unsigned char *b, size_t n);
int img_rd_is_cineon(const unsigned char *b, size_t n);

/* Largest picture a buffered format (BMP stored bottom up, PCX with its palette at the end)
 * holds in memory, in pixels; the buffer grows with the rows decoded, never from the header. */
#define IMGR_BUFFERED_MAX ((uint64_t)1 << 26)

#endif
