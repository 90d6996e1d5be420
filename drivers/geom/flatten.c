/* flatten.c: growable paths and the flattening of arcs and circles into chords (spec §5.4). */
#include <stdlib.h>
#include "util/grow.h"
#include "geom/scan_int.h"

/* p->open: 0 = no current point, 1 = last subpath open, 2 = last subpath closed (the current
 * point is its start; a draw begins a new subpath there). */

void scan_path_reset(scan_path_t *p)
{
	p->npts = 0;
	p->nsubs = 0;
	p->open = 0;
}

void scan_path_free(scan_path_t *p)
{
	free(p->pts);
	free(p->subs);
	p->pts = NULL;
	p->subs = NULL;
	p->npts = p->cappts = p->nsubs = p->capsubs = 0;
	p->open = 0;
}

static int push_pt(scan_path_t *p, int64_t x, int64_t y)
{
	if (dev_grow((void **)&p->pts, &p->cappts, p->npts + 1, sizeof *p->pts, 256))
		return META_ENOMEM;
	p->pts[p->npts].x = x;
	p->pts[p->npts].y = y;
	p->npts++;
	return 0;
}

int scan_path_move(scan_path_t *p, int64_t x, int64_t y)
{
	if (dev_grow((void **)&p->subs, &p->capsubs, p->nsubs + 1, sizeof *p->subs, 32))
		return META_ENOMEM;
	if (push_pt(p, x, y))
		return META_ENOMEM;
	scan_subpath_t *s = &p->subs[p->nsubs++];
	s->start = p->npts - 1;
	s->n = 1;
	s->closed = 0;
	p->open = 1;
	return 0;
}

int scan_path_draw(scan_path_t *p, int64_t x, int64_t y)
{
	if (p->open == 0)
		return META_ESTATE;
	if (p->open == 2) {
		scan_pt_t st = p->pts[p->subs[p->nsubs - 1].start];
		if (scan_path_move(p, st.x, st.y))
			return META_ENOMEM;
	}
	if (push_pt(p, x, y))
		return META_ENOMEM;
	p->subs[p->nsubs - 1].n++;
	return 0;
}

int scan_path_close(scan_path_t *p)
{
	if (p->open == 1) {
		p->subs[p->nsubs - 1].closed = 1;
		p->open = 2;
	}
	return 0;
}

int scan_path_has_current(const scan_path_t *p)
{
	return p->open != 0;
}

int scan_circle_chords(int64_t r)
{
	return meta_circle_chords(r);   /* §5.4: one formula, shared with the reader's limit check */
}

static void arc_point(int64_t cx, int64_t cy, int64_t r, int64_t start, int64_t sweep, int64_t k,
		int64_t n, int64_t *x, int64_t *y)
{
	double th = ((double)start * (double)n + (double)sweep * (double)k) / ((double)n * 180000.0) * M_PI;
	*x = cx + scan_round((double)r * cos(th));
	*y = cy + scan_round((double)r * sin(th));
}

int scan_path_arc(scan_path_t *p, int64_t cx, int64_t cy, int64_t r, int64_t start, int64_t sweep)
{
	return scan_path_arc_res(p, cx, cy, r, start, sweep, r);
}

int scan_path_arc_res(scan_path_t *p, int64_t cx, int64_t cy, int64_t r, int64_t start, int64_t sweep,
		int64_t rchord)
{
	int64_t m = scan_circle_chords(rchord), as = sweep < 0 ? -sweep : sweep;
	int64_t n = (as * m + 359999) / 360000;
	if (n < 1)
		n = 1;
	for (int64_t k = 0; k <= n; k++) {
		int64_t x, y;
		arc_point(cx, cy, r, start, sweep, k, n, &x, &y);
		int rc = (k == 0 && !p->open) ? scan_path_move(p, x, y) : scan_path_draw(p, x, y);
		if (rc)
			return rc;
	}
	return 0;
}

int scan_path_circle(scan_path_t *p, int64_t cx, int64_t cy, int64_t r)
{
	return scan_path_circle_res(p, cx, cy, r, r);
}

int scan_path_circle_res(scan_path_t *p, int64_t cx, int64_t cy, int64_t r, int64_t rchord)
{
	int64_t m = scan_circle_chords(rchord);
	for (int64_t k = 0; k < m; k++) {
		int64_t x, y;
		arc_point(cx, cy, r, 0, 360000, k, m, &x, &y);
		int rc = k == 0 ? scan_path_move(p, x, y) : scan_path_draw(p, x, y);
		if (rc)
			return rc;
	}
	p->subs[p->nsubs - 1].closed = 1;
	p->open = 0;
	return 0;
}

int scan_path_bbox(const scan_path_t *p, int64_t *x0, int64_t *y0, int64_t *x1, int64_t *y1)
{
	if (p->npts == 0)
		return 0;
	int64_t a = p->pts[0].x, b = p->pts[0].y, c = a, d = b;
	for (size_t k = 1; k < p->npts; k++) {
		const scan_pt_t *q = &p->pts[k];
		if (q->x < a) a = q->x;
		if (q->x > c) c = q->x;
		if (q->y < b) b = q->y;
		if (q->y > d) d = q->y;
	}
	*x0 = a; *y0 = b; *x1 = c; *y1 = d;
	return 1;
}
