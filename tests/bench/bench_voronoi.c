/* bench_voronoi.c: time a weighted Voronoi tessellation of 100 mixed point/segment nuclei at 1024x1024.
 *
 * usage: bench_voronoi [-n RUNS] [-t THREADS] [-m add|mul] [-o FILE.meta] [--help] [--version]
 *
 * Workload: 100 nuclei from a fixed xorshift64* sequence in the unit square,
 * 60 points and 40 segments (length up to 0.15), additive weights in
 * [0, 0.04) (or, with -m mul, multiplicative weights in [0.7, 1.3)), drawn on
 * a 1024 x 1024 page. Timed: labelling every pixel (THREADS threads, default
 * all online CPUs) and tracing the boundaries into joined polylines; the
 * meta output is not timed. Median of RUNS runs (default 5). Prints one
 * human line and one "BENCH voronoi-locus SECONDS s ..." line. With -o, also
 * writes cells + boundaries as a meta file so it can be looked at.
 *
 * There is no exact anchor: qhull (rbox 100000 D2 t1 | qvoronoi o) computes
 * unweighted point diagrams only; it is context, not the same task.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "locus_meta.h"
#include "voronoi.h"

#define N 1024
#define NUCLEI 100

static unsigned long long rng = 0x2545f4914f6cdd1dULL;
static double uniform(void)
{
	rng ^= rng >> 12;
	rng ^= rng << 25;
	rng ^= rng >> 27;
	return ((rng * 0x2545f4914f6cdd1dULL) >> 11) * (1.0 / 9007199254740992.0);
}

static int count_cb(void *user, int32_t l, int32_t r, const voronoi_point_t *p, size_t n, int closed)
{
	(void)l;
	(void)r;
	(void)p;
	(void)closed;
	*(size_t *)user += n;
	return 0;
}

static int write_meta(const char *path, const voronoi_t *v, const voronoi_rect_t *r, unsigned threads)
{
	bench_meta_out_t o;
	if (bench_meta_open(&o, "bench_voronoi", path) != 0)
		return 74;
	voronoi_style_t st = { 1, 1, 0x000000, 1.5, threads, 1, 0x000000, 3 };
	int rc = o.w ? meta_page(o.w, N, N) : -1;
	if (rc == 0)
		rc = voronoi_write_meta(o.w, v, r, &st, NULL);
	if (rc == 0)
		rc = meta_end_page(o.w);
	return bench_meta_close(&o, rc, voronoi_error());
}

int main(int argc, char **argv)
{
	bench_opts_t opt = { "bench_voronoi",
		             "usage: bench_voronoi [-n RUNS] [-t THREADS] [-m add|mul] [-o FILE.meta]\n"
		             "Times a weighted Voronoi tessellation of 100 point/segment nuclei at 1024x1024.\n",
		             5, NULL, 0 };
	int metric = VORONOI_ADDITIVE;
	unsigned threads = 0;
	for (int a = 1; a < argc; a++) {
		int k = bench_option(&opt, argc, argv, &a);
		if (k == BENCH_OPT_EXIT)
			return opt.exit_code;
		if (k == BENCH_OPT_DONE)
			continue;
		if (!strcmp(argv[a], "-t") && a + 1 < argc) {
			threads = (unsigned)atoi(argv[++a]);
		} else if (!strcmp(argv[a], "-m") && a + 1 < argc) {
			a++;
			if (!strcmp(argv[a], "add"))
				metric = VORONOI_ADDITIVE;
			else if (!strcmp(argv[a], "mul"))
				metric = VORONOI_MULTIPLICATIVE;
			else {
				fprintf(stderr, "bench_voronoi: -m wants add or mul\n");
				return 64;
			}
		} else {
			return bench_unknown(&opt, argv[a]);
		}
	}
	int runs = opt.runs;
	voronoi_nucleus_t nuc[NUCLEI];
	for (int k = 0; k < NUCLEI; k++) {
		double x = uniform(), y = uniform(), ang = uniform() * 6.283185307179586, len = 0.03 + 0.12 * uniform();
		double w = uniform();
		voronoi_nucleus_t *n = &nuc[k];
		n->kind = k % 5 < 3 ? VORONOI_POINT : VORONOI_SEGMENT;
		n->a[0] = x;
		n->a[1] = y;
		n->a[2] = 0;
		n->b[0] = x + len * cos(ang);
		n->b[1] = y + len * sin(ang);
		n->b[2] = 0;
		n->weight = metric == VORONOI_ADDITIVE ? 0.04 * w : 0.7 + 0.6 * w;
		/* light, distinct colours */
		n->colour = (meta_rgb_t)(0x808080 + ((unsigned)(uniform() * 0x7f) << 16) +
		                         ((unsigned)(uniform() * 0x7f) << 8) + (unsigned)(uniform() * 0x7f));
	}
	voronoi_t v = { nuc, NUCLEI, metric, { 0 } };
	voronoi_map_window(v.m, 0, 0, 1, 1, 0, 0, N, N);
	voronoi_rect_t r = { 0, 0, N, N };
	int32_t *lab = malloc((size_t)N * N * sizeof *lab);
	double *t = malloc(runs * sizeof *t), *tl = malloc(runs * sizeof *tl);
	if (!lab || !t || !tl) {
		fprintf(stderr, "bench_voronoi: out of memory\n");
		return 70;
	}
	voronoi_stats_t st = { 0 };
	size_t points = 0;
	for (int i = 0; i < runs; i++) {
		double t0 = bench_now();
		int rc = voronoi_label(&v, &r, threads, lab);
		double t1 = bench_now();
		points = 0;
		if (rc == 0)
			rc = voronoi_boundaries(&v, &r, lab, count_cb, &points, &st);
		t[i] = bench_now() - t0;
		tl[i] = t1 - t0;
		if (rc < 0) {
			fprintf(stderr, "bench_voronoi: %s\n", voronoi_error());
			return 70;
		}
	}
	double med = bench_median(t, runs), med_label = bench_median(tl, runs);
	printf("voronoi 1024x1024, %d nuclei (60 points, 40 segments, %s weights): %.4f s (median of %d; "
	       "labelling %.4f s), %zu crossings, %zu junction cells, %zu polylines (%zu closed), %zu points\n",
	       NUCLEI, metric ? "multiplicative" : "additive", med, runs, med_label, st.crossings,
	       st.junctions, st.polylines, st.closed, points);
	printf("BENCH voronoi-locus %.6f s label_s=%.6f polylines=%zu points=%zu\n", med, med_label,
	       st.polylines, points);
	int rc = opt.out ? write_meta(opt.out, &v, &r, threads) : 0;
	free(lab);
	free(t);
	free(tl);
	return rc;
}
