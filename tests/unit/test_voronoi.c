/* test_voronoi.c: distances, bisectors, weights, segment nuclei, exact accelerated labels, traced boundaries. */
#include <math.h>
#include <stdlib.h>

#include "unit.h"
#include "voronoi.h"

/* Everything the boundary callback saw. */
typedef struct {
	int lines, closed;
	int32_t left[64], right[64];
	size_t n[64];
	int isclosed[64];
	voronoi_point_t *p[64];
} sink_t;

static int collect(void *user, int32_t left, int32_t right, const voronoi_point_t *p, size_t n, int closed)
{
	sink_t *s = user;
	if (s->lines < 64) {
		s->left[s->lines] = left;
		s->right[s->lines] = right;
		s->n[s->lines] = n;
		s->isclosed[s->lines] = closed;
		s->p[s->lines] = malloc(n * sizeof *p);
		memcpy(s->p[s->lines], p, n * sizeof *p);
	}
	s->lines++;
	s->closed += closed != 0;
	return 0;
}

static void sink_free(sink_t *s)
{
	for (int i = 0; i < s->lines && i < 64; i++)
		free(s->p[i]);
	memset(s, 0, sizeof *s);
}

static voronoi_nucleus_t point(double x, double y, double w)
{
	voronoi_nucleus_t n = { VORONOI_POINT, { x, y, 0 }, { 0, 0, 0 }, w, 0, NULL, 0 };
	return n;
}

static voronoi_nucleus_t segment(double x0, double y0, double x1, double y1, double w)
{
	voronoi_nucleus_t n = { VORONOI_SEGMENT, { x0, y0, 0 }, { x1, y1, 0 }, w, 0, NULL, 0 };
	return n;
}

/* Plane point of a page point for a window map (the tests' own inverse). */
static void unmap(const double m[6], double px, double py, double p[3])
{
	p[0] = (px - m[0]) / m[1];
	p[1] = (py - m[3]) / m[5];
	p[2] = 0;
}

static void test_distance(void)
{
	voronoi_nucleus_t s = { VORONOI_SEGMENT, { 0, 0, 0 }, { 4, 0, 0 }, 0, 0, NULL, 0 };
	double p1[3] = { 2, 3, 4 }, p2[3] = { -3, 4, 0 }, p3[3] = { 7, 0, 4 };
	CHECK(fabs(voronoi_distance(&s, p1) - 5) < 1e-12, "3D distance to a segment's inside is perpendicular");
	CHECK(fabs(voronoi_distance(&s, p2) - 5) < 1e-12, "beyond the first end: distance to the end");
	CHECK(fabs(voronoi_distance(&s, p3) - 5) < 1e-12, "beyond the second end: distance to the end");
	voronoi_nucleus_t pt = { VORONOI_POINT, { 1, 2, 2 }, { 0, 0, 0 }, 1.5, 0, NULL, 0 };
	double o[3] = { 0, 0, 0 };
	CHECK(fabs(voronoi_distance(&pt, o) - 3) < 1e-12, "3D distance to a point");
	CHECK(fabs(voronoi_weighted_distance(&pt, VORONOI_ADDITIVE, o) - 1.5) < 1e-12, "additive: d - w");
	CHECK(fabs(voronoi_weighted_distance(&pt, VORONOI_MULTIPLICATIVE, o) - 2) < 1e-12, "multiplicative: d / w");
	voronoi_nucleus_t deg = { VORONOI_SEGMENT, { 1, 1, 0 }, { 1, 1, 0 }, 0, 0, NULL, 0 };
	double q[3] = { 4, 5, 0 };
	CHECK(fabs(voronoi_distance(&deg, q) - 5) < 1e-12, "a zero-length segment is a point");
	voronoi_nucleus_t two[2] = { point(0, 0, 0), point(2, 0, 0) };
	double mid[3] = { 1, 5, 0 }, dw;
	CHECK(voronoi_nearest(two, 2, VORONOI_ADDITIVE, mid, &dw) == 0 && fabs(dw - sqrt(26)) < 1e-12,
	      "an exact tie goes to the lower index");
	voronoi_nucleus_t three[3] = { point(0, 0, 0), point(3, 0, 0), point(1, 0, 0.5) };
	double p0[3] = { 0.9, 0, 0 }, d1, d2;
	size_t second;
	size_t first = voronoi_nearest2(three, 3, VORONOI_ADDITIVE, p0, &d1, &second, &d2);
	CHECK(first == 2 && second == 0 && fabs(d1 + 0.4) < 1e-12 && fabs(d2 - 0.9) < 1e-12,
	      "nearest2: the weighted nearest and runner-up (%zu %g, %zu %g)", first, d1, second, d2);
	first = voronoi_nearest2(two, 2, VORONOI_ADDITIVE, mid, &d1, &second, &d2);
	CHECK(first == 0 && second == 1 && d1 == d2, "nearest2 on a tie: lower index first, the other second");
	first = voronoi_nearest2(three, 1, VORONOI_ADDITIVE, p0, &d1, &second, &d2);
	CHECK(first == 0 && second == SIZE_MAX && isinf(d2), "nearest2 of one nucleus: no runner-up");
}

/* Two points at (-1, 0) and (1, 0), window [-2, 2]^2 on 64 x 64 pixels. */
static void test_bisector(void)
{
	voronoi_nucleus_t nuc[2] = { point(-1, 0, 0), point(1, 0, 0) };
	voronoi_t v = { nuc, 2, VORONOI_ADDITIVE, { 0 } };
	voronoi_map_window(v.m, -2, -2, 2, 2, 0, 0, 64, 64);
	voronoi_rect_t r = { 0, 0, 64, 64 };
	int32_t *lab = malloc(64 * 64 * sizeof *lab);
	CHECK(voronoi_label(&v, &r, 2, lab) == 0, "two points label");
	int split = 1;
	for (int j = 0; j < 64; j++)
		for (int i = 0; i < 64; i++)
			if (lab[j * 64 + i] != (i >= 32))
				split = 0;
	CHECK(split, "pixels left of the bisector x = 32 belong to the left point, the rest to the right");
	sink_t s = { 0 };
	voronoi_stats_t st;
	CHECK(voronoi_boundaries(&v, &r, lab, collect, &s, &st) == 0, "boundaries trace");
	CHECK(s.lines == 1 && s.closed == 0 && st.junctions == 0, "one open boundary (%d lines)", s.lines);
	double worst = 0;
	for (size_t k = 0; s.lines == 1 && k < s.n[0]; k++)
		worst = fmax(worst, fabs(s.p[0][k].x - 32));
	CHECK(s.lines == 1 && worst < 1e-6, "boundary exactly on the bisector (worst %.2g pixel)", worst);
	CHECK(s.lines == 1 && s.n[0] == 66 && st.crossings == 64, "one point per pixel row, plus both ends (%zu)", s.n[0]);
	CHECK(s.lines == 1 && s.p[0][0].y == 0 && s.p[0][s.n[0] - 1].y == 64, "open ends carried to the rectangle's edges");
	CHECK(s.lines == 1 && s.left[0] == 0 && s.right[0] == 1 && s.p[0][s.n[0] - 1].y > s.p[0][0].y,
	      "oriented: the lower-index cell on the left (walks upwards)");
	sink_free(&s);

	/* additive weight 0.5 on the left point moves the boundary by 0.25 = 4 px */
	nuc[0].weight = 0.5;
	voronoi_label(&v, &r, 1, lab);
	int moved = lab[31 * 64 + 35] == 0 && lab[31 * 64 + 36] == 1 && lab[32 * 64 + 35] == 0 && lab[32 * 64 + 36] == 1;
	CHECK(moved, "additive weight w moves the boundary w/2 away from the heavier nucleus");
	voronoi_boundaries(&v, &r, lab, collect, &s, NULL);
	double wmid = 99, werr = 0;
	for (size_t k = 1; s.lines == 1 && k + 1 < s.n[0]; k++) { /* the ends are extrapolated */
		double p[3];
		unmap(v.m, s.p[0][k].x, s.p[0][k].y, p);
		werr = fmax(werr, fabs((voronoi_distance(&nuc[0], p) - 0.5) - voronoi_distance(&nuc[1], p)));
		if (fabs(p[1]) < fabs(wmid))
			wmid = p[1], moved = fabs(p[0] - 0.25) < 0.01;
	}
	CHECK(s.lines == 1 && werr < 1e-6 && moved, "boundary points on the hyperbola d0 - 0.5 = d1 (error %.2g)", werr);
	sink_free(&s);
	free(lab);
}

static void test_multiplicative(void)
{
	/* d0 / 2 = d1: the Apollonius circle of centre (5/3, 0), radius 4/3 */
	voronoi_nucleus_t nuc[2] = { point(-1, 0, 2), point(1, 0, 1) };
	voronoi_t v = { nuc, 2, VORONOI_MULTIPLICATIVE, { 0 } };
	voronoi_map_window(v.m, -2, -3, 4, 3, 0, 0, 120, 120);
	voronoi_rect_t r = { 0, 0, 120, 120 };
	int32_t *lab = malloc(120 * 120 * sizeof *lab);
	sink_t s = { 0 };
	CHECK(voronoi_label(&v, &r, 0, lab) == 0 && voronoi_boundaries(&v, &r, lab, collect, &s, NULL) == 0,
	      "multiplicative tessellation traces");
	CHECK(s.lines == 1 && s.closed == 1, "the weaker point's cell is a closed loop (%d lines, %d closed)",
	      s.lines, s.closed);
	double worst = 0;
	for (size_t k = 0; s.lines == 1 && k < s.n[0]; k++) {
		double p[3];
		unmap(v.m, s.p[0][k].x, s.p[0][k].y, p);
		worst = fmax(worst, fabs(hypot(p[0] - 5.0 / 3, p[1]) - 4.0 / 3));
	}
	CHECK(s.lines == 1 && worst < 1e-6, "loop on the Apollonius circle (worst %.2g)", worst);
	sink_free(&s);
	nuc[1].weight = 0;
	CHECK(voronoi_label(&v, &r, 0, lab) == VORONOI_EARG && strstr(voronoi_error(), "nucleus 1"),
	      "a zero multiplicative weight is refused: %s", voronoi_error());
	free(lab);
}

static void test_segments_and_junctions(void)
{
	/* a vertical segment x = -1, |y| <= 1 and the point (1, 0): the boundary
	 * is x = 0 at y = 0 and bends into a parabola beyond the segment */
	voronoi_nucleus_t nuc[3] = { segment(-1, -1, -1, 1, 0), point(1, 0, 0), point(0, 3, 0) };
	voronoi_t v = { nuc, 2, VORONOI_ADDITIVE, { 0 } };
	voronoi_map_window(v.m, -4, -4, 4, 4, 0, 0, 128, 128);
	voronoi_rect_t r = { 0, 0, 128, 128 };
	int32_t *lab = malloc(128 * 128 * sizeof *lab);
	sink_t s = { 0 };
	voronoi_label(&v, &r, 2, lab);
	voronoi_boundaries(&v, &r, lab, collect, &s, NULL);
	double worst = 0, at0 = 0;
	for (size_t k = 0; s.lines == 1 && k < s.n[0]; k++) {
		double p[3];
		unmap(v.m, s.p[0][k].x, s.p[0][k].y, p);
		worst = fmax(worst, fabs(voronoi_distance(&nuc[0], p) - voronoi_distance(&nuc[1], p)));
		if (fabs(p[1]) <= 1)
			at0 = fmax(at0, fabs(p[0] - p[1] * p[1] / 4));
	}
	CHECK(s.lines == 1 && worst < 1e-6 && at0 < 1e-6,
	      "segment vs point: equidistant boundary (error %.2g), x = y^2/4 beside the segment (%.2g)", worst, at0);
	sink_free(&s);
	/* a third nucleus: three boundaries meeting at one junction */
	v.count = 3;
	voronoi_stats_t st;
	voronoi_label(&v, &r, 2, lab);
	voronoi_boundaries(&v, &r, lab, collect, &s, &st);
	CHECK(s.lines == 3 && s.closed == 0 && st.junctions >= 1, "three cells: 3 boundaries (%d), %zu junction cells",
	      s.lines, st.junctions);
	int meet = s.lines == 3;
	for (int a = 0; a < s.lines && a < 3; a++) {
		/* one end of each boundary is at the junction: near the other boundaries' ends */
		int found = 0;
		for (int e = 0; e < 2; e++) {
			voronoi_point_t q = e ? s.p[a][s.n[a] - 1] : s.p[a][0];
			for (int b = 0; b < s.lines && b < 3; b++)
				for (int f = 0; b != a && f < 2; f++) {
					voronoi_point_t o = f ? s.p[b][s.n[b] - 1] : s.p[b][0];
					if (q.x == o.x && q.y == o.y)
						found = 1;
				}
		}
		meet &= found;
	}
	CHECK(meet, "the three boundaries share their junction end point");
	double jerr = 1;
	for (int e = 0; s.lines == 3 && e < 2; e++) {
		voronoi_point_t q = e ? s.p[0][s.n[0] - 1] : s.p[0][0];
		double p[3];
		unmap(v.m, q.x, q.y, p);
		double d0 = voronoi_distance(&nuc[0], p), d1 = voronoi_distance(&nuc[1], p), d2 = voronoi_distance(&nuc[2], p);
		jerr = fmin(jerr, fmax(fabs(d0 - d1), fabs(d0 - d2)));
	}
	CHECK(jerr < 1e-6, "the junction is the Voronoi vertex, equidistant from all three (error %.2g)", jerr);
	int sides = 1;
	for (int a = 0; a < s.lines && a < 3; a++) {
		/* interior points are exact crossings: left and right equidistant */
		for (size_t k = 1; k + 1 < s.n[a]; k++) {
			double p[3];
			unmap(v.m, s.p[a][k].x, s.p[a][k].y, p);
			if (fabs(voronoi_distance(&nuc[s.left[a]], p) - voronoi_distance(&nuc[s.right[a]], p)) > 1e-6) {
				if (sides)
					printf("# line %d (%d|%d) point %zu of %zu: %g %g\n", a, s.left[a], s.right[a], k, s.n[a], p[0], p[1]);
				sides = 0;
			}
		}
	}
	CHECK(sides, "left/right labels name the two cells each boundary separates");
	sink_free(&s);
	free(lab);
}

/* Checks every boundary polyline of a tessellation as it arrives. */
typedef struct {
	const voronoi_t *v;
	size_t on_lines;   /* points on a pixel-centre line (crossings), not on the rectangle edge */
	size_t lines;
	int bad;
} bcheck_t;

static int bcheck(void *user, int32_t left, int32_t right, const voronoi_point_t *p, size_t n, int closed)
{
	bcheck_t *b = user;
	const voronoi_t *v = b->v;
	(void)closed;
	b->lines++;
	if (left == right || left < 0 || right < 0 || (size_t)left >= v->count || (size_t)right >= v->count)
		b->bad++;
	for (size_t k = 0; k < n; k++) {
		double fx = p[k].x - 0.5 - floor(p[k].x - 0.5), fy = p[k].y - 0.5 - floor(p[k].y - 0.5);
		if (fx == 0 || fy == 0)
			b->on_lines++;
		if (k == 0 || k + 1 == n)
			continue; /* ends: junctions or extrapolated to the edge */
		double q[3] = { (p[k].x - v->m[0]) / v->m[1], (p[k].y - v->m[3]) / v->m[5], 0 };
		double dl = voronoi_weighted_distance(&v->nuclei[left], v->metric, q);
		double dr = voronoi_weighted_distance(&v->nuclei[right], v->metric, q);
		if (fabs(dl - dr) > 1e-6)
			b->bad++;
	}
	return 0;
}

/* Accelerated labels equal brute force at every pixel, for any thread count. */
static void test_exact(void)
{
	enum { N = 40, W = 97, H = 83 };
	voronoi_nucleus_t nuc[N];
	unsigned long long r = 0x9e3779b97f4a7c15ULL;
	double u[6];
	for (int k = 0; k < N; k++) {
		for (int q = 0; q < 6; q++) {
			r ^= r << 13; r ^= r >> 7; r ^= r << 17;
			u[q] = (r >> 11) * (1.0 / 9007199254740992.0);
		}
		nuc[k] = k % 3 ? point(u[0] * 10, u[1] * 8, u[4] * 0.8)
		               : segment(u[0] * 10, u[1] * 8, u[0] * 10 + u[2] - 0.5, u[1] * 8 + u[3] - 0.5, u[4] * 0.8);
		nuc[k].colour = (meta_rgb_t)(r & 0xffffff);
	}
	for (int metric = 0; metric < 2; metric++) {
		if (metric == VORONOI_MULTIPLICATIVE)
			for (int k = 0; k < N; k++)
				nuc[k].weight += 0.6;
		voronoi_t v = { nuc, N, metric, { 0 } };
		voronoi_map_window(v.m, 0, 0, 10, 8, 3, 5, 3 + W, 5 + H);
		voronoi_rect_t rc = { 3, 5, W, H };
		int32_t *a = malloc(W * H * sizeof *a), *b = malloc(W * H * sizeof *b);
		voronoi_label(&v, &rc, 1, a);
		voronoi_label(&v, &rc, 3, b);
		int bad = 0, same = memcmp(a, b, W * H * sizeof *a) == 0;
		for (int j = 0; j < H; j++)
			for (int i = 0; i < W; i++) {
				double p[3], dw;
				unmap(v.m, 3 + i + 0.5, 5 + j + 0.5, p);
				size_t want = voronoi_nearest(nuc, N, metric, p, &dw);
				if ((size_t)a[j * W + i] != want &&
				    fabs(voronoi_weighted_distance(&nuc[a[j * W + i]], metric, p) - dw) > 1e-12)
					bad++;
			}
		CHECK(bad == 0, "%s: culled labels equal brute force (%d pixels differ)",
		      metric ? "multiplicative" : "additive", bad);
		CHECK(same, "%s: 1 and 3 threads give the same labels", metric ? "multiplicative" : "additive");
		bcheck_t bc = { &v, 0, 0, 0 };
		voronoi_stats_t st;
		CHECK(voronoi_boundaries(&v, &rc, a, bcheck, &bc, &st) == 0, "random boundaries trace");
		CHECK(bc.on_lines == st.crossings, "%s: one point per crossed pixel edge (%zu, %zu)",
		      metric ? "multiplicative" : "additive", bc.on_lines, st.crossings);
		CHECK(bc.bad == 0 && bc.lines == st.polylines, "%s: %zu polylines, interior points equidistant from left and right",
		      metric ? "multiplicative" : "additive", bc.lines);
		free(a);
		free(b);
	}
}

/* Output through the meta writer into memory. */
typedef struct {
	char buf[1 << 16];
	size_t n;
} mem_t;

static int mem_write(void *user, const void *p, size_t n)
{
	mem_t *m = user;
	if (m->n + n >= sizeof m->buf)
		return -1;
	memcpy(m->buf + m->n, p, n);
	m->n += n;
	m->buf[m->n] = 0;
	return 0;
}

static void test_meta(void)
{
	static mem_t mem;
	voronoi_nucleus_t nuc[2] = { point(-1, 0, 0), point(1, 0, 0) };
	nuc[0].colour = 0xff0000;
	nuc[1].colour = 0x0000ff;
	voronoi_t v = { nuc, 2, VORONOI_ADDITIVE, { 0 } };
	voronoi_map_window(v.m, -2, -2, 2, 2, 0, 0, 8, 8);
	voronoi_rect_t r = { 0, 0, 8, 8 };
	voronoi_style_t st = { 1, 1, 0x00ff00, 0.5, 1, 0, 0, 0 };
	meta_writer_t *w = meta_writer_new(mem_write, &mem, META_ENC_TEXT);
	int rc = meta_page(w, 8, 8);
	rc = rc < 0 ? rc : voronoi_write_meta(w, &v, &r, &st, NULL);
	rc = rc < 0 ? rc : meta_end_page(w);
	int rc2 = meta_writer_close(w);
	CHECK(rc == 0 && rc2 == 0, "cells and boundaries written (%d: %s)", rc, voronoi_error());
	CHECK(strstr(mem.buf, "image 0 0 8 8\nrow 4 #ff0000 4 #0000ff\n") != NULL, "cells as image rows");
	CHECK(strstr(mem.buf, "colour #00ff00\nwidth 0.5\nstroke\nmove 4 0\n") &&
	      strstr(mem.buf, "draw 4 8\nend\n"),
	      "boundary as one stroke on x = 4");
}

/* Cells alone are written in bands; the picture equals the one-piece labelling. */
static void test_banded(void)
{
	static mem_t a, b;
	voronoi_nucleus_t nuc[4] = { point(0.3, 0.2, 0), point(0.7, 0.8, 0.05), segment(0.1, 0.9, 0.4, 0.6, 0), point(0.9, 0.1, 0) };
	for (int k = 0; k < 4; k++)
		nuc[k].colour = 0x102030 * (meta_rgb_t)(k + 1);
	voronoi_t v = { nuc, 4, VORONOI_ADDITIVE, { 0 } };
	voronoi_map_window(v.m, 0, 0, 1, 1, 0, 0, 90, 150);
	voronoi_rect_t r = { 0, 0, 90, 150 };
	meta_writer_t *w = meta_writer_new(mem_write, &a, META_ENC_TEXT);
	int rc = meta_page(w, 90, 150);
	rc = rc < 0 ? rc : voronoi_write_cells(w, &v, &r, 2);
	rc = rc < 0 ? rc : meta_end_page(w);
	meta_writer_close(w);
	/* reference: the image written from one full label buffer */
	int32_t *lab = malloc(90 * 150 * sizeof *lab);
	voronoi_label(&v, &r, 1, lab);
	w = meta_writer_new(mem_write, &b, META_ENC_TEXT);
	meta_page(w, 90, 150);
	meta_image(w, 0, 0, 90, 150);
	for (int k = 149; k >= 0; k--) {
		meta_rgb_t row[90];
		for (int i = 0; i < 90; i++)
			row[i] = nuc[lab[k * 90 + i]].colour;
		meta_row_pixels(w, row, 90);
	}
	meta_end_page(w);
	meta_writer_close(w);
	free(lab);
	CHECK(rc == 0 && a.n == b.n && memcmp(a.buf, b.buf, a.n) == 0, "banded cells equal the one-piece image (%zu bytes)",
	      a.n);
}

static void test_edges(void)
{
	voronoi_nucleus_t one = point(0, 0, 0);
	voronoi_t v = { &one, 1, VORONOI_ADDITIVE, { 0 } };
	voronoi_map_window(v.m, -1, -1, 1, 1, 0, 0, 20, 20);
	voronoi_rect_t r = { 0, 0, 20, 20 };
	int32_t lab[400];
	sink_t s = { 0 };
	voronoi_stats_t st;
	int all0 = voronoi_label(&v, &r, 0, lab) == 0;
	for (int q = 0; q < 400; q++)
		all0 &= lab[q] == 0;
	CHECK(all0 && voronoi_boundaries(&v, &r, lab, collect, &s, &st) == 0 && s.lines == 0 && st.crossings == 0,
	      "one nucleus: one cell, no boundaries");
	lab[123] = 5;
	CHECK(voronoi_boundaries(&v, &r, lab, collect, &s, NULL) == VORONOI_EARG && strstr(voronoi_error(), "(3, 6)"),
	      "a label that is no nucleus is refused: %s", voronoi_error());
	voronoi_rect_t thin = { 4, 4, 1, 9 };
	CHECK(voronoi_label(&v, &thin, 3, lab) == 0 && voronoi_boundaries(&v, &thin, lab, collect, &s, NULL) == 0 &&
	      s.lines == 0, "a one-pixel-wide rectangle labels and has no boundary cells");
	v.count = 0;
	CHECK(voronoi_label(&v, &r, 1, lab) == VORONOI_EARG && strstr(voronoi_error(), "no nuclei"),
	      "no nuclei is refused: %s", voronoi_error());
	v.count = 1;
	v.m[1] = 0;
	CHECK(voronoi_label(&v, &r, 1, lab) == VORONOI_EARG && strstr(voronoi_error(), "invertible"),
	      "a singular map is refused: %s", voronoi_error());
	v.m[1] = 10;
	one.kind = 7;
	CHECK(voronoi_check(&v) == VORONOI_EARG && strstr(voronoi_error(), "kind 7"), "an unknown kind is refused: %s",
	      voronoi_error());
	one.kind = VORONOI_POINT;
	v.metric = 9;
	CHECK(voronoi_check(&v) == VORONOI_EARG, "an unknown metric is refused: %s", voronoi_error());
}

int main(void)
{
	test_distance();
	test_bisector();
	test_multiplicative();
	test_segments_and_junctions();
	test_exact();
	test_meta();
	test_banded();
	test_edges();
	return UNIT_DONE();
}
