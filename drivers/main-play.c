/* main-play.c: locus-play, replay a meta file through any registered device in-process. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "run.h"

static void usage(FILE *f)
{
	fprintf(f,
		"usage: locus-play -d DEVICE [-o OUT] [-O OPTIONS] [--band-rows N] [IN]\n"
		"       locus-play -l\n"
		"Replay a Locus meta file (IN, default stdin) through DEVICE into OUT (default stdout).\n"
		"With more than one page and a file OUT, page k goes to OUT with -00k before its suffix.\n"
		"  -l               list the devices: name, output suffix (- for none), description\n"
		"  -O OPTIONS       device options, key=value[,key=value...]\n"
		"  --band-rows N    raster devices: render N rows at a time\n"
		"  --help, --version\n");
}

int main(int argc, char **argv)
{
	const char *in = "-", *out = NULL, *dev = NULL, *opts = NULL;
	unsigned long band = 0;
	int nin = 0;
	for (int k = 1; k < argc; k++) {
		const char *a = argv[k];
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			usage(stdout);
			return 0;
		} else if (!strcmp(a, "--version")) {
			printf("locus-play %s\n", LOCUS_VERSION);
			return 0;
		} else if (!strcmp(a, "-l")) {
			for (size_t i = 0; dev_registry[i]; i++) {
				const char *ext = dev_registry[i]->extension;
				printf("%-10s %-5s %s\n", dev_registry[i]->name, ext && ext[0] == '.' ? ext + 1 : "-",
					dev_registry[i]->description);
			}
			return 0;
		} else if (!strcmp(a, "-d") && k + 1 < argc) {
			dev = argv[++k];
		} else if (!strcmp(a, "-o") && k + 1 < argc) {
			out = argv[++k];
		} else if (!strcmp(a, "-O") && k + 1 < argc) {
			opts = argv[++k];
		} else if (!strcmp(a, "--band-rows") && k + 1 < argc) {
			char *e;
			band = strtoul(argv[++k], &e, 10);
			if (*e || band == 0 || band > 1000000000UL) {
				fprintf(stderr, "locus-play: --band-rows needs a positive number, not '%s'\n", argv[k]);
				return 64;
			}
		} else if (a[0] == '-' && a[1]) {
			fprintf(stderr, "locus-play: unknown or incomplete option '%s' (try --help)\n", a);
			return 64;
		} else if (nin++ == 0) {
			in = a;
		} else {
			fprintf(stderr, "locus-play: more than one input file ('%s')\n", a);
			return 64;
		}
	}
	if (!dev) {
		fprintf(stderr, "locus-play: no device given: use -d DEVICE (locus-play -l lists them)\n");
		return 64;
	}
	const dev_ops_t *ops = dev_find(dev);
	if (!ops) {
		fprintf(stderr, "locus-play: unknown device '%s' (locus-play -l lists them)\n", dev);
		return 64;
	}
	if (!ops->extension || !ops->extension[0])
		out = NULL;   /* the device writes nothing */
	else if (!out)
		out = "-";
	dev_job_t job = { in, out, ops, (unsigned)band, 0, opts };
	char err[600];
	int st = dev_run(&job, err, sizeof err);
	if (st == 65)
		fprintf(stderr, "%s\n", err);   /* already "FILE:LINE:COL: ..." or "FILE: byte N: ..." */
	else if (st)
		fprintf(stderr, "locus-play: %s\n", err);
	return st;
}
