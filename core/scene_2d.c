/* scene_2d.c: the plane visualisations of a scene: contour maps of a shape's field and Voronoi tessellations. */
#include "scene_int.h"
#include "contour.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A distinct light colour per index: hues spread by the golden ratio. */
static meta_rgb_t cell_colour(size_t k)
{
	double h = fmod(k * 0.6180339887498949, 1.0) * 6, s = 0.45, v = 0.95;
	int i = (int)h;
	double f = h - i, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f)), c[3];
	switch (i) {
	case 0: c[0] = v; c[1] = t; c[2] = p; break;
	case 1: c[0] = q; c[1] = v; c[2] = p; break;
	case 2: c[0] = p; c[1] = v; c[2] = t; break;
	case 3: c[0] = p; c[1] = q; c[2] = v; break;
	case 4: c[0] = t; c[1] = p; c[2] = v; break;
	default: c[0] = v; c[1] = p; c[2] = q; break;
	}
	return (meta_rgb_t)((unsigned)(c[0] * 255 + 0.5) << 16 | (unsigned)(c[1] * 255 + 0.5) << 8 | (unsigned)(c[2] * 255 + 0.5));
}

static int map_contours(scene_t *s, const scene_render_t *r, meta_writer_t *w, const unsigned rect[4],
                       scene_stats_t *st, char *err, size_t errlen)
{
	const model_shape_t *shape = NULL;
	for (size_t i = 0; i < s->nobjs && !shape; i++)
		if (r->field[0] ? !strcmp(r->field, s->objs[i].name) : s->objs[i].drawn)
			shape = s->objs[i].shape;
	if (!shape) {
		snprintf(err, errlen, "%s:%u:%u: expected %s%s%s to map", s->name, r->line, r->col,
		         r->field[0] ? "a shape named '" : "an object", r->field, r->field[0] ? "'" : "");
		return -1;
	}
	unsigned x0 = rect[0], y0 = rect[1], nx = rect[2], ny = rect[3];
	size_t n = (size_t)nx * ny;
	float *z = malloc((n + 8) * sizeof *z);
	double *levels = malloc((r->nlevels + 1) * sizeof *levels);
	meta_rgb_t *cols = malloc((r->nlevels + 2) * sizeof *cols);
	int rc = 0;
	if (!z || !levels || !cols) {
		snprintf(err, errlen, "out of memory for a %ux%u field", nx, ny);
		rc = -1;
		goto done;
	}
	double t0 = scene_now();
	float x[8], y[8], zz[8], out[8];
	double sx = (r->window[2] - r->window[0]) / nx, sy = (r->window[3] - r->window[1]) / ny;
	for (size_t i0 = 0; i0 < n; i0 += 8) {
		for (size_t k = 0; k < 8; k++) {
			size_t i = i0 + k < n ? i0 + k : n - 1;
			x[k] = (float)(r->window[0] + ((double)(i % nx) + 0.5) * sx);
			y[k] = (float)(r->window[1] + ((double)(i / nx) + 0.5) * sy);
			zz[k] = (float)r->plane;
			if (r->has_on) {   /* any plane: P = O + s U + t V, (s, t) over the window */
				double a = r->window[0] + ((double)(i % nx) + 0.5) * sx, b = r->window[1] + ((double)(i / nx) + 0.5) * sy;
				const double *o = r->on;
				x[k] = (float)(o[0] + a * o[3] + b * o[6]);
				y[k] = (float)(o[1] + a * o[4] + b * o[7]);
				zz[k] = (float)(o[2] + a * o[5] + b * o[8]);
			}
		}
		model_eval8(shape, x, y, zz, out);
		for (size_t k = 0; k < 8 && i0 + k < n; k++)
			z[i0 + k] = out[k];
	}
	for (unsigned k = 0; k < r->nlevels; k++)
		levels[k] = r->nlevels == 1 ? r->level_from
		          : r->level_from + (r->level_to - r->level_from) * k / (r->nlevels - 1);
	contour_grid_t g;
	memset(&g, 0, sizeof g);
	g.z = z;
	g.nx = nx;
	g.ny = ny;
	contour_map_rect(g.m, nx, ny, x0 + 0.5, y0 + 0.5, x0 + nx - 0.5, y0 + ny - 0.5);
	contour_stats_t cs;
	contour_style_t style = {NULL, r->line_width};
	if (nx < 2 || ny < 2) {
		snprintf(err, errlen, "%s:%u:%u: expected a viewport of at least 2x2 pixels for a contour map", s->name, r->line, r->col);
		rc = -1;
		goto done;
	}
	if (r->bands) {
		contour_palette(cols, r->nlevels + 1);
		if (contour_write_bands(w, &g, levels, r->nlevels, cols, scene_rgb(s->background), x0, y0, nx, ny) < 0) {
			snprintf(err, errlen, "%s", contour_error());
			rc = -1;
			goto done;
		}
		for (unsigned k = 0; k < r->nlevels; k++)
			cols[k] = scene_rgb(r->line_colour);
	} else {
		contour_palette(cols, r->nlevels);
	}
	style.colours = cols;
	if (contour_write_meta(w, &g, levels, r->nlevels, &style, &cs) < 0) {
		snprintf(err, errlen, "%s", contour_error());
		rc = -1;
		goto done;
	}
	st->contour_segments += cs.segments;
	st->seconds_trace += scene_now() - t0;
	if (cs.segments == 0) {
		char msg[200];
		snprintf(msg, sizeof msg, "the contour map has no lines at levels %g..%g", r->level_from, r->level_to);
		scene_add_warning(s, msg);
	}
done:
	free(z);
	free(levels);
	free(cols);
	return rc;
}

static int map_voronoi(scene_t *s, const scene_render_t *r, meta_writer_t *w, const scene_opts_t *o,
                       const unsigned rect[4], scene_stats_t *st, char *err, size_t errlen)
{
	if (r->nnuclei == 0) {
		snprintf(err, errlen, "%s:%u:%u: expected at least one nucleus (point or segment) in the voronoi block",
		         s->name, r->line, r->col);
		return -1;
	}
	for (size_t i = 0; i < r->nnuclei; i++) {
		if (r->nuclei[i].colour == SCENE_NO_COLOUR)
			r->nuclei[i].colour = cell_colour(i);
		if (isnan(r->nuclei[i].weight))
			r->nuclei[i].weight = r->metric == VORONOI_MULTIPLICATIVE ? 1 : 0;
	}
	voronoi_t v;
	memset(&v, 0, sizeof v);
	v.nuclei = r->nuclei;
	v.count = r->nnuclei;
	v.metric = r->metric;
	unsigned x0 = rect[0], y0 = rect[1], nx = rect[2], ny = rect[3];
	voronoi_map_window(v.m, r->window[0], r->window[1], r->window[2], r->window[3], x0, y0, x0 + nx, y0 + ny);
	if (voronoi_check(&v) < 0) {
		snprintf(err, errlen, "%s:%u:%u: %s", s->name, r->line, r->col, voronoi_error());
		return -1;
	}
	voronoi_rect_t area = {x0, y0, nx, ny};
	voronoi_style_t style;
	memset(&style, 0, sizeof style);
	style.cells = r->cells;
	style.boundaries = r->boundaries;
	style.line_colour = scene_rgb(r->line_colour);
	style.line_width = r->line_width;
	style.nuclei = r->nuclei_marks;
	style.nucleus_colour = style.line_colour;
	style.nucleus_radius = fmax(1.5, fmin(nx, ny) / 130.0);
	style.threads = o ? o->threads : 0;
	voronoi_stats_t vs;
	double t0 = scene_now();
	if (voronoi_write_meta(w, &v, &area, &style, &vs) < 0) {
		snprintf(err, errlen, "%s", voronoi_error());
		return -1;
	}
	st->seconds_trace += scene_now() - t0;
	st->pixels += nx * ny;
	return 0;
}

/* A one-pixel frame just inside an inset's rectangle, in the line colour. */
static int inset_frame(const scene_render_t *r, meta_writer_t *w, const unsigned rect[4])
{
	double x0 = rect[0] + 0.5, y0 = rect[1] + 0.5, x1 = rect[0] + rect[2] - 0.5, y1 = rect[1] + rect[3] - 0.5;
	return meta_colour(w, scene_rgb(r->line_colour)) < 0 || meta_width(w, 1) < 0 || meta_stroke(w) < 0
	    || meta_move(w, x0, y0) < 0 || meta_draw(w, x1, y0) < 0 || meta_draw(w, x1, y1) < 0
	    || meta_draw(w, x0, y1) < 0 || meta_close(w) < 0 || meta_end(w) < 0 ? -1 : 0;
}

int scene_render_2d(scene_t *s, const scene_render_t *r, meta_writer_t *w, const scene_opts_t *o,
                    const unsigned rect[4], scene_stats_t *st, char *err, size_t errlen)
{
	int rc = r->kind == SCENE_CONTOUR ? map_contours(s, r, w, rect, st, err, errlen)
	                                  : map_voronoi(s, r, w, o, rect, st, err, errlen);
	if (rc == 0 && r->has_inset && inset_frame(r, w, rect) < 0) {
		snprintf(err, errlen, "%s", meta_writer_error(w));
		return -1;
	}
	return rc;
}
