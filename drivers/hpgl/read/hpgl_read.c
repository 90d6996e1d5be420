/* hpgl_read.c: HP-GL / HP-GL/2 reader: commands, parameters, PE data and escapes into strokes. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "hpgl/read/hpgl_read_int.h"

#define MAX_PARAMS 64   /* parameters kept per command (longer coordinate lists go pair by pair) */

/* ---- lexing ---- */

static int is_sep(unsigned char c)
{
	return hpgl_lex_sep(c);
}

/* Read the numeric parameters of a command up to ';', a letter, ESC or the end. */
static int params(hpgl_rd_t *r, const char *mn, double *v, int *nv)
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
		if (hpgl_lex_letter(c) || c == 0x1b)
			return 0;
		if (c == '"') {   /* a quoted string parameter (CO, DL labels): skipped */
			size_t e = r->i + 1;
			while (e < r->n && r->s[e] != '"')
				e++;
			if (e >= r->n)
				return hpgl_rd_fail(r, r->i, "unterminated string in %s", mn);
			r->i = e + 1;
			continue;
		}
		if (!hpgl_lex_numchar(c))
			return hpgl_rd_fail(r, r->i, "unexpected byte 0x%02x in the parameters of %s (expected a number, ',' or ';')", c, mn);
		size_t st = r->i, digits;
		r->i = hpgl_lex_number(r->s, r->n, st, &digits);
		if (!digits)
			return hpgl_rd_fail(r, st, "malformed number in the parameters of %s", mn);
		double x = hpgl_lex_value(r->s + st, r->i - st);
		if (!isfinite(x) || fabs(x) > 1e12)
			return hpgl_rd_fail(r, st, "number out of range in %s", mn);
		if (*nv < MAX_PARAMS)
			v[*nv] = x;
		(*nv)++;
		if (*nv > MAX_PARAMS && mn[0] != 'P' && strcmp(mn, "PE"))
			return hpgl_rd_fail(r, st, "more than %d parameters for %s", MAX_PARAMS, mn);
		/* long coordinate lists are handled pair by pair by the caller */
		if (*nv == MAX_PARAMS && (mn[0] == 'P' || !strcmp(mn, "EP")))
			return 1;   /* more to come */
	}
}

/* ---- commands ---- */

static int coords(hpgl_rd_t *r, const char *mn, int pen, int mode)
{
	double v[MAX_PARAMS];
	int nv, more;
	size_t st = r->i;
	if (pen >= 0) {
		if (!(pen && r->down))   /* PD after PD goes on drawing: the pen stays down */
			hpgl_rd_end_stroke(r);
		r->down = pen;
	}
	if (mode >= 0)
		r->rel = mode;
	do {
		more = params(r, mn, v, &nv);
		if (more < 0)
			return -1;
		if (nv % 2)
			return hpgl_rd_fail(r, st, "%s with an odd number of coordinates (%d)", mn, nv);
		for (int k = 0; k < nv && k < MAX_PARAMS; k += 2) {
			double x, y;
			if (r->rel) {
				hpgl_rd_user_len(r, v[k], v[k + 1], &x, &y);
				x += r->x;
				y += r->y;
			} else {
				hpgl_rd_user_to_pu(r, v[k], v[k + 1], &x, &y);
			}
			if (hpgl_rd_move_to(r, x, y))
				return -1;
			if (r->sm && !r->poly) {   /* SM: the symbol at each point */
				unsigned char c = r->sm;
				if (hpgl_rd_label(r, &c, 1, 1))
					return -1;
			}
		}
	} while (more);
	return 0;
}

/* PE: encoded polyline (HP-GL/2). */
static int pe(hpgl_rd_t *r)
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
			return hpgl_rd_fail(r, r->i - 1, "bad byte 0x%02x in PE data", c);
		}
		int term, digit;
		if (seven) {
			if (c > 126)
				return hpgl_rd_fail(r, r->i - 1, "byte 0x%02x in 7-bit PE data", c);
			term = c >= 95;
			digit = term ? c - 95 : c - 63;
		} else {
			term = c >= 191;
			digit = term ? c - 191 : c - 63;
		}
		if (shift > 60)
			return hpgl_rd_fail(r, r->i - 1, "PE number too long");
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
			hpgl_rd_end_stroke(r);
			r->pen = hpgl_rd_int(x);
			r->doc->pen_selects++;
			select = 0;
			continue;
		}
		if (select == 2) {   /* fractional bits */
			if (x < 0 || x > 26)
				return hpgl_rd_fail(r, r->i - 1, "PE fractional bits %g out of range", x);
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
			hpgl_rd_user_to_pu(r, val[0], val[1], &X, &Y);
		} else {
			hpgl_rd_user_len(r, val[0], val[1], &X, &Y);
			X += r->x;
			Y += r->y;
		}
		if (up)
			hpgl_rd_end_stroke(r);
		r->down = !up;
		if (hpgl_rd_move_to(r, X, Y))
			return -1;
		up = absn = 0;
	}
	if (nval || shift)
		return hpgl_rd_fail(r, st, "PE data ends inside a number or a coordinate pair");
	hpgl_rd_end_stroke(r);   /* the pen stays as the last pair left it */
	return 0;
}

/* Device-control (ESC . X [params] [:]), PCL (ESC % -12345 X, ESC E, ESC & l 1 O ...), PJL lines. */
static int escape(hpgl_rd_t *r)
{
	size_t st = r->i++;
	r->doc->nescapes++;
	if (r->i >= r->n)
		return 0;
	unsigned char c = r->s[r->i];
	if (c == '.') {
		r->i++;
		if (r->i >= r->n)
			return hpgl_rd_fail(r, st, "device-control escape cut off");
		r->i++;   /* the function letter or character */
		/* parameters: digits and ';' up to ':' (optional), within a short stretch */
		size_t e = r->i;
		while (e < r->n && e - r->i < 80 && (hpgl_lex_digit(r->s[e]) || r->s[e] == ';'))
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
		while (r->i < r->n && hpgl_lex_digit(r->s[r->i]))
			r->i++;
		if (r->i >= r->n || !hpgl_lex_letter(r->s[r->i]))
			return hpgl_rd_fail(r, st, "malformed PCL escape (ESC %% number letter)");
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
			while (r->i < r->n && (hpgl_lex_digit(r->s[r->i]) || r->s[r->i] == '.' || r->s[r->i] == '+' || r->s[r->i] == '-'))
				r->i++;
			if (r->i >= r->n)
				return 0;
			unsigned char t = r->s[r->i++];
			if (t >= 'A' && t <= 'Z')
				return 0;
			if (!(t >= 'a' && t <= 'z'))
				return hpgl_rd_fail(r, st, "malformed PCL escape");
		}
	}
	r->i++;   /* a two-byte escape */
	return 0;
}

/* LB (and BL): the text up to the terminator. */
static int label(hpgl_rd_t *r, const char *mn)
{
	size_t st = r->i;
	while (r->i < r->n && r->s[r->i] != r->term)
		r->i++;
	if (r->i >= r->n)
		return hpgl_rd_fail(r, st, "%s label not terminated (terminator 0x%02x, set by DT)", mn, r->term);
	size_t len = r->i - st;
	r->i++;
	if (mn[0] != 'L') {   /* BL: kept for PB */
		unsigned char *b = malloc(len + 1);
		if (!b)
			return hpgl_rd_nomem(r);
		memcpy(b, r->s + st, len);
		free(r->bl);
		r->bl = b;
		r->nbl = len;
		return 0;
	}
	hpgl_rd_end_stroke(r);
	return hpgl_rd_label(r, r->s + st, len, 0);
}

static void note_unknown(hpgl_rd_t *r, const char *mn)
{
	hpgl_doc_t *d = r->doc;
	d->nunknown++;
	char pat[4] = { mn[0], mn[1], 0, 0 };
	for (const char *p = d->unknown; (p = strstr(p, pat)); p += 2)
		if ((p == d->unknown || p[-1] == ' ') && (p[2] == ' ' || p[2] == 0))
			return;
	if (r->tolerant)   /* the first of each mnemonic */
		hpgl_rd_warn(r, r->cmd_off, "unknown command %s skipped with its parameters", pat);
	size_t n = strlen(d->unknown);
	if (n + 4 < sizeof d->unknown)
		snprintf(d->unknown + n, sizeof d->unknown - n, "%s%s", n ? " " : "", pat);
}

/* Polygon mode: PM0 starts, PM1 closes a contour, PM2 closes and ends. */
static int command(hpgl_rd_t *r, const char mn[3])
{
	double v[MAX_PARAMS];
	int nv = 0;
	int k = hpgl_lex_coord(mn);
	if (k >= 0)
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
			r->term = HPGL_LEX_TERM_DEFAULT;
			if (r->i < r->n)
				r->i++;
		}
		return 0;
	}
	if (!strcmp(mn, "SM")) {   /* symbol mode: one character, or none */
		r->sm = 0;
		if (r->i < r->n && r->s[r->i] != ';' && r->s[r->i] > ' ')
			r->sm = r->s[r->i++];
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
		return hpgl_rd_polygon_out(r, HPGL_RS_EDGE);
	}
	int more = params(r, mn, v, &nv);
	if (more < 0)
		return -1;
	if (nv > MAX_PARAMS)
		nv = MAX_PARAMS;
	if (!strcmp(mn, "IN") || !strcmp(mn, "DF")) {
		hpgl_rd_defaults(r, mn[0] == 'I');
		if (mn[0] == 'I')
			r->x = r->y = 0;
	} else if (!strcmp(mn, "SP")) {
		hpgl_rd_end_stroke(r);
		r->pen = nv ? hpgl_rd_int(v[0]) : 0;
		r->doc->pen_selects++;
	} else if (!strcmp(mn, "IP")) {
		r->ip_set = nv >= 2;
		if (nv >= 2) {
			/* only P1 given: P2 keeps its offset from P1 (the HP-GL/2 reference; hp2xx
			 * leaves P2 where it was, which turns a circle in user units into an ellipse) */
			double dx = r->p2x - r->p1x, dy = r->p2y - r->p1y;
			r->p1x = v[0];
			r->p1y = v[1];
			r->p2x = nv >= 4 ? v[2] : v[0] + dx;
			r->p2y = nv >= 4 ? v[3] : v[1] + dy;
		} else if (nv == 0) {   /* IP;: P1 and P2 back where IN puts them */
			hpgl_rd_default_p1p2(r);
		}
		if (r->sc && nv != 1)   /* as a plotter: the user units follow P1 and P2 */
			hpgl_rd_set_scaling(r, r->sc_v, r->sc_nv);
	} else if (!strcmp(mn, "SC")) {
		hpgl_rd_set_scaling(r, v, nv);
	} else if (!strcmp(mn, "RO")) {
		/* the coordinate system turned counter-clockwise on the paper (applied to what is drawn
		 * at the end of the read); P1 and P2 not set by IP turn with the paper's sides */
		int ro = nv ? hpgl_rd_int(v[0]) : 0;
		ro = ((ro % 360) + 360) % 360 / 90 * 90;
		hpgl_rd_end_stroke(r);
		if (!r->ip_set && (ro / 90 % 2) != (r->at.ro / 90 % 2)) {
			double t;
			t = r->p1x, r->p1x = r->p1y, r->p1y = t;
			t = r->p2x, r->p2x = r->p2y, r->p2y = t;
			if (r->sc)
				hpgl_rd_set_scaling(r, r->sc_v, r->sc_nv);
		}
		r->at.ro = ro;
	} else if (!strcmp(mn, "PG")) {   /* advance the page: what follows is drawn on the next */
		hpgl_rd_end_stroke(r);
		r->down = 0;   /* the sheet changes under a lifted pen */
		if (r->page_used)
			r->page++, r->page_used = 0;
	} else if (!strcmp(mn, "CS") || !strcmp(mn, "CA")) {
		int set = nv ? hpgl_rd_int(v[0]) : 0;
		if (mn[1] == 'S')
			r->at.cs = set;
		else
			r->at.ca = set;
	} else if (!strcmp(mn, "CI")) {
		if (nv < 1)
			return hpgl_rd_fail(r, r->cmd_off, "CI needs a radius");
		/* the radius in user units along each axis: anisotropic scaling draws an ellipse
		 * ("anisotropic scaling may produce an ellipse", HP's PCL 5 / HP-GL/2 reference, CI) */
		double rad, rady, dummy;
		hpgl_rd_user_len(r, v[0], 0, &rad, &dummy);
		hpgl_rd_user_len(r, 0, v[0], &dummy, &rady);
		return hpgl_rd_circle(r, fabs(rad), fabs(rady), nv > 1 ? v[1] : 5, HPGL_RS_LINE);
	} else if (!strcmp(mn, "AA") || !strcmp(mn, "AR")) {
		if (nv < 3)
			return hpgl_rd_fail(r, r->cmd_off, "%s needs a centre and a sweep", mn);
		double cx, cy;
		if (mn[1] == 'R') {
			hpgl_rd_user_len(r, v[0], v[1], &cx, &cy);
			cx += r->x;
			cy += r->y;
		} else {
			hpgl_rd_user_to_pu(r, v[0], v[1], &cx, &cy);
		}
		double rad = hypot(r->x - cx, r->y - cy), a0 = atan2(r->y - cy, r->x - cx);
		if (rad == 0)
			return 0;
		return hpgl_rd_arc_points(r, cx, cy, rad, a0, v[2], nv > 3 ? v[3] : 5);
	} else if (!strcmp(mn, "EA") || !strcmp(mn, "ER")) {
		return hpgl_rd_rects(r, mn, v, nv, mn[1] == 'R', HPGL_RS_EDGE);
	} else if (!strcmp(mn, "RA") || !strcmp(mn, "RR")) {
		return hpgl_rd_rects(r, mn, v, nv, mn[1] == 'R', HPGL_RS_FILL);
	} else if (!strcmp(mn, "EW") || !strcmp(mn, "WG")) {
		return hpgl_rd_wedge(r, mn, v, nv, mn[0] == 'E' ? HPGL_RS_EDGE : HPGL_RS_FILL);
	} else if (!strcmp(mn, "PM")) {
		return hpgl_rd_pm(r, v, nv);
	} else if (!strcmp(mn, "FP")) {
		r->at.nonzero = nv && v[0] == 1;
		return hpgl_rd_polygon_out(r, HPGL_RS_FILL);
	} else if (!strcmp(mn, "PB")) {
		hpgl_rd_end_stroke(r);
		if (r->bl && hpgl_rd_label(r, r->bl, r->nbl, 0))
			return -1;
	} else if (!strcmp(mn, "TL")) {
		r->tl_p = nv ? v[0] : 0.5;
		r->tl_n = nv >= 2 ? v[1] : nv ? 0 : 0.5;
	} else if (!strcmp(mn, "XT") || !strcmp(mn, "YT")) {   /* a tick through the pen */
		double ext = mn[0] == 'X' ? r->p2y - r->p1y : r->p2x - r->p1x;
		double a = r->tl_p / 100 * ext, b = r->tl_n / 100 * ext;
		hpgl_rpt_t t[2] = { { r->x, r->y - b }, { r->x, r->y + a } };
		if (mn[0] == 'Y')
			t[0] = (hpgl_rpt_t){ r->x - b, r->y }, t[1] = (hpgl_rpt_t){ r->x + a, r->y };
		if (a + b != 0 && hpgl_rd_figure(r, t, 2, HPGL_RS_LINE))
			return -1;
	} else if (hpgl_rd_state(r, mn, v, nv)) {
		r->doc->hpgl2 |= !strcmp(mn, "PW") || !strcmp(mn, "WU") || !strcmp(mn, "PC") || !strcmp(mn, "NP");
	} else if (!strcmp(mn, "PW") || !strcmp(mn, "WU") || !strcmp(mn, "NP") || !strcmp(mn, "PC") ||
			!strcmp(mn, "BP") || !strcmp(mn, "PS") || !strcmp(mn, "MC") || !strcmp(mn, "LA") ||
			!strcmp(mn, "RF") || !strcmp(mn, "SV") || !strcmp(mn, "TR") || !strcmp(mn, "SD") ||
			!strcmp(mn, "AD") || !strcmp(mn, "SB")) {
		r->doc->hpgl2 = 1;
	} else if (!strcmp(mn, "FT") || !strcmp(mn, "PT") || !strcmp(mn, "LT") || !strcmp(mn, "IW") ||
			!strcmp(mn, "SI") || !strcmp(mn, "SR") || !strcmp(mn, "DI") || !strcmp(mn, "DR") ||
			!strcmp(mn, "VS") || !strcmp(mn, "LO") ||
			!strcmp(mn, "SA") || !strcmp(mn, "SS") || !strcmp(mn, "UL") ||
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

/* Quote up to 16 bytes of s[a, b) printably into q. */
static void quote(const unsigned char *s, size_t a, size_t b, char *q, size_t n)
{
	size_t k = 0;
	for (size_t i = a; i < b && i < a + 16 && k + 5 < n; i++)
		k += (size_t)snprintf(q + k, n - k, s[i] >= 0x20 && s[i] < 0x7f && s[i] != '\\' ? "%c" : "\\x%02x", s[i]);
	if (b > a + 16 && k + 4 < n)
		k += (size_t)snprintf(q + k, n - k, "...");
	q[k] = 0;
}

/* Turn a point by ro degrees counter-clockwise (a multiple of 90). */
static void turn(int ro, double *x, double *y)
{
	double a = *x, b = *y;
	if (ro == 90)
		*x = -b, *y = a;
	else if (ro == 180)
		*x = -a, *y = -b;
	else if (ro == 270)
		*x = b, *y = -a;
}

/* RO: everything drawn under a rotation onto the paper's axes (each by the RO it was drawn with). */
static void apply_ro(hpgl_doc_t *d)
{
	for (size_t k = 0; k < d->nstrokes; k++) {
		int ro = d->attrs[d->strokes[k].attr].ro;
		for (size_t i = 0; ro && i < d->strokes[k].n; i++)
			turn(ro, &d->pts[d->strokes[k].start + i].x, &d->pts[d->strokes[k].start + i].y);
	}
	for (size_t k = 0; k < d->nlabels; k++) {
		hpgl_rlabel_t *l = &d->labels[k];
		int ro = d->attrs[l->attr].ro;
		turn(ro, &l->x, &l->y);
		turn(ro, &l->dx, &l->dy);
		turn(ro, &l->crx, &l->cry);
	}
	for (size_t k = 0; k < d->nattrs; k++) {
		hpgl_rattr_t *a = &d->attrs[k];
		if (!a->ro)
			continue;
		a->ft_angle += a->ro;
		if (a->iw) {
			double x0 = a->iw_x0, y0 = a->iw_y0, x1 = a->iw_x1, y1 = a->iw_y1;
			turn(a->ro, &x0, &y0);
			turn(a->ro, &x1, &y1);
			a->iw_x0 = fmin(x0, x1), a->iw_x1 = fmax(x0, x1);
			a->iw_y0 = fmin(y0, y1), a->iw_y1 = fmax(y0, y1);
		}
	}
}

int hpgl_read_mem(const void *buf, size_t len, const char *name, hpgl_doc_t *doc, char *err,
		size_t errlen)
{
	return hpgl_read_mem_flags(buf, len, name, 0, doc, err, errlen);
}

int hpgl_read_mem_flags(const void *buf, size_t len, const char *name, int flags, hpgl_doc_t *doc,
		char *err, size_t errlen)
{
	memset(doc, 0, sizeof *doc);
	hpgl_rd_t r;
	memset(&r, 0, sizeof r);
	r.tolerant = (flags & HPGL_READ_TOLERANT) != 0;
	r.s = buf;
	r.n = len;
	r.name = name;
	r.err = err;
	r.errlen = errlen;
	r.doc = doc;
	hpgl_rd_defaults(&r, 1);
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
		if (!hpgl_lex_letter(c) || r.i + 1 >= r.n || !hpgl_lex_letter(r.s[r.i + 1])) {
			if (stray == SIZE_MAX)
				stray = r.i;
			r.i++;
			continue;
		}
		if (stray != SIZE_MAX && !r.tolerant) {
			rc = hpgl_rd_fail(&r, stray, "expected a two-letter HP-GL command, got byte 0x%02x", r.s[stray]);
			break;
		}
		if (stray != SIZE_MAX) {   /* tolerant: junk between commands, skipped */
			char q[80];
			quote(r.s, stray, r.i, q, sizeof q);
			hpgl_rd_warn(&r, stray, "skipped %zu bytes that are no HP-GL command (%s)", r.i - stray, q);
			stray = SIZE_MAX;
		}
		char mn[3] = { hpgl_lex_upper(c), hpgl_lex_upper(r.s[r.i + 1]), 0 };
		r.cmd = doc->ncmds++;
		r.cmd_off = r.i;
		r.i += 2;
		rc = command(&r, mn);
		if (rc && r.tolerant && !r.nomem) {
			/* a command that cannot be read is skipped to its ';', as a plotter goes on
			 * at the next command */
			size_t j = r.fail_off > r.cmd_off ? r.fail_off : r.cmd_off + 2;
			while (j < r.n && r.s[j] != ';')
				j++;
			r.i = j < r.n ? j + 1 : r.n;
			hpgl_rd_warn(&r, r.fail_off, "%s; skipped to byte %zu", r.fail_msg, r.i);
			if (errlen)
				err[0] = 0;
			hpgl_rd_end_stroke(&r);
			rc = 0;
		}
	}
	if (rc == 0 && stray != SIZE_MAX) {
		doc->trailing = r.n - stray;
		if (r.tolerant) {
			char q[80];
			quote(r.s, stray, r.n, q, sizeof q);
			hpgl_rd_warn(&r, stray, "skipped %zu trailing bytes after the last command (%s)", r.n - stray, q);
		}
	}
	doc->npages = r.page + (r.page_used || !r.page);
	if (rc == 0 && r.rotated)
		apply_ro(doc);
	doc->p1x = r.p1x, doc->p1y = r.p1y, doc->p2x = r.p2x, doc->p2y = r.p2y;
	hpgl_rd_end_stroke(&r);
	free(r.bl);
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
	free(doc->attrs);
	free(doc->warns);
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
