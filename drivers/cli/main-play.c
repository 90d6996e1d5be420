/* main-play.c: locus-play, replay a meta file through any registered device in-process. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli/cli.h"
#include "cli/run.h"

static const char usage[] =
	"usage: locus-play -d DEVICE [-o OUT] [-O OPTIONS] [--band-rows N] [--mem-budget MIB] [IN]\n"
	"       locus-play -l\n"
	"       locus-play --list-devices\n"
	"Replay a Locus meta file (IN, default stdin) through DEVICE into OUT (default stdout).\n"
	"With more than one page and a file OUT, page k goes to OUT with -00k before its suffix.\n"
	"A file OUT is written to a temporary beside it and renamed only when the whole input\n"
	"replayed; a device, a pipe or stdout is written in place, pages in a row.\n"
	"  -d DEVICE        the device (-l lists them)\n"
	"  -l               list the devices: name, output suffix (- for none), description\n"
	"  --list-devices   list attached USB printers as -o names, with their IEEE-1284 IDs\n"
	"  -O OPTIONS       device options, key=value[,key=value...]; unknown keys are refused\n"
	"  --band-rows N    raster devices: render N rows at a time\n"
	"  --mem-budget MIB raster devices: page buffer budget for automatic banding (default 64)\n"
	"  --help, --version\n";

/* -l: name, output suffix (- for none), description; a write error is named with its cause. */
static int list_devices(cli_t *c)
{
	char err[600];
	io_transport_t *t = io_open_write("-", err, sizeof err);
	if (!t)
		return cli_fail(c, 74, "%s", err);
	for (size_t i = 0; dev_registry[i]; i++) {
		const char *ext = dev_registry[i]->extension;
		io_printf(t, "%-10s %-5s %s\n", dev_registry[i]->name, ext && ext[0] == '.' ? ext + 1 : "-",
			dev_registry[i]->description);
	}
	return io_close_err(t, IO_COMMIT, err, sizeof err) ? cli_fail(c, 74, "%s", err) : 0;
}

/* --list-devices: attached USB printer-class devices, in the form -o takes. */
static int list_links(cli_t *c)
{
	char err[600];
	io_transport_t *t = io_open_write("-", err, sizeof err);
	if (!t)
		return cli_fail(c, 74, "%s", err);
	if (io_list_devices(t, err, sizeof err) < 0) {
		io_close(t, IO_ABORT);
		return cli_fail(c, 69, "%s", err);
	}
	return io_close_err(t, IO_COMMIT, err, sizeof err) ? cli_fail(c, 74, "%s", err) : 0;
}

static int on_option(cli_t *c, int key, const char *arg)
{
	switch (key) {
	case 'L':
		return list_links(c);
	case 'd':
		c->user = (void *)arg;
		return CLI_RUN;
	case 'l':
		return list_devices(c);
	default:
		return cli_fail(c, 64, "unhandled option");
	}
}

int main(int argc, char **argv)
{
	static const struct option longs[] = { { "list-devices", no_argument, NULL, 'L' }, { 0, 0, 0, 0 } };
	cli_t c = { .prog = "locus-play", .usage = usage, .extra = longs, .extra_short = "d:l", .on_option = on_option };
	int st = cli_parse(&c, argc, argv);
	if (st != CLI_RUN)
		return st;
	const char *dev = c.user, *out = c.out;
	if (!dev)
		return cli_fail(&c, 64, "no device given: use -d DEVICE (locus-play -l lists them)");
	const dev_ops_t *ops = dev_find(dev);
	if (!ops)
		return cli_fail(&c, 64, "unknown device '%s' (locus-play -l lists them)", dev);
	if (!ops->extension || !ops->extension[0])
		out = NULL;   /* the device writes nothing */
	else if (!out)
		out = "-";
	dev_job_t job = { c.in[0], out, ops, c.band_rows, c.budget, c.options[0] ? c.options : NULL };
	char err[600];
	st = dev_run(&job, err, sizeof err);
	if (st == 65)
		fprintf(stderr, "%s\n", err);   /* already "FILE:LINE:COL: ..." or "FILE: byte N: ..." */
	else if (st)
		fprintf(stderr, "locus-play: %s\n", err);
	return st;
}
