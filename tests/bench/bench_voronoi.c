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
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "locus_meta.h"
#include "voronoi.h"

#ifndef LOCUS_VERSION
#define LOCUS_VERSION "unknown"
#endif

#define N 1024
#define NUCLEI 100

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + ts.tv_nsec * 1e-9;
}

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

static int cmp(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

static int fwrite_cb(void *user, const void *buf, size_t n)
{
	return fwrite(buf, 1, n, user) == n ? 0 : -1;
}

static int write_meta(const char *path, const voronoi_t *v, const voronoi_rect_t *r, unsigned threads)
{
	char tmp[4096];
	snprintf(tmp, sizeof tmp, "%s.tmp", path);
	FILE *f = fopen(tmp, "wb");
	if (!f) {
		fprintf(stderr, "bench_voronoi: %s: %s\n", tmp, strerror(errno));
		return 74;
	}
	meta_writer_t *w = meta_writer_new(fwrite_cb, f, META_ENC_TEXT);
	voronoi_style_t st = { 1, 1, 0x000000, 1.5, threads, 1, 0x000000, 3 };
	int rc = w ? meta_page(w, N, N) : -1;
	if (rc == 0)
		rc = voronoi_write_meta(w, v, r, &st, NULL);
	if (rc == 0)
		rc = meta_end_page(w);
	if (rc < 0)
		fprintf(stderr, "bench_voronoi: %s: %s\n", path,
		        *voronoi_error() ? voronoi_error() : w ? meta_writer_error(w) : "out of memory");
	int rc2 = w ? meta_writer_close(w) : 0;
	if (fclose(f) != 0 || rc2 < 0 || rc < 0) {
		if (rc >= 0)
			fprintf(stderr, "bench_voronoi: %s: write failed\n", path);
		remove(tmp);
		return 74;
	}
	if (rename(tmp, path) != 0) {
		fprintf(stderr, "bench_voronoi: %s: %s\n", path, strerror(errno));
		remove(tmp);
		return 74;
	}
	return 0;
}

int main(int argc, char **argv)
{
	int runs = 5, metric = VORONOI_ADDITIVE;
	unsigned threads = 0;
	const char *out = NULL;
	for (int a = 1; a < argc; a++) {
		if (!strcmp(argv[a], "--help")) {
			printf("usage: bench_voronoi [-n RUNS] [-t THREADS] [-m add|mul] [-o FILE.meta]\n"
			       "Times a weighted Voronoi tessellation of 100 point/segment nuclei at 1024x1024.\n");
			return 0;
		} else if (!strcmp(argv[a], "--version")) {
			printf("bench_voronoi %s\n", LOCUS_VERSION);
			return 0;
		} else if (!strcmp(argv[a], "-n") && a + 1 < argc) {
			runs = atoi(argv[++a]);
			if (runs < 1 || runs > 1000) {
				fprintf(stderr, "bench_voronoi: -n wants 1..1000\n");
				return 64;
			}
		} else if (!strcmp(argv[a], "-t") && a + 1 < argc) {
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
		} else if (!strcmp(argv[a], "-o") && a + 1 < argc) {
			out = argv[++a];
		} else {
			fprintf(stderr, "bench_voronoi: unknown argument '%s' (try --help)\n", argv[a]);
			return 64;
		}
	}
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
		double t0 = now();
		int rc = voronoi_label(&v, &r, threads, lab);
		double t1 = now();
		points = 0;
		if (rc == 0)
			rc = voronoi_boundaries(&v, &r, lab, count_cb, &points, &st);
		t[i] = now() - t0;
		tl[i] = t1 - t0;
		if (rc < 0) {
			fprintf(stderr, "bench_voronoi: %s\n", voronoi_error());
			return 70;
		}
	}
	qsort(t, runs, sizeof *t, cmp);
	qsort(tl, runs, sizeof *tl, cmp);
	printf("voronoi 1024x1024, %d nuclei (60 points, 40 segments, %s weights): %.4f s (median of %d; "
	       "labelling %.4f s), %zu crossings, %zu junction cells, %zu polylines (%zu closed), %zu points\n",
	       NUCLEI, metric ? "multiplicative" : "additive", t[runs / 2], runs, tl[runs / 2], st.crossings,
	       st.junctions, st.polylines, st.closed, points);
	printf("BENCH voronoi-locus %.6f s label_s=%.6f polylines=%zu points=%zu\n", t[runs / 2], tl[runs / 2],
	       st.polylines, points);
	int rc = out ? write_meta(out, &v, &r, threads) : 0;
	free(lab);
	free(t);
	free(tl);
	return rc;
}
