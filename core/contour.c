/* contour.c: marching-squares iso-lines joined into polylines by tracing from cell to cell. */
#include "contour.h"
#include "contour_int.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *contour_error(void)
{
	return msq_error();
}

#define KNAN 0xffffu      /* level count of a non-finite sample */
#define CELL_BAD 0x80u    /* cell flag: a corner is not finite */
#define MAX_LEVELS 65534u

/* Per-call state of one extraction. */
typedef struct {
	const contour_grid_t *g;
	const float *z;
	size_t nx, ny;          /* samples */
	size_t cx, cy;          /* cells */
	uint8_t *flags;         /* per cell: CELL_BAD, visited entry bits 0..3 */
	contour_point_t *pts;
	size_t npts, cap;
	contour_stats_t st;
} ctx_t;

/* Case index (0..31: bit 4 = centre above) of cell c = (i, j) for level L. */
static inline int cell_case(const ctx_t *x, size_t c, double L)
{
	size_t i = c % x->cx, j = c / x->cx;
	const float *r0 = x->z + j * x->nx + i, *r1 = r0 + x->nx;
	int cs = (r0[0] >= L) | (r0[1] >= L) << 1 | (r1[1] >= L) << 2 | (r1[0] >= L) << 3;
	if (cs == 5 || cs == 10) {
		double avg = ((double)r0[0] + r0[1] + r1[0] + r1[1]) * 0.25;
		if (avg >= L)
			cs |= 16;
	}
	return cs;
}

/* The cell across edge e of cell c, or SIZE_MAX when outside or bad. */
static inline size_t across(const ctx_t *x, size_t c, int e)
{
	size_t i = c % x->cx, j = c / x->cx, n;
	switch (e) {
	case 0: if (j == 0) return SIZE_MAX; n = c - x->cx; break;
	case 1: if (i + 1 == x->cx) return SIZE_MAX; n = c + 1; break;
	case 2: if (j + 1 == x->cy) return SIZE_MAX; n = c + x->cx; break;
	default: if (i == 0) return SIZE_MAX; n = c - 1; break;
	}
	return (x->flags[n] & CELL_BAD) ? SIZE_MAX : n;
}

static int grow(ctx_t *x)
{
	size_t cap = x->cap ? x->cap * 2 : 4096;
	contour_point_t *p = realloc(x->pts, cap * sizeof *p);
	if (!p)
		return contour_fail(CONTOUR_ENOMEM, "contour: out of memory for %zu points", cap);
	x->pts = p;
	x->cap = cap;
	return 0;
}

/* Append the crossing point of level L on edge e of cell c (page pixels).
 * Each point is computed from the edge's two samples in a fixed order
 * (left to right, bottom to top) so both cells sharing an edge agree. */
static inline int push(ctx_t *x, size_t c, int e, double L)
{
	size_t i = c % x->cx, j = c / x->cx;
	double gi, gj, za, zb;
	if (e == 0 || e == 2) {
		if (e == 2)
			j++;
		za = x->z[j * x->nx + i];
		zb = x->z[j * x->nx + i + 1];
		gi = (double)i + (L - za) / (zb - za);
		gj = (double)j;
	} else {
		if (e == 1)
			i++;
		za = x->z[j * x->nx + i];
		zb = x->z[(j + 1) * x->nx + i];
		gi = (double)i;
		gj = (double)j + (L - za) / (zb - za);
	}
	const double *m = x->g->m;
	contour_point_t p = { m[0] + m[1] * gi + m[2] * gj, m[3] + m[4] * gi + m[5] * gj };
	if (x->npts && x->pts[x->npts - 1].x == p.x && x->pts[x->npts - 1].y == p.y)
		return 0; /* a sample exactly on the level: drop the repeat */
	if (x->npts == x->cap) {
		int rc = grow(x);
		if (rc < 0)
			return rc;
	}
	x->pts[x->npts++] = p;
	return 0;
}

/* Follow the chain whose segment enters cell c by edge e, marking segments
 * visited, and hand the polyline to fn. */
static int trace(ctx_t *x, size_t c, int e, double L, unsigned level, contour_fn fn, void *user)
{
	size_t c0 = c;
	int e0 = e, closed = 0, rc;
	x->npts = 0;
	if ((rc = push(x, c, e, L)) < 0)
		return rc;
	for (;;) {
		if (x->flags[c] & (1u << e))
			break; /* cannot happen on consistent data; never loop */
		int cs = cell_case(x, c, L), out = msq_exit[cs >> 4][cs & 15][e];
		if (out < 0)
			break;
		x->flags[c] |= (uint8_t)(1u << e);
		x->st.segments++;
		size_t n = across(x, c, out);
		if (n == c0 && ((out + 2) & 3) == e0) {
			closed = 1;
			break;
		}
		if ((rc = push(x, c, out, L)) < 0)
			return rc;
		if (n == SIZE_MAX)
			break;
		c = n;
		e = (out + 2) & 3;
	}
	size_t np = x->npts;
	if (closed && np > 1 && x->pts[np - 1].x == x->pts[0].x && x->pts[np - 1].y == x->pts[0].y)
		np--;
	if (np < 2)
		return 0; /* degenerate: the level only touches samples */
	x->st.polylines++;
	x->st.closed += closed != 0;
	x->st.points += np;
	if (fn(user, level, x->pts, np, closed) < 0)
		return contour_fail(CONTOUR_ECALLBACK, "contour: stopped by the caller at level %u", level);
	return 0;
}

/* out[i] = the number of sorted levels sl[0..nl) <= z[i] (KNAN for a
 * non-finite sample): a cell is crossed by the sorted levels [min, max) of
 * its corners' counts. Smooth fields change the count rarely between
 * neighbours, so start from the previous sample's (*kk) and fall back to a
 * binary search on a jump. */
static void level_row(const float *z, size_t n, const double *sl, unsigned nl, unsigned *kk, uint16_t *out)
{
	unsigned kc = *kk;
	for (size_t s = 0; s < n; s++) {
		double v = z[s];
		if (!isfinite(v)) {
			out[s] = KNAN;
			continue;
		}
		if ((kc == 0 || sl[kc - 1] <= v) && (kc == nl || v < sl[kc])) {
			out[s] = (uint16_t)kc;
			continue;
		}
		unsigned lo = 0, hi = nl;
		if (kc < nl && v >= sl[kc]) {
			lo = kc + 1;
			if (lo < nl && v < sl[lo])
				hi = lo;
		} else {
			hi = kc - 1;
			if (hi > 0 && sl[hi - 1] <= v)
				lo = hi;
		}
		while (lo < hi) { /* first level > v within [lo, hi] */
			unsigned mid = lo + (hi - lo) / 2;
			if (sl[mid] <= v)
				lo = mid + 1;
			else
				hi = mid;
		}
		kc = lo;
		out[s] = (uint16_t)kc;
	}
	*kk = kc;
}

/* A crossed cell and its range of sorted level indices [lo, hi). */
typedef struct {
	uint32_t cell;
	uint16_t lo, hi;
} cand_t;

/* Sort helper: level indices by value (stable by index). */
static _Thread_local const double *sort_levels;
static int cmp_level(const void *a, const void *b)
{
	unsigned ia = *(const unsigned *)a, ib = *(const unsigned *)b;
	double va = sort_levels[ia], vb = sort_levels[ib];
	if (va != vb)
		return va < vb ? -1 : 1;
	return ia < ib ? -1 : ia > ib;
}

static int check_grid(const contour_grid_t *g)
{
	if (!g || !g->z)
		return contour_fail(CONTOUR_EARG, "contour: no grid");
	if (g->nx < 2 || g->ny < 2)
		return contour_fail(CONTOUR_EARG, "contour: grid of %ux%u samples, need at least 2x2", g->nx, g->ny);
	if ((uint64_t)(g->nx - 1) * (g->ny - 1) >= UINT32_MAX)
		return contour_fail(CONTOUR_EARG, "contour: grid of %ux%u samples is too large", g->nx, g->ny);
	for (int k = 0; k < 6; k++)
		if (!isfinite(g->m[k]))
			return contour_fail(CONTOUR_EARG, "contour: grid map coefficient m[%d] is not finite", k);
	return 0;
}

int contour_extract(const contour_grid_t *g, const double *levels, unsigned nlevels,
                    contour_fn fn, void *user, contour_stats_t *stats)
{
	ctx_t x = { 0 };
	uint16_t *k = NULL;
	uint32_t *bucket = NULL;
	cand_t *cand = NULL;
	size_t *start = NULL;
	unsigned *order = NULL, *pos = NULL;
	double *sl = NULL;
	int rc;
	msq_clear();
	if (stats)
		memset(stats, 0, sizeof *stats);
	if ((rc = check_grid(g)) < 0)
		return rc;
	if (!fn || (nlevels && !levels))
		return contour_fail(CONTOUR_EARG, "contour: no callback or no levels");
	if (nlevels > MAX_LEVELS)
		return contour_fail(CONTOUR_EARG, "contour: %u levels, at most %u", nlevels, MAX_LEVELS);
	for (unsigned l = 0; l < nlevels; l++)
		if (!isfinite(levels[l]))
			return contour_fail(CONTOUR_EARG, "contour: level %u is not finite", l);
	if (nlevels == 0)
		return 0;
	x.g = g;
	x.z = g->z;
	x.nx = g->nx;
	x.ny = g->ny;
	x.cx = x.nx - 1;
	x.cy = x.ny - 1;
	size_t ncells = x.cx * x.cy;

	order = malloc(nlevels * sizeof *order);
	pos = malloc(nlevels * sizeof *pos);
	sl = malloc(nlevels * sizeof *sl);
	start = calloc((size_t)nlevels + 1, sizeof *start);
	k = malloc(2 * x.nx * sizeof *k); /* two rows of level counts */
	x.flags = calloc(ncells, 1);
	if (!order || !pos || !sl || !start || !k || !x.flags) {
		rc = contour_fail(CONTOUR_ENOMEM, "contour: out of memory for a %ux%u grid", g->nx, g->ny);
		goto done;
	}
	for (unsigned l = 0; l < nlevels; l++)
		order[l] = l;
	sort_levels = levels;
	qsort(order, nlevels, sizeof *order, cmp_level);
	for (unsigned l = 0; l < nlevels; l++) {
		sl[l] = levels[order[l]];
		pos[order[l]] = l;
	}

	/* one scan: the crossed cells (most cells are not), then count and
	 * bucket them per level in scan order */
	size_t ncand = 0, capc = 0;
	unsigned kk = 0;
	uint16_t *k0 = k, *k1 = k + x.nx;
	level_row(x.z, x.nx, sl, nlevels, &kk, k0);
	for (size_t j = 0; j < x.cy; j++) {
		level_row(x.z + (j + 1) * x.nx, x.nx, sl, nlevels, &kk, k1);
		for (size_t i = 0; i < x.cx; i++) {
			unsigned a = k0[i], b = k0[i + 1], c = k1[i], d = k1[i + 1];
			if (((a ^ b) | (a ^ c) | (a ^ d)) == 0 && a != KNAN)
				continue;
			unsigned lo = a < b ? a : b, hi = a < b ? b : a;
			unsigned lo2 = c < d ? c : d, hi2 = c < d ? d : c;
			lo = lo < lo2 ? lo : lo2;
			hi = hi < hi2 ? hi2 : hi;
			if (hi == KNAN) {
				x.flags[j * x.cx + i] = CELL_BAD;
				continue;
			}
			if (ncand == capc) {
				size_t nc = capc ? capc * 2 : 4096;
				cand_t *p = realloc(cand, nc * sizeof *p);
				if (!p) {
					rc = contour_fail(CONTOUR_ENOMEM, "contour: out of memory for %zu crossed cells", nc);
					goto done;
				}
				cand = p;
				capc = nc;
			}
			cand[ncand].cell = (uint32_t)(j * x.cx + i);
			cand[ncand].lo = (uint16_t)lo;
			cand[ncand].hi = (uint16_t)hi;
			ncand++;
		}
		uint16_t *t = k0;
		k0 = k1;
		k1 = t;
	}
	for (size_t q = 0; q < ncand; q++)
		for (unsigned l = cand[q].lo; l < cand[q].hi; l++)
			start[l + 1]++;
	for (unsigned l = 0; l < nlevels; l++)
		start[l + 1] += start[l];
	bucket = malloc((start[nlevels] ? start[nlevels] : 1) * sizeof *bucket);
	if (!bucket) {
		rc = contour_fail(CONTOUR_ENOMEM, "contour: out of memory for %zu crossings", start[nlevels]);
		goto done;
	}
	for (size_t q = 0; q < ncand; q++)
		for (unsigned l = cand[q].lo; l < cand[q].hi; l++)
			bucket[start[l]++] = cand[q].cell;
	/* start[l] now holds the end of bucket l: shift back */
	memmove(start + 1, start, nlevels * sizeof *start);
	start[0] = 0;

	for (unsigned o = 0; o < nlevels; o++) {
		unsigned l = pos[o];
		double L = sl[l];
		const uint32_t *cells = bucket + start[l];
		size_t n = start[l + 1] - start[l];
		/* open chains first: segments entering from outside or a bad cell */
		for (size_t q = 0; q < n && rc == 0; q++) {
			size_t c = cells[q];
			int cs = cell_case(&x, c, L);
			for (int e = 0; e < 4 && rc == 0; e++)
				if (msq_exit[cs >> 4][cs & 15][e] >= 0 && !(x.flags[c] & (1u << e)) &&
				    across(&x, c, e) == SIZE_MAX)
					rc = trace(&x, c, e, L, o, fn, user);
		}
		/* then the closed loops: everything not yet visited */
		for (size_t q = 0; q < n && rc == 0; q++) {
			size_t c = cells[q];
			int cs = cell_case(&x, c, L);
			for (int e = 0; e < 4 && rc == 0; e++)
				if (msq_exit[cs >> 4][cs & 15][e] >= 0 && !(x.flags[c] & (1u << e)))
					rc = trace(&x, c, e, L, o, fn, user);
		}
		for (size_t q = 0; q < n; q++)
			x.flags[cells[q]] &= CELL_BAD;
		if (rc < 0)
			break;
	}
done:
	if (stats)
		*stats = x.st;
	free(x.pts);
	free(x.flags);
	free(k);
	free(bucket);
	free(cand);
	free(start);
	free(order);
	free(pos);
	free(sl);
	return rc;
}
