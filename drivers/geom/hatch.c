/* hatch.c: a filled polygon as horizontal hatch lines, covered exactly by the §5.1 rule. */
#include <stdlib.h>
#include "util/grow.h"
#include "geom/scan_int.h"

/* One crossing of a row: abscissa (thousandths, exact as a double) and winding step. */
typedef struct {
	double x;
	int dir;
} cross_t;

static int by_x(const void *a, const void *b)
{
	double u = ((const cross_t *)a)->x, v = ((const cross_t *)b)->x;
	return u < v ? -1 : u > v;
}

int scan_hatch(const scan_path_t *p, int rule, int64_t y0, int64_t step, scan_path_t *out)
{
	int64_t bx0, by0, bx1, by1;
	if (step <= 0 || !scan_path_bbox(p, &bx0, &by0, &bx1, &by1))
		return 0;
	size_t cap = 0, n;
	cross_t *cx = NULL;
	int rc = 0;
	/* the first line at or above the bottom of the box */
	int64_t k0 = by0 > y0 ? (by0 - y0 + step - 1) / step : -((y0 - by0) / step);
	for (int64_t y = y0 + k0 * step; y <= by1 && rc == 0; y += step) {
		n = 0;
		for (size_t s = 0; s < p->nsubs; s++) {
			const scan_pt_t *q = p->pts + p->subs[s].start;
			size_t m = p->subs[s].n;
			for (size_t i = 0; i < m && m >= 2; i++) {
				scan_pt_t a = q[i], b = q[i + 1 == m ? 0 : i + 1];
				if (a.y == b.y)
					continue;
				int dir = b.y > a.y ? 1 : -1;
				if (dir < 0) {
					scan_pt_t t = a; a = b; b = t;
				}
				if (!(a.y <= y && y < b.y))
					continue;
				if (dev_grow((void **)&cx, &cap, n + 1, sizeof *cx, 64)) {
					rc = META_ENOMEM;
					break;
				}
				cx[n].x = (double)a.x + (double)(y - a.y) * (double)(b.x - a.x) / (double)(b.y - a.y);
				cx[n].dir = dir;
				n++;
			}
		}
		if (rc)
			break;
		qsort(cx, n, sizeof *cx, by_x);
		/* a point of the row is inside after the crossings at or left of it (§5.1: X <= Xc) */
		int wind = 0;
		for (size_t i = 0; i + 1 < n && rc == 0; i++) {
			wind += cx[i].dir;
			int in = rule == META_RULE_EVEN_ODD ? (wind & 1) : wind != 0;
			if (!in || cx[i + 1].x <= cx[i].x)
				continue;
			int64_t xa = scan_round(cx[i].x), xb = scan_round(cx[i + 1].x);
			/* merge with the previous interval when they touch */
			if (out->open == 1 && out->nsubs && out->subs[out->nsubs - 1].n == 2) {
				scan_pt_t *last = &out->pts[out->npts - 1];
				if (last->y == y && last->x == xa) {
					last->x = xb;
					continue;
				}
			}
			if (!(rc = scan_path_move(out, xa, y)))
				rc = scan_path_draw(out, xb, y);
		}
	}
	free(cx);
	out->open = 0;
	return rc;
}
