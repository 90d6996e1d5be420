/* import_svg_occlude.c: -O occlude: hidden-line removal for pen plotters. Each filled shape,
 * in paint order, hides what was drawn before it: earlier strokes and earlier fills' outlines
 * are cut where they run inside its fill region (by its fill rule). Fills then become their
 * outlines (a plotter draws lines), as occlusion plugins (vpype-occult) treat closed shapes.
 * Work is on the flattened polylines; earlier items are found through a grid of the page by
 * their bounding boxes (items over many cells on one list every fill looks through) and a fill's edges through horizontal strips, so a drawing of n
 * segments costs about n log n, not n times the number of fills' edges. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "util/grow.h"
#include "import/svg_import.h"

typedef struct { double x0, y0, x1, y1; } box_t;

/* A fill region: its edges (each subpath closed), bucketed by horizontal strips. */
typedef struct {
	svg_pt_t *p, *q;
	size_t ne;
	box_t bb;
	int rule;
	int nstrip;
	double sy0, sh;
	size_t *sstart, *sidx;  /* CSR: strip s holds sidx[sstart[s] .. sstart[s+1]) */
	unsigned *stamp;
	unsigned cur;
	double *ts;             /* crossing parameters of one segment */
	size_t nts, tscap;
} region_t;

static void region_free(region_t *r)
{
	free(r->p), free(r->q), free(r->sstart), free(r->sidx), free(r->stamp), free(r->ts);
	memset(r, 0, sizeof *r);
}

static int strip_of(const region_t *r, double y)
{
	double s = floor((y - r->sy0) / r->sh);
	return !(s >= 0) ? 0 : s >= r->nstrip ? r->nstrip - 1 : (int)s;   /* NaN: strip 0, no UB */
}

/* 0, 1 (no area: nothing to hide) or -1 (out of memory). */
static int region_build(region_t *r, const svg_geom_t *g, int rule)
{
	memset(r, 0, sizeof *r);
	r->rule = rule;
	if (!g->n)
		return 1;
	r->p = malloc(g->n * sizeof *r->p);
	r->q = malloc(g->n * sizeof *r->q);
	if (!r->p || !r->q)
		return -1;
	r->bb = (box_t){ INFINITY, INFINITY, -INFINITY, -INFINITY };
	for (size_t s = 0; s < g->nsub; s++) {
		size_t a = g->sub[s], b = s + 1 < g->nsub ? g->sub[s + 1] : g->n;
		if (b - a < 3)
			continue;   /* no area */
		for (size_t i = a; i < b; i++) {
			svg_pt_t P = g->pt[i], Q = g->pt[i + 1 < b ? i + 1 : a];
			if (!isfinite(P.x) || !isfinite(P.y) || !isfinite(Q.x) || !isfinite(Q.y))
				continue;
			if (P.x == Q.x && P.y == Q.y)
				continue;
			r->p[r->ne] = P, r->q[r->ne++] = Q;
			r->bb.x0 = fmin(r->bb.x0, fmin(P.x, Q.x)), r->bb.x1 = fmax(r->bb.x1, fmax(P.x, Q.x));
			r->bb.y0 = fmin(r->bb.y0, fmin(P.y, Q.y)), r->bb.y1 = fmax(r->bb.y1, fmax(P.y, Q.y));
		}
	}
	if (r->ne < 3 || !(r->bb.y1 > r->bb.y0) || !(r->bb.x1 > r->bb.x0))
		return 1;
	/* about two edges a strip, but no more strips than keep the bucket entries (an edge is
	 * in every strip its height crosses) near four per edge: long edges of a scribble */
	double span = 0, H = r->bb.y1 - r->bb.y0;
	for (size_t e = 0; e < r->ne; e++)
		span += fabs(r->q[e].y - r->p[e].y);
	double ns = fmin((double)r->ne / 2, 3.0 * (double)r->ne * H / (span > 0 ? span : H));
	r->nstrip = !(ns >= 1) ? 1 : ns > 8192 ? 8192 : (int)ns;
	r->sy0 = r->bb.y0;
	r->sh = (r->bb.y1 - r->bb.y0) / r->nstrip;
	r->sstart = calloc((size_t)r->nstrip + 1, sizeof *r->sstart);
	r->stamp = calloc(r->ne, sizeof *r->stamp);
	if (!r->sstart || !r->stamp)
		return -1;
	for (size_t e = 0; e < r->ne; e++) {
		int s0 = strip_of(r, fmin(r->p[e].y, r->q[e].y)), s1 = strip_of(r, fmax(r->p[e].y, r->q[e].y));
		for (int s = s0; s <= s1; s++)
			r->sstart[s + 1]++;
	}
	for (int s = 0; s < r->nstrip; s++)
		r->sstart[s + 1] += r->sstart[s];
	r->sidx = malloc((r->sstart[r->nstrip] ? r->sstart[r->nstrip] : 1) * sizeof *r->sidx);
	size_t *fillp = malloc((size_t)r->nstrip * sizeof *fillp);
	if (!r->sidx || !fillp) {
		free(fillp);
		return -1;
	}
	memcpy(fillp, r->sstart, (size_t)r->nstrip * sizeof *fillp);
	for (size_t e = 0; e < r->ne; e++) {
		int s0 = strip_of(r, fmin(r->p[e].y, r->q[e].y)), s1 = strip_of(r, fmax(r->p[e].y, r->q[e].y));
		for (int s = s0; s <= s1; s++)
			r->sidx[fillp[s]++] = e;
	}
	free(fillp);
	return 0;
}

/* Is pt inside the region by its fill rule? (winding number of the edges crossing its row) */
static int inside(const region_t *r, svg_pt_t pt)
{
	if (pt.x < r->bb.x0 || pt.x > r->bb.x1 || pt.y < r->bb.y0 || pt.y > r->bb.y1)
		return 0;
	int s = strip_of(r, pt.y);
	long w = 0;
	for (size_t k = r->sstart[s]; k < r->sstart[s + 1]; k++) {
		size_t e = r->sidx[k];
		svg_pt_t P = r->p[e], Q = r->q[e];
		double side = (Q.x - P.x) * (pt.y - P.y) - (pt.x - P.x) * (Q.y - P.y);
		if (P.y <= pt.y) {
			if (Q.y > pt.y && side > 0)
				w++;
		} else if (Q.y <= pt.y && side < 0) {
			w--;
		}
	}
	return r->rule == META_RULE_EVEN_ODD ? (int)(w & 1) : w != 0;
}

static int cmp_d(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

/* The parameters (0..1, sorted, 0 and 1 included) where segment A-B crosses the region's edges. */
static int crossings(region_t *r, svg_pt_t A, svg_pt_t B)
{
	r->nts = 0;
	if (dev_grow((void **)&r->ts, &r->tscap, 2, sizeof *r->ts, 64))
		return -1;
	r->ts[r->nts++] = 0;
	double dx = B.x - A.x, dy = B.y - A.y;
	double ylo = fmax(fmin(A.y, B.y), r->bb.y0), yhi = fmin(fmax(A.y, B.y), r->bb.y1);
	if (ylo <= yhi) {
		if (++r->cur == 0) {
			memset(r->stamp, 0, r->ne * sizeof *r->stamp);
			r->cur = 1;
		}
		double sxlo = fmin(A.x, B.x), sxhi = fmax(A.x, B.x);
		int s0 = strip_of(r, ylo), s1 = strip_of(r, yhi);
		for (int s = s0; s <= s1; s++)
			for (size_t k = r->sstart[s]; k < r->sstart[s + 1]; k++) {
				size_t e = r->sidx[k];
				if (r->stamp[e] == r->cur)
					continue;
				r->stamp[e] = r->cur;
				svg_pt_t P = r->p[e], Q = r->q[e];
				if (fmax(P.x, Q.x) < sxlo || fmin(P.x, Q.x) > sxhi ||
						fmax(P.y, Q.y) < fmin(A.y, B.y) || fmin(P.y, Q.y) > fmax(A.y, B.y))
					continue;
				double ex = Q.x - P.x, ey = Q.y - P.y;
				double den = dx * ey - dy * ex;
				if (den == 0)
					continue;   /* parallel: the midpoints' tests decide */
				double t = ((P.x - A.x) * ey - (P.y - A.y) * ex) / den;
				double u = ((P.x - A.x) * dy - (P.y - A.y) * dx) / den;
				if (t > 0 && t < 1 && u >= 0 && u <= 1) {
					if (dev_grow((void **)&r->ts, &r->tscap, r->nts + 2, sizeof *r->ts, 64))
						return -1;
					r->ts[r->nts++] = t;
				}
			}
	}
	r->ts[r->nts++] = 1;
	if (r->nts > 3)
		qsort(r->ts + 1, r->nts - 2, sizeof *r->ts, cmp_d);
	return 0;
}

static int boxes_meet(box_t a, box_t b)
{
	return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1;
}

static box_t geom_box(const svg_geom_t *g, size_t a, size_t b)
{
	box_t bb = { INFINITY, INFINITY, -INFINITY, -INFINITY };
	for (size_t i = a; i < b; i++) {
		bb.x0 = fmin(bb.x0, g->pt[i].x), bb.x1 = fmax(bb.x1, g->pt[i].x);
		bb.y0 = fmin(bb.y0, g->pt[i].y), bb.y1 = fmax(bb.y1, g->pt[i].y);
	}
	return bb;
}

/* Cut from g what runs inside r. 0, or -1 out of memory. */
static int clip_hidden(svg_geom_t *g, region_t *r)
{
	svg_geom_t o = { .tol = g->tol, .m = { 1, 0, 0, 1, 0, 0 } };   /* cuts add at most two points a crossing */
	int changed = 0;
	for (size_t s = 0; s < g->nsub; s++) {
		size_t a = g->sub[s], b = s + 1 < g->nsub ? g->sub[s + 1] : g->n;
		box_t sb = geom_box(g, a, b);
		if (!boxes_meet(sb, r->bb) || b - a == 1) {
			if (b - a == 1 && inside(r, g->pt[a])) {   /* a dot under the shape */
				changed = 1;
				continue;
			}
			svg_geom_move(&o, g->pt[a].x, g->pt[a].y);
			for (size_t i = a + 1; i < b; i++)
				svg_geom_line(&o, g->pt[i].x, g->pt[i].y);
			if (g->closed[s])
				svg_geom_close(&o);
			continue;
		}
		size_t m = b - a + (g->closed[s] ? 1 : 0);
		int open = 0, whole = 1;
		size_t start_sub = o.nsub;
		for (size_t j = 1; j < m; j++) {
			svg_pt_t A = g->pt[a + j - 1], B = g->pt[j < b - a ? a + j : a];
			box_t eb = { fmin(A.x, B.x), fmin(A.y, B.y), fmax(A.x, B.x), fmax(A.y, B.y) };
			if (!boxes_meet(eb, r->bb)) {
				if (!open)
					svg_geom_move(&o, A.x, A.y);
				svg_geom_line(&o, B.x, B.y);
				open = 1;
				continue;
			}
			if (crossings(r, A, B))
				return svg_geom_free(&o), -1;
			double dx = B.x - A.x, dy = B.y - A.y;
			for (size_t k = 0; k + 1 < r->nts; k++) {
				double t0 = r->ts[k], t1 = r->ts[k + 1];
				if (t1 <= t0)
					continue;
				double tm = (t0 + t1) / 2;
				if (inside(r, (svg_pt_t){ A.x + dx * tm, A.y + dy * tm })) {
					whole = 0, open = 0;
					continue;
				}
				if (!open || t0 > 0) {
					if (open)
						whole = 0;
					svg_geom_move(&o, A.x + dx * t0, A.y + dy * t0);
				}
				svg_geom_line(&o, t1 >= 1 ? B.x : A.x + dx * t1, t1 >= 1 ? B.y : A.y + dy * t1);
				open = 1;
			}
		}
		if (!whole)
			changed = 1;
		if (whole && g->closed[s] && o.nsub == start_sub + 1 && o.n - o.sub[start_sub] > 1) {
			o.n--;   /* the closing point again: closed instead */
			svg_geom_close(&o);
		}
	}
	if (o.oom) {
		svg_geom_free(&o);
		return -1;
	}
	if (!changed) {
		svg_geom_free(&o);
		return 0;
	}
	svg_geom_free(g);
	*g = o;
	return 0;
}

/* ---- the page grid of items drawn so far ---- */

#define GRID 64

#define BIG_CELLS 64   /* an item over more cells goes on the list every fill looks through */

typedef struct {
	size_t *cell[GRID * GRID + 1];   /* the last: the big items */
	size_t n[GRID * GRID + 1], cap[GRID * GRID + 1];
	double x0, y0, cw, ch;
} grid_t;

static int grid_add(grid_t *G, size_t c, size_t i)
{
	if (dev_grow((void **)&G->cell[c], &G->cap[c], G->n[c] + 1, sizeof **G->cell, 16))
		return -1;
	G->cell[c][G->n[c]++] = i;
	return 0;
}

static void cells(const grid_t *G, box_t b, int *i0, int *j0, int *i1, int *j1)
{
	double f[4] = { (b.x0 - G->x0) / G->cw, (b.y0 - G->y0) / G->ch, (b.x1 - G->x0) / G->cw, (b.y1 - G->y0) / G->ch };
	int v[4];
	for (int k = 0; k < 4; k++)
		v[k] = !(f[k] >= 0) ? 0 : f[k] >= GRID - 1 ? GRID - 1 : (int)f[k];
	*i0 = v[0], *j0 = v[1], *i1 = v[2], *j1 = v[3];
}

int svg_occlude(svg_doc_t *d)
{
	if (!d->n)
		return 0;
	grid_t *G = calloc(1, sizeof *G);
	box_t *ib = malloc(d->n * sizeof *ib);
	unsigned *seen = calloc(d->n, sizeof *seen);
	size_t *cand = NULL, ncand = 0, candcap = 0;
	int ret = -1;
	if (!G || !ib || !seen)
		goto out;
	G->x0 = 0, G->y0 = 0;
	G->cw = (d->W > 0 ? d->W : 1) / GRID, G->ch = (d->H > 0 ? d->H : 1) / GRID;
	for (size_t i = 0; i < d->n; i++) {
		svg_item_t *it = &d->it[i];
		ib[i] = geom_box(&it->g, 0, it->g.n);
		if (it->kind == SVGI_FILL && it->g.n) {
			region_t r;
			int b = region_build(&r, &it->g, it->rule);
			if (b < 0) {
				region_free(&r);
				goto out;
			}
			if (b == 0) {
				int i0, j0, i1, j1;
				cells(G, r.bb, &i0, &j0, &i1, &j1);
				ncand = 0;
				for (int jj = j0; jj <= j1 + 1; jj++)
					for (int ii = i0; ii <= i1; ii++) {
						size_t c = jj > j1 ? GRID * GRID : (size_t)jj * GRID + (size_t)ii;
						if (jj > j1 && ii > i0)
							break;   /* the big items: once */
						for (size_t k = 0; k < G->n[c]; k++) {
							size_t q = G->cell[c][k];
							if (seen[q] == i + 1 || !boxes_meet(ib[q], r.bb))
								continue;
							seen[q] = (unsigned)(i + 1);
							if (dev_grow((void **)&cand, &candcap, ncand + 1, sizeof *cand, 64)) {
								region_free(&r);
								goto out;
							}
							cand[ncand++] = q;
						}
					}
				for (size_t k = 0; k < ncand; k++)
					if (clip_hidden(&d->it[cand[k]].g, &r)) {
						region_free(&r);
						goto out;
					}
			}
			region_free(&r);
			/* the fill becomes its outline: not at all when the element's stroke draws that
			 * edge, or when it is white (paper: it hides, it draws nothing) */
			it->kind = SVGI_STROKE;
			it->width = d->px_per_mm * 0.3;
			it->cap = META_CAP_ROUND, it->join = META_JOIN_ROUND;
			if (it->stroked || it->src_rgb == 0xffffff)
				svg_geom_free(&it->g);
		}
		if (!it->g.n)
			continue;
		int i0, j0, i1, j1;
		cells(G, ib[i], &i0, &j0, &i1, &j1);
		if ((long)(i1 - i0 + 1) * (j1 - j0 + 1) > BIG_CELLS) {
			if (grid_add(G, GRID * GRID, i))
				goto out;
			continue;
		}
		for (int jj = j0; jj <= j1; jj++)
			for (int ii = i0; ii <= i1; ii++)
				if (grid_add(G, (size_t)jj * GRID + (size_t)ii, i))
					goto out;
	}
	ret = 0;
out:
	if (G)
		for (size_t c = 0; c <= GRID * GRID; c++)
			free(G->cell[c]);
	free(G), free(ib), free(seen), free(cand);
	return ret;
}
