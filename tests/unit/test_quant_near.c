/* test_quant_near.c: the quantiser's exact searches and its two-thread split: the nearest and
 * second-nearest search (sorted sums and cells), undithered mapping of a big picture (two
 * halves, the whole-bin look-up) against a brute-force search, Floyd-Steinberg leaving colours
 * within the DAC's rounding of an entry undithered, and the rows a mapping reports. */
#include <stdlib.h>
#include "quant/quant.h"
#include "quant/quant_int.h"
#include "unit.h"

static uint32_t rng = 987654321u;
static unsigned rnd(void)
{
	rng = rng * 1103515245u + 12345u;
	return rng >> 8;
}

/* The nearest shown entry to an 8-bit colour by looking at every entry, ties to the lowest. */
static unsigned brute(const quant_palette_t *pal, const uint8_t *p)
{
	long best = -1;
	unsigned bi = 0;
	for (unsigned k = 0; k < pal->n; k++) {
		long d = 0;
		for (int c = 0; c < 3; c++) {
			long e = (long)quant_show(pal, pal->dac[k][c]) - p[c];
			d += e * e;
		}
		if (best < 0 || d < best)
			best = d, bi = k;
	}
	return bi;
}

/* Brute force: nearest (ties to the lowest index), its squared distance and the runner-up's. */
static unsigned brute2(const int (*col)[3], unsigned n, const int *x, long *d1, long *d2)
{
	long b1 = -1, b2 = -1;
	unsigned bi = 0;
	for (unsigned k = 0; k < n; k++) {
		long d = 0;
		for (int c = 0; c < 3; c++)
			d += (long)(col[k][c] - x[c]) * (col[k][c] - x[c]);
		if (b1 < 0 || d < b1)
			b2 = b1, b1 = d, bi = k;
		else if (b2 < 0 || d < b2)
			b2 = d;
	}
	*d1 = b1, *d2 = b2;
	return bi;
}

/* quant_near_find2: the nearest entry and the distances to it and to the runner-up. */
static void test_find2(void)
{
	int col[QUANT_MAX][3];
	unsigned n = 200;
	for (unsigned k = 0; k < n; k++)
		for (int c = 0; c < 3; c++)
			col[k][c] = (int)(rnd() % 1021);
	qnear_t *q = malloc(sizeof *q);
	quant_near_init(q, (const int (*)[3])col, n);
	int bad = 0;
	for (int t = 0; t < 20000; t++) {
		int x[3] = { (int)(rnd() % 1021), (int)(rnd() % 1021), (int)(rnd() % 1021) };
		long d1 = -1, d2 = -1, b1, b2;
		unsigned bi = brute2((const int (*)[3])col, n, x, &b1, &b2);
		unsigned got = quant_near_find2(q, x[0], x[1], x[2], &d1, &d2);
		bad += got != bi || d1 != b1 || d2 != b2 || got != quant_near_find(q, x[0], x[1], x[2]);
	}
	CHECK(bad == 0, "quant_near_find2: nearest and runner-up as a brute-force search (%d of 20000 differ)", bad);
	long d1, d2;
	quant_near_init(q, (const int (*)[3])col, 1);
	quant_near_find2(q, 0, 0, 0, &d1, &d2);
	CHECK(d2 == -1 && d1 >= 0, "quant_near_find2: one entry has no runner-up");
	free(q);
}

/* quant_cells_find2 (k-means' search through cells) gives exactly what a brute-force search
 * gives: on random entries, on entries of a coarse lattice with twins (ties everywhere), at the
 * entries' own places, after a reset to other entries, and with one entry. */
static void test_cells(void)
{
	int col[QUANT_MAX][3];
	qnear_t *q = malloc(sizeof *q);
	qcells_t *cells = quant_cells_new();
	int bad = 0, tries = 0;
	/* the places of the lattice sets: either side of the cells' borders (256 units) and between */
	static const int edge[] = { 0, 128, 255, 256, 384, 511, 512, 640, 767, 768, 896, 1020 };
	for (int set = 0; set < 24; set++) {
		/* sets 0, 1: random; 2, 3: a lattice (twins, ties, colours on the cells' borders);
		 * 4 on: 2 to 6 entries, so the runner-up is often far outside the colour's cell */
		unsigned n = set < 2 ? 256 - 56 * (unsigned)set : set < 4 ? 60 : 2 + (unsigned)set % 5;
		int lattice = set == 2 || set == 3;
		for (unsigned k = 0; k < n; k++)
			for (int c = 0; c < 3; c++)
				col[k][c] = lattice ? edge[rnd() % 12] : (int)(rnd() % 1021);
		quant_near_init(q, (const int (*)[3])col, n);
		quant_cells_reset(cells, (const int (*)[3])col, n);
		for (int t = 0; t < (set < 4 ? 20000 : 2000); t++, tries++) {
			int x[3];
			for (int c = 0; c < 3; c++)
				x[c] = t % 4 == 0 ? col[t / 4 % n][c] : lattice || t % 4 == 1 ? edge[rnd() % 12] : (int)(rnd() % 1021);
			long d1, d2, e1, e2;
			unsigned want = brute2((const int (*)[3])col, n, x, &e1, &e2);
			unsigned got = quant_cells_find2(cells, q, x[0], x[1], x[2], &d1, &d2);
			bad += got != want || d1 != e1 || d2 != e2;
		}
	}
	CHECK(bad == 0, "quant_cells_find2: nearest (ties to the lowest index) and runner-up as a brute-force search (%d of %d differ)", bad, tries);
	col[0][0] = 500, col[0][1] = 20, col[0][2] = 1000;
	quant_near_init(q, (const int (*)[3])col, 1);
	quant_cells_reset(cells, (const int (*)[3])col, 1);
	long d1, d2;
	unsigned got = quant_cells_find2(cells, q, 0, 0, 0, &d1, &d2);
	CHECK(got == 0 && d1 == 500L * 500 + 20 * 20 + 1000L * 1000 && d2 == -1, "quant_cells_find2: one entry, no runner-up");
	quant_cells_free(cells);
	free(q);
}

/* Rows told by quant_map_rows: each row once, and the indices those of quant_map. */
static void count_row(void *ctx, unsigned y)
{
	((unsigned char *)ctx)[y]++;
}

static void test_map_rows(void)
{
	unsigned w = 512, h = 600;   /* two halves */
	uint8_t *pic = malloc((size_t)w * h * 3), *a = malloc((size_t)w * h), *b = malloc((size_t)w * h);
	unsigned char *seen = calloc(h, 1);
	for (unsigned y = 0; y < h; y++)
		for (unsigned x = 0; x < w; x++) {
			uint8_t *p = pic + 3 * ((size_t)y * w + x);
			p[0] = (uint8_t)(x / 2), p[1] = (uint8_t)(y * 255 / h), p[2] = (uint8_t)(x < 100 ? 40 : rnd());
		}
	quant_hist_t *hi = quant_hist_new();
	quant_hist_add(hi, pic, w, h, (size_t)w * 3);
	quant_palette_t pal;
	char err[100];
	int rc = quant_build(hi, QUANT_BEST, 256, &pal, err, sizeof err);
	rc |= quant_map(&pal, hi, pic, w, h, (size_t)w * 3, QUANT_DITHER_FS, a);
	rc |= quant_map_rows(&pal, hi, pic, w, h, (size_t)w * 3, QUANT_DITHER_FS, b, count_row, seen);
	int once = 1;
	for (unsigned y = 0; y < h; y++)
		once &= seen[y] == 1;
	CHECK(rc == 0 && once, "quant_map_rows: every row of a 512x600 page told once");
	CHECK(rc == 0 && memcmp(a, b, (size_t)w * h) == 0, "quant_map_rows: the same indices as quant_map");
	quant_hist_free(hi);
	free(pic), free(a), free(b), free(seen);
}

/* A random picture of 512x512 (2^18 pixels: two halves on two threads): undithered, every pixel gets the
 * entry a brute-force search gives, with 6- and 8-bit palettes. */
static void test_big_map(void)
{
	unsigned w = 512, h = 512;
	uint8_t *pic = malloc((size_t)w * h * 3), *idx = malloc((size_t)w * h);
	for (size_t k = 0; k < (size_t)w * h * 3; k++)
		pic[k] = (uint8_t)rnd();
	/* a smooth part too: the whole-bin look-up meets colours near the entries' boundaries */
	for (unsigned y = 0; y < h / 4; y++)
		for (unsigned x = 0; x < w; x++) {
			uint8_t *p = pic + 3 * ((size_t)y * w + x);
			p[0] = (uint8_t)(x * 255 / w), p[1] = (uint8_t)(y * 255 / h), p[2] = 128;
		}
	quant_hist_t *hist = quant_hist_new();
	quant_hist_add(hist, pic, w, h, 3 * (size_t)w);
	for (unsigned bits = 6; bits <= 8; bits += 2) {
		quant_palette_t pal;
		char err[200];
		int rc = quant_build_bits(hist, QUANT_BEST, 256, bits, &pal, err, sizeof err);
		rc = rc || quant_map(&pal, hist, pic, w, h, 3 * (size_t)w, QUANT_DITHER_NONE, idx);
		size_t bad = 0;
		for (size_t k = 0; k < (size_t)w * h; k++)
			bad += idx[k] != brute(&pal, pic + 3 * k);
		CHECK(rc == 0 && pal.n == 256 && bad == 0,
			"%u-bit palette, 512x512 mapped in two halves: every pixel its nearest entry (%zu differ)", bits, bad);
		/* the same palette and picture give the same bytes again (no timing in the answer) */
		uint8_t *again = malloc((size_t)w * h), *fs = malloc((size_t)w * h);
		quant_palette_t pal2;
		rc = quant_build_bits(hist, QUANT_BEST, 256, bits, &pal2, err, sizeof err);
		rc = rc || quant_map(&pal2, hist, pic, w, h, 3 * (size_t)w, QUANT_DITHER_FS, again);
		rc = rc || quant_map(&pal, hist, pic, w, h, 3 * (size_t)w, QUANT_DITHER_FS, fs);
		CHECK(rc == 0 && memcmp(&pal, &pal2, sizeof pal) == 0 && memcmp(again, fs, (size_t)w * h) == 0,
			"%u-bit: the palette (k-means in two halves) and the dithered picture are the same twice", bits);
		free(again);
		free(fs);
	}
	quant_hist_free(hist);
	free(pic);
	free(idx);
}

/* Floyd-Steinberg: colours within the 6-bit DAC's rounding of an entry are not dithered; a
 * colour farther from every entry is. */
static void test_fs_near(void)
{
	unsigned w = 64, h = 64;
	uint8_t *pic = malloc((size_t)w * h * 3), *idx = malloc((size_t)w * h);
	quant_palette_t pal;
	memset(&pal, 0, sizeof pal);
	pal.n = 2, pal.bits = 8;
	pal.dac[1][0] = pal.dac[1][1] = pal.dac[1][2] = 200;
	/* left half 198..202 (within 2 levels of 200), right half 100 (half-way) */
	for (unsigned y = 0; y < h; y++)
		for (unsigned x = 0; x < w; x++)
			memset(pic + 3 * ((size_t)y * w + x), x < w / 2 ? 198 + (int)((x + y) % 5) : 100, 3);
	int rc = quant_map(&pal, NULL, pic, w, h, 3 * (size_t)w, QUANT_DITHER_FS, idx);
	size_t left = 0, right1 = 0;
	for (unsigned y = 0; y < h; y++)
		for (unsigned x = 0; x < w; x++) {
			if (x < w / 2)
				left += idx[(size_t)y * w + x] != 1;
			else
				right1 += idx[(size_t)y * w + x] == 1;
		}
	CHECK(rc == 0 && left == 0, "fs: every pixel within 2 levels of an entry gets it, undithered (%zu not)", left);
	CHECK(right1 > 0 && right1 < (size_t)w * h / 2, "fs: a colour between the entries is still dithered (%zu of %u light)",
		right1, w * h / 2);
	free(pic);
	free(idx);
}

int main(void)
{
	test_find2();
	test_cells();
	test_map_rows();
	test_big_map();
	test_fs_near();
	return UNIT_DONE();
}
