/* voronoi.h: extended, weighted Voronoi tessellations of point and segment nuclei (raster cells, vector boundaries).
 *
 * Plain data in, meta-language out; nothing here knows about scenes.
 *
 * Nuclei are points, line segments or polylines with a weight and a colour.
 * The distance d(P, N) from a point P to a nucleus N is the Euclidean distance
 * to the nearest point of N (for a segment, to the nearest point of the closed
 * segment AB; for a polyline, the smallest over its segments: one nucleus, one
 * cell, 1-Lipschitz like the others). Coordinates are 3D so the same distance serves 3D uses;
 * tessellations are drawn in the plane z = 0 (the z coordinates of nuclei are
 * then taken into account as given, i.e. P = (x, y, 0)).
 *
 * Weighted distance (the metric), w the nucleus weight:
 *   VORONOI_ADDITIVE        dw = d - w     (w any finite value; w = 0 for all
 *                           nuclei is the ordinary tessellation). Between two
 *                           points at distance D the boundary is a hyperbola
 *                           branch crossing the segment between them at
 *                           (D + w1 - w2) / 2 from the first: raising one
 *                           weight by w moves the boundary w/2 away from it.
 *   VORONOI_MULTIPLICATIVE  dw = d / w     (w > 0). Between two points the
 *                           boundary is an Apollonius circle (a straight
 *                           bisector when w1 == w2); a heavier nucleus grows
 *                           and may enclose the other one.
 * The cell of nucleus k is the set of points where dw_k is the smallest; on
 * exact ties the lowest index wins (so results are deterministic).
 *
 * Page placement: plane point (X, Y) maps to page pixels
 *   x = m[0] + m[1]*X + m[2]*Y,   y = m[3] + m[4]*X + m[5]*Y
 * (m invertible); pixel (i, j) is evaluated at its centre (i + 0.5, j + 0.5)
 * mapped back to the plane.
 *
 * Errors: functions return 0 (or a count) on success and a negative
 * VORONOI_E* code on failure; voronoi_error() then gives a one-line message.
 * Nothing here prints or exits.
 */
#ifndef LOCUS_VORONOI_H
#define LOCUS_VORONOI_H

#include <stddef.h>
#include <stdint.h>
#include "locus_meta.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Error codes (negative). */
enum {
	VORONOI_EARG = -1,      /* invalid argument (no nuclei, bad weight, singular map...) */
	VORONOI_ENOMEM = -2,    /* allocation failed */
	VORONOI_ECALLBACK = -3, /* the polyline callback returned < 0 */
	VORONOI_EMETA = -4,     /* the meta writer failed; voronoi_error() holds its message */
	VORONOI_ETHREAD = -5    /* a worker thread could not be started */
};

/* Nucleus kinds. */
enum { VORONOI_POINT = 0, VORONOI_SEGMENT = 1, VORONOI_POLYLINE = 2 };
/* Metrics (how the weight enters). */
enum { VORONOI_ADDITIVE = 0, VORONOI_MULTIPLICATIVE = 1 };

/* One nucleus. */
typedef struct {
	int kind;           /* VORONOI_POINT (uses a), VORONOI_SEGMENT (a to b) or VORONOI_POLYLINE (pts) */
	double a[3];        /* the point, or the segment's first end */
	double b[3];        /* the segment's second end (ignored for points) */
	double weight;      /* additive: subtracted; multiplicative: divides (> 0) */
	meta_rgb_t colour;  /* fill colour of its cell */
	double *pts;        /* polyline: npts >= 2 points, x y z each (the caller's; never written here) */
	size_t npts;
} voronoi_nucleus_t;

/* A tessellation: the nuclei, the metric and where the plane lies on the page. */
typedef struct {
	const voronoi_nucleus_t *nuclei;
	size_t count;       /* >= 1, at most VORONOI_MAX_NUCLEI */
	int metric;         /* VORONOI_ADDITIVE or VORONOI_MULTIPLICATIVE */
	double m[6];        /* affine map plane -> page pixels (see above) */
} voronoi_t;

#define VORONOI_MAX_NUCLEI 1000000

/* A page rectangle of pixels: [x, x+width) x [y, y+height). */
typedef struct {
	unsigned x, y, width, height;
} voronoi_rect_t;

/* A point in page pixels. */
typedef struct {
	double x, y;
} voronoi_point_t;

/* Counts of one boundary extraction. */
typedef struct {
	size_t crossings;   /* pixel edges where the label changes */
	size_t junctions;   /* cells where three or more cells meet */
	size_t polylines;   /* joined polylines (open + closed) */
	size_t closed;      /* of which closed loops */
	size_t points;      /* points handed to the callback */
} voronoi_stats_t;

/* Euclidean distance from the 3D point p to the nucleus (unweighted). */
double voronoi_distance(const voronoi_nucleus_t *n, const double p[3]);

/* Weighted distance dw of p from the nucleus under metric. */
double voronoi_weighted_distance(const voronoi_nucleus_t *n, int metric, const double p[3]);

/* Index of the nucleus nearest to the 3D point p by weighted distance (lowest
 * index on ties); *dw (if non-NULL) receives its weighted distance. Brute
 * force: the reference the accelerated labelling must agree with. */
size_t voronoi_nearest(const voronoi_nucleus_t *nuclei, size_t count, int metric,
                       const double p[3], double *dw);

/* The nearest and second-nearest nuclei of p (lowest index first on ties):
 * returns the nearest, *dw1 its weighted distance, *second the runner-up
 * (SIZE_MAX when count == 1, with *dw2 = INFINITY). dw2 - dw1 >= 0 is zero
 * exactly on cell boundaries, so a 3D renderer can show the boundary
 * surfaces of a tessellation as the level set dw2 - dw1 = thickness (pointers
 * may be NULL). */
size_t voronoi_nearest2(const voronoi_nucleus_t *nuclei, size_t count, int metric,
                        const double p[3], double *dw1, size_t *second, double *dw2);

/* Set m so that the plane window [wx0, wx1] x [wy0, wy1] maps onto the page
 * rectangle [px0, px1] x [py0, py1] (axis-aligned; no aspect correction). */
void voronoi_map_window(double m[6], double wx0, double wy0, double wx1, double wy1,
                        double px0, double py0, double px1, double py1);

/* Check a tessellation (count, kinds, finite coordinates, weights, metric,
 * invertible map). Returns 0 or VORONOI_EARG with a message. */
int voronoi_check(const voronoi_t *v);

/* Label every pixel of r: labels[j * r->width + i] is the index of the nucleus
 * owning pixel (r->x + i, r->y + j) (BOTTOM row first). Exact (equal to
 * voronoi_nearest at each pixel centre) but accelerated by culling nuclei
 * with distance bounds per block of 64, then 16, then 4 pixels (most blocks
 * keep one nucleus and need no per-pixel distance at all), and spread over
 * `threads` threads (0 = the
 * number of online CPUs, at most 16); the result does not depend on the
 * thread count. */
int voronoi_label(const voronoi_t *v, const voronoi_rect_t *r, unsigned threads,
                  int32_t *labels);

/* Receives one boundary polyline in page pixels, n >= 2 points; `left` and
 * `right` are the nuclei whose cells lie on either side (left of the
 * direction of travel, right of it; along a chain traced through two-label
 * cells the smaller index is on the left). Open polylines end at junctions
 * (where three or more cells meet) or on the edge of the rectangle; closed != 0
 * means the last point joins back to the first (not repeated). Points are
 * only valid during the call. Return 0 to continue, < 0 to stop. */
typedef int (*voronoi_fn)(void *user, int32_t left, int32_t right,
                          const voronoi_point_t *p, size_t n, int closed);

/* Trace the cell boundaries of a labelled rectangle (labels as produced by
 * voronoi_label for the same v and r) into joined polylines: each crossing
 * point lies on the segment between two pixel centres of different labels,
 * where the two weighted distances are equal (solved to 1e-6 pixel), so
 * boundaries are sub-pixel accurate, not staircases. Where exactly three
 * cells meet, the junction point is the Voronoi vertex (equal weighted
 * distance to all three, by Newton's method; the mean of the crossings
 * around it when that fails or four cells meet). Open ends half a pixel
 * inside the rectangle are carried along their last segment to its edge.
 * Cost: O(pixels) scan plus O(boundary length). stats may be NULL. */
int voronoi_boundaries(const voronoi_t *v, const voronoi_rect_t *r, const int32_t *labels,
                       voronoi_fn fn, void *user, voronoi_stats_t *stats);

/* Write the filled cells of r to w as one `image` of r->height rows (each
 * pixel the colour of its nucleus). threads as for voronoi_label. Labels are
 * computed in bands of rows, so memory is O(r->width), not O(pixels). */
int voronoi_write_cells(meta_writer_t *w, const voronoi_t *v, const voronoi_rect_t *r,
                        unsigned threads);

/* How voronoi_write_meta draws. */
typedef struct {
	int cells;          /* non-zero: draw the filled cells (raster image) */
	int boundaries;     /* non-zero: draw the boundaries (vectors) on top */
	meta_rgb_t line_colour;
	double line_width;  /* pixels (<= 0 means 1) */
	unsigned threads;   /* as for voronoi_label */
	int nuclei;         /* non-zero: mark the nuclei on top (points as discs,
	                     * segments as round-capped strokes; z ignored), those
	                     * inside the rectangle: a point by its centre, a
	                     * segment clipped to it */
	meta_rgb_t nucleus_colour;
	double nucleus_radius; /* pixels (<= 0 means 2) */
} voronoi_style_t;

/* Label r once and write cells and/or boundaries to w on the current page:
 * the image first, then one stroked path per boundary polyline, then the
 * nuclei. Boundaries need the whole label image (4 bytes per pixel); cells
 * alone are written in bands. stats may be NULL. */
int voronoi_write_meta(meta_writer_t *w, const voronoi_t *v, const voronoi_rect_t *r,
                       const voronoi_style_t *style, voronoi_stats_t *stats);

/* The message of the last error in this thread ("" if none). */
const char *voronoi_error(void);

#ifdef __cplusplus
}
#endif
#endif
