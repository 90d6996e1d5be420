/* scan.c: exact polygon coverage (spec §5.1) with an active edge table and integer DDA. */
#include <stdlib.h>
#include <string.h>
#include "util/grow.h"
#include "geom/scan.h"
#include "geom/scan_int.h"

/* One non-horizontal edge, normalised to go upwards, with its crossing DDA.
 * For row j the crossing pixel index i is the smallest i whose centre is at or right of the
 * edge's crossing abscissa X: (1000i + 500) >= X, i.e. i = ceil((N - 500*dy) / (1000*dy)) with
 * N = x0*dy + (Yc - y0)*dx. It is kept as i and a remainder r (0 <= r < D) such that the exact
 * numerator equals i*D - r; one row up adds 1000*dx to the numerator. */
typedef struct {
	int64_t i, r, d, sq, sr;
	int jf, jl;
	int dir;
} edge_t;

typedef struct {
	int64_t i;
	int dir;
} cross_t;

/* A fill colour as 16 pixels of bytes, made once per statement so that spans are stored as
 * 48-byte chunks (three 16-byte stores) with nothing built per row. */
typedef struct {
	uint8_t pat[48];
} pen_t;

static inline void pen_make(pen_t *pen, meta_rgb_t rgb)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
	for (int k = 0; k < 48; k += 3) {
		pen->pat[k] = (uint8_t)(rgb >> 16);
		pen->pat[k + 1] = (uint8_t)(rgb >> 8);
		pen->pat[k + 2] = (uint8_t)rgb;
	}
#else
	/* r g b r g b ... as three little-endian 64-bit words, twice (six stores, not 48: a pen
	 * is made for every stroke piece) */
	uint64_t c = (uint64_t)(rgb >> 16 & 255) | (uint64_t)(rgb >> 8 & 255) << 8 | (uint64_t)(rgb & 255) << 16;
	uint64_t w[3] = { c | c << 24 | c << 48, c >> 16 | c << 8 | c << 32 | c << 56, c >> 8 | c << 16 | c << 40 };
	memcpy(pen->pat, w, 24);
	memcpy(pen->pat + 24, w, 24);
#endif
}

struct scan_ctx {
	edge_t *edges;
	size_t cap_edges;
	edge_t **active;
	size_t cap_active;
	cross_t *cross;
	size_t cap_cross;
	scan_path_t piece;    /* stroke pieces */
	scan_path_t dashed;   /* dash pieces */
	pen_t pen;            /* the pen of pen_rgb (pen_set: made) */
	meta_rgb_t pen_rgb;
	int pen_set;
};

scan_ctx_t *scan_ctx_new(void)
{
	return calloc(1, sizeof(scan_ctx_t));
}

void scan_ctx_free(scan_ctx_t *c)
{
	if (!c)
		return;
	free(c->edges);
	free(c->active);
	free(c->cross);
	scan_path_free(&c->piece);
	scan_path_free(&c->dashed);
	free(c);
}

scan_path_t *scan_ctx_piece(scan_ctx_t *c)
{
	return &c->piece;
}

scan_path_t *scan_ctx_dashed(scan_ctx_t *c)
{
	return &c->dashed;
}

static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
	return dev_grow(p, cap, need, elem, 64) ? META_ENOMEM : 0;
}

/* ceil(a / b) for b > 0. */
static inline int64_t ceil_div(int64_t a, int64_t b)
{
	int64_t q = a / b;
	if (q * b != a && a > 0)
		q++;
	return q;
}

static inline int64_t floor_div(int64_t a, int64_t b)
{
	int64_t q = a / b;
	if (q * b != a && a < 0)
		q--;
	return q;
}

/* ceil(a / b) for b > 0 through a double estimate corrected exactly (divisions are slow). */
static inline int64_t fast_ceil_div(int64_t a, int64_t b)
{
	const int64_t lim = (int64_t)1 << 52;
	if (a > -lim && a < lim && b < lim) {
		int64_t q = (int64_t)ceil((double)a / (double)b);
		while (q * b < a)
			q++;
		while ((q - 1) * b >= a)
			q--;
		return q;
	}
	return ceil_div(a, b);
}

#define SMALL ((int64_t)1 << 30)
#define SMALL_EDGES 12

/* Set up the edge (x0,y0)->(x1,y1) for rows within [lo, hi); returns 0 when no row is crossed. */
static int edge_init(edge_t *e, int64_t x0, int64_t y0, int64_t x1, int64_t y1, int lo, int hi)
{
	int dir = 1;
	if (y0 == y1)
		return 0;
	if (y0 > y1) {
		int64_t t = x0; x0 = x1; x1 = t;
		t = y0; y0 = y1; y1 = t;
		dir = -1;
	}
	if (y1 <= (int64_t)lo * 1000 || y0 >= (int64_t)hi * 1000)
		return 0;   /* no centre row of the band */
	/* rows j with y0 <= 1000j + 500 < y1 */
	int64_t jf = ceil_div(y0 - 500, 1000), jl = ceil_div(y1 - 500, 1000) - 1;
	if (jf < lo)
		jf = lo;
	if (jl > hi - 1)
		jl = hi - 1;
	if (jf > jl)
		return 0;
	int64_t dx = x1 - x0, dy = y1 - y0, yc = 1000 * jf + 500;
	int64_t d = 1000 * dy;
	if (x0 > -SMALL && x0 < SMALL && x1 > -SMALL && x1 < SMALL && y0 > -SMALL && y1 < SMALL) {
		int64_t n = x0 * dy + (yc - y0) * dx - 500 * dy;
		e->i = fast_ceil_div(n, d);
		e->r = e->i * d - n;
	} else {
		__int128 n = (__int128)x0 * dy + (__int128)(yc - y0) * dx - (__int128)500 * dy;
		__int128 q = n / d;
		if (q * d != n && n > 0)
			q++;
		e->i = (int64_t)q;
		e->r = (int64_t)(q * d - n);
	}
	if (jl > jf) {
		int64_t s = 1000 * dx;
		e->sq = floor_div(s, d);
		e->sr = s - e->sq * d;
	} else {
		e->sq = e->sr = 0;
	}
	e->d = d;
	e->jf = (int)jf;
	e->jl = (int)jl;
	e->dir = dir;
	return 1;
}

static inline void edge_step(edge_t *e)
{
	/* without a branch: whether the remainder went below zero is close to a coin toss */
	int64_t r = e->r - e->sr, neg = -(int64_t)(r < 0);   /* -1 when r < 0 */
	e->r = r + (e->d & neg);
	e->i += e->sq - neg;
}

/* Store n pixels (1 <= n <= 16) of the pen at p: two fixed-size stores that overlap, each
 * starting on a pixel (a short row was 3 byte stores per pixel, the most frequent instructions
 * of thin strokes). */
static inline void store_short(uint8_t *p, int64_t n, const pen_t *pen)
{
	size_t e = (size_t)n * 3;
	if (n >= 8) {
		memcpy(p, pen->pat, 24);
		memcpy(p + e - 24, pen->pat, 24);
	} else if (n >= 4) {
		memcpy(p, pen->pat, 12);
		memcpy(p + e - 12, pen->pat, 12);
	} else if (n >= 2) {
		memcpy(p, pen->pat, 6);
		memcpy(p + e - 6, pen->pat, 6);
	} else {
		memcpy(p, pen->pat, 3);
	}
}

/* Paint pixels [a, b) of page row j (already known to be inside the band). */
static inline void paint(const scan_band_t *b, int j, int64_t a, int64_t e, const pen_t *pen)
{
	if (a < 0)
		a = 0;
	if (e > b->width)
		e = b->width;
	if (a >= e)
		return;
	uint8_t *p = b->pix + (size_t)(b->jhi - 1 - j) * b->stride + (size_t)a * 3;
	int64_t n = e - a;
	if (n <= 16) {
		store_short(p, n, pen);
		return;
	}
	/* whole chunks, then one more ending at the span's end (it overlaps the last one with the
	 * same bytes, as every chunk starts on a pixel); the doubling memmove this replaces was
	 * most of the time of large fills */
	uint8_t *end = p + (size_t)n * 3;
	for (; n >= 16; n -= 16, p += 48)
		memcpy(p, pen->pat, 48);
	if (n)
		memcpy(end - 48, pen->pat, 48);
}

/* The context's pen for rgb, made when the colour changes (strokes are cut into many pieces
 * of one colour). */
static inline const pen_t *ctx_pen(scan_ctx_t *c, meta_rgb_t rgb)
{
	if (!c->pen_set || c->pen_rgb != rgb) {
		pen_make(&c->pen, rgb);
		c->pen_rgb = rgb;
		c->pen_set = 1;
	}
	return &c->pen;
}

/* Insert crossing x into cr[0..n) kept sorted by pixel index (n is the count before). */
static inline void insert_crossing(cross_t *cr, size_t n, cross_t x)
{
	while (n > 0 && cr[n - 1].i > x.i) {
		cr[n] = cr[n - 1];
		n--;
	}
	cr[n] = x;
}

/* Paint row j between sorted crossings where the winding number is inside by the rule (§5.1). */
static inline void paint_crossings(const scan_band_t *b, int j, const cross_t *cr, size_t na, int rule,
		const pen_t *pen)
{
	int w = 0;
	for (size_t k = 0; k + 1 < na; k++) {
		w += cr[k].dir;
		int in = rule == META_RULE_EVEN_ODD ? (w & 1) : (w != 0);
		if (in && cr[k + 1].i > cr[k].i)
			paint(b, j, cr[k].i, cr[k + 1].i, pen);
	}
}

void scan_span(const scan_band_t *b, int64_t x, int64_t y, int64_t n, meta_rgb_t rgb)
{
	int lo = b->jlo < 0 ? 0 : b->jlo, hi = b->jhi > b->height ? b->height : b->jhi;
	if (y < lo || y >= hi || n <= 0)
		return;
	pen_t pen;
	pen_make(&pen, rgb);
	paint(b, (int)y, x, x + n, &pen);
}

void scan_clear(const scan_band_t *b, meta_rgb_t rgb)
{
	pen_t pen;
	pen_make(&pen, rgb);
	int lo = b->jlo < 0 ? 0 : b->jlo, hi = b->jhi > b->height ? b->height : b->jhi;
	for (int j = lo; j < hi; j++)
		paint(b, j, 0, b->width, &pen);
}

static int cmp_edge(const void *a, const void *b)
{
	const edge_t *x = a, *y = b;
	return (x->jf > y->jf) - (x->jf < y->jf);
}

/* Paint row j of a closed polygon from its na active edges. Two crossings (most rows of most
 * polygons) have opposite directions, as a row crosses every closed contour as often upwards as
 * downwards: inside by either rule between them, so no sorting or winding walk is needed. */
static inline void paint_active(const scan_band_t *b, int j, edge_t *const *act, size_t na,
		cross_t *cr, int rule, const pen_t *pen)
{
	if (na == 2) {
		int64_t x0 = act[0]->i, x1 = act[1]->i;
		if (x0 > x1) {
			int64_t t = x0; x0 = x1; x1 = t;
		}
		if (x1 > x0)
			paint(b, j, x0, x1, pen);
		return;
	}
	for (size_t k = 0; k < na; k++)
		insert_crossing(cr, k, (cross_t){ act[k]->i, act[k]->dir });
	paint_crossings(b, j, cr, na, rule, pen);
}

/* Step the active edges to the next row and retire those ending at row j; the new count. */
static inline size_t step_active(edge_t **act, size_t na, int j)
{
	size_t keep = 0;
	for (size_t k = 0; k < na; k++) {
		if (act[k]->jl == j)
			continue;
		edge_step(act[k]);
		act[keep++] = act[k];
	}
	return keep;
}

/* Few edges (small polygons, stroke pieces): the edges ordered by first row by insertion, and
 * each row visits only the edges active on it (testing every edge on every row was most of
 * the time of workload b's 10,000 small polygons). */
static void sweep_small(const scan_band_t *b, edge_t *e, size_t n, int rule, const pen_t *pen)
{
	edge_t *ord[SMALL_EDGES], *act[SMALL_EDGES];
	cross_t cr[SMALL_EDGES];
	int jmax = e[0].jl;
	for (size_t k = 0; k < n; k++) {
		size_t m = k;
		while (m > 0 && ord[m - 1]->jf > e[k].jf) {
			ord[m] = ord[m - 1];
			m--;
		}
		ord[m] = &e[k];
		if (e[k].jl > jmax)
			jmax = e[k].jl;
	}
	size_t next = 0, na = 0;
	for (int j = ord[0]->jf; j <= jmax; j++) {
		while (next < n && ord[next]->jf == j)
			act[na++] = ord[next++];
		if (na == 0) {
			j = ord[next]->jf - 1;   /* a gap between contours: edges remain, as j <= jmax */
			continue;
		}
		paint_active(b, j, act, na, cr, rule, pen);
		na = step_active(act, na, j);
	}
}

/* Convex polygons: every row crosses exactly two edges (or none), the span lies between. */
static void sweep_convex(const scan_band_t *b, edge_t *e, size_t n, const pen_t *pen)
{
	int j0 = e[0].jf, j1 = e[0].jl;
	for (size_t k = 1; k < n; k++) {
		if (e[k].jf < j0) j0 = e[k].jf;
		if (e[k].jl > j1) j1 = e[k].jl;
	}
	for (int j = j0; j <= j1; j++) {
		int64_t lo = INT64_MAX, hi = INT64_MIN;
		for (size_t k = 0; k < n; k++) {
			edge_t *a = &e[k];
			if (j < a->jf || j > a->jl)
				continue;
			if (a->i < lo) lo = a->i;
			if (a->i > hi) hi = a->i;
			if (j < a->jl)
				edge_step(a);
		}
		if (hi > lo)
			paint(b, j, lo, hi, pen);
	}
}

/* The general scanline loop over n prepared edges. */
static int sweep(scan_ctx_t *c, const scan_band_t *b, size_t n, int rule, meta_rgb_t rgb)
{
	if (n == 0)
		return 0;
	const pen_t *pen = ctx_pen(c, rgb);
	if (n <= SMALL_EDGES) {
		sweep_small(b, c->edges, n, rule, pen);
		return 0;
	}
	if (grow((void **)&c->active, &c->cap_active, n, sizeof(edge_t *)) ||
			grow((void **)&c->cross, &c->cap_cross, n, sizeof(cross_t)))
		return META_ENOMEM;
	edge_t *e = c->edges;
	if (n > 1)
		qsort(e, n, sizeof(edge_t), cmp_edge);
	int jmax = e[0].jl;
	for (size_t k = 1; k < n; k++)
		if (e[k].jl > jmax)
			jmax = e[k].jl;
	size_t next = 0, na = 0;
	edge_t **act = c->active;
	cross_t *cr = c->cross;
	for (int j = e[0].jf; j <= jmax; j++) {
		while (next < n && e[next].jf == j)
			act[na++] = &e[next++];
		if (na == 0) {
			if (next < n)
				j = e[next].jf - 1;
			continue;
		}
		paint_active(b, j, act, na, cr, rule, pen);
		na = step_active(act, na, j);
	}
	return 0;
}

/* Pieces with every coordinate within +-TINY (most stroke pieces): each crossing is computed
 * directly per row from the exact numerator (x0*dy + (Yc - y0)*dx - 500*dy, below 2^51, so
 * exact in a double) with a per-edge reciprocal estimate corrected exactly: the same pixel
 * indices as the DDA of edge_init, without its integer divisions or the edge table. */
#define TINY ((int64_t)1 << 24)

typedef struct {
	int64_t n, s, d;    /* numerator at row j0, its step per row (1000*dx), 1000*dy */
	double inv;         /* 1 / d */
	int j0, j1, dir;
} tedge_t;

/* ceil((v - 500) / 1000) for |v| < TINY: the first pixel row (column) whose centre is at or
 * above (right of) v, as floor((v + 499) / 1000) shifted positive by 16777 * 1000 so that
 * an unsigned 32-bit division (a multiply) computes it, not a signed 64-bit one and its
 * correction (ceil_div was a tenth of workload a's instructions). */
static inline int64_t tiny_row(int64_t v)
{
	return (int64_t)((uint32_t)(v + 16777499) / 1000u) - 16777;
}

/* ceil(n / d) for d > 0, |n| < 2^52: the estimate n * inv is within one of it. */
static inline int64_t tiny_ceil(int64_t n, int64_t d, double inv)
{
	int64_t q = (int64_t)ceil((double)n * inv);
	/* q is right when 0 <= q*d - n < d; being within one, a step either way without a loop
	 * (the two correction loops were a tenth of a film frame's instructions) */
	int64_t r = q * d - n;
	return q + (r < 0) - (r >= d);
}

/* Sort the edges of one direction by first row (insertion: a chain has a few) and tell whether
 * they tile rows [j0, j1] exactly, each row crossing one of them. */
static inline int chain(tedge_t **ch, size_t n, int *j0, int *j1)
{
	if (n == 2) {   /* a parallelogram's side: most chains */
		if (ch[0]->j0 > ch[1]->j0) {
			tedge_t *t = ch[0]; ch[0] = ch[1]; ch[1] = t;
		}
		*j0 = ch[0]->j0;
		*j1 = ch[1]->j1;
		return ch[1]->j0 == ch[0]->j1 + 1;
	}
	for (size_t k = 1; k < n; k++) {
		tedge_t *t = ch[k];
		size_t m = k;
		while (m > 0 && ch[m - 1]->j0 > t->j0) {
			ch[m] = ch[m - 1];
			m--;
		}
		ch[m] = t;
	}
	for (size_t k = 1; k < n; k++)
		if (ch[k]->j0 != ch[k - 1]->j1 + 1)
			return 0;
	*j0 = ch[0]->j0;
	*j1 = ch[n - 1]->j1;
	return 1;
}

/* Paint the piece from its upward and downward chains when each row of it crosses exactly one
 * edge of each (every convex piece, most join pieces): two crossings of opposite directions, so
 * the row is inside by either rule between them, and only those two edges are computed on
 * each row. Returns 0 (painted) or -1 when the chains do not tile the same rows. */
static int fill_chains(const scan_band_t *b, tedge_t *e, size_t ne, const pen_t *pen)
{
	tedge_t *up[SMALL_EDGES], *dn[SMALL_EDGES];
	size_t nu = 0, nd = 0;
	for (size_t k = 0; k < ne; k++) {
		if (e[k].dir > 0)
			up[nu++] = &e[k];
		else
			dn[nd++] = &e[k];
	}
	int u0, u1, d0, d1;
	if (!nu || !nd || !chain(up, nu, &u0, &u1) || !chain(dn, nd, &d0, &d1) || u0 != d0 || u1 != d1)
		return -1;
	size_t iu = 0, id = 0;
	tedge_t *u = up[0], *d = dn[0];
	for (int j = u0; j <= u1; j++) {
		if (j > u->j1)
			u = up[++iu];
		if (j > d->j1)
			d = dn[++id];
		int64_t l = tiny_ceil(u->n, u->d, u->inv), r = tiny_ceil(d->n, d->d, d->inv);
		u->n += u->s;
		d->n += d->s;
		if (l > r) {
			int64_t t = l; l = r; r = t;
		}
		if (r > l)
			paint(b, j, l, r, pen);
	}
	return 0;
}

/* Fill a piece of m <= SMALL_EDGES points within +-TINY, rows clipped to [lo, hi). */
static void fill_tiny(const scan_band_t *b, const scan_pt_t *pts, size_t m, int rule,
		const pen_t *pen, int convex, int lo, int hi)
{
	tedge_t e[SMALL_EDGES];
	int64_t jv[SMALL_EDGES];   /* each vertex's first pixel-centre row at or above it */
	for (size_t k = 0; k < m; k++)
		jv[k] = tiny_row(pts[k].y);
	size_t ne = 0;
	int jmin = INT32_MAX, jmax = INT32_MIN;
	for (size_t k = 0; k < m; k++) {
		size_t kz = k + 1 == m ? 0 : k + 1;
		if (jv[k] == jv[kz])
			continue;   /* no centre row between them (a horizontal edge among them) */
		const scan_pt_t *a = &pts[k], *z = &pts[kz];
		int up = a->y < z->y, dir = up ? 1 : -1;
		int64_t x0 = up ? a->x : z->x, y0 = up ? a->y : z->y;
		int64_t x1 = up ? z->x : a->x, y1 = up ? z->y : a->y;
		int64_t j0 = up ? jv[k] : jv[kz], j1 = (up ? jv[kz] : jv[k]) - 1;
		if (j0 < lo)
			j0 = lo;
		if (j1 > hi - 1)
			j1 = hi - 1;
		if (j0 > j1)
			continue;
		int64_t dx = x1 - x0, dy = y1 - y0;
		tedge_t *t = &e[ne++];
		t->d = 1000 * dy;
		t->n = x0 * dy + (1000 * j0 + 500 - y0) * dx - 500 * dy;
		t->s = 1000 * dx;
		t->inv = 1.0 / (double)t->d;
		t->j0 = (int)j0;
		t->j1 = (int)j1;
		t->dir = dir;
		if (t->j0 < jmin)
			jmin = t->j0;
		if (t->j1 > jmax)
			jmax = t->j1;
	}
	if (ne == 0 || fill_chains(b, e, ne, pen) == 0)
		return;
	for (int j = jmin; j <= jmax; j++) {
		if (convex) {
			int64_t l = INT64_MAX, r = INT64_MIN;
			for (size_t k = 0; k < ne; k++) {
				tedge_t *t = &e[k];
				if (j < t->j0 || j > t->j1)
					continue;
				int64_t i = tiny_ceil(t->n, t->d, t->inv);
				t->n += t->s;
				if (i < l) l = i;
				if (i > r) r = i;
			}
			if (r > l)
				paint(b, j, l, r, pen);
			continue;
		}
		cross_t cr[SMALL_EDGES];
		size_t na = 0;
		for (size_t k = 0; k < ne; k++) {
			tedge_t *t = &e[k];
			if (j < t->j0 || j > t->j1)
				continue;
			insert_crossing(cr, na++, (cross_t){ tiny_ceil(t->n, t->d, t->inv), t->dir });
			t->n += t->s;
		}
		paint_crossings(b, j, cr, na, rule, pen);
	}
}

static void band_rows(const scan_band_t *b, int *lo, int *hi)
{
	*lo = b->jlo < 0 ? 0 : b->jlo;
	*hi = b->jhi > b->height ? b->height : b->jhi;
}

int scan_fill(scan_ctx_t *c, const scan_band_t *b, const scan_path_t *p, int rule, meta_rgb_t rgb)
{
	int lo, hi;
	band_rows(b, &lo, &hi);
	if (lo >= hi)
		return 0;
	if (grow((void **)&c->edges, &c->cap_edges, p->npts, sizeof(edge_t)))
		return META_ENOMEM;
	size_t n = 0;
	for (size_t s = 0; s < p->nsubs; s++) {
		const scan_pt_t *q = p->pts + p->subs[s].start;
		size_t m = p->subs[s].n;
		if (m < 2)
			continue;
		for (size_t k = 0; k < m; k++) {
			const scan_pt_t *a = &q[k], *z = &q[k + 1 == m ? 0 : k + 1];
			n += (size_t)edge_init(&c->edges[n], a->x, a->y, z->x, z->y, lo, hi);
		}
	}
	return sweep(c, b, n, rule, rgb);
}

int scan_fill_piece(scan_ctx_t *c, const scan_band_t *b, const scan_pt_t *pts, size_t m, int rule,
		meta_rgb_t rgb, int convex)
{
	int lo, hi;
	band_rows(b, &lo, &hi);
	if (lo >= hi || m < 3)
		return 0;
	/* a covered centre lies inside the bounding box: skip pieces that hold no centre row or
	 * column (most join pieces of thin lines) */
	int64_t x0 = pts[0].x, x1 = x0, y0 = pts[0].y, y1 = y0;
	for (size_t k = 1; k < m; k++) {
		if (pts[k].x < x0) x0 = pts[k].x;
		if (pts[k].x > x1) x1 = pts[k].x;
		if (pts[k].y < y0) y0 = pts[k].y;
		if (pts[k].y > y1) y1 = pts[k].y;
	}
	if (x0 > -TINY && x1 < TINY && y0 > -TINY && y1 < TINY) {
		if (tiny_row(y0) >= tiny_row(y1) || tiny_row(x0) >= tiny_row(x1))
			return 0;
		if (m <= SMALL_EDGES) {
			fill_tiny(b, pts, m, rule, ctx_pen(c, rgb), convex, lo, hi);
			return 0;
		}
	} else if (ceil_div(y0 - 500, 1000) > ceil_div(y1 - 500, 1000) - 1 ||
			ceil_div(x0 - 500, 1000) > ceil_div(x1 - 500, 1000) - 1) {
		return 0;
	}
	if (grow((void **)&c->edges, &c->cap_edges, m, sizeof(edge_t)))
		return META_ENOMEM;
	size_t n = 0;
	for (size_t k = 0; k < m; k++) {
		const scan_pt_t *a = &pts[k], *z = &pts[k + 1 == m ? 0 : k + 1];
		n += (size_t)edge_init(&c->edges[n], a->x, a->y, z->x, z->y, lo, hi);
	}
	if (convex && n > 0) {
		sweep_convex(b, c->edges, n, ctx_pen(c, rgb));
		return 0;
	}
	return sweep(c, b, n, rule, rgb);
}
