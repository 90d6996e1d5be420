/* test_quant.c: the palette quantiser: exactness, quality against fixed palettes, the papers'
 * hand-worked cases, flat colours, dithering, fixed palettes and palette files. */
#include <math.h>
#include <stdlib.h>
#include "quant/quant.h"
#include "unit.h"

static uint32_t rng = 12345;
static unsigned rnd(void)
{
	rng = rng * 1103515245u + 12345u;
	return rng >> 8;
}

/* A picture of w x h pixels, all of colour c. */
static uint8_t *picture(unsigned w, unsigned h)
{
	return calloc((size_t)w * h, 3);
}

static void put(uint8_t *p, unsigned w, unsigned x, unsigned y, unsigned r, unsigned g, unsigned b)
{
	uint8_t *q = p + 3 * ((size_t)y * w + x);
	q[0] = (uint8_t)r, q[1] = (uint8_t)g, q[2] = (uint8_t)b;
}

static int has_entry(const quant_palette_t *pal, unsigned r, unsigned g, unsigned b)
{
	for (unsigned k = 0; k < pal->n; k++)
		if (pal->dac[k][0] == r && pal->dac[k][1] == g && pal->dac[k][2] == b)
			return 1;
	return 0;
}

static double psnr_of(const quant_palette_t *pal, const quant_hist_t *h, const uint8_t *pic, unsigned w,
		unsigned hh, int dither)
{
	uint8_t *idx = malloc((size_t)w * hh);
	quant_map(pal, h, pic, w, hh, 3 * (size_t)w, dither, idx);
	double p = quant_psnr(pal, pic, w, hh, 3 * (size_t)w, idx);
	free(idx);
	return p;
}

/* A picture of at most n DAC colours comes back exactly (every method, every dithering). */
static void test_exact(void)
{
	unsigned w = 64, h = 50;
	uint8_t *pic = picture(w, h);
	uint8_t cols[200][3];
	for (int k = 0; k < 200; k++)
		for (int c = 0; c < 3; c++)
			cols[k][c] = (uint8_t)(rnd() & 255);
	for (unsigned y = 0; y < h; y++)
		for (unsigned x = 0; x < w; x++) {
			const uint8_t *c = cols[rnd() % 200];
			put(pic, w, x, y, c[0], c[1], c[2]);
		}
	quant_hist_t *hist = quant_hist_new();
	quant_hist_add(hist, pic, w, h, 3 * (size_t)w);
	uint8_t *idx = malloc((size_t)w * h);
	char err[200];
	for (int m = 0; m < 3; m++)
		for (int d = 0; d < 3; d++) {
			quant_palette_t pal;
			int rc = quant_build(hist, m, 256, &pal, err, sizeof err);
			rc |= quant_map(&pal, hist, pic, w, h, 3 * (size_t)w, d, idx);
			int bad = 0;
			for (size_t k = 0; k < (size_t)w * h; k++)
				for (int c = 0; c < 3; c++)
					bad += pal.dac[idx[k]][c] != quant_dac6(pic[3 * k + c]);
			CHECK(rc == 0 && bad == 0 && pal.n <= 200, "%zu DAC colours come back exact (method %d, dither %d)",
				quant_hist_colours(hist), m, d);
		}
	/* with 8-bit entries the 24-bit colours themselves come back */
	for (int m = 0; m < 3; m++) {
		quant_palette_t pal;
		int rc = quant_build_bits(hist, m, 256, 8, &pal, err, sizeof err);
		rc |= quant_map(&pal, hist, pic, w, h, 3 * (size_t)w, QUANT_DITHER_FS, idx);
		int bad = 0;
		for (size_t k = 0; k < (size_t)w * h; k++)
			for (int c = 0; c < 3; c++)
				bad += pal.dac[idx[k]][c] != pic[3 * k + c];
		CHECK(rc == 0 && bad == 0 && pal.bits == 8 && quant_psnr(&pal, pic, w, h, 3 * (size_t)w, idx) == 99,
			"8-bit palette: 200 colours come back exact in 24 bits (method %d)", m);
	}
	free(idx);
	free(pic);
	quant_hist_free(hist);
}

/* Adaptive palettes are never worse (PSNR) than the best fixed palette, at 256 and 16. */
static void test_against_fixed(void)
{
	unsigned w = 160, h = 120;
	uint8_t *pic = picture(w, h);
	for (unsigned y = 0; y < h; y++)
		for (unsigned x = 0; x < w; x++) {
			double u = (double)x / w, v = (double)y / h;
			put(pic, w, x, y, (unsigned)(200 * u + 30 * sin(9 * v) + 20 + rnd() % 8),
				(unsigned)(120 + 100 * v * u + rnd() % 8), (unsigned)(40 + 150 * (1 - u) * v + rnd() % 8));
		}
	quant_hist_t *hist = quant_hist_new();
	quant_hist_add(hist, pic, w, h, 3 * (size_t)w);
	char err[200];
	for (unsigned n = 16; n <= 256; n += 240) {
		double best_fixed = 0;
		int fixed[] = { QUANT_FIXED_VGA, QUANT_FIXED_EGA, QUANT_FIXED_CUBE, QUANT_FIXED_GREY };
		for (int f = 0; f < 4; f++) {
			quant_palette_t pal;
			if (quant_fixed(fixed[f], n, &pal, err, sizeof err) == 0)
				for (int d = 0; d < 3; d++) {
					double p = psnr_of(&pal, hist, pic, w, h, d);
					if (p > best_fixed)
						best_fixed = p;
				}
		}
		for (int m = 0; m < 3; m++) {
			quant_palette_t pal;
			quant_build(hist, m, n, &pal, err, sizeof err);
			double p = psnr_of(&pal, hist, pic, w, h, QUANT_DITHER_NONE);
			CHECK(p >= best_fixed, "%u colours, method %d: %.2f dB >= best fixed %.2f dB", n, m, p, best_fixed);
		}
		quant_palette_t pb, pm, po;
		quant_build(hist, QUANT_BEST, n, &pb, err, sizeof err);
		quant_build(hist, QUANT_MEDIAN, n, &pm, err, sizeof err);
		quant_build(hist, QUANT_OCTREE, n, &po, err, sizeof err);
		double b = psnr_of(&pb, hist, pic, w, h, 0), md = psnr_of(&pm, hist, pic, w, h, 0), o = psnr_of(&po, hist, pic, w, h, 0);
		CHECK(b >= md && b >= o, "%u colours: the default (%.2f dB) beats median cut (%.2f) and octree (%.2f)", n, b, md, o);
	}
	free(pic);
	quant_hist_free(hist);
}

/* Four reds a, b, c, d (DAC 0, 30, 31, 32) quantised to two entries, by hand:
 *  - median cut: one box, longest side red; cut at the pixel median: {0, 30} {31, 32}
 *    (with a weight of 3 on 0: {0} {30, 31, 32});
 *  - octree: 0 = 000000, 30 = 011110, 31 = 011111, 32 = 100000; the deepest merge joins the
 *    siblings 30 and 31, then single-child chains rise until the node of prefix 0 merges 0 with
 *    them: {0, 30, 31} {32}, though 31 and 32 are the nearest pair;
 *  - the default: {0} {30, 31, 32}. */
static void test_hand_worked(void)
{
	static const unsigned red6[4] = { 0, 30, 31, 32 };
	char err[200];
	for (int weighted = 0; weighted < 2; weighted++) {
		unsigned w = weighted ? 6 : 4;
		uint8_t *pic = picture(w, 1);
		for (unsigned x = 0; x < w; x++) {
			unsigned k = weighted ? (x < 3 ? 0 : x - 2) : x;
			put(pic, w, x, 0, quant_dac8(red6[k]), 0, 0);
		}
		quant_hist_t *hist = quant_hist_new();
		quant_hist_add(hist, pic, w, 1, 3 * (size_t)w);
		quant_palette_t pal;
		quant_build(hist, QUANT_MEDIAN, 2, &pal, err, sizeof err);
		if (!weighted) {
			/* DAC 0, 30, 31, 32 show 0, 121, 125, 130: means (0 + 121) / 2 = 60.5 -> DAC 15,
			 * (125 + 130) / 2 = 127.5 -> DAC 32 */
			CHECK(pal.n == 2 && has_entry(&pal, 15, 0, 0) && has_entry(&pal, 32, 0, 0),
				"median cut cuts at the pixel median: {0,30} {31,32}");
			quant_build(hist, QUANT_OCTREE, 2, &pal, err, sizeof err);
			/* (0 + 121 + 125) / 3 = 82 -> DAC 20; 32 alone */
			CHECK(pal.n == 2 && has_entry(&pal, 20, 0, 0) && has_entry(&pal, 32, 0, 0),
				"octree merges by the tree: {0,30,31} {32}");
			quant_build(hist, QUANT_BEST, 2, &pal, err, sizeof err);
			CHECK(pal.n == 2 && has_entry(&pal, 0, 0, 0) && has_entry(&pal, 31, 0, 0),
				"the default finds the least-error split: {0} {30,31,32}");
		} else {
			/* 0 holds half the pixels: {0} and {121, 125, 130} -> mean 125.3 = DAC 31 */
			CHECK(pal.n == 2 && has_entry(&pal, 0, 0, 0) && has_entry(&pal, 31, 0, 0),
				"median cut counts pixels, not colours: {0 x3} {30,31,32}");
		}
		free(pic);
		quant_hist_free(hist);
	}
	/* median cut cuts the longest side: green spread 0..63, red 0..8 */
	uint8_t *pic = picture(4, 1);
	put(pic, 4, 0, 0, quant_dac8(0), quant_dac8(0), 0);
	put(pic, 4, 1, 0, quant_dac8(8), quant_dac8(4), 0);
	put(pic, 4, 2, 0, quant_dac8(0), quant_dac8(60), 0);
	put(pic, 4, 3, 0, quant_dac8(8), quant_dac8(63), 0);
	quant_hist_t *hist = quant_hist_new();
	quant_hist_add(hist, pic, 4, 1, 12);
	quant_palette_t pal;
	quant_build(hist, QUANT_MEDIAN, 2, &pal, err, sizeof err);
	CHECK(pal.n == 2 && pal.dac[0][1] + pal.dac[1][1] > 50 && abs((int)pal.dac[0][0] - (int)pal.dac[1][0]) <= 1,
		"median cut splits along the longest side (green)");
	free(pic);
	quant_hist_free(hist);
}

/* A colour filling many pixels keeps its own entry and is never dithered, even amid noise. */
static void test_flat(void)
{
	unsigned w = 200, h = 100;
	uint8_t *pic = picture(w, h);
	for (unsigned y = 0; y < h; y++)
		for (unsigned x = 0; x < w; x++) {
			if (x >= 60 && x < 140 && y >= 20 && y < 80)
				put(pic, w, x, y, 0x33, 0x99, 0xcc);     /* a fill */
			else if (y == 10)
				put(pic, w, x, y, 0xe8, 0x10, 0x10);     /* a line */
			else
				put(pic, w, x, y, rnd() & 255, rnd() & 255, rnd() & 255);
		}
	quant_hist_t *hist = quant_hist_new();
	quant_hist_add(hist, pic, w, h, 3 * (size_t)w);
	char err[200];
	uint8_t *idx = malloc((size_t)w * h);
	for (int d = 0; d < 3; d++) {
		quant_palette_t pal;
		quant_build(hist, QUANT_BEST, 256, &pal, err, sizeof err);
		quant_map(&pal, hist, pic, w, h, 3 * (size_t)w, d, idx);
		int bad = 0;
		unsigned fill = idx[(size_t)20 * w + 60], line = idx[(size_t)10 * w];
		for (unsigned y = 0; y < h; y++)
			for (unsigned x = 0; x < w; x++) {
				int in_fill = x >= 60 && x < 140 && y >= 20 && y < 80;
				if ((in_fill && idx[(size_t)y * w + x] != fill) || (y == 10 && idx[(size_t)y * w + x] != line))
					bad++;
			}
		const uint8_t *f = pal.dac[fill], *l = pal.dac[line];
		CHECK(bad == 0 && f[0] == quant_dac6(0x33) && f[1] == quant_dac6(0x99) && f[2] == quant_dac6(0xcc) &&
			l[0] == quant_dac6(0xe8) && l[1] == quant_dac6(0x10),
			"flat fill and line keep their exact DAC colour on every pixel (dither %d)", d);
	}
	free(idx);
	free(pic);
	quant_hist_free(hist);
}

/* Dithering keeps local averages: an 8x8 block average of a grey ramp on 16 greys. */
static void test_dither(void)
{
	unsigned w = 256, h = 64;
	uint8_t *pic = picture(w, h);
	for (unsigned y = 0; y < h; y++)
		for (unsigned x = 0; x < w; x++)
			put(pic, w, x, y, x, x, x);
	quant_palette_t pal;
	char err[200];
	quant_fixed(QUANT_FIXED_GREY, 16, &pal, err, sizeof err);
	uint8_t *idx = malloc((size_t)w * h);
	double e[3];
	for (int d = 0; d < 3; d++) {
		quant_map(&pal, NULL, pic, w, h, 3 * (size_t)w, d, idx);
		double se = 0;
		for (unsigned by = 16; by < h - 8; by += 8)
			for (unsigned bx = 0; bx < w; bx += 8) {
				double s = 0, t = 0;
				for (unsigned y = by; y < by + 8; y++)
					for (unsigned x = bx; x < bx + 8; x++)
						s += quant_dac8(pal.dac[idx[(size_t)y * w + x]][0]), t += x;
				se += (s - t) / 64 * ((s - t) / 64);
			}
		e[d] = se;
	}
	CHECK(e[QUANT_DITHER_ORDERED] < e[QUANT_DITHER_NONE] / 4, "ordered dithering keeps block averages (%.0f < %.0f / 4)",
		e[1], e[0]);
	CHECK(e[QUANT_DITHER_FS] < e[QUANT_DITHER_NONE] / 4, "Floyd-Steinberg keeps block averages (%.0f < %.0f / 4)",
		e[2], e[0]);
	/* 5-6-5: exact grid colours come back exactly, undithered */
	uint16_t *px = malloc((size_t)w * h * 2);
	for (unsigned x = 0; x < w; x++)
		put(pic, w, x, 0, (x & 31) << 3 | (x & 31) >> 2, (x & 63) << 2 | (x & 63) >> 4, 0);
	quant_map565(NULL, pic, w, 1, 3 * (size_t)w, QUANT_DITHER_NONE, px);
	int bad = 0;
	for (unsigned x = 0; x < w; x++)
		bad += px[x] != ((x & 31) << 11 | (x & 63) << 5);
	CHECK(bad == 0, "5-6-5 keeps colours on its grid");
	free(px);
	free(idx);
	free(pic);
}

/* 8-bit palettes made from the exact colours (quant_hist_exact) beat those made from the DAC
 * bins when colours share bins: 240 colours, four to a bin, with 256 entries come back exact;
 * from the 60 bins only their means would. */
static void test_exact_colours(void)
{
	unsigned w = 240, h = 20;
	uint8_t *pic = picture(w, h);
	for (unsigned x = 0; x < w; x++) {
		unsigned base = (x / 4) * 4, d = x % 4;   /* 0..3 apart: one 6-bit bin */
		for (unsigned y = 0; y < h; y++)
			put(pic, w, x, y, base + (d & 1), (base * 3 + (d >> 1)) & 255, 200 - base / 2);
	}
	char err[200];
	quant_hist_t *bins = quant_hist_new(), *ex = quant_hist_new();
	quant_hist_add(bins, pic, w, h, 3 * (size_t)w);
	quant_hist_add(ex, pic, w, h, 3 * (size_t)w);
	int rc = quant_hist_exact(ex, pic, w, h, 3 * (size_t)w);
	quant_palette_t pb, pe;
	rc |= quant_build_bits(bins, QUANT_BEST, 256, 8, &pb, err, sizeof err);
	rc |= quant_build_bits(ex, QUANT_BEST, 256, 8, &pe, err, sizeof err);
	double b = psnr_of(&pb, bins, pic, w, h, QUANT_DITHER_NONE), e = psnr_of(&pe, ex, pic, w, h, QUANT_DITHER_NONE);
	CHECK(rc == 0 && e == 99 && b < 99, "8-bit palette from exact colours: exact (%.0f dB); from the DAC bins %.2f dB",
		e, b);
	free(pic);
	quant_hist_free(bins);
	quant_hist_free(ex);
}

static void test_fixed_and_files(void)
{
	quant_palette_t pal;
	char err[300];
	CHECK(quant_fixed(QUANT_FIXED_VGA, 256, &pal, err, sizeof err) == 0 && pal.n == 256, "VGA palette");
	CHECK(pal.dac[1][2] == 42 && pal.dac[6][1] == 21 && pal.dac[15][0] == 63, "VGA 0-15: the EGA colours (6 is brown)");
	CHECK(pal.dac[16][0] == 0 && pal.dac[31][0] == 63 && pal.dac[24][1] == 28, "VGA 16-31: the grey ramp");
	CHECK(pal.dac[32][2] == 63 && pal.dac[32][0] == 0 && pal.dac[40][0] == 63 && pal.dac[40][2] == 0 &&
		pal.dac[48][1] == 63, "VGA 32-55: blue, red, green around the hue circle");
	CHECK(pal.dac[104][2] == 28 && pal.dac[176][2] == 16 && pal.dac[255][0] == 0, "VGA: dimmer blocks, then black");
	CHECK(quant_fixed(QUANT_FIXED_VGA, 16, &pal, err, sizeof err) < 0, "VGA palette refused for 16 colours: %s", err);
	CHECK(quant_fixed(QUANT_FIXED_CUBE, 256, &pal, err, sizeof err) == 0 && pal.dac[215][0] == 63 &&
		pal.dac[43][0] == 12 && pal.dac[43][1] == 12 && pal.dac[43][2] == 12, "6x6x6 cube");
	CHECK(quant_fixed(QUANT_FIXED_GREY, 16, &pal, err, sizeof err) == 0 && pal.dac[15][0] == 63 &&
		pal.dac[5][1] == 21, "16 greys");
	const char *txt = "; a palette\n#000000\n#FF8000\n\n#ffffff\n";
	CHECK(quant_parse_palette((const unsigned char *)txt, strlen(txt), "p.txt", 256, &pal, err, sizeof err) == 0 &&
		pal.n == 3 && pal.dac[1][0] == 63 && pal.dac[1][1] == 32 && pal.dac[1][2] == 0, "#rrggbb palette file");
	const char *bad = "#000000\n#12345g\n";
	CHECK(quant_parse_palette((const unsigned char *)bad, strlen(bad), "p.txt", 256, &pal, err, sizeof err) < 0 &&
		strcmp(err, "p.txt:2:1: expected #rrggbb") == 0, "bad line named: %s", err);
	const char *many = "#000000\n#000000\n#000000\n";
	CHECK(quant_parse_palette((const unsigned char *)many, strlen(many), "p.txt", 2, &pal, err, sizeof err) < 0 &&
		strstr(err, "p.txt:3:1:"), "too many colours for the mode: %s", err);
	unsigned char raw[768];
	for (int k = 0; k < 768; k++)
		raw[k] = (unsigned char)(k % 64);
	raw[0] = 5;
	CHECK(quant_parse_palette(raw, 768, "p.dac", 256, &pal, err, sizeof err) == 0 && pal.dac[0][0] == 5 &&
		pal.dac[1][0] == 3, "raw 768-byte DAC dump");
	raw[100] = 64;
	CHECK(quant_parse_palette(raw, 768, "p.dac", 256, &pal, err, sizeof err) < 0 && strstr(err, "byte 100"),
		"DAC value above 63 named by offset: %s", err);
	CHECK(quant_parse_palette(raw, 700, "p.dac", 256, &pal, err, sizeof err) < 0, "short DAC dump refused: %s", err);
}

int main(void)
{
	test_exact();
	test_against_fixed();
	test_hand_worked();
	test_flat();
	test_dither();
	test_exact_colours();
	test_fixed_and_files();
	return UNIT_DONE();
}
