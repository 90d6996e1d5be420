/* test_dash.c: the closed-form dash walk: bands agree with the whole page, dash pieces and
 * stroke pieces reproduce the stroke, patterns finer than a pixel are solid, long segments
 * cost what the page can show. */
#include <stdlib.h>
#include <time.h>
#include "geom/scan.h"
#include "unit.h"

enum { W = 96, H = 80 };

static uint8_t page_a[W * H * 3], page_b[W * H * 3];

static void white(uint8_t *pix)
{
	memset(pix, 0xff, (size_t)W * H * 3);
}

/* Stroke p into pix (top row first) in bands of rows rows (0 = one band). */
static int stroke_banded(scan_ctx_t *c, uint8_t *pix, const scan_path_t *p, const scan_style_t *st, int rows)
{
	if (rows == 0)
		rows = H;
	for (int top = 0; top < H; top += rows) {
		int n = H - top < rows ? H - top : rows;
		scan_band_t b = { pix + (size_t)top * W * 3, (size_t)W * 3, W, H, H - top - n, H - top };
		int rc = scan_stroke(c, &b, p, st, 0x000000);
		if (rc)
			return rc;
	}
	return 0;
}

static int fill_whole(scan_ctx_t *c, uint8_t *pix, const scan_path_t *p)
{
	scan_band_t b = { pix, (size_t)W * 3, W, H, 0, H };
	return scan_fill(c, &b, p, META_RULE_NON_ZERO, 0x000000);
}

static unsigned seed = 12345;
static int64_t rnd(int64_t lo, int64_t hi)
{
	seed = seed * 1103515245u + 12345u;
	return lo + (int64_t)((seed >> 8) % (uint64_t)(hi - lo + 1));
}

/* A random polyline, some of it far off the page, and a random style. */
static void random_case(scan_path_t *p, scan_style_t *st, int64_t *dash)
{
	scan_path_reset(p);
	int nsub = (int)rnd(1, 3);
	for (int s = 0; s < nsub; s++) {
		int n = (int)rnd(2, 7);
		for (int k = 0; k < n; k++) {
			int64_t far = rnd(0, 5) == 0 ? 400000 : 0;
			int64_t x = rnd(-20000 - far, W * 1000 + 20000 + far), y = rnd(-20000, H * 1000 + 20000 + far);
			k ? scan_path_draw(p, x, y) : scan_path_move(p, x, y);
		}
		if (rnd(0, 2) == 0)
			scan_path_close(p);
	}
	st->width = rnd(0, 9000);
	st->cap = (int)rnd(0, 2);
	st->join = (int)rnd(0, 2);
	st->miter_limit = rnd(1000, 10000);
	st->ndash = 2 * (size_t)rnd(1, 3);
	for (size_t k = 0; k < st->ndash; k++)
		dash[k] = rnd(300, 9000);
	st->dash = dash;
}

static void test_random(void)
{
	scan_ctx_t *c = scan_ctx_new();
	scan_path_t p = { 0 }, pieces = { 0 }, dashes = { 0 };
	int64_t dash[8];
	int bands_ok = 1, pieces_ok = 1, dashes_ok = 1, rc = 0;
	for (int t = 0; t < 150; t++) {
		scan_style_t st;
		random_case(&p, &st, dash);
		white(page_a);
		rc |= stroke_banded(c, page_a, &p, &st, 0);
		int rows = t % 2 ? 1 : 7;
		white(page_b);
		rc |= stroke_banded(c, page_b, &p, &st, rows);
		if (memcmp(page_a, page_b, sizeof page_a))
			bands_ok = 0;
		scan_path_reset(&pieces);
		rc |= scan_stroke_pieces(c, &p, &st, W, H, &pieces);
		white(page_b);
		rc |= fill_whole(c, page_b, &pieces);
		if (memcmp(page_a, page_b, sizeof page_a))
			pieces_ok = 0;
		scan_path_reset(&dashes);
		rc |= scan_dash_path(&p, st.dash, st.ndash, &dashes);
		scan_style_t solid = st;
		solid.dash = NULL;
		solid.ndash = 0;
		white(page_b);
		rc |= stroke_banded(c, page_b, &dashes, &solid, 0);
		if (memcmp(page_a, page_b, sizeof page_a))
			dashes_ok = 0;
	}
	CHECK(rc == 0 && bands_ok, "150 random dashed strokes: bands of 1 and 7 rows paint the whole page's pixels");
	CHECK(pieces_ok, "scan_stroke_pieces filled non-zero paints the stroke's pixels");
	CHECK(dashes_ok, "scan_dash_path's pieces stroked solid paint the dashed stroke's pixels");
	scan_path_free(&p);
	scan_path_free(&pieces);
	scan_path_free(&dashes);
	scan_ctx_free(c);
}

static void test_fine_and_long(void)
{
	scan_ctx_t *c = scan_ctx_new();
	scan_path_t p = { 0 };
	scan_path_move(&p, -1000000000, 40500);
	scan_path_draw(&p, 1000000000, 39500);
	int64_t fine[2] = { 1, 1 }, pix[2] = { 499, 500 }, one[2] = { 1000, 1000 };
	scan_style_t st = { 3000, META_CAP_BUTT, META_JOIN_MITER, 10000, NULL, 0 };
	white(page_a);
	stroke_banded(c, page_a, &p, &st, 0);
	clock_t t0 = clock();
	st.dash = fine;
	st.ndash = 2;
	white(page_b);
	int rc = stroke_banded(c, page_b, &p, &st, 1);
	double secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
	CHECK(rc == 0 && !memcmp(page_a, page_b, sizeof page_a) && secs < 2,
		"dash 0.001 along a 2,000,000-pixel segment is solid, in 1-row bands in %.3f s", secs);
	st.dash = pix;
	white(page_b);
	stroke_banded(c, page_b, &p, &st, 0);
	CHECK(!memcmp(page_a, page_b, sizeof page_a), "dash 0.499 0.5 (period below a pixel) is solid too");
	st.dash = one;
	white(page_b);
	t0 = clock();
	rc = stroke_banded(c, page_b, &p, &st, 1);
	secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
	CHECK(rc == 0 && memcmp(page_a, page_b, sizeof page_a) != 0 && secs < 2,
		"dash 1 along it is dashed, 80 one-row bands in %.3f s (10^6 boundaries per band walked before)", secs);
	uint8_t *whole = malloc(sizeof page_b);
	white(whole);
	stroke_banded(c, whole, &p, &st, 0);
	CHECK(!memcmp(whole, page_b, sizeof page_b), "and the bands agree with the whole page");
	/* the pattern's phase far along the segment: 1-pixel dashes, on at even pixels from -10^6 */
	int dashes = 0;
	for (int x = 1; x < W; x++)
		dashes += whole[(40 * W + x) * 3] != whole[(40 * W + x - 1) * 3];
	CHECK(dashes >= 90, "1-pixel dashes alternate along the page row (%d changes)", dashes);
	free(whole);
	scan_path_free(&p);
	scan_ctx_free(c);
}

int main(void)
{
	test_random();
	test_fine_and_long();
	return UNIT_DONE();
}
