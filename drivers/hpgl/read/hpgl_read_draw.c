/* hpgl_read_draw.c: the HP-GL reader's drawing: strokes, the polygon buffer, arcs, circles,
 * rectangles, wedges and scaling (the parser is hpgl_read.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hpgl/read/hpgl_read_int.h"

/* ---- strokes ---- */

void hpgl_rd_end_stroke(hpgl_rd_t *r)
{
	hpgl_doc_t *d = r->doc;
	if (r->open && d->strokes[d->nstrokes - 1].n < 2) {
		d->npts = d->strokes[d->nstrokes - 1].start;   /* a lone point draws nothing */
		d->nstrokes--;
	}
	r->open = 0;
}

int hpgl_rd_add_pt(hpgl_rd_t *r, double x, double y)
{
	hpgl_doc_t *d = r->doc;
	if (hpgl_rd_grow((void **)&d->pts, &d->cappts, d->npts + 1, sizeof *d->pts))
		return hpgl_rd_nomem(r);
	d->pts[d->npts++] = (hpgl_rpt_t){ x, y };
	d->strokes[d->nstrokes - 1].n++;
	return 0;
}

int hpgl_rd_begin_stroke(hpgl_rd_t *r, int kind)
{
	hpgl_doc_t *d = r->doc;
	hpgl_rd_end_stroke(r);
	if (hpgl_rd_grow((void **)&d->strokes, &d->capstrokes, d->nstrokes + 1, sizeof *d->strokes))
		return hpgl_rd_nomem(r);
	size_t a = hpgl_rd_attr(r);
	if (a == (size_t)-1)
		return -1;
	d->strokes[d->nstrokes++] = (hpgl_rstroke_t){ r->pen, kind, d->npts, 0, r->cmd, r->cmd_off, a, r->group, r->page };
	r->page_used = 1;
	r->rotated |= r->at.ro != 0;
	r->open = 1;
	return hpgl_rd_add_pt(r, r->x, r->y);
}

/* Polygon mode: start a contour at (x, y) (a contour of one point is replaced). */
int hpgl_rd_start_contour(hpgl_rd_t *r, double x, double y)
{
	if (r->npbs && r->npb - r->pbs[r->npbs - 1] == 1) {
		r->pb[r->npb - 1] = (hpgl_rpt_t){ x, y };
		return 0;
	}
	if (hpgl_rd_grow((void **)&r->pbs, &r->cappbs, r->npbs + 1, sizeof *r->pbs) ||
			hpgl_rd_grow((void **)&r->pb, &r->cappb, r->npb + 1, sizeof *r->pb))
		return hpgl_rd_nomem(r);
	r->pbs[r->npbs++] = r->npb;
	r->pb[r->npb++] = (hpgl_rpt_t){ x, y };
	r->newc = 0;
	return 0;
}

/* Move to (x, y) in plotter units with the pen as it is. */
int hpgl_rd_move_to(hpgl_rd_t *r, double x, double y)
{
	r->crx = x, r->cry = y;
	if (r->poly) {
		/* a pen-up move, or the first after PM1 (or a circle), starts a contour at its end:
		 * the way there is no edge (hp2xx and the plotters draw none) */
		if (!r->down || r->newc) {
			if (hpgl_rd_start_contour(r, x, y))
				return -1;
			r->x = x;
			r->y = y;
			return 0;
		}
		if (r->npbs == 0 && hpgl_rd_start_contour(r, r->x, r->y))
			return -1;
		if (hpgl_rd_grow((void **)&r->pb, &r->cappb, r->npb + 1, sizeof *r->pb))
			return hpgl_rd_nomem(r);
		r->pb[r->npb++] = (hpgl_rpt_t){ x, y };
		r->x = x;
		r->y = y;
		return 0;
	}
	if (r->down) {
		if (!r->open && hpgl_rd_begin_stroke(r, HPGL_RS_LINE))
			return -1;
		if (hpgl_rd_add_pt(r, x, y))
			return -1;
	} else {
		hpgl_rd_end_stroke(r);
	}
	r->x = x;
	r->y = y;
	return 0;
}

/* A closed figure drawn as its own stroke (edges, fills); the pen position is unchanged. */
int hpgl_rd_figure(hpgl_rd_t *r, const hpgl_rpt_t *p, size_t n, int kind)
{
	double x = r->x, y = r->y;
	hpgl_rd_end_stroke(r);
	r->x = p[0].x;
	r->y = p[0].y;
	if (hpgl_rd_begin_stroke(r, kind))
		return -1;
	for (size_t i = 1; i < n; i++)
		if (hpgl_rd_add_pt(r, p[i].x, p[i].y))
			return -1;
	hpgl_rd_end_stroke(r);
	r->x = x;
	r->y = y;
	return 0;
}

/* ---- arcs ---- */

double hpgl_rd_chord(double chord)
{
	/* HP-GL/2 takes the magnitude and clamps it to 0.5 .. 180 degrees; no angle is 5 */
	chord = fabs(chord);
	if (!(chord > 0))
		return 5;
	return chord < 0.5 ? 0.5 : chord > 180 ? 180 : chord;
}

/* Points of an arc about (cx, cy) from angle a0 (radians) through sweep degrees, chord degrees
 * apart, written to fn's target: calls move_to for each point after the first. */
int hpgl_rd_arc_points(hpgl_rd_t *r, double cx, double cy, double rad, double a0, double sweep, double chord)
{
	chord = hpgl_rd_chord(chord);
	double steps = ceil(fabs(sweep) / chord);
	int n = steps > 100000 ? 100000 : steps < 1 ? 1 : (int)steps;
	/* the arc is round in user units: under anisotropic scaling (SC) it is an ellipse in
	 * plotter units, as HP's manuals say of CI; a0 and rad are then taken in user units */
	double kx = 1, ky = 1;
	if (r->sc) {
		double t;
		hpgl_rd_user_len(r, 1, 0, &kx, &t);
		hpgl_rd_user_len(r, 0, 1, &t, &ky);
		if (kx != 0 && ky != 0 && fabs(kx) != fabs(ky)) {
			double u = (r->x - cx) / kx, v = (r->y - cy) / ky;
			rad = hypot(u, v);
			a0 = atan2(v, u);
		} else {
			kx = ky = 1;
		}
	}
	for (int k = 1; k <= n; k++) {
		double a = a0 + sweep * M_PI / 180 * k / n;
		if (hpgl_rd_move_to(r, cx + kx * rad * cos(a), cy + ky * rad * sin(a)))
			return -1;
	}
	return 0;
}

int hpgl_rd_circle(hpgl_rd_t *r, double rad, double rady, double chord, int kind)
{
	chord = hpgl_rd_chord(chord);
	int n = (int)ceil(360 / chord);
	hpgl_rpt_t *p = malloc((size_t)(n + 1) * sizeof *p);
	if (!p)
		return hpgl_rd_nomem(r);
	for (int k = 0; k <= n; k++)
		p[k] = (hpgl_rpt_t){ r->x + rad * cos(2 * M_PI * k / n), r->y + rady * sin(2 * M_PI * k / n) };
	int rc = 0;
	if (r->poly) {   /* a circle in polygon mode is a contour of its own */
		rc = hpgl_rd_start_contour(r, p[0].x, p[0].y);
		for (int k = 1; k <= n && !rc; k++) {
			if (hpgl_rd_grow((void **)&r->pb, &r->cappb, r->npb + 1, sizeof *r->pb))
				rc = hpgl_rd_nomem(r);
			else
				r->pb[r->npb++] = p[k];
		}
		r->newc = 1;
	} else {
		rc = hpgl_rd_figure(r, p, (size_t)n + 1, kind);
	}
	free(p);
	return rc;
}

void hpgl_rd_set_scaling(hpgl_rd_t *r, const double *v, int nv)
{
	if (nv < 4) {
		r->sc = 0;
		return;
	}
	int type = nv >= 5 ? hpgl_rd_int(v[4]) : 0;
	r->sc = 1;
	r->sc_nv = nv > 5 ? 5 : nv;
	if (v != r->sc_v)
		memcpy(r->sc_v, v, (size_t)r->sc_nv * sizeof *v);
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

void hpgl_rd_default_p1p2(hpgl_rd_t *r)
{
	r->p1x = 603;   /* 7475A A4 defaults for P1 and P2 (a file that uses SC without IP) */
	r->p1y = 521;
	r->p2x = 10603;
	r->p2y = 7721;
}

void hpgl_rd_defaults(hpgl_rd_t *r, int in)
{
	hpgl_rd_end_stroke(r);
	r->rel = 0;
	r->sc = 0;
	r->poly = 0;
	r->term = HPGL_LEX_TERM_DEFAULT;
	if (in) {
		r->down = 0;
		r->ip_set = 0;
		hpgl_rd_default_p1p2(r);
	}
	hpgl_rd_attr_defaults(r, in);
}

int hpgl_rd_pm(hpgl_rd_t *r, const double *v, int nv)
{
	int k = nv ? hpgl_rd_int(v[0]) : 0;
	r->doc->hpgl2 = 1;
	if (k == 0) {
		hpgl_rd_end_stroke(r);
		r->poly = 1;
		r->npb = r->npbs = 0;
		return hpgl_rd_start_contour(r, r->x, r->y);
	}
	if (r->poly)
		r->newc = 1;
	if (k == 2)
		r->poly = 0;
	return 0;
}

/* One contour of the polygon buffer as a closed figure. */
static int contour_out(hpgl_rd_t *r, size_t k, int kind)
{
	size_t a = r->pbs[k], b = k + 1 < r->npbs ? r->pbs[k + 1] : r->npb;
	if (b - a < 2)
		return 0;
	hpgl_rpt_t *p = malloc((b - a + 1) * sizeof *p);
	if (!p)
		return hpgl_rd_nomem(r);
	memcpy(p, r->pb + a, (b - a) * sizeof *p);
	size_t n = b - a;
	/* a fill closes every contour; an edge (EP) only what the file closed, as plotters draw it */
	if (kind != HPGL_RS_EDGE && (p[n - 1].x != p[0].x || p[n - 1].y != p[0].y))
		p[n++] = p[0];
	int rc = hpgl_rd_figure(r, p, n, kind);
	free(p);
	return rc ? -1 : 0;
}

/* FP / EP: the polygon buffer's contours as strokes of one group. */
int hpgl_rd_polygon_out(hpgl_rd_t *r, int kind)
{
	r->doc->hpgl2 = 1;
	r->group = ++r->ngroups;   /* the contours of this polygon fill (and edge) together */
	int rc = 0;
	for (size_t k = 0; k < r->npbs && !rc; k++)
		rc = contour_out(r, k, kind);
	r->group = 0;
	return rc;
}

int hpgl_rd_rect(hpgl_rd_t *r, const char *mn, const double *v, int nv, int relative, int kind)
{
	if (nv < 2)
		return hpgl_rd_fail(r, r->cmd_off, "%s needs two coordinates", mn);
	double x, y;
	if (relative) {
		hpgl_rd_user_len(r, v[0], v[1], &x, &y);
		x += r->x;
		y += r->y;
	} else {
		hpgl_rd_user_to_pu(r, v[0], v[1], &x, &y);
	}
	hpgl_rpt_t p[5] = { { r->x, r->y }, { x, r->y }, { x, y }, { r->x, y }, { r->x, r->y } };
	return hpgl_rd_figure(r, p, 5, kind);
}

int hpgl_rd_rects(hpgl_rd_t *r, const char *mn, const double *v, int nv, int relative, int kind)
{
	/* more than one corner: one rectangle from the pen to each (as hp2xx reads RA0,0,4000,4000) */
	int rc = hpgl_rd_rect(r, mn, v, nv, relative, kind);
	for (int k = 2; k + 1 < nv && !rc; k += 2)
		rc = hpgl_rd_rect(r, mn, v + k, 2, relative, kind);
	return rc;
}

int hpgl_rd_wedge(hpgl_rd_t *r, const char *mn, const double *v, int nv, int kind)
{
	if (nv < 3)
		return hpgl_rd_fail(r, r->cmd_off, "%s needs radius, start and sweep", mn);
	double rad, dummy;
	hpgl_rd_user_len(r, v[0], 0, &rad, &dummy);
	double chord = hpgl_rd_chord(nv > 3 ? v[3] : 5);
	double sweep = fmin(fabs(v[2]), 360);
	int n = (int)ceil(sweep / chord);
	if (n < 1)
		n = 1;
	hpgl_rpt_t *p = malloc((size_t)(n + 3) * sizeof *p);
	if (!p)
		return hpgl_rd_nomem(r);
	size_t m = 0;
	p[m++] = (hpgl_rpt_t){ r->x, r->y };
	for (int k = 0; k <= n; k++) {
		double a = (v[1] + (v[2] < 0 ? -sweep : sweep) * k / n) * M_PI / 180;
		p[m++] = (hpgl_rpt_t){ r->x + rad * cos(a), r->y + rad * sin(a) };
	}
	p[m++] = (hpgl_rpt_t){ r->x, r->y };
	int rc = hpgl_rd_figure(r, p, m, kind);
	free(p);
	return rc;
}
