/* quant_near.c: the nearest palette entry search: sorted entries, candidate pools, cells. */
#include <stdlib.h>
#include <string.h>
#include "quant/quant_int.h"

/* ---- nearest entry ------------------------------------------------------------------ */

void quant_near_init(qnear_t *q, const int (*col)[3], unsigned n)
{
	q->n = n;
	for (unsigned k = 0; k < n; k++) {   /* insertion sort by r + g + b: n <= 256 */
		int key = col[k][0] + col[k][1] + col[k][2];
		unsigned j = k;
		while (j > 0 && q->key[j - 1] > key) {
			memcpy(q->c[j], q->c[j - 1], sizeof q->c[0]);
			q->idx[j] = q->idx[j - 1];
			q->key[j] = q->key[j - 1];
			j--;
		}
		memcpy(q->c[j], col[k], sizeof q->c[0]);
		q->idx[j] = (uint8_t)k;
		q->key[j] = key;
	}
	for (unsigned j = 0; j < n; j++)
		q->pos[q->idx[j]] = (uint8_t)j;
}

unsigned quant_near_find(const qnear_t *q, int r, int g, int b)
{
	return quant_near_find_from(q, r, g, b, -1);
}

unsigned quant_near_find_from(const qnear_t *q, int r, int g, int b, int hint)
{
	int key = r + g + b;
	unsigned lo = 0, hi = q->n;
	while (lo < hi) {            /* first entry with key >= key */
		unsigned mid = (lo + hi) / 2;
		if (q->key[mid] < key)
			lo = mid + 1;
		else
			hi = mid;
	}
	/* |dr + dg + db| <= sqrt(3) * distance: an entry whose key differs by dk is no nearer
	 * than dk^2 / 3, and neither is any entry beyond it */
	long best = -1;
	unsigned bi = 0;
	if (hint >= 0) {             /* a good first guess bounds the search from the start */
		const int *c = q->c[q->pos[hint]];
		long dr = c[0] - r, dg = c[1] - g, db = c[2] - b;
		best = dr * dr + dg * dg + db * db;
		bi = (unsigned)hint;
	}
	int up = (int)lo, down = (int)lo - 1;
	while (up < (int)q->n || down >= 0) {
		if (up < (int)q->n) {
			long dk = q->key[up] - key;
			if (best >= 0 && dk * dk > 3 * best) {
				up = (int)q->n;
			} else {
				long dr = q->c[up][0] - r, dg = q->c[up][1] - g, db = q->c[up][2] - b;
				long d = dr * dr + dg * dg + db * db;
				if (best < 0 || d < best || (d == best && q->idx[up] < bi))
					best = d, bi = q->idx[up];
				up++;
			}
		}
		if (down >= 0) {
			long dk = key - q->key[down];
			if (best >= 0 && dk * dk > 3 * best) {
				down = -1;
			} else {
				long dr = q->c[down][0] - r, dg = q->c[down][1] - g, db = q->c[down][2] - b;
				long d = dr * dr + dg * dg + db * db;
				if (best < 0 || d < best || (d == best && q->idx[down] < bi))
					best = d, bi = q->idx[down];
				down--;
			}
		}
	}
	return bi;
}

unsigned quant_near_find2(const qnear_t *q, int r, int g, int b, long *d1, long *d2)
{
	int key = r + g + b;
	unsigned lo = 0, hi = q->n;
	while (lo < hi) {
		unsigned mid = (lo + hi) / 2;
		if (q->key[mid] < key)
			lo = mid + 1;
		else
			hi = mid;
	}
	/* as quant_near_find_from, the bound being the second best: no entry beyond a key
	 * difference dk is nearer than dk^2 / 3 */
	long best = -1, second = -1;
	unsigned bi = 0;
	int up = (int)lo, down = (int)lo - 1;
	while (up < (int)q->n || down >= 0) {
		for (int side = 0; side < 2; side++) {
			int j = side ? down : up;
			if (side ? j < 0 : j >= (int)q->n)
				continue;
			long dk = side ? key - q->key[j] : q->key[j] - key;
			if (second >= 0 && dk * dk > 3 * second) {
				if (side)
					down = -1;
				else
					up = (int)q->n;
				continue;
			}
			long dr = q->c[j][0] - r, dg = q->c[j][1] - g, db = q->c[j][2] - b;
			long d = dr * dr + dg * dg + db * db;
			if (best < 0 || d < best || (d == best && q->idx[j] < bi)) {
				second = best;
				best = d, bi = q->idx[j];
			} else if (second < 0 || d < second) {
				second = d;
			}
			if (side)
				down--;
			else
				up++;
		}
	}
	*d1 = best, *d2 = second;
	return bi;
}

void quant_near_palette(qnear_t *q, const quant_palette_t *pal)
{
	int col[QUANT_MAX][3];
	for (unsigned k = 0; k < pal->n; k++)
		for (int c = 0; c < 3; c++)
			col[k][c] = (int)quant_show(pal, pal->dac[k][c]) * 4;
	quant_near_init(q, (const int (*)[3])col, pal->n);
}


/* ---- cell candidates ---------------------------------------------------------------- */

long quant_pool_add(qpool_t *p, const int32_t *dmin, unsigned n, int32_t bound, size_t *start)
{
	if (p->n + n > p->cap) {
		size_t cap = p->cap ? p->cap * 2 : 65536;
		while (cap < p->n + n)
			cap *= 2;
		uint8_t *e = realloc(p->e, cap);
		if (e)
			p->e = e;
		int32_t *d = realloc(p->d, cap * sizeof *d);
		if (d)
			p->d = d;
		if (!e || !d)
			return -1;
		p->cap = cap;
	}
	size_t s = p->n, k = s;
	for (unsigned e = 0; e < n; e++) {
		if (dmin[e] > bound)
			continue;
		size_t j = k++;           /* insertion by distance, then index */
		while (j > s && p->d[j - 1] > dmin[e]) {
			p->e[j] = p->e[j - 1];
			p->d[j] = p->d[j - 1];
			j--;
		}
		p->e[j] = (uint8_t)e;
		p->d[j] = dmin[e];
	}
	p->n = k;
	*start = s;
	return (long)(k - s);
}

void quant_pool_free(qpool_t *p)
{
	free(p->e);
	free(p->d);
	p->e = NULL;
	p->d = NULL;
	p->n = p->cap = 0;
}

/* ---- nearest and second-nearest by cells ------------------------------------------- */

#define QCSHIFT 8               /* cells of 256 search units (64 8-bit levels) a side ... */
#define QCLEVELS 4              /* ... 4 a channel: measured best on workload a (2, 8 and 16 slower) */

struct qcells {
	unsigned n;
	int col[QUANT_MAX][3];
	int32_t cnear[3][QCLEVELS][QUANT_MAX];   /* per channel and grid level: each entry's ... */
	int32_t cfar[3][QCLEVELS][QUANT_MAX];    /* ... squared distance to its nearest and farthest value */
	uint32_t start[QCLEVELS * QCLEVELS * QCLEVELS];   /* per cell: its candidates in pool ... */
	uint16_t count[QCLEVELS * QCLEVELS * QCLEVELS];   /* ... (count 0: not built) */
	qpool_t pool;
};

qcells_t *quant_cells_new(void)
{
	return calloc(1, sizeof(qcells_t));
}

void quant_cells_free(qcells_t *c)
{
	if (!c)
		return;
	quant_pool_free(&c->pool);
	free(c);
}

void quant_cells_reset(qcells_t *c, const int (*col)[3], unsigned n)
{
	c->n = n;
	memcpy(c->col, col, n * sizeof c->col[0]);
	for (int ch = 0; ch < 3; ch++)   /* level L of a channel spans [128 L, 128 L + 127] */
		for (int L = 0; L < QCLEVELS; L++)
			for (unsigned k = 0; k < n; k++) {
				int32_t v = col[k][ch], lo = L << QCSHIFT, hi = lo + (1 << QCSHIFT) - 1;
				int32_t in = v < lo ? lo - v : v > hi ? v - hi : 0, out = v - lo > hi - v ? v - lo : hi - v;
				c->cnear[ch][L][k] = in * in;
				c->cfar[ch][L][k] = out * out;
			}
	memset(c->count, 0, sizeof c->count);
	c->pool.n = 0;
}

/* The candidates of a cell: every entry that can be nearest or second nearest to a colour in
 * it (no farther from the cell than the second least farthest-corner distance: the two
 * entries of the least farthest corners are within it of every colour of the cell). */
static int cell_build(qcells_t *c, unsigned cell)
{
	unsigned n = c->n, l0 = cell / (QCLEVELS * QCLEVELS), l1 = cell / QCLEVELS % QCLEVELS, l2 = cell % QCLEVELS;
	const int32_t *n0 = c->cnear[0][l0], *n1 = c->cnear[1][l1], *n2 = c->cnear[2][l2];
	const int32_t *f0 = c->cfar[0][l0], *f1 = c->cfar[1][l1], *f2 = c->cfar[2][l2];
	int32_t dmin[QUANT_MAX], dfar[QUANT_MAX], least1 = INT32_MAX, least2 = INT32_MAX;
	for (unsigned e = 0; e < n; e++) {
		dmin[e] = n0[e] + n1[e] + n2[e];
		dfar[e] = f0[e] + f1[e] + f2[e];
	}
	for (unsigned e = 0; e < n; e++) {
		int32_t b = dfar[e];
		if (b < least2) {
			if (b < least1)
				least2 = least1, least1 = b;
			else
				least2 = b;
		}
	}
	if (n < 2)
		least2 = least1;
	size_t start;
	long k = quant_pool_add(&c->pool, dmin, n, least2, &start);
	if (k < 0)
		return -1;
	c->start[cell] = (uint32_t)start;
	c->count[cell] = (uint16_t)k;
	return 0;
}

unsigned quant_cells_find2(qcells_t *c, const qnear_t *q, int r, int g, int b, long *d1, long *d2)
{
	unsigned cell = ((unsigned)(r >> QCSHIFT) * QCLEVELS + (unsigned)(g >> QCSHIFT)) * QCLEVELS + (unsigned)(b >> QCSHIFT);
	if (r < 0 || g < 0 || b < 0 || r > 1023 || g > 1023 || b > 1023 ||
			(c->count[cell] == 0 && cell_build(c, cell) < 0))
		return quant_near_find2(q, r, g, b, d1, d2);
	const uint8_t *cand = c->pool.e + c->start[cell];
	const int32_t *cd = c->pool.d + c->start[cell];
	long best = -1, second = -1;
	unsigned bi = 0;
	/* a candidate farther from the cell than the second best so far is farther than it from
	 * the colour, and so are all after it */
	for (unsigned k = 0; k < c->count[cell] && !(second >= 0 && cd[k] > second); k++) {
		const int *e = c->col[cand[k]];
		long dr = e[0] - r, dg = e[1] - g, db = e[2] - b, d = dr * dr + dg * dg + db * db;
		if (best < 0 || d < best || (d == best && cand[k] < bi)) {
			second = best;
			best = d, bi = cand[k];
		} else if (second < 0 || d < second) {
			second = d;
		}
	}
	*d1 = best, *d2 = second;
	return bi;
}
