/* test_scan_tiny.c: the small-piece fast path of scan_fill_piece against §5.1 by brute force. */
#include <stdlib.h>
#include "geom/scan.h"
#include "geom/scan_int.h"
#include "unit.h"

#define W 24
#define H 20

static uint8_t pix[W * H * 3];
static long painted;   /* pixels painted by all the pieces, so that the checks compare something */

static int on(int i, int j)
{
	const uint8_t *p = pix + (size_t)(H - 1 - j) * W * 3 + (size_t)i * 3;
	return !(p[0] == 0xff && p[1] == 0xff && p[2] == 0xff);
}

/* §5.1 to the letter for one contour: winding number of centre (xc, yc). */
static int winding(const scan_pt_t *q, size_t n, int64_t xc, int64_t yc)
{
	int w = 0;
	for (size_t k = 0; k < n; k++) {
		scan_pt_t a = q[k], b = q[k + 1 == n ? 0 : k + 1];
		if (a.y == b.y)
			continue;
		int dir = b.y > a.y ? 1 : -1;
		if (dir < 0) {
			scan_pt_t t = a; a = b; b = t;
		}
		if (!(a.y <= yc && yc < b.y))
			continue;
		__int128 lhs = (__int128)a.x * (b.y - a.y) + (__int128)(yc - a.y) * (b.x - a.x);
		if (lhs <= (__int128)xc * (b.y - a.y))
			w += dir;
	}
	return w;
}

static uint64_t rng = 88172645463325252u;

static int64_t rnd(int64_t n)
{
	rng ^= rng << 13;
	rng ^= rng >> 7;
	rng ^= rng << 17;
	return (int64_t)(rng % (uint64_t)n);
}

/* A coordinate in thousandths around the page, often on a centre or a pixel edge (ties). */
static int64_t coord(int64_t span)
{
	int64_t v = rnd(span + 4000) - 2000;
	int k = (int)rnd(4);
	if (k == 0)
		v = v / 500 * 500;
	else if (k == 1)
		v = v / 1000 * 1000 + 500;
	return v;
}

/* Paint q with the piece path over a band of rows [jlo, jhi); count pixels that differ from
 * the brute-force rule. */
static int mismatches(const scan_pt_t *q, size_t n, int rule, int convex, int jlo, int jhi)
{
	scan_ctx_t *c = scan_ctx_new();
	memset(pix, 0xff, sizeof pix);
	scan_band_t b = { pix + (size_t)(H - jhi) * W * 3, W * 3, W, H, jlo, jhi };
	scan_fill_piece(c, &b, q, n, rule, 0x102030, convex);
	scan_ctx_free(c);
	int bad = 0;
	for (int j = 0; j < H; j++)
		for (int i = 0; i < W; i++) {
			int w = winding(q, n, 1000 * (int64_t)i + 500, 1000 * (int64_t)j + 500);
			int want = j >= jlo && j < jhi &&
				(rule == META_RULE_EVEN_ODD ? (w & 1) : w != 0);
			bad += want != on(i, j);
			painted += on(i, j);
		}
	return bad;
}

int main(void)
{
	int bad_convex = 0, bad_general = 0, bad_band = 0;
	for (int t = 0; t < 3000; t++) {
		/* convex: a parallelogram P - o, Q - o, Q + o, P + o or a triangle */
		scan_pt_t p = { coord(W * 1000), coord(H * 1000) };
		scan_pt_t o = { rnd(3001) - 1500, rnd(3001) - 1500 };
		scan_pt_t d = { rnd(6001) - 3000, rnd(6001) - 3000 };
		scan_pt_t par[4] = { { p.x - o.x, p.y - o.y }, { p.x + d.x - o.x, p.y + d.y - o.y },
			{ p.x + d.x + o.x, p.y + d.y + o.y }, { p.x + o.x, p.y + o.y } };
		bad_convex += mismatches(par, 4, META_RULE_NON_ZERO, 1, 0, H);
		bad_convex += mismatches(par, 3, META_RULE_NON_ZERO, 1, 0, H);
		/* general: any 3 to 12 points, both rules (self-crossing ones included) */
		size_t n = 3 + (size_t)rnd(10);
		scan_pt_t g[12];
		scan_pt_t base = { coord(W * 1000), coord(H * 1000) };
		for (size_t k = 0; k < n; k++) {
			g[k].x = base.x + rnd(8001) - 4000;
			g[k].y = base.y + rnd(8001) - 4000;
		}
		int rule = t & 1 ? META_RULE_EVEN_ODD : META_RULE_NON_ZERO;
		bad_general += mismatches(g, n, rule, 0, 0, H);
		/* a band of a few rows only */
		int jlo = (int)rnd(H), jhi = jlo + 1 + (int)rnd(H - jlo);
		bad_band += mismatches(g, n, rule, 0, jlo, jhi);
		bad_band += mismatches(par, 4, META_RULE_NON_ZERO, 1, jlo, jhi);
	}
	CHECK(bad_convex == 0, "convex pieces (parallelograms, triangles) match 5.1: %d pixels differ", bad_convex);
	CHECK(bad_general == 0, "general pieces of 3-12 points, both rules, match 5.1: %d pixels differ", bad_general);
	CHECK(bad_band == 0, "pieces painted into a band of some rows match 5.1: %d pixels differ", bad_band);
	CHECK(painted > 20000, "the random pieces cover pixels (%ld painted)", painted);
	return UNIT_DONE();
}
