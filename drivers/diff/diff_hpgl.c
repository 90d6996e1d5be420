/* diff_hpgl.c: HP-GL compared as drawn geometry: segments per pen within a tolerance, any order. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "diff/diff.h"
#include "hpgl/hpgl.h"
#include "hpgl/read/hpgl_read.h"

/* One straight piece of a stroke, its ends in plotter units. */
typedef struct {
	int pen;
	double x0, y0, x1, y1;
	size_t stroke;              /* index in the doc's strokes */
	int used;
} seg_t;

/* What one side holds. */
typedef struct {
	hpgl_doc_t doc;
	seg_t *seg;
	size_t nseg;
	size_t *order;              /* segments sorted by pen, then the smaller x of the ends */
	unsigned char *bad;         /* per stroke: a segment found no partner */
	double down_mm, up_mm, secs;
} side_t;

static const side_t *sort_side;

static double minx(const seg_t *s)
{
	return s->x0 < s->x1 ? s->x0 : s->x1;
}

static int by_pen_x(const void *a, const void *b)
{
	const seg_t *p = &sort_side->seg[*(const size_t *)a], *q = &sort_side->seg[*(const size_t *)b];
	if (p->pen != q->pen)
		return p->pen < q->pen ? -1 : 1;
	double u = minx(p), v = minx(q);
	return u < v ? -1 : u > v;
}

/* Read a side, split its strokes into segments, total its lengths and plot time. */
static int load(side_t *s, const void *buf, size_t n, const char *name, char *err, size_t errlen)
{
	memset(s, 0, sizeof *s);
	if (hpgl_read_mem(buf, n, name, &s->doc, err, errlen))
		return -1;
	const hpgl_doc_t *d = &s->doc;
	size_t total = 0;
	for (size_t k = 0; k < d->nstrokes; k++)
		total += d->strokes[k].n - 1;
	s->seg = malloc((total ? total : 1) * sizeof *s->seg);
	s->order = malloc((total ? total : 1) * sizeof *s->order);
	s->bad = calloc(d->nstrokes ? d->nstrokes : 1, 1);
	popt_pt_t *pp = NULL;
	size_t cap = 0;
	if (!s->seg || !s->order || !s->bad) {
		snprintf(err, errlen, "%s: out of memory", name);
		return -1;
	}
	const hpgl_profile_t *prof = hpgl_profile_builtin(0);
	hpgl_time_t t;
	memset(&t, 0, sizeof t);
	double px = 0, py = 0;
	int pen = -1;
	for (size_t k = 0; k < d->nstrokes; k++) {
		const hpgl_rstroke_t *st = &d->strokes[k];
		const hpgl_rpt_t *p = d->pts + st->start;
		for (size_t i = 0; i + 1 < st->n; i++) {
			seg_t *g = &s->seg[s->nseg];
			g->pen = st->pen;
			g->x0 = p[i].x, g->y0 = p[i].y, g->x1 = p[i + 1].x, g->y1 = p[i + 1].y;
			g->stroke = k;
			g->used = 0;
			s->order[s->nseg] = s->nseg;
			s->nseg++;
		}
		if (st->n > cap) {
			popt_pt_t *q = realloc(pp, st->n * 2 * sizeof *pp);
			if (!q) {
				free(pp);
				snprintf(err, errlen, "%s: out of memory", name);
				return -1;
			}
			pp = q;
			cap = st->n * 2;
		}
		for (size_t i = 0; i < st->n; i++)
			pp[i].x = (int32_t)lround(p[i].x), pp[i].y = (int32_t)lround(p[i].y);
		double travel = hypot(p[0].x - px, p[0].y - py);
		hpgl_time_add(&t, prof, travel, pp, st->n);
		if (st->pen != pen && pen >= 0)
			s->secs += prof->t_change;
		pen = st->pen;
		px = p[st->n - 1].x, py = p[st->n - 1].y;
	}
	free(pp);
	s->down_mm = t.down_mm;
	s->up_mm = t.up_mm;
	s->secs += t.down_s + t.up_s + t.lift_s;
	sort_side = s;
	qsort(s->order, s->nseg, sizeof *s->order, by_pen_x);
	return 0;
}

static void unload(side_t *s)
{
	hpgl_doc_free(&s->doc);
	free(s->seg);
	free(s->order);
	free(s->bad);
}

static int near(double ax, double ay, double bx, double by, double tol)
{
	return fabs(ax - bx) <= tol && fabs(ay - by) <= tol;
}

/* An unused segment of b equal to g within tol (either direction), marked used; 1 if found. */
static int take(side_t *b, const seg_t *g, double tol)
{
	double x = minx(g);
	size_t lo = 0, hi = b->nseg;
	while (lo < hi) {   /* the first of pen g->pen with min x >= x - tol */
		size_t mid = (lo + hi) / 2;
		const seg_t *m = &b->seg[b->order[mid]];
		if (m->pen < g->pen || (m->pen == g->pen && minx(m) < x - tol))
			lo = mid + 1;
		else
			hi = mid;
	}
	seg_t *best = NULL;
	double bestd = INFINITY;
	for (size_t i = lo; i < b->nseg; i++) {   /* the nearest unused one: greedy but not blind */
		seg_t *m = &b->seg[b->order[i]];
		if (m->pen != g->pen || minx(m) > x + tol)
			break;
		if (m->used)
			continue;
		double d1 = fmax(fmax(fabs(g->x0 - m->x0), fabs(g->y0 - m->y0)), fmax(fabs(g->x1 - m->x1), fabs(g->y1 - m->y1)));
		double d2 = fmax(fmax(fabs(g->x0 - m->x1), fabs(g->y0 - m->y1)), fmax(fabs(g->x1 - m->x0), fabs(g->y1 - m->y0)));
		double d = fmin(d1, d2);
		if (d <= tol && d < bestd) {
			best = m;
			bestd = d;
			if (d == 0)
				break;
		}
	}
	if (best)
		best->used = 1;
	return best != NULL;
}

/* Is stroke j of b stroke i of a moved by a constant offset (either direction)? */
static int moved(const side_t *a, size_t i, const side_t *b, size_t j, double tol, double *dx, double *dy)
{
	const hpgl_rstroke_t *p = &a->doc.strokes[i], *q = &b->doc.strokes[j];
	if (p->pen != q->pen || p->n != q->n)
		return 0;
	for (int rev = 0; rev < 2; rev++) {
		const hpgl_rpt_t *u = a->doc.pts + p->start, *v = b->doc.pts + q->start;
		size_t n = p->n;
		double ox = v[rev ? n - 1 : 0].x - u[0].x, oy = v[rev ? n - 1 : 0].y - u[0].y;
		size_t k = 0;
		for (; k < n; k++) {
			const hpgl_rpt_t *w = &v[rev ? n - 1 - k : k];
			if (!near(u[k].x + ox, u[k].y + oy, w->x, w->y, tol))
				break;
		}
		if (k == n) {
			*dx = ox, *dy = oy;
			return 1;
		}
	}
	return 0;
}

/* Strict order: stroke k against stroke k, same pen, points and direction. */
static size_t strict(const side_t *a, const side_t *b, double tol, size_t *first)
{
	size_t n = a->doc.nstrokes > b->doc.nstrokes ? a->doc.nstrokes : b->doc.nstrokes, ndiff = 0;
	*first = (size_t)-1;
	for (size_t k = 0; k < n; k++) {
		int same = k < a->doc.nstrokes && k < b->doc.nstrokes;
		if (same) {
			const hpgl_rstroke_t *p = &a->doc.strokes[k], *q = &b->doc.strokes[k];
			same = p->pen == q->pen && p->n == q->n;
			for (size_t i = 0; same && i < p->n; i++)
				same = near(a->doc.pts[p->start + i].x, a->doc.pts[p->start + i].y,
					b->doc.pts[q->start + i].x, b->doc.pts[q->start + i].y, tol);
		}
		if (!same) {
			if (*first == (size_t)-1)
				*first = k;
			ndiff++;
		}
	}
	return ndiff;
}

static void stroke_desc(FILE *out, const side_t *s, size_t k)
{
	const hpgl_rstroke_t *st = &s->doc.strokes[k];
	const hpgl_rpt_t *p = s->doc.pts + st->start;
	fprintf(out, "pen %d, %zu points from (%.0f,%.0f) to (%.0f,%.0f), command %zu at byte %zu",
		st->pen, st->n, p[0].x, p[0].y, p[st->n - 1].x, p[st->n - 1].y, st->cmd, st->offset);
}

int diff_hpgl(const void *abuf, size_t na, const char *aname, const void *bbuf, size_t nb,
		const char *bname, const diff_opts_t *o, FILE *out, char *err, size_t errlen)
{
	side_t s[2];
	memset(s, 0, sizeof s);
	int rc = load(&s[0], abuf, na, aname, err, errlen);
	if (rc == 0)
		rc = load(&s[1], bbuf, nb, bname, err, errlen);
	if (rc) {
		unload(&s[0]);
		unload(&s[1]);
		return -1;
	}
	double tol = o->hpgl_tol;
	size_t miss = 0, extra = 0, first = 0, sdiff = 0;
	/* every segment of A looks for a partner in B; what is left in B is extra */
	for (size_t i = 0; i < s[0].nseg; i++)
		if (!take(&s[1], &s[0].seg[i], tol))
			s[0].bad[s[0].seg[i].stroke] = 1;
	for (size_t i = 0; i < s[1].nseg; i++)
		if (!s[1].seg[i].used)
			s[1].bad[s[1].seg[i].stroke] = 1;
	for (size_t k = 0; k < s[0].doc.nstrokes; k++)
		miss += s[0].bad[k];
	for (size_t k = 0; k < s[1].doc.nstrokes; k++)
		extra += s[1].bad[k];
	if (o->strict_order)
		sdiff = strict(&s[0], &s[1], tol, &first);
	/* labels: text and place */
	size_t ldiff = 0;
	for (size_t k = 0; k < s[0].doc.nlabels || k < s[1].doc.nlabels; k++) {
		const hpgl_rlabel_t *p = k < s[0].doc.nlabels ? &s[0].doc.labels[k] : NULL;
		const hpgl_rlabel_t *q = k < s[1].doc.nlabels ? &s[1].doc.labels[k] : NULL;
		if (!p || !q || p->pen != q->pen || strcmp(p->text, q->text) || !near(p->x, p->y, q->x, q->y, tol))
			ldiff++;
	}
	int same = miss == 0 && extra == 0 && ldiff == 0 && sdiff == 0;
	/* pair changed strokes that are only moved */
	unsigned char *pairedb = calloc(s[1].doc.nstrokes ? s[1].doc.nstrokes : 1, 1);
	if (o->json) {
		fprintf(out, "{\"kind\":\"hpgl\",\"a\":");
		diff_json_str(out, aname);
		fprintf(out, ",\"b\":");
		diff_json_str(out, bname);
		fprintf(out, ",\"same\":%s,\"strokes\":[%zu,%zu],\"segments\":[%zu,%zu],\"missing\":%zu,"
			"\"extra\":%zu,\"labels_differing\":%zu,\"pen_down_mm\":[%.1f,%.1f],\"pen_up_mm\":[%.1f,%.1f],"
			"\"plot_s\":[%.1f,%.1f]", same ? "true" : "false", s[0].doc.nstrokes, s[1].doc.nstrokes,
			s[0].nseg, s[1].nseg, miss, extra, ldiff, s[0].down_mm, s[1].down_mm, s[0].up_mm,
			s[1].up_mm, s[0].secs, s[1].secs);
		if (o->strict_order)
			fprintf(out, ",\"order_differing\":%zu", sdiff);
		fprintf(out, ",\"changes\":[");
		unsigned listed = 0;
		for (size_t k = 0; k < s[0].doc.nstrokes && listed < o->nfirst; k++) {
			if (!s[0].bad[k])
				continue;
			double dx = 0, dy = 0;
			size_t j = 0;
			for (; j < s[1].doc.nstrokes; j++)
				if (s[1].bad[j] && pairedb && !pairedb[j] && moved(&s[0], k, &s[1], j, tol, &dx, &dy))
					break;
			if (j < s[1].doc.nstrokes) {
				pairedb[j] = 1;
				fprintf(out, "%s{\"moved\":{\"a_cmd\":%zu,\"b_cmd\":%zu,\"dx\":%.2f,\"dy\":%.2f}}",
					listed ? "," : "", s[0].doc.strokes[k].cmd, s[1].doc.strokes[j].cmd, dx, dy);
			} else {
				fprintf(out, "%s{\"missing\":{\"a_cmd\":%zu,\"pen\":%d}}", listed ? "," : "",
					s[0].doc.strokes[k].cmd, s[0].doc.strokes[k].pen);
			}
			listed++;
		}
		for (size_t j = 0; j < s[1].doc.nstrokes && listed < o->nfirst; j++)
			if (s[1].bad[j] && !(pairedb && pairedb[j])) {
				fprintf(out, "%s{\"extra\":{\"b_cmd\":%zu,\"pen\":%d}}", listed ? "," : "",
					s[1].doc.strokes[j].cmd, s[1].doc.strokes[j].pen);
				listed++;
			}
		fprintf(out, "]}\n");
	} else {
		fprintf(out, "%s %s: HP-GL, %zu and %zu strokes: %zu missing or changed, %zu extra", aname,
			bname, s[0].doc.nstrokes, s[1].doc.nstrokes, miss, extra);
		if (ldiff)
			fprintf(out, ", %zu labels differ", ldiff);
		if (o->strict_order)
			fprintf(out, ", %zu out of order", sdiff);
		fprintf(out, "; pen-up travel %.1f vs %.1f mm, plot time %.1f vs %.1f s\n", s[0].up_mm,
			s[1].up_mm, s[0].secs, s[1].secs);
		if (o->verbose) {
			fprintf(out, "  pen-down length %.1f vs %.1f mm; tolerance %g plotter units\n",
				s[0].down_mm, s[1].down_mm, tol);
			if (o->strict_order && sdiff)
				fprintf(out, "  first stroke out of order: number %zu\n", first + 1);
			unsigned listed = 0;
			for (size_t k = 0; k < s[0].doc.nstrokes && listed < o->nfirst; k++, listed += 0) {
				if (!s[0].bad[k])
					continue;
				double dx = 0, dy = 0;
				size_t j = 0;
				for (; j < s[1].doc.nstrokes; j++)
					if (s[1].bad[j] && pairedb && !pairedb[j] && moved(&s[0], k, &s[1], j, tol, &dx, &dy))
						break;
				fprintf(out, "  %s A's stroke (", j < s[1].doc.nstrokes ? "moved:" : "missing:");
				stroke_desc(out, &s[0], k);
				if (j < s[1].doc.nstrokes) {
					pairedb[j] = 1;
					fprintf(out, ") by (%.1f,%.1f) to B's command %zu\n", dx, dy, s[1].doc.strokes[j].cmd);
				} else {
					fprintf(out, ")\n");
				}
				listed++;
			}
			for (size_t j = 0; j < s[1].doc.nstrokes && listed < o->nfirst; j++)
				if (s[1].bad[j] && !(pairedb && pairedb[j])) {
					fprintf(out, "  extra: B's stroke (");
					stroke_desc(out, &s[1], j);
					fprintf(out, ")\n");
					listed++;
				}
		}
	}
	free(pairedb);
	unload(&s[0]);
	unload(&s[1]);
	return same ? 0 : 1;
}
