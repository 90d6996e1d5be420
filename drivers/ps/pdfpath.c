/* pdfpath.c: the PDF device's content streams and paths: graphics state, path origins (fills
 * chained by cm inside q ... Q groups), and points as text or as fixed-width samples under the
 * Flate filter's TIFF predictor. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "util/grow.h"
#include "ps/pdf_int.h"

#define ROWS_MIN 256       /* points a lattice path needs to open a predicted stream */
#define TEXT_RUN 1024      /* points of text paths in a predicted stream before a plain one reopens */

/* ---- tokens (psdev.c's writer: one line per path, never wrapped inside one) ---- */

static void tok(pdf_t *s, const char *t)
{
	psd_tok(&s->p, t);
}

static void tok_int(pdf_t *s, long long v)
{
	psd_int(&s->p, v);
}

/* A colour component v/255 with three decimals, shortest: 0, 1, .502 */
static void tok_unit(pdf_t *s, unsigned v)
{
	char b[16];
	psd_unit(v, b, sizeof b);
	tok(s, b);
}

static void colour(pdf_t *s, meta_rgb_t c, int fill)
{
	if (fill ? s->g.have_fill && s->g.fill_rgb == c : s->g.have_stroke && s->g.stroke_rgb == c)
		return;
	if (s->p.grey) {
		tok_unit(s, psd_luma(c));
		tok(s, fill ? "g" : "G");
	} else {
		tok_unit(s, c >> 16 & 255);
		tok_unit(s, c >> 8 & 255);
		tok_unit(s, c & 255);
		tok(s, fill ? "rg" : "RG");
	}
	if (fill)
		s->g.fill_rgb = c, s->g.have_fill = 1;
	else
		s->g.stroke_rgb = c, s->g.have_stroke = 1;
}

static void line_state(pdf_t *s, const dev_state_t *st)
{
	int64_t w = st->width > 1000 ? st->width : 1000;
	if (!s->g.known || s->g.width != w) {
		tok_int(s, psd_grid(w));
		tok(s, "w");
	}
	if (!s->g.known || s->g.cap != st->cap) {
		tok_int(s, st->cap);
		tok(s, "J");
	}
	if (!s->g.known || s->g.join != st->join) {
		tok_int(s, st->join);
		tok(s, "j");
	}
	if (!s->g.known || s->g.miter != st->miter_limit) {
		psd_sep(&s->p);
		dev_w_fix(&s->p.out, st->miter_limit);
		s->p.col += 6;
		tok(s, "M");
	}
	if (!s->g.known || s->g.ndash != st->ndash || memcmp(s->g.dash, st->dash, st->ndash * sizeof st->dash[0])) {
		tok(s, "[");
		for (size_t k = 0; k < st->ndash; k++) {
			psd_sep(&s->p);
			dev_w_real(&s->p.out, (double)st->dash[k] * PSD_GRID / 1000, 2);
			s->p.col += 6;
		}
		tok(s, "] 0 d");
	}
	s->g.width = w;
	s->g.cap = st->cap;
	s->g.join = st->join;
	s->g.miter = st->miter_limit;
	s->g.ndash = st->ndash;
	memcpy(s->g.dash, st->dash, st->ndash * sizeof st->dash[0]);
	s->g.known = 1;
}

/* ---- paths ---- */

static void point(pdf_t *s, double x, double y, const char *op)
{
	tok_int(s, llround(x * PSD_GRID / 1000) - s->org_x);
	tok_int(s, llround(y * PSD_GRID / 1000) - s->org_y);
	if (op)
		tok(s, op);
}

/* An arc as cubic Bezier pieces of at most 90 degrees; joins or starts at its first point. */
static void arc(pdf_t *s, const dev_elem_t *e, int cur, int circle)
{
	double cx = e->f[0], cy = e->f[1], r = e->f[2];
	double a0 = circle ? 0 : e->f[3] / 180000.0 * M_PI;
	double sw = circle ? 2 * M_PI : e->f[4] / 180000.0 * M_PI;
	int n = (int)ceil(fabs(sw) / (M_PI / 2) - 1e-9);
	if (n < 1)
		n = 1;
	point(s, cx + r * cos(a0), cy + r * sin(a0), cur ? "l" : "m");
	double t = sw / n, k = 4.0 / 3.0 * tan(t / 4);
	for (int i = 0; i < n; i++) {
		double b0 = a0 + t * i, b1 = b0 + t;
		double x0 = cos(b0), y0 = sin(b0), x1 = cos(b1), y1 = sin(b1);
		point(s, cx + r * (x0 - k * y0), cy + r * (y0 + k * x0), NULL);
		point(s, cx + r * (x1 + k * y1), cy + r * (y1 - k * x1), NULL);
		point(s, cx + r * x1, cy + r * y1, "c");
	}
	if (circle)
		tok(s, "h");
}

/* The path's origin: its lower left grid point (x0, y0), moved down to the phase that most of its
 * coordinates share modulo ORG_MOD when there is one (a contour on a 2-pixel lattice, shapes on
 * whole pixels), so that those coordinates become round numbers (contours: 7% smaller). */
#define ORG_MOD 20
static void origin(pdf_t *s, const scan_path_t *f, long long x0, long long y0)
{
	size_t hx[ORG_MOD] = { 0 }, hy[ORG_MOD] = { 0 }, n = 0;
	for (size_t k = 0; k < f->nsubs; k++) {
		const scan_pt_t *q = f->pts + f->subs[k].start;
		for (size_t i = 0; i < f->subs[k].n; i++, n++) {
			long long x = psd_grid(q[i].x) - x0, y = psd_grid(q[i].y) - y0;   /* >= 0 */
			hx[x % ORG_MOD]++;
			hy[y % ORG_MOD]++;
		}
	}
	int bx = 0, by = 0;
	for (int r = 1; r < ORG_MOD; r++) {
		if (hx[r] > hx[bx])
			bx = r;
		if (hy[r] > hy[by])
			by = r;
	}
	/* a phase that a quarter of the points, and at least four, share (at random: a twentieth;
	 * two of a triangle's three points by chance one time in seven) */
	s->org_x = x0 + (bx && 4 * hx[bx] >= n && hx[bx] >= 4 ? bx - ORG_MOD : 0);
	s->org_y = y0 + (by && 4 * hy[by] >= n && hy[by] >= 4 ? by - ORG_MOD : 0);
}

void pdf_fill_colour(pdf_t *s, meta_rgb_t c)
{
	colour(s, c, 1);
}

void pdf_reset_state(pdf_t *s)
{
	s->g.known = s->g.have_fill = s->g.have_stroke = 0;
	s->group = 0;
}

void pdf_end_group(pdf_t *s)
{
	if (!s->group)
		return;
	tok(s, "Q");
	s->g = s->saved;
	s->group = 0;
}

/* ---- the points of a path without arcs ---- */

static int push(pdf_t *s, double x, double y, char op)
{
	if (dev_grow((void **)&s->pts, &s->cappts, s->npts + 1, sizeof *s->pts, 256))
		return dev_fail(s->p.dev, META_ENOMEM, "out of memory");
	/* as point() rounds */
	s->pts[s->npts].x = op == 'h' ? 0 : llround(x * PSD_GRID / 1000) - s->org_x;
	s->pts[s->npts].y = op == 'h' ? 0 : llround(y * PSD_GRID / 1000) - s->org_y;
	s->pts[s->npts++].op = op;
	return 0;
}

/* The path's points relative to its origin into s->pts, with the closepaths that the paint
 * needs (f closes every subpath itself: h only where a draw goes on from it). 1, or 0 when the
 * path has arcs (it is then written from its elements), or <0. */
static int collect(pdf_t *s, const dev_path_t *dp, int fill)
{
	int rc = 0;
	s->npts = 0;
	if (!psd_native(dp)) {
		const scan_path_t *f = dp->flat;
		for (size_t k = 0; k < f->nsubs && !rc; k++) {
			const scan_pt_t *q = f->pts + f->subs[k].start;
			for (size_t i = 0; i < f->subs[k].n && !rc; i++)
				rc = push(s, (double)q[i].x, (double)q[i].y, i ? 'l' : 'm');
			if (!rc && f->subs[k].closed && f->subs[k].n && !fill)
				rc = push(s, 0, 0, 'h');
		}
		return rc ? rc : 1;
	}
	for (size_t k = 0; k < dp->nelems; k++)
		if (dp->elems[k].op == META_ARC || dp->elems[k].op == META_CIRCLE)
			return 0;
	for (size_t k = 0; k < dp->nelems && !rc; k++) {
		const dev_elem_t *e = &dp->elems[k];
		if (e->op == META_MOVE || e->op == META_DRAW)
			rc = push(s, (double)e->f[0], (double)e->f[1], e->op == META_MOVE ? 'm' : 'l');
		else if (e->op == META_CLOSE && (!fill || (k + 1 < dp->nelems && dp->elems[k + 1].op == META_DRAW)))
			rc = push(s, 0, 0, 'h');
	}
	return rc ? rc : 1;
}

/* Drops the points that draw nothing on the grid: a point equal to the one before it, and a point
 * on the straight way from the one before it to the one after (contour maps: 20% of their
 * points, where marching squares meet the grid). The stroke and the fill are the same shapes:
 * a dropped point had no length and turned no corner, and dashes measure the same length. A
 * subpath left with no segment keeps one of no length, which round and square caps draw as a dot;
 * a draw that turns back along its way is kept. */
static void drop_idle(pdf_t *s)
{
	size_t w = 0, run = 0;       /* run: points of the current subpath written so far */
	int dropped = 0;
	for (size_t k = 0; k <= s->npts; k++) {
		const pdf_pt_t *q = k < s->npts ? &s->pts[k] : NULL;
		if (q && q->op == 'l' && run >= 1) {
			pdf_pt_t *b = &s->pts[w - 1];
			if (q->x == b->x && q->y == b->y) {
				dropped = 1;
				continue;
			}
			const pdf_pt_t *a = run >= 2 && b->op == 'l' ? &s->pts[w - 2] : NULL;
			if (a && psd_straight(b->x - a->x, b->y - a->y, q->x - b->x, q->y - b->y)) {
				*b = *q;
				continue;
			}
		}
		if ((!q || q->op != 'l') && run == 1 && dropped) {
			s->pts[w] = s->pts[w - 1];   /* room: a point was dropped */
			s->pts[w++].op = 'l';
		}
		if (!q)
			break;
		if (q->op != 'l') {
			run = q->op == 'm';
			dropped = 0;
		} else {
			run += run > 0;
		}
		s->pts[w++] = *q;
	}
	s->npts = w;
}

/* digits (and sign) of v */
static size_t digits(long long v)
{
	size_t n = v < 0 ? 2 : 1;
	for (long long a = v < 0 ? -v : v; a >= 10; a /= 10)
		n++;
	return n;
}

/* v (-999 ... 9999) right-aligned in the four columns at r */
static void field(char *r, long long v)
{
	char *p = r + 4;
	unsigned long long a = v < 0 ? 0ULL - (unsigned long long)v : (unsigned long long)v;
	memset(r, ' ', 4);
	do {
		*--p = (char)('0' + a % 10);
		a /= 10;
	} while (a && p > r);
	if (v < 0 && p > r)
		*--p = '-';
}

/* the bytes of a four-column field of v that differ from those of u */
static size_t moved(long long u, long long v)
{
	char a[4], b[4];
	size_t n = 0;
	field(a, u);
	field(b, v);
	for (int k = 0; k < 4; k++)
		n += a[k] != b[k];
	return n;
}

/* 1 when the points profit from predicted samples: every coordinate fits a sample's four
 * columns, at least half the points lie on the origin's 2-pixel lattice in x or y
 * (marching-squares contours, after origin() found their phase), and the bytes that differ from
 * the point before are fewer than half the path's text (contours: 1/4 to 2/5). A lattice
 * point's difference keeps little more than the digits that moved, where text repeats every
 * digit; random walks and polygons (a tenth of their points on a lattice, 2/5 to 1/2 of their
 * text left) are smaller as text: predicted, workload a would grow by 10%. *n: the points. */
static int rows_pay(const pdf_t *s, size_t *n)
{
	size_t on = 0, text = 0, up = 0;
	const pdf_pt_t *last = NULL;
	*n = 0;
	for (size_t k = 0; k < s->npts; k++) {
		const pdf_pt_t *q = &s->pts[k];
		if (q->op == 'h')
			continue;
		if (q->x < -999 || q->x > 9999 || q->y < -999 || q->y > 9999)
			return 0;
		++*n;
		on += q->x % ORG_MOD == 0 || q->y % ORG_MOD == 0;
	}
	if (!*n || 2 * on < *n)
		return 0;
	for (size_t k = 0; k < s->npts; k++) {
		const pdf_pt_t *q = &s->pts[k];
		if (q->op == 'h') {
			last = NULL;
			continue;
		}
		text += digits(q->x) + digits(q->y) + 3;
		up += last ? moved(last->x, q->x) + moved(last->y, q->y) + (last->op != q->op) : 12;
		last = q;
	}
	return 2 * up < text;
}

static void reverse(pdf_pt_t *p, size_t n)
{
	for (size_t i = 0, j = n; i + 1 < j; i++, j--) {
		pdf_pt_t t = p[i];
		p[i] = p[j - 1];
		p[j - 1] = t;
	}
}

/* A fill of one subpath (f closes it) is the same polygon from any of its vertices: start it at
 * its lowest (then leftmost) vertex and put the origin there, so that its first point is 0 0 and
 * every y is positive (random polygons: 4.6% smaller than from the box's corner). Only where
 * origin() found no common phase: a lattice shape keeps its round numbers. */
static void lowest_first(pdf_t *s)
{
	size_t k = 0;
	if (s->npts < 3 || s->pts[0].op != 'm')
		return;
	for (size_t i = 1; i < s->npts; i++) {
		const pdf_pt_t *q = &s->pts[i];
		if (q->op != 'l')
			return;
		if (q->y < s->pts[k].y || (q->y == s->pts[k].y && q->x < s->pts[k].x))
			k = i;
	}
	long long dx = s->pts[k].x, dy = s->pts[k].y;
	/* rotate left by k: reverse [0, k), [k, n), then the whole */
	reverse(s->pts, k);
	reverse(s->pts + k, s->npts - k);
	reverse(s->pts, s->npts);
	for (size_t i = 0; i < s->npts; i++) {
		s->pts[i].x -= dx;
		s->pts[i].y -= dy;
		s->pts[i].op = i ? 'l' : 'm';
	}
	s->org_x += dx;
	s->org_y += dy;
}

static void text_points(pdf_t *s)
{
	static const char *ops[] = { "m", "l" };
	for (size_t k = 0; k < s->npts; k++) {
		const pdf_pt_t *q = &s->pts[k];
		if (q->op == 'h') {
			tok(s, "h");
			continue;
		}
		tok_int(s, q->x);
		tok_int(s, q->y);
		tok(s, ops[q->op == 'l']);
	}
}

/* The points as predictor samples "xxxx yyyy l\n", each less the one before it (the first of a
 * path less the padded head before it); a closepath is a sample "h". */
static void row_points(pdf_t *s)
{
	dev_writer_t *o = &s->p.out;
	dev_w_write(o, "\n", 1);   /* ends the head even where it fills its sample exactly */
	pse_rows_pad(o, ' ');
	for (size_t k = 0; k < s->npts; k++) {
		const pdf_pt_t *q = &s->pts[k];
		char r[PDF_ROW];
		if (q->op == 'h') {
			dev_w_write(o, "h", 1);
			pse_rows_pad(o, ' ');
			continue;
		}
		field(r, q->x);
		r[4] = ' ';
		field(r + 5, q->y);
		r[9] = ' ';
		r[10] = q->op;
		r[11] = '\n';
		dev_w_write(o, r, PDF_ROW);
	}
	s->p.col = 0;
}

/* A path with arcs, from its elements. */
static void elem_points(pdf_t *s, const dev_path_t *dp, int fill)
{
	int cur = 0;
	for (size_t k = 0; k < dp->nelems; k++) {
		const dev_elem_t *e = &dp->elems[k];
		switch (e->op) {
		case META_MOVE: point(s, e->f[0], e->f[1], "m"); cur = 1; break;
		case META_DRAW: point(s, e->f[0], e->f[1], "l"); break;
		case META_ARC: arc(s, e, cur, 0); cur = 1; break;
		case META_CIRCLE: arc(s, e, 0, 1); cur = 0; break;
		case META_CLOSE:
			if (!fill || (k + 1 < dp->nelems && (dp->elems[k + 1].op == META_DRAW || dp->elems[k + 1].op == META_ARC)))
				tok(s, "h");
			break;
		default: break;
		}
	}
}

static int switch_stream(pdf_t *s, int rows)
{
	int rc = pdf_close_stream(s);
	if (!rc && (rc = pdf_open_stream(s, rows)))
		rc = dev_fail(s->p.dev, META_ENOMEM, "out of memory");
	s->packed_run = 0;
	return rc;
}

/* The path with its origin at its lower left grid point: PDF has no relative path operators,
 * and small positive numbers compress better (workload a: 28% smaller). A stroke is written in
 * q 1 0 0 1 X Y cm ... S Q. Fills chain their origins: the first fill of a group opens q and moves
 * the origin, each next one moves it on from the one before (1 0 0 1 DX DY cm), without a q ... Q
 * of its own, which costs Ghostscript 6% of its instructions on random polygons; a group ends
 * after PDF_GROUP fills, so that interpreters that multiply matrices in single precision never
 * drift by more than that many roundings, and before anything in page coordinates. Strokes keep
 * their own q ... Q: their line state would be undone at a group's end and written again, and
 * stroked paths are long (walks, contours), where the pair costs nothing measurable. */
int pdf_paint(pdf_t *s, const dev_path_t *dp, const dev_state_t *st, int fill)
{
	int64_t x0, y0, x1, y1;
	size_t n = 0;
	s->org_x = s->org_y = 0;
	if (scan_path_bbox(dp->flat, &x0, &y0, &x1, &y1))
		origin(s, dp->flat, psd_grid(x0), psd_grid(y0));
	int corner = s->org_x == psd_grid(x0) && s->org_y == psd_grid(y0);
	int pts = collect(s, dp, fill), rc = 0;
	if (pts < 0)
		return pts;
	if (pts)
		drop_idle(s);
	if (pts && fill && corner)
		lowest_first(s);
	int rec = pts && rows_pay(s, &n);
	if (rec && !s->rows && n >= ROWS_MIN)
		rc = switch_stream(s, 1);
	else if (!rec && s->rows && s->packed_run >= TEXT_RUN)
		rc = switch_stream(s, 0);
	if (rc)
		return rc;
	rec = rec && s->rows;
	/* an origin far off the page (Ghostscript's single-precision matrix would lose the page's
	 * fractions in its translation) stands alone in a group of its own */
	unsigned side = s->p.page.width > s->p.page.height ? s->p.page.width : s->p.page.height;
	long long lim = 4LL * side * PSD_GRID;
	int far = s->org_x < -lim || s->org_x > lim || s->org_y < -lim || s->org_y > lim;
	if (!fill || s->group >= PDF_GROUP || (s->group && (far || s->group_far)))
		pdf_end_group(s);
	s->group_far = far;
	colour(s, st->colour, fill);
	if (!fill)
		line_state(s, st);
	if (!fill || !s->group) {
		tok(s, "q 1 0 0 1");
		tok_int(s, s->org_x);
		tok_int(s, s->org_y);
		if (fill)
			s->saved = s->g;
	} else {
		tok(s, "1 0 0 1");
		tok_int(s, s->org_x - s->gx);
		tok_int(s, s->org_y - s->gy);
	}
	tok(s, "cm");
	if (fill) {
		s->group++;
		s->gx = s->org_x;
		s->gy = s->org_y;
	}
	if (rec) {
		row_points(s);
		s->packed_run = 0;
	} else {
		if (pts)
			text_points(s);
		else
			elem_points(s, dp, fill);
		if (s->rows)
			s->packed_run += pts ? s->npts : dp->nelems;
	}
	tok(s, !fill ? "S Q" : st->rule == META_RULE_EVEN_ODD ? "f*" : "f");
	psd_newline(&s->p);
	return 0;
}

/* ---- content streams ---- */

int pdf_open_stream(pdf_t *s, int rows)
{
	unsigned n = pdf_new_obj(s);
	if (!n || pdf_list_add(&s->p, &s->contents, n) || !pdf_new_obj(s))
		return META_ENOMEM;
	pdf_begin_obj(s, n);
	dev_w_printf(&s->p.out, "<< /Length %u 0 R /Filter /FlateDecode", n + 1);
	if (rows)
		dev_w_printf(&s->p.out, " /DecodeParms << /Predictor 2 /Colors %d /Columns %d >>", PDF_ROW, PDF_COLUMNS);
	dev_w_puts(&s->p.out, " >>\nstream\n");
	s->stream_obj = n;
	s->stream_start = s->p.out.pos;
	s->p.col = 0;
	s->rows = rows;
	s->packed_run = 0;
	int rc = pse_deflate_begin(&s->p.out, 0, rows ? PSE_ROWS : PSE_TEXT);
	return rc || !rows ? rc : pse_rows_begin(&s->p.out, PDF_ROW, PDF_COLUMNS);
}

int pdf_close_stream(pdf_t *s)
{
	if (!s->stream_obj)
		return 0;
	pdf_end_group(s);
	psd_newline(&s->p);
	pse_rows_end(&s->p.out, ' ');   /* rows end whole */
	pse_deflate_end(&s->p.out, NULL);
	uint64_t len = s->p.out.pos - s->stream_start;
	dev_w_puts(&s->p.out, "\nendstream\nendobj\n");
	pdf_begin_obj(s, s->stream_obj + 1);
	dev_w_printf(&s->p.out, "%llu\nendobj\n", (unsigned long long)len);
	s->stream_obj = 0;
	return pdf_failed(s);
}
