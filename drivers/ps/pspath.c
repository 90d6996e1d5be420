/* pspath.c: the PostScript device's paths and graphics state as compact tokens. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "util/grow.h"
#include "ps/ps_int.h"

/* Colours as 8-bit values, exactly: RGB as a hex string <rrggbb> K, grey as an integer G. */
void psp_colour(ps_t *s, meta_rgb_t c)
{
	char b[16];
	if (s->known && s->colour == c)
		return;
	if (s->p.grey) {
		psd_int(&s->p, psd_luma(c));
		psd_tok(&s->p, "G");
	} else {
		snprintf(b, sizeof b, "<%06x>", (unsigned)c & 0xffffff);
		psd_tok(&s->p, b);
		psd_tok(&s->p, "K");
	}
	s->colour = c;
}

void psp_line(ps_t *s, const dev_state_t *st)
{
	int64_t w = st->width > 1000 ? st->width : 1000;
	if (!s->known || s->width != w) {
		psd_int(&s->p, psd_grid(w));
		psd_tok(&s->p, "W");
		s->width = w;
	}
	if (!s->known || s->cap != st->cap) {
		psd_int(&s->p, st->cap);
		psd_tok(&s->p, "J");
		s->cap = st->cap;
	}
	if (!s->known || s->join != st->join) {
		psd_int(&s->p, st->join);
		psd_tok(&s->p, "j");
		s->join = st->join;
	}
	if (!s->known || s->miter != st->miter_limit) {
		psd_sep(&s->p);
		dev_w_fix(&s->p.out, st->miter_limit);
		s->p.col += 6;
		psd_tok(&s->p, "X");
		s->miter = st->miter_limit;
	}
	if (!s->known || s->ndash != st->ndash || memcmp(s->dash, st->dash, st->ndash * sizeof st->dash[0])) {
		psd_tok(&s->p, "[");
		for (size_t k = 0; k < st->ndash; k++) {
			psd_sep(&s->p);
			dev_w_real(&s->p.out, (double)st->dash[k] * PSD_GRID / 1000, 2);
			s->p.col += 6;
		}
		psd_tok(&s->p, "] 0 setdash");
		s->ndash = st->ndash;
		memcpy(s->dash, st->dash, st->ndash * sizeof st->dash[0]);
	}
}

/* ---- paths: absolute moves, relative integer draws in reversed chunks ---- */

/* A draw into the pending run, less what draws nothing (as pdfpath.c's drop_idle): a draw of no
 * length after another is dropped, and one that goes straight on from the draw before joins it
 * (contour maps: a fifth of their draws). The run's first draw stays even at no length, so that a
 * dot keeps its caps, until a draw with a length replaces it. */
static int push_draw(ps_t *s, long long dx, long long dy)
{
	if (s->ndx >= 2) {
		long long *u = &s->dx[s->ndx - 2];
		if (dx == 0 && dy == 0)
			return 0;
		if ((u[0] == 0 && u[1] == 0) || psd_straight(u[0], u[1], dx, dy)) {
			u[0] += dx;
			u[1] += dy;
			return 0;
		}
	}
	if (dev_grow((void **)&s->dx, &s->capdx, s->ndx + 2, sizeof *s->dx, 256))
		return dev_fail(s->p.dev, META_ENOMEM, "out of memory");
	s->dx[s->ndx++] = dx;
	s->dx[s->ndx++] = dy;
	return 0;
}

/* In a compressed (level 3) page body, k draws from pair `at` as one binary token: an encoded
 * number string of 16-bit integers (PLRM 3.14.5: 149, representation 32, count, big-endian
 * values) that H unpacks with aload. Ghostscript scans it without reading decimal text (workload
 * c: 7% less of its time) and it compresses better. 1 when written, 0 when a value does not
 * fit in 16 bits. */
static int binary_chunk(ps_t *s, size_t at, size_t k)
{
	uint8_t b[4 + 4 * PSP_CHUNK], *q = b + 4;
	for (size_t i = at + k; i-- > at;)
		for (int c = 0; c < 2; c++) {
			long long v = s->dx[2 * i + c];
			if (v < -32768 || v > 32767)
				return 0;
			uint16_t u = (uint16_t)(int16_t)v;
			*q++ = (uint8_t)(u >> 8);
			*q++ = (uint8_t)u;
		}
	b[0] = 149;
	b[1] = 32;
	b[2] = (uint8_t)(2 * k >> 8);
	b[3] = (uint8_t)(2 * k);
	psd_sep(&s->p);
	dev_w_write(&s->p.out, b, (size_t)(q - b));
	s->p.col += 8;
	psd_tok(&s->p, "H");
	return 1;
}

static void flush_draws(ps_t *s)
{
	size_t n = s->ndx / 2;
	for (size_t at = 0; at < n;) {
		size_t k = n - at > PSP_CHUNK ? PSP_CHUNK : n - at;
		if (k < 3) {
			for (size_t i = at; i < at + k; i++) {
				psd_int(&s->p, s->dx[2 * i]);
				psd_int(&s->p, s->dx[2 * i + 1]);
				psd_tok(&s->p, "l");
			}
		} else if (!s->packed || !binary_chunk(s, at, k)) {
			for (size_t i = at + k; i-- > at;) {
				psd_int(&s->p, s->dx[2 * i]);
				psd_int(&s->p, s->dx[2 * i + 1]);
			}
			psd_int(&s->p, (long long)k);
			psd_tok(&s->p, "L");
		}
		at += k;
	}
	s->ndx = 0;
}

/* The path walker's position: the last grid point, when the interpreter's current point is
 * exactly on it (not after an arc). */
typedef struct {
	long long x, y, sx, sy;
	int on_grid, start_on_grid, cur;   /* cur: the meta path has a current point */
} walk_t;

static void move_abs(ps_t *s, walk_t *w, long long x, long long y, const char *op)
{
	flush_draws(s);
	psd_int(&s->p, x);
	psd_int(&s->p, y);
	psd_tok(&s->p, op);
	w->x = x, w->y = y;
	w->on_grid = 1;
}

static int draw_to(ps_t *s, walk_t *w, long long x, long long y)
{
	if (!w->on_grid) {
		move_abs(s, w, x, y, "D");
		return 0;
	}
	int rc = push_draw(s, x - w->x, y - w->y);
	w->x = x, w->y = y;
	return rc;
}

static void arc_start(ps_t *s, const dev_elem_t *e)
{
	double a = e->f[3] / 180000.0 * M_PI;
	psd_sep(&s->p);
	dev_w_real(&s->p.out, (e->f[0] + e->f[2] * cos(a)) * PSD_GRID / 1000.0, 2);
	psd_sep(&s->p);
	dev_w_real(&s->p.out, (e->f[1] + e->f[2] * sin(a)) * PSD_GRID / 1000.0, 2);
	s->p.col += 20;
	psd_tok(&s->p, "M");
}

static int path_elems(ps_t *s, const dev_path_t *dp, int fill)
{
	walk_t w = { 0, 0, 0, 0, 0, 0, 0 };
	int ps_cur = 0;     /* the interpreter has a current point */
	for (size_t k = 0; k < dp->nelems; k++) {
		const dev_elem_t *e = &dp->elems[k];
		long long x = psd_grid(e->f[0]), y = psd_grid(e->f[1]);
		switch (e->op) {
		case META_MOVE:
			move_abs(s, &w, x, y, "M");
			w.sx = x, w.sy = y;
			w.start_on_grid = 1;
			w.cur = ps_cur = 1;
			break;
		case META_DRAW:
			if (draw_to(s, &w, x, y))
				return META_ENOMEM;
			break;
		case META_ARC:
			flush_draws(s);
			if (!w.cur && ps_cur)
				arc_start(s, e);
			if (!w.cur)
				w.start_on_grid = 0;
			psd_int(&s->p, x);
			psd_int(&s->p, y);
			psd_int(&s->p, psd_grid(e->f[2]) > 0 ? psd_grid(e->f[2]) : 1);
			psd_sep(&s->p);
			dev_w_fix(&s->p.out, e->f[3]);
			psd_sep(&s->p);
			dev_w_fix(&s->p.out, (long long)e->f[3] + e->f[4]);
			s->p.col += 16;
			psd_tok(&s->p, e->f[4] >= 0 ? "A" : "N");
			w.on_grid = 0;
			w.cur = ps_cur = 1;
			break;
		case META_CIRCLE:
			flush_draws(s);
			psd_int(&s->p, x);
			psd_int(&s->p, y);
			psd_int(&s->p, psd_grid(e->f[2]) > 0 ? psd_grid(e->f[2]) : 1);
			psd_tok(&s->p, "C");
			w.on_grid = 0;
			w.cur = 0;
			ps_cur = 1;
			break;
		case META_CLOSE:
			flush_draws(s);
			/* fill closes every subpath itself: Z only where a draw or arc goes on from it */
			if (!fill || (k + 1 < dp->nelems && (dp->elems[k + 1].op == META_DRAW || dp->elems[k + 1].op == META_ARC)))
				psd_tok(&s->p, "Z");
			w.on_grid = w.start_on_grid;
			w.x = w.sx, w.y = w.sy;
			break;
		default:
			break;
		}
	}
	flush_draws(s);
	return 0;
}

static int path_flat(ps_t *s, const scan_path_t *f, int fill)
{
	walk_t w = { 0, 0, 0, 0, 0, 0, 0 };
	for (size_t k = 0; k < f->nsubs; k++) {
		const scan_pt_t *q = f->pts + f->subs[k].start;
		size_t n = f->subs[k].n;
		if (!n)
			continue;
		move_abs(s, &w, psd_grid(q[0].x), psd_grid(q[0].y), "M");
		for (size_t i = 1; i < n; i++)
			if (draw_to(s, &w, psd_grid(q[i].x), psd_grid(q[i].y)))
				return META_ENOMEM;
		flush_draws(s);
		if (f->subs[k].closed && !fill)
			psd_tok(&s->p, "Z");
	}
	return 0;
}

int psp_path(ps_t *s, const dev_path_t *dp, int fill)
{
	return psd_native(dp) ? path_elems(s, dp, fill) : path_flat(s, dp->flat, fill);
}

