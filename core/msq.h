/* msq.h: internals shared by the grid tracers contour*.c and voronoi*.c (not part of the public API). */
#ifndef LOCUS_MSQ_H
#define LOCUS_MSQ_H

/* The marching-squares exit table: msq_exit[s][case][entry] is the edge by
 * which the iso-line that enters a cell by edge `entry` leaves it, or -1.
 * Corners 0 (i, j), 1 (i+1, j), 2 (i+1, j+1), 3 (i, j+1); edge k joins corner
 * k to corner k+1; case bit k = corner k is "above" (contours: the sample is
 * above the level; Voronoi: the corner has the smaller label). Walking the
 * cell border counter-clockwise, a line enters an edge that goes from above
 * to below and leaves by one that goes from below to above, so the above side
 * is always on the left. A saddle (two entries: corners 0 and 2 above, or 1
 * and 3) is decided by s: s = 1 when the cell centre is above, which joins
 * the two above corners through the centre (the segments cut off the below
 * corners); s = 0 cuts off the above corners instead. */
extern const signed char msq_exit[2][16][4];

/* Record a printf-style one-line error message for this thread and return
 * code; contour_error() and voronoi_error() both read it (msq_error()). */
int msq_fail(int code, const char *fmt, ...)
#ifdef __GNUC__
	__attribute__((format(printf, 2, 3)))
#endif
	;

/* The message recorded last by msq_fail() in this thread ("" if none). */
const char *msq_error(void);

/* Forget the recorded message (at the start of a public call). */
void msq_clear(void);

#endif
