/* test_hpgl_opt.c: path optimisation (merge, simplify, nearest-end order, 2-opt), hatching, the
 * drag-knife path, profiles, pens and the plot-time model. */
#include <math.h>
#include <stdlib.h>
#include <time.h>
#include "hpgl/hpgl_hatch.h"
#include "hpgl/hpgl.h"
#include "unit.h"

static uint64_t rng = 88172645463325252ULL;
static int32_t rnd(int32_t n)
{
	rng ^= rng << 13;
	rng ^= rng >> 7;
	rng ^= rng << 17;
	return (int32_t)(rng % (uint64_t)n);
}

/* Sum over the drawn segments of a hash of each undirected segment: equal multisets, equal sums. */
static uint64_t seg_hash(const popt_set_t *s)
{
	uint64_t h = 0;
	popt_pt_t *buf = malloc((s->npts + 2) * sizeof *buf);
	for (size_t k = 0; k < s->npaths; k++) {
		size_t n = popt_get(s, k, buf);
		for (size_t i = 0; i + 1 < n; i++) {
			popt_pt_t a = buf[i], b = buf[i + 1];
			if (a.x > b.x || (a.x == b.x && a.y > b.y)) {
				popt_pt_t t = a;
				a = b;
				b = t;
			}
			uint64_t v = ((uint64_t)(uint32_t)a.x * 1000003u) ^ ((uint64_t)(uint32_t)a.y << 21) ^
				((uint64_t)(uint32_t)b.x * 998244353u) ^ ((uint64_t)(uint32_t)b.y << 42);
			v *= 0x9E3779B97F4A7C15ULL;
			h += v ^ (v >> 29);
		}
	}
	free(buf);
	return h;
}

static void optimiser(void)
{
	popt_set_t s = { 0 };
	/* two paths meeting end to end, one reversed: merged into one */
	popt_pt_t a[] = { { 0, 0 }, { 100, 0 } }, b[] = { { 200, 0 }, { 100, 0 } }, c[] = { { 1000, 1000 }, { 1100, 1000 } };
	popt_add(&s, a, 2, 0);
	popt_add(&s, b, 2, 0);
	popt_add(&s, c, 2, 0);
	popt_opts_t o = { 1, 2, 0, 1, 0.05, 0 };
	popt_stats_t st;
	uint64_t h0;
	popt_keep_order(&s);
	h0 = seg_hash(&s);
	CHECK(popt_optimise(&s, (popt_pt_t){ 0, 0 }, &o, &st) == 0 && s.npaths == 2 && st.paths_before == 3,
		"merge: paths whose ends meet become one (%zu paths)", s.npaths);
	CHECK(seg_hash(&s) == h0, "merge keeps every segment once");
	popt_free(&s);

	/* a closed square starts at the vertex nearest to the pen */
	popt_pt_t q[] = { { 0, 0 }, { 100, 0 }, { 100, 100 }, { 0, 100 } };
	popt_add(&s, q, 4, 1);
	popt_optimise(&s, (popt_pt_t){ 120, 120 }, &o, &st);
	popt_pt_t f, l;
	popt_ends(&s, 0, &f, &l);
	CHECK(f.x == 100 && f.y == 100 && st.travel_after < 30, "closed path rotated to start near the pen (%d,%d)", f.x, f.y);
	popt_free(&s);

	/* random short segments: travel falls, every segment kept, 2-opt no worse than greedy */
	for (int k = 0; k < 20000; k++) {
		popt_pt_t p[2] = { { rnd(100000), rnd(70000) } };
		p[1] = (popt_pt_t){ p[0].x + rnd(2000) - 1000, p[0].y + rnd(2000) - 1000 };
		popt_add(&s, p, 2, 0);
	}
	popt_keep_order(&s);
	h0 = seg_hash(&s);
	o.budget_s = 0.5;
	o.merge = 0;   /* random ends may meet: keep every path to compare */
	clock_t t0 = clock();
	popt_optimise(&s, (popt_pt_t){ 0, 0 }, &o, &st);
	double secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
	CHECK(seg_hash(&s) == h0 && s.npaths == 20000, "20000 random segments all kept");
	CHECK(st.travel_greedy < st.travel_before / 10 && st.travel_after <= st.travel_greedy,
		"travel %.0f -> greedy %.0f -> 2-opt %.0f (%.1f%% by 2-opt) in %.3f s", st.travel_before, st.travel_greedy,
		st.travel_after, 100 * (1 - st.travel_after / st.travel_greedy), secs);
	CHECK(fabs(popt_travel(&s, (popt_pt_t){ 0, 0 }) - st.travel_after) < 1e-6 * st.travel_after, "reported travel is the order's");
	popt_free(&s);

	/* simplification within tolerance */
	popt_pt_t z[] = { { 0, 0 }, { 50, 1 }, { 100, 0 }, { 100, 0 }, { 200, 50 } };
	popt_add(&s, z, 5, 0);
	popt_opts_t o2 = { 0, 0, 2, 0, 0, 0 };
	popt_optimise(&s, (popt_pt_t){ 0, 0 }, &o2, &st);
	CHECK(s.paths[0].n == 3, "simplify: a point 1 unit off the line and a repeat dropped (%zu points)", s.paths[0].n);
	popt_free(&s);
}

typedef struct {
	double len;
	size_t n;
	double ymin, ymax;
} acc_t;

static int acc(void *u, double x0, double y0, double x1, double y1)
{
	acc_t *a = u;
	a->len += hypot(x1 - x0, y1 - y0);
	a->n++;
	if (y0 < a->ymin) a->ymin = y0;
	if (y0 > a->ymax) a->ymax = y0;
	return 0;
}

static void hatching(void)
{
	/* a 100 x 100 square with a 50 x 50 hole, horizontal lines 10 apart */
	double pts[] = { 0, 0, 100, 0, 100, 100, 0, 100, 25, 25, 75, 25, 75, 75, 25, 75 };
	size_t starts[] = { 0, 4, 8 };
	acc_t a = { 0, 0, 1e9, -1e9 };
	hatch_polygon(pts, starts, 2, 1, 0, 10, 5, acc, &a);
	CHECK(fabs(a.len - (10 * 100 - 5 * 50)) < 1e-6 && a.n == 15, "even-odd: the hole is left out (%.1f, %zu pieces)", a.len, a.n);
	acc_t b = { 0, 0, 1e9, -1e9 };
	hatch_polygon(pts, starts, 2, 0, 0, 10, 5, acc, &b);
	CHECK(fabs(b.len - 1000) < 1e-6, "non-zero, same orientation: the hole is filled (%.1f)", b.len);
	double rev[] = { 0, 0, 100, 0, 100, 100, 0, 100, 25, 25, 25, 75, 75, 75, 75, 25 };
	acc_t c = { 0, 0, 1e9, -1e9 };
	hatch_polygon(rev, starts, 2, 0, 0, 10, 5, acc, &c);
	CHECK(fabs(c.len - 750) < 1e-6, "non-zero, hole reversed: a hole again (%.1f)", c.len);
	acc_t d = { 0, 0, 1e9, -1e9 };
	hatch_polygon(pts, starts, 1, 1, 45, 10, 0, acc, &d);
	CHECK(fabs(d.len - 1000) < 100 && d.n > 10, "45 degrees: about area / spacing of line (%.1f)", d.len);
	double dark[4] = { 0, 0.3, 0.6, 1 };
	acc_t e = { 0, 0, 1e9, -1e9 };
	for (unsigned row = 0; row < 8; row++)
		hatch_row(dark, 4, 0, 40, row * 10.0, 10, 1, row, acc, &e);
	CHECK(fabs(e.len - 10 * (0 + 2 + 5 + 8)) < 1e-6, "brightness rows: ink grows with darkness (%.1f)", e.len);
}

static int grab(void *u, const hpgl_dpt_t *p, size_t n, int closed)
{
	(void)closed;
	hpgl_dpt_t *out = u;
	out[0] = p[0];
	out[1] = p[n - 1];
	out[2].x = (double)n;
	return 0;
}

static void geometry_profiles(void)
{
	/* the knife: a square with blade offset 10 ends past its start by the overcut plus offset */
	hpgl_dpt_t sq[] = { { 0, 0 }, { 100, 0 }, { 100, 100 }, { 0, 100 } }, got[3];
	hpgl_knife_poly(sq, 4, 1, 10, 20, grab, got);
	CHECK(got[0].x == 0 && got[0].y == 0 && fabs(got[1].x - 30) < 1e-9 && fabs(got[1].y) < 1e-9 && got[2].x > 20,
		"knife: starts at the path, swings corners, ends overcut + offset past the start (%.1f,%.1f; %g points)",
		got[1].x, got[1].y, got[2].x);
	/* (dashes are the framework's, geom/dash.c: tests/unit/test_dash*, t_dash.sh) */

	char err[256];
	hpgl_pens_t pens;
	CHECK(hpgl_pens_parse("1=black,2=red:0.5mm;3=#00ff00", 0.3, &pens, err, sizeof err) == 0 && pens.n == 3 &&
		pens.pen[1].width_mm == 0.5 && pens.pen[2].rgb == 0x00ff00, "pens parse");
	CHECK(hpgl_pens_nearest(&pens, 0xd02020) == 1 && hpgl_pens_nearest(&pens, 0x303030) == 0 &&
		hpgl_pens_nearest(&pens, 0x40c040) == 2, "nearest pen in CIELAB");
	hpgl_pens_t six;
	hpgl_pens_parse(hpgl_profile_find("7475a")->pens, 0.3, &six, err, sizeof err);
	CHECK(six.pen[hpgl_pens_nearest(&six, 0x0000ff)].slot == 4 && six.pen[hpgl_pens_nearest(&six, 0xe08000)].slot == 2,
		"CIE94: pure blue takes the blue pen (CIE76 would take magenta), orange the red one");
	CHECK(hpgl_pens_pick(&pens, 0xffffff) < 0 && hpgl_pens_pick(&pens, 0xe8c6c6) < 0 && hpgl_pens_pick(&pens, 0xd0d0d0) < 0,
		"white, a pastel pink and a light grey are the paper");
	hpgl_pens_t mono;
	hpgl_pens_parse("1=black", 0.3, &mono, err, sizeof err);
	CHECK(hpgl_pens_pick(&mono, 0xff0000) == 0 && hpgl_pens_pick(&mono, 0x808080) == 0 && hpgl_pens_pick(&mono, 0xffff00) < 0,
		"one black pen: red and mid grey are drawn with it, yellow (L* 97) is the paper");
	CHECK(hpgl_pens_parse("1=black,0=red", 0.3, &pens, err, sizeof err) < 0 && strstr(err, "'0=red'"), "bad slot: %s", err);
	CHECK(hpgl_pens_parse("1=blak", 0.3, &pens, err, sizeof err) < 0 && strstr(err, "unknown colour"), "bad colour: %s", err);
	CHECK(hpgl_pens_parse("1=red,1=blue", 0.3, &pens, err, sizeof err) < 0 && strstr(err, "twice"), "pen twice: %s", err);

	hpgl_profile_t p;
	const char *good = "# a test plotter\nname = t1\nbase = 7475a\nmax-pairs = 8\nclip.a4 = 0 0 1000 800\r\n";
	CHECK(hpgl_profile_parse(good, strlen(good), "t.prof", &p, err, sizeof err) == 0 && !strcmp(p.name, "t1") &&
		p.max_pairs == 8 && p.clip[0][2] == 1000 && p.dialect == 1 && p.npens == 6, "profile file with a base");
	const char *bad = "name = t\nspeed-down = fast\n";
	CHECK(hpgl_profile_parse(bad, strlen(bad), "t.prof", &p, err, sizeof err) < 0 && strstr(err, "t.prof:2:1:") &&
		strstr(err, "speed-down"), "bad number: %s", err);
	const char *bad2 = "name = t\n  colour = red\n";
	CHECK(hpgl_profile_parse(bad2, strlen(bad2), "t.prof", &p, err, sizeof err) < 0 && strstr(err, "t.prof:2:3:") &&
		strstr(err, "unknown key"), "unknown key: %.60s", err);
	const char *bad3 = "name = t\nclip.a3 = 0 0 10\n";
	CHECK(hpgl_profile_parse(bad3, strlen(bad3), "t.prof", &p, err, sizeof err) < 0 && strstr(err, ":2:"), "bad clip: %.70s", err);

	/* page mapping: an A4-sized page fills the 7475A's A4 area, centred; rotation swaps */
	hpgl_map_t m;
	hpgl_place_t pl = { HPGL_PAPER_A4, 0, 0, 1, 1.0 };
	hpgl_map_page(hpgl_profile_find("7475a"), &pl, 1100, 770, 0, 0, &m, err, sizeof err);
	double X, Y;
	hpgl_map_point(&m, 0, 0, &X, &Y);
	CHECK(m.clip[0] >= 0 && m.clip[2] <= 11040 && m.clip[3] <= 7721 && X >= 0 && Y >= 0, "fit: inside the clip limits");
	pl.rotate = 90;
	hpgl_map_page(hpgl_profile_find("7475a"), &pl, 100, 200, 10, 20, &m, err, sizeof err);
	hpgl_map_point(&m, 100000, 0, &X, &Y);
	double X0, Y0;
	hpgl_map_point(&m, 0, 0, &X0, &Y0);
	CHECK(fabs(X - X0) < 1e-6 && fabs(Y - Y0 - 400) < 1e-6, "rotate 90: model x runs up the paper, 10 mm = 400 pu");

	/* time model: 100 mm at 10 cm/s with 10 m/s^2: 1 s cruising plus 0.01 s of ramps */
	CHECK(fabs(hpgl_move_time(100, 10, 10) - 1.01) < 1e-9 && fabs(hpgl_move_time(0.5, 10, 10) - 2 * sqrt(0.5 / 10000)) < 1e-12,
		"trapezoid and triangle move times");
}

int main(void)
{
	optimiser();
	hatching();
	geometry_profiles();
	return UNIT_DONE();
}
