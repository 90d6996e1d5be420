/* image.h: 24-bit raster files: streaming PNG/PPM/RLE writers and readers (drivers). */
#ifndef LOCUS_IMAGE_H
#define LOCUS_IMAGE_H

#include <stddef.h>
#include <stdint.h>
#include "io/transport.h"

/* File formats. */
enum { IMG_FMT_PNG, IMG_FMT_PPM, IMG_FMT_RLE, IMG_FMT_UNKNOWN = -1 };

/* The RLE raster file header (docs/rle-format.md): magic, version, width, height. */
#define DEV_RLE_MAGIC "LRLE"
#define DEV_RLE_VERSION 1
#define DEV_RLE_HEADER 13

/* Format by name ("png", "ppm", "rle") or by the suffix of a path; IMG_FMT_UNKNOWN if none. */
int img_format_by_name(const char *name);
int img_format_by_suffix(const char *path);

typedef struct img_writer img_writer_t;

/* Start writing a width x height image of format fmt to t (borrowed). NULL + err on failure,
 * errno then the cause (ENOMEM when memory ran out, the transport's io_errno for a write). */
img_writer_t *img_writer_new(int fmt, io_transport_t *t, unsigned width, unsigned height, char *err,
		size_t errlen);
/* Where img_writer_new_png_fn's bytes go: write n bytes, 0 or <0 (the callback keeps its own
 * message). */
typedef int (*img_sink_fn)(void *user, const void *buf, size_t n);
/* A PNG writer whose bytes go to fn(user, ...) instead of a transport: for a PNG embedded in
 * another file (the SVG device's base64 <image>). compact = 1: zlib level 9 and adaptive row
 * filters, smaller and slower than the PNG files' level 3 with the Sub filter. The rest of the
 * interface is the same; img_writer_finish does not flush anything (the caller owns the sink). */
img_writer_t *img_writer_new_png_fn(img_sink_fn fn, void *user, int compact, unsigned width,
		unsigned height, char *err, size_t errlen);
/* Record the physical size (PNG: the pHYs chunk, pixels per metre); call before the first row.
 * Pixels stay square (spec §4 `size`): both axes get the resolution at which the page fits
 * width_mm x height_mm, max(width/width_mm, height/height_mm). Formats without such a field
 * ignore it. */
void img_writer_physical(img_writer_t *w, double width_mm, double height_mm);
/* Append n rows (top first), 3 bytes per pixel, row k at pix + k*stride. 0 or <0. */
int img_writer_rows(img_writer_t *w, const uint8_t *pix, size_t stride, unsigned n);
/* Finish the file (all rows must have been written) and free the writer. 0 or <0. */
int img_writer_finish(img_writer_t *w);
/* Free without finishing (error paths). */
void img_writer_abort(img_writer_t *w);
/* Message of the last failure. */
const char *img_writer_error(const img_writer_t *w);
/* Its cause as an errno, set where it was raised: ENOMEM when memory ran out (a program's exit
 * 70), the transport's io_errno for a write, EINVAL for rows that do not fit, else EIO. */
int img_writer_errno(const img_writer_t *w);

/* Readers. A reader decodes one image a row at a time from a stream, so its memory is one row
 * and one input buffer whatever the size of the file. The header is checked against these limits
 * before anything is allocated. */
#define DEV_IMAGE_MAX_DIM 65536

/* Read callback (as meta_read_fn): up to n bytes into buf; count, 0 at end, <0 on error. */
typedef long (*img_source_fn)(void *user, void *buf, size_t n);

typedef struct img_reader img_reader_t;

/* Start reading a PNG, PPM (P6, maxval 255) or RLE image from fn/user (borrowed); head/nhead are
 * bytes the caller already read from the stream (to sniff it), copied. name is for messages.
 * Reads and checks the header. Returns 0 with *out set, or -65 (bad content: "NAME: byte N:
 * ..."), -74 (read error), -70 (out of memory) with the message in err; *out is then NULL. */
int img_reader_open(img_source_fn fn, void *user, const void *head, size_t nhead, const char *name,
		img_reader_t **out, char *err, size_t errlen);
/* 1 when the first n bytes of b look like an image img_reader_open reads (PNG, PPM P6, Locus RLE,
 * PCX, BMP, DPX, Cineon), else 0: how locus-diff tells an image from other inputs. */
int img_reader_sniff(const unsigned char *b, size_t n);
/* Headerless framebuffer dumps, told by their size: the dump mode (rd_fbdump.c) of a file of
 * size bytes, or -1. */
int img_rd_fbdump_mode(uint64_t size);
/* img_reader_open for a headerless framebuffer dump of size bytes (its mode follows from it). */
int img_rd_open_fbdump(img_source_fn fn, void *user, const void *head, size_t nhead, const char *name,
		uint64_t size, img_reader_t **out, char *err, size_t errlen);
/* Size of the image. */
unsigned img_reader_width(const img_reader_t *r);
unsigned img_reader_height(const img_reader_t *r);
/* Decode the next row (top first) into row (width*3 bytes). 0, or -65/-74/-70 (img_reader_error). */
int img_reader_row(img_reader_t *r, uint8_t *row);
/* After the last row: check the end of the file (RLE: no trailing bytes; PNG: the chunks up to
 * IEND). Reads at most one byte past a well-formed RLE or PPM image. 0 or <0 as img_reader_row. */
int img_reader_end(img_reader_t *r);
/* The message of the last failure (one line naming the input). */
const char *img_reader_error(const img_reader_t *r);
/* Free the reader. */
void img_reader_free(img_reader_t *r);

/* A decoded image: width x height, 3 bytes per pixel, top row first. */
typedef struct {
	unsigned width, height;
	uint8_t *pix;
} img_t;

/* Decode a whole image from memory (same formats and rules; name is for messages). The pixel
 * buffer grows with the rows actually decoded, so a header promising more than the data holds
 * costs no more than the data. Returns 0, or -65/-70 with the message in err. */
int img_decode(const unsigned char *buf, size_t n, const char *name, img_t *img,
		char *err, size_t errlen);
/* Free the pixels. */
void img_free(img_t *img);

#endif
