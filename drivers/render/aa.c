/* aa.c: anti-aliasing by supersampling: k x k exact samples per pixel, averaged in linear
 * light, band by band, so banding and the memory budget work as in the exact mode. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "render/aa.h"

/* The steps of the table that starts to_byte near its answer. */
#define AA_ENC 4096

struct devaa {
	unsigned k, width, height;   /* the factor; the device's raster */
	double *acc;                 /* one output row being summed, width * 3 */
	unsigned acc_rows;           /* sample rows summed into acc */
	uint8_t *out;                /* finished output rows not yet handed over */
	unsigned out_rows, out_cap, y0;
	float lin[256], mid[255];
	uint8_t enc[AA_ENC + 1];     /* to_byte's start: the byte of v = i / AA_ENC */
};

static uint8_t search_byte(const render_aa_t *a, double v);

render_aa_t *render_aa_new(unsigned k, unsigned width, unsigned height)
{
	render_aa_t *a = calloc(1, sizeof *a);
	if (!a)
		return NULL;
	a->k = k;
	a->width = width;
	a->height = height;
	a->out_cap = 64;
	a->acc = calloc((size_t)width * 3, sizeof *a->acc);
	a->out = malloc((size_t)width * 3 * a->out_cap);
	if (!a->acc || !a->out) {
		render_aa_free(a);
		return NULL;
	}
	for (int c = 0; c < 256; c++) {
		double v = c / 255.0;
		a->lin[c] = (float)(v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4));
	}
	for (int c = 0; c < 255; c++)
		a->mid[c] = (float)(((double)a->lin[c] + a->lin[c + 1]) / 2.0);
	for (int i = 0; i <= AA_ENC; i++)
		a->enc[i] = search_byte(a, (double)i / AA_ENC);
	return a;
}

void render_aa_free(render_aa_t *a)
{
	if (!a)
		return;
	free(a->acc);
	free(a->out);
	free(a);
}

/* The byte whose linear value is nearest v: the first c with v <= mid[c] (ties go down). */
static uint8_t search_byte(const render_aa_t *a, double v)
{
	unsigned lo = 0, hi = 255;
	while (lo < hi) {
		unsigned m = (lo + hi) / 2;
		if (v > a->mid[m])
			lo = m + 1;
		else
			hi = m;
	}
	return (uint8_t)lo;
}

/* search_byte(v) for v in [0, 1], started from the table and moved to the same answer (the
 * table's neighbours bracket it, so this is a step or two, not eight). */
static inline uint8_t to_byte(const render_aa_t *a, double v)
{
	if (!(v > 0))
		return search_byte(a, v);
	if (v >= 1)
		return 255;
	unsigned c = a->enc[(unsigned)(v * AA_ENC)];
	while (c < 255 && v > a->mid[c])
		c++;
	while (c > 0 && !(v > a->mid[c - 1]))
		c--;
	return (uint8_t)c;
}

/* Whether the n bytes at p and q are equal (n = 3k, a few words: inline, not memcmp). */
static inline int same(const uint8_t *p, const uint8_t *q, size_t n)
{
	size_t i = 0;
	for (; i + 8 <= n; i += 8) {
		uint64_t u, v;
		memcpy(&u, p + i, 8);
		memcpy(&v, q + i, 8);
		if (u != v)
			return 0;
	}
	if (i + 4 <= n) {   /* k = 4: 12 bytes, one word and a half; the tail byte by byte was a
			     * sixth of an anti-aliased replay of workload b (callgrind) */
		uint32_t u, v;
		memcpy(&u, p + i, 4);
		memcpy(&v, q + i, 4);
		if (u != v)
			return 0;
		i += 4;
	}
	for (; i < n; i++)
		if (p[i] != q[i])
			return 0;
	return 1;
}

static int hand_over(render_aa_t *a, render_aa_fn fn, void *user)
{
	if (!a->out_rows)
		return 0;
	render_band_t b = { a->out, (size_t)a->width * 3, a->width, a->y0, a->out_rows, a->height };
	int rc = fn(user, &b);
	a->y0 += a->out_rows;
	a->out_rows = 0;
	return rc;
}

int render_aa_band(render_aa_t *a, const render_band_t *in, render_aa_fn fn, void *user)
{
	unsigned k = a->k, w = a->width;
	double norm = 1.0 / ((double)k * k);
	for (unsigned r = 0; r < in->nrows; r++) {
		const uint8_t *q = in->pix + (size_t)r * in->stride;
		double s0 = 0, s1 = 0, s2 = 0;
		size_t run = (size_t)k * 3;
		for (unsigned x = 0; x < w; x++, q += run) {
			/* the same k samples as the pixel before (flat areas): the same sums */
			if (!x || !same(q, q - run, run)) {
				s0 = s1 = s2 = 0;
				for (unsigned i = 0; i < run; i += 3) {
					s0 += a->lin[q[i]];
					s1 += a->lin[q[i + 1]];
					s2 += a->lin[q[i + 2]];
				}
			}
			a->acc[3 * x] += s0;
			a->acc[3 * x + 1] += s1;
			a->acc[3 * x + 2] += s2;
		}
		if (++a->acc_rows < k)
			continue;
		uint8_t *o = a->out + (size_t)a->out_rows * w * 3;
		for (unsigned x = 0; x < 3 * w; x++)
			o[x] = to_byte(a, a->acc[x] * norm);
		memset(a->acc, 0, (size_t)w * 3 * sizeof *a->acc);
		a->acc_rows = 0;
		if (++a->out_rows == a->out_cap) {
			int rc = hand_over(a, fn, user);
			if (rc)
				return rc;
		}
	}
	/* hand over what this band finished, so bands reach the device as they are rendered */
	return hand_over(a, fn, user);
}
