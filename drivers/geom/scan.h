/* scan.h: exact scan conversion on the thousandths grid (meta-language spec §5), band by band.
 *
 * Everything here works in page coordinates: thousandths of a pixel, x to the right, y up,
 * pixel (i, j) is the square [i, i+1) x [j, j+1) and is painted when its centre
 * (1000i + 500, 1000j + 500) is covered. Painting goes into a band: a block of whole page rows
 * held top row first, 3 bytes (R, G, B) per pixel, so that a raster device never needs the
 * whole frame. Nothing here allocates per primitive once the work buffers have grown.
 */
#ifndef LOCUS_SCAN_H
#define LOCUS_SCAN_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include "locus_meta.h"

/* A point in thousandths of a pixel. int64 so that offsets of wide strokes never overflow. */
typedef struct {
	int64_t x, y;
} scan_pt_t;

/* Rows [jlo, jhi) of a page of width x height pixels. Page row j (counted from the bottom)
 * is stored at pix + (jhi - 1 - j) * stride: the top row of the band comes first. */
typedef struct {
	uint8_t *pix;
	size_t stride;
	int width, height;
	int jlo, jhi;
} scan_band_t;

/* A subpath of a scan_path_t: n points from index start; closed adds the segment back. */
typedef struct {
	size_t start, n;
	int closed;
} scan_subpath_t;

/* A growable path: points plus subpaths. Used for flattened meta paths, text and pieces. */
typedef struct {
	scan_pt_t *pts;
	size_t npts, cappts;
	scan_subpath_t *subs;
	size_t nsubs, capsubs;
	int open;          /* 1 while the last subpath can still take points */
} scan_path_t;

/* Stroke style in meta units (thousandths); dash already normalised to an even count. */
typedef struct {
	int64_t width;
	int cap, join;            /* META_CAP_*, META_JOIN_* */
	int64_t miter_limit;      /* thousandths, >= 1000 */
	const int64_t *dash;      /* on, off, on, off ... in thousandths; NULL/0 = solid */
	size_t ndash;
} scan_style_t;

/* Work buffers, reused from one primitive to the next. */
typedef struct scan_ctx scan_ctx_t;

/* Create/free a context. scan_ctx_new returns NULL when out of memory. */
scan_ctx_t *scan_ctx_new(void);
void scan_ctx_free(scan_ctx_t *c);

/* Fill the polygon made of the closed contours of p (every subpath implicitly closed) with
 * rgb into the band, by rule (META_RULE_EVEN_ODD or META_RULE_NON_ZERO), exactly per §5.1.
 * Returns 0, or META_ENOMEM. */
int scan_fill(scan_ctx_t *c, const scan_band_t *b, const scan_path_t *p, int rule, meta_rgb_t rgb);
/* Stroke the path's subpaths with the style (§5.3). Returns 0 or META_ENOMEM. */
int scan_stroke(scan_ctx_t *c, const scan_band_t *b, const scan_path_t *p, const scan_style_t *st,
		meta_rgb_t rgb);
/* The pieces of that stroke (§5.3: segments, joins, caps, dots, dash pieces), appended to out
 * as closed convex contours, each counter-clockwise, so that filling out by the non-zero rule
 * (§5.1) paints exactly the pixels scan_stroke paints. Pieces that cannot reach the page of
 * width x height pixels are left out. For vector devices that fill or hatch a stroke's
 * outline themselves. Returns 0 or META_ENOMEM. */
int scan_stroke_pieces(scan_ctx_t *c, const scan_path_t *p, const scan_style_t *st, int width,
		int height, scan_path_t *out);
/* The dash pieces of p by the §5.3 walk, appended to out as open subpaths (a subpath whose
 * points are all equal is copied as it is: it is a dot). Stroking out solid paints what
 * stroking p dashed paints. dash: the even list in thousandths, ndash > 0. */
int scan_dash_path(const scan_path_t *p, const int64_t *dash, size_t ndash, scan_path_t *out);
/* scan_dash_path with the pieces made only where they meet the box x0..x1, y0..y1
 * (thousandths; dash.c): a dashed line that runs far off the page costs what the page shows. */
int scan_dash_path_box(const scan_path_t *p, const int64_t *dash, size_t ndash, int64_t x0, int64_t y0,
		int64_t x1, int64_t y1, scan_path_t *out);
/* The polygon p (subpaths implicitly closed) as horizontal hatch lines y = y0 + k * step
 * (thousandths): on each line, the intervals whose points the §5.1 rule covers, appended to out
 * as open two-point subpaths from crossing to crossing. With y0 = 500 and step = 1000 the lines
 * run through the pixel centres and cover exactly the centres scan_fill paints. For devices
 * that cannot fill (pen plotters). Returns 0 or META_ENOMEM. */
int scan_hatch(const scan_path_t *p, int rule, int64_t y0, int64_t step, scan_path_t *out);
/* Paint n pixels from pixel (x, y) rightwards, clipped to the band and page. */
void scan_span(const scan_band_t *b, int64_t x, int64_t y, int64_t n, meta_rgb_t rgb);
/* Paint the whole band with rgb. */
void scan_clear(const scan_band_t *b, meta_rgb_t rgb);

/* ---- Paths (flatten.c) ---- */

/* Empty the path, keeping its memory. */
void scan_path_reset(scan_path_t *p);
/* Free the path's memory. */
void scan_path_free(scan_path_t *p);
/* Begin a new subpath at (x, y). */
int scan_path_move(scan_path_t *p, int64_t x, int64_t y);
/* Append a point to the current subpath (which must exist). */
int scan_path_draw(scan_path_t *p, int64_t x, int64_t y);
/* Close the current subpath; a following draw starts a new subpath at its start. */
int scan_path_close(scan_path_t *p);
/* 1 if there is a current point. */
int scan_path_has_current(const scan_path_t *p);
/* Arc per §5.4 (all values thousandths; angles thousandths of degrees). With a current point
 * a segment joins it to the arc's start, else the arc starts a subpath. */
int scan_path_arc(scan_path_t *p, int64_t cx, int64_t cy, int64_t r, int64_t start, int64_t sweep);
/* Full circle as a closed subpath of its own; leaves no current point. */
int scan_path_circle(scan_path_t *p, int64_t cx, int64_t cy, int64_t r);
/* The same with the chord count M of a circle of radius rchord: a raster device of its own
 * resolution flattens at its pixels (rchord = the radius in device thousandths), then maps. */
int scan_path_arc_res(scan_path_t *p, int64_t cx, int64_t cy, int64_t r, int64_t start, int64_t sweep,
		int64_t rchord);
int scan_path_circle_res(scan_path_t *p, int64_t cx, int64_t cy, int64_t r, int64_t rchord);
/* Number of chords M of a full circle of radius r thousandths (§5.4). */
int scan_circle_chords(int64_t r);
/* Bounding box of the path's points; returns 0 when the path has no points. */
int scan_path_bbox(const scan_path_t *p, int64_t *x0, int64_t *y0, int64_t *x1, int64_t *y1);

/* The dash pattern's period (sum of the even list); §5.3 draws a pattern whose period is below
 * one pixel (SCAN_DASH_MIN_PERIOD thousandths) as a solid line (§6). */
int64_t scan_dash_period(const int64_t *dash, size_t ndash);
#define SCAN_DASH_MIN_PERIOD 1000

/* Round a double to the nearest integer (thousandths), ties away from zero. */
static inline int64_t scan_round(double v)
{
	double t = trunc(v), f = v - t;
	/* without branches (the fraction's side is unpredictable); |t| >= 2^53 has f = 0 */
	return (int64_t)t + (f >= 0.5) - (f <= -0.5);
}

/* ---- Text (font.c) ---- */

/* Append the strokes of the text (§5.5) to p as open subpaths. size and angle in thousandths
 * (pixels, degrees). Returns 0 or META_ENOMEM. */
int scan_text_path(scan_path_t *p, const char *s, size_t len, int64_t x, int64_t y, int64_t size,
		int64_t angle);
/* Advance width of a text in font units (6 units = capital height); used by docs and tests. */
double scan_text_advance(const char *s, size_t len);
/* The glyph strokes of character ch (0x20-0x7e, anything else = replacement) as the font's
 * source string, and its advance in font units. For docs/stroke-font.md generation. */
const char *scan_glyph_source(int ch, double *advance);

#endif
