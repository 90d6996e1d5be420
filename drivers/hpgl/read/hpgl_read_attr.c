/* hpgl_read_attr.c: the HP-GL reader's line, fill, window and label state (PW WU PC CR LT FT IW
 * SI SR DI DR SL LO ES CP), the attribute sets strokes refer to, and labels with their layout. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "hpgl/read/hpgl_read_int.h"

/* HP-GL/2's fixed line types 1 .. 8: dash, gap, ... in percent of the pattern length. */
static const double lt_fixed[8][8] = {
	{ 0, 100 }, { 50, 50 }, { 70, 30 }, { 80, 10, 0, 10 }, { 70, 10, 10, 10 },
	{ 50, 10, 10, 10, 10, 10 }, { 70, 10, 0, 10, 0, 10 }, { 50, 10, 0, 10, 10, 10, 0, 10 },
};
static const int lt_fixed_n[8] = { 2, 2, 2, 4, 4, 6, 6, 8 };

/* The pattern of line type lt (UL's where defined) into a. */
static void lt_pattern(const hpgl_rd_t *r, hpgl_rattr_t *a)
{
	int t = a->lt == HPGL_LT_SOLID || a->lt == 0 ? 0 : abs(a->lt);
	memset(a->lt_pat, 0, sizeof a->lt_pat);
	a->lt_n = 0;
	if (!t)
		return;
	if (r->ul_n[t - 1]) {
		a->lt_n = r->ul_n[t - 1];
		memcpy(a->lt_pat, r->ul[t - 1], sizeof a->lt_pat);
	} else {
		a->lt_n = lt_fixed_n[t - 1];
		memcpy(a->lt_pat, lt_fixed[t - 1], (size_t)a->lt_n * sizeof *a->lt_pat);
	}
}

static double diagonal(const hpgl_rd_t *r)
{
	double d = hypot(r->p2x - r->p1x, r->p2y - r->p1y);
	return d > 0 ? d : 1;
}

void hpgl_rd_attr_defaults(hpgl_rd_t *r, int in)
{
	r->at.lt = HPGL_LT_SOLID;
	r->at.lt_len = 0.04 * diagonal(r);
	r->lt_saved = HPGL_LT_SOLID;
	r->lt_saved_len = r->at.lt_len;
	lt_pattern(r, &r->at);
	r->at.cap = r->at.join = 0;
	r->at.ft = 1;
	r->at.ft_space = 0.01 * diagonal(r);
	r->at.ft_angle = 0;
	r->at.ft_shade = 100;
	r->at.nonzero = 0;
	r->at.iw = 0;
	r->at.cs = r->at.ca = 0;   /* CS0, CA0 (DF and IN) */
	if (in)
		r->at.ro = 0;          /* RO0 (IN only) */
	r->lsize = r->ldir = 0;
	r->lsw = 0.19, r->lsh = 0.27;   /* SI defaults, cm */
	r->ldx = 1, r->ldy = 0;
	r->slant = r->es_char = r->es_line = 0;
	r->lo = 1;
	r->sm = 0;
	r->tl_p = r->tl_n = 0.5;
	if (in) {
		memset(r->ul_n, 0, sizeof r->ul_n);
		for (int k = 0; k < 256; k++)
			r->pw[k] = -1, r->pal[k] = -1;
		for (int k = 0; k < 6; k++)
			r->cr[k] = k % 2 ? 255 : 0;
		r->wu = 0;
		r->crx = r->x, r->cry = r->y;
	}
}

size_t hpgl_rd_attr(hpgl_rd_t *r)
{
	hpgl_doc_t *d = r->doc;
	hpgl_rattr_t a;
	memcpy(&a, &r->at, sizeof a);   /* padding too (r was zeroed): the sets compare by bytes */
	int p = r->pen & 255;
	a.width_mm = r->pw[p];
	a.rgb = r->pal[p];
	if (d->nattrs && !memcmp(&d->attrs[d->nattrs - 1], &a, sizeof a))
		return d->nattrs - 1;
	if (hpgl_rd_grow((void **)&d->attrs, &d->capattrs, d->nattrs + 1, sizeof *d->attrs)) {
		hpgl_rd_nomem(r);
		return (size_t)-1;
	}
	memcpy(&d->attrs[d->nattrs], &a, sizeof a);
	return d->nattrs++;
}

/* A colour component v on the range [b, w] to 0 .. 255. */
static long comp(double v, double b, double w)
{
	double t = w != b ? (v - b) / (w - b) : 0;
	t = t < 0 ? 0 : t > 1 ? 1 : t;
	return lround(t * 255);
}

static void label_state(const hpgl_rd_t *r, hpgl_rlabel_t *l);

static double len_x(const hpgl_rd_t *r, double u)
{
	double x, y;
	hpgl_rd_user_len(r, u, 0, &x, &y);
	return fabs(x);
}

int hpgl_rd_state(hpgl_rd_t *r, const char *mn, const double *v, int nv)
{
	double diag = diagonal(r);
	if (!strcmp(mn, "PW")) {
		double w = nv ? v[0] : (r->wu ? 0.1 : 0.35);
		if (r->wu)
			w = w / 100 * diag / 40;   /* percent of the diagonal, to mm */
		w = fabs(w);
		if (nv >= 2) {
			r->pw[(int)fmod(fabs(v[1]), 256)] = w;
		} else {
			for (int k = 0; k < 256; k++)
				r->pw[k] = w;
		}
	} else if (!strcmp(mn, "WU")) {
		r->wu = nv && v[0] == 1;
	} else if (!strcmp(mn, "PC")) {
		if (nv == 0) {
			for (int k = 0; k < 256; k++)
				r->pal[k] = -1;
		} else {
			int p = (int)fmod(fabs(v[0]), 256);
			r->pal[p] = nv < 4 ? -1 : comp(v[1], r->cr[0], r->cr[1]) << 16 |
				comp(v[2], r->cr[2], r->cr[3]) << 8 | comp(v[3], r->cr[4], r->cr[5]);
		}
	} else if (!strcmp(mn, "CR")) {
		for (int k = 0; k < 6; k++)
			r->cr[k] = nv >= 6 ? v[k] : k % 2 ? 255 : 0;
	} else if (!strcmp(mn, "NP")) {
		/* the palette's size: pens past it are drawn with the default colours anyway */
	} else if (!strcmp(mn, "LT")) {
		if (nv == 0) {
			if (r->at.lt != HPGL_LT_SOLID)
				r->lt_saved = r->at.lt, r->lt_saved_len = r->at.lt_len;
			r->at.lt = HPGL_LT_SOLID;
		} else if (v[0] == 99) {
			r->at.lt = r->lt_saved;
			r->at.lt_len = r->lt_saved_len;
		} else {
			int n = hpgl_rd_int(v[0]);
			double len = nv >= 2 && v[1] > 0 ? v[1] : 4;
			int mm = nv >= 3 && v[2] == 1;
			r->at.lt = n >= -8 && n <= 8 && n == v[0] ? n : HPGL_LT_SOLID;
			r->at.lt_len = mm ? len * 40 : len / 100 * diag;
			if (!(r->at.lt_len > 0) || r->at.lt_len > 1e9)
				r->at.lt_len = 0.04 * diag;
		}
		lt_pattern(r, &r->at);
	} else if (!strcmp(mn, "UL")) {
		int t = nv ? hpgl_rd_int(v[0]) : 0;
		if (nv == 0) {
			memset(r->ul_n, 0, sizeof r->ul_n);
		} else if (t >= 1 && t <= 8 && t == v[0]) {
			double sum = 0;
			int n = nv - 1 < 20 ? nv - 1 : 20;
			for (int k = 0; k < n; k++)
				sum += fmax(v[k + 1], 0);
			r->ul_n[t - 1] = sum > 0 ? n : 0;   /* normalised to percent */
			for (int k = 0; k < n && sum > 0; k++)
				r->ul[t - 1][k] = fmax(v[k + 1], 0) / sum * 100;
		}
		lt_pattern(r, &r->at);
	} else if (!strcmp(mn, "LA")) {
		for (int k = 0; k + 1 < nv; k += 2) {
			int kind = hpgl_rd_int(v[k]), val = hpgl_rd_int(v[k + 1]);
			if (kind == 1)
				r->at.cap = val >= 1 && val <= 4 ? val : 0;
			else if (kind == 2)
				r->at.join = val >= 1 && val <= 6 ? val : 0;
		}
		if (nv == 0)
			r->at.cap = r->at.join = 0;
	} else if (!strcmp(mn, "FT")) {
		int t = nv ? hpgl_rd_int(v[0]) : 1;
		r->at.ft = t == 3 || t == 4 || t == 10 ? t : 1;
		if (t == 3 || t == 4) {
			double sp = nv >= 2 ? len_x(r, v[1]) : 0;
			r->at.ft_space = sp > 0 && sp < 1e9 ? sp : 0.01 * diag;
			r->at.ft_angle = nv >= 3 ? fmod(v[2], 360) : 0;
		} else if (t == 10) {
			double s = nv >= 2 ? v[1] : 100;
			r->at.ft_shade = s < 0 ? 0 : s > 100 ? 100 : s;
		}
	} else if (!strcmp(mn, "IW")) {
		if (nv >= 4) {
			double x0, y0, x1, y1;
			hpgl_rd_user_to_pu(r, v[0], v[1], &x0, &y0);
			hpgl_rd_user_to_pu(r, v[2], v[3], &x1, &y1);
			r->at.iw = 1;
			r->at.iw_x0 = fmin(x0, x1), r->at.iw_x1 = fmax(x0, x1);
			r->at.iw_y0 = fmin(y0, y1), r->at.iw_y1 = fmax(y0, y1);
		} else {
			r->at.iw = 0;
		}
	} else if (!strcmp(mn, "SI") || !strcmp(mn, "SR")) {
		r->lsize = mn[1] == 'R';
		r->lsw = nv >= 2 ? v[0] : r->lsize ? 0.75 : 0.19;
		r->lsh = nv >= 2 ? v[1] : r->lsize ? 1.5 : 0.27;
	} else if (!strcmp(mn, "DI") || !strcmp(mn, "DR")) {
		r->ldir = mn[1] == 'R';
		r->ldx = nv >= 2 ? v[0] : 1;
		r->ldy = nv >= 2 ? v[1] : 0;
		if (r->ldx == 0 && r->ldy == 0)
			r->ldx = 1;
	} else if (!strcmp(mn, "SL")) {
		r->slant = nv ? tan(fmod(atan(v[0]), M_PI / 2)) : 0;
		if (!isfinite(r->slant) || fabs(r->slant) > 100)
			r->slant = 0;
	} else if (!strcmp(mn, "ES")) {
		r->es_char = nv ? fmax(fmin(v[0], 100), -1) : 0;
		r->es_line = nv >= 2 ? fmax(fmin(v[1], 100), -1) : 0;
	} else if (!strcmp(mn, "LO")) {
		int n = nv ? hpgl_rd_int(v[0]) : 1;
		r->lo = (n >= 1 && n <= 9) || (n >= 11 && n <= 19) ? n : 1;
		r->crx = r->x, r->cry = r->y;   /* LO sets the carriage-return point */
	} else if (!strcmp(mn, "CP")) {
		/* spaces along the run, lines up (positive) or down; none: to the next line's start */
		hpgl_rlabel_t l;
		label_state(r, &l);
		double cell = 1.5 * l.cw * (1 + l.es_char), lh = 2 * l.ch * (1 + l.es_line);
		if (nv >= 2) {
			r->x += v[0] * cell * l.dx - v[1] * lh * l.dy;
			r->y += v[0] * cell * l.dy + v[1] * lh * l.dx;
			r->crx -= v[1] * lh * l.dy;   /* lines move the CR point too */
			r->cry += v[1] * lh * l.dx;
		} else {
			r->crx += lh * l.dy;
			r->cry -= lh * l.dx;
			r->x = r->crx, r->y = r->cry;
		}
	} else {
		return 0;
	}
	return 1;
}

/* The label state in force as a label at the pen (text not set). */
static void label_state(const hpgl_rd_t *r, hpgl_rlabel_t *l)
{
	memset(l, 0, sizeof *l);
	l->pen = r->pen;
	l->x = r->x, l->y = r->y;
	double w = r->lsw, h = r->lsh;
	if (r->lsize)
		l->cw = w / 100 * (r->p2x - r->p1x), l->ch = h / 100 * (r->p2y - r->p1y);
	else
		l->cw = w * 400, l->ch = h * 400;
	double dx = r->ldx, dy = r->ldy;
	if (r->ldir)
		dx *= r->p2x - r->p1x, dy *= r->p2y - r->p1y;
	double n = hypot(dx, dy);
	if (!(n > 0) || !isfinite(n))
		dx = 1, dy = 0, n = 1;
	l->dx = dx / n, l->dy = dy / n;
	l->slant = r->slant;
	l->es_char = r->es_char, l->es_line = r->es_line;
	l->origin = r->lo;
	l->crx = r->crx, l->cry = r->cry;
	if (!isfinite(l->cw) || fabs(l->cw) > 1e9)
		l->cw = 76;
	if (!isfinite(l->ch) || fabs(l->ch) > 1e9)
		l->ch = 108;
}

/* LO's offset, in label space (along the run, up), of a portion of n characters. */
static void lo_offset(const hpgl_rlabel_t *l, size_t n, double cell, double *u, double *w)
{
	double len = n ? (double)n * cell - (cell - l->cw) : 0;
	int o = l->origin > 10 ? l->origin - 10 : l->origin;
	if (o < 1 || o > 9)
		o = 1;
	int hz = (o - 1) / 3, vt = (o - 1) % 3;
	*u = -hz * len / 2;
	*w = -vt * l->ch / 2;
	if (l->origin > 10) {
		*u += hz == 0 ? 0.5 * l->cw : hz == 2 ? -0.5 * l->cw : 0;
		*w += vt == 0 ? 0.5 * l->ch : vt == 2 ? -0.5 * l->ch : 0;
	}
}

int hpgl_label_walk(const hpgl_rlabel_t *l, int (*fn)(void *user, int ch, double x, double y),
		void *user, double *px, double *py)
{
	const unsigned char *t = (const unsigned char *)l->text;
	double cell = 1.5 * l->cw * (1 + l->es_char), lh = 2 * l->ch * (1 + l->es_line);
	double u = 0, w = 0, ou = 0, ow = 0;   /* the pen and the portion's LO offset, label space */
	double ex = l->crx - l->x, ey = l->cry - l->y;
	double cu = ex * l->dx + ey * l->dy, cw = -ex * l->dy + ey * l->dx;   /* the CR point */
	int fresh = 1;                          /* the next character starts a portion */
	int alt = 0;                            /* SO (0x0e) selected the alternate set, SI back */
	for (size_t i = 0; i < l->len; i++) {
		unsigned char c = t[i];
		if (c == 0x0e || c == 0x0f) {
			alt = c == 0x0e;
		} else if (c == '\r') {
			u = cu, w = cw, ou = ow = 0, fresh = 1;
		} else if (c == '\n') {
			w -= lh, cw -= lh;
		} else if (c == 8) {
			u -= cell;
		} else if (c >= 32 && c != 127) {
			if (fresh) {   /* a portion (to CR or LF) is placed as a label of its own */
				size_t n = 0;
				while (i + n < l->len && t[i + n] != '\r' && t[i + n] != '\n')
					n++;
				lo_offset(l, n, cell, &ou, &ow);
				fresh = 0;
			}
			double a = u + ou, b = w + ow;
			int rc = fn ? fn(user, c | (alt ? 0x100 : 0), l->x + a * l->dx - b * l->dy, l->y + a * l->dy + b * l->dx) : 0;
			if (rc)
				return rc;
			u += cell;
		}
	}
	double a = u + ou, b = w + ow;   /* the next character's origin (a CR: the CR point) */
	*px = l->x + a * l->dx - b * l->dy;
	*py = l->y + a * l->dy + b * l->dx;
	return 0;
}

int hpgl_rd_label(hpgl_rd_t *r, const unsigned char *text, size_t len, int symbol)
{
	hpgl_rlabel_t l;
	label_state(r, &l);
	if (symbol) {
		l.origin = 5;
		l.symbol = 1;
	}
	hpgl_doc_t *d = r->doc;
	if ((l.attr = hpgl_rd_attr(r)) == (size_t)-1)
		return -1;
	if (hpgl_rd_grow((void **)&d->labels, &d->caplabels, d->nlabels + 1, sizeof *d->labels))
		return hpgl_rd_nomem(r);
	char *t = malloc(len + 1);
	if (!t)
		return hpgl_rd_nomem(r);
	memcpy(t, text, len);
	t[len] = 0;
	l.text = t;
	l.len = len;
	l.offset = r->cmd_off;
	l.page = r->page;
	r->page_used = 1;
	r->rotated |= r->at.ro != 0;
	d->labels[d->nlabels++] = l;
	if (!symbol) {
		/* the pen at the next character's origin; each LF moves the CR point down a line */
		double lh = 2 * l.ch * (1 + l.es_line);
		size_t lf = 0;
		for (size_t i = 0; i < len; i++)
			lf += text[i] == '\n';
		hpgl_label_walk(&l, NULL, NULL, &r->x, &r->y);
		r->crx += (double)lf * lh * l.dy;
		r->cry -= (double)lf * lh * l.dx;
	}
	return 0;
}
