/* import_svg_dedupe.c: -O dedupe: strokes that retrace earlier ones of the same pen (duplicates,
 * overlapping collinear pieces, shared edges of tiles) removed within a tolerance. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "import/svg_import.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define ANG_BUCKETS 360      /* half a degree a bucket */
#define MAX_IV 4             /* kept pieces per segment; more fragments keep the segment whole */

typedef struct {
	svg_pt_t p, q;
	uint64_t pen;           /* colour and width: only strokes of one pen retrace each other */
	double t0[MAX_IV], t1[MAX_IV];   /* kept parts, parameters 0..1 */
	int niv;
	long next;              /* next segment in the same bucket */
} seg_t;

typedef struct {
	uint64_t *key;
	long *head;
	size_t mask;
} table_t;

static uint64_t mix(uint64_t x)
{
	x ^= x >> 33;
	x *= 0xff51afd7ed558ccdULL;
	x ^= x >> 33;
	x *= 0xc4ceb9fe1a85ec53ULL;
	return x ^ (x >> 33);
}

static long *slot(table_t *t, uint64_t k)
{
	for (size_t i = mix(k) & t->mask;; i = (i + 1) & t->mask) {
		if (t->head[i] == -1) {
			t->key[i] = k;
			return &t->head[i];
		}
		if (t->key[i] == k)
			return &t->head[i];
	}
}

static uint64_t bkey(uint64_t pen, long a, long c)
{
	a = ((a % ANG_BUCKETS) + ANG_BUCKETS) % ANG_BUCKETS;
	return mix(pen) ^ ((uint64_t)a << 40) ^ (uint64_t)(c & 0xffffffffffLL);
}

static void line_of(const seg_t *s, double *ang, double *c)
{
	double dx = s->q.x - s->p.x, dy = s->q.y - s->p.y;
	double a = atan2(dy, dx);
	if (a < 0)
		a += M_PI;
	if (a >= M_PI)
		a -= M_PI;
	*ang = a;
	*c = -sin(a) * s->p.x + cos(a) * s->p.y;
}

/* Remove from s the part that q covers (q collinear with s within tol). */
static void subtract(seg_t *s, const seg_t *q, double tol)
{
	double dx = s->q.x - s->p.x, dy = s->q.y - s->p.y, L2 = dx * dx + dy * dy;
	if (L2 <= 0)
		return;
	double L = sqrt(L2);
	/* both ends of s's covered part must lie within tol of q's line: check q's ends against s */
	double ex = q->q.x - q->p.x, ey = q->q.y - q->p.y, M = hypot(ex, ey);
	if (M <= 0)
		return;
	for (int e = 0; e < 2; e++) {
		svg_pt_t a = e ? s->q : s->p;
		double dist = fabs((a.x - q->p.x) * ey - (a.y - q->p.y) * ex) / M;
		double t = ((a.x - q->p.x) * ex + (a.y - q->p.y) * ey) / (M * M);
		if (dist > tol && t >= 0 && t <= 1)
			return;
	}
	for (int e = 0; e < 2; e++) {
		svg_pt_t a = e ? q->q : q->p;
		double dist = fabs((a.x - s->p.x) * dy - (a.y - s->p.y) * dx) / L;
		if (dist > tol)
			return;
	}
	double u0 = ((q->p.x - s->p.x) * dx + (q->p.y - s->p.y) * dy) / L2;
	double u1 = ((q->q.x - s->p.x) * dx + (q->q.y - s->p.y) * dy) / L2;
	if (u0 > u1) {
		double t = u0;
		u0 = u1, u1 = t;
	}
	double small = tol / L;   /* what is left shorter than the tolerance goes too */
	double n0[MAX_IV * 2], n1[MAX_IV * 2];
	int n = 0;
	for (int i = 0; i < s->niv; i++) {
		double a = s->t0[i], b = s->t1[i];
		if (u1 <= a || u0 >= b) {
			n0[n] = a, n1[n++] = b;
			continue;
		}
		if (u0 - a > small)
			n0[n] = a, n1[n++] = u0;
		if (b - u1 > small)
			n0[n] = u1, n1[n++] = b;
	}
	if (n > MAX_IV)
		return;   /* too fragmented: kept as it was */
	for (int i = 0; i < n; i++)
		s->t0[i] = n0[i], s->t1[i] = n1[i];
	s->niv = n;
}

int svg_dedupe(svg_doc_t *d, double tol)
{
	size_t ns = 0;
	for (size_t i = 0; i < d->n; i++) {
		const svg_geom_t *g = &d->it[i].g;
		if (d->it[i].kind == SVGI_STROKE)
			for (size_t s = 0; s < g->nsub; s++)
				ns += (s + 1 < g->nsub ? g->sub[s + 1] : g->n) - g->sub[s] + 1;
	}
	if (!ns || !(tol > 0))
		return 0;
	seg_t *seg = malloc(ns * sizeof *seg);
	table_t t;
	size_t cap = 16;
	while (cap < ns * 2)
		cap *= 2;
	t.mask = cap - 1;
	t.key = malloc(cap * sizeof *t.key);
	t.head = malloc(cap * sizeof *t.head);
	if (!seg || !t.key || !t.head) {
		free(seg), free(t.key), free(t.head);
		return -1;
	}
	for (size_t i = 0; i < cap; i++)
		t.head[i] = -1;
	double abucket = M_PI / ANG_BUCKETS;
	size_t k = 0;
	for (size_t i = 0; i < d->n; i++) {
		svg_item_t *it = &d->it[i];
		if (it->kind != SVGI_STROKE)
			continue;
		uint64_t pen = (uint64_t)(d->o->pens_mode ? (uint32_t)it->pen : it->rgb) << 32 ^ (uint64_t)lround(it->width * 1000);
		const svg_geom_t *g = &it->g;
		for (size_t s = 0; s < g->nsub; s++) {
			size_t a = g->sub[s], b = s + 1 < g->nsub ? g->sub[s + 1] : g->n;
			size_t m = b - a + (g->closed[s] && b - a > 1 ? 1 : 0);
			for (size_t j = 1; j < m; j++, k++) {
				seg_t *sg = &seg[k];
				sg->p = g->pt[a + j - 1], sg->q = g->pt[j < b - a ? a + j : a];
				sg->pen = pen;
				sg->niv = 1, sg->t0[0] = 0, sg->t1[0] = 1;
				double L = hypot(sg->q.x - sg->p.x, sg->q.y - sg->p.y);
				if (L <= tol) {
					sg->next = -2;   /* too short to tell its direction: kept, not indexed */
					continue;
				}
				double ang, c;
				line_of(sg, &ang, &c);
				long ab = (long)floor(ang / abucket), cb = (long)floor(c / tol);
				/* neighbours: the angle and offset buckets around (the offset's sign flips at the wrap) */
				for (long da = -1; da <= 1 && sg->niv; da++)
					for (long dc = -1; dc <= 1 && sg->niv; dc++) {
						long aa = ab + da, cc = cb + dc;
						if (aa < 0 || aa >= ANG_BUCKETS)
							cc = -cb - 1 + dc;
						long *h = slot(&t, bkey(pen, aa, cc));
						for (long q = *h; q >= 0 && sg->niv; q = seg[q].next)
							if (seg[q].pen == pen)
								subtract(sg, &seg[q], tol);
					}
				long *h = slot(&t, bkey(pen, ab, cb));
				sg->next = *h;
				*h = (long)k;
			}
			k += 0;
		}
	}
	/* rebuild each stroke from its kept pieces */
	k = 0;
	for (size_t i = 0; i < d->n; i++) {
		svg_item_t *it = &d->it[i];
		if (it->kind != SVGI_STROKE)
			continue;
		svg_geom_t *g = &it->g, o = { .tol = g->tol, .m = { 1, 0, 0, 1, 0, 0 } };
		for (size_t s = 0; s < g->nsub; s++) {
			size_t a = g->sub[s], b = s + 1 < g->nsub ? g->sub[s + 1] : g->n;
			size_t m = b - a + (g->closed[s] && b - a > 1 ? 1 : 0);
			if (m == 1) {   /* a lone point (a dot with round caps) stays */
				svg_geom_move(&o, g->pt[a].x, g->pt[a].y);
				if (g->closed[s])
					svg_geom_close(&o);
				continue;
			}
			int open = 0, whole = 1;
			size_t start_sub = o.nsub;
			for (size_t j = 1; j < m; j++, k++) {
				seg_t *sg = &seg[k];
				if (!(sg->niv == 1 && sg->t0[0] <= 0 && sg->t1[0] >= 1))
					whole = 0;
				for (int v = 0; v < sg->niv; v++) {
					double t0 = fmax(sg->t0[v], 0), t1 = fmin(sg->t1[v], 1);
					if (t1 - t0 <= 0)
						continue;
					double dx = sg->q.x - sg->p.x, dy = sg->q.y - sg->p.y;
					if (!open || t0 > 0)
						svg_geom_move(&o, sg->p.x + dx * t0, sg->p.y + dy * t0);
					svg_geom_line(&o, sg->p.x + dx * t1, sg->p.y + dy * t1);
					open = t1 >= 1;
				}
				if (sg->niv == 0 || sg->t1[sg->niv - 1] < 1)
					open = 0;
			}
			if (whole && g->closed[s] && o.nsub == start_sub + 1) {
				o.n--;   /* the closing point again: closed instead */
				svg_geom_close(&o);
			}
		}
		if (o.oom) {
			svg_geom_free(&o);
			free(seg), free(t.key), free(t.head);
			return -1;
		}
		svg_geom_free(g);
		*g = o;
	}
	free(seg), free(t.key), free(t.head);
	return 0;
}
