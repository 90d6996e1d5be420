/* band.h: a band of finished raster rows, what the renderer hands to a raster device. */
#ifndef LOCUS_BAND_H
#define LOCUS_BAND_H

#include <stddef.h>
#include <stdint.h>

/* Finished rows for a raster device: rows [y0, y0 + nrows) counted from the TOP of the page
 * (y0 = 0 is the top row), 3 bytes per pixel R, G, B, row k at pix + k * stride. */
typedef struct {
	const uint8_t *pix;
	size_t stride;
	unsigned width;
	unsigned y0, nrows;
	unsigned page_height;
} render_band_t;

#endif
