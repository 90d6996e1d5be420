/* image.h: 24-bit raster files: streaming PNG/PPM/RLE writers and whole-file readers (drivers). */
#ifndef LOCUS_IMAGE_H
#define LOCUS_IMAGE_H

#include <stddef.h>
#include <stdint.h>
#include "transport.h"

/* File formats. */
enum { DEV_FMT_PNG, DEV_FMT_PPM, DEV_FMT_RLE, DEV_FMT_UNKNOWN = -1 };

/* The RLE raster file header (docs/rle-format.md): magic, version, width, height. */
#define DEV_RLE_MAGIC "LRLE"
#define DEV_RLE_VERSION 1
#define DEV_RLE_HEADER 13

/* Format by name ("png", "ppm", "rle") or by the suffix of a path; DEV_FMT_UNKNOWN if none. */
int dev_format_by_name(const char *name);
int dev_format_by_suffix(const char *path);
/* Suffix of a format, with the dot. */
const char *dev_format_suffix(int fmt);

typedef struct dev_imgw dev_imgw_t;

/* Start writing a width x height image of format fmt to t (borrowed). NULL + err on failure. */
dev_imgw_t *dev_imgw_new(int fmt, io_transport_t *t, unsigned width, unsigned height, char *err,
		size_t errlen);
/* Record the physical size (PNG: the pHYs chunk, pixels per metre); call before the first row.
 * Formats without such a field ignore it. */
void dev_imgw_physical(dev_imgw_t *w, double width_mm, double height_mm);
/* Append n rows (top first), 3 bytes per pixel, row k at pix + k*stride. 0 or <0. */
int dev_imgw_rows(dev_imgw_t *w, const uint8_t *pix, size_t stride, unsigned n);
/* Finish the file (all rows must have been written) and free the writer. 0 or <0. */
int dev_imgw_finish(dev_imgw_t *w);
/* Free without finishing (error paths). */
void dev_imgw_abort(dev_imgw_t *w);
/* Message of the last failure. */
const char *dev_imgw_error(const dev_imgw_t *w);

/* A decoded image: width x height, 3 bytes per pixel, top row first. */
typedef struct {
	unsigned width, height;
	uint8_t *pix;
} dev_image_t;

/* Load a PNG, PPM (P6, maxval 255) or RLE file ("-" = stdin). Returns 0, or -66 when the file
 * cannot be opened, -65 when its content is bad (message in err: "NAME: byte N: ..."). */
int dev_image_load(const char *path, dev_image_t *img, char *err, size_t errlen);
/* Load from memory (same rules; name is for messages). */
int dev_image_decode(const unsigned char *buf, size_t n, const char *name, dev_image_t *img,
		char *err, size_t errlen);
/* Free the pixels. */
void dev_image_free(dev_image_t *img);

#endif
