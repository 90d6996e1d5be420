/* voronoi_out.c: Voronoi tessellations to the meta-language: cells as image rows, boundaries as strokes. */
#include "voronoi_int.h"

#include <stdlib.h>

static int fail_meta(meta_writer_t *w, const char *what)
{
	const char *msg = meta_writer_error(w);
	return voronoi_fail(VORONOI_EMETA, "voronoi: %s: %s", what, msg && *msg ? msg : "meta writer failed");
}

static int check_rect(const voronoi_rect_t *r)
{
	if (!r || r->width == 0 || r->height == 0 || r->width > META_MAX_DIM || r->height > META_MAX_DIM)
		return voronoi_fail(VORONOI_EARG, "voronoi: rectangle must be 1..%d pixels each way", META_MAX_DIM);
	return 0;
}

/* Write the labelled rectangle as one image, top row first. */
static int write_image(meta_writer_t *w, const voronoi_t *v, const voronoi_rect_t *r,
                       const int32_t *labels)
{
	meta_rgb_t *row = malloc(r->width * sizeof *row);
	int rc = 0;
	if (!row)
		return voronoi_fail(VORONOI_ENOMEM, "voronoi: out of memory for a %u-pixel row", r->width);
	if (meta_image(w, r->x, r->y, r->width, r->height) < 0) {
		rc = fail_meta(w, "starting the cell image");
		goto done;
	}
	for (unsigned k = 0; k < r->height; k++) {
		const int32_t *lr = labels + (size_t)(r->height - 1 - k) * r->width;
		for (unsigned i = 0; i < r->width; i++)
			row[i] = v->nuclei[lr[i]].colour;
		if (meta_row_pixels(w, row, r->width) < 0) {
			rc = fail_meta(w, "writing a cell row");
			goto done;
		}
	}
done:
	free(row);
	return rc;
}

#define BAND 64 /* rows labelled at a time when only cells are drawn */

/* The cell image in bands of BAND rows from the top; labels are per pixel,
 * so the picture is the same as labelling the whole rectangle at once. */
static int write_banded(meta_writer_t *w, const voronoi_t *v, const voronoi_rect_t *r, unsigned threads)
{
	unsigned bh = r->height < BAND ? r->height : BAND;
	int32_t *labels = malloc((size_t)r->width * bh * sizeof *labels);
	meta_rgb_t *row = malloc(r->width * sizeof *row);
	int rc = 0;
	if (!labels || !row) {
		rc = voronoi_fail(VORONOI_ENOMEM, "voronoi: out of memory for %ux%u labels", r->width, bh);
		goto done;
	}
	if (meta_image(w, r->x, r->y, r->width, r->height) < 0) {
		rc = fail_meta(w, "starting the cell image");
		goto done;
	}
	for (unsigned top = r->height; top > 0;) {
		unsigned n = top < bh ? top : bh;
		voronoi_rect_t band = { r->x, r->y + top - n, r->width, n };
		if ((rc = voronoi_label(v, &band, threads, labels)) < 0)
			goto done;
		for (unsigned k = 0; k < n; k++) {
			const int32_t *lr = labels + (size_t)(n - 1 - k) * r->width;
			for (unsigned i = 0; i < r->width; i++)
				row[i] = v->nuclei[lr[i]].colour;
			if (meta_row_pixels(w, row, r->width) < 0) {
				rc = fail_meta(w, "writing a cell row");
				goto done;
			}
		}
		top -= n;
	}
done:
	free(labels);
	free(row);
	return rc;
}

int voronoi_write_cells(meta_writer_t *w, const voronoi_t *v, const voronoi_rect_t *r,
                        unsigned threads)
{
	voronoi_style_t st = { 1, 0, 0, 1, threads, 0, 0, 0 };
	return voronoi_write_meta(w, v, r, &st, NULL);
}

static int stroke_cb(void *user, int32_t left, int32_t right, const voronoi_point_t *p, size_t n, int closed)
{
	meta_writer_t *w = user;
	(void)left;
	(void)right;
	/* a boundary is at most a few times the rectangle's perimeter, far
	 * below META_MAX_PATH_POINTS; split anyway to stay within the limit */
	size_t step = META_MAX_PATH_POINTS - 1;
	for (size_t s = 0; s + 1 < n; s += step) {
		size_t m = n - s < step + 1 ? n - s : step + 1;
		if (meta_stroke(w) < 0 || meta_move(w, p[s].x, p[s].y) < 0)
			return -1;
		for (size_t i = 1; i < m; i++)
			if (meta_draw(w, p[s + i].x, p[s + i].y) < 0)
				return -1;
		if (closed && m == n && meta_close(w) < 0)
			return -1;
		if (meta_end(w) < 0)
			return -1;
	}
	if (closed && n > step + 1) {
		if (meta_stroke(w) < 0 || meta_move(w, p[n - 1].x, p[n - 1].y) < 0 ||
		    meta_draw(w, p[0].x, p[0].y) < 0 || meta_end(w) < 0)
			return -1;
	}
	return 0;
}

/* Clip the page segment a-b to the rectangle r (Liang-Barsky): 0 when nothing is left. */
static int clip_segment(const voronoi_rect_t *r, double *ax, double *ay, double *bx, double *by)
{
	double x0 = r->x, y0 = r->y, x1 = (double)r->x + r->width, y1 = (double)r->y + r->height;
	double dx = *bx - *ax, dy = *by - *ay, t0 = 0, t1 = 1;
	double p[4] = {-dx, dx, -dy, dy}, q[4] = {*ax - x0, x1 - *ax, *ay - y0, y1 - *ay};
	for (int i = 0; i < 4; i++) {
		if (p[i] == 0) {
			if (q[i] < 0)
				return 0;
			continue;
		}
		double t = q[i] / p[i];
		if (p[i] < 0)
			t0 = t > t0 ? t : t0;
		else
			t1 = t < t1 ? t : t1;
	}
	if (t0 > t1)
		return 0;
	double sx = *ax, sy = *ay;
	*ax = sx + t0 * dx;
	*ay = sy + t0 * dy;
	*bx = sx + t1 * dx;
	*by = sy + t1 * dy;
	return 1;
}

/* Mark every nucleus inside the rectangle: a disc for a point (its centre
 * inside), a round-capped stroke for a segment or each segment of a polyline
 * (the part inside), so that the
 * marks stay within the picture when it is an inset of a larger page. */
static int write_nuclei(meta_writer_t *w, const voronoi_t *v, const voronoi_rect_t *r, const voronoi_style_t *style)
{
	double rad = style->nucleus_radius > 0 ? style->nucleus_radius : 2;
	double x0 = r->x, y0 = r->y, x1 = (double)r->x + r->width, y1 = (double)r->y + r->height;
	const double *m = v->m;
	if (meta_colour(w, style->nucleus_colour) < 0)
		return fail_meta(w, "setting the nucleus colour");
	for (size_t k = 0; k < v->count; k++) {
		const voronoi_nucleus_t *n = &v->nuclei[k];
		double ax = m[0] + m[1] * n->a[0] + m[2] * n->a[1], ay = m[3] + m[4] * n->a[0] + m[5] * n->a[1];
		int rc = 0;
		if (n->kind == VORONOI_POLYLINE) {
			/* each segment's part inside, round-capped, so the joints are round too */
			if (meta_width(w, 2 * rad) < 0 || meta_cap(w, META_CAP_ROUND) < 0)
				return fail_meta(w, "writing a nucleus");
			for (size_t i = 0; i + 1 < n->npts && !rc; i++) {
				const double *a = n->pts + 3 * i, *b = a + 3;
				double sx = m[0] + m[1] * a[0] + m[2] * a[1], sy = m[3] + m[4] * a[0] + m[5] * a[1];
				double ex = m[0] + m[1] * b[0] + m[2] * b[1], ey = m[3] + m[4] * b[0] + m[5] * b[1];
				if (clip_segment(r, &sx, &sy, &ex, &ey))
					rc = meta_stroke(w) < 0 || meta_move(w, sx, sy) < 0 || meta_draw(w, ex, ey) < 0 || meta_end(w) < 0;
			}
		} else if (n->kind == VORONOI_SEGMENT) {
			double bx = m[0] + m[1] * n->b[0] + m[2] * n->b[1], by = m[3] + m[4] * n->b[0] + m[5] * n->b[1];
			if (!clip_segment(r, &ax, &ay, &bx, &by))
				continue;
			rc = meta_width(w, 2 * rad) < 0 || meta_cap(w, META_CAP_ROUND) < 0 || meta_stroke(w) < 0 ||
			     meta_move(w, ax, ay) < 0 || meta_draw(w, bx, by) < 0 || meta_end(w) < 0;
		} else {
			if (!(ax >= x0 && ax <= x1 && ay >= y0 && ay <= y1))
				continue;
			rc = meta_fill(w) < 0 || meta_circle(w, ax, ay, rad) < 0 || meta_end(w) < 0;
		}
		if (rc)
			return fail_meta(w, "writing a nucleus");
	}
	return 0;
}

int voronoi_write_meta(meta_writer_t *w, const voronoi_t *v, const voronoi_rect_t *r,
                       const voronoi_style_t *style, voronoi_stats_t *stats)
{
	int rc = voronoi_check(v);
	if (rc < 0)
		return rc;
	if ((rc = check_rect(r)) < 0)
		return rc;
	if (!w || !style)
		return voronoi_fail(VORONOI_EARG, "voronoi: no meta writer or no style");
	if (!style->boundaries) {
		/* cells only: label and write in bands, memory O(width) */
		if (style->cells && (rc = write_banded(w, v, r, style->threads)) < 0)
			return rc;
		return style->nuclei ? write_nuclei(w, v, r, style) : 0;
	}
	int32_t *labels = malloc((size_t)r->width * r->height * sizeof *labels);
	if (!labels)
		return voronoi_fail(VORONOI_ENOMEM, "voronoi: out of memory for %ux%u labels", r->width, r->height);
	if ((rc = voronoi_label(v, r, style->threads, labels)) < 0)
		goto done;
	if (style->cells && (rc = write_image(w, v, r, labels)) < 0)
		goto done;
	if (style->boundaries) {
		if (meta_colour(w, style->line_colour) < 0 ||
		    meta_width(w, style->line_width > 0 ? style->line_width : 1) < 0) {
			rc = fail_meta(w, "setting the boundary style");
			goto done;
		}
		rc = voronoi_boundaries(v, r, labels, stroke_cb, w, stats);
		if (rc == VORONOI_ECALLBACK)
			rc = fail_meta(w, "writing a boundary");
	}
	if (rc == 0 && style->nuclei)
		rc = write_nuclei(w, v, r, style);
done:
	free(labels);
	return rc;
}
