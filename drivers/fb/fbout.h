/* fbout.h: files of a framebuffer picture: the video memory dump, indexed PNG, PCX and BMP.
 *
 * A picture is what a VGA/XGA mode holds: indices into a 6-bit DAC palette (8 bits per pixel,
 * or 4 for a 16-colour planar mode) or 5-6-5 direct colour. The layouts are documented in
 * docs/framebuffer.md. Writers go through a borrowed transport; they never print.
 */
#ifndef LOCUS_FBOUT_H
#define LOCUS_FBOUT_H

#include <stdint.h>
#include "quant/quant.h"
#include "io/transport.h"

/* How the mode stores pixels (and so how it is dumped). */
enum {
	FBOUT_LINEAR8 = 0,           /* one byte per pixel, then 256 x 3 DAC bytes (13h, XGA) */
	FBOUT_PLANAR4 = 1,           /* four bit planes, then 16 x 3 DAC bytes (12h) */
	FBOUT_DIRECT565 = 2          /* 16-bit little-endian 5-6-5 pixels, no palette (XGA) */
};
/* Output formats. */
enum { FBOUT_DUMP = 0, FBOUT_PNG = 1, FBOUT_PCX = 2, FBOUT_BMP = 3, FBOUT_UNKNOWN = -1 };

/* One page of a mode. */
typedef struct {
	unsigned width, height;
	int layout;                  /* FBOUT_LINEAR8 / PLANAR4 / DIRECT565 */
	const uint8_t *idx;          /* LINEAR8, PLANAR4: width x height indices, top row first */
	const uint16_t *pix;         /* DIRECT565: width x height pixels */
	const quant_palette_t *pal;  /* LINEAR8, PLANAR4 */
	double pixel_aspect;         /* width / height of one pixel; 0 or 1 = square */
	/* NULL, or: wait until row y of the pixels is final (the picture still being mapped on
	 * another thread); nonzero when it never will be (the writer gives up) */
	int (*wait_row)(void *ctx, unsigned y);
	void *wait_ctx;
} fbout_picture_t;

/* Format by name ("dump", "png", "pcx", "bmp") or by a path's suffix (".dump", ".png", ...);
 * FBOUT_UNKNOWN when none. */
int fbout_format_by_name(const char *name);
int fbout_format_by_suffix(const char *path);
/* Write the picture as one file of the format. 0, or -errno with a message in err: -ENOMEM when
 * memory ran out (a program's exit 70), the transport's -io_errno for a write, else -EIO. */
int fbout_write(io_transport_t *t, int format, const fbout_picture_t *p, char *err, size_t errlen);

#endif
