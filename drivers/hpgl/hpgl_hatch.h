/* hpgl_hatch.h: hatching for pen plotters: parallel lines filling a polygon by either fill rule
 * (holes included), and brightness hatching of raster rows (an ordered line halftone).
 */
#ifndef LOCUS_HPGL_HATCH_H
#define LOCUS_HPGL_HATCH_H

#include <stddef.h>

/* One hatch line piece, handed to the caller. Returns 0 or <0 to stop. */
typedef int (*hatch_fn)(void *user, double x0, double y0, double x1, double y1);

/* Hatch the polygon made of ncont closed contours (contour k is pts[2*starts[k] ..] with
 * starts[k+1] - starts[k] points, starts has ncont + 1 entries; pts holds x, y pairs) with
 * lines at angle_deg, spacing apart, the lines placed at offsets phase + k * spacing from the
 * origin (so that neighbouring fills line up). even_odd selects the rule (else non-zero).
 * Consecutive lines run in alternate directions (fewer long pen-up moves). Returns 0, <0 from
 * fn, or -1 when out of memory. */
int hatch_polygon(const double *pts, const size_t *starts, size_t ncont, int even_odd,
		double angle_deg, double spacing, double phase, hatch_fn fn, void *user);

/* Brightness halftone of one pixel row: the row spans [x0, x1) horizontally and [y0, y0 + h)
 * vertically (any units); darkness in [0, 1] of each of the n pixels (width (x1 - x0) / n
 * each). Draws lines lines horizontally across the row (lines >= 1, at y0 + (k + 0.5) h /
 * lines) wherever darkness exceeds the k-th ordered threshold, so the ink per pixel grows with
 * its darkness. Runs of inked pixels become one piece. */
int hatch_row(const double *darkness, size_t n, double x0, double x1, double y0, double h,
		unsigned lines, unsigned row_index, hatch_fn fn, void *user);

#endif
