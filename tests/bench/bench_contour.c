/* bench_contour.c: time contour_extract on the anchor workload (3-point distance sum, 1024x1024, 19 levels).
 *
 * usage: bench_contour [-n RUNS] [-o FILE.meta] [--help] [--version]
 *
 * The workload, identical in tests/bench/contourpy_anchor.py:
 *   grid  1024 x 1024 samples over [-3, 3] x [-3, 3] (x_i = -3 + 6 i / 1023)
 *   field z = |P - (-1, 0)| + |P - (1, 0)| + |P - (0, 1.2)|, as float
 *   levels 3.0, 3.5, ..., 12.0 (19 levels)
 * Only the extraction is timed (segments found and joined into polylines,
 * handed to a callback that counts them), median of RUNS runs (default 7).
 * Prints one human line and one "BENCH contour-locus SECONDS s ..." line.
 * With -o, also writes the map (colour bands + iso-lines) as a meta file on
 * a 1024 x 1024 page so it can be looked at.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "contour.h"
#include "locus_meta.h"

#define N 1024
#define NLEVELS 19

static int count_cb(void *user, unsigned level, const contour_point_t *p, size_t n, int closed)
{
	(void)level;
	size_t *sum = user;
	sum[0] += closed ? n : n - 1;     /* drawn segments */
	sum[1] += (size_t)(p[0].x >= 0);  /* touch the data */
	return 0;
}

static int write_meta(const char *path, const contour_grid_t *g, const double *levels)
{
	bench_meta_out_t o;
	if (bench_meta_open(&o, "bench_contour", path) != 0)
		return 74;
	meta_writer_t *w = o.w;
	meta_rgb_t bands[NLEVELS + 1], lines[NLEVELS];
	contour_palette(bands, NLEVELS + 1);
	for (int k = 0; k < NLEVELS + 1; k++) /* pale bands: mix with white */
		bands[k] = ((((bands[k] >> 16) & 255) + 255) / 2) << 16 |
		           ((((bands[k] >> 8) & 255) + 255) / 2) << 8 | (((bands[k] & 255) + 255) / 2);
	for (int k = 0; k < NLEVELS; k++)
		lines[k] = 0x000000;
	contour_style_t st = { lines, 1.0 };
	int rc = w ? 0 : -1;
	if (rc == 0)
		rc = meta_page(w, N, N);
	if (rc == 0)
		rc = contour_write_bands(w, g, levels, NLEVELS, bands, 0xffffff, 0, 0, N, N);
	if (rc == 0)
		rc = contour_write_meta(w, g, levels, NLEVELS, &st, NULL);
	if (rc == 0)
		rc = meta_end_page(w);
	return bench_meta_close(&o, rc, contour_error());
}

int main(int argc, char **argv)
{
	bench_opts_t opt = { "bench_contour",
		             "usage: bench_contour [-n RUNS] [-o FILE.meta]\n"
		             "Times contour extraction of a 1024x1024 3-point distance sum, 19 levels.\n",
		             7, NULL, 0 };
	for (int a = 1; a < argc; a++) {
		int k = bench_option(&opt, argc, argv, &a);
		if (k == BENCH_OPT_EXIT)
			return opt.exit_code;
		if (k == BENCH_OPT_OTHER)
			return bench_unknown(&opt, argv[a]);
	}
	int runs = opt.runs;
	float *z = malloc((size_t)N * N * sizeof *z);
	double levels[NLEVELS], *t = malloc(runs * sizeof *t);
	if (!z || !t) {
		fprintf(stderr, "bench_contour: out of memory\n");
		return 70;
	}
	static const double px[3] = { -1, 1, 0 }, py[3] = { 0, 0, 1.2 };
	for (int j = 0; j < N; j++)
		for (int i = 0; i < N; i++) {
			double x = -3 + 6.0 * i / (N - 1), y = -3 + 6.0 * j / (N - 1), s = 0;
			for (int k = 0; k < 3; k++)
				s += hypot(x - px[k], y - py[k]);
			z[(size_t)j * N + i] = (float)s;
		}
	for (int l = 0; l < NLEVELS; l++)
		levels[l] = 3.0 + 0.5 * l;
	contour_grid_t g = { z, N, N, { 0 } };
	contour_map_rect(g.m, N, N, 0.5, 0.5, N - 0.5, N - 0.5);
	contour_stats_t st = { 0 };
	size_t sum[2] = { 0, 0 };
	for (int r = 0; r < runs; r++) {
		sum[0] = sum[1] = 0;
		double t0 = bench_now();
		int rc = contour_extract(&g, levels, NLEVELS, count_cb, sum, &st);
		t[r] = bench_now() - t0;
		if (rc < 0) {
			fprintf(stderr, "bench_contour: %s\n", contour_error());
			return 70;
		}
	}
	double med = bench_median(t, runs);
	printf("contour 1024x1024, 19 levels: %.4f s (median of %d, best %.4f), %zu segments, "
	       "%zu polylines (%zu closed), %zu points\n",
	       med, runs, t[0], st.segments, st.polylines, st.closed, st.points);
	/* segments: marching-squares cell segments, as contourpy counts them (its
	 * points - 1 per line); a few are zero-length where a sample equals a
	 * level, and the polylines drop those repeated points */
	printf("BENCH contour-locus %.6f s segments=%zu polylines=%zu points=%zu\n", med, st.segments, st.polylines,
	       st.points);
	int rc = opt.out ? write_meta(opt.out, &g, levels) : 0;
	free(z);
	free(t);
	return rc;
}
