/* voronoi_trace.c: Voronoi cell boundaries traced from a label image into joined sub-pixel polylines. */
#include "voronoi_int.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The dual grid: cell (i, j) has the pixel centres (i, j), (i+1, j),
 * (i+1, j+1), (i, j+1) as corners 0..3; edge k joins corner k to k+1. A cell
 * whose corners carry two labels is crossed by one boundary (or two, for a
 * diagonal pair) and traced like a marching-squares cell with the smaller
 * label "above"; a cell with three or more labels is a junction: its crossed
 * edges all join one junction point. */

#define JUNCTION 0x10u
#define MIXED 0x20u

typedef struct {
	const voronoi_t *v;
	const voronoi_rect_t *r;
	const int32_t *lab;
	voronoi_inv_t inv;
	size_t w, h, cx, cy;       /* pixels, cells */
	uint8_t *flags;            /* per cell: visited entries (bits 0..3), JUNCTION, MIXED */
	voronoi_point_t *pts;
	size_t npts, cap;
	int start_border, end_border; /* the polyline being built starts/ends at the rectangle's edge */
	voronoi_fn fn;
	void *user;
	voronoi_stats_t st;
} tctx_t;

/* Corner labels of cell c. */
static inline void corners(const tctx_t *x, size_t c, int32_t L[4])
{
	size_t i = c % x->cx, j = c / x->cx;
	const int32_t *r0 = x->lab + j * x->w + i, *r1 = r0 + x->w;
	L[0] = r0[0];
	L[1] = r0[1];
	L[2] = r1[1];
	L[3] = r1[0];
}

static double wdist(const tctx_t *x, int32_t k, double px, double py)
{
	double p[3];
	voronoi_unmap(&x->inv, px, py, p);
	const voronoi_nucleus_t *n = &x->v->nuclei[k];
	double d = voronoi_dist(n, p);
	return x->v->metric == VORONOI_MULTIPLICATIVE ? d / n->weight : d - n->weight;
}

/* Case index (bit 4: centre owned by the smaller label) of a two-label cell. */
static int cell_case(const tctx_t *x, size_t c, int32_t *lo, int32_t *hi)
{
	int32_t L[4];
	corners(x, c, L);
	int32_t a = L[0], b = L[0];
	for (int k = 1; k < 4; k++) {
		a = L[k] < a ? L[k] : a;
		b = L[k] > b ? L[k] : b;
	}
	int cs = (L[0] == a) | (L[1] == a) << 1 | (L[2] == a) << 2 | (L[3] == a) << 3;
	if (cs == 5 || cs == 10) {
		double px = x->r->x + (double)(c % x->cx) + 1, py = x->r->y + (double)(c / x->cx) + 1;
		if (wdist(x, a, px, py) <= wdist(x, b, px, py))
			cs |= 16;
	}
	*lo = a;
	*hi = b;
	return cs;
}

/* The boundary point on edge e of cell c: where the two labels' weighted
 * distances are equal on the segment between the edge's pixel centres,
 * always solved from the left/bottom pixel so both cells agree. */
static voronoi_point_t crossing(const tctx_t *x, size_t c, int e)
{
	size_t i = c % x->cx, j = c / x->cx, i2, j2;
	if (e == 0 || e == 2) {
		j += e == 2;
		i2 = i + 1;
		j2 = j;
	} else {
		i += e == 1;
		i2 = i;
		j2 = j + 1;
	}
	int32_t la = x->lab[j * x->w + i], lb = x->lab[j2 * x->w + i2];
	double x0 = x->r->x + (double)i + 0.5, y0 = x->r->y + (double)j + 0.5;
	double dx = (double)i2 - (double)i, dy = (double)j2 - (double)j;
	/* g(t) = dw_a - dw_b: <= 0 at t = 0, >= 0 at t = 1; Illinois regula falsi */
	double t0 = 0, t1 = 1;
	double g0 = wdist(x, la, x0, y0) - wdist(x, lb, x0, y0);
	double g1 = wdist(x, la, x0 + dx, y0 + dy) - wdist(x, lb, x0 + dx, y0 + dy);
	double t = 0.5;
	int side = 0;
	if (g0 >= 0)
		t1 = 0; /* a tie at the first pixel centre */
	else if (g1 <= 0)
		t0 = 1; /* a tie at the second */
	double tprev = -1;
	for (int it = 0; it < 60 && t1 - t0 > 1e-7; it++) {
		t = t0 - g0 * (t1 - t0) / (g1 - g0);
		if (!(t > t0 && t < t1))
			t = 0.5 * (t0 + t1);
		if (fabs(t - tprev) < 1e-8) { /* the estimates have converged */
			t0 = t1 = t;
			break;
		}
		tprev = t;
		double g = wdist(x, la, x0 + t * dx, y0 + t * dy) - wdist(x, lb, x0 + t * dx, y0 + t * dy);
		if (g == 0) {
			t0 = t1 = t;
			break;
		}
		if (g < 0) {
			t0 = t;
			g0 = g;
			if (side == -1)
				g1 *= 0.5;
			side = -1;
		} else {
			t1 = t;
			g1 = g;
			if (side == 1)
				g0 *= 0.5;
			side = 1;
		}
	}
	t = 0.5 * (t0 + t1);
	voronoi_point_t p = { x0 + t * dx, y0 + t * dy };
	return p;
}

/* The junction point of a junction cell. Where exactly three cells meet it is
 * the Voronoi vertex, solved by Newton's method (dw_a = dw_b = dw_c) from the
 * mean of the cell's crossings, accepted when it converges inside the cell
 * (with half a pixel of slack); otherwise (four cells, or no convergence) the
 * mean of the crossings. */
static voronoi_point_t junction(const tctx_t *x, size_t c)
{
	int32_t L[4], u[4];
	corners(x, c, L);
	voronoi_point_t s = { 0, 0 };
	int n = 0, nu = 0;
	for (int e = 0; e < 4; e++) {
		int seen = 0;
		for (int k = 0; k < nu; k++)
			seen |= u[k] == L[e];
		if (!seen)
			u[nu++] = L[e];
		if (L[e] != L[(e + 1) & 3]) {
			voronoi_point_t p = crossing(x, c, e);
			s.x += p.x;
			s.y += p.y;
			n++;
		}
	}
	s.x /= n;
	s.y /= n;
	if (nu != 3)
		return s;
	double px = s.x, py = s.y, h = 1e-4;
	double x0 = x->r->x + (double)(c % x->cx), y0 = x->r->y + (double)(c / x->cx);
	for (int it = 0; it < 12; it++) {
		double f[3][2];
		for (int k = 0; k < 3; k++) { /* F at P, P + h x, P + h y */
			double qx = px + (k == 1 ? h : 0), qy = py + (k == 2 ? h : 0);
			double da = wdist(x, u[0], qx, qy);
			f[k][0] = da - wdist(x, u[1], qx, qy);
			f[k][1] = da - wdist(x, u[2], qx, qy);
		}
		double j00 = (f[1][0] - f[0][0]) / h, j01 = (f[2][0] - f[0][0]) / h;
		double j10 = (f[1][1] - f[0][1]) / h, j11 = (f[2][1] - f[0][1]) / h;
		double det = j00 * j11 - j01 * j10;
		if (!(fabs(det) > 1e-12))
			return s;
		double dx = -(j11 * f[0][0] - j01 * f[0][1]) / det, dy = -(-j10 * f[0][0] + j00 * f[0][1]) / det;
		px += dx;
		py += dy;
		if (!(px > x0 && px < x0 + 2 && py > y0 && py < y0 + 2))
			return s; /* left the cell (plus slack): keep the mean */
		if (fabs(dx) + fabs(dy) < 1e-9) {
			voronoi_point_t v = { px, py };
			return v;
		}
	}
	return s;
}

/* Cell across edge e of c, or SIZE_MAX outside. */
static inline size_t across(const tctx_t *x, size_t c, int e)
{
	size_t i = c % x->cx, j = c / x->cx;
	switch (e) {
	case 0: return j == 0 ? SIZE_MAX : c - x->cx;
	case 1: return i + 1 == x->cx ? SIZE_MAX : c + 1;
	case 2: return j + 1 == x->cy ? SIZE_MAX : c + x->cx;
	default: return i == 0 ? SIZE_MAX : c - 1;
	}
}

static int push(tctx_t *x, voronoi_point_t p)
{
	if (x->npts && x->pts[x->npts - 1].x == p.x && x->pts[x->npts - 1].y == p.y)
		return 0;
	if (x->npts == x->cap) {
		size_t cap = x->cap ? x->cap * 2 : 1024;
		voronoi_point_t *q = realloc(x->pts, cap * sizeof *q);
		if (!q)
			return voronoi_fail(VORONOI_ENOMEM, "voronoi: out of memory for %zu boundary points", cap);
		x->pts = q;
		x->cap = cap;
	}
	x->pts[x->npts++] = p;
	return 0;
}

/* The point where the ray from q through p leaves the rectangle, when it is
 * at most one pixel beyond p: boundaries are traced between pixel centres, so
 * an open end lies half a pixel inside the rectangle; this carries it to the
 * edge (skipped when the boundary runs nearly along the edge). */
static int to_border(const tctx_t *x, voronoi_point_t q, voronoi_point_t p, voronoi_point_t *out)
{
	double dx = p.x - q.x, dy = p.y - q.y, len = hypot(dx, dy);
	if (!(len > 0))
		return 0;
	dx /= len;
	dy /= len;
	double ex[2] = { x->r->x, (double)x->r->x + x->w }, ey[2] = { x->r->y, (double)x->r->y + x->h };
	double t = INFINITY;
	int side = -1;
	for (int k = 0; k < 4; k++) {
		double d = k < 2 ? dx : dy, e = k < 2 ? ex[k & 1] : ey[k & 1], c = k < 2 ? p.x : p.y;
		if ((k & 1) ? d > 0 : d < 0) {
			double tk = (e - c) / d;
			if (tk < t) {
				t = tk;
				side = k;
			}
		}
	}
	if (side < 0 || !(t > 1e-9 && t <= 1.0))
		return 0;
	out->x = side < 2 ? ex[side & 1] : p.x + t * dx;
	out->y = side < 2 ? p.y + t * dy : ey[side & 1];
	return 1;
}

static int emit(tctx_t *x, int32_t left, int32_t right, int closed)
{
	size_t n = x->npts;
	voronoi_point_t b;
	if (!closed && n >= 2 && x->end_border && to_border(x, x->pts[n - 2], x->pts[n - 1], &b)) {
		int rc = push(x, b);
		if (rc < 0)
			return rc;
		n = x->npts;
	}
	if (!closed && n >= 2 && x->start_border && to_border(x, x->pts[1], x->pts[0], &b)) {
		int rc = push(x, b); /* room for one more, then shift it to the front */
		if (rc < 0)
			return rc;
		memmove(x->pts + 1, x->pts, (x->npts - 1) * sizeof *x->pts);
		x->pts[0] = b;
		n = x->npts;
	}
	if (closed && n > 1 && x->pts[n - 1].x == x->pts[0].x && x->pts[n - 1].y == x->pts[0].y)
		n--;
	if (n < 2)
		return 0;
	x->st.polylines++;
	x->st.closed += closed != 0;
	x->st.points += n;
	if (x->fn(x->user, left, right, x->pts, n, closed) < 0)
		return voronoi_fail(VORONOI_ECALLBACK, "voronoi: stopped by the caller");
	return 0;
}

/* Follow a chain of two-label cells entering cell c by edge e; the polyline
 * already holds its first point(s). */
static int trace(tctx_t *x, size_t c, int e)
{
	size_t c0 = c;
	int e0 = e, closed = 0, rc;
	int32_t a = 0, b = 0;
	x->end_border = 0;
	for (;;) {
		if (x->flags[c] & (1u << e))
			break;
		int cs = cell_case(x, c, &a, &b), out = msq_exit[cs >> 4][cs & 15][e];
		if (out < 0)
			break;
		x->flags[c] |= (uint8_t)(1u << e);
		size_t n = across(x, c, out);
		if (n == c0 && ((out + 2) & 3) == e0) {
			closed = 1;
			break;
		}
		if ((rc = push(x, crossing(x, c, out))) < 0)
			return rc;
		if (n == SIZE_MAX) {
			x->end_border = 1;
			break;
		}
		if (x->flags[n] & JUNCTION) {
			if ((rc = push(x, junction(x, n))) < 0)
				return rc;
			break;
		}
		c = n;
		e = (out + 2) & 3;
	}
	return emit(x, a, b, closed); /* the smaller label is on the left */
}

int voronoi_boundaries(const voronoi_t *v, const voronoi_rect_t *r, const int32_t *labels,
                       voronoi_fn fn, void *user, voronoi_stats_t *stats)
{
	tctx_t x = { 0 };
	uint32_t *mixed = NULL;
	size_t nmixed = 0;
	int rc = voronoi_check(v);
	if (stats)
		memset(stats, 0, sizeof *stats);
	if (rc < 0)
		return rc;
	if (!r || !labels || !fn || r->width == 0 || r->height == 0)
		return voronoi_fail(VORONOI_EARG, "voronoi: boundaries need a rectangle, labels and a callback");
	if (r->width < 2 || r->height < 2)
		return 0;
	if ((uint64_t)r->width * r->height >= UINT32_MAX)
		return voronoi_fail(VORONOI_EARG, "voronoi: rectangle of %ux%u pixels is too large", r->width, r->height);
	x.v = v;
	x.r = r;
	x.lab = labels;
	voronoi_invert(v, &x.inv);
	x.w = r->width;
	x.h = r->height;
	x.cx = x.w - 1;
	x.cy = x.h - 1;
	x.fn = fn;
	x.user = user;
	size_t ncells = x.cx * x.cy, capm = 0;
	x.flags = calloc(ncells, 1);
	if (!x.flags) {
		rc = voronoi_fail(VORONOI_ENOMEM, "voronoi: out of memory for %zu cells", ncells);
		goto done;
	}
	/* one pass: check the labels, count crossings, list the mixed cells */
	size_t ncross = 0;
	const uint32_t count = (uint32_t)v->count;
	for (size_t j = 0; j < x.h; j++) {
		const int32_t *r0 = labels + j * x.w, *r1 = j + 1 < x.h ? r0 + x.w : NULL;
		uint32_t bad = 0;
		for (size_t i = 0; i < x.w; i++)
			bad |= (uint32_t)((uint32_t)r0[i] >= count);
		if (bad) {
			size_t i = 0;
			while ((uint32_t)r0[i] < count)
				i++;
			rc = voronoi_fail(VORONOI_EARG, "voronoi: label %ld at pixel (%zu, %zu) is not a nucleus",
			                  (long)r0[i], i, j);
			goto done;
		}
		if (!r1) {
			for (size_t i = 0; i + 1 < x.w; i++)
				ncross += r0[i] != r0[i + 1];
			break;
		}
		ncross += r0[x.cx] != r1[x.cx];
		for (size_t i = 0; i < x.cx; i++) {
			int32_t L[4] = { r0[i], r0[i + 1], r1[i + 1], r1[i] };
			ncross += (size_t)(L[0] != L[1]) + (L[0] != L[3]);
			if (L[0] == L[1] && L[0] == L[2] && L[0] == L[3])
				continue;
			int distinct = 1 + (L[1] != L[0]) + (L[2] != L[0] && L[2] != L[1]) +
			               (L[3] != L[0] && L[3] != L[1] && L[3] != L[2]);
			size_t c = j * x.cx + i;
			x.flags[c] = (uint8_t)(MIXED | (distinct > 2 ? JUNCTION : 0));
			x.st.junctions += distinct > 2;
			if (nmixed == capm) {
				size_t nc = capm ? capm * 2 : 4096;
				uint32_t *p = realloc(mixed, nc * sizeof *p);
				if (!p) {
					rc = voronoi_fail(VORONOI_ENOMEM, "voronoi: out of memory for %zu mixed cells", nc);
					goto done;
				}
				mixed = p;
				capm = nc;
			}
			mixed[nmixed++] = (uint32_t)c;
		}
	}
	x.st.crossings = ncross;
	/* pass 0: chains of two-label cells that start at the border or at a
	 * junction; pass 1: what is left of them, closed loops */
	for (int pass = 0; pass < 2; pass++)
		for (size_t q = 0; q < nmixed && rc == 0; q++) {
			size_t c = mixed[q];
			if (x.flags[c] & JUNCTION)
				continue;
			int32_t a, b;
			int cs = cell_case(&x, c, &a, &b);
			for (int e = 0; e < 4 && rc == 0; e++) {
				if (msq_exit[cs >> 4][cs & 15][e] < 0 || (x.flags[c] & (1u << e)))
					continue;
				size_t n = pass == 0 ? across(&x, c, e) : 0;
				if (pass == 0 && n != SIZE_MAX && !(x.flags[n] & JUNCTION))
					continue;
				x.npts = 0;
				x.start_border = pass == 0 && n == SIZE_MAX;
				if (pass == 0 && n != SIZE_MAX)
					rc = push(&x, junction(&x, n));
				if (rc == 0)
					rc = push(&x, crossing(&x, c, e));
				if (rc == 0)
					rc = trace(&x, c, e);
			}
		}
	/* then: short pieces from a junction to the border or to a neighbouring
	 * junction (each junction pair once, from the lower cell index) */
	for (size_t q = 0; q < nmixed && rc == 0; q++) {
		size_t c = mixed[q];
		if (!(x.flags[c] & JUNCTION))
			continue;
		int32_t L[4];
		corners(&x, c, L);
		for (int e = 0; e < 4 && rc == 0; e++) {
			if (L[e] == L[(e + 1) & 3])
				continue;
			size_t n = across(&x, c, e);
			if (n != SIZE_MAX && (!(x.flags[n] & JUNCTION) || n < c))
				continue;
			voronoi_point_t jp = junction(&x, c), xp = crossing(&x, c, e);
			x.npts = 0;
			x.start_border = 0;
			x.end_border = n == SIZE_MAX;
			rc = push(&x, jp);
			if (rc == 0)
				rc = push(&x, xp);
			if (rc == 0 && n != SIZE_MAX)
				rc = push(&x, junction(&x, n));
			if (rc < 0)
				break;
			/* corner e of the cell lies left of the walk J -> X when the
			 * cross product of (X - J) and (corner - X) is positive */
			double cxp = r->x + (double)(c % x.cx) + ((e == 1 || e == 2) ? 1.5 : 0.5);
			double cyp = r->y + (double)(c / x.cx) + ((e >= 2) ? 1.5 : 0.5);
			double cr = (xp.x - jp.x) * (cyp - xp.y) - (xp.y - jp.y) * (cxp - xp.x);
			int32_t l = cr > 0 ? L[e] : L[(e + 1) & 3], rt = cr > 0 ? L[(e + 1) & 3] : L[e];
			rc = emit(&x, l, rt, 0);
		}
	}
done:
	if (stats)
		*stats = x.st;
	free(x.flags);
	free(x.pts);
	free(mixed);
	return rc;
}
