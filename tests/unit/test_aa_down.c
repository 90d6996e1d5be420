/* test_aa_down.c: the anti-aliased downsampler (render/aa.c) against a plain reference: every output
 * byte is the linear-light mean of its k x k samples encoded by a linear scan, whatever the band
 * rows, with flat runs (the neighbour-reuse path) and random samples (the table start). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include "render/aa.h"
#include "unit.h"

#define W 37
#define H 5

static float lin[256], mid[255];

static void tables(void)
{
	for (int c = 0; c < 256; c++) {
		double v = c / 255.0;
		lin[c] = (float)(v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4));
	}
	for (int c = 0; c < 255; c++)
		mid[c] = (float)(((double)lin[c] + lin[c + 1]) / 2.0);
}

/* The reference encoding: the first byte whose midpoint to the next is not below v. */
static uint8_t ref_byte(double v)
{
	int c = 0;
	while (c < 255 && v > mid[c])
		c++;
	return (uint8_t)c;
}

typedef struct {
	uint8_t out[W * H * 3];
	unsigned rows;
} sink_t;

static int take(void *user, const render_band_t *b)
{
	sink_t *s = user;
	for (unsigned r = 0; r < b->nrows; r++)
		memcpy(s->out + (size_t)(b->y0 + r) * W * 3, b->pix + (size_t)r * b->stride, W * 3);
	s->rows += b->nrows;
	return 0;
}

/* Run k x k samples through devaa in bands of `band` sample rows; compare with the reference. */
static int run(unsigned k, const uint8_t *smp, unsigned band, unsigned *bad)
{
	size_t sw = (size_t)W * k * 3;
	render_aa_t *a = render_aa_new(k, W, H);
	sink_t s = { { 0 }, 0 };
	if (!a)
		return -1;
	for (unsigned y = 0; y < H * k; y += band) {
		unsigned n = y + band > H * k ? H * k - y : band;
		render_band_t in = { (uint8_t *)smp + y * sw, sw, W * k, y, n, H * k };
		if (render_aa_band(a, &in, take, &s))
			return -1;
	}
	render_aa_free(a);
	*bad = 0;
	for (unsigned y = 0; y < H; y++)
		for (unsigned x = 0; x < W; x++)
			for (unsigned ch = 0; ch < 3; ch++) {
				double sum = 0;
				for (unsigned j = 0; j < k; j++) {
					double row = 0;
					for (unsigned i = 0; i < k; i++)
						row += lin[smp[(size_t)(y * k + j) * sw + (size_t)(x * k + i) * 3 + ch]];
					sum += row;
				}
				if (s.out[((size_t)y * W + x) * 3 + ch] != ref_byte(sum * (1.0 / ((double)k * k))))
					++*bad;
			}
	return s.rows == H ? 0 : -1;
}

int main(void)
{
	tables();
	srand(7);
	static const unsigned ks[] = { 2, 3, 4, 5 };
	for (size_t t = 0; t < sizeof ks / sizeof ks[0]; t++) {
		unsigned k = ks[t];
		size_t n = (size_t)W * k * H * k * 3;
		uint8_t *smp = malloc(n);
		if (!smp)
			return 1;
		/* random samples, then runs of flat pixels between random edges */
		for (size_t i = 0; i < n; i++)
			smp[i] = (uint8_t)rand();
		unsigned bad1 = 99, bad2 = 99;
		int rc1 = run(k, smp, 1, &bad1);
		for (size_t i = 0; i < n; i += 3) {
			uint8_t v = (i / 3 / (k * 6)) % 3 ? 40 : (uint8_t)(rand() & 1 ? 255 : rand());
			smp[i] = v; smp[i + 1] = (uint8_t)(v / 2); smp[i + 2] = (uint8_t)(255 - v);
		}
		int rc2 = run(k, smp, 2 * k + 1, &bad2);
		CHECK(rc1 == 0 && bad1 == 0, "k=%u, random samples, bands of 1 row: every byte is the reference's (%u differ)", k, bad1);
		CHECK(rc2 == 0 && bad2 == 0, "k=%u, flat runs, bands of %u rows: every byte is the reference's (%u differ)", k, 2 * k + 1, bad2);
		free(smp);
	}
	/* every grey level of a flat area comes back unchanged, and a half-covered pixel of black on
	 * white is the byte nearest linear 0.5 (188) */
	unsigned same = 0;
	for (int c = 0; c < 256; c++)
		same += ref_byte(lin[c]) == c;
	CHECK(same == 256, "the reference keeps all 256 flat levels (%u)", same);
	CHECK(ref_byte(0.5) == 188, "linear 0.5 encodes to 188 (#bcbcbc)");
	return UNIT_DONE();
}
