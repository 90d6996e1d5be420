/* hpgl_geom.c: polyline geometry for the plotter: clipping, dashes by the spec's rules, sideways
 * offsets for wide-line passes, and drag-knife compensation with overcut. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "util/grow.h"
#include "hpgl/hpgl.h"
#include "locus_meta.h"

/* A growing point buffer. */
typedef struct {
	hpgl_dpt_t *p;
	size_t n, cap;
} buf_t;

static int put(buf_t *b, double x, double y)
{
	if (b->n && b->p[b->n - 1].x == x && b->p[b->n - 1].y == y)
		return 0;
	if (dev_grow((void **)&b->p, &b->cap, b->n + 1, sizeof *b->p, 64))
		return -1;
	b->p[b->n++] = (hpgl_dpt_t){ x, y };
	return 0;
}

static int flush(buf_t *b, hpgl_poly_fn fn, void *user, int closed)
{
	int rc = 0;
	if (b->n >= 2)
		rc = fn(user, b->p, b->n, closed);
	b->n = 0;
	return rc;
}

/* Liang-Barsky: clip segment p->q to r; 1 with the parameter range when visible. */
static int clip_seg(hpgl_dpt_t p, hpgl_dpt_t q, const double r[4], double *t0, double *t1)
{
	double dx = q.x - p.x, dy = q.y - p.y, a = 0, b = 1;
	double pp[4] = { -dx, dx, -dy, dy }, qq[4] = { p.x - r[0], r[2] - p.x, p.y - r[1], r[3] - p.y };
	for (int i = 0; i < 4; i++) {
		if (pp[i] == 0) {
			if (qq[i] < 0)
				return 0;
			continue;
		}
		double t = qq[i] / pp[i];
		if (pp[i] < 0) {
			if (t > b)
				return 0;
			if (t > a)
				a = t;
		} else {
			if (t < a)
				return 0;
			if (t < b)
				b = t;
		}
	}
	*t0 = a;
	*t1 = b;
	return 1;
}

int hpgl_clip_poly(const hpgl_dpt_t *pts, size_t n, int closed, const double r[4],
		hpgl_poly_fn fn, void *user)
{
	int inside = 1;
	for (size_t i = 0; i < n && inside; i++)
		inside = pts[i].x >= r[0] && pts[i].x <= r[2] && pts[i].y >= r[1] && pts[i].y <= r[3];
	if (inside)
		return n >= 2 ? fn(user, pts, n, closed) : 0;
	buf_t b = { 0 };
	int rc = 0;
	size_t segs = closed ? n : n - 1;
	for (size_t i = 0; i < segs && !rc; i++) {
		hpgl_dpt_t p = pts[i], q = pts[(i + 1) % n];
		double t0, t1;
		if (!clip_seg(p, q, r, &t0, &t1)) {
			rc = flush(&b, fn, user, 0);
			continue;
		}
		hpgl_dpt_t a = { p.x + t0 * (q.x - p.x), p.y + t0 * (q.y - p.y) };
		hpgl_dpt_t e = { p.x + t1 * (q.x - p.x), p.y + t1 * (q.y - p.y) };
		if (t0 > 0)
			rc = flush(&b, fn, user, 0);
		if (!rc && (put(&b, a.x, a.y) || put(&b, e.x, e.y)))
			rc = -1;
		if (!rc && t1 < 1)
			rc = flush(&b, fn, user, 0);
	}
	if (!rc)
		rc = flush(&b, fn, user, 0);
	free(b.p);
	return rc;
}

size_t hpgl_offset_poly(const hpgl_dpt_t *pts, size_t n, int closed, double dist, hpgl_dpt_t *out)
{
	size_t m = 0;
	for (size_t i = 0; i < n; i++) {
		/* unit left normals of the segments before (a) and after (b) vertex i */
		double ax = 0, ay = 0, bx = 0, by = 0;
		if (closed || i > 0) {
			hpgl_dpt_t p = pts[(i + n - 1) % n], q = pts[i];
			double L = hypot(q.x - p.x, q.y - p.y);
			if (L > 0) {
				ax = -(q.y - p.y) / L;
				ay = (q.x - p.x) / L;
			}
		}
		if (closed || i + 1 < n) {
			hpgl_dpt_t p = pts[i], q = pts[(i + 1) % n];
			double L = hypot(q.x - p.x, q.y - p.y);
			if (L > 0) {
				bx = -(q.y - p.y) / L;
				by = (q.x - p.x) / L;
			}
		}
		int both = (ax || ay) && (bx || by);
		double c = ax * bx + ay * by;
		double z = ax * by - ay * bx;   /* > 0: a left turn, whose outer side is the right */
		if (both && c < -0.5 && z * dist <= 0) {   /* sharp, outer side (or a reversal): bevel */
			out[m++] = (hpgl_dpt_t){ pts[i].x + dist * ax, pts[i].y + dist * ay };
			out[m++] = (hpgl_dpt_t){ pts[i].x + dist * bx, pts[i].y + dist * by };
		} else if (both) {   /* the offset lines' intersection, at most 4 x dist away */
			double k = 1 + c < 0.125 ? 0.125 : 1 + c;
			out[m++] = (hpgl_dpt_t){ pts[i].x + dist * (ax + bx) / k, pts[i].y + dist * (ay + by) / k };
		} else {
			out[m++] = (hpgl_dpt_t){ pts[i].x + dist * (ax + bx), pts[i].y + dist * (ay + by) };
		}
	}
	return m;
}

/* Move end e of a pass (0: first point, 1: last) outward by ext along its end segment. */
static void extend_end(hpgl_dpt_t *pts, size_t n, int e, double ext)
{
	hpgl_dpt_t *a = &pts[e ? n - 1 : 0];
	for (size_t k = 1; k < n; k++) {   /* the nearest point that differs gives the direction */
		const hpgl_dpt_t *b = &pts[e ? n - 1 - k : k];
		double dx = a->x - b->x, dy = a->y - b->y, L = hypot(dx, dy);
		if (L > 0) {
			a->x += ext * dx / L;
			a->y += ext * dy / L;
			return;
		}
	}
}

void hpgl_cap_pass(hpgl_dpt_t *pts, size_t n, int cap, double r, double pen, double dist)
{
	double ext;
	if (n < 2 || cap == META_CAP_BUTT)
		return;
	if (cap == META_CAP_SQUARE)
		ext = r - pen / 2;
	else   /* the chord of the cap's half disc along the pass, less the pen tip's reach */
		ext = (fabs(dist) < r ? sqrt(r * r - dist * dist) : 0) - pen / 2;
	if (ext <= 0)
		return;
	extend_end(pts, n, 0, ext);
	extend_end(pts, n, 1, ext);
}

/* Append an arc about c of radius r from direction a0 to a1 (radians), the shorter way. */
static int arc(buf_t *b, hpgl_dpt_t c, double r, double a0, double a1)
{
	double sweep = a1 - a0;
	while (sweep > M_PI)
		sweep -= 2 * M_PI;
	while (sweep < -M_PI)
		sweep += 2 * M_PI;
	int steps = (int)ceil(fabs(sweep) / (M_PI / 12));   /* 15 degree chords */
	for (int k = 1; k <= steps; k++) {
		double a = a0 + sweep * k / steps;
		if (put(b, c.x + r * cos(a), c.y + r * sin(a)))
			return -1;
	}
	return 0;
}

int hpgl_knife_poly(const hpgl_dpt_t *pts, size_t n, int closed, double offset, double overcut,
		hpgl_poly_fn fn, void *user)
{
	buf_t src = { 0 }, b = { 0 };
	int rc = -1;
	/* the cut path without repeated points, a closed one extended by the overcut */
	for (size_t i = 0; i < n; i++)
		if (put(&src, pts[i].x, pts[i].y))
			goto done;
	if (closed && src.n > 2) {
		if (put(&src, pts[0].x, pts[0].y))
			goto done;
		double left = overcut;
		for (size_t i = 0; i + 1 < n && left > 0; i++) {
			hpgl_dpt_t p = pts[i], q = pts[i + 1];
			double L = hypot(q.x - p.x, q.y - p.y);
			if (L <= 0)
				continue;
			double f = left >= L ? 1 : left / L;
			if (put(&src, p.x + f * (q.x - p.x), p.y + f * (q.y - p.y)))
				goto done;
			left -= L;
		}
	}
	if (src.n < 2 || offset <= 0) {
		rc = src.n >= 2 ? fn(user, src.p, src.n, 0) : 0;
		goto done;
	}
	double prev = 0;
	for (size_t i = 0; i + 1 < src.n; i++) {
		hpgl_dpt_t p = src.p[i], q = src.p[i + 1];
		double L = hypot(q.x - p.x, q.y - p.y);
		if (L <= 0)
			continue;
		double dx = (q.x - p.x) / L, dy = (q.y - p.y) / L, a = atan2(dy, dx);
		if (b.n == 0) {
			if (put(&b, p.x, p.y))   /* the blade starts at the path's first point */
				goto done;
			if (put(&b, p.x + offset * dx, p.y + offset * dy))
				goto done;
		} else if (arc(&b, p, offset, prev, a)) {
			goto done;
		}
		if (put(&b, q.x + offset * dx, q.y + offset * dy))
			goto done;
		prev = a;
	}
	rc = b.n >= 2 ? fn(user, b.p, b.n, 0) : 0;
done:
	free(src.p);
	free(b.p);
	return rc;
}
