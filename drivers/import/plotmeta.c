/* plotmeta.c: GNU plotutils metafiles (portable and binary) replayed as Locus meta statements. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "import/plotmeta.h"

#define PAGE 570
#define MAXPTS 100000

/* Arguments of each op code: i integer, f float (a float in the binary form), s a string to the
 * newline, c one byte, d a dash list (count, that many numbers, offset); NULL: unknown. */
static const char *sig(int op)
{
	switch (op) {
	case 'o': case 'x': case 'e': case 'E': case ']': case 'k': case 'O': case 'U': return "";
	case 's': case 'l': case 'I': case 'B': case 'H': return "iiii";
	case '*': case '8': case '9': case '3': case '4': return "ffff";
	case ':': case 'a': case 'A': case '?': case '/': case 'q': case 'r': return "iiiiii";
	case ';': case '1': case '2': case '}': case '|': case '`': case '\'': case '\\': case 'j': return "ffffff";
	case 'm': case 'M': case 'n': case 'N': case 'p': case 'P': return "ii";
	case '$': case '%': case ')': case '_': case '^': case '&': return "ff";
	case 'c': case 'G': return "iii";
	case '5': case '6': return "fff";
	case '+': case '=': return "iiiii";
	case '{': case '[': return "fffff";
	case 'y': case 'z': return "iiiiiiii";
	case ',': case '.': return "ffffffff";
	case 't': case 'f': case 'K': case 'J': case 'g': case 'F': case '#': return "s";
	case 'T': return "ccs";
	case 'W': case 'S': case 'R': case 'L': case 'h': case 'b': return "i";
	case '0': case '7': case '(': case 'i': return "f";
	case '-': case 'D': case '~': return "iii";
	case 'Y': case 'Z': return "iiii";
	case '!': case '@': return "ffif";
	case 'd': return "d";
	case 'w': return "D";
	default: return NULL;
	}
}

typedef struct {
	const unsigned char *b;
	size_t n, at;
	int portable;
	const char *name;
	char *err;
	size_t errlen;
	meta_writer_t *w;
	/* state */
	double m[6];                    /* user to unit square: x' = m0 x + m2 y + m4, y' = m1 x + m3 y + m5 */
	double cx, cy;                  /* current point, user units */
	double *pts;                    /* the open path, page pixels */
	size_t npts, cap;
	int open;                       /* a page is open */
	meta_rgb_t pen, fillc, bg;
	int filltype, pentype;
	double lw, fontsize, angle;
	int wrc;                        /* a writer error */
} pm_t;

static int fail(pm_t *p, size_t at, const char *what)
{
	snprintf(p->err, p->errlen, "%s: byte %zu: %s", p->name, at, what);
	return -65;
}

static void skip_blank(pm_t *p)
{
	while (p->at < p->n && (p->b[p->at] == ' ' || p->b[p->at] == '\t'))
		p->at++;
}

/* One number: text in the portable form, 4 bytes (int or float) in the binary. */
static int num(pm_t *p, int isfloat, double *v)
{
	if (!p->portable) {
		if (p->n - p->at < 4)
			return fail(p, p->at, "truncated operand");
		uint32_t u = (uint32_t)p->b[p->at] | (uint32_t)p->b[p->at + 1] << 8 |
			(uint32_t)p->b[p->at + 2] << 16 | (uint32_t)p->b[p->at + 3] << 24;
		p->at += 4;
		if (isfloat) {
			float f;
			char t[32];
			memcpy(&f, &u, 4);
			/* as the portable form prints it (%g, 6 digits), so both forms give one drawing */
			snprintf(t, sizeof t, "%g", (double)f);
			*v = strtod(t, NULL);
		} else {
			*v = (int32_t)u;
		}
		if (!isfinite(*v))
			return fail(p, p->at - 4, "not a finite number");
		return 0;
	}
	skip_blank(p);
	char buf[64];
	size_t k = 0;
	while (p->at < p->n && k + 1 < sizeof buf && strchr("0123456789+-.eE", p->b[p->at]))
		buf[k++] = (char)p->b[p->at++];
	buf[k] = 0;
	char *e;
	*v = strtod(buf, &e);
	if (!k || *e || !isfinite(*v))
		return fail(p, p->at - k, "expected a number");
	return 0;
}

/* A string to the newline (the newline consumed); *s points into the input, *len its length. */
static int str(pm_t *p, const char **s, size_t *len)
{
	if (p->portable && p->at < p->n && p->b[p->at] == ' ')
		p->at++;
	const unsigned char *nl = memchr(p->b + p->at, '\n', p->n - p->at);
	if (!nl)
		return fail(p, p->at, "string without its newline");
	*s = (const char *)p->b + p->at;
	*len = (size_t)(nl - (p->b + p->at));
	p->at = (size_t)(nl - p->b) + 1;
	return 0;
}

static void xf(const pm_t *p, double x, double y, double *px, double *py)
{
	*px = (p->m[0] * x + p->m[2] * y + p->m[4]) * PAGE;
	*py = (p->m[1] * x + p->m[3] * y + p->m[5]) * PAGE;
}

/* xf, refusing a point the meta file cannot hold (beyond a million pixels off the page). */
static int xfc(pm_t *p, double x, double y, double *px, double *py)
{
	xf(p, x, y, px, py);
	if (!(fabs(*px) <= 1e6 && fabs(*py) <= 1e6))
		return fail(p, p->at, "a point maps beyond a million pixels from the page");
	return 0;
}

static int add(pm_t *p, double x, double y)
{
	if (p->npts == p->cap) {
		if (p->cap >= MAXPTS)
			return fail(p, p->at, "path of more than 100000 points");
		size_t nc = p->cap ? p->cap * 2 : 64;
		double *q = realloc(p->pts, nc * 2 * sizeof *q);
		if (!q) {
			snprintf(p->err, p->errlen, "%s: out of memory", p->name);
			return -70;
		}
		p->pts = q;
		p->cap = nc;
	}
	if (xfc(p, x, y, &p->pts[2 * p->npts], &p->pts[2 * p->npts + 1]))
		return -65;
	p->npts++;
	p->cx = x, p->cy = y;
	return 0;
}

#define W(x) do { int r_ = (x); if (r_ < 0) { p->wrc = r_; return r_; } } while (0)

/* Draw the open path: filled when filltype says so, stroked unless pentype is 0. */
static int flush(pm_t *p, int closed)
{
	if (p->npts < 2 || !p->open) {
		p->npts = 0;
		return 0;
	}
	for (int pass = 0; pass < 2; pass++) {
		if (pass == 0 && !p->filltype)
			continue;
		if (pass == 1 && !p->pentype)
			continue;
		W(meta_colour(p->w, pass ? p->pen : p->fillc));
		W(pass ? meta_stroke(p->w) : meta_fill(p->w));
		W(meta_move(p->w, p->pts[0], p->pts[1]));
		for (size_t k = 1; k < p->npts; k++)
			W(meta_draw(p->w, p->pts[2 * k], p->pts[2 * k + 1]));
		if (closed || pass == 0)
			W(meta_close(p->w));
		W(meta_end(p->w));
	}
	p->npts = 0;
	return 0;
}

/* An elliptic arc about (xc, yc) with axes (rx, ry) rotated rot degrees, from angle a0 by
 * sweep (radians), flattened to 2 degrees a step, in user space. */
static int arcpath(pm_t *p, double xc, double yc, double rx, double ry, double rot, double a0, double sweep, int closed)
{
	int rc = flush(p, 0);
	if (rc)
		return rc;
	int steps = (int)ceil(fabs(sweep) / (M_PI / 90));
	if (steps < 2)
		steps = 2;
	double cr = cos(rot * M_PI / 180), sr = sin(rot * M_PI / 180);
	for (int k = 0; k <= steps; k++) {
		double t = a0 + sweep * k / steps, ex = rx * cos(t), ey = ry * sin(t);
		if ((rc = add(p, xc + ex * cr - ey * sr, yc + ex * sr + ey * cr)))
			return rc;
	}
	return flush(p, closed);
}

/* A Bezier curve of 3 or 4 control points (user space) added to the path. */
static int bezier(pm_t *p, const double *c, int n)
{
	int rc;
	if (p->npts == 0 && (rc = add(p, c[0], c[1])))
		return rc;
	for (int k = 1; k <= 32; k++) {
		double t = k / 32.0, u = 1 - t, x, y;
		if (n == 3) {
			x = u * u * c[0] + 2 * u * t * c[2] + t * t * c[4];
			y = u * u * c[1] + 2 * u * t * c[3] + t * t * c[5];
		} else {
			x = u * u * u * c[0] + 3 * u * u * t * c[2] + 3 * u * t * t * c[4] + t * t * t * c[6];
			y = u * u * u * c[1] + 3 * u * u * t * c[3] + 3 * u * t * t * c[5] + t * t * t * c[7];
		}
		if ((rc = add(p, x, y)))
			return rc;
	}
	return 0;
}

/* The scale of the map (for widths and font sizes): the square root of its determinant. */
static double mscale(const pm_t *p)
{
	return sqrt(fabs(p->m[0] * p->m[3] - p->m[1] * p->m[2])) * PAGE;
}

static void space(pm_t *p, double x0, double y0, double x1, double y1, double x2, double y2)
{
	/* (x0,y0) to (0,0), (x1,y1) to (1,0), (x2,y2) to (0,1): solve the affine map */
	double ax = x1 - x0, ay = y1 - y0, bx = x2 - x0, by = y2 - y0, det = ax * by - ay * bx;
	if (det == 0)
		return;
	p->m[0] = by / det, p->m[2] = -bx / det;
	p->m[1] = -ay / det, p->m[3] = ax / det;
	p->m[4] = -(p->m[0] * x0 + p->m[2] * y0);
	p->m[5] = -(p->m[1] * x0 + p->m[3] * y0);
}

static meta_rgb_t rgb48(const double *a)
{
	unsigned c[3];
	for (int k = 0; k < 3; k++) {
		double v = a[k] < 0 ? 0 : a[k] > 65535 ? 65535 : a[k];
		c[k] = (unsigned)v >> 8;
	}
	return (meta_rgb_t)(c[0] << 16 | c[1] << 8 | c[2]);
}

static void reset(pm_t *p)
{
	static const double unit[6] = { 1.0 / 4096, 0, 0, 1.0 / 4096, 0, 0 };   /* space 0 0 4096 4096 */
	memcpy(p->m, unit, sizeof unit);
	p->cx = p->cy = 0;
	p->npts = 0;
	p->pen = 0x000000, p->fillc = 0x000000, p->bg = 0xffffff;
	p->filltype = 0, p->pentype = 1;
	p->lw = -1, p->fontsize = -1, p->angle = 0;
}

static int op(pm_t *p, int c, const double *a, const char *s, size_t slen, const unsigned char *ch)
{
	int rc = 0;
	double x, y;
	switch (c) {
	case 'o':
		if (p->open)
			return fail(p, p->at - 1, "openpl inside an open page");
		reset(p);
		p->open = 1;
		W(meta_page(p->w, PAGE, PAGE));
		W(meta_clear(p->w, p->bg));
		W(meta_cap(p->w, META_CAP_BUTT));
		W(meta_width(p->w, 1));
		return 0;
	case 'x':
		if (!p->open)
			return fail(p, p->at - 1, "closepl without openpl");
		if ((rc = flush(p, 0)))
			return rc;
		p->open = 0;
		W(meta_end_page(p->w));
		return 0;
	case '#':
		return 0;
	}
	if (!p->open)
		return fail(p, p->at - 1, "drawing outside openpl .. closepl");
	switch (c) {
	case 'e': rc = flush(p, 0); if (!rc) W(meta_clear(p->w, p->bg)); break;
	case 's': case '*': space(p, a[0], a[1], a[2], a[1], a[0], a[3]); break;
	case ':': case ';': space(p, a[0], a[1], a[2], a[3], a[4], a[5]); break;
	case 'j': memcpy(p->m, a, sizeof p->m); for (int k = 0; k < 6; k++) p->m[k] = a[k]; break;
	case '\\': {
		double n[6] = { a[0] * p->m[0] + a[1] * p->m[2], a[0] * p->m[1] + a[1] * p->m[3],
			a[2] * p->m[0] + a[3] * p->m[2], a[2] * p->m[1] + a[3] * p->m[3],
			a[4] * p->m[0] + a[5] * p->m[2] + p->m[4], a[4] * p->m[1] + a[5] * p->m[3] + p->m[5] };
		memcpy(p->m, n, sizeof n);
		break;
	}
	case 'm': case '$': rc = flush(p, 0); p->cx = a[0], p->cy = a[1]; break;
	case 'M': case '%': rc = flush(p, 0); p->cx += a[0], p->cy += a[1]; break;
	case 'n': case ')': case 'N': case '_':
		x = c == 'n' || c == ')' ? a[0] : p->cx + a[0];
		y = c == 'n' || c == ')' ? a[1] : p->cy + a[1];
		if (p->npts == 0)
			rc = add(p, p->cx, p->cy);
		if (!rc)
			rc = add(p, x, y);
		break;
	case 'l': case '8': case 'I': case '9': {
		double o = c == 'I' || c == '9';
		rc = flush(p, 0);
		if (!rc)
			rc = add(p, a[0] + o * p->cx, a[1] + o * p->cy);
		if (!rc)
			rc = add(p, a[2] + o * p->cx, a[3] + o * p->cy);
		break;
	}
	case 'p': case '^': case 'P': case '&': {
		double o = c == 'P' || c == '&';
		rc = flush(p, 0);
		x = a[0] + o * p->cx, y = a[1] + o * p->cy;
		double px, py;
		if (xfc(p, x, y, &px, &py))
			return -65;
		W(meta_colour(p->w, p->pen));   /* a point: a dot of one pixel */
		W(meta_fill(p->w));
		W(meta_circle(p->w, px, py, 0.6));
		W(meta_end(p->w));
		p->cx = x, p->cy = y;
		break;
	}
	case 'c': case '5': case 'G': case '6': {
		double o = c == 'G' || c == '6';
		rc = arcpath(p, a[0] + o * p->cx, a[1] + o * p->cy, a[2], a[2], 0, 0, 2 * M_PI, 1);
		p->cx = a[0] + o * p->cx, p->cy = a[1] + o * p->cy;
		break;
	}
	case '+': case '{': case '=': case '[': {
		double o = c == '=' || c == '[';
		rc = arcpath(p, a[0] + o * p->cx, a[1] + o * p->cy, a[2], a[3], a[4], 0, 2 * M_PI, 1);
		break;
	}
	case 'a': case '1': case 'A': case '2': case '?': case '}': case '/': case '|': {
		double o = c == 'A' || c == '2' || c == '/' || c == '|', xc = a[0] + o * p->cx, yc = a[1] + o * p->cy;
		double x0 = a[2] + o * p->cx - xc, y0 = a[3] + o * p->cy - yc, x1 = a[4] + o * p->cx - xc, y1 = a[5] + o * p->cy - yc;
		if (c == 'a' || c == '1' || c == 'A' || c == '2') {   /* circular, counterclockwise */
			double r = hypot(x0, y0), t0 = atan2(y0, x0), t1 = atan2(y1, x1), sw = t1 - t0;
			while (sw <= 0)
				sw += 2 * M_PI;
			rc = flush(p, 0);
			if (!rc && p->npts == 0)
				rc = arcpath(p, xc, yc, r, r, 0, t0, sw, 0);
		} else {   /* a quarter ellipse: p0 and p1 the ends of conjugate semi-diameters */
			rc = flush(p, 0);
			for (int k = 0; k <= 45 && !rc; k++) {
				double t = M_PI / 2 * k / 45;
				rc = add(p, xc + x0 * cos(t) + x1 * sin(t), yc + y0 * cos(t) + y1 * sin(t));
			}
			if (!rc)
				rc = flush(p, 0);
		}
		p->cx = x1 + xc, p->cy = y1 + yc;
		break;
	}
	case 'B': case '3': case 'H': case '4': {
		double o = c == 'H' || c == '4', x0 = a[0] + o * p->cx, y0 = a[1] + o * p->cy, x1 = a[2] + o * p->cx, y1 = a[3] + o * p->cy;
		rc = flush(p, 0);
		if (!rc) rc = add(p, x0, y0);
		if (!rc) rc = add(p, x1, y0);
		if (!rc) rc = add(p, x1, y1);
		if (!rc) rc = add(p, x0, y1);
		if (!rc) rc = flush(p, 1);
		p->cx = (x0 + x1) / 2, p->cy = (y0 + y1) / 2;
		break;
	}
	case 'q': case '`': case 'r': case '\'': case 'y': case ',': case 'z': case '.': {
		int nc = c == 'q' || c == '`' || c == 'r' || c == '\'' ? 3 : 4;
		double o = c == 'r' || c == '\'' || c == 'z' || c == '.', cc[8];
		for (int k = 0; k < 2 * nc; k++)
			cc[k] = a[k] + o * (k % 2 ? p->cy : p->cx);
		if (p->npts && (fabs(cc[0] - p->cx) > 1e-9 || fabs(cc[1] - p->cy) > 1e-9))
			rc = flush(p, 0);
		if (!rc)
			rc = bezier(p, cc, nc);
		break;
	}
	case 'E': case ']': rc = flush(p, 0); break;
	case 'k': rc = flush(p, 1); break;
	case '-': rc = flush(p, 0); p->pen = rgb48(a); break;
	case 'D': rc = flush(p, 0); p->fillc = rgb48(a); break;
	case '~': p->bg = rgb48(a); break;
	case 'L': rc = flush(p, 0); p->filltype = (int)a[0]; break;
	case 'h': rc = flush(p, 0); p->pentype = (int)a[0]; break;
	case 'W': case '0':
		rc = flush(p, 0);
		p->lw = a[0];
		if (!rc)
			W(meta_width(p->w, a[0] <= 0 ? 1 : fmin(fmax(a[0] * mscale(p), 0), 1000)));
		break;
	case 'S': case '7': p->fontsize = a[0]; break;
	case 'R': case '(': p->angle = a[0]; break;
	case 't': case 'T': {
		rc = flush(p, 0);
		double px, py, size = (p->fontsize > 0 ? p->fontsize * mscale(p) : PAGE / 50.0) * 0.7;
		if (xfc(p, p->cx, p->cy, &px, &py))
			return -65;
		char t[4097];
		size_t k = 0;
		for (; k < slen && k < 4096; k++)
			t[k] = (unsigned char)s[k] < 32 || s[k] == 127 ? ' ' : s[k];
		t[k] = 0;
		if (c == 'T') {   /* justification: the stroke font's advance is about 0.8 of the size */
			double wdt = 0.8 * size * (double)k, dx = ch[0] == 'c' ? -wdt / 2 : ch[0] == 'r' ? -wdt : 0;
			double dy = ch[1] == 'c' || ch[1] == 'x' ? -size / 2 : ch[1] == 't' ? -size : 0;
			double ca = cos(p->angle * M_PI / 180), sa = sin(p->angle * M_PI / 180);
			px += dx * ca - dy * sa, py += dx * sa + dy * ca;
		}
		if (!rc && k && !(fabs(px) <= 1e6 && fabs(py) <= 1e6))
			return fail(p, p->at, "a label starts beyond a million pixels from the page");
		if (!rc && k)
			W(meta_text(p->w, px, py, fmin(fmax(size, 0), 10000), fmod(p->angle, 360), t));
		break;
	}
	default: break;   /* linemod, capmod, joinmod, fillmod, fontname, orientation, markers, dashes,
	                   * save/restore, miter limit: no picture of their own here */
	}
	return rc;
}

int plotmeta_is(const void *buf, size_t n)
{
	return n >= 8 && (memcmp(buf, "#PLOT 1\n", 8) == 0 || memcmp(buf, "#PLOT 2\n", 8) == 0);
}

int plotmeta_import(const void *buf, size_t n, const char *name, meta_writer_t *w, char *err,
		size_t errlen)
{
	pm_t p;
	memset(&p, 0, sizeof p);
	p.b = buf, p.n = n, p.name = name, p.err = err, p.errlen = errlen, p.w = w;
	if (!plotmeta_is(buf, n)) {
		snprintf(err, errlen, "%s: byte 0: expected \"#PLOT 1\" or \"#PLOT 2\"", name);
		return -65;
	}
	p.portable = p.b[6] == '2';
	p.at = 8;
	int rc = 0;
	size_t pages = 0;
	while (!rc) {
		if (p.portable)
			while (p.at < p.n && (p.b[p.at] == '\n' || p.b[p.at] == ' '))
				p.at++;
		if (p.at >= p.n)
			break;
		int c = p.b[p.at++];
		const char *sg = sig(c);
		if (!sg) {
			rc = fail(&p, p.at - 1, "unknown plotutils op code");
			break;
		}
		double a[64];
		size_t na = 0, slen = 0;
		const char *s = NULL;
		unsigned char ch[2] = { 'l', 'x' };
		for (const char *q = sg; *q && !rc; q++) {
			if (*q == 'i' || *q == 'f')
				rc = num(&p, *q == 'f', &a[na++]);
			else if (*q == 's')
				rc = str(&p, &s, &slen);
			else if (*q == 'c') {
				if (p.at >= p.n)
					rc = fail(&p, p.at, "truncated label justification");
				else
					ch[q - sg] = p.b[p.at++];
			} else {   /* dash list: count (an integer), numbers, offset */
				double cnt;
				rc = num(&p, 0, &cnt);
				if (!rc && (cnt < 0 || cnt > 60))
					rc = fail(&p, p.at, "dash list of more than 60 lengths");
				for (int k = 0; !rc && k <= (int)cnt; k++) {
					double v;
					rc = num(&p, *q == 'D', &v);
				}
			}
		}
		if (!rc && p.portable && *sg && sg[strlen(sg) - 1] != 's') {   /* the argument list's newline */
			skip_blank(&p);
			if (p.at < p.n && p.b[p.at] != '\n')
				rc = fail(&p, p.at, "expected the end of the operand list");
		}
		if (!rc) {
			rc = op(&p, c, a, s, slen, ch);
			pages += c == 'x';
		}
	}
	if (!rc && p.open)
		rc = fail(&p, p.n, "the last page has no closepl");
	if (!rc && pages == 0)
		rc = fail(&p, p.n, "no page (openpl .. closepl)");
	free(p.pts);
	if (p.wrc) {
		snprintf(err, errlen, "%s", meta_writer_error(w));
		return p.wrc == META_ENOMEM ? -70 : p.wrc == META_EIO ? -74 : -65;
	}
	return rc;
}
