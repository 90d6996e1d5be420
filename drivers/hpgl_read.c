/* hpgl_read.c: HP-GL / HP-GL/2 reader: commands, parameters, PE data and escapes into strokes. */
#include <ctype.h>
#include <stdint.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include "hpgl_read.h"

#define MAX_PARAMS 64

typedef struct {
	const unsigned char *s;
	size_t n, i;
	const char *name;
	char *err;
	size_t errlen;
	hpgl_doc_t *doc;
	/* plotter state */
	int pen, down, rel, poly;   /* poly: inside PM0 .. PM2 */
	int newc;                   /* poly: the next pen-down point starts a contour */
	double x, y;                /* current position, plotter units */
	int sc;                     /* 0 none, 1 scaling on */
	double p1x, p1y, p2x, p2y;  /* IP */
	double sc_xmin, sc_xmax, sc_ymin, sc_ymax, sx, sy, ox, oy;
	unsigned char term;         /* label terminator */
	int open;                   /* 1 while a stroke is being drawn */
	size_t cmd, cmd_off;
	/* the polygon buffer: contours of points */
	hpgl_rpt_t *pb;
	size_t npb, cappb;
	size_t *pbs;                /* contour starts */
	size_t npbs, cappbs;
} rd_t;

static int fail(rd_t *r, size_t off, const char *fmt, ...)
{
	char m[256];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(m, sizeof m, fmt, ap);
	va_end(ap);
	snprintf(r->err, r->errlen, "%s: byte %zu: %s", r->name, off, m);
	return -1;
}

static int nomem(rd_t *r)
{
	return fail(r, r->i, "out of memory");
}

static int grow(void **p, size_t *cap, size_t need, size_t size)
{
	if (need <= *cap)
		return 0;
	size_t n = *cap ? *cap : 64;
	while (n < need)
		n *= 2;
	void *q = realloc(*p, n * size);
	if (!q)
		return -1;
	*p = q;
	*cap = n;
	return 0;
}

/* ---- strokes ---- */

static void end_stroke(rd_t *r)
{
	hpgl_doc_t *d = r->doc;
	if (r->open && d->strokes[d->nstrokes - 1].n < 2) {
		d->npts = d->strokes[d->nstrokes - 1].start;   /* a lone point draws nothing */
		d->nstrokes--;
	}
	r->open = 0;
}

static int add_pt(rd_t *r, double x, double y)
{
	hpgl_doc_t *d = r->doc;
	if (grow((void **)&d->pts, &d->cappts, d->npts + 1, sizeof *d->pts))
		return nomem(r);
	d->pts[d->npts++] = (hpgl_rpt_t){ x, y };
	d->strokes[d->nstrokes - 1].n++;
	return 0;
}

static int begin_stroke(rd_t *r, int kind)
{
	hpgl_doc_t *d = r->doc;
	end_stroke(r);
	if (grow((void **)&d->strokes, &d->capstrokes, d->nstrokes + 1, sizeof *d->strokes))
		return nomem(r);
	d->strokes[d->nstrokes++] = (hpgl_rstroke_t){ r->pen, kind, d->npts, 0, r->cmd, r->cmd_off };
	r->open = 1;
	return add_pt(r, r->x, r->y);
}

/* Polygon mode: start a contour at (x, y) (a contour of one point is replaced). */
static int start_contour(rd_t *r, double x, double y)
{
	if (r->npbs && r->npb - r->pbs[r->npbs - 1] == 1) {
		r->pb[r->npb - 1] = (hpgl_rpt_t){ x, y };
		return 0;
	}
	if (grow((void **)&r->pbs, &r->cappbs, r->npbs + 1, sizeof *r->pbs) ||
			grow((void **)&r->pb, &r->cappb, r->npb + 1, sizeof *r->pb))
		return nomem(r);
	r->pbs[r->npbs++] = r->npb;
	r->pb[r->npb++] = (hpgl_rpt_t){ x, y };
	r->newc = 0;
	return 0;
}

/* Move to (x, y) in plotter units with the pen as it is. */
static int move_to(rd_t *r, double x, double y)
{
	if (r->poly) {
		if (!r->down || r->newc || r->npbs == 0) {
			if (start_contour(r, r->down ? r->x : x, r->down ? r->y : y))
				return -1;
			if (!r->down) {
				r->x = x;
				r->y = y;
				return 0;
			}
		}
		if (grow((void **)&r->pb, &r->cappb, r->npb + 1, sizeof *r->pb))
			return nomem(r);
		r->pb[r->npb++] = (hpgl_rpt_t){ x, y };
		r->x = x;
		r->y = y;
		return 0;
	}
	if (r->down) {
		if (!r->open && begin_stroke(r, HPGL_RS_LINE))
			return -1;
		if (add_pt(r, x, y))
			return -1;
	} else {
		end_stroke(r);
	}
	r->x = x;
	r->y = y;
	return 0;
}

/* A closed figure drawn as its own stroke (edges, fills); the pen position is unchanged. */
static int figure(rd_t *r, const hpgl_rpt_t *p, size_t n, int kind)
{
	double x = r->x, y = r->y;
	end_stroke(r);
	r->x = p[0].x;
	r->y = p[0].y;
	if (begin_stroke(r, kind))
		return -1;
	for (size_t i = 1; i < n; i++)
		if (add_pt(r, p[i].x, p[i].y))
			return -1;
	end_stroke(r);
	r->x = x;
	r->y = y;
	return 0;
}

/* User units to plotter units (SC in force). */
static void user_to_pu(const rd_t *r, double u, double v, double *x, double *y)
{
	if (r->sc) {
		*x = r->ox + (u - r->sc_xmin) * r->sx;
		*y = r->oy + (v - r->sc_ymin) * r->sy;
	} else {
		*x = u;
		*y = v;
	}
}

static void user_len(const rd_t *r, double u, double v, double *x, double *y)
{
	*x = r->sc ? u * r->sx : u;
	*y = r->sc ? v * r->sy : v;
}

/* ---- arcs ---- */

/* Points of an arc about (cx, cy) from angle a0 (radians) through sweep degrees, chord degrees
 * apart, written to fn's target: calls move_to for each point after the first. */
static int arc_points(rd_t *r, double cx, double cy, double rad, double a0, double sweep, double chord)
{
	if (!(chord > 0) || chord > 180)
		chord = 5;
	int n = (int)ceil(fabs(sweep) / chord);
	if (n < 1)
		n = 1;
	if (n > 100000)
		n = 100000;
	for (int k = 1; k <= n; k++) {
		double a = a0 + sweep * M_PI / 180 * k / n;
		if (move_to(r, cx + rad * cos(a), cy + rad * sin(a)))
			return -1;
	}
	return 0;
}

static int circle(rd_t *r, double rad, double chord, int kind)
{
	if (!(chord > 0) || chord > 180)
		chord = 5;
	int n = (int)ceil(360 / chord);
	hpgl_rpt_t *p = malloc((size_t)(n + 1) * sizeof *p);
	if (!p)
		return nomem(r);
	for (int k = 0; k <= n; k++)
		p[k] = (hpgl_rpt_t){ r->x + rad * cos(2 * M_PI * k / n), r->y + rad * sin(2 * M_PI * k / n) };
	int rc = 0;
	if (r->poly) {   /* a circle in polygon mode is a contour of its own */
		rc = start_contour(r, p[0].x, p[0].y);
		for (int k = 1; k <= n && !rc; k++) {
			if (grow((void **)&r->pb, &r->cappb, r->npb + 1, sizeof *r->pb))
				rc = nomem(r);
			else
				r->pb[r->npb++] = p[k];
		}
		r->newc = 1;
	} else {
		rc = figure(r, p, (size_t)n + 1, kind);
	}
	free(p);
	return rc;
}

/* ---- lexing ---- */

static int is_sep(unsigned char c)
{
	return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == ',';
}

/* Read the numeric parameters of a command up to ';', a letter, ESC or the end. */
static int params(rd_t *r, const char *mn, double *v, int *nv)
{
	*nv = 0;
	for (;;) {
		while (r->i < r->n && is_sep(r->s[r->i]))
			r->i++;
		if (r->i >= r->n)
			return 0;
		unsigned char c = r->s[r->i];
		if (c == ';') {
			r->i++;
			return 0;
		}
		if (isalpha(c) || c == 0x1b)
			return 0;
		if (c == '"') {   /* a quoted string parameter (CO, DL labels): skipped */
			size_t e = r->i + 1;
			while (e < r->n && r->s[e] != '"')
				e++;
			if (e >= r->n)
				return fail(r, r->i, "unterminated string in %s", mn);
			r->i = e + 1;
			continue;
		}
		if (!(isdigit(c) || c == '-' || c == '+' || c == '.'))
			return fail(r, r->i, "unexpected byte 0x%02x in the parameters of %s (expected a number, ',' or ';')", c, mn);
		size_t st = r->i;
		if (c == '-' || c == '+')
			r->i++;
		size_t digits = 0;
		while (r->i < r->n && isdigit(r->s[r->i]))
			r->i++, digits++;
		if (r->i < r->n && r->s[r->i] == '.') {
			r->i++;
			while (r->i < r->n && isdigit(r->s[r->i]))
				r->i++, digits++;
		}
		if (!digits)
			return fail(r, st, "malformed number in the parameters of %s", mn);
		if (r->i < r->n && (r->s[r->i] == 'e' || r->s[r->i] == 'E') && r->i + 1 < r->n &&
				(isdigit(r->s[r->i + 1]) || r->s[r->i + 1] == '-' || r->s[r->i + 1] == '+')) {
			/* an exponent is no HP-GL, but some writers print one */
			r->i++;
			if (r->s[r->i] == '-' || r->s[r->i] == '+')
				r->i++;
			while (r->i < r->n && isdigit(r->s[r->i]))
				r->i++;
		}
		char buf[64];
		size_t len = r->i - st < sizeof buf - 1 ? r->i - st : sizeof buf - 1;
		memcpy(buf, r->s + st, len);
		buf[len] = 0;
		double x = strtod(buf, NULL);
		if (!isfinite(x) || fabs(x) > 1e12)
			return fail(r, st, "number out of range in %s", mn);
		if (*nv < MAX_PARAMS)
			v[*nv] = x;
		(*nv)++;
		if (*nv > MAX_PARAMS && mn[0] != 'P' && strcmp(mn, "PE"))
			return fail(r, st, "more than %d parameters for %s", MAX_PARAMS, mn);
		/* long coordinate lists are handled pair by pair by the caller */
		if (*nv == MAX_PARAMS && (mn[0] == 'P' || !strcmp(mn, "EP")))
			return 1;   /* more to come */
	}
}

/* ---- commands ---- */

static int coords(rd_t *r, const char *mn, int pen, int mode)
{
	double v[MAX_PARAMS];
	int nv, more;
	size_t st = r->i;
	if (pen >= 0) {
		end_stroke(r);
		r->down = pen;
	}
	if (mode >= 0)
		r->rel = mode;
	do {
		more = params(r, mn, v, &nv);
		if (more < 0)
			return -1;
		if (nv % 2)
			return fail(r, st, "%s with an odd number of coordinates (%d)", mn, nv);
		for (int k = 0; k < nv && k < MAX_PARAMS; k += 2) {
			double x, y;
			if (r->rel) {
				user_len(r, v[k], v[k + 1], &x, &y);
				x += r->x;
				y += r->y;
			} else {
				user_to_pu(r, v[k], v[k + 1], &x, &y);
			}
			if (move_to(r, x, y))
				return -1;
		}
	} while (more);
	return 0;
}

/* PE: encoded polyline (HP-GL/2). */
static int pe(rd_t *r)
{
	int up = 0, absn = 0, seven = 0, frac = 0, select = 0;
	double val[2];
	int nval = 0;
	uint64_t acc = 0;
	int shift = 0;
	size_t st = r->i;
	r->doc->hpgl2 = 1;
	while (r->i < r->n) {
		unsigned char c = r->s[r->i++];
		if (c == ';')
			break;
		if (c == '<') { up = 1; continue; }
		if (c == '=') { absn = 1; continue; }
		if (c == '7') { seven = 1; continue; }
		if (c == ':') { select = 1; continue; }
		if (c == '>') { select = 2; continue; }
		if (c < 63 || c == 127 || c == 255 || (!seven && c > 126 && c < 191)) {
			if (c <= ' ')
				continue;   /* blanks and line ends between numbers */
			return fail(r, r->i - 1, "bad byte 0x%02x in PE data", c);
		}
		int term, digit;
		if (seven) {
			if (c > 126)
				return fail(r, r->i - 1, "byte 0x%02x in 7-bit PE data", c);
			term = c >= 95;
			digit = term ? c - 95 : c - 63;
		} else {
			term = c >= 191;
			digit = term ? c - 191 : c - 63;
		}
		if (shift > 60)
			return fail(r, r->i - 1, "PE number too long");
		acc |= (uint64_t)digit << shift;
		shift += seven ? 5 : 6;
		if (!term)
			continue;
		double x = (double)(acc >> 1) * ((acc & 1) ? -1 : 1);
		if (frac)
			x /= (double)(1ULL << frac);
		acc = 0;
		shift = 0;
		if (select == 1) {   /* pen number */
			end_stroke(r);
			r->pen = (int)x;
			r->doc->pen_selects++;
			select = 0;
			continue;
		}
		if (select == 2) {   /* fractional bits */
			if (x < 0 || x > 26)
				return fail(r, r->i - 1, "PE fractional bits %g out of range", x);
			frac = (int)x;
			select = 0;
			continue;
		}
		val[nval++] = x;
		if (nval < 2)
			continue;
		nval = 0;
		double X, Y;
		if (absn) {
			user_to_pu(r, val[0], val[1], &X, &Y);
		} else {
			user_len(r, val[0], val[1], &X, &Y);
			X += r->x;
			Y += r->y;
		}
		if (up)
			end_stroke(r);
		r->down = !up;
		if (move_to(r, X, Y))
			return -1;
		up = absn = 0;
	}
	if (nval || shift)
		return fail(r, st, "PE data ends inside a number or a coordinate pair");
	end_stroke(r);   /* the pen stays as the last pair left it */
	return 0;
}

/* Device-control (ESC . X [params] [:]), PCL (ESC % -12345 X, ESC E, ESC & l 1 O ...), PJL lines. */
static int escape(rd_t *r)
{
	size_t st = r->i++;
	r->doc->nescapes++;
	if (r->i >= r->n)
		return 0;
	unsigned char c = r->s[r->i];
	if (c == '.') {
		r->i++;
		if (r->i >= r->n)
			return fail(r, st, "device-control escape cut off");
		r->i++;   /* the function letter or character */
		/* parameters: digits and ';' up to ':' (optional), within a short stretch */
		size_t e = r->i;
		while (e < r->n && e - r->i < 80 && (isdigit(r->s[e]) || r->s[e] == ';'))
			e++;
		r->i = e;
		if (r->i < r->n && r->s[r->i] == ':')
			r->i++;
		return 0;
	}
	if (c == '%') {
		r->i++;
		if (r->i < r->n && (r->s[r->i] == '-' || r->s[r->i] == '+'))
			r->i++;
		while (r->i < r->n && isdigit(r->s[r->i]))
			r->i++;
		if (r->i >= r->n || !isalpha(r->s[r->i]))
			return fail(r, st, "malformed PCL escape (ESC %% number letter)");
		r->i++;
		/* after a universal exit (ESC%-12345X) PJL lines may follow */
		while (r->i + 4 < r->n && !memcmp(r->s + r->i, "@PJL", 4)) {
			while (r->i < r->n && r->s[r->i] != '\n')
				r->i++;
			if (r->i < r->n)
				r->i++;
		}
		return 0;
	}
	if (c == 'E') {
		r->i++;
		return 0;
	}
	if (c >= 0x21 && c <= 0x2f) {   /* parameterised PCL: ESC & l 1 O, ESC * c 100 X ... */
		r->i++;
		if (r->i < r->n)
			r->i++;   /* group character */
		for (;;) {
			while (r->i < r->n && (isdigit(r->s[r->i]) || r->s[r->i] == '.' || r->s[r->i] == '+' || r->s[r->i] == '-'))
				r->i++;
			if (r->i >= r->n)
				return 0;
			unsigned char t = r->s[r->i++];
			if (t >= 'A' && t <= 'Z')
				return 0;
			if (!(t >= 'a' && t <= 'z'))
				return fail(r, st, "malformed PCL escape");
		}
	}
	r->i++;   /* a two-byte escape */
	return 0;
}

/* LB (and BL): the text up to the terminator. */
static int label(rd_t *r, const char *mn)
{
	size_t st = r->i;
	while (r->i < r->n && r->s[r->i] != r->term)
		r->i++;
	if (r->i >= r->n)
		return fail(r, st, "%s label not terminated (terminator 0x%02x, set by DT)", mn, r->term);
	size_t len = r->i - st;
	r->i++;
	if (mn[0] != 'L')
		return 0;
	hpgl_doc_t *d = r->doc;
	if (grow((void **)&d->labels, &d->caplabels, d->nlabels + 1, sizeof *d->labels))
		return nomem(r);
	char *t = malloc(len + 1);
	if (!t)
		return nomem(r);
	memcpy(t, r->s + st, len);
	t[len] = 0;
	d->labels[d->nlabels++] = (hpgl_rlabel_t){ r->pen, r->x, r->y, t, len, r->cmd_off };
	return 0;
}

static void set_scaling(rd_t *r, const double *v, int nv)
{
	if (nv < 4) {
		r->sc = 0;
		return;
	}
	int type = nv >= 5 ? (int)v[4] : 0;
	r->sc = 1;
	r->sc_xmin = v[0];
	r->sc_ymin = v[2];
	r->ox = r->p1x;
	r->oy = r->p1y;
	if (type == 2) {   /* point factor: SC xmin, xfactor, ymin, yfactor, 2 */
		r->sx = v[1];
		r->sy = v[3];
		return;
	}
	r->sc_xmax = v[1];
	r->sc_ymax = v[3];
	double dx = v[1] - v[0], dy = v[3] - v[2];
	r->sx = dx ? (r->p2x - r->p1x) / dx : 1;
	r->sy = dy ? (r->p2y - r->p1y) / dy : 1;
	if (type == 1) {   /* isotropic: the smaller factor both ways */
		double k = fabs(r->sx) < fabs(r->sy) ? fabs(r->sx) : fabs(r->sy);
		r->sx = r->sx < 0 ? -k : k;
		r->sy = r->sy < 0 ? -k : k;
	}
}

static void defaults(rd_t *r, int in)
{
	end_stroke(r);
	r->rel = 0;
	r->sc = 0;
	r->poly = 0;
	r->term = 3;
	if (in) {
		r->down = 0;
		r->p1x = 603;   /* 7475A A4 defaults for P1 and P2 (a file that uses SC without IP) */
		r->p1y = 521;
		r->p2x = 10603;
		r->p2y = 7721;
	}
}

static void note_unknown(rd_t *r, const char *mn)
{
	hpgl_doc_t *d = r->doc;
	d->nunknown++;
	char pat[4] = { mn[0], mn[1], 0, 0 };
	for (const char *p = d->unknown; (p = strstr(p, pat)); p += 2)
		if ((p == d->unknown || p[-1] == ' ') && (p[2] == ' ' || p[2] == 0))
			return;
	size_t n = strlen(d->unknown);
	if (n + 4 < sizeof d->unknown)
		snprintf(d->unknown + n, sizeof d->unknown - n, "%s%s", n ? " " : "", pat);
}

/* Polygon mode: PM0 starts, PM1 closes a contour, PM2 closes and ends. */
static int pm(rd_t *r, const double *v, int nv)
{
	int k = nv ? (int)v[0] : 0;
	r->doc->hpgl2 = 1;
	if (k == 0) {
		end_stroke(r);
		r->poly = 1;
		r->npb = r->npbs = 0;
		return start_contour(r, r->x, r->y);
	}
	if (r->poly)
		r->newc = 1;
	if (k == 2)
		r->poly = 0;
	return 0;
}

/* FP / EP: the polygon buffer's contours as strokes. */
static int polygon_out(rd_t *r, int kind)
{
	r->doc->hpgl2 = 1;
	for (size_t k = 0; k < r->npbs; k++) {
		size_t a = r->pbs[k], b = k + 1 < r->npbs ? r->pbs[k + 1] : r->npb;
		if (b - a < 2)
			continue;
		hpgl_rpt_t *p = malloc((b - a + 1) * sizeof *p);
		if (!p)
			return nomem(r);
		memcpy(p, r->pb + a, (b - a) * sizeof *p);
		size_t n = b - a;
		if (p[n - 1].x != p[0].x || p[n - 1].y != p[0].y)
			p[n++] = p[0];
		int rc = figure(r, p, n, kind);
		free(p);
		if (rc)
			return -1;
	}
	return 0;
}

static int rect(rd_t *r, const char *mn, const double *v, int nv, int relative, int kind)
{
	if (nv < 2)
		return fail(r, r->cmd_off, "%s needs two coordinates", mn);
	double x, y;
	if (relative) {
		user_len(r, v[0], v[1], &x, &y);
		x += r->x;
		y += r->y;
	} else {
		user_to_pu(r, v[0], v[1], &x, &y);
	}
	hpgl_rpt_t p[5] = { { r->x, r->y }, { x, r->y }, { x, y }, { r->x, y }, { r->x, r->y } };
	return figure(r, p, 5, kind);
}

static int wedge(rd_t *r, const char *mn, const double *v, int nv, int kind)
{
	if (nv < 3)
		return fail(r, r->cmd_off, "%s needs radius, start and sweep", mn);
	double rad, dummy;
	user_len(r, v[0], 0, &rad, &dummy);
	double chord = nv > 3 ? v[3] : 5;
	if (!(chord > 0) || chord > 180)
		chord = 5;
	int n = (int)ceil(fabs(v[2]) / chord);
	if (n < 1)
		n = 1;
	hpgl_rpt_t *p = malloc((size_t)(n + 3) * sizeof *p);
	if (!p)
		return nomem(r);
	size_t m = 0;
	p[m++] = (hpgl_rpt_t){ r->x, r->y };
	for (int k = 0; k <= n; k++) {
		double a = (v[1] + v[2] * k / n) * M_PI / 180;
		p[m++] = (hpgl_rpt_t){ r->x + rad * cos(a), r->y + rad * sin(a) };
	}
	p[m++] = (hpgl_rpt_t){ r->x, r->y };
	int rc = figure(r, p, m, kind);
	free(p);
	return rc;
}

static int command(rd_t *r, const char mn[3])
{
	double v[MAX_PARAMS];
	int nv = 0;
	const char *coord_cmds[] = { "PU", "PD", "PA", "PR", NULL };
	for (int k = 0; coord_cmds[k]; k++)
		if (!strcmp(mn, coord_cmds[k]))
			return coords(r, mn, k == 0 ? 0 : k == 1 ? 1 : -1, k == 2 ? 0 : k == 3 ? 1 : -1);
	if (!strcmp(mn, "PE"))
		return pe(r);
	if (!strcmp(mn, "LB") || !strcmp(mn, "BL"))
		return label(r, mn);
	if (!strcmp(mn, "DT")) {
		if (r->i < r->n && r->s[r->i] != ';') {
			r->term = r->s[r->i++];
			if (params(r, mn, v, &nv) < 0)
				return -1;
		} else {
			r->term = 3;
			if (r->i < r->n)
				r->i++;
		}
		return 0;
	}
	if (!strcmp(mn, "SM")) {   /* symbol mode: one character, or none */
		if (r->i < r->n && r->s[r->i] != ';' && r->s[r->i] > ' ')
			r->i++;
		if (r->i < r->n && r->s[r->i] == ';')
			r->i++;
		return 0;
	}
	if (!strcmp(mn, "CO")) {   /* comment: a quoted string */
		return params(r, mn, v, &nv) < 0 ? -1 : 0;
	}
	if (!strcmp(mn, "EP")) {
		if (params(r, mn, v, &nv) < 0)
			return -1;
		return polygon_out(r, HPGL_RS_EDGE);
	}
	int more = params(r, mn, v, &nv);
	if (more < 0)
		return -1;
	if (nv > MAX_PARAMS)
		nv = MAX_PARAMS;
	if (!strcmp(mn, "IN") || !strcmp(mn, "DF")) {
		defaults(r, mn[0] == 'I');
		if (mn[0] == 'I')
			r->x = r->y = 0;
	} else if (!strcmp(mn, "SP")) {
		end_stroke(r);
		r->pen = nv ? (int)v[0] : 0;
		r->doc->pen_selects++;
	} else if (!strcmp(mn, "IP")) {
		if (nv >= 2) {
			double dx = r->p2x - r->p1x, dy = r->p2y - r->p1y;
			r->p1x = v[0];
			r->p1y = v[1];
			r->p2x = nv >= 4 ? v[2] : v[0] + dx;
			r->p2y = nv >= 4 ? v[3] : v[1] + dy;
		}
	} else if (!strcmp(mn, "SC")) {
		set_scaling(r, v, nv);
	} else if (!strcmp(mn, "CI")) {
		if (nv < 1)
			return fail(r, r->cmd_off, "CI needs a radius");
		double rad, dummy;
		user_len(r, v[0], 0, &rad, &dummy);
		return circle(r, fabs(rad), nv > 1 ? v[1] : 5, HPGL_RS_LINE);
	} else if (!strcmp(mn, "AA") || !strcmp(mn, "AR")) {
		if (nv < 3)
			return fail(r, r->cmd_off, "%s needs a centre and a sweep", mn);
		double cx, cy;
		if (mn[1] == 'R') {
			user_len(r, v[0], v[1], &cx, &cy);
			cx += r->x;
			cy += r->y;
		} else {
			user_to_pu(r, v[0], v[1], &cx, &cy);
		}
		double rad = hypot(r->x - cx, r->y - cy), a0 = atan2(r->y - cy, r->x - cx);
		if (rad == 0)
			return 0;
		return arc_points(r, cx, cy, rad, a0, v[2], nv > 3 ? v[3] : 5);
	} else if (!strcmp(mn, "EA") || !strcmp(mn, "ER")) {
		return rect(r, mn, v, nv, mn[1] == 'R', HPGL_RS_EDGE);
	} else if (!strcmp(mn, "RA") || !strcmp(mn, "RR")) {
		return rect(r, mn, v, nv, mn[1] == 'R', HPGL_RS_FILL);
	} else if (!strcmp(mn, "EW") || !strcmp(mn, "WG")) {
		return wedge(r, mn, v, nv, mn[0] == 'E' ? HPGL_RS_EDGE : HPGL_RS_FILL);
	} else if (!strcmp(mn, "PM")) {
		return pm(r, v, nv);
	} else if (!strcmp(mn, "FP")) {
		return polygon_out(r, HPGL_RS_FILL);
	} else if (!strcmp(mn, "PW") || !strcmp(mn, "WU") || !strcmp(mn, "NP") || !strcmp(mn, "PC") ||
			!strcmp(mn, "BP") || !strcmp(mn, "PS") || !strcmp(mn, "MC") || !strcmp(mn, "LA") ||
			!strcmp(mn, "RF") || !strcmp(mn, "SV") || !strcmp(mn, "TR") || !strcmp(mn, "SD") ||
			!strcmp(mn, "AD") || !strcmp(mn, "SB") || !strcmp(mn, "RO") || !strcmp(mn, "PG")) {
		r->doc->hpgl2 |= strcmp(mn, "RO") && strcmp(mn, "PG");
	} else if (!strcmp(mn, "FT") || !strcmp(mn, "PT") || !strcmp(mn, "LT") || !strcmp(mn, "IW") ||
			!strcmp(mn, "SI") || !strcmp(mn, "SR") || !strcmp(mn, "DI") || !strcmp(mn, "DR") ||
			!strcmp(mn, "VS") || !strcmp(mn, "LO") || !strcmp(mn, "CA") || !strcmp(mn, "CS") ||
			!strcmp(mn, "SA") || !strcmp(mn, "SS") || !strcmp(mn, "UL") || !strcmp(mn, "CP") ||
			!strcmp(mn, "XT") || !strcmp(mn, "YT") || !strcmp(mn, "PB") || !strcmp(mn, "TL") ||
			!strcmp(mn, "FS") || !strcmp(mn, "EC") || !strcmp(mn, "OI") || !strcmp(mn, "OS") ||
			!strcmp(mn, "OA") || !strcmp(mn, "OE") || !strcmp(mn, "OP") || !strcmp(mn, "OW") ||
			!strcmp(mn, "ES") || !strcmp(mn, "CT")) {
		/* state that does not change the strokes' geometry here */
	} else {
		note_unknown(r, mn);
	}
	while (more > 0) {   /* the rest of an over-long list of a skipped command */
		more = params(r, mn, v, &nv);
		if (more < 0)
			return -1;
	}
	return 0;
}

int hpgl_read_mem(const void *buf, size_t len, const char *name, hpgl_doc_t *doc, char *err,
		size_t errlen)
{
	memset(doc, 0, sizeof *doc);
	rd_t r;
	memset(&r, 0, sizeof r);
	r.s = buf;
	r.n = len;
	r.name = name;
	r.err = err;
	r.errlen = errlen;
	r.doc = doc;
	defaults(&r, 1);
	int rc = 0;
	size_t stray = SIZE_MAX;   /* the first byte that was no command, since the last command */
	while (r.i < r.n && rc == 0) {
		unsigned char c = r.s[r.i];
		if (c == 0x1b) {
			rc = escape(&r);
			continue;
		}
		if (is_sep(c) || c == ';' || c < 0x20 || c == 0x7f) {
			r.i++;
			continue;
		}
		if (!isalpha(c) || r.i + 1 >= r.n || !isalpha(r.s[r.i + 1])) {
			if (stray == SIZE_MAX)
				stray = r.i;
			r.i++;
			continue;
		}
		if (stray != SIZE_MAX) {
			rc = fail(&r, stray, "expected a two-letter HP-GL command, got byte 0x%02x", r.s[stray]);
			break;
		}
		char mn[3] = { (char)toupper(c), (char)toupper(r.s[r.i + 1]), 0 };
		r.cmd = doc->ncmds++;
		r.cmd_off = r.i;
		r.i += 2;
		rc = command(&r, mn);
	}
	if (rc == 0 && stray != SIZE_MAX)
		doc->trailing = r.n - stray;
	end_stroke(&r);
	free(r.pb);
	free(r.pbs);
	return rc;
}

int hpgl_read_stream(FILE *f, const char *name, hpgl_doc_t *doc, char *err, size_t errlen)
{
	char *buf = NULL;
	size_t n = 0, cap = 0;
	for (;;) {
		if (n == cap) {
			size_t c = cap ? 2 * cap : 65536;
			char *b = realloc(buf, c);
			if (!b) {
				free(buf);
				memset(doc, 0, sizeof *doc);
				snprintf(err, errlen, "%s: out of memory", name);
				return -1;
			}
			buf = b;
			cap = c;
		}
		size_t k = fread(buf + n, 1, cap - n, f);
		n += k;
		if (k == 0)
			break;
	}
	if (ferror(f)) {
		free(buf);
		memset(doc, 0, sizeof *doc);
		snprintf(err, errlen, "%s: read error", name);
		return -1;
	}
	int rc = hpgl_read_mem(buf, n, name, doc, err, errlen);
	free(buf);
	return rc;
}

void hpgl_doc_free(hpgl_doc_t *doc)
{
	for (size_t k = 0; k < doc->nlabels; k++)
		free(doc->labels[k].text);
	free(doc->labels);
	free(doc->pts);
	free(doc->strokes);
	memset(doc, 0, sizeof *doc);
}

double hpgl_doc_length(const hpgl_doc_t *doc, int kind)
{
	double t = 0;
	for (size_t k = 0; k < doc->nstrokes; k++) {
		const hpgl_rstroke_t *s = &doc->strokes[k];
		if (kind >= 0 && s->kind != kind)
			continue;
		for (size_t i = 1; i < s->n; i++)
			t += hypot(doc->pts[s->start + i].x - doc->pts[s->start + i - 1].x,
				doc->pts[s->start + i].y - doc->pts[s->start + i - 1].y);
	}
	return t;
}
