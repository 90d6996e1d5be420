/* hpgl_hatch.c: polygon hatching by either fill rule, and the brightness line halftone of rows. */
#include <math.h>
#include <stdlib.h>
#include "util/grow.h"
#include "hpgl/hpgl_hatch.h"

typedef struct {
	long line;                  /* hatch line index */
	double x;                   /* crossing abscissa in the rotated frame */
	int dir;                    /* +1 upward edge, -1 downward */
} cross_t;

static int cross_cmp(const void *a, const void *b)
{
	const cross_t *p = a, *q = b;
	if (p->line != q->line)
		return p->line < q->line ? -1 : 1;
	if (p->x != q->x)
		return p->x < q->x ? -1 : 1;
	return p->dir - q->dir;
}

int hatch_polygon(const double *pts, const size_t *starts, size_t ncont, int even_odd,
		double angle_deg, double spacing, double phase, hatch_fn fn, void *user)
{
	if (!(spacing > 0) || ncont == 0)
		return 0;
	double a = angle_deg * M_PI / 180, ca = cos(a), sa = sin(a);
	/* rotate by -a: hatch lines become horizontal, v = const */
	size_t cap = 0, nc = 0;
	cross_t *cr = NULL;
	for (size_t k = 0; k < ncont; k++) {
		size_t s = starts[k], n = starts[k + 1] - s;
		for (size_t i = 0; i < n; i++) {
			const double *p = pts + 2 * (s + i), *q = pts + 2 * (s + (i + 1) % n);
			double u0 = p[0] * ca + p[1] * sa, v0 = -p[0] * sa + p[1] * ca;
			double u1 = q[0] * ca + q[1] * sa, v1 = -q[0] * sa + q[1] * ca;
			if (v0 == v1)
				continue;
			int dir = v1 > v0 ? 1 : -1;
			double lo = v0 < v1 ? v0 : v1, hi = v0 < v1 ? v1 : v0;
			/* lines v = phase + m * spacing with lo <= v < hi */
			double c0 = ceil((lo - phase) / spacing), c1 = ceil((hi - phase) / spacing) - 1;
			if (!(c0 > -1e15 && c1 < 1e15))
				continue;   /* no such edge on a page; a cast beyond long would be undefined */
			long m0 = (long)c0, m1 = (long)c1;
			for (long m = m0; m <= m1; m++) {
				double v = phase + m * spacing;
				if (v < lo || v >= hi)
					continue;
				if (dev_grow((void **)&cr, &cap, nc + 1, sizeof *cr, 256)) {
					free(cr);
					return -1;
				}
				cr[nc++] = (cross_t){ m, u0 + (v - v0) * (u1 - u0) / (v1 - v0), dir };
			}
		}
	}
	if (nc)
		qsort(cr, nc, sizeof *cr, cross_cmp);   /* (qsort of NULL is undefined, even for 0) */
	int rc = 0, flip = 0;
	for (size_t i = 0; i < nc && !rc;) {
		size_t j = i;
		while (j < nc && cr[j].line == cr[i].line)
			j++;
		double v = phase + cr[i].line * spacing;
		/* collect the inside intervals of this line */
		int w = 0;
		size_t count = 0;
		double ustart = 0;
		double *iv = malloc(((j - i) + 2) * sizeof *iv);
		if (!iv) {
			free(cr);
			return -1;
		}
		for (size_t k = i; k < j; k++) {
			int was = even_odd ? (w & 1) : w != 0;
			w += cr[k].dir;
			int is = even_odd ? (w & 1) : w != 0;
			if (!was && is)
				ustart = cr[k].x;
			else if (was && !is && cr[k].x > ustart) {
				iv[count++] = ustart;
				iv[count++] = cr[k].x;
			}
		}
		for (size_t t = 0; t < count && !rc; t += 2) {
			size_t q = flip ? count - 2 - t : t;
			double ua = iv[q + (flip ? 1 : 0)], ub = iv[q + (flip ? 0 : 1)];
			rc = fn(user, ua * ca - v * sa, ua * sa + v * ca, ub * ca - v * sa, ub * sa + v * ca);
		}
		free(iv);
		if (count)
			flip ^= 1;
		i = j;
	}
	free(cr);
	return rc;
}

/* Bit-reversed order of 8 thresholds: consecutive lines spread the levels evenly. */
static const unsigned char order8[8] = { 0, 4, 2, 6, 1, 5, 3, 7 };

int hatch_row(const double *darkness, size_t n, double x0, double x1, double y0, double h,
		unsigned lines, unsigned row_index, hatch_fn fn, void *user)
{
	if (lines == 0 || n == 0)
		return 0;
	double pw = (x1 - x0) / n;
	for (unsigned k = 0; k < lines; k++) {
		unsigned g = row_index * lines + k;
		double thr = (order8[g % 8] + 0.5) / 8, y = y0 + (k + 0.5) * h / lines;
		int odd = g & 1;
		/* alternate direction line by line */
		for (size_t i = 0; i < n;) {
			size_t p = odd ? n - 1 - i : i;
			if (darkness[p] <= thr) {
				i++;
				continue;
			}
			size_t j = i;
			while (j < n && darkness[odd ? n - 1 - j : j] > thr)
				j++;
			double xa, xb;
			if (odd) {
				xa = x0 + (double)(n - i) * pw;
				xb = x0 + (double)(n - j) * pw;
			} else {
				xa = x0 + (double)i * pw;
				xb = x0 + (double)j * pw;
			}
			int rc = fn(user, xa, y, xb, y);
			if (rc)
				return rc;
			i = j;
		}
	}
	return 0;
}
