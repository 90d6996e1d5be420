/* quant.c: adaptive palettes from the histogram: median cut, octree, variance cut + k-means. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "quant_int.h"

/* ---- colours to quantise ------------------------------------------------------------ */

typedef struct {
	double c[3];                /* mean 8-bit colour of the bin */
	double w;                   /* pixels */
} qcol_t;

static double mean_of(const qbin_t *q, int c)
{
	return (double)q->sum[c] / q->count;
}

/* The palette entry of a mean colour. */
static void put_entry(quant_palette_t *pal, const double c[3])
{
	double top = pal->bits == 8 ? 255 : 63;
	for (int k = 0; k < 3; k++) {
		double v = c[k] * top / 255.0 + 0.5;
		pal->dac[pal->n][k] = (uint8_t)(v < 0 ? 0 : v > top ? top : v);
	}
	pal->n++;
}

/* ---- median cut (Heckbert 1982) ----------------------------------------------------- */

/* Order by channel axis first, then all channels: a total order, the same result from any qsort. */
static int by_channels(const qcol_t *p, const qcol_t *q, int axis)
{
	if (p->c[axis] != q->c[axis])
		return p->c[axis] < q->c[axis] ? -1 : 1;
	for (int k = 0; k < 3; k++)
		if (p->c[k] != q->c[k])
			return p->c[k] < q->c[k] ? -1 : 1;
	return 0;
}
static int by_red(const void *a, const void *b) { return by_channels(a, b, 0); }
static int by_green(const void *a, const void *b) { return by_channels(a, b, 1); }
static int by_blue(const void *a, const void *b) { return by_channels(a, b, 2); }
static int (*const by_axis[3])(const void *, const void *) = { by_red, by_green, by_blue };

/* p before q in the order of by_channels (inlined: the cuts sort most of the colours ~8 times) */
static inline int before(const qcol_t *p, const qcol_t *q, int axis)
{
	if (p->c[axis] != q->c[axis])
		return p->c[axis] < q->c[axis];
	for (int k = 0; k < 3; k++)
		if (p->c[k] != q->c[k])
			return p->c[k] < q->c[k];
	return 0;
}

static inline void swap_col(qcol_t *a, qcol_t *b)
{
	qcol_t t = *a;
	*a = *b, *b = t;
}

/* Sort n colours by by_axis[axis]: quicksort (median of three) down to insertion sort of short
 * runs; qsort past a depth of 2 log2 n. Colours are distinct, so the order is total and the
 * result is the one qsort gives. */
static void sort_axis(qcol_t *a, size_t n, int axis, int depth)
{
	while (n > 16) {
		if (depth-- <= 0) {
			qsort(a, n, sizeof *a, by_axis[axis]);
			return;
		}
		size_t mid = n / 2;
		if (before(&a[mid], &a[0], axis))
			swap_col(&a[mid], &a[0]);
		if (before(&a[n - 1], &a[mid], axis)) {
			swap_col(&a[n - 1], &a[mid]);
			if (before(&a[mid], &a[0], axis))
				swap_col(&a[mid], &a[0]);
		}
		qcol_t pivot = a[mid];
		size_t i = 0, j = n - 1;
		for (;;) {               /* Hoare's partition: a[0..j] <= pivot <= a[j+1..n) */
			while (before(&a[i], &pivot, axis))
				i++;
			while (before(&pivot, &a[j], axis))
				j--;
			if (i >= j)
				break;
			swap_col(&a[i], &a[j]);
			i++, j--;
		}
		size_t left = j + 1;
		if (left < n - left) {   /* the smaller side by recursion, the larger by the loop */
			sort_axis(a, left, axis, depth);
			a += left, n -= left;
		} else {
			sort_axis(a + left, n - left, axis, depth);
			n = left;
		}
	}
	for (size_t i = 1; i < n; i++) {
		qcol_t t = a[i];
		size_t j = i;
		while (j > 0 && before(&t, &a[j - 1], axis))
			a[j] = a[j - 1], j--;
		a[j] = t;
	}
}

/* The depth sort_axis allows for n colours. */
static int sort_depth(size_t n)
{
	int d = 0;
	while (n > 1)
		n >>= 1, d += 2;
	return d + 2;
}

typedef struct {
	size_t lo, hi;              /* colours [lo, hi) */
	double w;
	int sorted;                 /* the axis the colours are in order of (by_axis), -1 none */
} qbox_t;

/* Put a box's colours in order of axis, unless they are already (a box cut across the same
 * axis as its parent: the sort would give the same order). */
static void sort_box(qcol_t *col, qbox_t *bx, int axis)
{
	if (bx->sorted != axis)
		sort_axis(col + bx->lo, bx->hi - bx->lo, axis, sort_depth(bx->hi - bx->lo));
	bx->sorted = axis;
}

/* Split colours into at most k boxes; each box's weighted mean goes into means (returns the
 * number of boxes). The box split next is the one with the most pixels among those holding
 * more than one colour; it is cut across its longest side at the pixel median. */
static size_t median_cut(qcol_t *col, size_t n, size_t k, double (*means)[3])
{
	qbox_t box[QUANT_MAX];
	size_t nb = 0;
	if (n == 0 || k == 0)
		return 0;
	box[0].lo = 0, box[0].hi = n, box[0].w = 0, box[0].sorted = -1;
	for (size_t i = 0; i < n; i++)
		box[0].w += col[i].w;
	nb = 1;
	while (nb < k) {
		size_t pick = nb;
		for (size_t b = 0; b < nb; b++)
			if (box[b].hi - box[b].lo > 1 && (pick == nb || box[b].w > box[pick].w))
				pick = b;
		if (pick == nb)
			break;
		qbox_t *bx = &box[pick];
		double lo[3] = { 1e9, 1e9, 1e9 }, hi[3] = { -1e9, -1e9, -1e9 };
		for (size_t i = bx->lo; i < bx->hi; i++)
			for (int c = 0; c < 3; c++) {
				if (col[i].c[c] < lo[c]) lo[c] = col[i].c[c];
				if (col[i].c[c] > hi[c]) hi[c] = col[i].c[c];
			}
		int axis = 0;
		for (int c = 1; c < 3; c++)
			if (hi[c] - lo[c] > hi[axis] - lo[axis])
				axis = c;
		sort_box(col, bx, axis);
		double acc = 0;
		size_t m = bx->lo;
		while (m < bx->hi - 1 && (acc + col[m].w) * 2 <= bx->w)
			acc += col[m++].w;
		if (m == bx->lo)     /* the first colour alone holds half: it goes below the cut */
			acc += col[m++].w;
		box[nb].lo = m, box[nb].hi = bx->hi, box[nb].w = bx->w - acc, box[nb].sorted = axis;
		bx->hi = m, bx->w = acc;
		nb++;
	}
	for (size_t b = 0; b < nb; b++) {
		double s[3] = { 0, 0, 0 };
		for (size_t i = box[b].lo; i < box[b].hi; i++)
			for (int c = 0; c < 3; c++)
				s[c] += col[i].c[c] * col[i].w;
		for (int c = 0; c < 3; c++)
			means[b][c] = s[c] / box[b].w;
	}
	return nb;
}

/* ---- variance cut (the start of the default) ---------------------------------------- */

/* Sum of squared distances to the mean of colours [lo, hi). */
static double box_sse(const qcol_t *col, size_t lo, size_t hi)
{
	double w = 0, s[3] = { 0, 0, 0 }, q = 0;
	for (size_t i = lo; i < hi; i++) {
		w += col[i].w;
		for (int c = 0; c < 3; c++) {
			s[c] += col[i].w * col[i].c[c];
			q += col[i].w * col[i].c[c] * col[i].c[c];
		}
	}
	return w > 0 ? q - (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / w : 0;
}

/* Like median_cut, but the box split next is the one of the largest squared error, cut
 * across its axis of largest variance where the two halves' squared errors sum least. */
static size_t variance_cut(qcol_t *col, size_t n, size_t k, double (*means)[3])
{
	qbox_t box[QUANT_MAX];
	double sse[QUANT_MAX];
	if (n == 0 || k == 0)
		return 0;
	size_t nb = 1;
	box[0].lo = 0, box[0].hi = n, box[0].w = 0, box[0].sorted = -1;
	for (size_t i = 0; i < n; i++)
		box[0].w += col[i].w;
	sse[0] = box_sse(col, 0, n);
	while (nb < k) {
		size_t pick = nb;
		for (size_t b = 0; b < nb; b++)
			if (box[b].hi - box[b].lo > 1 && sse[b] > 0 && (pick == nb || sse[b] > sse[pick]))
				pick = b;
		if (pick == nb)
			break;
		qbox_t *bx = &box[pick];
		size_t lo = bx->lo, hi = bx->hi, m = lo + 1;
		double var[3];
		for (int c = 0; c < 3; c++) {
			double s = 0, q = 0;
			for (size_t i = lo; i < hi; i++)
				s += col[i].w * col[i].c[c], q += col[i].w * col[i].c[c] * col[i].c[c];
			var[c] = q - s * s / bx->w;
		}
		int axis = var[1] > var[0] ? 1 : 0;
		if (var[2] > var[axis])
			axis = 2;
		sort_box(col, bx, axis);
		/* the squared error along the axis only, for each cut (the other axes' share of the
		 * error changes less and is left out, as in Wu's and pngquant's cuts) */
		double W = 0, S = 0;
		for (size_t i = lo; i < hi; i++)
			W += col[i].w, S += col[i].w * col[i].c[axis];
		double wl = 0, sl = 0, best = -1;
		for (size_t i = lo; i + 1 < hi; i++) {
			wl += col[i].w, sl += col[i].w * col[i].c[axis];
			if (col[i + 1].c[axis] == col[i].c[axis])
				continue;
			double wr = W - wl, sr = S - sl;
			double gain = sl * sl / wl + sr * sr / wr;   /* maximal gain = least error */
			if (gain > best)
				best = gain, m = i + 1;
		}
		double wsum = 0;
		for (size_t i = lo; i < m; i++)
			wsum += col[i].w;
		box[nb].lo = m, box[nb].hi = hi, box[nb].w = bx->w - wsum, box[nb].sorted = axis;
		bx->hi = m, bx->w = wsum;
		sse[pick] = box_sse(col, lo, m);
		sse[nb] = box_sse(col, m, hi);
		nb++;
	}
	for (size_t b = 0; b < nb; b++) {
		double s[3] = { 0, 0, 0 };
		for (size_t i = box[b].lo; i < box[b].hi; i++)
			for (int c = 0; c < 3; c++)
				s[c] += col[i].c[c] * col[i].w;
		for (int c = 0; c < 3; c++)
			means[b][c] = s[c] / box[b].w;
	}
	return nb;
}

/* ---- octree (Gervautz and Purgathofer 1988) ----------------------------------------- */

#define ODEPTH 6                /* one level per bit of the 6-bit DAC value */

typedef struct {
	int child[8];
	int nchild;
	int leaf;
	int slot;                   /* position in its level's reducible list, -1 if none */
	double w, s[3];
} onode_t;

typedef struct {
	onode_t *node;
	size_t nnode, cap;
	int *red[ODEPTH];           /* internal nodes per level, reducible */
	size_t nred[ODEPTH], capred[ODEPTH];
	size_t leaves;
	int fail;
} otree_t;

static int onew(otree_t *t, int level)
{
	if (t->nnode == t->cap) {
		size_t c = t->cap ? t->cap * 2 : 1024;
		onode_t *p = realloc(t->node, c * sizeof *p);
		if (!p)
			return t->fail = -1;
		t->node = p, t->cap = c;
	}
	int id = (int)t->nnode++;
	onode_t *o = &t->node[id];
	memset(o, 0, sizeof *o);
	for (int k = 0; k < 8; k++)
		o->child[k] = -1;
	o->slot = -1;
	o->leaf = level == ODEPTH;
	if (o->leaf) {
		t->leaves++;
	} else {
		if (t->nred[level] == t->capred[level]) {
			size_t c = t->capred[level] ? t->capred[level] * 2 : 64;
			int *p = realloc(t->red[level], c * sizeof *p);
			if (!p)
				return t->fail = -1;
			t->red[level] = p, t->capred[level] = c;
		}
		o->slot = (int)t->nred[level];
		t->red[level][t->nred[level]++] = id;
	}
	return id;
}

static void oinsert(otree_t *t, const qcol_t *c)
{
	int r6 = (int)quant_dac6((unsigned)(c->c[0] + 0.5)), g6 = (int)quant_dac6((unsigned)(c->c[1] + 0.5));
	int b6 = (int)quant_dac6((unsigned)(c->c[2] + 0.5));
	int id = 0;
	for (int level = 0;; level++) {
		onode_t *o = &t->node[id];
		o->w += c->w;
		for (int k = 0; k < 3; k++)
			o->s[k] += c->c[k] * c->w;
		if (o->leaf)
			return;
		int sh = ODEPTH - 1 - level;
		int ci = ((r6 >> sh) & 1) << 2 | ((g6 >> sh) & 1) << 1 | ((b6 >> sh) & 1);
		if (t->node[id].child[ci] < 0) {
			int nid = onew(t, level + 1);
			if (nid < 0)
				return;
			t->node[id].child[ci] = nid;
			t->node[id].nchild++;
		}
		id = t->node[id].child[ci];
	}
}

/* Merge the children of the reducible node at the deepest level holding the fewest pixels. */
static void oreduce(otree_t *t)
{
	int level = ODEPTH - 1;
	while (level >= 0 && t->nred[level] == 0)
		level--;
	if (level < 0)
		return;
	size_t pick = 0;
	for (size_t k = 1; k < t->nred[level]; k++)
		if (t->node[t->red[level][k]].w < t->node[t->red[level][pick]].w)
			pick = k;
	int id = t->red[level][pick];
	int last = t->red[level][--t->nred[level]];
	t->red[level][pick] = last;
	t->node[last].slot = (int)pick;
	onode_t *o = &t->node[id];
	o->leaf = 1;
	o->slot = -1;
	t->leaves -= (size_t)o->nchild - 1;   /* its children are leaves: it is at the deepest level */
	for (int k = 0; k < 8; k++)
		o->child[k] = -1;
	o->nchild = 0;
}

static void ocollect(const otree_t *t, int id, double (*means)[3], size_t *n)
{
	const onode_t *o = &t->node[id];
	if (o->leaf) {
		if (o->w > 0) {
			for (int k = 0; k < 3; k++)
				means[*n][k] = o->s[k] / o->w;
			(*n)++;
		}
		return;
	}
	for (int k = 0; k < 8; k++)
		if (o->child[k] >= 0)
			ocollect(t, o->child[k], means, n);
}

static long octree(const qcol_t *col, size_t n, size_t k, double (*means)[3])
{
	otree_t t;
	memset(&t, 0, sizeof t);
	size_t nm = 0;
	if (n == 0 || k == 0)
		return 0;
	onew(&t, 0);
	for (size_t i = 0; i < n && !t.fail; i++) {
		oinsert(&t, &col[i]);
		while (t.leaves > k)
			oreduce(&t);
	}
	if (!t.fail)
		ocollect(&t, 0, means, &nm);
	free(t.node);
	for (int l = 0; l < ODEPTH; l++)
		free(t.red[l]);
	return t.fail ? -1 : (long)nm;
}

/* ---- k-means refinement ------------------------------------------------------------- */

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
static int kmeans(const qcol_t *col, size_t n, double (*means)[3], size_t fixed, size_t k, int passes,
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

/* ---- palettes ----------------------------------------------------------------------- */

static int by_weight_desc(const void *a, const void *b)
{
	const qcol_t *p = a, *q = b;
	if (p->w != q->w)
		return p->w > q->w ? -1 : 1;
	return by_red(a, b);
}

static int by_key(const void *a, const void *b)
{
	uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
	return x < y ? -1 : x > y;
}

int quant_build(const quant_hist_t *h, int method, unsigned ncolours, quant_palette_t *pal,
		char *err, size_t errlen)
{
	return quant_build_bits(h, method, ncolours, 6, pal, err, errlen);
}

/* 1 if the exact colour in slot s is flat: many pixels, and the only colour of its bin. */
static int exact_flat(const quant_hist_t *h, size_t s, unsigned long thr)
{
	uint32_t c = h->xkey[s];
	return h->xcount[s] >= thr && !(h->bin[quant_key(c >> 16 & 255, c >> 8 & 255, c & 255)].first & QMIXED);
}

/* 8 bits: 1 if every bin holds one exact colour and there are at most n: the palette is them. */
static int exact8(const quant_hist_t *h, unsigned n, quant_palette_t *pal)
{
	if (h->nused > n)
		return 0;
	for (size_t k = 0; k < h->nused; k++)
		if (h->bin[h->used[k]].first & QMIXED)
			return 0;
	uint32_t c[QUANT_MAX];
	for (size_t k = 0; k < h->nused; k++)
		c[k] = h->bin[h->used[k]].first;
	qsort(c, h->nused, sizeof *c, by_key);
	for (size_t k = 0; k < h->nused; k++) {
		pal->dac[k][0] = (uint8_t)(c[k] >> 16);
		pal->dac[k][1] = (uint8_t)(c[k] >> 8);
		pal->dac[k][2] = (uint8_t)c[k];
	}
	pal->n = (unsigned)h->nused;
	return 1;
}

int quant_build_bits(const quant_hist_t *h, int method, unsigned ncolours, unsigned bits,
		quant_palette_t *pal, char *err, size_t errlen)
{
	pal->n = 0;
	pal->bits = bits == 8 ? 8 : 6;
	if (ncolours < 1 || ncolours > QUANT_MAX) {
		snprintf(err, errlen, "palette size %u out of range 1..256", ncolours);
		return -1;
	}
	if (pal->bits == 8 && exact8(h, ncolours, pal))
		return 0;
	if (pal->bits == 6 && h->nused <= ncolours) {   /* every DAC colour gets its own entry: exact */
		uint32_t keys[QUANT_MAX];
		memcpy(keys, h->used, h->nused * sizeof *keys);
		qsort(keys, h->nused, sizeof *keys, by_key);
		for (size_t k = 0; k < h->nused; k++) {
			pal->dac[k][0] = (uint8_t)(keys[k] >> 12);
			pal->dac[k][1] = (uint8_t)(keys[k] >> 6 & 63);
			pal->dac[k][2] = (uint8_t)(keys[k] & 63);
		}
		pal->n = (unsigned)h->nused;
		return 0;
	}
	unsigned long thr = quant_flat_threshold(h);
	int exact = pal->bits == 8 && h->xstate == 1;   /* the exact colours, not the bins */
	size_t ncol = exact ? h->nx : h->nused;
	qcol_t *col = malloc(ncol * sizeof *col);
	double (*means)[3] = malloc(QUANT_MAX * sizeof *means);
	if (!col || !means) {
		free(col);
		free(means);
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	/* the flat colours first (most pixels first), then the rest */
	size_t nflat = 0, n = ncol;
	if (exact) {
		/* flat as with the bins: many pixels, and alone in its DAC bin */
		for (size_t s = 0; s < QXSLOTS; s++)
			nflat += h->xkey[s] && exact_flat(h, s, thr);
		size_t fi = 0, ri = nflat;
		for (size_t s = 0; s < QXSLOTS; s++) {
			if (!h->xkey[s])
				continue;
			qcol_t *c = &col[exact_flat(h, s, thr) ? fi++ : ri++];
			c->c[0] = h->xkey[s] >> 16 & 255, c->c[1] = h->xkey[s] >> 8 & 255, c->c[2] = h->xkey[s] & 255;
			c->w = h->xcount[s];
		}
	} else {
		for (size_t k = 0; k < h->nused; k++)
			nflat += quant_bin_flat(h, &h->bin[h->used[k]], thr);
		size_t fi = 0, ri = nflat;
		for (size_t k = 0; k < h->nused; k++) {
			const qbin_t *q = &h->bin[h->used[k]];
			qcol_t *c = &col[quant_bin_flat(h, q, thr) ? fi++ : ri++];
			for (int i = 0; i < 3; i++)
				c->c[i] = mean_of(q, i);
			c->w = q->count;
		}
	}
	qsort(col, nflat, sizeof *col, by_weight_desc);
	size_t keep = nflat < ncolours / 2 ? nflat : ncolours / 2;
	for (size_t k = 0; k < keep; k++)
		memcpy(means[k], col[k].c, sizeof means[k]);
	/* the flat colours beyond the half are quantised with the rest */
	qcol_t *rest = col + keep;
	size_t nrest = n - keep, kfree = ncolours - keep;
	long got;
	if (method == QUANT_OCTREE)
		got = octree(rest, nrest, kfree, means + keep);
	else if (method == QUANT_MEDIAN)
		got = (long)median_cut(rest, nrest, kfree, means + keep);
	else
		got = (long)variance_cut(rest, nrest, kfree, means + keep);
	int rc = got < 0 ? -1 : 0;
	if (rc == 0 && method == QUANT_BEST)
		rc = kmeans(rest, nrest, means, keep, keep + (size_t)got, 30, 0);
	if (rc == 0 && method == QUANT_BEST)
		rc = kmeans(rest, nrest, means, keep, keep + (size_t)got, 4, pal->bits);
	if (rc == 0)
		for (size_t k = 0; k < keep + (size_t)got; k++)
			put_entry(pal, means[k]);
	else
		snprintf(err, errlen, "out of memory");
	free(col);
	free(means);
	return rc;
}
