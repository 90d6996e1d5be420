/* quant_build.c: adaptive palettes from the histogram: median cut, octree, variance cut + k-means. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "quant/quant_int.h"

/* ---- colours to quantise ------------------------------------------------------------ */

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
		rc = quant_kmeans(rest, nrest, means, keep, keep + (size_t)got, 30, 0);
	if (rc == 0 && method == QUANT_BEST)
		rc = quant_kmeans(rest, nrest, means, keep, keep + (size_t)got, 4, pal->bits);
	if (rc == 0)
		for (size_t k = 0; k < keep + (size_t)got; k++)
			put_entry(pal, means[k]);
	else
		snprintf(err, errlen, "out of memory");
	free(col);
	free(means);
	return rc;
}
