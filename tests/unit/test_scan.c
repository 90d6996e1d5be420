/* test_scan.c: polygon coverage rules of spec §5.1 against exact brute force, and banding. */
#include <math.h>
#include <stdlib.h>
#include "geom/scan.h"
#include "render/render.h"
#include "unit.h"

#define W 40
#define H 30

static uint8_t pix[W * H * 3];
static scan_band_t band = { pix, W * 3, W, H, 0, H };

static void clear(void)
{
	memset(pix, 0xff, sizeof pix);
}

/* 1 if pixel (i, j) (j from the bottom) is not white. */
static int on(int i, int j)
{
	const uint8_t *p = pix + (size_t)(H - 1 - j) * W * 3 + (size_t)i * 3;
	return !(p[0] == 0xff && p[1] == 0xff && p[2] == 0xff);
}

static uint32_t colour_at(int i, int j)
{
	const uint8_t *p = pix + (size_t)(H - 1 - j) * W * 3 + (size_t)i * 3;
	return (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
}

static void poly(scan_path_t *p, const double *xy, size_t n)
{
	scan_path_move(p, (int64_t)(xy[0] * 1000), (int64_t)(xy[1] * 1000));
	for (size_t k = 1; k < n; k++)
		scan_path_draw(p, (int64_t)(xy[2 * k] * 1000), (int64_t)(xy[2 * k + 1] * 1000));
}

/* Winding number of point (xc, yc) by the letter of §5.1, exact with 128-bit arithmetic. */
static int winding(const scan_path_t *p, int64_t xc, int64_t yc)
{
	int w = 0;
	for (size_t s = 0; s < p->nsubs; s++) {
		const scan_pt_t *q = p->pts + p->subs[s].start;
		size_t n = p->subs[s].n;
		for (size_t k = 0; k < n; k++) {
			scan_pt_t a = q[k], b = q[(k + 1) % n];
			if (a.y == b.y)
				continue;
			int64_t lo = a.y < b.y ? a.y : b.y, hi = a.y < b.y ? b.y : a.y;
			if (!(lo <= yc && yc < hi))
				continue;
			/* X <= xc  <=>  x0*(y1-y0) + (yc-y0)(x1-x0) <= xc*(y1-y0), sign of (y1-y0) */
			__int128 dy = b.y - a.y;
			__int128 lhs = (__int128)a.x * dy + (__int128)(yc - a.y) * (b.x - a.x);
			__int128 rhs = (__int128)xc * dy;
			int le = dy > 0 ? lhs <= rhs : lhs >= rhs;
			if (le)
				w += b.y > a.y ? 1 : -1;
		}
	}
	return w;
}

static int brute_matches(const scan_path_t *p, int rule)
{
	for (int j = 0; j < H; j++)
		for (int i = 0; i < W; i++) {
			int w = winding(p, 1000 * i + 500, 1000 * j + 500);
			int want = rule == META_RULE_EVEN_ODD ? (w & 1) : (w != 0);
			if (want != on(i, j)) {
				printf("# pixel (%d,%d): winding %d, painted %d\n", i, j, w, on(i, j));
				return 0;
			}
		}
	return 1;
}

static void test_rectangles(scan_ctx_t *c)
{
	scan_path_t p = { 0 };
	/* a rectangle paints exactly the pixels whose centres lie in [a, c) x [b, d) */
	double r1[] = { 2, 3, 7, 3, 7, 8, 2, 8 };
	clear();
	poly(&p, r1, 4);
	scan_fill(c, &band, &p, META_RULE_NON_ZERO, 0);
	int ok = 1, count = 0;
	for (int j = 0; j < H; j++)
		for (int i = 0; i < W; i++) {
			int want = i >= 2 && i < 7 && j >= 3 && j < 8;
			ok &= want == on(i, j);
			count += on(i, j);
		}
	CHECK(ok && count == 25, "integer rectangle (2,3)-(7,8) paints exactly 5x5 pixels (%d)", count);

	/* fractional: centres 1.5 .. 4.5 in [1.5, 4.6) -> i = 1..4; y [0.5, 1.5) -> j = 0 only */
	double r2[] = { 1.5, 0.5, 4.6, 0.5, 4.6, 1.5, 1.5, 1.5 };
	clear();
	scan_path_reset(&p);
	poly(&p, r2, 4);
	scan_fill(c, &band, &p, META_RULE_NON_ZERO, 0);
	CHECK(on(1, 0) && on(4, 0) && !on(0, 0) && !on(5, 0) && !on(1, 1), "half-open rule at centres on the edges");
	CHECK(brute_matches(&p, META_RULE_NON_ZERO), "fractional rectangle matches brute force");

	/* clockwise gives the same pixels */
	double r3[] = { 2, 3, 2, 8, 7, 8, 7, 3 };
	clear();
	scan_path_reset(&p);
	poly(&p, r3, 4);
	scan_fill(c, &band, &p, META_RULE_EVEN_ODD, 0);
	CHECK(on(2, 3) && on(6, 7) && !on(7, 7) && !on(6, 8), "clockwise rectangle, even-odd");
	scan_path_free(&p);
}

static void test_shared_edges(scan_ctx_t *c)
{
	/* a fan of triangles around an interior point, each its own colour: every pixel of the
	 * hexagon painted exactly once (painting in order, no pixel of an earlier triangle may be
	 * overwritten, and no gap may remain) */
	double cx = 20.3, cy = 14.7;
	double ring[] = { 3.2, 2.1, 35.7, 4.4, 38.1, 17.9, 26.6, 28.2, 5.5, 26.9, 1.3, 13.3 };
	uint8_t count[W * H];
	memset(count, 0, sizeof count);
	scan_path_t p = { 0 }, all = { 0 };
	for (int k = 0; k < 6; k++) {
		double t[] = { cx, cy, ring[2 * k], ring[2 * k + 1], ring[(2 * k + 2) % 12], ring[(2 * k + 3) % 12] };
		clear();
		scan_path_reset(&p);
		poly(&p, t, 3);
		scan_fill(c, &band, &p, META_RULE_NON_ZERO, 0x102030);
		for (int j = 0; j < H; j++)
			for (int i = 0; i < W; i++)
				count[j * W + i] += (uint8_t)on(i, j);
	}
	clear();
	poly(&all, ring, 6);
	scan_fill(c, &band, &all, META_RULE_NON_ZERO, 0);
	int twice = 0, gap = 0, outside = 0;
	for (int j = 0; j < H; j++)
		for (int i = 0; i < W; i++) {
			int n = count[j * W + i];
			twice += n > 1;
			gap += on(i, j) && n == 0;
			outside += !on(i, j) && n > 0;
		}
	CHECK(twice == 0, "triangles sharing edges paint no pixel twice (%d)", twice);
	CHECK(gap == 0 && outside == 0, "their union is exactly the hexagon (%d gaps, %d outside)", gap, outside);
	scan_path_free(&p);
	scan_path_free(&all);
}

static void test_rules(scan_ctx_t *c)
{
	/* the thesis' figs 2.1 / 2.2: a self-intersecting five-pointed star */
	double star[10];
	for (int k = 0; k < 5; k++) {
		double a = M_PI / 2 + k * 4 * M_PI / 5;
		star[2 * k] = 20 + 13 * cos(a);
		star[2 * k + 1] = 15 + 13 * sin(a);
	}
	scan_path_t p = { 0 };
	poly(&p, star, 5);
	clear();
	scan_fill(c, &band, &p, META_RULE_NON_ZERO, 0);
	CHECK(on(20, 15) && on(19, 22), "non-zero: the star's centre and a point are painted");
	CHECK(brute_matches(&p, META_RULE_NON_ZERO), "non-zero star matches brute force");
	clear();
	scan_fill(c, &band, &p, META_RULE_EVEN_ODD, 0);
	CHECK(!on(20, 15) && on(19, 22), "even-odd: the star's centre (winding 2) is a hole");
	CHECK(brute_matches(&p, META_RULE_EVEN_ODD), "even-odd star matches brute force");

	/* a square with a square hole: inner contour the same way round / the other way round */
	double outer[] = { 5, 5, 35, 5, 35, 25, 5, 25 };
	double same[] = { 15, 10, 25, 10, 25, 20, 15, 20 };
	double other[] = { 15, 10, 15, 20, 25, 20, 25, 10 };
	scan_path_reset(&p);
	poly(&p, outer, 4);
	poly(&p, same, 4);
	clear();
	scan_fill(c, &band, &p, META_RULE_NON_ZERO, 0);
	CHECK(on(20, 15) && on(6, 6), "non-zero, inner contour same direction: no hole");
	clear();
	scan_fill(c, &band, &p, META_RULE_EVEN_ODD, 0);
	CHECK(!on(20, 15) && on(6, 6) && on(14, 15) && !on(15, 15), "even-odd: hole [15,25)x[10,20)");
	scan_path_reset(&p);
	poly(&p, outer, 4);
	poly(&p, other, 4);
	clear();
	scan_fill(c, &band, &p, META_RULE_NON_ZERO, 0);
	CHECK(!on(20, 15) && on(6, 6), "non-zero, inner contour reversed: hole");
	scan_path_free(&p);
}

static void test_random(scan_ctx_t *c)
{
	/* random polygons (some with huge and negative coordinates) against brute force */
	srand(12345);
	int bad = 0;
	scan_path_t p = { 0 };
	for (int t = 0; t < 300 && !bad; t++) {
		scan_path_reset(&p);
		int ncont = 1 + rand() % 2;
		for (int k = 0; k < ncont; k++) {
			int n = 3 + rand() % 9;
			for (int v = 0; v < n; v++) {
				int64_t x = rand() % 50000 - 5000, y = rand() % 40000 - 5000;
				if (t % 10 == 0 && v == 0)
					x = (rand() % 2 ? 1 : -1) * (int64_t)999999000;
				if (t % 7 == 0)
					y = y / 1000 * 1000 + 500;   /* vertices exactly on centre rows */
				v ? scan_path_draw(&p, x, y) : scan_path_move(&p, x, y);
			}
		}
		int rule = t % 2 ? META_RULE_EVEN_ODD : META_RULE_NON_ZERO;
		clear();
		scan_fill(c, &band, &p, rule, 0x00ff00);
		bad = !brute_matches(&p, rule);
	}
	CHECK(!bad, "300 random polygons (both rules, huge coordinates) match brute force");
	scan_path_free(&p);
}

/* Banded and whole-page renderings of the same statements must agree. */
static uint8_t whole[W * H * 3];
static size_t got_rows;

static int keep_band(void *user, const render_band_t *b)
{
	uint8_t *dst = user;
	for (unsigned k = 0; k < b->nrows; k++)
		memcpy(dst + (size_t)(b->y0 + k) * W * 3, b->pix + k * b->stride, W * 3);
	got_rows += b->nrows;
	return 0;
}

static void scene(render_t *r)
{
	scan_path_t p = { 0 };
	double t[] = { 1, 1, 39, 3, 20, 29 };
	poly(&p, t, 3);
	render_clear(r, 0xeeeeee);
	render_fill(r, &p, META_RULE_NON_ZERO, 0xff0000);
	scan_path_reset(&p);
	double l[] = { 2, 25, 30, 5, 38, 28 };
	poly(&p, l, 3);
	int64_t dash[2] = { 4000, 2000 };
	scan_style_t st = { 3000, META_CAP_ROUND, META_JOIN_MITER, 10000, dash, 2 };
	render_stroke(r, &p, &st, 0x0000ff);
	scan_path_reset(&p);
	scan_text_path(&p, "Ab", 2, 3000, 3000, 8000, 15000);
	scan_style_t ts = { 1000, META_CAP_ROUND, META_JOIN_ROUND, 10000, NULL, 0 };
	render_stroke(r, &p, &ts, 0x000000);
	render_span(r, 5, 12, 30, 0x00ff00);
	meta_run_t runs[2] = { { 3, 0x123456 }, { 50, 0x654321 } };
	render_row(r, 30, 29, runs, 2);
	scan_path_free(&p);
}

static void test_bands(void)
{
	char err[200];
	uint8_t banded[W * H * 3];
	render_t *r = render_new(W, H, 0, 64 << 20, err, sizeof err);
	CHECK(r && render_bands(r) == 1, "a small page is one band");
	scene(r);
	got_rows = 0;
	render_finish(r, keep_band, whole);
	render_free(r);
	for (unsigned rows = 1; rows <= 8; rows += 3) {
		r = render_new(W, H, rows, 0, err, sizeof err);
		scene(r);
		got_rows = 0;
		memset(banded, 0, sizeof banded);
		render_finish(r, keep_band, banded);
		CHECK(got_rows == H && memcmp(banded, whole, sizeof whole) == 0,
			"bands of %u rows (%u bands) equal the whole page", rows, render_bands(r));
		render_free(r);
	}
	r = render_new(W, H, 0, W * 3 * 4, err, sizeof err);
	CHECK(r && render_bands(r) == 8, "a budget of 4 rows gives 8 bands");
	render_free(r);
	CHECK(colour_at(0, 0) == colour_at(0, 0), "colour helper");
}

int main(void)
{
	scan_ctx_t *c = scan_ctx_new();
	test_rectangles(c);
	test_shared_edges(c);
	test_rules(c);
	test_random(c);
	test_bands();
	scan_ctx_free(c);
	return UNIT_DONE();
}
