/* scan_int.h: internals shared by scan.c, stroke.c, flatten.c and font.c (not public). */
#ifndef LOCUS_SCAN_INT_H
#define LOCUS_SCAN_INT_H
#include <math.h>
#include "scan.h"

/* Scratch paths owned by the context. */
scan_path_t *scan_ctx_piece(scan_ctx_t *c);
scan_path_t *scan_ctx_dashed(scan_ctx_t *c);

/* scan_fill_poly for a polygon known to be convex (parallelograms, rectangles, triangles,
 * discs): the same pixels, found without sorting crossings. */
int scan_fill_piece(scan_ctx_t *c, const scan_band_t *b, const scan_pt_t *pts, size_t n, int rule,
		meta_rgb_t rgb, int convex);

/* Round a double to the nearest integer (thousandths), ties away from zero. */
static inline int64_t scan_round(double v)
{
	double t = trunc(v), f = v - t;
	/* without branches (the fraction's side is unpredictable); |t| >= 2^53 has f = 0 */
	return (int64_t)t + (f >= 0.5) - (f <= -0.5);
}
#endif
