/* voronoi.c: weighted distances to point/segment nuclei and exact, tile-culled, threaded pixel labelling. */
#include "voronoi_int.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

const char *voronoi_error(void)
{
	return msq_error();
}

double voronoi_distance(const voronoi_nucleus_t *n, const double p[3])
{
	return voronoi_dist(n, p);
}

/* Weighted distance of an unweighted distance d. */
static inline double weigh(const voronoi_nucleus_t *n, int metric, double d)
{
	return metric == VORONOI_MULTIPLICATIVE ? d / n->weight : d - n->weight;
}

double voronoi_weighted_distance(const voronoi_nucleus_t *n, int metric, const double p[3])
{
	return weigh(n, metric, voronoi_dist(n, p));
}

size_t voronoi_nearest(const voronoi_nucleus_t *nuclei, size_t count, int metric,
                       const double p[3], double *dw)
{
	size_t best = 0;
	double bd = INFINITY;
	for (size_t k = 0; k < count; k++) {
		double d = voronoi_weighted_distance(&nuclei[k], metric, p);
		if (d < bd) {
			bd = d;
			best = k;
		}
	}
	if (dw)
		*dw = bd;
	return best;
}

size_t voronoi_nearest2(const voronoi_nucleus_t *nuclei, size_t count, int metric,
                        const double p[3], double *dw1, size_t *second, double *dw2)
{
	size_t b1 = 0, b2 = SIZE_MAX;
	double d1 = INFINITY, d2 = INFINITY;
	for (size_t k = 0; k < count; k++) {
		double d = voronoi_weighted_distance(&nuclei[k], metric, p);
		if (d < d1) {
			b2 = b1 == 0 && d1 == INFINITY ? SIZE_MAX : b1;
			d2 = d1;
			b1 = k;
			d1 = d;
		} else if (d < d2 || b2 == SIZE_MAX) {
			b2 = k;
			d2 = d;
		}
	}
	if (dw1)
		*dw1 = d1;
	if (second)
		*second = b2;
	if (dw2)
		*dw2 = d2;
	return b1;
}

void voronoi_map_window(double m[6], double wx0, double wy0, double wx1, double wy1,
                        double px0, double py0, double px1, double py1)
{
	double sx = wx1 != wx0 ? (px1 - px0) / (wx1 - wx0) : 0;
	double sy = wy1 != wy0 ? (py1 - py0) / (wy1 - wy0) : 0;
	m[0] = px0 - sx * wx0;
	m[1] = sx;
	m[2] = 0;
	m[3] = py0 - sy * wy0;
	m[4] = 0;
	m[5] = sy;
}

int voronoi_invert(const voronoi_t *v, voronoi_inv_t *inv)
{
	const double *m = v->m;
	double det = m[1] * m[5] - m[2] * m[4];
	if (!isfinite(det) || fabs(det) < 1e-300)
		return voronoi_fail(VORONOI_EARG, "voronoi: the plane-to-page map is not invertible");
	inv->m0 = m[0];
	inv->m3 = m[3];
	inv->a = m[5] / det;
	inv->b = -m[2] / det;
	inv->c = -m[4] / det;
	inv->d = m[1] / det;
	return 0;
}

int voronoi_check(const voronoi_t *v)
{
	voronoi_inv_t inv;
	msq_clear();
	if (!v || !v->nuclei || v->count == 0)
		return voronoi_fail(VORONOI_EARG, "voronoi: no nuclei");
	if (v->count > VORONOI_MAX_NUCLEI)
		return voronoi_fail(VORONOI_EARG, "voronoi: %zu nuclei, at most %d", v->count, VORONOI_MAX_NUCLEI);
	if (v->metric != VORONOI_ADDITIVE && v->metric != VORONOI_MULTIPLICATIVE)
		return voronoi_fail(VORONOI_EARG, "voronoi: unknown metric %d", v->metric);
	for (int k = 0; k < 6; k++)
		if (!isfinite(v->m[k]))
			return voronoi_fail(VORONOI_EARG, "voronoi: map coefficient m[%d] is not finite", k);
	for (size_t k = 0; k < v->count; k++) {
		const voronoi_nucleus_t *n = &v->nuclei[k];
		int ends = n->kind == VORONOI_SEGMENT ? 2 : n->kind == VORONOI_POLYLINE ? 0 : 1;
		if (n->kind != VORONOI_POINT && n->kind != VORONOI_SEGMENT && n->kind != VORONOI_POLYLINE)
			return voronoi_fail(VORONOI_EARG, "voronoi: nucleus %zu: unknown kind %d", k, n->kind);
		if (n->kind == VORONOI_POLYLINE && (!n->pts || n->npts < 2))
			return voronoi_fail(VORONOI_EARG, "voronoi: nucleus %zu: a polyline needs at least 2 points", k);
		for (size_t i = 0; n->kind == VORONOI_POLYLINE && i < 3 * n->npts; i++)
			if (!isfinite(n->pts[i]))
				return voronoi_fail(VORONOI_EARG, "voronoi: nucleus %zu: coordinate not finite", k);
		for (int e = 0; e < ends; e++)
			for (int c = 0; c < 3; c++)
				if (!isfinite(e ? n->b[c] : n->a[c]))
					return voronoi_fail(VORONOI_EARG, "voronoi: nucleus %zu: coordinate not finite", k);
		if (!isfinite(n->weight) || (v->metric == VORONOI_MULTIPLICATIVE && !(n->weight > 0)))
			return voronoi_fail(VORONOI_EARG, "voronoi: nucleus %zu: weight %g (multiplicative weights must be > 0)",
			                    k, n->weight);
	}
	return voronoi_invert(v, &inv);
}

/* ---- labelling ------------------------------------------------------- */

#define TILE 64  /* pixels per tile side (the unit of work) */
#define SPLIT 4  /* a block with several candidates splits into SPLIT x SPLIT sub-blocks */
#define LEAF 4   /* blocks of at most LEAF x LEAF pixels are labelled pixel by pixel */
#define DEPTH 4  /* levels of splitting from TILE down to LEAF, plus one */

/* Shared state of one labelling; workers take tile rows t, t+T, t+2T... */
typedef struct {
	const voronoi_t *v;
	const voronoi_rect_t *r;
	voronoi_inv_t inv;
	int32_t *labels;
	unsigned nthreads;
	size_t tiles_y;
} job_t;

typedef struct {
	job_t *job;
	unsigned index;
	int rc;
} worker_t;

/* Label the pixels [i0, i1) x [j0, j1) of the rectangle. The nuclei in[0..nin)
 * (all nuclei when in is NULL) are culled with distance bounds at the block
 * centre (distances are 1-Lipschitz: |d(P) - d(C)| <= |P - C|) into out; one
 * survivor owns the whole block; otherwise a large block is split into
 * SPLIT x SPLIT sub-blocks culled again (64, 16, 4 pixels), and a small one
 * is labelled pixel by pixel
 * over the survivors, in index order with a strict <, exactly as
 * voronoi_nearest does. out has room for DEPTH * count entries. */
static void label_block(job_t *jb, unsigned i0, unsigned j0, unsigned i1, unsigned j1,
                        const size_t *in, size_t nin, size_t *out, double *lower)
{
	const voronoi_t *v = jb->v;
	const voronoi_rect_t *r = jb->r;
	double cxp = r->x + (i0 + i1) * 0.5, cyp = r->y + (j0 + j1) * 0.5, c[3], q[3];
	voronoi_unmap(&jb->inv, cxp, cyp, c);
	/* radius: farthest pixel centre of the block from its centre, in the plane */
	double rad = 0;
	for (int k = 0; k < 4; k++) {
		double px = r->x + ((k & 1) ? i1 - 0.5 : i0 + 0.5), py = r->y + ((k & 2) ? j1 - 0.5 : j0 + 0.5);
		voronoi_unmap(&jb->inv, px, py, q);
		double ex = q[0] - c[0], ey = q[1] - c[1], dd = sqrt(ex * ex + ey * ey);
		rad = dd > rad ? dd : rad;
	}
	double ubest = INFINITY;
	for (size_t s = 0; s < nin; s++) {
		const voronoi_nucleus_t *n = &v->nuclei[in ? in[s] : s];
		double d = voronoi_dist(n, c);
		double lo = d - rad, hi = d + rad;
		lo = lo < 0 ? 0 : lo;
		double whi = weigh(n, v->metric, hi);
		lower[s] = weigh(n, v->metric, lo);
		ubest = whi < ubest ? whi : ubest;
	}
	/* a margin for rounding: a nucleus is dropped only when it surely loses */
	double margin = 1e-9 * (fabs(ubest) + rad + 1); /* also covers sqrt's rounding in rad */
	size_t nc = 0;
	for (size_t s = 0; s < nin; s++)
		if (lower[s] <= ubest + margin)
			out[nc++] = in ? in[s] : s;
	if (nc == 1) { /* the usual case: the whole block belongs to one nucleus */
		for (unsigned j = j0; j < j1; j++)
			for (unsigned i = i0; i < i1; i++)
				jb->labels[(size_t)j * r->width + i] = (int32_t)out[0];
		return;
	}
	unsigned side = (i1 - i0 > j1 - j0 ? i1 - i0 : j1 - j0);
	if (side > LEAF) {
		unsigned sub = (side + SPLIT - 1) / SPLIT;
		sub = sub < LEAF ? LEAF : sub;
		for (unsigned sj = j0; sj < j1; sj += sub)
			for (unsigned si = i0; si < i1; si += sub)
				label_block(jb, si, sj, si + sub < i1 ? si + sub : i1, sj + sub < j1 ? sj + sub : j1,
				            out, nc, out + nc, lower);
		return;
	}
	for (unsigned j = j0; j < j1; j++) {
		int32_t *row = jb->labels + (size_t)j * r->width;
		for (unsigned i = i0; i < i1; i++) {
			voronoi_unmap(&jb->inv, r->x + i + 0.5, r->y + j + 0.5, q);
			size_t best = out[0];
			double bd = INFINITY;
			for (size_t s = 0; s < nc; s++) {
				const voronoi_nucleus_t *n = &v->nuclei[out[s]];
				double d = weigh(n, v->metric, voronoi_dist(n, q));
				if (d < bd) {
					bd = d;
					best = out[s];
				}
			}
			row[i] = (int32_t)best;
		}
	}
}

static void *work(void *arg)
{
	worker_t *wk = arg;
	job_t *jb = wk->job;
	size_t n = jb->v->count;
	size_t *cand = malloc(DEPTH * n * sizeof *cand);
	double *lower = malloc(n * sizeof *lower);
	if (!cand || !lower) {
		wk->rc = VORONOI_ENOMEM;
	} else {
		unsigned tiles_x = (jb->r->width + TILE - 1) / TILE;
		for (size_t ty = wk->index; ty < jb->tiles_y; ty += jb->nthreads)
			for (unsigned tx = 0; tx < tiles_x; tx++) {
				unsigned i0 = tx * TILE, j0 = (unsigned)ty * TILE;
				unsigned i1 = i0 + TILE < jb->r->width ? i0 + TILE : jb->r->width;
				unsigned j1 = j0 + TILE < jb->r->height ? j0 + TILE : jb->r->height;
				label_block(jb, i0, j0, i1, j1, NULL, n, cand, lower);
			}
	}
	free(cand);
	free(lower);
	return NULL;
}

int voronoi_label(const voronoi_t *v, const voronoi_rect_t *r, unsigned threads,
                  int32_t *labels)
{
	int rc = voronoi_check(v);
	if (rc < 0)
		return rc;
	if (!r || !labels || r->width == 0 || r->height == 0)
		return voronoi_fail(VORONOI_EARG, "voronoi: empty rectangle or no label buffer");
	job_t jb;
	memset(&jb, 0, sizeof jb);
	jb.v = v;
	jb.r = r;
	jb.labels = labels;
	jb.tiles_y = (r->height + TILE - 1) / TILE;
	voronoi_invert(v, &jb.inv);
	if (threads == 0) {
		long n = sysconf(_SC_NPROCESSORS_ONLN);
		threads = n > 0 ? (unsigned)n : 1;
	}
	threads = threads > 16 ? 16 : threads;
	threads = threads > jb.tiles_y ? (unsigned)jb.tiles_y : threads;
	jb.nthreads = threads;
	worker_t wk[16];
	pthread_t tid[16];
	unsigned started = 0;
	for (unsigned t = 0; t < threads; t++) {
		wk[t].job = &jb;
		wk[t].index = t;
		wk[t].rc = 0;
	}
	/* worker 0 runs in this thread; a worker that cannot be started is run
	 * here too, so the result never depends on what the system allows */
	for (unsigned t = 1; t < threads; t++) {
		if (pthread_create(&tid[t], NULL, work, &wk[t]) != 0)
			break;
		started = t;
	}
	work(&wk[0]);
	for (unsigned t = started + 1; t < threads; t++)
		work(&wk[t]);
	for (unsigned t = 1; t <= started; t++)
		pthread_join(tid[t], NULL);
	for (unsigned t = 0; t < threads; t++)
		if (wk[t].rc < 0)
			return voronoi_fail(wk[t].rc, "voronoi: out of memory for %zu nuclei", v->count);
	return 0;
}
