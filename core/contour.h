/* contour.h: iso-line maps of a 2D grid of samples (marching squares), as polylines or meta vectors.
 *
 * The input is plain data: a grid of float samples and an affine map from
 * grid index to page pixels. Nothing here knows about scenes.
 *
 * Extraction ("marching squares"):
 *   - A sample is ABOVE a level L when z >= L, otherwise below. A cell (the
 *     square between samples (i,j), (i+1,j), (i+1,j+1), (i,j+1)) is crossed
 *     by L when its corners are on both sides. Crossing points on cell edges
 *     are linearly interpolated between the two samples of the edge, always
 *     computed from the same two samples, so neighbouring cells share points
 *     exactly.
 *   - Saddle cells (two diagonal corners above, two below) are decided by the
 *     cell-centre average of the four samples: when the average is >= L the
 *     two above corners are connected through the centre, otherwise the two
 *     below corners are.
 *   - A cell with a NaN (or infinite) corner is skipped; iso-lines end at its
 *     edges as open chains.
 *   - Segments are joined into maximal polylines: open chains (which end on
 *     the grid border or at a skipped cell) and closed loops. Every polyline
 *     is oriented so that the HIGHER values lie on its LEFT (closed loops
 *     around a maximum run counter-clockwise on the page when the map keeps
 *     orientation). Closed loops do not repeat their first point; the
 *     callback's `closed` flag says to close them.
 *   - Cost: O(cells + segments) time, O(cells) bytes of scratch allocated once
 *     per call (no allocation per segment, no hashing: links are found by edge
 *     index while tracing from cell to cell).
 *
 * Filled bands: drawn as RASTER image rows (meta_image + meta_row_pixels), not
 * as polygons: each pixel centre is mapped back into the grid, the field is
 * bilinearly interpolated there, and the pixel takes the colour of its band
 * (band k = the values with exactly k levels <= value). Rasters keep the
 * band edges consistent with the iso-lines to within a pixel and cost
 * O(pixels) regardless of the shape complexity. Draw bands first, lines on top.
 *
 * Errors: functions return 0 (or a count) on success and a negative
 * CONTOUR_E* code on failure; contour_error() then gives a one-line message.
 * Nothing here prints or exits.
 */
#ifndef LOCUS_CONTOUR_H
#define LOCUS_CONTOUR_H

#include <stddef.h>
#include "locus_meta.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Error codes (negative). */
enum {
	CONTOUR_EARG = -1,    /* invalid argument (sizes, NULL pointers, NaN levels...) */
	CONTOUR_ENOMEM = -2,  /* allocation failed */
	CONTOUR_ECALLBACK = -3, /* the polyline callback returned < 0 (extraction stopped) */
	CONTOUR_EMETA = -4    /* the meta writer failed; contour_error() holds its message */
};

/* A grid of samples with its place on the page.
 * z[j * nx + i] is the sample at grid index (i, j): row-major, BOTTOM row
 * (j = 0) first. NaN marks "no data". Grid index (i, j) maps to the page
 * point x = m[0] + m[1]*i + m[2]*j, y = m[3] + m[4]*i + m[5]*j (pixels). */
typedef struct {
	const float *z;     /* nx * ny samples */
	unsigned nx, ny;    /* samples per row / number of rows; each >= 2 */
	double m[6];        /* affine map grid index -> page pixels */
} contour_grid_t;

/* A point in page pixels. */
typedef struct {
	double x, y;
} contour_point_t;

/* Counts of one extraction. */
typedef struct {
	size_t segments;    /* cell segments (marching-squares output before joining) */
	size_t polylines;   /* polylines after joining (open + closed) */
	size_t closed;      /* of which closed loops */
	size_t points;      /* points handed to the callback */
} contour_stats_t;

/* Receives one joined polyline of level index `level` (index into the caller's
 * levels array): n >= 2 points in page pixels; closed != 0 means the last
 * point joins back to the first (which is not repeated). The points are only
 * valid during the call. Return 0 to continue, < 0 to stop the extraction. */
typedef int (*contour_fn)(void *user, unsigned level, const contour_point_t *p,
                          size_t n, int closed);

/* Set m so that grid index (0, 0) maps to page (x0, y0) and (nx-1, ny-1) to
 * (x1, y1), axis-aligned (x1 < x0 or y1 < y0 flips). */
void contour_map_rect(double m[6], unsigned nx, unsigned ny,
                      double x0, double y0, double x1, double y1);

/* Extract the iso-lines of every level and hand each joined polyline to fn,
 * level by level in the caller's order of `levels` (any order, repeats
 * allowed; each level must be finite). Within a level the order is
 * deterministic: open chains in scan order of their first cell, then closed
 * loops in scan order. stats may be NULL. Returns 0 or a CONTOUR_E* code. */
int contour_extract(const contour_grid_t *g, const double *levels, unsigned nlevels,
                    contour_fn fn, void *user, contour_stats_t *stats);

/* How contour_write_meta draws the lines. */
typedef struct {
	const meta_rgb_t *colours;  /* one colour per level, or NULL: all black */
	double width;               /* line width in pixels (<= 0 means 1) */
} contour_style_t;

/* Extract the iso-lines and write them to w on the current page: per level a
 * colour (and the width once), then one `stroke move draw... [close] end` path
 * per polyline, so that a pen plotter draws each iso-line in one pen-down
 * stroke. Polylines longer than META_MAX_PATH_POINTS are split into several
 * paths. style may be NULL (black, width 1). stats may be NULL. */
int contour_write_meta(meta_writer_t *w, const contour_grid_t *g, const double *levels,
                       unsigned nlevels, const contour_style_t *style,
                       contour_stats_t *stats);

/* Write colour-filled bands as one raster image covering the page pixels
 * [x, x+width) x [y, y+height): band_colours holds nlevels + 1 colours, band k
 * for values with exactly k of the levels <= value (levels need not be
 * sorted). Pixels whose centre maps outside the grid, or next to a NaN
 * sample, get `nodata`. The grid map m must be invertible. */
int contour_write_bands(meta_writer_t *w, const contour_grid_t *g, const double *levels,
                        unsigned nlevels, const meta_rgb_t *band_colours, meta_rgb_t nodata,
                        unsigned x, unsigned y, unsigned width, unsigned height);

/* Choose n evenly spaced levels strictly inside the range of the grid's finite
 * samples: levels[k] = min + (k + 1) (max - min) / (n + 1). Returns n, 0 when
 * the grid has no two different finite samples (nothing to contour), or a
 * CONTOUR_E* code. */
int contour_auto_levels(const contour_grid_t *g, unsigned n, double *levels);

/* Fill out[0..n-1] with a ramp of n distinct colours from dark blue through
 * green and yellow to dark red, good for levels or bands in order. */
void contour_palette(meta_rgb_t *out, unsigned n);

/* The message of the last error in this thread ("" if none). */
const char *contour_error(void);

#ifdef __cplusplus
}
#endif
#endif
