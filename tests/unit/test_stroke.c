/* test_stroke.c: wide lines (spec §5.3): caps, joins, miter limit, dashes, dots, arcs (§5.4). */
#include <math.h>
#include <stdlib.h>
#include "geom/scan.h"
#include "unit.h"

#define W 40
#define H 30

static uint8_t pix[W * H * 3];
static scan_band_t band = { pix, W * 3, W, H, 0, H };
static scan_ctx_t *ctx;

static int on(int i, int j)
{
	const uint8_t *p = pix + (size_t)(H - 1 - j) * W * 3 + (size_t)i * 3;
	return !(p[0] == 0xff && p[1] == 0xff && p[2] == 0xff);
}

static int count(void)
{
	int n = 0;
	for (int j = 0; j < H; j++)
		for (int i = 0; i < W; i++)
			n += on(i, j);
	return n;
}

/* Stroke the polyline xy (pixels) with the style; closed adds the closing segment. */
static void stroke(const double *xy, size_t n, int closed, double width, int cap, int join,
		double limit, const int64_t *dash, size_t ndash)
{
	scan_path_t p = { 0 };
	memset(pix, 0xff, sizeof pix);
	scan_path_move(&p, llround(xy[0] * 1000), llround(xy[1] * 1000));
	for (size_t k = 1; k < n; k++)
		scan_path_draw(&p, llround(xy[2 * k] * 1000), llround(xy[2 * k + 1] * 1000));
	if (closed)
		scan_path_close(&p);
	scan_style_t st = { llround(width * 1000), cap, join, llround(limit * 1000), dash, ndash };
	scan_stroke(ctx, &band, &p, &st, 0);
	scan_path_free(&p);
}

static void test_caps(void)
{
	double seg[] = { 2, 5.5, 12, 5.5 };
	stroke(seg, 2, 0, 1, META_CAP_BUTT, META_JOIN_MITER, 10, NULL, 0);
	int row = 1;
	for (int i = 0; i < W; i++)
		row &= on(i, 5) == (i >= 2 && i < 12);
	CHECK(row && count() == 10, "width 1 butt: exactly pixels 2..11 of row 5 (%d)", count());
	stroke(seg, 2, 0, 0.2, META_CAP_BUTT, META_JOIN_MITER, 10, NULL, 0);
	CHECK(count() == 10, "widths below 1 draw as 1");
	stroke(seg, 2, 0, 2, META_CAP_SQUARE, META_JOIN_MITER, 10, NULL, 0);
	CHECK(on(1, 5) && on(12, 5) && on(1, 4) && !on(0, 5) && !on(13, 5) && count() == 24,
		"width 2 square: [1,13) x [4.5,6.5) = 24 pixels (%d)", count());
	double wide[] = { 10, 10, 20, 10 };
	stroke(wide, 2, 0, 4, META_CAP_BUTT, META_JOIN_MITER, 10, NULL, 0);
	CHECK(!on(8, 9) && on(10, 9) && !on(9, 9), "butt cap ends at the end point");
	stroke(wide, 2, 0, 4, META_CAP_ROUND, META_JOIN_MITER, 10, NULL, 0);
	CHECK(on(8, 9) && !on(7, 9) && on(21, 10) && !on(22, 10), "round cap: a disc of radius 2 at each end");
}

static void test_joins(void)
{
	/* left turn at (20,10): outer corner (22,8); pixel (21,8) tells the joins apart */
	double l[] = { 10, 10, 20, 10, 20, 20 };
	stroke(l, 3, 0, 4, META_CAP_BUTT, META_JOIN_MITER, 10, NULL, 0);
	CHECK(on(21, 8), "miter join fills the outer corner");
	stroke(l, 3, 0, 4, META_CAP_BUTT, META_JOIN_BEVEL, 10, NULL, 0);
	CHECK(!on(21, 8) && on(20, 9), "bevel join cuts the corner (keeps (20,9), drops (21,8))");
	stroke(l, 3, 0, 4, META_CAP_BUTT, META_JOIN_ROUND, 10, NULL, 0);
	CHECK(!on(21, 8) && on(21, 9), "round join: disc of radius 2 (pixel (21,8) at 2.12 is out)");
	stroke(l, 3, 0, 4, META_CAP_BUTT, META_JOIN_MITER, 1.4, NULL, 0);
	CHECK(!on(21, 8), "miter limit 1.4 < sqrt 2: the right-angle miter becomes a bevel");
	stroke(l, 3, 0, 4, META_CAP_BUTT, META_JOIN_MITER, 1.5, NULL, 0);
	CHECK(on(21, 8), "miter limit 1.5 >= sqrt 2: miter kept");
	/* right turn: the outer side is the left one */
	double r[] = { 10, 20, 20, 20, 20, 10 };
	stroke(r, 3, 0, 4, META_CAP_BUTT, META_JOIN_MITER, 10, NULL, 0);
	CHECK(on(21, 21), "right turn: miter on the left side");
	stroke(r, 3, 0, 4, META_CAP_BUTT, META_JOIN_BEVEL, 10, NULL, 0);
	CHECK(!on(21, 21), "right turn: bevel");
	/* a sharp spike: miter length 1/sin(theta/2) far above the limit -> bevel */
	double sp[] = { 5, 10, 35, 12, 5, 14 };
	stroke(sp, 3, 0, 2, META_CAP_BUTT, META_JOIN_MITER, 10, NULL, 0);
	int far = 0;
	for (int i = 37; i < W; i++)
		far |= on(i, 12);
	CHECK(!far, "spike beyond the miter limit is bevelled");
	/* closed square: the start vertex gets a join too */
	double sq[] = { 10, 10, 30, 10, 30, 20, 10, 20 };
	stroke(sq, 4, 1, 4, META_CAP_BUTT, META_JOIN_MITER, 10, NULL, 0);
	CHECK(on(8, 8) && on(31, 21), "closed subpath: miter at the start vertex too");
	stroke(sq, 4, 0, 4, META_CAP_BUTT, META_JOIN_MITER, 10, NULL, 0);
	CHECK(!on(8, 8) && !on(8, 21), "open subpath: butt ends, no join at the start");
}

static void test_dashes(void)
{
	double seg[] = { 0, 5.5, 30, 5.5 };
	int64_t d[] = { 3000, 2000 };
	stroke(seg, 2, 0, 1, META_CAP_BUTT, META_JOIN_MITER, 10, d, 2);
	int ok = 1;
	for (int i = 0; i < 30; i++)
		ok &= on(i, 5) == (i % 5 < 3);
	CHECK(ok && count() == 18, "dash 3 2 along 30 pixels: 6 dashes of 3 (%d)", count());
	/* the pattern continues around a corner and restarts at each subpath */
	double l[] = { 0, 5.5, 4, 5.5, 4, 15.5 };
	stroke(l, 3, 0, 1, META_CAP_BUTT, META_JOIN_MITER, 10, d, 2);
	CHECK(on(0, 5) && on(2, 5) && !on(3, 5) && !on(3, 5) && on(3, 6) && on(3, 8) && !on(3, 9),
		"dash carried across the vertex: on [0,3), off [3,5), on [5,8) = column 3, rows 6..8");
	int64_t one[] = { 1000, 1000 };
	stroke(seg, 2, 0, 1, META_CAP_SQUARE, META_JOIN_MITER, 10, one, 2);
	CHECK(count() == 29, "dash 1 1 with square caps closes the gaps up to 29.5 (%d)", count());
}

static void test_dots(void)
{
	double pt[] = { 20.5, 15.5, 20.5, 15.5 };
	stroke(pt, 2, 0, 5, META_CAP_BUTT, META_JOIN_MITER, 10, NULL, 0);
	CHECK(count() == 0, "zero-length subpath, butt: nothing");
	stroke(pt, 2, 0, 5, META_CAP_ROUND, META_JOIN_MITER, 10, NULL, 0);
	int n = count();
	CHECK(n > 15 && n < 25 && on(20, 15) && on(22, 15) && !on(23, 15), "round: a disc of radius 2.5 (%d)", n);
	stroke(pt, 2, 0, 5, META_CAP_SQUARE, META_JOIN_MITER, 10, NULL, 0);
	CHECK(count() == 25, "square: a 5x5 square (%d)", count());
	double one[] = { 20.5, 15.5 };
	stroke(one, 1, 0, 5, META_CAP_ROUND, META_JOIN_MITER, 10, NULL, 0);
	CHECK(count() == 0, "a lone move paints nothing");
}

static void test_arcs(void)
{
	CHECK(scan_circle_chords(250) == 8 && scan_circle_chords(100) == 8, "tiny radius: 8 chords");
	int m = scan_circle_chords(100000);
	CHECK(m == 89, "radius 100: %d chords (ceil(2pi / acos(1 - 0.0025)) = 89)", m);
	CHECK(100.0 * (1 - cos(M_PI / m)) <= 0.25, "chord error at most 0.25 pixel");
	scan_path_t p = { 0 };
	scan_path_arc(&p, 0, 0, 10000, 0, 90000);
	CHECK(p.nsubs == 1 && p.pts[0].x == 10000 && p.pts[0].y == 0 &&
		p.pts[p.npts - 1].x == 0 && p.pts[p.npts - 1].y == 10000, "quarter arc from (10,0) to (0,10)");
	CHECK((int)p.npts - 1 == (90 * scan_circle_chords(10000) + 359) / 360, "N = ceil(|s| M / 360) chords");
	scan_path_reset(&p);
	scan_path_move(&p, 50000, 50000);
	scan_path_arc(&p, 0, 0, 10000, 180000, -90000);
	CHECK(p.nsubs == 1 && p.pts[1].x == -10000 && p.pts[p.npts - 1].y == 10000,
		"with a current point a segment joins the arc; negative sweep goes clockwise");
	scan_path_circle(&p, 5000, 5000, 3000);
	CHECK(p.nsubs == 2 && p.subs[1].closed && !scan_path_has_current(&p), "circle: own closed subpath");
	scan_path_free(&p);
}

int main(void)
{
	ctx = scan_ctx_new();
	test_caps();
	test_joins();
	test_dashes();
	test_dots();
	test_arcs();
	scan_ctx_free(ctx);
	return UNIT_DONE();
}
