/* import_hpgl.c: HP-GL to meta for `locus-meta import`: pen widths and colours, line types as
 * dashes, fills with their rule and hatching, IW clipping, labels laid out as the plotter does. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "util/grow.h"
#include "hpgl/hpgl.h"
#include "hpgl/read/hpgl_read.h"
#include "import/meta_import.h"
#include "geom/scan.h"

#define MAX_HATCH 20000   /* hatch lines per fill and direction at most (the spacing widens) */

/* hp2xx's default pen colours: 1 black, 2 red, 3 green, 4 blue, 5 cyan, 6 magenta, 7 yellow;
 * pen 0 (none selected) is drawn black as hp2xx does with pen 1; higher pens repeat 1..7. */
static meta_rgb_t pen_rgb(int pen)
{
	static const meta_rgb_t c[8] = { 0x000000, 0x000000, 0xff0000, 0x00ff00, 0x0000ff, 0x00ffff,
		0xff00ff, 0xffff00 };
	return pen <= 0 ? c[0] : c[(pen - 1) % 7 + 1];
}

/* The output: a measuring pass (bounding box in plotter units) or the writing pass. */
typedef struct {
	meta_writer_t *w;           /* NULL: measure */
	const hpgl_doc_t *d;
	double s, x0, y0;           /* pixels per plotter unit, the page's origin in plotter units */
	double bx0, by0, bx1, by1;  /* measured extent */
	int open;                   /* a stroked path is open */
	long colour;
	double width, dash[16];
	int ndash, rule, cap, join;
	double def_mm;              /* pen width where the file gives none */
	int rc;
	const hpgl_pens_t *pens;    /* a profile's carousel: colours and widths the file leaves open */
	size_t page;                /* the file's page (PG) being drawn */
	FILE *warn;                 /* where warnings go (NULL: none) */
	const char *name;
	int cs_told[4];             /* character sets: what was told (per *how of charset_char) */
} out_t;

/* The carousel's pen in slot pen, or NULL. */
static const hpgl_pen_t *slot(const out_t *o, int pen)
{
	for (size_t k = 0; o->pens && k < o->pens->n; k++)
		if (o->pens->pen[k].slot == pen)
			return &o->pens->pen[k];
	return NULL;
}

/* The colour of pen: PC, else the carousel's, else hp2xx's default. */
static long colour_of(const out_t *o, const hpgl_rattr_t *a, int pen)
{
	const hpgl_pen_t *p = slot(o, pen);
	return a->rgb >= 0 ? a->rgb : p ? (long)p->rgb : (long)pen_rgb(pen);
}

#define CK(x) do { int r_ = (x); if (r_ < 0) { o->rc = r_; return r_; } } while (0)

static int pt_out(out_t *o, int move, double x, double y)
{
	if (!o->w) {
		o->bx0 = fmin(o->bx0, x), o->bx1 = fmax(o->bx1, x);
		o->by0 = fmin(o->by0, y), o->by1 = fmax(o->by1, y);
		return 0;
	}
	double X = (x - o->x0) * o->s, Y = (y - o->y0) * o->s;
	return move ? meta_move(o->w, X, Y) : meta_draw(o->w, X, Y);
}

static int end_path(out_t *o)
{
	if (o->open && o->w)
		CK(meta_end(o->w));
	o->open = 0;
	return 0;
}

/* State statements only when they change. */
static int set_colour(out_t *o, long rgb)
{
	if (!o->w || rgb == o->colour)
		return 0;
	o->colour = rgb;
	return meta_colour(o->w, (meta_rgb_t)rgb);
}

static int set_width(out_t *o, const hpgl_rattr_t *a, int pen)
{
	const hpgl_pen_t *p = slot(o, pen);
	double mm = a->width_mm >= 0 ? a->width_mm : p ? p->width_mm : o->def_mm;
	double px = fmin(fmax(mm * 40 * o->s, 1.0), 10000);
	if (!o->w || px == o->width)
		return 0;
	o->width = px;
	return meta_width(o->w, px);
}

static int set_dash(out_t *o, const double *len, size_t n)
{
	if (!o->w || ((int)n == o->ndash && (!n || !memcmp(len, o->dash, n * sizeof *len))))
		return 0;
	o->ndash = (int)n;
	if (n)
		memcpy(o->dash, len, n * sizeof *len);
	return meta_dash(o->w, len, n);
}

/* LA's ends and joins (triangular ones as round; none given: round, a pen's own). */
static int set_ends(out_t *o, const hpgl_rattr_t *a)
{
	int cap = a->cap == 1 ? META_CAP_BUTT : a->cap == 2 ? META_CAP_SQUARE : META_CAP_ROUND;
	int join = a->join == 1 || a->join == 2 ? META_JOIN_MITER : a->join == 5 || a->join == 6 ?
		META_JOIN_BEVEL : META_JOIN_ROUND;
	if (!o->w)
		return 0;
	if (cap != o->cap)
		CK(meta_cap(o->w, o->cap = cap));
	if (join != o->join)
		CK(meta_join(o->w, o->join = join));
	return 0;
}

/* ---- clipping to IW ---- */

/* Liang-Barsky: the part [t0, t1] of p->q inside the window; 0 when none. */
static int clip_seg(const hpgl_rattr_t *a, hpgl_rpt_t p, hpgl_rpt_t q, double *t0, double *t1)
{
	double dx = q.x - p.x, dy = q.y - p.y;
	double pp[4] = { -dx, dx, -dy, dy };
	double qq[4] = { p.x - a->iw_x0, a->iw_x1 - p.x, p.y - a->iw_y0, a->iw_y1 - p.y };
	*t0 = 0, *t1 = 1;
	for (int k = 0; k < 4; k++) {
		if (pp[k] == 0) {
			if (qq[k] < 0)
				return 0;
			continue;
		}
		double t = qq[k] / pp[k];
		if (pp[k] < 0)
			*t0 = fmax(*t0, t);
		else
			*t1 = fmin(*t1, t);
	}
	return *t0 <= *t1;
}

/* A polyline into the open stroked path (begun here when needed), clipped by a's window. */
static int polyline(out_t *o, const hpgl_rpt_t *p, size_t n, const hpgl_rattr_t *a)
{
	int in = 0;
	for (size_t i = 1; i < n; i++) {
		double t0 = 0, t1 = 1;
		if (a->iw && !clip_seg(a, p[i - 1], p[i], &t0, &t1)) {
			in = 0;
			continue;
		}
		hpgl_rpt_t u = { p[i - 1].x + t0 * (p[i].x - p[i - 1].x), p[i - 1].y + t0 * (p[i].y - p[i - 1].y) };
		hpgl_rpt_t v = { p[i - 1].x + t1 * (p[i].x - p[i - 1].x), p[i - 1].y + t1 * (p[i].y - p[i - 1].y) };
		if (!o->open && o->w)
			CK(meta_stroke(o->w));
		o->open = 1;
		if (!in || t0 > 0)
			CK(pt_out(o, 1, u.x, u.y));
		CK(pt_out(o, 0, v.x, v.y));
		in = t1 >= 1;
	}
	return 0;
}

/* Sutherland-Hodgman against one side (k: 0 x >= x0, 1 x <= x1, 2 y >= y0, 3 y <= y1). */
static size_t clip_side(const hpgl_rattr_t *a, int k, const hpgl_rpt_t *p, size_t n, hpgl_rpt_t *q)
{
	double e = k == 0 ? a->iw_x0 : k == 1 ? a->iw_x1 : k == 2 ? a->iw_y0 : a->iw_y1;
#define INSIDE(P) (k == 0 ? (P).x >= e : k == 1 ? (P).x <= e : k == 2 ? (P).y >= e : (P).y <= e)
	size_t m = 0;
	for (size_t i = 0; i < n; i++) {
		hpgl_rpt_t c = p[i], prev = p[(i + n - 1) % n];
		int ci = INSIDE(c), pi = INSIDE(prev);
		if (ci != pi) {
			double t = k < 2 ? (e - prev.x) / (c.x - prev.x) : (e - prev.y) / (c.y - prev.y);
			q[m++] = (hpgl_rpt_t){ prev.x + t * (c.x - prev.x), prev.y + t * (c.y - prev.y) };
		}
		if (ci)
			q[m++] = c;
	}
#undef INSIDE
	return m;
}

/* ---- fills ---- */

typedef struct {
	hpgl_rpt_t *p;
	size_t n;
} contour_t;

typedef struct {
	double u;
	int dir;
} cross_t;

static int cmp_cross(const void *a, const void *b)
{
	double x = ((const cross_t *)a)->u, y = ((const cross_t *)b)->u;
	return x < y ? -1 : x > y;
}

/* Hatch lines at angle (degrees), spacing apart, anchored at the plotter origin, over the
 * contours filled by the rule; drawn as solid lines of the pen. */
static int hatch(out_t *o, const contour_t *c, size_t nc, double space, double angle, int nonzero)
{
	double ca = cos(angle * M_PI / 180), sa = sin(angle * M_PI / 180);
	double v0 = INFINITY, v1 = -INFINITY;
	size_t ne = 0;
	for (size_t k = 0; k < nc; k++) {
		ne += c[k].n;
		for (size_t i = 0; i < c[k].n; i++) {
			double v = -c[k].p[i].x * sa + c[k].p[i].y * ca;
			v0 = fmin(v0, v), v1 = fmax(v1, v);
		}
	}
	if (!(v0 < v1))
		return 0;
	/* at most MAX_HATCH lines, and lines times edges bounded (each line meets every edge) */
	double most = fmin(MAX_HATCH, fmax(20e6 / (double)(ne + 1), 100));
	if ((v1 - v0) / space > most)
		space = (v1 - v0) / most;
	cross_t *x = malloc((ne + 1) * sizeof *x);
	if (!x)
		return o->rc = META_ENOMEM;
	for (double L = ceil(v0 / space); L * space <= v1; L++) {
		double v = L * space;
		size_t nx = 0;
		for (size_t k = 0; k < nc; k++)
			for (size_t i = 0; i < c[k].n; i++) {
				hpgl_rpt_t a = c[k].p[i], b = c[k].p[(i + 1) % c[k].n];
				double va = -a.x * sa + a.y * ca, vb = -b.x * sa + b.y * ca;
				if ((va <= v) == (vb <= v))
					continue;
				double t = (v - va) / (vb - va);
				double ua = a.x * ca + a.y * sa, ub = b.x * ca + b.y * sa;
				x[nx++] = (cross_t){ ua + t * (ub - ua), vb > va ? 1 : -1 };
			}
		qsort(x, nx, sizeof *x, cmp_cross);
		int wind = 0;
		for (size_t i = 0; i + 1 < nx; i++) {
			wind += nonzero ? x[i].dir : 1;
			if ((nonzero ? wind == 0 : !(wind & 1)) || x[i + 1].u - x[i].u < 1e-6)
				continue;   /* outside, or a corner touched */
			hpgl_rpt_t seg[2] = { { x[i].u * ca - v * sa, x[i].u * sa + v * ca },
				{ x[i + 1].u * ca - v * sa, x[i + 1].u * sa + v * ca } };
			hpgl_rattr_t none = { 0 };
			if (polyline(o, seg, 2, &none) < 0) {
				free(x);
				return o->rc;
			}
		}
	}
	free(x);
	return 0;
}

/* Strokes first .. last - 1 (one fill: a group's contours, or one RA RR WG) filled. */
static int fill(out_t *o, size_t first, size_t last)
{
	const hpgl_doc_t *d = o->d;
	const hpgl_rstroke_t *st = &d->strokes[first];
	const hpgl_rattr_t *a = &d->attrs[st->attr];
	contour_t *c = calloc(last - first, sizeof *c);
	size_t nc = 0;
	int rc = c ? 0 : META_ENOMEM;
	for (size_t k = first; k < last && !rc; k++) {
		const hpgl_rstroke_t *s = &d->strokes[k];
		size_t n = s->n, cap = 2 * n + 8;
		hpgl_rpt_t *p = malloc(cap * sizeof *p), *q = malloc(cap * sizeof *q);
		if (!p || !q) {
			free(p), free(q);
			rc = META_ENOMEM;
			break;
		}
		memcpy(p, d->pts + s->start, n * sizeof *p);
		if (a->iw)   /* each side adds at most one point per edge crossing: 2n + 4 suffices */
			for (int side = 0; side < 4 && n; side++) {
				n = clip_side(a, side, p, n, q);
				hpgl_rpt_t *t = p;
				p = q, q = t;
			}
		free(q);
		if (n >= 3)
			c[nc++] = (contour_t){ p, n };
		else
			free(p);
	}
	long rgb = colour_of(o, a, st->pen);
	if (!rc && nc && !o->w) {   /* measuring: the contours are the extent */
		for (size_t k = 0; k < nc; k++)
			for (size_t i = 0; i < c[k].n; i++)
				pt_out(o, 0, c[k].p[i].x, c[k].p[i].y);
	} else if (!rc && nc && (a->ft == 3 || a->ft == 4)) {
		rc = set_colour(o, rgb);
		if (rc >= 0)
			rc = set_width(o, a, st->pen);
		if (rc >= 0)
			rc = set_dash(o, NULL, 0);
		for (int k = 0; k < (a->ft == 4 ? 2 : 1) && rc >= 0; k++)
			rc = hatch(o, c, nc, a->ft_space, a->ft_angle + 90 * k, a->nonzero);
		if (rc >= 0)
			rc = end_path(o);
	} else if (!rc && nc) {
		if (a->ft == 10) {   /* shading: the pen's colour over white at the level */
			double t = a->ft_shade / 100;
			long r = rgb >> 16 & 255, g = rgb >> 8 & 255, b = rgb & 255;
			rgb = lround(255 - (255 - r) * t) << 16 | lround(255 - (255 - g) * t) << 8 | lround(255 - (255 - b) * t);
		}
		rc = set_colour(o, rgb);
		int rule = a->nonzero ? META_RULE_NON_ZERO : META_RULE_EVEN_ODD;
		if (rc >= 0 && o->w && rule != o->rule)
			rc = meta_fill_rule(o->w, o->rule = rule);
		if (rc >= 0 && o->w)
			rc = meta_fill(o->w);
		for (size_t k = 0; k < nc && rc >= 0; k++) {
			for (size_t i = 0; i < c[k].n && rc >= 0; i++)
				rc = pt_out(o, i == 0, c[k].p[i].x, c[k].p[i].y);
			if (rc >= 0 && o->w)
				rc = meta_close(o->w);
		}
		if (rc >= 0 && o->w)
			rc = meta_end(o->w);
	}
	for (size_t k = 0; k < nc; k++)
		free(c[k].p);
	free(c);
	if (rc < 0)
		o->rc = rc;
	return rc < 0 ? rc : 0;
}

/* ---- lines ---- */

static double polylen(const hpgl_rpt_t *p, size_t n)
{
	double L = 0;
	for (size_t i = 1; i < n; i++)
		L += hypot(p[i].x - p[i - 1].x, p[i].y - p[i - 1].y);
	return L;
}

static int line(out_t *o, const hpgl_rstroke_t *st)
{
	const hpgl_rattr_t *a = &o->d->attrs[st->attr];
	const hpgl_rpt_t *p = o->d->pts + st->start;
	CK(set_colour(o, colour_of(o, a, st->pen)));
	CK(set_width(o, a, st->pen));
	CK(set_ends(o, a));
	if (a->lt == 0) {   /* LT 0: a dot at each point */
		CK(set_dash(o, NULL, 0));
		for (size_t i = 0; i < st->n; i++) {
			hpgl_rpt_t q[2] = { p[i], { p[i].x + 0.01 / o->s, p[i].y } };
			CK(polyline(o, q, 2, a));
		}
		return end_path(o);
	}
	if (a->lt_n) {
		double len = a->lt_len, dl[20];
		if (a->lt < 0) {   /* adaptive: a whole number of patterns along the stroke */
			double L = polylen(p, st->n);
			double k = fmax(1, round(L / len));
			len = L / k > 0 ? L / k : len;
		}
		int n = a->lt_n > 16 ? 16 : a->lt_n;
		for (int i = 0; i < n; i++)
			dl[i] = fmin(fmax(a->lt_pat[i] / 100 * len * o->s, 0.001), 100000);
		CK(set_dash(o, dl, (size_t)n));
	} else {
		CK(set_dash(o, NULL, 0));
	}
	CK(polyline(o, p, st->n, a));
	return end_path(o);
}


/* ---- character sets (CS, CA; SO and SI in labels) ---- */

/* The upper halves (0xa0 .. 0xff) of HP Roman-8 and ISO 8859-1 as what the stroke font can draw:
 * the same character where ASCII has it (` ^ ~ in Roman-8, the spaces, the dash), the base letter
 * of an accented one, 0 where neither exists (currency, fractions, ligatures, guillemets ...). */
static const char roman8_hi[97] = " AAEEEII\0`^\0~UU\0\0Yy\0CcNn\0\0\0\0\0\0\0\0aeouaeouaeouaeouAiO\0aio\0AiOUEi\0OAAaD\0IIOOOoSsUYy\0\0\0\0\0\0-\0\0\0\0\0\0\0\0\0";
static const char latin1_hi[97] = " \0\0\0\0\0\0\0\0\0\0\0\0-\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0AAAAAA\0CEEEEIIIIDNOOOOO\0OUUUUY\0\0aaaaaa\0ceeeeiiii\0nooooo\0ouuuuy\0y";

/* HP-GL character sets the import knows: 0 ANSI ASCII; 7 the Roman extension set (Roman-8's upper
 * half on 0x21 .. 0x7e); HP-GL/2's symbol-set numbers 21 (US ASCII), 277 (Roman-8) and 14
 * (ISO 8859-1). Byte c of set s as an ASCII character for the stroke font, or -1 (the replacement
 * box); *how: 0 exact, 1 the base letter of an accented one, 2 none (box), 3 the set unknown. */
static int charset_char(int s, int c, int *how)
{
	const char *hi = NULL;
	*how = 0;
	if (s == 7) {   /* 7-bit: c + 0x80 in Roman-8 */
		if (c == ' ')
			return c;
		if (c < 0x21 || c > 0x7e) {
			*how = 2;
			return -1;
		}
		c += 0x80;
		hi = roman8_hi;
	} else if (s == 0 || s == 21 || s == 277 || s == 14) {
		if (c >= 0x20 && c <= 0x7e)
			return c;
		hi = s == 277 ? roman8_hi : s == 14 ? latin1_hi : NULL;
	} else {
		*how = 3;
		return c >= 0x20 && c <= 0x7e ? c : -1;
	}
	if (!hi || c < 0xa0 || c > 0xff || !hi[c - 0xa0]) {
		*how = 2;
		return -1;
	}
	int exact = s == 14 ? (c == 0xa0 || c == 0xad) : (c == 0xa0 || c == 0xa9 || c == 0xaa || c == 0xac || c == 0xf6);
	*how = exact ? 0 : 1;
	return (unsigned char)hi[c - 0xa0];
}

/* ---- labels ---- */

/* One character's glyph in the cell whose origin is (x, y), sized, turned and slanted as l. */
typedef struct {
	out_t *o;
	const hpgl_rlabel_t *l;
	const hpgl_rattr_t *a;
} glyph_t;

static int glyph(void *user, int ch, double x, double y)
{
	glyph_t *g = user;
	out_t *o = g->o;
	const hpgl_rlabel_t *l = g->l;
	int set = ch & 0x100 ? g->a->ca : g->a->cs, how;
	ch = charset_char(set, ch & 0xff, &how);
	if (how && o->w && o->warn && !o->cs_told[how]) {   /* once a file for each kind */
		o->cs_told[how] = 1;
		fprintf(o->warn, "locus-meta: warning: %s: byte %zu: character set %d: %s\n", o->name, l->offset, set,
			how == 1 ? "accented letters drawn as their base letters (the stroke font has no accents)" :
			how == 2 ? "a character the stroke font cannot draw, drawn as the replacement box" :
			"not a set the import knows, its characters drawn as ASCII");
	}
	if (ch == ' ')
		return 0;
	const char *src = scan_glyph_source(ch, NULL);
	double ku = l->cw / 4, kw = l->ch / 6;
	hpgl_rpt_t q[64];
	size_t n = 0;
	for (const char *s = src;; ) {
		double gx, gy;
		int used = 0;
		if (*s && sscanf(s, "%lf,%lf%n", &gx, &gy, &used) == 2 && n < 64) {
			double u = gx * ku + gy * kw * l->slant, w = gy * kw;
			q[n++] = (hpgl_rpt_t){ x + u * l->dx - w * l->dy, y + u * l->dy + w * l->dx };
			s += used;
			while (*s == ' ')
				s++;
		}
		if (!*s || *s == ';' || !used) {
			if (n == 1)   /* a dot */
				q[n++] = (hpgl_rpt_t){ q[0].x + 0.01 / o->s, q[0].y };
			CK(polyline(o, q, n, g->a));
			n = 0;
			if (!*s || !used)
				break;
			s++;
		}
	}
	return 0;
}

static int label(out_t *o, const hpgl_rlabel_t *l)
{
	const hpgl_rattr_t *a = &o->d->attrs[l->attr];
	CK(set_colour(o, colour_of(o, a, l->pen)));
	CK(set_width(o, a, l->pen));
	CK(set_dash(o, NULL, 0));
	hpgl_rattr_t round = { 0 };
	CK(set_ends(o, &round));
	glyph_t g = { o, l, a };
	double x, y;
	CK(hpgl_label_walk(l, glyph, &g, &x, &y));
	return end_path(o);
}

/* Everything, measured (o->w NULL) or written. */
static int draw(out_t *o)
{
	const hpgl_doc_t *d = o->d;
	for (size_t k = 0; k < d->nstrokes; ) {
		const hpgl_rstroke_t *st = &d->strokes[k];
		size_t e = k + 1;
		if (st->page != o->page) {
			k = e;
			continue;
		}
		if (st->kind == HPGL_RS_FILL) {
			while (st->group && e < d->nstrokes && d->strokes[e].group == st->group &&
					d->strokes[e].kind == HPGL_RS_FILL)
				e++;
			CK(fill(o, k, e));
		} else {
			CK(line(o, st));
		}
		k = e;
	}
	for (size_t k = 0; k < d->nlabels; k++)
		if (d->labels[k].page == o->page)
			CK(label(o, &d->labels[k]));
	return 0;
}

int mimp_hpgl(const void *buf, size_t n, const char *name, double px_per_mm, meta_writer_t *w,
		char *err, size_t errlen)
{
	return mimp_hpgl_pens(buf, n, name, px_per_mm, NULL, w, err, errlen);
}

int mimp_hpgl_pens(const void *buf, size_t n, const char *name, double px_per_mm, const char *pens,
		meta_writer_t *w, char *err, size_t errlen)
{
	return mimp_hpgl_read(buf, n, name, px_per_mm, pens, 1, NULL, w, err, errlen);
}

/* One page of the file (o->page) as a meta page: its extent with a margin of 2 %. */
static int one_page(out_t *o, double px_per_mm, meta_writer_t *w)
{
	o->w = NULL;
	o->bx0 = o->by0 = INFINITY, o->bx1 = o->by1 = -INFINITY;
	o->open = 0;
	int rc = draw(o);   /* the extent, plotter units */
	if (rc < 0)
		return rc;
	double x0 = o->bx0, y0 = o->by0, x1 = o->bx1, y1 = o->by1;
	if (!(x0 <= x1)) {   /* nothing drawn: an empty A4 landscape sheet */
		x0 = y0 = 0;
		x1 = 297 * 40.0, y1 = 210 * 40.0;
	}
	double wu = x1 - x0, hu = y1 - y0, side = fmax(fmax(wu, hu), 40.0);
	double margin = 0.02 * side;
	wu += 2 * margin, hu += 2 * margin;
	x0 -= margin, y0 -= margin;
	double s = px_per_mm / 40.0;                          /* pixels per plotter unit */
	if (fmax(wu, hu) * s > 8000)
		s = 8000 / fmax(wu, hu);
	unsigned wpx = (unsigned)ceil(fmax(wu * s, 1)), hpx = (unsigned)ceil(fmax(hu * s, 1));
	o->w = w, o->s = s, o->x0 = x0, o->y0 = y0;
	o->width = 0;
	o->ndash = 0;
	o->rule = META_RULE_EVEN_ODD, o->cap = META_CAP_ROUND, o->join = META_JOIN_ROUND;
	/* a drawing more than a kilometre across (no plotter's) keeps its picture; its size is
	 * given as the meta file's largest, 1000000 mm */
	double wmm = fmin(wpx / (s * 40), 1e6), hmm = fmin(hpx / (s * 40), 1e6);
	if ((rc = meta_page(w, wpx, hpx)) < 0 || (rc = meta_page_size_mm(w, wmm, hmm)) < 0 ||
			(rc = meta_clear(w, 0xffffff)) < 0 || (rc = meta_cap(w, META_CAP_ROUND)) < 0 ||
			(rc = meta_join(w, META_JOIN_ROUND)) < 0)
		return rc;
	hpgl_rattr_t none = { .width_mm = -1 };
	if ((rc = set_width(o, &none, -1)) < 0 || (rc = meta_fill_rule(w, META_RULE_EVEN_ODD)) < 0)
		return rc;
	o->colour = -1;
	if ((rc = draw(o)) < 0 || (rc = meta_end_page(w)) < 0)
		return rc;
	return 0;
}

int mimp_hpgl_read(const void *buf, size_t n, const char *name, double px_per_mm, const char *pens,
		int strict, FILE *warn, meta_writer_t *w, char *err, size_t errlen)
{
	hpgl_pens_t *car = NULL;
	if (pens) {
		if (!(car = malloc(sizeof *car))) {
			snprintf(err, errlen, "%s: out of memory", name);
			return -70;
		}
		if (hpgl_pens_parse(pens, 0.3, car, err, errlen)) {
			free(car);
			return -64;
		}
	}
	hpgl_doc_t d;
	if (hpgl_read_mem_flags(buf, n, name, strict ? 0 : HPGL_READ_TOLERANT, &d, err, errlen)) {
		hpgl_doc_free(&d);
		free(car);
		return -65;
	}
	for (size_t k = 0; warn && k < d.nwarns; k++)
		fprintf(warn, "locus-meta: warning: %s\n", d.warns[k].msg);
	if (warn && d.nwarns_more)
		fprintf(warn, "locus-meta: warning: %s: %zu more warnings\n", name, d.nwarns_more);
	out_t o = { NULL, &d, 1, 0, 0, INFINITY, INFINITY, -INFINITY, -INFINITY, 0, -1, -1, { 0 }, 0,
		META_RULE_EVEN_ODD, META_CAP_ROUND, META_JOIN_ROUND, d.hpgl2 ? 0.35 : 0.3, 0, car, 0, warn, name, { 0 } };
	int rc = 0;
	for (size_t p = 0; p < d.npages && rc >= 0; p++) {   /* PG: one meta page per plotter page */
		o.page = p;
		rc = one_page(&o, px_per_mm, w);
	}
	if (rc < 0)
		goto fail;
	hpgl_doc_free(&d);
	free(car);
	return 0;
fail:
	snprintf(err, errlen, "%s", rc == META_ENOMEM && !*meta_writer_error(w) ? "out of memory" : meta_writer_error(w));
	hpgl_doc_free(&d);
	free(car);
	return rc == META_ENOMEM ? -70 : rc == META_EIO ? -74 : -65;
}
