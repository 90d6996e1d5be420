/* pathopt.c: merge, simplify, nearest-end ordering on a spatial grid, windowed 2-opt and Or-opt. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "util/grow.h"
#include "hpgl/pathopt.h"

static double now_s(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* The 2-opt budget is counted in candidate moves looked at, not in clock time, so that a page
 * comes out the same on a busy machine as on an idle one: -O budget=S allows S times this many,
 * about what one core of the machine this was measured on (x86-64, 2026) looks at in a second
 * (1.23-1.25e8 on workload a). */
#define POPT_MOVES_PER_S 1.25e8

/* Work done and allowed, in candidate moves. */
typedef struct {
	unsigned long long done, max;
} work_t;

static double dist(popt_pt_t a, popt_pt_t b)
{
	double dx = (double)a.x - b.x, dy = (double)a.y - b.y;
	return sqrt(dx * dx + dy * dy);
}

void popt_reset(popt_set_t *s)
{
	s->npts = s->npaths = 0;
}

void popt_free(popt_set_t *s)
{
	free(s->pts);
	free(s->paths);
	free(s->order);
	free(s->rev);
	memset(s, 0, sizeof *s);
}

static int grow(void **p, size_t *cap, size_t need, size_t size)
{
	return dev_grow(p, cap, need, size, 256);
}

int popt_add(popt_set_t *s, const popt_pt_t *pts, size_t n, int closed)
{
	if (n == 0)
		return 0;
	if (grow((void **)&s->pts, &s->cappts, s->npts + n, sizeof *s->pts) ||
			grow((void **)&s->paths, &s->cappaths, s->npaths + 1, sizeof *s->paths))
		return -1;
	memcpy(s->pts + s->npts, pts, n * sizeof *pts);
	s->paths[s->npaths++] = (popt_path_t){ s->npts, n, closed && n > 2 };
	s->npts += n;
	return 0;
}

static int alloc_order(popt_set_t *s)
{
	free(s->order);
	free(s->rev);
	s->order = malloc((s->npaths + 1) * sizeof *s->order);
	s->rev = calloc(s->npaths + 1, 1);
	return s->order && s->rev ? 0 : -1;
}

int popt_keep_order(popt_set_t *s)
{
	if (alloc_order(s))
		return -1;
	for (size_t k = 0; k < s->npaths; k++)
		s->order[k] = k;
	return 0;
}

void popt_ends(const popt_set_t *s, size_t k, popt_pt_t *first, popt_pt_t *last)
{
	const popt_path_t *p = &s->paths[s->order[k]];
	popt_pt_t a = s->pts[p->start], b = p->closed ? a : s->pts[p->start + p->n - 1];
	*first = s->rev[k] ? b : a;
	*last = s->rev[k] ? a : b;
}

double popt_travel(const popt_set_t *s, popt_pt_t start)
{
	double t = 0;
	popt_pt_t at = start, f, l;
	for (size_t k = 0; k < s->npaths; k++) {
		popt_ends(s, k, &f, &l);
		t += dist(at, f);
		at = l;
	}
	return t;
}

size_t popt_get(const popt_set_t *s, size_t k, popt_pt_t *out)
{
	const popt_path_t *p = &s->paths[s->order[k]];
	const popt_pt_t *q = s->pts + p->start;
	for (size_t i = 0; i < p->n; i++)
		out[i] = q[s->rev[k] ? p->n - 1 - i : i];
	if (p->closed) {
		out[p->n] = out[0];
		return p->n + 1;
	}
	return p->n;
}

/* ---- the endpoint grid ---- */

typedef struct {
	int64_t x0, y0;
	double cell;
	int64_t nx, ny;
	size_t *head;               /* per cell: first entry index in ent, entries sorted by cell */
	struct ent { popt_pt_t p; size_t id; } *ent;   /* endpoints: id 2 * path + end (0 first, 1 last) */
	size_t *live;               /* per cell: live entries at the front of its block */
	size_t nent;
} grid_t;

static void grid_free(grid_t *g)
{
	free(g->head);
	free(g->ent);
	free(g->live);
	memset(g, 0, sizeof *g);
}

static popt_pt_t end_pt(const popt_set_t *s, size_t id)
{
	const popt_path_t *p = &s->paths[id >> 1];
	return (id & 1) && !p->closed ? s->pts[p->start + p->n - 1] : s->pts[p->start];
}

static int64_t cell_of(const grid_t *g, popt_pt_t q, int64_t *cx, int64_t *cy)
{
	int64_t x = (int64_t)floor((q.x - g->x0) / g->cell), y = (int64_t)floor((q.y - g->y0) / g->cell);
	if (x < 0) x = 0;
	if (y < 0) y = 0;
	if (x >= g->nx) x = g->nx - 1;
	if (y >= g->ny) y = g->ny - 1;
	*cx = x;
	*cy = y;
	return y * g->nx + x;
}

/* Build the grid over the endpoints ids[0..n) with about per entries per cell. */
static int grid_build(grid_t *g, const popt_set_t *s, const size_t *ids, size_t n, double per)
{
	grid_free(g);
	int64_t x0 = INT64_MAX, y0 = INT64_MAX, x1 = INT64_MIN, y1 = INT64_MIN;
	for (size_t k = 0; k < n; k++) {
		popt_pt_t q = end_pt(s, ids[k]);
		if (q.x < x0) x0 = q.x;
		if (q.y < y0) y0 = q.y;
		if (q.x > x1) x1 = q.x;
		if (q.y > y1) y1 = q.y;
	}
	if (n == 0)
		x0 = y0 = x1 = y1 = 0;
	double w = (double)(x1 - x0) + 1, h = (double)(y1 - y0) + 1;
	double cells = n / per + 1;
	g->cell = sqrt(w * h / cells);
	if (g->cell < 1)
		g->cell = 1;
	g->x0 = x0;
	g->y0 = y0;
	g->nx = (int64_t)(w / g->cell) + 1;
	g->ny = (int64_t)(h / g->cell) + 1;
	size_t nc = (size_t)(g->nx * g->ny);
	g->head = calloc(nc + 1, sizeof *g->head);
	g->live = calloc(nc, sizeof *g->live);
	g->ent = malloc((n ? n : 1) * sizeof *g->ent);
	if (!g->head || !g->live || !g->ent)
		return -1;
	int64_t cx, cy;
	for (size_t k = 0; k < n; k++)
		g->head[cell_of(g, end_pt(s, ids[k]), &cx, &cy) + 1]++;
	for (size_t c = 0; c < nc; c++) {
		g->live[c] = g->head[c + 1];
		g->head[c + 1] += g->head[c];
	}
	size_t *fill = malloc((nc ? nc : 1) * sizeof *fill);
	if (!fill)
		return -1;
	memcpy(fill, g->head, nc * sizeof *fill);
	for (size_t k = 0; k < n; k++) {
		popt_pt_t q = end_pt(s, ids[k]);
		g->ent[fill[cell_of(g, q, &cx, &cy)]++] = (struct ent){ q, ids[k] };
	}
	free(fill);
	g->nent = n;
	return 0;
}

/* The nearest live endpoint to q (used[path] == 0), or SIZE_MAX. Dead entries found on the way
 * are dropped from their cells. */
static size_t grid_nearest(grid_t *g, const unsigned char *used, popt_pt_t q,
		double maxd, double *best_d)
{
	int64_t cx, cy;
	cell_of(g, q, &cx, &cy);
	size_t best = SIZE_MAX;
	double bd = INFINITY;
	int64_t rmax = g->nx > g->ny ? g->nx : g->ny;
	for (int64_t r = 0; r <= rmax; r++) {
		double reach = (r - 1) * g->cell;   /* every point in ring r or beyond is at least this far */
		if ((best != SIZE_MAX && reach >= 0 && bd <= reach * reach) || reach > maxd)
			break;
		for (int64_t y = cy - r; y <= cy + r; y++) {
			if (y < 0 || y >= g->ny)
				continue;
			int edge = y == cy - r || y == cy + r;
			for (int64_t x = cx - r; x <= cx + r; x += edge ? 1 : 2 * r) {
				if (x >= 0 && x < g->nx) {
					size_t c = (size_t)(y * g->nx + x);
					struct ent *e = g->ent + g->head[c];
					for (size_t i = 0; i < g->live[c];) {
						if (used[e[i].id >> 1]) {
							e[i] = e[--g->live[c]];
							continue;
						}
						double dx = (double)q.x - e[i].p.x, dy = (double)q.y - e[i].p.y, d = dx * dx + dy * dy;
						if (d < bd || (d == bd && e[i].id < best)) {
							bd = d;
							best = e[i].id;
						}
						i++;
					}
				}
				if (r == 0)
					break;
			}
		}
	}
	*best_d = sqrt(bd);
	return best;
}

/* ---- merging ---- */

/* Append path id's points to the new point array (reversed when rev), skipping its first point
 * when it equals the last one written. */
static int append_path(const popt_set_t *s, size_t id, int rev, popt_pt_t **np, size_t *nn, size_t *cap,
		int skip_first)
{
	const popt_path_t *p = &s->paths[id];
	if (grow((void **)np, cap, *nn + p->n, sizeof **np))
		return -1;
	for (size_t i = skip_first ? 1 : 0; i < p->n; i++)
		(*np)[(*nn)++] = s->pts[p->start + (rev ? p->n - 1 - i : i)];
	return 0;
}

static int merge_paths(popt_set_t *s, double tol)
{
	size_t n = s->npaths, *ids = malloc((2 * n + 1) * sizeof *ids), m = 0;
	unsigned char *used = calloc(n + 1, 1);
	popt_path_t *out = malloc((n + 1) * sizeof *out);
	size_t *chain = malloc((n + 1) * sizeof *chain);
	unsigned char *crev = malloc(n + 1);
	popt_pt_t *np = NULL;
	size_t nn = 0, cap = 0, nout = 0;
	grid_t g = { 0 };
	int rc = -1;
	if (!ids || !used || !out || !chain || !crev)
		goto done;
	for (size_t k = 0; k < n; k++)
		if (!s->paths[k].closed) {
			ids[m++] = 2 * k;
			ids[m++] = 2 * k + 1;
		}
	if (grid_build(&g, s, ids, m, 0.5))
		goto done;
	for (size_t k = 0; k < n; k++) {
		const popt_path_t *p = &s->paths[k];
		if (used[k])
			continue;
		used[k] = 1;
		size_t start = nn;
		if (p->closed) {
			if (append_path(s, k, 0, &np, &nn, &cap, 0))
				goto done;
			out[nout++] = (popt_path_t){ start, nn - start, 1 };
			continue;
		}
		/* grow backwards from the first point, then forwards from the last */
		size_t nb = 0;
		popt_pt_t head = s->pts[p->start], tail = s->pts[p->start + p->n - 1];
		for (;;) {
			double d;
			size_t e = grid_nearest(&g, used, head, tol, &d);
			if (e == SIZE_MAX || d > tol)
				break;
			used[e >> 1] = 1;
			chain[nb] = e >> 1;
			crev[nb++] = (e & 1) == 0;   /* its first point meets our head: draw it reversed, before us */
			const popt_path_t *q = &s->paths[e >> 1];
			head = (e & 1) ? s->pts[q->start] : s->pts[q->start + q->n - 1];
		}
		for (size_t i = nb; i-- > 0;) {
			int skip = nn > start && !memcmp(&np[nn - 1],
				&s->pts[s->paths[chain[i]].start + (crev[i] ? s->paths[chain[i]].n - 1 : 0)], sizeof *np);
			if (append_path(s, chain[i], crev[i], &np, &nn, &cap, skip))
				goto done;
		}
		if (append_path(s, k, 0, &np, &nn, &cap, nn > start && !memcmp(&np[nn - 1], &s->pts[p->start], sizeof *np)))
			goto done;
		for (;;) {
			double d;
			size_t e = grid_nearest(&g, used, tail, tol, &d);
			if (e == SIZE_MAX || d > tol)
				break;
			used[e >> 1] = 1;
			const popt_path_t *q = &s->paths[e >> 1];
			int rev = (e & 1) != 0;
			popt_pt_t first = s->pts[q->start + (rev ? q->n - 1 : 0)];
			if (append_path(s, e >> 1, rev, &np, &nn, &cap, !memcmp(&np[nn - 1], &first, sizeof first)))
				goto done;
			tail = np[nn - 1];
		}
		out[nout++] = (popt_path_t){ start, nn - start, 0 };
	}
	free(s->pts);
	free(s->paths);
	s->pts = np;
	s->npts = nn;
	s->cappts = cap;
	s->paths = out;
	s->npaths = s->cappaths = nout;
	np = NULL;
	out = NULL;
	rc = 0;
done:
	grid_free(&g);
	free(ids);
	free(used);
	free(out);
	free(chain);
	free(crev);
	free(np);
	return rc;
}

/* ---- simplification (Douglas-Peucker, iterative) ---- */

static double seg_dist(popt_pt_t p, popt_pt_t a, popt_pt_t b)
{
	double dx = (double)b.x - a.x, dy = (double)b.y - a.y, L2 = dx * dx + dy * dy;
	double px = (double)p.x - a.x, py = (double)p.y - a.y;
	if (L2 == 0)
		return sqrt(px * px + py * py);
	double t = (px * dx + py * dy) / L2;
	t = t < 0 ? 0 : t > 1 ? 1 : t;
	double ex = px - t * dx, ey = py - t * dy;
	return sqrt(ex * ex + ey * ey);
}

static int simplify_paths(popt_set_t *s, double tol)
{
	unsigned char *keep = NULL;
	size_t *stack = NULL, capk = 0, caps = 0, w = 0;
	for (size_t k = 0; k < s->npaths; k++) {
		popt_path_t *p = &s->paths[k];
		popt_pt_t *q = s->pts + p->start;
		size_t n = 0;
		for (size_t i = 0; i < p->n; i++)    /* drop repeated points */
			if (n == 0 || memcmp(&q[n - 1], &q[i], sizeof *q))
				q[n++] = q[i];
		if (tol > 0 && n > 2) {
			if (grow((void **)&keep, &capk, n, 1) || grow((void **)&stack, &caps, 2 * n, sizeof *stack)) {
				free(keep);
				free(stack);
				return -1;
			}
			memset(keep, 0, n);
			keep[0] = keep[n - 1] = 1;
			size_t sp = 0;
			stack[sp++] = 0;
			stack[sp++] = n - 1;
			while (sp) {
				size_t b = stack[--sp], a = stack[--sp], far = 0;
				double fd = -1;
				for (size_t i = a + 1; i < b; i++) {
					double d = seg_dist(q[i], q[a], q[b]);
					if (d > fd) {
						fd = d;
						far = i;
					}
				}
				if (fd > tol) {
					keep[far] = 1;
					stack[sp++] = a;
					stack[sp++] = far;
					stack[sp++] = far;
					stack[sp++] = b;
				}
			}
			size_t m = 0;
			for (size_t i = 0; i < n; i++)
				if (keep[i])
					q[m++] = q[i];
			n = m;
		}
		if (p->closed && n > 1 && !memcmp(&q[0], &q[n - 1], sizeof *q))
			n--;
		/* compact in place */
		memmove(s->pts + w, q, n * sizeof *q);
		p->start = w;
		p->n = n;
		if (p->closed && n < 3)
			p->closed = 0;
		w += n;
	}
	s->npts = w;
	free(keep);
	free(stack);
	return 0;
}

/* ---- ordering ---- */

static int greedy_order(popt_set_t *s, popt_pt_t start)
{
	size_t n = s->npaths, *ids = malloc((2 * n + 1) * sizeof *ids), m = 0;
	unsigned char *used = calloc(n + 1, 1);
	grid_t g = { 0 };
	int rc = -1;
	if (!ids || !used)
		goto done;
	for (size_t k = 0; k < n; k++) {
		ids[m++] = 2 * k;
		if (!s->paths[k].closed)
			ids[m++] = 2 * k + 1;
	}
	if (grid_build(&g, s, ids, m, 0.5))
		goto done;
	popt_pt_t at = start;
	size_t left = n, rebuild_at = n / 4;
	for (size_t k = 0; k < n; k++) {
		double d;
		size_t e = grid_nearest(&g, used, at, INFINITY, &d);
		if (e == SIZE_MAX)
			goto done;   /* cannot happen: left > 0 */
		used[e >> 1] = 1;
		s->order[k] = e >> 1;
		s->rev[k] = (e & 1) != 0;
		popt_pt_t f, l;
		popt_ends(s, k, &f, &l);
		at = l;
		if (--left && left < rebuild_at) {   /* keep the grid about as fine as the live points */
			m = 0;
			for (size_t i = 0; i < n; i++)
				if (!used[i]) {
					ids[m++] = 2 * i;
					if (!s->paths[i].closed)
						ids[m++] = 2 * i + 1;
				}
			if (grid_build(&g, s, ids, m, 0.5))
				goto done;
			rebuild_at = left / 4;
		}
	}
	rc = 0;
done:
	grid_free(&g);
	free(ids);
	free(used);
	return rc;
}

/* Start each closed path at its vertex nearest to the previous path's end. */
static void rotate_closed(popt_set_t *s, popt_pt_t start)
{
	popt_pt_t at = start, f, l;
	for (size_t k = 0; k < s->npaths; k++) {
		popt_path_t *p = &s->paths[s->order[k]];
		if (p->closed) {
			popt_pt_t *q = s->pts + p->start;
			size_t bi = 0;
			double bd = INFINITY;
			for (size_t i = 0; i < p->n; i++) {
				double d = dist(at, q[i]);
				if (d < bd) {
					bd = d;
					bi = i;
				}
			}
			if (bi) {   /* rotate left by bi (three reversals) */
				for (size_t a = 0, b = bi - 1; a < b; a++, b--) { popt_pt_t t = q[a]; q[a] = q[b]; q[b] = t; }
				for (size_t a = bi, b = p->n - 1; a < b; a++, b--) { popt_pt_t t = q[a]; q[a] = q[b]; q[b] = t; }
				for (size_t a = 0, b = p->n - 1; a < b; a++, b--) { popt_pt_t t = q[a]; q[a] = q[b]; q[b] = t; }
			}
			s->rev[k] = 0;
		}
		popt_ends(s, k, &f, &l);
		at = l;
	}
}

/* Windowed 2-opt on the open tour: reversing positions i..j (and each path's direction) when
 * that shortens the two links at its ends. */
/* Positions lo - 1 .. hi + 1 changed links: look at them again ("don't look" bits). */
static void wake(unsigned char *act2, unsigned char *acto, ptrdiff_t n, ptrdiff_t lo, ptrdiff_t hi)
{
	lo = lo > 0 ? lo - 1 : 0;
	hi = hi + 1 < n ? hi + 1 : n - 1;
	memset(act2 + lo, 1, (size_t)(hi - lo + 1));
	memset(acto + lo, 1, (size_t)(hi - lo + 1));
}

/* Or-opt: move path i (turned round if that is shorter) to between positions j and j + 1 within
 * the window, when the links it leaves and makes are shorter. Returns the travel gained. */
static double or_opt(popt_set_t *s, popt_pt_t *F, popt_pt_t *L, popt_pt_t start, int window,
		work_t *wk, unsigned char *act2, unsigned char *acto)
{
	ptrdiff_t n = (ptrdiff_t)s->npaths;
	double gained = 0;
	for (ptrdiff_t i = 0; i < n; i++) {
		if ((i & 255) == 0 && wk->done >= wk->max)
			break;
		if (!acto[i])
			continue;
		popt_pt_t prev = i ? L[i - 1] : start;
		double take = dist(prev, F[i]) + (i + 1 < n ? dist(L[i], F[i + 1]) - dist(prev, F[i + 1]) : 0);
		ptrdiff_t best = -2;
		int flip = 0;
		double bestc = take - 1e-9;
		ptrdiff_t j0 = i - window < -1 ? -1 : i - window, j1 = i + window >= n ? n - 1 : i + window;
		wk->done += (unsigned long long)(j1 - j0 + 1);
		for (ptrdiff_t j = j0; j <= j1; j++) {
			if (j == i || j == i - 1)
				continue;
			popt_pt_t a = j >= 0 ? L[j] : start;
			int has_next = j + 1 < n;
			popt_pt_t b = has_next ? F[j + 1] : a;
			double base = has_next ? dist(a, b) : 0;
			double c0 = dist(a, F[i]) + (has_next ? dist(L[i], b) : 0) - base;
			double c1 = dist(a, L[i]) + (has_next ? dist(F[i], b) : 0) - base;
			if (c0 < bestc) {
				bestc = c0;
				best = j;
				flip = 0;
			}
			if (c1 < bestc) {
				bestc = c1;
				best = j;
				flip = 1;
			}
		}
		if (best == -2) {
			acto[i] = 0;   /* nothing to gain here until a neighbour changes */
			continue;
		}
		size_t ord = s->order[i];
		unsigned char rv = s->rev[i] ^ (unsigned char)flip;
		popt_pt_t f = flip ? L[i] : F[i], l = flip ? F[i] : L[i];
		ptrdiff_t to;
		if (best > i) {
			memmove(s->order + i, s->order + i + 1, (size_t)(best - i) * sizeof *s->order);
			memmove(s->rev + i, s->rev + i + 1, (size_t)(best - i));
			memmove(F + i, F + i + 1, (size_t)(best - i) * sizeof *F);
			memmove(L + i, L + i + 1, (size_t)(best - i) * sizeof *L);
			to = best;
		} else {
			memmove(s->order + best + 2, s->order + best + 1, (size_t)(i - best - 1) * sizeof *s->order);
			memmove(s->rev + best + 2, s->rev + best + 1, (size_t)(i - best - 1));
			memmove(F + best + 2, F + best + 1, (size_t)(i - best - 1) * sizeof *F);
			memmove(L + best + 2, L + best + 1, (size_t)(i - best - 1) * sizeof *L);
			to = best + 1;
		}
		s->order[to] = ord;
		s->rev[to] = rv;
		F[to] = f;
		L[to] = l;
		gained += take - bestc;
		wake(act2, acto, n, i < to ? i : to, i < to ? to : i);
	}
	return gained;
}

/* Improve the order within the work budget; the passes made in *npasses. 0, or -1 when out of
 * memory (the order is then the greedy one: the caller fails the page rather than plot it in
 * another order than asked). */
static int two_opt(popt_set_t *s, popt_pt_t start, double budget, int window, unsigned *npasses)
{
	work_t wk = { 0, (unsigned long long)(budget * POPT_MOVES_PER_S) };
	size_t n = s->npaths;
	unsigned passes = 0;
	*npasses = 0;
	if (n < 3)
		return 0;
	popt_pt_t *F = malloc(n * sizeof *F), *L = malloc(n * sizeof *L);
	if (!F || !L) {
		free(F);
		free(L);
		return -1;
	}
	unsigned char *act2 = malloc(n), *acto = malloc(n);
	if (!act2 || !acto) {
		free(F);
		free(L);
		free(act2);
		free(acto);
		return -1;
	}
	memset(act2, 1, n);
	memset(acto, 1, n);
	for (size_t k = 0; k < n; k++)
		popt_ends(s, k, &F[k], &L[k]);
	double travel = popt_travel(s, start), gain = travel;
	/* passes until one gains less than 0.05 % of the travel, or the budget is spent */
	while (gain > 5e-4 * travel && wk.done < wk.max) {
		travel -= gain == travel ? 0 : gain;
		gain = 0;
		passes++;
		for (size_t i = 0; i < n; i++) {
			if ((i & 255) == 0 && wk.done >= wk.max)
				break;
			if (!act2[i])
				continue;
			int moved = 0;
			popt_pt_t prev = i ? L[i - 1] : start;
			double dprev = dist(prev, F[i]);
			size_t jmax = i + (size_t)window < n ? i + (size_t)window : n - 1;
			wk.done += jmax - i;
			for (size_t j = i + 1; j <= jmax; j++) {
				double old = dprev + (j + 1 < n ? dist(L[j], F[j + 1]) : 0);
				double nw = dist(prev, L[j]) + (j + 1 < n ? dist(F[i], F[j + 1]) : 0);
				if (nw < old - 1e-9) {
					for (size_t a = i, b = j; a < b; a++, b--) {
						size_t to = s->order[a]; s->order[a] = s->order[b]; s->order[b] = to;
						unsigned char tr = s->rev[a]; s->rev[a] = s->rev[b]; s->rev[b] = tr;
						popt_pt_t tf = F[a]; F[a] = F[b]; F[b] = tf;
						popt_pt_t tl = L[a]; L[a] = L[b]; L[b] = tl;
					}
					for (size_t a = i; a <= j; a++) {
						s->rev[a] ^= 1;
						popt_pt_t t = F[a]; F[a] = L[a]; L[a] = t;
					}
					dprev = dist(prev, F[i]);
					gain += old - nw;
					moved = 1;
					wake(act2, acto, (ptrdiff_t)n, (ptrdiff_t)i, (ptrdiff_t)j);
				}
			}
			if (!moved)
				act2[i] = 0;
		}
		gain += or_opt(s, F, L, start, window, &wk, act2, acto);
	}
	free(F);
	free(L);
	free(act2);
	free(acto);
	*npasses = passes;
	return 0;
}

int popt_optimise(popt_set_t *s, popt_pt_t start, const popt_opts_t *o, popt_stats_t *st)
{
	double t0 = now_s();
	memset(st, 0, sizeof *st);
	st->paths_before = s->npaths;
	if (popt_keep_order(s))
		return -1;
	st->travel_before = popt_travel(s, start);
	if (simplify_paths(s, o->simplify_tol))
		return -1;
	if (o->merge && s->npaths > 1 && merge_paths(s, o->merge_tol))
		return -1;
	if (popt_keep_order(s))
		return -1;
	if (o->reorder && s->npaths > 1) {
		if (greedy_order(s, start))
			return -1;
		rotate_closed(s, start);
	}
	st->travel_greedy = popt_travel(s, start);
	if (o->reorder && o->budget_s > 0) {
		if (two_opt(s, start, o->budget_s, o->window > 0 ? o->window : 64, &st->twoopt_passes))
			return -1;
		rotate_closed(s, start);
	}
	st->travel_after = popt_travel(s, start);
	st->paths_after = s->npaths;
	st->seconds = now_s() - t0;
	return 0;
}
