/* test_contour.c: marching squares: loop radius and orientation, joining, saddles, NaN holes, errors. */
#include <math.h>
#include <stdlib.h>

#include "contour.h"
#include "msq.h"
#include "unit.h"

#define MAXP 100000

/* Everything the callback saw. */
typedef struct {
	int lines, closed, stop_after;
	unsigned level[64];
	size_t n[64];
	int isclosed[64];
	contour_point_t *p[64];
	size_t points;
	int nan_points;
} sink_t;

static int collect(void *user, unsigned level, const contour_point_t *p, size_t n, int closed)
{
	sink_t *s = user;
	for (size_t i = 0; i < n; i++)
		if (!isfinite(p[i].x) || !isfinite(p[i].y))
			s->nan_points++;
	if (s->lines < 64) {
		s->level[s->lines] = level;
		s->n[s->lines] = n;
		s->isclosed[s->lines] = closed;
		s->p[s->lines] = malloc(n * sizeof *p);
		memcpy(s->p[s->lines], p, n * sizeof *p);
	}
	s->lines++;
	s->closed += closed != 0;
	s->points += n;
	if (s->stop_after && s->lines >= s->stop_after)
		return -1;
	return 0;
}

static void sink_free(sink_t *s)
{
	for (int i = 0; i < s->lines && i < 64; i++)
		free(s->p[i]);
	memset(s, 0, sizeof *s);
}

/* Shoelace area (positive = counter-clockwise). */
static double area(const contour_point_t *p, size_t n)
{
	double a = 0;
	for (size_t i = 0; i < n; i++) {
		size_t k = (i + 1) % n;
		a += p[i].x * p[k].y - p[k].x * p[i].y;
	}
	return a / 2;
}

static float *cone(unsigned nx, unsigned ny, double cx, double cy)
{
	float *z = malloc((size_t)nx * ny * sizeof *z);
	for (unsigned j = 0; j < ny; j++)
		for (unsigned i = 0; i < nx; i++)
			z[j * nx + i] = (float)hypot(i - cx, j - cy);
	return z;
}

static void test_circle(void)
{
	float *z = cone(101, 101, 50.3, 49.6);
	/* page = 10 + 2 * index: a radius of 20 samples is 40 pixels */
	contour_grid_t g = { z, 101, 101, { 0 } };
	contour_map_rect(g.m, 101, 101, 10, 10, 210, 210);
	CHECK(g.m[1] == 2 && g.m[5] == 2 && g.m[0] == 10, "map_rect scales 2 pixels per sample");
	double lv = 20;
	sink_t s = { 0 };
	contour_stats_t st;
	int rc = contour_extract(&g, &lv, 1, collect, &s, &st);
	CHECK(rc == 0, "cone extracts (rc %d: %s)", rc, contour_error());
	CHECK(s.lines == 1 && s.closed == 1, "one closed loop for a circle (%d lines, %d closed)", s.lines, s.closed);
	double worst = 0;
	for (size_t i = 0; s.lines == 1 && i < s.n[0]; i++) {
		double r = hypot(s.p[0][i].x - (10 + 2 * 50.3), s.p[0][i].y - (10 + 2 * 49.6));
		worst = fmax(worst, fabs(r - 40));
	}
	CHECK(s.lines == 1 && worst < 0.02, "loop points at radius 40 pixels (worst error %.4f)", worst);
	CHECK(st.segments == s.points && st.polylines == 1 && st.closed == 1,
	      "stats: %zu segments for %zu points of a closed loop", st.segments, s.points);
	/* higher values (outside) on the left: a clockwise loop */
	CHECK(s.lines == 1 && area(s.p[0], s.n[0]) < -4900, "loop runs clockwise around a minimum (area %.1f)",
	      s.lines ? area(s.p[0], s.n[0]) : 0);
	sink_free(&s);
	/* negated: a maximum, so counter-clockwise */
	for (unsigned q = 0; q < 101 * 101; q++)
		z[q] = -z[q];
	lv = -20;
	contour_extract(&g, &lv, 1, collect, &s, NULL);
	CHECK(s.lines == 1 && area(s.p[0], s.n[0]) > 4900, "loop runs counter-clockwise around a maximum");
	sink_free(&s);
	free(z);
}

static void test_joining(void)
{
	/* a tilted plane: each level is one straight open line across the grid */
	unsigned nx = 40, ny = 30;
	float *z = malloc(nx * ny * sizeof *z);
	for (unsigned j = 0; j < ny; j++)
		for (unsigned i = 0; i < nx; i++)
			z[j * nx + i] = (float)(i + 0.7 * j);
	contour_grid_t g = { z, nx, ny, { 0, 1, 0, 0, 0, 1 } };
	double lv[3] = { 30.33, 10.55, 20.125 }; /* not sorted: output follows this order */
	sink_t s = { 0 };
	contour_stats_t st;
	CHECK(contour_extract(&g, lv, 3, collect, &s, &st) == 0, "plane extracts");
	CHECK(s.lines == 3 && s.closed == 0, "one open polyline per level (%d lines)", s.lines);
	CHECK(s.lines == 3 && s.level[0] == 0 && s.level[1] == 1 && s.level[2] == 2, "levels in the caller's order");
	int on_border = 1, on_line = 1;
	for (int l = 0; l < s.lines && l < 3; l++) {
		contour_point_t a = s.p[l][0], b = s.p[l][s.n[l] - 1];
		double L = lv[s.level[l]];
		for (int e = 0; e < 2; e++) {
			contour_point_t q = e ? b : a;
			if (!(q.x == 0 || q.y == 0 || q.x == nx - 1 || q.y == ny - 1))
				on_border = 0;
		}
		for (size_t i = 0; i < s.n[l]; i++)
			if (fabs(s.p[l][i].x + 0.7 * s.p[l][i].y - L) > 1e-4)
				on_line = 0;
	}
	CHECK(on_border, "open chains end on the grid border");
	CHECK(on_line, "points lie on the exact iso-line of a linear field");
	CHECK(st.segments + 3 == s.points, "segments = points - 1 per open chain (%zu, %zu)", st.segments, s.points);
	sink_free(&s);
	free(z);
}

/* Random field: every crossed edge gives exactly one point, consecutive points share a cell. */
static void test_random_consistency(void)
{
	unsigned nx = 60, ny = 45;
	float *z = malloc(nx * ny * sizeof *z);
	unsigned long long r = 88172645463325252ULL;
	for (unsigned q = 0; q < nx * ny; q++) {
		r ^= r << 13; r ^= r >> 7; r ^= r << 17;
		z[q] = (float)((r >> 11) * (1.0 / 9007199254740992.0));
	}
	double lv[2] = { 0.5, 0.3 };
	size_t crossed = 0, cellsegs = 0;
	for (int l = 0; l < 2; l++) {
		for (unsigned j = 0; j < ny; j++)
			for (unsigned i = 0; i < nx; i++) {
				int a = z[j * nx + i] >= lv[l];
				if (i + 1 < nx && a != (z[j * nx + i + 1] >= lv[l]))
					crossed++;
				if (j + 1 < ny && a != (z[(j + 1) * nx + i] >= lv[l]))
					crossed++;
				if (i + 1 < nx && j + 1 < ny) {
					int c = a + (z[j * nx + i + 1] >= lv[l]) + (z[(j + 1) * nx + i] >= lv[l]) +
					        (z[(j + 1) * nx + i + 1] >= lv[l]);
					int saddle = c == 2 && a == (z[(j + 1) * nx + i + 1] >= lv[l]);
					cellsegs += saddle ? 2 : (c >= 1 && c <= 3);
				}
			}
	}
	contour_grid_t g = { z, nx, ny, { 0, 1, 0, 0, 0, 1 } };
	sink_t s = { 0 };
	contour_stats_t st;
	CHECK(contour_extract(&g, lv, 2, collect, &s, &st) == 0, "random field extracts");
	CHECK(st.points == crossed, "each crossed edge gives one point (%zu points, %zu edges)", st.points, crossed);
	CHECK(st.segments == cellsegs, "each cell gives its segments once (%zu, %zu)", st.segments, cellsegs);
	CHECK(st.polylines == (size_t)s.lines && s.nan_points == 0, "%d polylines, no NaN points", s.lines);
	int near = 1;
	for (int l = 0; l < s.lines && l < 64; l++)
		for (size_t i = 0; i + 1 < s.n[l]; i++)
			if (fabs(s.p[l][i].x - s.p[l][i + 1].x) > 1 || fabs(s.p[l][i].y - s.p[l][i + 1].y) > 1)
				near = 0;
	CHECK(near, "consecutive points of a polyline lie in one cell");
	sink_free(&s);
	free(z);
}

/* Random field with NaN holes: every crossed edge of a valid cell gives one
 * point, chains are open exactly where they meet a hole or the border. */
static void test_random_holes(void)
{
	unsigned nx = 50, ny = 40;
	float *z = malloc(nx * ny * sizeof *z);
	unsigned long long r = 0x243f6a8885a308d3ULL;
	for (unsigned q = 0; q < nx * ny; q++) {
		r ^= r << 13; r ^= r >> 7; r ^= r << 17;
		double u = (r >> 11) * (1.0 / 9007199254740992.0);
		z[q] = u < 0.04 ? NAN : (float)u;
	}
	double lv = 0.5;
	size_t crossed = 0;
	/* an edge counts when a cell next to it has four finite corners */
#define Z(i, j) z[(j) * nx + (i)]
#define OK(i, j) ((i) < nx - 1 && (j) < ny - 1 && !isnan(Z(i, j)) && !isnan(Z((i) + 1, j)) && \
                  !isnan(Z(i, (j) + 1)) && !isnan(Z((i) + 1, (j) + 1)))
	for (unsigned j = 0; j < ny; j++)
		for (unsigned i = 0; i < nx; i++) {
			if (i + 1 < nx && (Z(i, j) >= lv) != (Z(i + 1, j) >= lv) &&
			    (OK(i, j) || (j > 0 && OK(i, j - 1))))
				crossed++;
			if (j + 1 < ny && (Z(i, j) >= lv) != (Z(i, j + 1) >= lv) &&
			    (OK(i, j) || (i > 0 && OK(i - 1, j))))
				crossed++;
		}
#undef OK
#undef Z
	contour_grid_t g = { z, nx, ny, { 0, 1, 0, 0, 0, 1 } };
	sink_t s = { 0 };
	contour_stats_t st;
	CHECK(contour_extract(&g, &lv, 1, collect, &s, &st) == 0, "holed random field extracts");
	CHECK(st.points == crossed, "holes: each crossed edge of a valid cell gives one point (%zu, %zu)", st.points,
	      crossed);
	CHECK(st.segments + (st.polylines - st.closed) == st.points, "holes: open chains have one point more than segments");
	CHECK(s.nan_points == 0 && st.closed < st.polylines, "holes: no NaN points, some chains opened");
	sink_free(&s);
	free(z);
}

static void test_saddle(void)
{
	/* corners 0 (0,0) and 2 (1,1) above, 1 and 3 below */
	float z[4] = { 1, -1, -1, 1 }; /* row 0: (0,0) (1,0); row 1: (0,1) (1,1) */
	contour_grid_t g = { z, 2, 2, { 0, 1, 0, 0, 0, 1 } };
	double lv = 0;
	sink_t s = { 0 };
	/* average 0 >= 0: the above corners join; the below corners are cut off */
	contour_extract(&g, &lv, 1, collect, &s, NULL);
	int cut_low = s.lines == 2;
	for (int l = 0; l < s.lines && l < 2; l++) {
		double mx = (s.p[l][0].x + s.p[l][1].x) / 2, my = (s.p[l][0].y + s.p[l][1].y) / 2;
		/* the midpoint of a cut lies near a below corner (1,0) or (0,1) */
		if (!((mx > 0.5 && my < 0.5) || (mx < 0.5 && my > 0.5)))
			cut_low = 0;
	}
	CHECK(cut_low, "saddle with centre average >= level joins the above corners (%d lines)", s.lines);
	sink_free(&s);
	float z2[4] = { 1, -1.5f, -1.5f, 1 }; /* average < 0: the below corners join */
	g.z = z2;
	contour_extract(&g, &lv, 1, collect, &s, NULL);
	int cut_high = s.lines == 2;
	for (int l = 0; l < s.lines && l < 2; l++) {
		double mx = (s.p[l][0].x + s.p[l][1].x) / 2, my = (s.p[l][0].y + s.p[l][1].y) / 2;
		if (!((mx < 0.5 && my < 0.5) || (mx > 0.5 && my > 0.5)))
			cut_high = 0;
	}
	CHECK(cut_high, "saddle with centre average < level joins the below corners");
	sink_free(&s);
	/* a saddle between two bumps: two loops or one depending on the level,
	 * and the decision is the same whichever level order is asked */
	unsigned nx = 31, ny = 21;
	float *zz = malloc(nx * ny * sizeof *zz);
	for (unsigned j = 0; j < ny; j++)
		for (unsigned i = 0; i < nx; i++)
			zz[j * nx + i] = (float)fmin(hypot(i - 10.0, j - 10.3), hypot(i - 20.0, j - 10.3));
	contour_grid_t g2 = { zz, nx, ny, { 0, 1, 0, 0, 0, 1 } };
	double two[2] = { 4.0, 6.0 };
	contour_extract(&g2, two, 2, collect, &s, NULL);
	int loops4 = 0, loops6 = 0;
	for (int l = 0; l < s.lines && l < 64; l++) {
		if (s.isclosed[l] && s.level[l] == 0)
			loops4++;
		if (s.isclosed[l] && s.level[l] == 1)
			loops6++;
	}
	CHECK(loops4 == 2 && loops6 == 1 && s.lines == 3, "two bumps: 2 loops below the saddle, 1 above (%d, %d)",
	      loops4, loops6);
	sink_free(&s);
	free(zz);
}

static void test_nan(void)
{
	float *z = cone(41, 41, 20, 20);
	for (unsigned j = 18; j <= 22; j++)
		z[j * 41 + 30] = NAN;   /* a hole that cuts the loop of radius 10 */
	z[0] = INFINITY;
	contour_grid_t g = { z, 41, 41, { 0, 1, 0, 0, 0, 1 } };
	double lv = 10;
	sink_t s = { 0 };
	contour_stats_t st;
	CHECK(contour_extract(&g, &lv, 1, collect, &s, &st) == 0, "NaN field extracts");
	CHECK(s.lines == 1 && s.closed == 0, "a NaN hole opens the loop into one chain (%d lines, %d closed)",
	      s.lines, s.closed);
	CHECK(s.nan_points == 0, "no NaN points");
	int ends_at_hole = s.lines == 1;
	for (int e = 0; s.lines == 1 && e < 2; e++) {
		contour_point_t q = e ? s.p[0][s.n[0] - 1] : s.p[0][0];
		if (!(q.x >= 28.9 && q.x <= 30.1 + 1e-9 && q.y >= 16.9 && q.y <= 23.1))
			ends_at_hole = 0;
	}
	CHECK(ends_at_hole, "the chain ends at the cells next to the hole");
	sink_free(&s);
	/* all NaN: nothing, no error */
	for (unsigned q = 0; q < 41 * 41; q++)
		z[q] = NAN;
	CHECK(contour_extract(&g, &lv, 1, collect, &s, NULL) == 0 && s.lines == 0, "an all-NaN grid gives nothing");
	free(z);
}

static void test_errors(void)
{
	float z[4] = { 0, 1, 2, 3 };
	contour_grid_t g = { z, 1, 4, { 0, 1, 0, 0, 0, 1 } };
	double lv = 1.5;
	sink_t s = { 0 };
	CHECK(contour_extract(&g, &lv, 1, collect, &s, NULL) == CONTOUR_EARG && strstr(contour_error(), "1x4"),
	      "a 1-wide grid is refused: %s", contour_error());
	g.nx = 2;
	g.ny = 2;
	double bad = NAN;
	CHECK(contour_extract(&g, &bad, 1, collect, &s, NULL) == CONTOUR_EARG && strstr(contour_error(), "level 0"),
	      "a NaN level is refused: %s", contour_error());
	g.m[0] = INFINITY;
	CHECK(contour_extract(&g, &lv, 1, collect, &s, NULL) == CONTOUR_EARG, "a non-finite map is refused");
	g.m[0] = 0;
	s.stop_after = 1;
	double two[2] = { 0.5, 2.5 };
	CHECK(contour_extract(&g, two, 2, collect, &s, NULL) == CONTOUR_ECALLBACK && s.lines == 1,
	      "a callback returning < 0 stops the extraction: %s", contour_error());
	sink_free(&s);
	CHECK(contour_extract(&g, two, 0, collect, &s, NULL) == 0 && s.lines == 0, "no levels, no lines");
}

static void test_auto_levels(void)
{
	float z[6] = { 2, NAN, 5, 3, 4, INFINITY };
	contour_grid_t g = { z, 3, 2, { 0, 1, 0, 0, 0, 1 } };
	double lv[3];
	CHECK(contour_auto_levels(&g, 3, lv) == 3 && lv[0] == 2.75 && lv[1] == 3.5 && lv[2] == 4.25,
	      "auto levels split the finite range [2, 5] evenly: %g %g %g", lv[0], lv[1], lv[2]);
	float flat[4] = { 1, 1, NAN, 1 };
	contour_grid_t f = { flat, 2, 2, { 0, 1, 0, 0, 0, 1 } };
	CHECK(contour_auto_levels(&f, 3, lv) == 0, "a flat grid has no levels");
}

static void test_palette(void)
{
	meta_rgb_t c[7];
	contour_palette(c, 7);
	int distinct = 1;
	for (int i = 0; i < 7; i++)
		for (int k = 0; k < i; k++)
			if (c[i] == c[k])
				distinct = 0;
	CHECK(distinct && c[0] == 0x2c3e9e && c[6] == 0xa61c1c, "palette: 7 distinct colours, blue to red");
}

/* Meta output into memory. */
typedef struct {
	char buf[1 << 14];
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
	/* z = i on a 2 x 2 grid spread over x 0..2: bands 0 | 1 at x = 1, no data beyond x = 2 */
	float z[4] = { 0, 1, 0, 1 };
	contour_grid_t g = { z, 2, 2, { 0 } };
	contour_map_rect(g.m, 2, 2, 0, 0, 2, 3);
	double lv = 0.5;
	meta_rgb_t bands[2] = { 0xaaaaaa, 0xbbbbbb }, lines[1] = { 0xff0000 };
	contour_style_t st = { lines, 2 };
	meta_writer_t *w = meta_writer_new(mem_write, &mem, META_ENC_TEXT);
	int rc = meta_page(w, 3, 3);
	rc = rc < 0 ? rc : contour_write_bands(w, &g, &lv, 1, bands, 0x123456, 0, 0, 3, 3);
	rc = rc < 0 ? rc : contour_write_meta(w, &g, &lv, 1, &st, NULL);
	rc = rc < 0 ? rc : meta_end_page(w);
	int rc2 = meta_writer_close(w);
	CHECK(rc == 0 && rc2 == 0, "bands and lines written (%d: %s)", rc, contour_error());
	CHECK(strstr(mem.buf, "image 0 0 3 3\nrow 1 #aaaaaa 1 #bbbbbb 1 #123456\n"
	                      "row 1 #aaaaaa 1 #bbbbbb 1 #123456\nrow 1 #aaaaaa 1 #bbbbbb 1 #123456\n") != NULL,
	      "bands: one pixel per band, no data outside the grid");
	CHECK(strstr(mem.buf, "width 2\ncolour #ff0000\nstroke\nmove 1 3\ndraw 1 0\nend\n") != NULL,
	      "the iso-line x = 1 as one stroke, higher values on its left");
	mem.n = 0;
	w = meta_writer_new(mem_write, &mem, META_ENC_TEXT);
	g.m[1] = 0;
	g.m[2] = 0;
	rc = meta_page(w, 3, 3);
	CHECK(contour_write_bands(w, &g, &lv, 1, bands, 0, 0, 0, 3, 3) == CONTOUR_EARG &&
	      strstr(contour_error(), "not invertible"), "bands need an invertible map: %s", contour_error());
	meta_writer_close(w);
}

/* The shared marching-squares table (core/msq.c, used by contours and Voronoi boundaries)
 * derived again from the rule stated in msq.h: the above side on the left, saddles by s. */
static void test_msq_table(void)
{
	int bad = 0, entries = 0;
	for (int s = 0; s < 2; s++)
		for (int c = 0; c < 16; c++) {
			int up[4];
			for (int k = 0; k < 4; k++)
				up[k] = (c >> k) & 1;
			for (int e = 0; e < 4; e++) {
				int enters = up[e] && !up[(e + 1) & 3], want = -1;
				if (enters) {
					int leaves[4], n = 0;
					for (int x = 0; x < 4; x++)
						if (!up[x] && up[(x + 1) & 3])
							leaves[n++] = x;
					if (n == 1) {
						want = leaves[0];
					} else {
						/* saddle: the segment cuts off the corner shared by edge e and its
						 * neighbour; with s = 1 the cut corners are the below ones */
						int cut_next = up[(e + 1) & 3] == (s ? 0 : 1);  /* corner e+1 is cut */
						want = cut_next ? (e + 1) & 3 : (e + 3) & 3;
					}
					entries++;
				}
				if (msq_exit[s][c][e] != want)
					bad++;
			}
		}
	CHECK(bad == 0 && entries == 2 * (12 + 4), "msq_exit follows its rule (%d wrong, %d entries)", bad, entries);
	CHECK(msq_exit[1][5][0] == 1 && msq_exit[0][5][0] == 3, "saddle 5 entering by edge 0: s = 1 turns to edge 1, s = 0 to edge 3");
}

int main(void)
{
	test_msq_table();
	test_circle();
	test_joining();
	test_random_consistency();
	test_random_holes();
	test_saddle();
	test_nan();
	test_errors();
	test_palette();
	test_auto_levels();
	test_meta();
	return UNIT_DONE();
}
