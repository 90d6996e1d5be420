/* quant_kmeans.c: Lloyd k-means passes over weighted colours, with Hamerly's bounds (exact). */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include "quant/quant_int.h"

/* The 8-bit value the DAC of bits (6 or 8) shows nearest to v. */
static double on_grid(double v, unsigned bits)
{
	if (bits == 8)
		return v < 0 ? 0 : v > 255 ? 255 : floor(v + 0.5);
	double x = v * 63.0 / 255.0 + 0.5;
	return quant_dac8((unsigned)(x < 0 ? 0 : x > 63 ? 63 : x));
}

/* One pass's assignment of colours [lo, hi) to their nearest entries: sums into acc (k x
 * (r, g, b, weight)), the colour of the largest weighted error into worst / wi. Hamerly's
 * bounds skip most searches: u[i] bounds from above the distance from colour i to its entry
 * was[i], l[i] from below its distance to every other entry (both kept through the entries'
 * moves by the triangle inequality); when u[i] < max(l[i], half the distance from the entry
 * to its nearest other), the entry is strictly the nearest: the same answer as a search.
 * One entry that jumps (an empty one moved to the worst colour) would lower every l[i] by its
 * jump: the QJUMP entries that moved most are measured instead (their exact distances), and
 * the bound of the others falls only by the largest move among the rest. */
#define QJUMP 16

typedef struct {
	const qcol_t *col;
	const int (*c4)[3];         /* the colours in search units (times 4, rounded) */
	size_t lo, hi, k;
	int pass;
	const qnear_t *q;
	qcells_t *cells;            /* the same entries by cells (this part's own when threaded) */
	const int (*ic)[3];
	const double *half;         /* half the distance from each entry to its nearest other */
	const double *delta;        /* how far each entry moved since the pass before */
	double dmax1, dmax2;        /* the largest move, and the largest of the others */
	unsigned dmaxi;             /* the entry that moved most */
	unsigned nj;                /* how many entries moved most, measured: ... */
	const int32_t (*jc)[QJUMP]; /* ... their places by channel (the unused ones far away) ... */
	const int32_t *jidx;        /* ... and indices (-1 unused) ... */
	double drest1, drest2;      /* ... and the largest move of the others, and the next */
	unsigned dresti;            /* the other entry that moved most */
	const double (*means)[3];
	uint8_t *was;
	double *u, *l;
	double (*acc)[4];
	double worst;
	size_t wi;
} qassign_t;

static void *assign(void *arg)
{
	qassign_t *a = arg;
	const qcol_t *col = a->col;
	memset(a->acc, 0, a->k * sizeof *a->acc);
	a->worst = -1, a->wi = a->lo;
	for (size_t i = a->lo; i < a->hi; i++) {
		int r = a->c4[i][0], g = a->c4[i][1], b = a->c4[i][2];
		unsigned e = a->was[i];
		int search = a->pass == 0;
		if (!search) {
			double lold = a->l[i];
			a->u[i] += a->delta[e];
			a->l[i] = lold - (e == a->dmaxi ? a->dmax2 : a->dmax1);
			double m = a->l[i] > a->half[e] ? a->l[i] : a->half[e];
			if (!(a->u[i] < m) && a->nj) {
				/* the entries that jumped at their exact distances, the rest by their moves */
				int32_t dmin = INT32_MAX;   /* all QJUMP at once (vectorised), own entry left out */
				for (unsigned j = 0; j < QJUMP; j++) {
					int32_t dr = a->jc[0][j] - r, dg = a->jc[1][j] - g, db = a->jc[2][j] - b;
					int32_t d = a->jidx[j] == (int32_t)e ? INT32_MAX : dr * dr + dg * dg + db * db;
					dmin = d < dmin ? d : dmin;
				}
				long dj = dmin == INT32_MAX ? -1 : dmin;
				double lj = lold - (e == a->dresti ? a->drest2 : a->drest1);
				if (dj >= 0 && sqrt((double)dj) < lj)
					lj = sqrt((double)dj);
				if (lj > a->l[i])    /* both bound every other entry: the larger holds */
					a->l[i] = lj;
				m = a->l[i] > a->half[e] ? a->l[i] : a->half[e];
			}
			if (!(a->u[i] < m)) {
				const int *c = a->ic[e];
				long dr = c[0] - r, dg = c[1] - g, db = c[2] - b;
				a->u[i] = sqrt((double)(dr * dr + dg * dg + db * db));
				search = !(a->u[i] < m);
			}
		}
		if (search) {
			long d1, d2;
			e = quant_cells_find2(a->cells, a->q, r, g, b, &d1, &d2);
			a->u[i] = sqrt((double)d1);
			a->l[i] = d2 < 0 ? 1e30 : sqrt((double)d2);
		}
		a->was[i] = (uint8_t)e;
		double d = 0;
		for (int c = 0; c < 3; c++) {
			a->acc[e][c] += col[i].c[c] * col[i].w;
			d += (col[i].c[c] - a->means[e][c]) * (col[i].c[c] - a->means[e][c]);
		}
		a->acc[e][3] += col[i].w;
		if (d * col[i].w > a->worst)
			a->worst = d * col[i].w, a->wi = i;
	}
	return NULL;
}

/* Colours of at least this many are assigned in two halves, the second on a thread of its
 * own when a core is spare (quant_spare_core); the halves' sums are added in one order, so the
 * palette depends only on the input (the same when the halves run one after the other). */
#define QKSPLIT 4096

/* Lloyd passes over the weighted colours: entries [fixed, k) move to the mean of the colours
 * nearest to them; entries below fixed (the flat colours) stay. An entry left with no colour
 * is moved to the colour of the largest weighted error. With grid, every entry is held at
 * the nearest colour the DAC shows (the last passes: assignments then match the palette
 * that will be used). */
int quant_kmeans(const qcol_t *col, size_t n, double (*means)[3], size_t fixed, size_t k, int passes,
		unsigned grid)
{
	double (*acc)[4] = malloc(2 * k * sizeof *acc);
	uint8_t *was = calloc(n ? n : 1, 1);   /* each colour's entry in the pass before */
	qnear_t *q = malloc(sizeof *q);
	int (*c4)[3] = malloc((n ? n : 1) * sizeof *c4);
	double *u = malloc((n ? n : 1) * sizeof *u), *l = malloc((n ? n : 1) * sizeof *l);
	qcells_t *cells[2] = { quant_cells_new(), NULL };
	if (!acc || !was || !q || !c4 || !u || !l || !cells[0]) {
		free(acc), free(was), free(q), free(c4), free(u), free(l);
		quant_cells_free(cells[0]);
		return -1;
	}
	for (size_t i = 0; i < n; i++)
		for (int c = 0; c < 3; c++)
			c4[i][c] = (int)lround(col[i].c[c] * 4);
	if (grid)
		for (size_t e = 0; e < k; e++)
			for (int c = 0; c < 3; c++)
				means[e][c] = on_grid(means[e][c], grid);
	unsigned nparts = n >= QKSPLIT ? 2 : 1;
	int spare = nparts == 2 && quant_spare_core() && (cells[1] = quant_cells_new()) != NULL;
	int ic[QUANT_MAX][3], prev[QUANT_MAX][3];
	for (int pass = 0; pass < passes; pass++) {
		double half[QUANT_MAX], delta[QUANT_MAX], dmax1 = 0, dmax2 = 0;
		unsigned dmaxi = 0;
		for (size_t e = 0; e < k; e++) {
			for (int c = 0; c < 3; c++)
				ic[e][c] = (int)lround(means[e][c] * 4);
			delta[e] = 0;
			if (pass) {
				long dr = ic[e][0] - prev[e][0], dg = ic[e][1] - prev[e][1], db = ic[e][2] - prev[e][2];
				delta[e] = sqrt((double)(dr * dr + dg * dg + db * db));
			}
			if (delta[e] > dmax1)
				dmax2 = dmax1, dmax1 = delta[e], dmaxi = (unsigned)e;
			else if (delta[e] > dmax2)
				dmax2 = delta[e];
		}
		memcpy(prev, ic, sizeof prev);
		/* the QJUMP entries that moved most (more than nothing), largest first */
		uint8_t jump[QJUMP], injump[QUANT_MAX] = { 0 };
		unsigned nj = 0, dresti = 0;
		for (size_t e = 0; e < k; e++) {
			if (!(delta[e] > 0) || (nj == QJUMP && !(delta[e] > delta[jump[nj - 1]])))
				continue;
			unsigned j = nj < QJUMP ? nj++ : nj - 1;
			while (j > 0 && delta[jump[j - 1]] < delta[e])
				jump[j] = jump[j - 1], j--;
			jump[j] = (uint8_t)e;
		}
		for (unsigned j = 0; j < nj; j++)
			injump[jump[j]] = 1;
		int32_t jc[3][QJUMP], jidx[QJUMP];
		for (unsigned j = 0; j < QJUMP; j++) {
			jidx[j] = j < nj ? jump[j] : -1;
			for (int c = 0; c < 3; c++)   /* an unused one 8,192 units away: never the nearest */
				jc[c][j] = j < nj ? ic[jump[j]][c] : 8192;
		}
		double drest1 = 0, drest2 = 0;
		for (size_t e = 0; e < k; e++) {
			if (injump[e])
				continue;
			if (delta[e] > drest1)
				drest2 = drest1, drest1 = delta[e], dresti = (unsigned)e;
			else if (delta[e] > drest2)
				drest2 = delta[e];
		}
		quant_near_init(q, (const int (*)[3])ic, (unsigned)k);
		for (int t = 0; t < 2; t++)
			if (cells[t])
				quant_cells_reset(cells[t], (const int (*)[3])ic, (unsigned)k);
		for (size_t e = 0; e < k; e++) {
			/* the second nearest to the entry's own place: its nearest other (0 for a twin) */
			long d1, m;
			quant_cells_find2(cells[0], q, ic[e][0], ic[e][1], ic[e][2], &d1, &m);
			half[e] = m < 0 ? 1e30 : sqrt((double)m) / 2;
		}
		qassign_t part[2];
		for (unsigned t = 0; t < nparts; t++)
			part[t] = (qassign_t){ .col = col, .c4 = (const int (*)[3])c4, .lo = n * t / nparts,
				.hi = n * (t + 1) / nparts, .k = k, .pass = pass, .q = q, .cells = cells[t && spare],
				.ic = (const int (*)[3])ic,
				.half = half, .delta = delta, .dmax1 = dmax1, .dmax2 = dmax2, .dmaxi = dmaxi, .nj = nj,
				.jc = (const int32_t (*)[QJUMP])jc, .jidx = jidx, .drest1 = drest1, .drest2 = drest2,
				.dresti = dresti,
				.means = (const double (*)[3])means, .was = was, .u = u, .l = l, .acc = acc + t * k,
				.worst = -1, .wi = 0 };
		pthread_t th;
		int threaded = spare && pthread_create(&th, NULL, assign, &part[1]) == 0;
		assign(&part[0]);
		if (threaded)
			pthread_join(th, NULL);
		else if (nparts == 2)
			assign(&part[1]);
		double worst = part[0].worst;
		size_t wi = part[0].wi;
		if (nparts == 2) {
			for (size_t e = 0; e < k; e++)
				for (int c = 0; c < 4; c++)
					acc[e][c] += acc[k + e][c];
			if (part[1].worst > worst)
				worst = part[1].worst, wi = part[1].wi;
		}
		double moved = 0;
		for (size_t e = fixed; e < k; e++) {
			double nc[3];
			if (acc[e][3] > 0) {
				for (int c = 0; c < 3; c++)
					nc[c] = acc[e][c] / acc[e][3];
			} else if (worst > 0) {
				memcpy(nc, col[wi].c, sizeof nc);
				worst = 0;
			} else {
				continue;
			}
			for (int c = 0; c < 3; c++) {
				if (grid)
					nc[c] = on_grid(nc[c], grid);
				moved += fabs(nc[c] - means[e][c]);
				means[e][c] = nc[c];
			}
		}
		if (moved < (grid ? 0.5 : 0.01 * (double)(k - fixed)))
			break;
	}
	free(acc), free(was), free(q), free(c4), free(u), free(l);
	quant_cells_free(cells[0]);
	quant_cells_free(cells[1]);
	return 0;
}
