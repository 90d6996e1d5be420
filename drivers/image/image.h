/* image.h: 24-bit raster files: streaming PNG/PPM/RLE writers and readers (drivers). */
#ifndef LOCUS_IMAGE_H
#define LOCUS_IMAGE_H

#include <stddef.h>
#include <stdint.h>
#include "io/transport.h"

/* File formats. */
enum { DEV_FMT_PNG, DEV_FMT_PPM, DEV_FMT_RLE, DEV_FMT_UNKNOWN = -1 };

/* The RLE raster file header (docs/rle-format.md): magic, version, width, height. */
#define DEV_RLE_MAGIC "LRLE"
#define DEV_RLE_VERSION 1
#define DEV_RLE_HEADER 13

/* Format by name ("png", "ppm", "rle") or by the suffix of a path; DEV_FMT_UNKNOWN if none. */
int dev_format_by_name(const char *name);
int dev_format_by_suffix(const char *path);

typedef struct dev_imgw dev_imgw_t;

/* Start writing a width x height image of format fmt to t (borrowed). NULL + err on failure,
 * errno then the cause (ENOMEM when memory ran out, the transport's io_errno for a write). */
dev_imgw_t *dev_imgw_new(int fmt, io_transport_t *t, unsigned width, unsigned height, char *err,
		size_t errlen);
/* Where dev_imgw_new_png_fn's bytes go: write n bytes, 0 or <0 (the callback keeps its own
 * message). */
typedef int (*dev_write_fn)(void *user, const void *buf, size_t n);
/* A PNG writer whose bytes go to fn(user, ...) instead of a transport: for a PNG embedded in
 * another file (the SVG device's base64 <image>). compact = 1: zlib level 9 and adaptive row
 * filters, smaller and slower than the PNG files' level 3 with the Sub filter. The rest of the
 * interface is the same; dev_imgw_finish does not flush anything (the caller owns the sink). */
dev_imgw_t *dev_imgw_new_png_fn(dev_write_fn fn, void *user, int compact, unsigned width,
		unsigned height, char *err, size_t errlen);
/* Record the physical size (PNG: the pHYs chunk, pixels per metre); call before the first row.
 * Pixels stay square (spec §4 `size`): both axes get the resolution at which the page fits
 * width_mm x height_mm, max(width/width_mm, height/height_mm). Formats without such a field
 * ignore it. */
void dev_imgw_physical(dev_imgw_t *w, double width_mm, double height_mm);
/* Append n rows (top first), 3 bytes per pixel, row k at pix + k*stride. 0 or <0. */
int dev_imgw_rows(dev_imgw_t *w, const uint8_t *pix, size_t stride, unsigned n);
/* Finish the file (all rows must have been written) and free the writer. 0 or <0. */
int dev_imgw_finish(dev_imgw_t *w);
/* Free without finishing (error paths). */
void dev_imgw_abort(dev_imgw_t *w);
/* Message of the last failure. */
const char *dev_imgw_error(const dev_imgw_t *w);
/* Its cause as an errno, set where it was raised: ENOMEM when memory ran out (a program's exit
 * 70), the transport's io_errno for a write, EINVAL for rows that do not fit, else EIO. */
int dev_imgw_errno(const dev_imgw_t *w);

/* Readers. A reader decodes one image a row at a time from a stream, so its memory is one row
 * and one input buffer whatever the size of the file. The header is checked against these limits
 * before anything is allocated. */
#define DEV_IMAGE_MAX_DIM 65536

/* Read callback (as meta_read_fn): up to n bytes into buf; count, 0 at end, <0 on error. */
typedef long (*dev_read_fn)(void *user, void *buf, size_t n);

typedef struct dev_imgr dev_imgr_t;

/* Start reading a PNG, PPM (P6, maxval 255) or RLE image from fn/user (borrowed); head/nhead are
 * bytes the caller already read from the stream (to sniff it), copied. name is for messages.
 * Reads and checks the header. Returns 0 with *out set, or -65 (bad content: "NAME: byte N:
 * ..."), -74 (read error), -70 (out of memory) with the message in err; *out is then NULL. */
int dev_imgr_open(dev_read_fn fn, void *user, const void *head, size_t nhead, const char *name,
		dev_imgr_t **out, char *err, size_t errlen);
/* 1 when the first n bytes of b look like an image dev_imgr_open reads (PNG, PPM P6, Locus RLE,
 * PCX, BMP, DPX, Cineon), else 0: how locus-diff tells an image from other inputs. */
int dev_imgr_sniff(const unsigned char *b, size_t n);
/* Headerless framebuffer dumps, told by their size: the dump mode (rd_fbdump.c) of a file of
 * size bytes, or -1. */
int imgr_fbdump_mode(uint64_t size);
/* dev_imgr_open for a headerless framebuffer dump of size bytes (its mode follows from it). */
int imgr_open_fbdump(dev_read_fn fn, void *user, const void *head, size_t nhead, const char *name,
		uint64_t size, dev_imgr_t **out, char *err, size_t errlen);
/* Size of the image. */
unsigned dev_imgr_width(const dev_imgr_t *r);
unsigned dev_imgr_height(const dev_imgr_t *r);
/* Decode the next row (top first) into row (width*3 bytes). 0, or -65/-74/-70 (dev_imgr_error). */
int dev_imgr_row(dev_imgr_t *r, uint8_t *row);
/* After the last row: check the end of the file (RLE: no trailing bytes; PNG: the chunks up to
 * IEND). Reads at most one byte past a well-formed RLE or PPM image. 0 or <0 as dev_imgr_row. */
int dev_imgr_end(dev_imgr_t *r);
/* The message of the last failure (one line naming the input). */
const char *dev_imgr_error(const dev_imgr_t *r);
/* Free the reader. */
void dev_imgr_free(dev_imgr_t *r);

/* A decoded image: width x height, 3 bytes per pixel, top row first. */
typedef struct {
	unsigned width, height;
	uint8_t *pix;
} dev_image_t;

/* Decode a whole image from memory (same formats and rules; name is for messages). The pixel
 * buffer grows with the rows actually decoded, so a header promising more than the data holds
 * costs no more than the data. Returns 0, or -65/-70 with the message in err. */
int dev_image_decode(const unsigned char *buf, size_t n, const char *name, dev_image_t *img,
		char *err, size_t errlen);
/* Free the pixels. */
void dev_image_free(dev_image_t *img);

#endif
