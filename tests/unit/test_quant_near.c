/* test_quant_near.c: the quantiser's exact searches and its two-thread split: the nearest and
 * second-nearest search, undithered mapping of a big picture (two halves, the whole-bin look-up)
 * against a brute-force search, and Floyd-Steinberg leaving colours within the DAC's rounding
 * of an entry undithered. */
#include <stdlib.h>
#include "quant.h"
#include "quant_int.h"
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
		long d1 = -1, d2 = -1, b1 = -1, b2 = -1;
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
	test_big_map();
	test_fs_near();
	return UNIT_DONE();
}
