/* stroke.c: wide lines as a union of convex pieces (spec §5.3): segments, joins, caps, dashes. */
#include <stdlib.h>
#include <string.h>
#include "geom/scan_int.h"

/* Everything one stroke call needs. */
typedef struct {
	scan_ctx_t *c;
	const scan_band_t *b;
	meta_rgb_t rgb;
	double h;              /* half width, thousandths */
	int64_t hr;            /* h rounded, for square dots */
	int cap, join;
	double limit2;
	double ext;            /* farthest a piece reaches from its path, thousandths */         /* miter limit squared (pixels/pixels) */
	scan_pt_t *disc;       /* disc offsets for radius h */
	size_t ndisc;
	scan_path_t *out;      /* scan_stroke_pieces: pieces are collected here, not painted */
	int rc;
} stroker_t;

/* Append the piece to s->out as a closed counter-clockwise contour (zero-area pieces, which
 * cover no pixel centre, are left out). */
static void collect(stroker_t *s, const scan_pt_t *q, size_t n)
{
	__int128 a2 = 0;
	for (size_t k = 0; k < n; k++) {
		const scan_pt_t *u = &q[k], *v = &q[k + 1 == n ? 0 : k + 1];
		a2 += (__int128)u->x * v->y - (__int128)v->x * u->y;
	}
	if (a2 == 0)
		return;
	for (size_t k = 0; k < n && s->rc == 0; k++) {
		const scan_pt_t *u = &q[a2 > 0 ? k : n - 1 - k];
		s->rc = k ? scan_path_draw(s->out, u->x, u->y) : scan_path_move(s->out, u->x, u->y);
	}
	if (s->rc == 0)
		s->rc = scan_path_close(s->out);
}

static void piece(stroker_t *s, const scan_pt_t *q, size_t n)
{
	if (s->rc == 0 && s->out)
		collect(s, q, n);
	else if (s->rc == 0)
		s->rc = scan_fill_piece(s->c, s->b, q, n, META_RULE_NON_ZERO, s->rgb, 0);
}

/* A piece that is convex by construction, whatever the rounding: parallelograms of segments,
 * rectangles of caps, triangles, discs (their chords' sagitta far exceeds the rounding). */
static void convex_piece(stroker_t *s, const scan_pt_t *q, size_t n)
{
	if (s->rc == 0 && s->out)
		collect(s, q, n);
	else if (s->rc == 0)
		s->rc = scan_fill_piece(s->c, s->b, q, n, META_RULE_NON_ZERO, s->rgb, 1);
}

/* Disc offsets: the §5.4 full circle of radius h, points (round(h cos t), round(h sin t)). */
static int make_disc(stroker_t *s)
{
	double rp = s->h / 1000.0;
	int m = 8;
	if (rp > 0.25) {
		double mm = ceil(2.0 * M_PI / acos(1.0 - 0.25 / rp));
		m = mm < 8 ? 8 : mm > 1e6 ? 1000000 : (int)mm;
	}
	s->disc = malloc((size_t)m * sizeof(scan_pt_t));
	if (!s->disc)
		return META_ENOMEM;
	for (int k = 0; k < m; k++) {
		double th = (0.0 * m + 360000.0 * k) / ((double)m * 180000.0) * M_PI;
		s->disc[k].x = scan_round(s->h * cos(th));
		s->disc[k].y = scan_round(s->h * sin(th));
	}
	s->ndisc = (size_t)m;
	return 0;
}

static void disc(stroker_t *s, scan_pt_t v)
{
	double r = s->h + 2.0;   /* the polygon lies within h (+ rounding) of v */
	if ((double)v.y + r < s->b->jlo * 1000.0 || (double)v.y - r > s->b->jhi * 1000.0 ||
			(double)v.x + r < 0 || (double)v.x - r > s->b->width * 1000.0)
		return;
	if (!s->disc && (s->rc = make_disc(s) ? META_ENOMEM : s->rc) != 0)   /* a success keeps an earlier failure */
		return;
	scan_path_t *pc = scan_ctx_piece(s->c);
	scan_path_reset(pc);
	for (size_t k = 0; k < s->ndisc; k++) {
		int rc = k ? scan_path_draw(pc, v.x + s->disc[k].x, v.y + s->disc[k].y)
			: scan_path_move(pc, v.x + s->disc[k].x, v.y + s->disc[k].y);
		if (rc) {
			s->rc = rc;
			return;
		}
	}
	convex_piece(s, pc->pts, pc->npts);
}

/* The rounded offset o = round(h * n) of segment direction (dx, dy), n = (-dy, dx)/len. */
static void offset(const stroker_t *s, int64_t dx, int64_t dy, scan_pt_t *o, double *ux, double *uy)
{
	double len = sqrt((double)dx * (double)dx + (double)dy * (double)dy);
	*ux = -(double)dy / len;
	*uy = (double)dx / len;
	o->x = scan_round(s->h * *ux);
	o->y = scan_round(s->h * *uy);
}

static void segment(stroker_t *s, scan_pt_t p, scan_pt_t q, scan_pt_t o)
{
	scan_pt_t v[4] = {
		{ p.x - o.x, p.y - o.y }, { q.x - o.x, q.y - o.y },
		{ q.x + o.x, q.y + o.y }, { p.x + o.x, p.y + o.y } };
	convex_piece(s, v, 4);
}

/* Join at v from segment (d1, o1, n1) into segment (d2, o2, n2). */
static void join(stroker_t *s, scan_pt_t v, scan_pt_t d1, scan_pt_t o1, double n1x, double n1y,
		scan_pt_t d2, scan_pt_t o2, double n2x, double n2y)
{
	__int128 cross = (__int128)d1.x * d2.y - (__int128)d1.y * d2.x;
	if (cross == 0) {
		__int128 dot = (__int128)d1.x * d2.x + (__int128)d1.y * d2.y;
		if (dot < 0 && s->join == META_JOIN_ROUND)
			disc(s, v);
		return;
	}
	if (s->join == META_JOIN_ROUND) {
		disc(s, v);
		return;
	}
	double sg = cross > 0 ? -1.0 : 1.0;   /* left turn: the outer side is the right one (-n) */
	int64_t g = cross > 0 ? -1 : 1;
	scan_pt_t a = { v.x + g * o1.x, v.y + g * o1.y }, b = { v.x + g * o2.x, v.y + g * o2.y };
	if (s->join == META_JOIN_MITER) {
		double u1x = sg * n1x, u1y = sg * n1y, u2x = sg * n2x, u2y = sg * n2y;
		double c = u1x * u2x + u1y * u2y;
		if ((1.0 + c) * s->limit2 >= 2.0) {
			scan_pt_t m = { v.x + scan_round(s->h * (u1x + u2x) / (1.0 + c)),
				v.y + scan_round(s->h * (u1y + u2y) / (1.0 + c)) };
			scan_pt_t q[4] = { v, a, m, b };
			piece(s, q, 4);
			return;
		}
	}
	scan_pt_t q[3] = { v, a, b };
	convex_piece(s, q, 3);
}

static void cap(stroker_t *s, scan_pt_t p, scan_pt_t o, int at_start)
{
	if (s->cap == META_CAP_ROUND) {
		disc(s, p);
	} else if (s->cap == META_CAP_SQUARE) {
		scan_pt_t e = { o.y, -o.x };
		if (at_start) {
			e.x = -e.x;
			e.y = -e.y;
		}
		scan_pt_t q[4] = { { p.x + o.x, p.y + o.y }, { p.x - o.x, p.y - o.y },
			{ p.x - o.x + e.x, p.y - o.y + e.y }, { p.x + o.x + e.x, p.y + o.y + e.y } };
		convex_piece(s, q, 4);
	}
}

static void dot(stroker_t *s, scan_pt_t v)
{
	if (s->cap == META_CAP_ROUND) {
		disc(s, v);
	} else if (s->cap == META_CAP_SQUARE) {
		scan_pt_t q[4] = { { v.x - s->hr, v.y - s->hr }, { v.x + s->hr, v.y - s->hr },
			{ v.x + s->hr, v.y + s->hr }, { v.x - s->hr, v.y + s->hr } };
		convex_piece(s, q, 4);
	}
}

/* 1 if the segment cannot reach the band's pixels (farther than the stroke's reach). */
static int far_segment(const stroker_t *s, scan_pt_t p, scan_pt_t q)
{
	double lo = s->b->jlo * 1000.0 - s->ext, hi = s->b->jhi * 1000.0 + s->ext;
	double right = s->b->width * 1000.0 + s->ext;
	return ((double)p.y < lo && (double)q.y < lo) || ((double)p.y > hi && (double)q.y > hi) ||
		((double)p.x < -s->ext && (double)q.x < -s->ext) || ((double)p.x > right && (double)q.x > right);
}

/* Stroke n points (consecutive duplicates allowed) as one subpath, solid. */
static void solid(stroker_t *s, const scan_pt_t *pts, size_t n, int closed)
{
	/* first and last distinct points */
	size_t first = 0, last = n - 1;
	if (closed)
		while (last > 0 && pts[last].x == pts[0].x && pts[last].y == pts[0].y)
			last--;
	size_t k = 1;
	while (k < n && pts[k].x == pts[0].x && pts[k].y == pts[0].y)
		k++;
	if (k >= n || (closed && last == 0)) {
		dot(s, pts[0]);
		return;
	}
	/* walk segments p -> q over distinct points; a segment out of reach of the band (far)
	 * makes no piece, nor do the joins and caps at its ends: they lie within s->ext of them */
	scan_pt_t prev_d = { 0, 0 }, prev_o = { 0, 0 }, first_d = { 0, 0 }, first_o = { 0, 0 };
	double pnx = 0, pny = 0, fnx = 0, fny = 0;
	int have_prev = 0, prev_far = 0, first_far = 0;
	scan_pt_t p = pts[first];
	size_t end = closed ? last + 1 : n;
	for (size_t i = 1; i <= end && s->rc == 0; i++) {
		scan_pt_t q = i < end ? pts[i] : pts[first];
		if (i == end && !closed)
			break;
		if (q.x == p.x && q.y == p.y)
			continue;
		scan_pt_t d = { q.x - p.x, q.y - p.y }, o = { 0, 0 };
		double nx = 0, ny = 0;
		int far = far_segment(s, p, q);
		if (!far) {
			offset(s, d.x, d.y, &o, &nx, &ny);
			segment(s, p, q, o);
		}
		if (have_prev) {
			if (!far && !prev_far)
				join(s, p, prev_d, prev_o, pnx, pny, d, o, nx, ny);
		} else {
			first_d = d; first_o = o; fnx = nx; fny = ny; first_far = far;
			if (!closed && !far)
				cap(s, p, o, 1);
		}
		have_prev = 1;
		prev_d = d; prev_o = o; pnx = nx; pny = ny; prev_far = far;
		p = q;
	}
	if (!have_prev)
		return;
	if (closed) {
		if (!prev_far && !first_far)
			join(s, pts[first], prev_d, prev_o, pnx, pny, first_d, first_o, fnx, fny);
	} else if (!prev_far) {
		cap(s, p, prev_o, 0);
	}
}

/* The dash walk's window: the part of p -> q within the stroke's reach of the band (clipped
 * to the reach box by Liang-Barsky, widened by a few thousandths for the rounding). */
static int reach_window(void *user, scan_pt_t p, scan_pt_t q, double len, double *ta, double *tb)
{
	const stroker_t *s = user;
	double lo[2] = { -s->ext - 16.0, s->b->jlo * 1000.0 - s->ext - 16.0 };
	double hi[2] = { s->b->width * 1000.0 + s->ext + 16.0, s->b->jhi * 1000.0 + s->ext + 16.0 };
	return scan_clip_window(lo, hi, p, q, len, ta, tb);
}

/* A finished dash piece: stroked solid and open (culled segment by segment). */
static int dash_piece(void *user, scan_path_t *dp)
{
	stroker_t *s = user;
	if (dp->nsubs && dp->subs[0].n >= 2)
		solid(s, dp->pts + dp->subs[0].start, dp->subs[0].n, 0);
	return s->rc;
}

/* Split the subpath into dash pieces, each stroked solid and open as soon as it ends; pieces
 * are made only where the band can see them (dash.c). */
static void dashed(stroker_t *s, const scan_style_t *st, const scan_pt_t *pts, size_t n, int closed)
{
	size_t same = 1;
	while (same < n && pts[same].x == pts[0].x && pts[same].y == pts[0].y)
		same++;
	if (same == n) {
		solid(s, pts, n, closed);   /* all points equal: the dot, as when solid */
		return;
	}
	scan_dasher_t w = { reach_window, dash_piece, s };
	int rc = scan_dash_walk(scan_ctx_dashed(s->c), st->dash, st->ndash, pts, n, closed, &w);
	if (rc && s->rc == 0)
		s->rc = rc;
}

/* The stroke into the band, or its pieces into out (then b is a band without pixels). */
static int stroke(scan_ctx_t *c, const scan_band_t *b, const scan_path_t *p, const scan_style_t *st,
		meta_rgb_t rgb, scan_path_t *out)
{
	stroker_t s = { 0 };
	s.out = out;
	s.c = c;
	s.b = b;
	s.rgb = rgb;
	s.h = (double)(st->width < 1000 ? 1000 : st->width) / 2.0;
	s.hr = scan_round(s.h);
	s.cap = st->cap;
	s.join = st->join;
	double lim = (double)st->miter_limit / 1000.0;
	s.limit2 = lim * lim;
	/* cull whole subpaths that cannot reach the band */
	double ext = s.h * (lim > 1.5 ? lim : 1.5) + 2000.0;
	s.ext = ext;
	double lo = (double)b->jlo * 1000.0 - ext, hi = (double)b->jhi * 1000.0 + ext;
	double right = (double)b->width * 1000.0 + ext;
	int solid_only = st->ndash == 0 || st->dash == NULL ||
		scan_dash_period(st->dash, st->ndash) < SCAN_DASH_MIN_PERIOD;
	for (size_t k = 0; k < p->nsubs && s.rc == 0; k++) {
		const scan_pt_t *q = p->pts + p->subs[k].start;
		size_t n = p->subs[k].n;
		if (n < 2 && !p->subs[k].closed)
			continue;   /* a lone move paints nothing; move + close is a dot */
		int64_t x0 = q[0].x, x1 = q[0].x, y0 = q[0].y, y1 = q[0].y;
		for (size_t i = 1; i < n; i++) {
			if (q[i].x < x0) x0 = q[i].x;
			if (q[i].x > x1) x1 = q[i].x;
			if (q[i].y < y0) y0 = q[i].y;
			if (q[i].y > y1) y1 = q[i].y;
		}
		if ((double)y1 < lo || (double)y0 > hi || (double)x1 < -ext || (double)x0 > right)
			continue;
		if (solid_only)
			solid(&s, q, n, p->subs[k].closed);
		else
			dashed(&s, st, q, n, p->subs[k].closed);
	}
	free(s.disc);
	return s.rc;
}

int scan_stroke(scan_ctx_t *c, const scan_band_t *b, const scan_path_t *p, const scan_style_t *st,
		meta_rgb_t rgb)
{
	return stroke(c, b, p, st, rgb, NULL);
}

int scan_stroke_pieces(scan_ctx_t *c, const scan_path_t *p, const scan_style_t *st, int width,
		int height, scan_path_t *out)
{
	/* the page as a band without pixels: the pieces that cannot reach it are left out */
	scan_band_t page = { NULL, 0, width, height, 0, height };
	return stroke(c, &page, p, st, 0, out);
}
