/* contour_out.c: contour maps to the meta-language: stroked iso-lines, raster bands, a level palette. */
#include "contour.h"
#include "contour_int.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Record the meta writer's message as the contour error. */
static int fail_meta(meta_writer_t *w, const char *what)
{
	const char *msg = meta_writer_error(w);
	return contour_fail(CONTOUR_EMETA, "contour: %s: %s", what, msg && *msg ? msg : "meta writer failed");
}

void contour_map_rect(double m[6], unsigned nx, unsigned ny,
                      double x0, double y0, double x1, double y1)
{
	m[0] = x0;
	m[1] = nx > 1 ? (x1 - x0) / (nx - 1) : 0;
	m[2] = 0;
	m[3] = y0;
	m[4] = 0;
	m[5] = ny > 1 ? (y1 - y0) / (ny - 1) : 0;
}

/* State of contour_write_meta's callback. */
typedef struct {
	meta_writer_t *w;
	const contour_style_t *style;
	int rc;
} wctx_t;

/* One path of points p[0..n-1]; close it when asked. */
static int write_path(meta_writer_t *w, const contour_point_t *p, size_t n, int closed)
{
	if (meta_stroke(w) < 0 || meta_move(w, p[0].x, p[0].y) < 0)
		return -1;
	for (size_t i = 1; i < n; i++)
		if (meta_draw(w, p[i].x, p[i].y) < 0)
			return -1;
	if (closed && meta_close(w) < 0)
		return -1;
	return meta_end(w);
}

static int write_polyline(void *user, unsigned level, const contour_point_t *p, size_t n, int closed)
{
	wctx_t *c = user;
	meta_rgb_t rgb = c->style && c->style->colours ? c->style->colours[level] : 0x000000;
	if (meta_colour(c->w, rgb) < 0)
		goto bad;
	if (n + (closed != 0) <= META_MAX_PATH_POINTS) {
		if (write_path(c->w, p, n, closed) < 0)
			goto bad;
		return 0;
	}
	/* too long for one path: consecutive open pieces sharing end points,
	 * the last one returning to the start of a closed loop */
	size_t step = META_MAX_PATH_POINTS - 1;
	for (size_t s = 0; s + 1 < n; s += step) {
		size_t m = n - s < step + 1 ? n - s : step + 1;
		if (write_path(c->w, p + s, m, 0) < 0)
			goto bad;
	}
	if (closed) {
		contour_point_t last[2] = { p[n - 1], p[0] };
		if (write_path(c->w, last, 2, 0) < 0)
			goto bad;
	}
	return 0;
bad:
	c->rc = fail_meta(c->w, "writing iso-lines");
	return -1;
}

int contour_write_meta(meta_writer_t *w, const contour_grid_t *g, const double *levels,
                       unsigned nlevels, const contour_style_t *style,
                       contour_stats_t *stats)
{
	wctx_t c = { w, style, 0 };
	if (!w)
		return contour_fail(CONTOUR_EARG, "contour: no meta writer");
	double width = style && style->width > 0 ? style->width : 1;
	if (meta_width(w, width) < 0)
		return fail_meta(w, "setting the line width");
	int rc = contour_extract(g, levels, nlevels, write_polyline, &c, stats);
	if (c.rc < 0)
		return c.rc; /* the writer's message, not "stopped by the caller" */
	return rc;
}

/* Number of sorted levels sl[0..n-1] that are <= v. */
static unsigned band_of(const double *sl, unsigned n, double v)
{
	unsigned lo = 0, hi = n;
	while (lo < hi) {
		unsigned mid = lo + (hi - lo) / 2;
		if (sl[mid] <= v)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo;
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

int contour_write_bands(meta_writer_t *w, const contour_grid_t *g, const double *levels,
                        unsigned nlevels, const meta_rgb_t *band_colours, meta_rgb_t nodata,
                        unsigned x, unsigned y, unsigned width, unsigned height)
{
	const double *m = g ? g->m : NULL;
	double *sl = NULL;
	meta_rgb_t *row = NULL;
	int rc = 0;
	if (!w || !g || !g->z || g->nx < 2 || g->ny < 2 || !band_colours || (nlevels && !levels))
		return contour_fail(CONTOUR_EARG, "contour: bands need a writer, a grid of 2x2 or more and colours");
	if (width == 0 || height == 0 || width > META_MAX_DIM || height > META_MAX_DIM)
		return contour_fail(CONTOUR_EARG, "contour: band image of %ux%u pixels", width, height);
	double det = m[1] * m[5] - m[2] * m[4];
	if (!isfinite(det) || fabs(det) < 1e-300)
		return contour_fail(CONTOUR_EARG, "contour: the grid map is not invertible");
	/* inverse: grid index of a page point */
	double a = m[5] / det, b = -m[2] / det, c = -m[4] / det, d = m[1] / det;
	sl = malloc((nlevels ? nlevels : 1) * sizeof *sl);
	row = malloc(width * sizeof *row);
	if (!sl || !row) {
		rc = contour_fail(CONTOUR_ENOMEM, "contour: out of memory for a %u-pixel row", width);
		goto done;
	}
	for (unsigned l = 0; l < nlevels; l++) {
		if (!isfinite(levels[l])) {
			rc = contour_fail(CONTOUR_EARG, "contour: level %u is not finite", l);
			goto done;
		}
		sl[l] = levels[l];
	}
	qsort(sl, nlevels, sizeof *sl, cmp_double);
	if (meta_image(w, x, y, width, height) < 0) {
		rc = fail_meta(w, "starting the band image");
		goto done;
	}
	size_t nx = g->nx;
	double gmaxi = g->nx - 1, gmaxj = g->ny - 1;
	for (unsigned r = 0; r < height; r++) {
		double py = (double)y + (height - 1 - r) + 0.5; /* top row first */
		for (unsigned i = 0; i < width; i++) {
			double px = (double)x + i + 0.5 - m[0], qy = py - m[3];
			double gi = a * px + b * qy, gj = c * px + d * qy;
			meta_rgb_t col = nodata;
			if (gi >= 0 && gj >= 0 && gi <= gmaxi && gj <= gmaxj) {
				size_t i0 = (size_t)gi, j0 = (size_t)gj;
				if (i0 >= nx - 1)
					i0 = nx - 2;
				if (j0 >= g->ny - 1)
					j0 = g->ny - 2;
				double u = gi - i0, v = gj - j0;
				const float *z0 = g->z + j0 * nx + i0, *z1 = z0 + nx;
				double val = (1 - v) * ((1 - u) * z0[0] + u * z0[1]) + v * ((1 - u) * z1[0] + u * z1[1]);
				if (isfinite(z0[0]) && isfinite(z0[1]) && isfinite(z1[0]) && isfinite(z1[1]))
					col = band_colours[band_of(sl, nlevels, val)];
			}
			row[i] = col;
		}
		if (meta_row_pixels(w, row, width) < 0) {
			rc = fail_meta(w, "writing a band row");
			goto done;
		}
	}
done:
	free(sl);
	free(row);
	return rc;
}

int contour_auto_levels(const contour_grid_t *g, unsigned n, double *levels)
{
	if (!g || !g->z || (n && !levels))
		return contour_fail(CONTOUR_EARG, "contour: auto levels need a grid and room for the levels");
	size_t ns = (size_t)g->nx * g->ny;
	double lo = INFINITY, hi = -INFINITY;
	for (size_t s = 0; s < ns; s++) {
		double v = g->z[s];
		if (isfinite(v)) {
			lo = v < lo ? v : lo;
			hi = v > hi ? v : hi;
		}
	}
	if (!(hi > lo))
		return 0;
	for (unsigned k = 0; k < n; k++)
		levels[k] = lo + (k + 1) * (hi - lo) / (n + 1);
	return (int)n;
}

void contour_palette(meta_rgb_t *out, unsigned n)
{
	static const unsigned char stop[6][3] = {
		{ 0x2c, 0x3e, 0x9e }, { 0x1f, 0x9e, 0xa6 }, { 0x4c, 0xaf, 0x50 },
		{ 0xe0, 0xc4, 0x2c }, { 0xf2, 0x8c, 0x28 }, { 0xa6, 0x1c, 0x1c },
	};
	for (unsigned k = 0; k < n; k++) {
		double t = n > 1 ? (double)k / (n - 1) * 5 : 2.5;
		int s = (int)t;
		if (s > 4)
			s = 4;
		double f = t - s;
		meta_rgb_t rgb = 0;
		for (int ch = 0; ch < 3; ch++) {
			double v = stop[s][ch] + f * (stop[s + 1][ch] - stop[s][ch]);
			rgb = rgb << 8 | (meta_rgb_t)lround(v);
		}
		out[k] = rgb;
	}
}
