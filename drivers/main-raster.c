/* main-raster.c: locus-raster, the reference raster driver: meta file to PNG, PPM or RLE. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "image.h"
#include "run.h"

extern const dev_ops_t dev_png_ops, dev_ppm_ops, dev_rle_ops;

static void usage(FILE *f)
{
	fprintf(f,
		"usage: locus-raster [-o OUT] [-f png|ppm|rle] [--band-rows N] [--mem-budget MIB] [IN]\n"
		"Replay a Locus meta file (IN, default stdin) at 24 bits per pixel into OUT (default\n"
		"stdout). The format comes from -f, else from OUT's suffix, else PNG. With more than\n"
		"one page, page k goes to OUT with -00k before its suffix (stdout: pages in a row).\n"
		"  --band-rows N    render N rows at a time (default: whole page within the budget)\n"
		"  --mem-budget MIB page buffer budget for automatic banding (default 64)\n"
		"  --help, --version\n");
}

static int number(const char *s, unsigned long *v)
{
	char *e;
	if (!s || *s < '0' || *s > '9')
		return -1;
	*v = strtoul(s, &e, 10);
	return *e || *v > 1000000000UL ? -1 : 0;
}

int main(int argc, char **argv)
{
	const char *in = "-", *out = "-", *fmt = NULL;
	unsigned long band = 0, budget = 0;
	int nin = 0;
	for (int k = 1; k < argc; k++) {
		const char *a = argv[k];
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			usage(stdout);
			return 0;
		} else if (!strcmp(a, "--version")) {
			printf("locus-raster %s\n", LOCUS_VERSION);
			return 0;
		} else if (!strcmp(a, "-o") && k + 1 < argc) {
			out = argv[++k];
		} else if (!strcmp(a, "-f") && k + 1 < argc) {
			fmt = argv[++k];
		} else if (!strcmp(a, "--band-rows") && k + 1 < argc) {
			if (number(argv[++k], &band) || band == 0) {
				fprintf(stderr, "locus-raster: --band-rows needs a positive number, not '%s'\n", argv[k]);
				return 64;
			}
		} else if (!strcmp(a, "--mem-budget") && k + 1 < argc) {
			if (number(argv[++k], &budget) || budget == 0 || budget > 1 << 20) {
				fprintf(stderr, "locus-raster: --mem-budget needs a size in MiB, not '%s'\n", argv[k]);
				return 64;
			}
		} else if (a[0] == '-' && a[1]) {
			fprintf(stderr, "locus-raster: unknown or incomplete option '%s' (try --help)\n", a);
			return 64;
		} else if (nin++ == 0) {
			in = a;
		} else {
			fprintf(stderr, "locus-raster: more than one input file ('%s')\n", a);
			return 64;
		}
	}
	int f = fmt ? dev_format_by_name(fmt) : strcmp(out, "-") ? dev_format_by_suffix(out) : DEV_FMT_PNG;
	if (f == DEV_FMT_UNKNOWN) {
		if (fmt) {
			fprintf(stderr, "locus-raster: unknown format '%s' (png, ppm or rle)\n", fmt);
			return 64;
		}
		f = DEV_FMT_PNG;
	}
	dev_job_t job = { in, out, f == DEV_FMT_PPM ? &dev_ppm_ops : f == DEV_FMT_RLE ? &dev_rle_ops : &dev_png_ops,
		(unsigned)band, (size_t)budget << 20, NULL };
	char err[600];
	int st = dev_run(&job, err, sizeof err);
	if (st == 65)
		fprintf(stderr, "%s\n", err);   /* already "FILE:LINE:COL: ..." or "FILE: byte N: ..." */
	else if (st)
		fprintf(stderr, "locus-raster: %s\n", err);
	return st;
}
