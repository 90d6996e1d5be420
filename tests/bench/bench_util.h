/* bench_util.h: timing, medians, common options and all-or-nothing meta output of the bench programs.
 *
 * Shared by tests/bench/bench_contour.c and tests/bench/bench_voronoi.c (compiled by
 * scripts/bench.sh, not by the Makefile). Everything is static inline so that a program
 * that does not use a helper gets no unused-function warning.
 */
#ifndef BENCH_UTIL_H
#define BENCH_UTIL_H

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "locus_meta.h"

#ifndef LOCUS_VERSION
#define LOCUS_VERSION "unknown"
#endif

/* bench_now: monotonic clock in seconds */
static inline double bench_now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* bench_cmp_double: qsort order of doubles */
static inline int bench_cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

/* bench_median: sorts the N > 0 times T in place and returns the median (t[n / 2]) */
static inline double bench_median(double *t, int n)
{
	qsort(t, (size_t)n, sizeof *t, bench_cmp_double);
	return t[n / 2];
}

/* Options every bench program takes: --help, --version, -n RUNS (1..1000), -o FILE.meta */
typedef struct {
	const char *prog;  /* program name, for messages */
	const char *usage; /* --help text (usage line and what is timed) */
	int runs;          /* -n: the default before parsing */
	const char *out;   /* -o: NULL when not given */
	int exit_code;     /* set when bench_option returns BENCH_OPT_EXIT */
} bench_opts_t;

enum {
	BENCH_OPT_DONE = 0,  /* argv[*a] (and its value) was a common option */
	BENCH_OPT_OTHER = 1, /* not a common option: the program parses it */
	BENCH_OPT_EXIT = 2   /* stop now with o->exit_code (after --help, --version or an error) */
};

/* bench_option: parse argv[*a] if it is a common option, advancing *a past its value */
static inline int bench_option(bench_opts_t *o, int argc, char **argv, int *a)
{
	const char *s = argv[*a];
	if (!strcmp(s, "--help")) {
		fputs(o->usage, stdout);
		o->exit_code = 0;
		return BENCH_OPT_EXIT;
	}
	if (!strcmp(s, "--version")) {
		printf("%s %s\n", o->prog, LOCUS_VERSION);
		o->exit_code = 0;
		return BENCH_OPT_EXIT;
	}
	if (!strcmp(s, "-n") && *a + 1 < argc) {
		o->runs = atoi(argv[++*a]);
		if (o->runs < 1 || o->runs > 1000) {
			fprintf(stderr, "%s: -n wants 1..1000\n", o->prog);
			o->exit_code = 64;
			return BENCH_OPT_EXIT;
		}
		return BENCH_OPT_DONE;
	}
	if (!strcmp(s, "-o") && *a + 1 < argc) {
		o->out = argv[++*a];
		return BENCH_OPT_DONE;
	}
	return BENCH_OPT_OTHER;
}

/* bench_unknown: the message for an argument nobody took; returns the usage exit code 64 */
static inline int bench_unknown(const bench_opts_t *o, const char *arg)
{
	fprintf(stderr, "%s: unknown argument '%s' (try --help)\n", o->prog, arg);
	return 64;
}

/* A meta file written to PATH.tmp and renamed when complete, so a failure leaves no file */
typedef struct {
	const char *prog, *path;
	char tmp[4096];
	FILE *f;
	meta_writer_t *w; /* NULL when the writer could not be made (out of memory) */
} bench_meta_out_t;

/* bench_fwrite: meta writer callback onto a FILE * */
static inline int bench_fwrite(void *user, const void *buf, size_t n)
{
	return fwrite(buf, 1, n, user) == n ? 0 : -1;
}

/* bench_meta_open: start PATH as a text meta file; 0, or prints why and returns 74 */
static inline int bench_meta_open(bench_meta_out_t *o, const char *prog, const char *path)
{
	o->prog = prog;
	o->path = path;
	snprintf(o->tmp, sizeof o->tmp, "%s.tmp", path);
	o->f = fopen(o->tmp, "wb");
	o->w = NULL;
	if (!o->f) {
		fprintf(stderr, "%s: %s: %s\n", prog, o->tmp, strerror(errno));
		return 74;
	}
	o->w = meta_writer_new(bench_fwrite, o->f, META_ENC_TEXT);
	return 0;
}

/* bench_meta_close: finish the file. RC < 0 means drawing failed with message ERR (empty: the
 * writer's own message); then, or when closing fails, the message is printed, the temporary
 * file removed and 74 returned. 0 when PATH is complete. */
static inline int bench_meta_close(bench_meta_out_t *o, int rc, const char *err)
{
	if (rc < 0)
		fprintf(stderr, "%s: %s: %s\n", o->prog, o->path,
		        err && *err ? err : o->w ? meta_writer_error(o->w) : "out of memory");
	int rc2 = o->w ? meta_writer_close(o->w) : 0;
	if (fclose(o->f) != 0 || rc2 < 0 || rc < 0) {
		if (rc >= 0)
			fprintf(stderr, "%s: %s: write failed\n", o->prog, o->path);
		remove(o->tmp);
		return 74;
	}
	if (rename(o->tmp, o->path) != 0) {
		fprintf(stderr, "%s: %s: %s\n", o->prog, o->path, strerror(errno));
		remove(o->tmp);
		return 74;
	}
	return 0;
}

#endif
