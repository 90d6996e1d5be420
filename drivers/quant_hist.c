/* quant_hist.c: the histogram of DAC colours and the nearest palette entry search. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "quant_int.h"

/* ---- histogram ---------------------------------------------------------------------- */

quant_hist_t *quant_hist_new(void)
{
	quant_hist_t *h = calloc(1, sizeof *h);
	if (!h)
		return NULL;
	h->bin = calloc(QBINS, sizeof *h->bin);
	h->used = malloc(QBINS * sizeof *h->used);
	if (!h->bin || !h->used) {
		quant_hist_free(h);
		return NULL;
	}
	return h;
}

void quant_hist_free(quant_hist_t *h)
{
	if (!h)
		return;
	free(h->bin);
	free(h->used);
	free(h->xkey);
	free(h->xcount);
	free(h);
}

int quant_hist_exact(quant_hist_t *h, const uint8_t *rgb, unsigned w, unsigned hgt, size_t stride)
{
	if (h->xstate < 0)
		return 0;
	if (!h->xkey) {
		h->xkey = calloc(QXSLOTS, sizeof *h->xkey);
		h->xcount = calloc(QXSLOTS, sizeof *h->xcount);
		if (!h->xkey || !h->xcount)
			return -1;
	}
	if (h->xstate == 0) {
		memset(h->xkey, 0, QXSLOTS * sizeof *h->xkey);
		h->nx = 0;
		h->xstate = 1;
	}
	for (unsigned y = 0; y < hgt; y++) {
		const uint8_t *p = rgb + y * stride;
		for (unsigned x = 0; x < w; x++, p += 3) {
			uint32_t c = (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2], k = QMIXED | c;
			uint32_t s = (c * 2654435761u) >> 15;   /* 17 bits */
			while (h->xkey[s] && h->xkey[s] != k)
				s = (s + 1) & (QXSLOTS - 1);
			if (!h->xkey[s]) {
				if (h->nx == QXMAX) {
					h->xstate = -1;
					return 0;
				}
				h->xkey[s] = k;
				h->xcount[s] = 0;
				h->nx++;
			}
			h->xcount[s]++;
		}
	}
	return 0;
}

void quant_hist_clear(quant_hist_t *h)
{
	for (size_t k = 0; k < h->nused; k++)
		memset(&h->bin[h->used[k]], 0, sizeof h->bin[0]);
	h->nused = 0;
	h->npix = 0;
	h->xstate = 0;
}

void quant_hist_add(quant_hist_t *h, const uint8_t *rgb, unsigned w, unsigned hgt, size_t stride)
{
	uint32_t last = ~0u;
	qbin_t *q = NULL;
	for (unsigned y = 0; y < hgt; y++) {
		const uint8_t *p = rgb + y * stride;
		for (unsigned x = 0; x < w; x++, p += 3) {
			uint32_t c24 = (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
			if (c24 == last) {   /* a run of one colour: same bin, nothing new */
				q->count++;
				q->sum[0] += p[0], q->sum[1] += p[1], q->sum[2] += p[2];
				continue;
			}
			last = c24;
			uint32_t key = quant_key(p[0], p[1], p[2]);
			q = &h->bin[key];
			if (q->count++ == 0) {
				h->used[h->nused++] = key;
				q->first = c24;
			} else if ((q->first & ~QMIXED) != c24) {
				q->first |= QMIXED;
			}
			q->sum[0] += p[0];
			q->sum[1] += p[1];
			q->sum[2] += p[2];
		}
	}
	h->npix += (unsigned long)w * hgt;
}

size_t quant_hist_colours(const quant_hist_t *h)
{
	return h->nused;
}

unsigned long quant_flat_threshold(const quant_hist_t *h)
{
	unsigned long t = h->npix / 2048;
	return t < 32 ? 32 : t;
}

/* The threads runnable at this moment, the caller included (Linux: the fourth field of
 * /proc/loadavg, "runnable/existing"), or -1 when that is not known. */
static long runnable_now(void)
{
	FILE *f = fopen("/proc/loadavg", "r");
	long run = -1;
	if (f) {
		if (fscanf(f, "%*f %*f %*f %ld/", &run) != 1)
			run = -1;
		fclose(f);
	}
	return run;
}

int quant_spare_core(void)
{
	long n = sysconf(_SC_NPROCESSORS_ONLN), run = n >= 2 ? runnable_now() : -1;
	double load;
	if (n < 2 || getloadavg(&load, 1) != 1)
		return 0;
	/* a core idle now (the 1-minute average lags: a benchmark's own runs before this one
	 * keep it near the number of cores while the cores are free), on a machine not busy for
	 * long; without the count of runnable threads, the average alone */
	if (run >= 1)
		return run < n && load < (double)n + 0.5;
	return load < (double)n - 0.5;
}

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

