/* main-raster.c: locus-raster, the reference raster driver: meta file to PNG, PPM or RLE. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli/cli.h"
#include "image/image.h"
#include "cli/run.h"

extern const dev_ops_t dev_png_ops, dev_ppm_ops, dev_rle_ops;

static const char usage[] =
	"usage: locus-raster [-o OUT] [-f png|ppm|rle] [--antialias[=K]] [--band-rows N] [--mem-budget MIB] [IN]\n"
	"Replay a Locus meta file (IN, default stdin) at 24 bits per pixel into OUT (default\n"
	"stdout). The format comes from -f, else from OUT's suffix, else PNG. With more than\n"
	"one page, page k goes to OUT with -00k before its suffix (stdout, a device or a pipe:\n"
	"pages in a row). A file OUT is written to a temporary beside it and renamed only when\n"
	"the whole input replayed.\n"
	"  -f FORMAT        png, ppm or rle\n"
	"  --antialias[=K]  K x K samples per pixel averaged in linear light (K 2..16, default 4,\n"
	"                   0 or 1 exact); without it the exact mode, the reference\n"
	"  --band-rows N    render N rows at a time (default: whole page within the budget)\n"
	"  --mem-budget MIB page buffer budget for automatic banding (default 64)\n"
	"  --help, --version\n";

static int on_option(cli_t *c, int key, const char *arg)
{
	if (key != 'f')
		return cli_fail(c, 64, "unhandled option");
	if (img_format_by_name(arg) == IMG_FMT_UNKNOWN)
		return cli_fail(c, 64, "unknown format '%s' (png, ppm or rle)", arg);
	c->user = (void *)arg;
	return CLI_RUN;
}

int main(int argc, char **argv)
{
	cli_t c = { .prog = "locus-raster", .usage = usage, .extra_short = "f:", .on_option = on_option };
	int st = cli_parse(&c, argc, argv);
	if (st != CLI_RUN)
		return st;
	const char *out = c.out ? c.out : "-", *fmt = c.user;
	int f = fmt ? img_format_by_name(fmt) : strcmp(out, "-") ? img_format_by_suffix(out) : IMG_FMT_PNG;
	if (f == IMG_FMT_UNKNOWN)
		f = IMG_FMT_PNG;
	dev_job_t job = { c.in[0], out, f == IMG_FMT_PPM ? &dev_ppm_ops : f == IMG_FMT_RLE ? &dev_rle_ops : &dev_png_ops,
		c.band_rows, c.budget, c.options[0] ? c.options : NULL };
	char err[600];
	st = dev_run(&job, err, sizeof err);
	if (st == 65)
		fprintf(stderr, "%s\n", err);   /* already "FILE:LINE:COL: ..." or "FILE: byte N: ..." */
	else if (st)
		fprintf(stderr, "locus-raster: %s\n", err);
	return st;
}
