/* convenience.c: producer calls over meta_write: doubles rounded to thousandths, unchanged page state elided. */
#include <stdlib.h>
#include <string.h>
#include "meta_int.h"

/* Convert n doubles; an infinite, NaN or out-of-range value is the caller's error. */
static int fixes(meta_writer_t *w, const char *fn, const double *v, int n, meta_fix_t *out)
{
	int i, ok;
	for (i = 0; i < n; i++) {
		out[i] = meta_fix_from_double(v[i], &ok);
		if (!ok)
			return meta_wr_fail(w, META_EARG, fn, "expected a finite number from -1000000 to 1000000 as argument %d, found %g",
			                    i + 1, v[i]);
	}
	return 0;
}

static int simple(meta_writer_t *w, meta_op_t op)
{
	meta_cmd_t c;
	memset(&c, 0, sizeof c);
	c.op = op;
	return meta_write(w, &c);
}

static int with_fix(meta_writer_t *w, meta_op_t op, const char *fn, const double *v, int n)
{
	meta_cmd_t c;
	memset(&c, 0, sizeof c);
	c.op = op;
	if (fixes(w, fn, v, n, c.f) < 0)
		return META_EARG;
	return meta_write(w, &c);
}

static int with_uint(meta_writer_t *w, meta_op_t op, unsigned a, unsigned b, unsigned c3, unsigned d, meta_rgb_t rgb)
{
	meta_cmd_t c;
	memset(&c, 0, sizeof c);
	c.op = op;
	c.u[0] = a, c.u[1] = b, c.u[2] = c3, c.u[3] = d;
	c.rgb = rgb;
	return meta_write(w, &c);
}

/* 1 when a state statement would repeat the page's current value. */
#define SAME(cond) (w->chk.in_page && !w->chk.in_path && !w->chk.rows_left && (cond))

int meta_page(meta_writer_t *w, unsigned width, unsigned height)
{
	return with_uint(w, META_PAGE, width, height, 0, 0, 0);
}

int meta_page_size_mm(meta_writer_t *w, double width_mm, double height_mm)
{
	double v[2] = { width_mm, height_mm };
	return with_fix(w, META_SIZE, "meta_page_size_mm", v, 2);
}

int meta_clear(meta_writer_t *w, meta_rgb_t rgb)
{
	return with_uint(w, META_CLEAR, 0, 0, 0, 0, rgb);
}

int meta_end_page(meta_writer_t *w) { return simple(w, META_END_PAGE); }

int meta_colour(meta_writer_t *w, meta_rgb_t rgb)
{
	if (SAME(w->colour == rgb))
		return 0;
	return with_uint(w, META_COLOUR, 0, 0, 0, 0, rgb);
}

int meta_width(meta_writer_t *w, double width)
{
	meta_cmd_t c;
	memset(&c, 0, sizeof c);
	c.op = META_WIDTH;
	if (fixes(w, "meta_width", &width, 1, c.f) < 0)
		return META_EARG;
	if (SAME(w->width == c.f[0]))
		return 0;
	return meta_write(w, &c);
}

int meta_miter_limit(meta_writer_t *w, double limit)
{
	meta_cmd_t c;
	memset(&c, 0, sizeof c);
	c.op = META_MITER_LIMIT;
	if (fixes(w, "meta_miter_limit", &limit, 1, c.f) < 0)
		return META_EARG;
	if (SAME(w->miter == c.f[0]))
		return 0;
	return meta_write(w, &c);
}

int meta_dash(meta_writer_t *w, const double *lengths, size_t n)
{
	meta_fix_t list[META_MAX_DASH];
	meta_cmd_t c;
	if (n > META_MAX_DASH)
		return meta_wr_fail(w, META_ELIMIT, "meta_dash", "expected at most %d dash lengths, found %zu",
		                    META_MAX_DASH, n);
	if (n && !lengths)
		return meta_wr_fail(w, META_EARG, "meta_dash", "expected a list of lengths, found a null pointer");
	if (fixes(w, "meta_dash", lengths, (int)n, list) < 0)
		return META_EARG;
	if (SAME(w->ndash == n && (n == 0 || memcmp(w->dash, list, n * sizeof *list) == 0)))
		return 0;
	memset(&c, 0, sizeof c);
	c.op = META_DASH;
	c.list = list;
	c.nlist = n;
	return meta_write(w, &c);
}

static int keyword(meta_writer_t *w, meta_op_t op, int k, int current)
{
	meta_cmd_t c;
	if (SAME(current == k))
		return 0;
	memset(&c, 0, sizeof c);
	c.op = op;
	c.k = k;
	return meta_write(w, &c);
}

int meta_cap(meta_writer_t *w, int cap) { return keyword(w, META_CAP, cap, w->cap); }
int meta_join(meta_writer_t *w, int join) { return keyword(w, META_JOIN, join, w->join); }
int meta_fill_rule(meta_writer_t *w, int rule) { return keyword(w, META_FILL_RULE, rule, w->rule); }
int meta_stroke(meta_writer_t *w) { return simple(w, META_STROKE); }
int meta_fill(meta_writer_t *w) { return simple(w, META_FILL); }
int meta_close(meta_writer_t *w) { return simple(w, META_CLOSE); }
int meta_end(meta_writer_t *w) { return simple(w, META_END); }

int meta_move(meta_writer_t *w, double x, double y)
{
	double v[2] = { x, y };
	return with_fix(w, META_MOVE, "meta_move", v, 2);
}

int meta_draw(meta_writer_t *w, double x, double y)
{
	double v[2] = { x, y };
	return with_fix(w, META_DRAW, "meta_draw", v, 2);
}

int meta_arc(meta_writer_t *w, double cx, double cy, double r, double start_deg, double sweep_deg)
{
	double v[5] = { cx, cy, r, start_deg, sweep_deg };
	return with_fix(w, META_ARC, "meta_arc", v, 5);
}

int meta_circle(meta_writer_t *w, double cx, double cy, double r)
{
	double v[3] = { cx, cy, r };
	return with_fix(w, META_CIRCLE, "meta_circle", v, 3);
}

int meta_text(meta_writer_t *w, double x, double y, double size, double angle_deg, const char *s)
{
	double v[4] = { x, y, size, angle_deg };
	meta_cmd_t c;
	memset(&c, 0, sizeof c);
	c.op = META_TEXT;
	if (fixes(w, "meta_text", v, 4, c.f) < 0)
		return META_EARG;
	c.str = s ? s : "";
	c.len = strlen(c.str);
	return meta_write(w, &c);
}

int meta_span(meta_writer_t *w, unsigned x, unsigned y, unsigned n, meta_rgb_t rgb)
{
	return with_uint(w, META_SPAN, x, y, n, 0, rgb);
}

int meta_image(meta_writer_t *w, unsigned x, unsigned y, unsigned width, unsigned height)
{
	return with_uint(w, META_IMAGE, x, y, width, height, 0);
}

int meta_row_pixels(meta_writer_t *w, const meta_rgb_t *pixels, size_t width)
{
	meta_cmd_t c;
	size_t i, n = 0;
	if (width > META_MAX_DIM)
		return meta_wr_fail(w, META_ELIMIT, "meta_row_pixels", "expected at most %d pixels, found %zu",
		                    META_MAX_DIM, width);
	if (width && !pixels)
		return meta_wr_fail(w, META_EARG, "meta_row_pixels", "expected pixels, found a null pointer");
	if (width > w->runs_cap) {
		meta_run_t *nr = realloc(w->runs, width * sizeof *nr);
		if (!nr)
			return meta_wr_fail(w, META_ENOMEM, "meta_row_pixels", "out of memory");
		w->runs = nr;
		w->runs_cap = width;
	}
	for (i = 0; i < width; i++) {
		if (n && w->runs[n - 1].rgb == pixels[i]) {
			w->runs[n - 1].count++;
		} else {
			w->runs[n].count = 1;
			w->runs[n++].rgb = pixels[i];
		}
	}
	memset(&c, 0, sizeof c);
	c.op = META_ROW;
	c.runs = w->runs;
	c.nruns = n;
	return meta_write(w, &c);
}

int meta_comment(meta_writer_t *w, const char *text)
{
	meta_cmd_t c;
	memset(&c, 0, sizeof c);
	c.op = META_COMMENT;
	c.str = text ? text : "";
	c.len = strlen(c.str);
	return meta_write(w, &c);
}
