/* quant_hist.c: the histogram of DAC colours, and whether a second thread would run beside this one. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>
#include "quant/quant_int.h"

/* ---- histogram ---------------------------------------------------------------------- */

#define QHUGE ((size_t)2 << 20)   /* a transparent huge page */

/* The zeroed bins (8 MiB): in 2 MiB pages where Linux offers them (madvise MADV_HUGEPAGE),
 * else calloc. A picture's colours fall all over the table: on workload a (9,777 bins) the
 * faults of its 2,048 pages of 4 KiB cost more than the counting itself. */
static qbin_t *bins_new(quant_hist_t *h)
{
	size_t len = QBINS * sizeof(qbin_t);
#ifdef MADV_HUGEPAGE
	void *base = mmap(NULL, len + QHUGE, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
	if (base != MAP_FAILED) {
		uintptr_t a = ((uintptr_t)base + QHUGE - 1) & ~(uintptr_t)(QHUGE - 1);
		madvise((void *)a, len, MADV_HUGEPAGE);   /* only advice: 4 KiB pages if refused */
		h->map_base = base, h->map_len = len + QHUGE;
		return (qbin_t *)a;
	}
#endif
	return calloc(QBINS, sizeof(qbin_t));
}

quant_hist_t *quant_hist_new(void)
{
	quant_hist_t *h = calloc(1, sizeof *h);
	if (!h)
		return NULL;
	h->bin = bins_new(h);
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
	if (h->map_base)
		munmap(h->map_base, h->map_len);
	else
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
	uint32_t k0[256], k1[256], k2[256];   /* quant_key by channel, looked up */
	for (unsigned v = 0; v < 256; v++)
		k0[v] = quant_dac6(v) << 12, k1[v] = quant_dac6(v) << 6, k2[v] = quant_dac6(v);
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
			uint32_t key = k0[p[0]] | k1[p[1]] | k2[p[2]];
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
