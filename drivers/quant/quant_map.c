/* quant_map.c: mapping pixels to a palette or 5-6-5, undithered, ordered or Floyd-Steinberg. */
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "quant/quant_int.h"

/* ---- mapping ------------------------------------------------------------------------ */

static const uint8_t bayer8[8][8] = {
	{ 0, 32, 8, 40, 2, 34, 10, 42 }, { 48, 16, 56, 24, 50, 18, 58, 26 },
	{ 12, 44, 4, 36, 14, 46, 6, 38 }, { 60, 28, 52, 20, 62, 30, 54, 22 },
	{ 3, 35, 11, 43, 1, 33, 9, 41 }, { 51, 19, 59, 27, 49, 17, 57, 25 },
	{ 15, 47, 7, 39, 13, 45, 5, 37 }, { 63, 31, 55, 23, 61, 29, 53, 21 },
};

/* Answers per DAC bin, each a function of the palette and the picture only, so the threads
 * mapping the parts of one picture share them: a part that finds an answer unknown works it
 * out and stores it; another part doing the same at the same moment stores the same value.
 * Relaxed atomics make those plain 16-bit loads and stores well defined. */
typedef struct {
	_Atomic int16_t cache[QBINS];   /* pick(): the entry nearest to the bin's colour, -1 = not yet */
	_Atomic int16_t exact[QBINS];   /* holds(), -2 = not yet known */
	_Atomic int16_t pure[QBINS];    /* nearest entry of a one-colour bin, -1 = not yet */
} qbins_t;

#define BIN_GET(a, k) atomic_load_explicit(&(a)[k], memory_order_relaxed)
#define BIN_PUT(a, k, v) atomic_store_explicit(&(a)[k], (int16_t)(v), memory_order_relaxed)

/* The target space of a mapping: a palette (through a cache per DAC colour) or 5-6-5. */
typedef struct {
	const quant_palette_t *pal;
	qnear_t near;
	qbins_t *bc;                /* the per-bin answers, shared by the parts of a mapping */
	int own_bc;                 /* 1: this part made bc (and frees it) */
	const uint8_t *mixed;       /* QBINS bits: the bin holds more than one 24-bit colour (a
	                             * copy of the histogram's flags small enough for the caches) */
	const uint8_t *undith;      /* QBINS bits: a one-colour bin whose pixels are drawn ... */
	const uint8_t *runent;      /* ... undithered, with the entry runent[bin] (NULL: not known) */
	void (*done)(void *, unsigned);   /* told each row that is final (quant_map_rows), or NULL */
	void *done_ctx;
	uint32_t cellstart[4096];   /* per grid cell: its candidates in pool (count 0: not built) */
	int32_t cnear[3][16][QUANT_MAX];   /* per channel and grid level: each entry's squared ... */
	int32_t cfar[3][16][QUANT_MAX];    /* ... distance to the nearest and farthest value of it */
	uint16_t cellcount[4096];
	qpool_t pool;
	int show[QUANT_MAX][3];     /* 8-bit colour each entry shows */
} qmap_t;

static int clamp8(int v) { return v < 0 ? 0 : v > 255 ? 255 : v; }

static unsigned nearest_cached(qmap_t *m, const int *t);

/* Index chosen for an 8-bit colour; its shown colour in out. */
static unsigned pick(qmap_t *m, int r, int g, int b, int *out)
{
	r = clamp8(r), g = clamp8(g), b = clamp8(b);
	if (!m->pal) {               /* 5-6-5 */
		unsigned r5 = ((unsigned)r * 31 + 127) / 255, g6 = ((unsigned)g * 63 + 127) / 255;
		unsigned b5 = ((unsigned)b * 31 + 127) / 255;
		out[0] = (int)(r5 << 3 | r5 >> 2), out[1] = (int)(g6 << 2 | g6 >> 4), out[2] = (int)(b5 << 3 | b5 >> 2);
		return r5 << 11 | g6 << 5 | b5;
	}
	uint32_t key = quant_key((unsigned)r, (unsigned)g, (unsigned)b);
	int e = BIN_GET(m->bc->cache, key);
	if (e < 0) {
		/* the DAC colour of this bin stands for every 8-bit colour in it */
		int c[3] = { (int)quant_dac8(key >> 12), (int)quant_dac8(key >> 6 & 63), (int)quant_dac8(key & 63) };
		e = (int)nearest_cached(m, c);
		BIN_PUT(m->bc->cache, key, e);
	}
	memcpy(out, m->show[e], sizeof m->show[0]);
	return (unsigned)e;
}

/* The entry showing the colour of bin key exactly (6 bits: its DAC colour; 8 bits: its one
 * 24-bit colour), or -1; remembered per bin. */
static int holds(qmap_t *m, const quant_hist_t *h, uint32_t key)
{
	int e = BIN_GET(m->bc->exact, key);
	if (e != -2)
		return e;
	const qbin_t *q = &h->bin[key];
	int shown[3];
	if (m->pal->bits == 8) {
		uint32_t c = q->first;
		e = -1;
		if (!(c & QMIXED)) {
			e = (int)quant_near_find(&m->near, (int)(c >> 16) * 4, (int)(c >> 8 & 255) * 4, (int)(c & 255) * 4);
			const uint8_t *d = m->pal->dac[e];
			if ((uint32_t)(d[0] << 16 | d[1] << 8 | d[2]) != c)
				e = -1;
		}
	} else {
		e = (int)pick(m, (int)quant_dac8(key >> 12), (int)quant_dac8(key >> 6 & 63), (int)quant_dac8(key & 63), shown);
		const uint8_t *d = m->pal->dac[e];
		if ((uint32_t)(d[0] << 12 | d[1] << 6 | d[2]) != key)
			e = -1;
	}
	BIN_PUT(m->bc->exact, key, e);
	return e;
}

/* Heckbert's locally sorted search: the candidates of a grid cell (16 levels a side) are the
 * entries that can be nearest to some colour in it (no farther from the cell than the least
 * farthest-corner distance of any entry), sorted by their distance to the cell; a query stops
 * at the first candidate no nearer to the cell than the best so far. Built per cell on first
 * use. Same answers as quant_near_find (ties to the lowest index). */
static int cell_candidates(qmap_t *m, unsigned cell)
{
	unsigned n = m->pal->n, l0 = cell >> 8, l1 = cell >> 4 & 15, l2 = cell & 15;
	/* the distances per channel come from the tables of qmap_new: sums only, a loop the
	 * compiler vectorises (every cell of a dithered picture is built: 4,096 x 256 entries) */
	const int32_t *n0 = m->cnear[0][l0], *n1 = m->cnear[1][l1], *n2 = m->cnear[2][l2];
	const int32_t *f0 = m->cfar[0][l0], *f1 = m->cfar[1][l1], *f2 = m->cfar[2][l2];
	int32_t dmin[QUANT_MAX], least = INT32_MAX;
	for (unsigned e = 0; e < n; e++) {
		int32_t b = f0[e] + f1[e] + f2[e];
		dmin[e] = n0[e] + n1[e] + n2[e];
		least = b < least ? b : least;
	}
	size_t start;
	long k = quant_pool_add(&m->pool, dmin, n, least, &start);
	if (k < 0)
		return -1;
	m->cellstart[cell] = (uint32_t)start;
	m->cellcount[cell] = (uint16_t)k;
	return 0;
}

/* The entry nearest to an 8-bit colour (exact, through the cell candidates). */
static inline unsigned nearest_cached(qmap_t *m, const int *t)
{
	unsigned cell = (unsigned)(t[0] >> 4) << 8 | (unsigned)(t[1] >> 4) << 4 | (unsigned)(t[2] >> 4);
	if (m->cellcount[cell] == 0 && cell_candidates(m, cell) < 0)
		return quant_near_find(&m->near, t[0] * 4, t[1] * 4, t[2] * 4);
	const uint8_t *cand = m->pool.e + m->cellstart[cell];
	const int32_t *cd = m->pool.d + m->cellstart[cell];
	unsigned n = m->cellcount[cell], bi = cand[0];
	const int *s = m->show[bi];
	int32_t dr = (s[0] - t[0]) * 4, dg = (s[1] - t[1]) * 4, db = (s[2] - t[2]) * 4;
	int32_t best = dr * dr + dg * dg + db * db;   /* the first candidate, then the others */
	if (n > 1) {                 /* the second one always (no branch to mispredict: a farther
	                              * candidate only loses), the rest while they can be nearer */
		unsigned c1 = cand[1];
		s = m->show[c1];
		dr = (s[0] - t[0]) * 4, dg = (s[1] - t[1]) * 4, db = (s[2] - t[2]) * 4;
		int32_t d = dr * dr + dg * dg + db * db;
		int take = d < best || (d == best && c1 < bi);
		best = take ? d : best;
		bi = take ? c1 : bi;
	}
	for (unsigned k = 2; k < n && cd[k] <= best; k++) {
		s = m->show[cand[k]];
		dr = (s[0] - t[0]) * 4, dg = (s[1] - t[1]) * 4, db = (s[2] - t[2]) * 4;
		int32_t d = dr * dr + dg * dg + db * db;
		if (d < best || (d == best && cand[k] < bi))
			best = d, bi = cand[k];
	}
	return bi;
}

/* Index of a flat colour: the entry holding its colour exactly, or -1. */
static int flat_entry(qmap_t *m, const quant_hist_t *h, unsigned long thr, const uint8_t *p)
{
	if (!h)
		return -1;
	uint32_t key = quant_key(p[0], p[1], p[2]);
	if (m->pal && !(m->mixed[key >> 3] >> (key & 7) & 1))
		return holds(m, h, key);     /* one exact colour that the palette holds: as is */
	if (m->pal && m->pal->bits == 8) {   /* 8-bit entries: the pixel's own colour, if held */
		int t[3] = { p[0], p[1], p[2] };
		unsigned e = nearest_cached(m, t);
		return m->show[e][0] == p[0] && m->show[e][1] == p[1] && m->show[e][2] == p[2] ? (int)e : -1;
	}
	if (!quant_bin_flat(h, &h->bin[key], thr))
		return -1;
	if (!m->pal) {
		int shown[3];
		return (int)pick(m, p[0], p[1], p[2], shown);
	}
	return holds(m, h, key);
}

/* The differences (sum over channels) between rows a and b, pixel by pixel. */
static void row_diff(const uint8_t *a, const uint8_t *b, unsigned w, uint16_t *d)
{
	for (unsigned x = 0; x < w; x++)
		d[x] = (uint16_t)(abs(a[3 * x] - b[3 * x]) + abs(a[3 * x + 1] - b[3 * x + 1]) + abs(a[3 * x + 2] - b[3 * x + 2]));
}

/* The contrast of each pixel of row y: the largest difference (sum over channels) between it
 * and its four neighbours (a neighbour outside the picture being the pixel itself), into ct.
 * up holds on entry the differences of row y to row y - 1 (zeros on the first row); on return
 * it holds those to row y + 1, for the next row. dn is scratch of w values. */
static void row_contrast(const uint8_t *rgb, size_t stride, unsigned w, unsigned h, unsigned y,
		uint16_t *up, uint16_t *dn, uint16_t *ct)
{
	const uint8_t *row = rgb + y * stride;
	if (y + 1 < h)
		row_diff(row, row + stride, w, dn);
	else
		memset(dn, 0, w * sizeof *dn);
	int left = 0;                /* the difference to the pixel on the left */
	for (unsigned x = 0; x < w; x++) {
		const uint8_t *p = row + 3 * x;
		int right = x + 1 < w ? abs(p[3] - p[0]) + abs(p[4] - p[1]) + abs(p[5] - p[2]) : 0;
		int best = up[x] > dn[x] ? up[x] : dn[x];
		best = left > best ? left : best;
		best = right > best ? right : best;
		ct[x] = (uint16_t)best;
		left = right;
	}
	memcpy(up, dn, w * sizeof *up);
}

/* The entry within the DAC's rounding of an 8-bit colour (squared distance at most near), or -1. */
static int near_entry(qmap_t *m, const uint8_t *p, int near)
{
	if (near <= 0)
		return -1;
	int sh[3], t[3] = { p[0], p[1], p[2] };
	unsigned e;
	if (m->pal->bits == 8) {
		e = nearest_cached(m, t);
		memcpy(sh, m->show[e], sizeof sh);
	} else {
		e = pick(m, p[0], p[1], p[2], sh);
	}
	int dr = sh[0] - p[0], dg = sh[1] - p[1], db = sh[2] - p[2];
	return dr * dr + dg * dg + db * db <= near ? (int)e : -1;
}

/* Undithered: the entry nearest to the pixel's own colour; searched once per bin when one
 * colour fills the bin (vector content), per pixel otherwise. */
static unsigned nearest_of_pixel(qmap_t *m, const uint8_t *p)
{
	uint32_t key = quant_key(p[0], p[1], p[2]);
	int t[3] = { p[0], p[1], p[2] };
	if (m->mixed[key >> 3] >> (key & 7) & 1)
		return nearest_cached(m, t);
	int e = BIN_GET(m->bc->pure, key);
	if (e < 0)
		e = (int)nearest_cached(m, t), BIN_PUT(m->bc->pure, key, e);
	return (unsigned)e;
}

/* The entry a pixel of colour p gets without dithering: its flat or held entry, else (near >
 * 0) the entry within the DAC's rounding of it; -1 when it is to be dithered. A function of
 * the colour only. */
static int run_entry(qmap_t *m, const quant_hist_t *h, unsigned long thr, const uint8_t *p, int near)
{
	int e = flat_entry(m, h, thr, p);
	return e >= 0 ? e : near_entry(m, p, near);
}

/* A pixel with an entry within the 6-bit DAC's rounding (2 levels a channel: 3 * 2^2) is drawn
 * with it by Floyd-Steinberg, undithered, taking no error and giving none: a difference the
 * DAC could not even show is not worth the noise of dithering (the plate: 44.29 dB, at the
 * 6-bit ceiling, instead of 41.5; 59.9 instead of 59.2 with 8-bit entries) */
#define QFS_NEAR 12

/* Rows [y0, y1) of the picture; the error diffusion state is one row of (w + 2) pixels x 3
 * channels, in 1/256 steps, starting at zero on row y0. */
static int map_image(qmap_t *m, const quant_hist_t *h, const uint8_t *rgb, unsigned w,
		unsigned hgt, size_t stride, int dither, uint8_t *out8, uint16_t *out16, unsigned y0, unsigned y1)
{
	unsigned long thr = h ? quant_flat_threshold(h) : 0;
	/* Floyd-Steinberg passes on 14/16 of the error, at most 16 levels a channel reach a
	 * pixel, and less where the picture has detail, down to a quarter at a step of 12 levels
	 * (summed over the channels) to a neighbour: edges and texture hide banding themselves,
	 * so dithering there only adds noise. Measured on the benchmark pictures: +4.7 dB PSNR
	 * against plain FS on the photograph; smooth gradients still dither fully. */
	const int fs_damp = 14, fs_clamp = 16, fs_edge = 12;
	int *err0 = NULL, *err1 = NULL;
	uint16_t *cup = NULL, *cdn = NULL, *ct = NULL;
	uint8_t damp[16];            /* the share of the error passed on, by contrast: fs_edge is
	                              * below 16, so every contrast from 15 on is damped as 15 */
	int spread = 0;
	if (dither == QUANT_DITHER_FS) {
		err0 = calloc((size_t)(w + 2) * 3, sizeof *err0);
		err1 = calloc((size_t)(w + 2) * 3, sizeof *err1);
		cup = calloc((size_t)w * 3, sizeof *cup);
		if (!err0 || !err1 || !cup) {
			free(err0);
			free(err1);
			free(cup);
			return -1;
		}
		cdn = cup + w, ct = cdn + w;
		if (y0 > 0 && y0 < hgt)
			row_diff(rgb + y0 * stride, rgb + (y0 - 1) * stride, w, cup);
		for (int c = 0; c < 16; c++)
			damp[c] = (uint8_t)(c >= fs_edge ? fs_damp / 4 : fs_damp - (fs_damp * 3 / 4) * c / fs_edge);
	} else if (dither == QUANT_DITHER_ORDERED) {
		/* the threshold spread: the median distance from an entry to its nearest other */
		if (!m->pal) {
			spread = 8;
		} else {
			int d[QUANT_MAX];
			unsigned n = m->pal->n;
			for (unsigned i = 0; i < n; i++) {
				long best = 255L * 255 * 3;
				for (unsigned j = 0; j < n; j++) {
					if (j == i)
						continue;
					long s = 0;
					for (int c = 0; c < 3; c++)
						s += (long)(m->show[i][c] - m->show[j][c]) * (m->show[i][c] - m->show[j][c]);
					if (s > 0 && s < best)
						best = s;
				}
				d[i] = (int)sqrt((double)best);
			}
			for (unsigned i = 1; i < n; i++)   /* insertion sort, n <= 256 */
				for (unsigned j = i; j > 0 && d[j - 1] > d[j]; j--) {
					int t = d[j]; d[j] = d[j - 1]; d[j - 1] = t;
				}
			spread = n > 1 ? d[n / 2] : 0;
		}
	}
	uint32_t last_c24 = ~0u;
	int last_fe = -1;
	uint8_t dac6[256];           /* quant_dac6, looked up */
	for (unsigned v = 0; v < 256; v++)
		dac6[v] = (uint8_t)quant_dac6(v);
	for (unsigned y = y0; y < y1; y++) {
		const uint8_t *row = rgb + y * stride;
		int rtl = dither == QUANT_DITHER_FS && (y & 1);   /* serpentine */
		if (err1) {
			memset(err1, 0, (size_t)(w + 2) * 3 * sizeof *err1);
			row_contrast(rgb, stride, w, hgt, y, cup, cdn, ct);
		}
		int carry[3] = { 0, 0, 0 };  /* 7/16 of the last pixel's error, for this one (kept here,
		                              * not in err0: no store and reload on the way) */
		for (unsigned i = 0; i < w; i++) {
			unsigned x = rtl ? w - 1 - i : i;
			const uint8_t *p = row + 3 * x;
			int shown[3];
			unsigned v;
			uint32_t c24 = (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
			uint32_t key = (uint32_t)dac6[p[0]] << 12 | (uint32_t)dac6[p[1]] << 6 | dac6[p[2]];
			int fe;
			if (m->undith && !(m->mixed[key >> 3] >> (key & 7) & 1)) {
				/* the bin's one colour, asked before the mapping (map_split) */
				fe = m->undith[key >> 3] >> (key & 7) & 1 ? m->runent[key] : -1;
			} else {
				if (c24 != last_c24)     /* runs of one colour: ask once */
					last_fe = run_entry(m, h, thr, p, err0 && m->pal ? QFS_NEAR : 0), last_c24 = c24;
				fe = last_fe;
			}
			if (fe >= 0) {
				v = (unsigned)fe;    /* flat: no error taken, none given */
				carry[0] = carry[1] = carry[2] = 0;
			} else if (err0) {
				int t[3], e[3];
				const int *ec = err0 + 3 * (x + 1);
				for (int c = 0; c < 3; c++) {
					int a = ec[c] + carry[c];
					int in = (a + (a >= 0 ? 128 : -128)) / 256;
					in = in > fs_clamp ? fs_clamp : in < -fs_clamp ? -fs_clamp : in;
					t[c] = clamp8(p[c] + in);
				}
				if (m->pal) {
					v = nearest_cached(m, t);
					memcpy(shown, m->show[v], sizeof shown);
				} else {
					v = pick(m, t[0], t[1], t[2], shown);
				}
				int dmp = damp[ct[x] < 15 ? ct[x] : 15];
				for (int c = 0; c < 3; c++)
					e[c] = (t[c] - shown[c]) * dmp;
				int fwd = rtl ? -3 : 3;
				for (int c = 0; c < 3; c++) {
					carry[c] = e[c] * 7;
					int *nx = err1 + 3 * (x + 1) + c;
					nx[-fwd] += e[c] * 3;
					nx[0] += e[c] * 5;
					nx[fwd] += e[c];
				}
			} else if (spread) {
				int off = ((2 * bayer8[y & 7][x & 7] + 1) * spread) / 128 - spread / 2;
				v = pick(m, p[0] + off, p[1] + off, p[2] + off, shown);
			} else if (h && m->pal) {
				v = nearest_of_pixel(m, p);
			} else {
				v = pick(m, p[0], p[1], p[2], shown);
			}
			if (out8)
				out8[(size_t)y * w + x] = (uint8_t)v;
			else
				out16[(size_t)y * w + x] = (uint16_t)v;
		}
		int *t = err0; err0 = err1; err1 = t;
		if (m->done)
			m->done(m->done_ctx, y);
	}
	free(err0);
	free(err1);
	free(cup);
	return 0;
}

/* 1 if every colour of the picture is an entry of the palette. */
static int exact_palette(qmap_t *m, const quant_hist_t *h)
{
	if (h->nused > m->pal->n)
		return 0;
	for (size_t k = 0; k < h->nused; k++)
		if (holds(m, h, h->used[k]) < 0)
			return 0;
	return 1;
}

/* A mapping for one part of the picture: the per-bin answers of another part (shared), or
 * new ones when shared is NULL; the cell candidates are its own. */
static qmap_t *qmap_new(const quant_palette_t *pal, qbins_t *shared)
{
	qmap_t *m = calloc(1, sizeof *m);
	if (!m || !pal)
		return m;
	m->bc = shared;
	if (!m->bc) {
		m->bc = malloc(sizeof *m->bc);
		if (!m->bc) {
			free(m);
			return NULL;
		}
		m->own_bc = 1;
		for (size_t k = 0; k < QBINS; k++) {
			atomic_init(&m->bc->cache[k], -1);
			atomic_init(&m->bc->exact[k], -2);
			atomic_init(&m->bc->pure[k], -1);
		}
	}
	m->pal = pal;
	quant_near_palette(&m->near, pal);
	for (unsigned k = 0; k < pal->n; k++)
		for (int c = 0; c < 3; c++)
			m->show[k][c] = (int)quant_show(pal, pal->dac[k][c]);
	/* a grid level L of a channel spans [64 L, 64 L + 63] in search units */
	for (int c = 0; c < 3; c++)
		for (int L = 0; L < 16; L++)
			for (unsigned k = 0; k < pal->n; k++) {
				int32_t v = m->show[k][c] * 4, lo = L * 64, hi = lo + 63;
				int32_t in = v < lo ? lo - v : v > hi ? v - hi : 0, out = v - lo > hi - v ? v - lo : hi - v;
				m->cnear[c][L][k] = in * in;
				m->cfar[c][L][k] = out * out;
			}
	return m;
}

static void qmap_free(qmap_t *m)
{
	if (!m)
		return;
	if (m->own_bc)
		free(m->bc);
	quant_pool_free(&m->pool);
	free(m);
}

/* One part of a mapping: rows [y0, y1). */
typedef struct {
	qmap_t *m;
	const quant_hist_t *h;
	const uint8_t *rgb;
	unsigned w, hgt, y0, y1;
	size_t stride;
	int dither, rc;
	uint8_t *out8;
	uint16_t *out16;
} qpart_t;

static void *map_part(void *arg)
{
	qpart_t *p = arg;
	p->rc = map_image(p->m, p->h, p->rgb, p->w, p->hgt, p->stride, p->dither, p->out8, p->out16, p->y0, p->y1);
	return NULL;
}

/* Pictures of at least this many pixels are mapped as two halves (top and bottom rows), the
 * bottom one on a second thread when a core is spare (quant_spare_core): each half is diffused
 * on its own, from zero error at its first row. The split depends only on the picture's size,
 * never on the machine, so the output is the same everywhere (the halves are mapped one after
 * the other, with one set of caches, when no core is spare or the thread cannot start). */
#define QSPLIT_PIXELS (1u << 18)

static int map_split(const quant_palette_t *pal, const quant_hist_t *h, const uint8_t *rgb,
		unsigned w, unsigned hgt, size_t stride, int dither, uint8_t *out8, uint16_t *out16,
		void (*done)(void *, unsigned), void *ctx)
{
	qpart_t part[2];
	unsigned nparts = (size_t)w * hgt >= QSPLIT_PIXELS && hgt >= 2 ? 2 : 1;
	int rc = 0;
	uint8_t *mixed = h ? calloc(QBINS / 8, 1) : NULL;
	if (h && !mixed)
		rc = -1;
	for (size_t k = 0; mixed && k < h->nused; k++)
		if (h->bin[h->used[k]].first & QMIXED)
			mixed[h->used[k] >> 3] |= (uint8_t)(1u << (h->used[k] & 7));
	for (unsigned k = 0; k < nparts; k++) {
		part[k] = (qpart_t){ qmap_new(pal, k && part[0].m ? part[0].m->bc : NULL), h, rgb, w, hgt,
			hgt * k / nparts, hgt * (k + 1) / nparts, stride, dither, -1, out8, out16 };
		if (!part[k].m)
			rc = -1;
		else
			part[k].m->mixed = mixed, part[k].m->done = done, part[k].m->done_ctx = ctx;
	}
	if (rc == 0 && pal && h && dither != QUANT_DITHER_NONE && exact_palette(part[0].m, h))
		for (unsigned k = 0; k < nparts; k++)   /* every colour of the picture is in the palette */
			part[k].dither = QUANT_DITHER_NONE;
	/* the pixels of each one-colour bin (most of vector content's) before dithering: asked
	 * once here, a bit and a byte per bin for the parts (a 32 KiB bitmap the caches keep) */
	uint8_t *undith = NULL, *runent = NULL;
	if (rc == 0 && pal && h) {
		undith = calloc(QBINS / 8, 1);
		runent = malloc(QBINS);
		if (!undith || !runent)
			rc = -1;
		unsigned long thr = quant_flat_threshold(h);
		int near = part[0].dither == QUANT_DITHER_FS ? QFS_NEAR : 0;
		for (size_t k = 0; rc == 0 && k < h->nused; k++) {
			uint32_t key = h->used[k], c = h->bin[key].first;
			if (c & QMIXED)
				continue;
			uint8_t p[3] = { (uint8_t)(c >> 16), (uint8_t)(c >> 8), (uint8_t)c };
			int e = run_entry(part[0].m, h, thr, p, near);
			if (e >= 0)
				undith[key >> 3] |= (uint8_t)(1u << (key & 7)), runent[key] = (uint8_t)e;
		}
		for (unsigned k = 0; rc == 0 && k < nparts; k++)
			part[k].m->undith = undith, part[k].m->runent = runent;
	}
	if (rc == 0) {
		pthread_t th;
		int threaded = nparts == 2 && quant_spare_core() && pthread_create(&th, NULL, map_part, &part[1]) == 0;
		map_part(&part[0]);
		if (threaded) {
			pthread_join(th, NULL);
		} else if (nparts == 2) {   /* one after the other: the first part's caches serve */
			qmap_free(part[1].m);
			part[1].m = part[0].m;
			map_part(&part[1]);
			part[1].m = NULL;
		}
		for (unsigned k = 0; k < nparts; k++)
			if (part[k].rc)
				rc = -1;
	}
	for (unsigned k = nparts; k-- > 0;)   /* part 0 owns the shared answers: freed last */
		qmap_free(part[k].m);
	free(mixed);
	free(undith);
	free(runent);
	return rc;
}

int quant_map(const quant_palette_t *pal, const quant_hist_t *h, const uint8_t *rgb,
		unsigned w, unsigned hgt, size_t stride, int dither, uint8_t *out)
{
	return quant_map_rows(pal, h, rgb, w, hgt, stride, dither, out, NULL, NULL);
}

int quant_map_rows(const quant_palette_t *pal, const quant_hist_t *h, const uint8_t *rgb,
		unsigned w, unsigned hgt, size_t stride, int dither, uint8_t *out,
		void (*done)(void *ctx, unsigned y), void *ctx)
{
	if (pal->n == 0)
		return -1;
	return map_split(pal, h, rgb, w, hgt, stride, dither, out, NULL, done, ctx);
}

int quant_map565(const quant_hist_t *h, const uint8_t *rgb, unsigned w, unsigned hgt,
		size_t stride, int dither, uint16_t *out)
{
	return map_split(NULL, h, rgb, w, hgt, stride, dither, NULL, out, NULL, NULL);
}

double quant_psnr(const quant_palette_t *pal, const uint8_t *rgb, unsigned w, unsigned hgt,
		size_t stride, const uint8_t *idx)
{
	double se = 0;
	for (unsigned y = 0; y < hgt; y++)
		for (unsigned x = 0; x < w; x++) {
			const uint8_t *p = rgb + y * stride + 3 * x, *d = pal->dac[idx[(size_t)y * w + x]];
			for (int c = 0; c < 3; c++) {
				double e = (double)p[c] - quant_show(pal, d[c]);
				se += e * e;
			}
		}
	if (se == 0)
		return 99;
	return 10 * log10(255.0 * 255.0 * 3.0 * w * hgt / se);
}
