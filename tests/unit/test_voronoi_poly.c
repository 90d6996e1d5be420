/* test_voronoi_poly.c: polyline nuclei of the 2D tessellation: distance, labels against brute force and against the split segments, both metrics, checks. */
#include <math.h>
#include <stdlib.h>

#include "unit.h"
#include "voronoi.h"

#define W 96
#define H 80

static double zig[] = {-2.5, -2, 0, -1, 0, 0, 0.5, -1.5, 0, 2, 0.5, 0, 2.2, 2.4, 0};   /* 5 points */

static voronoi_nucleus_t nuc(int kind, double x0, double y0, double x1, double y1, double w)
{
	voronoi_nucleus_t n;
	memset(&n, 0, sizeof n);
	n.kind = kind;
	n.a[0] = x0, n.a[1] = y0, n.b[0] = x1, n.b[1] = y1;
	n.weight = w;
	return n;
}

/* Labels of nuclei (the polyline first) under metric, and of the same nuclei with the polyline
 * split into its 4 segments (indices 0..3, the others shifted by 3): the polyline's cell must be
 * the union of its segments' cells, every other cell the same. Also against brute force. */
static void compare(int metric, double wpoly, const char *what)
{
	voronoi_nucleus_t a[4], b[7];
	a[0] = nuc(VORONOI_POLYLINE, 0, 0, 0, 0, wpoly);
	a[0].pts = zig;
	a[0].npts = 5;
	a[1] = nuc(VORONOI_POINT, -1.5, 2, 0, 0, metric ? 1 : 0);
	a[2] = nuc(VORONOI_SEGMENT, 0.5, 2.5, 2.5, 1.5, metric ? 1 : 0);
	a[3] = nuc(VORONOI_POINT, 2.5, -2.5, 0, 0, metric ? 0.7 : 0.2);
	for (int i = 0; i < 4; i++)
		b[i] = nuc(VORONOI_SEGMENT, zig[3 * i], zig[3 * i + 1], zig[3 * i + 3], zig[3 * i + 4], wpoly);
	for (int i = 1; i < 4; i++)
		b[i + 3] = a[i];
	voronoi_t va = {a, 4, metric, {0}}, vb = {b, 7, metric, {0}};
	voronoi_map_window(va.m, -3, -3, 3, 3, 0, 0, W, H);
	memcpy(vb.m, va.m, sizeof va.m);
	voronoi_rect_t r = {0, 0, W, H};
	int32_t *la = malloc(W * H * sizeof *la), *lb = malloc(W * H * sizeof *lb);
	int rc = voronoi_check(&va);
	CHECK(rc == 0, "%s: the tessellation with a polyline nucleus is accepted (%s)", what, rc ? voronoi_error() : "");
	rc = voronoi_label(&va, &r, 2, la) | voronoi_label(&vb, &r, 2, lb);
	int split = 0, brute = 0, owned = 0;
	for (int j = 0; j < H; j++)
		for (int i = 0; i < W; i++) {
			int32_t x = la[j * W + i], y = lb[j * W + i];
			int32_t yy = y < 4 ? 0 : y - 3;
			/* a tie between the polyline's own segments is no tie in va; one between a segment
			 * and another nucleus may go either way in the two: count only clear cases */
			double p[3], d1, d2;
			p[0] = -3 + 6 * (i + 0.5) / W;
			p[1] = -3 + 6 * (j + 0.5) / H;
			p[2] = 0;
			size_t s2;
			voronoi_nearest2(b, 7, metric, p, &d1, &s2, &d2);
			int tie = d2 - d1 < 1e-12 && (s2 < 4) != (y < 4);
			split += x != yy && !tie;
			brute += (size_t)x != voronoi_nearest(a, 4, metric, p, NULL);
			owned += x == 0;
		}
	CHECK(rc == 0 && split == 0, "%s: the polyline's cell is the union of its segments' cells (%d pixels differ)", what, split);
	CHECK(brute == 0, "%s: accelerated labels equal brute force (%d differ)", what, brute);
	CHECK(owned > W * H / 8, "%s: the polyline owns %d of %d pixels", what, owned, W * H);
	free(la);
	free(lb);
}

int main(void)
{
	voronoi_nucleus_t n = nuc(VORONOI_POLYLINE, 0, 0, 0, 0, 0);
	n.pts = zig;
	n.npts = 5;
	/* the distance is the smallest over the segments, checked on a grid against the segments */
	double worst = 0;
	for (int j = 0; j <= 60; j++)
		for (int i = 0; i <= 60; i++) {
			double p[3] = {-3 + 0.1 * i, -3 + 0.1 * j, 0.3}, best = INFINITY;
			for (int s = 0; s < 4; s++) {
				voronoi_nucleus_t g = nuc(VORONOI_SEGMENT, zig[3 * s], zig[3 * s + 1], zig[3 * s + 3], zig[3 * s + 4], 0);
				best = fmin(best, voronoi_distance(&g, p));
			}
			worst = fmax(worst, fabs(voronoi_distance(&n, p) - best));
		}
	CHECK(worst == 0, "polyline distance = the smallest segment distance on a 61x61 grid (worst difference %g)", worst);
	compare(VORONOI_ADDITIVE, 0.3, "additive");
	compare(VORONOI_MULTIPLICATIVE, 1.4, "multiplicative");
	/* checks: one point is not a polyline, coordinates must be finite */
	voronoi_t v = {&n, 1, VORONOI_ADDITIVE, {0}};
	voronoi_map_window(v.m, -3, -3, 3, 3, 0, 0, W, H);
	n.npts = 1;
	CHECK(voronoi_check(&v) < 0 && strstr(voronoi_error(), "at least 2 points"), "a one-point polyline is refused: %s", voronoi_error());
	n.npts = 5;
	double bad[15];
	memcpy(bad, zig, sizeof bad);
	bad[7] = NAN;
	n.pts = bad;
	CHECK(voronoi_check(&v) < 0 && strstr(voronoi_error(), "not finite"), "a NaN coordinate is refused: %s", voronoi_error());
	return UNIT_DONE();
}
