/* fbcli.c: the command line shared by locus-vga and locus-xga (options to device options, job). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "cli/cli.h"
#include "cli/fbcli.h"
#include "fb/fbmode.h"
#include "quant/quant.h"
#include "cli/run.h"

enum { OPT_MODE = 0x2000, OPT_LIST, OPT_PALETTE, OPT_QUANT, OPT_DITHER, OPT_FIT, OPT_LETTERBOX, OPT_HOLD, OPT_DAC };

static const struct option fb_long[] = {
	{ "mode", required_argument, NULL, OPT_MODE },
	{ "list-modes", no_argument, NULL, OPT_LIST },
	{ "format", required_argument, NULL, 'f' },
	{ "palette", required_argument, NULL, OPT_PALETTE },
	{ "quant", required_argument, NULL, OPT_QUANT },
	{ "dither", required_argument, NULL, OPT_DITHER },
	{ "fit", required_argument, NULL, OPT_FIT },
	{ "letterbox", required_argument, NULL, OPT_LETTERBOX },
	{ "hold", required_argument, NULL, OPT_HOLD },
	{ "dac", required_argument, NULL, OPT_DAC },
	{ 0, 0, 0, 0 }
};

typedef struct {
	const fbm_modes_t *ml;
	const char *palette;
} fbcli_t;

static int on_option(cli_t *c, int key, const char *arg)
{
	fbcli_t *fc = c->user;
	switch (key) {
	case OPT_LIST:
		for (size_t k = 0; k < fc->ml->n; k++) {
			char line[256];
			fbm_describe(&fc->ml->modes[k], line, sizeof line);
			printf("%s%s\n", line, k == 0 ? " (default)" : "");
		}
		return 0;
	case OPT_MODE: return cli_set_option(c, "mode", arg) ? 64 : CLI_RUN;
	case 'f': return cli_set_option(c, "format", arg) ? 64 : CLI_RUN;
	case OPT_PALETTE:
		fc->palette = arg;
		return cli_set_option(c, "palette", arg) ? 64 : CLI_RUN;
	case OPT_QUANT: return cli_set_option(c, "quant", arg) ? 64 : CLI_RUN;
	case OPT_DITHER: return cli_set_option(c, "dither", arg) ? 64 : CLI_RUN;
	case OPT_FIT: return cli_set_option(c, "fit", arg) ? 64 : CLI_RUN;
	case OPT_LETTERBOX: return cli_set_option(c, "letterbox", arg) ? 64 : CLI_RUN;
	case OPT_HOLD: return cli_set_option(c, "hold", arg) ? 64 : CLI_RUN;
	case OPT_DAC: return cli_set_option(c, "dac", arg) ? 64 : CLI_RUN;
	}
	return cli_fail(c, 64, "unhandled option");
}

/* A palette file is checked before the run, so that its faults get their own exit status. */
static int check_palette_file(const cli_t *c, const char *path)
{
	if (!strcmp(path, "page") || !strcmp(path, "adaptive") || !strcmp(path, "shared") || quant_fixed_by_name(path) >= 0)
		return 0;
	FILE *fp = fopen(path, "rb");
	if (!fp)
		return cli_fail(c, 66, "cannot open palette file '%s'", path);
	unsigned char buf[65536];
	size_t n = fread(buf, 1, sizeof buf, fp);
	fclose(fp);
	if (n == sizeof buf)
		return cli_fail(c, 65, "%s: byte 65536: too long for a palette file", path);
	quant_palette_t pal;
	char err[300];
	if (quant_parse_palette(buf, n, path, QUANT_MAX, &pal, err, sizeof err)) {
		fprintf(stderr, "%s\n", err);
		return 65;
	}
	return 0;
}

static int run_job(const char *prog, const dev_job_t *job)
{
	char err[600];
	int st = dev_run(job, err, sizeof err);
	if (st == 65)
		fprintf(stderr, "%s\n", err);
	else if (st)
		fprintf(stderr, "%s: %s\n", prog, err);
	return st;
}

/* A temporary file (its name in name) holding the rest of stdin, or -1. */
static int spool_stdin(char *name, size_t n)
{
	const char *dir = getenv("TMPDIR");
	snprintf(name, n, "%s/locus-fb-in.XXXXXX", dir && *dir ? dir : "/tmp");
	int fd = mkstemp(name);
	if (fd < 0)
		return -1;
	char buf[65536];
	size_t k;
	int bad = 0;
	while (!bad && (k = fread(buf, 1, sizeof buf, stdin)) > 0)
		bad = write(fd, buf, k) != (ssize_t)k;
	if (close(fd) != 0 || bad || ferror(stdin)) {
		unlink(name);
		return -1;
	}
	return 0;
}

/* --palette shared: a first pass counts every page into one palette (written to a temporary
 * palette file), the second draws every page with it. stdin is spooled to a file for that. */
static int run_shared(cli_t *c, const char *prog, dev_job_t *job)
{
	char in[4096] = "", pal[4096], saved[sizeof c->options];
	const char *dir = getenv("TMPDIR");
	int st;
	if (strcmp(job->in, "-") == 0) {
		if (spool_stdin(in, sizeof in))
			return cli_fail(c, 74, "cannot keep standard input for the two passes of --palette shared");
		job->in = in;
	}
	snprintf(pal, sizeof pal, "%s/locus-fb-pal.XXXXXX", dir && *dir ? dir : "/tmp");
	int fd = mkstemp(pal);
	if (fd < 0) {
		st = cli_fail(c, 74, "cannot make a temporary palette file");
		goto done;
	}
	close(fd);
	memcpy(saved, c->options, sizeof saved);
	if ((st = cli_set_option(c, "palette", "page")) != 0 || (st = cli_set_option(c, "collect", pal)) != 0)
		goto done;
	dev_job_t first = *job;
	first.out = NULL;
	first.options = c->options;
	if ((st = run_job(prog, &first)) != 0)
		goto done;
	memcpy(c->options, saved, sizeof saved);
	if ((st = cli_set_option(c, "palette", pal)) != 0)
		goto done;
	job->options = c->options;
	st = run_job(prog, job);
done:
	unlink(pal);
	if (in[0])
		unlink(in);
	return st;
}

int fbcli_main(int argc, char **argv, const char *prog, const dev_ops_t *ops, const fbm_modes_t *ml)
{
	char usage[2048], names[128] = "";
	for (size_t k = 0; k < ml->n; k++)
		snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", k ? "|" : "", ml->modes[k].name);
	snprintf(usage, sizeof usage,
		"usage: %s [-o OUT|fb:/dev/fbN] [-f dump|png|pcx|bmp] [--mode %s] [options] [IN]\n"
		"Replay a Locus meta file (IN, default stdin) onto a %s framebuffer mode and write each\n"
		"page as the video memory dump, an indexed PNG, PCX or BMP (format from -f, else OUT's\n"
		"suffix, else PNG; page k of several goes to OUT with -00k before its suffix), or show it\n"
		"on a Linux framebuffer with -o fb:/dev/fb0.\n"
		"  --mode M         display mode (default %s); --list-modes lists them\n"
		"  --palette P      page (adaptive per page, default), shared (one from all pages),\n"
		"                   vga, ega, cube, grey, or FILE (#rrggbb lines or a 768-byte DAC dump)\n"
		"  --quant Q        best (median cut + k-means, default), median, octree\n"
		"  --dither D       fs (serpentine Floyd-Steinberg, default), ordered (Bayer 8x8), none\n"
		"  --fit F          aspect (default, letterboxed), fill (crop) or stretch\n"
		"  --letterbox C    bar colour #rrggbb with --fit aspect\n"
		"  --hold S         framebuffer: show each page S seconds, then restore the screen\n"
		"  --dac 6|8        palette precision: 6 bits as the hardware (default), or 8 for files\n"
		"  -O KEY=VALUE     device options (the same keys as above; locus-play -d %s -O ...)\n"
		"  --band-rows N, --mem-budget MIB, --help, --version\n",
		prog, names, ops->name, ml->modes[0].name, ops->name);
	fbcli_t fc = { ml, NULL };
	cli_t c;
	memset(&c, 0, sizeof c);
	c.prog = prog;
	c.usage = usage;
	c.extra = fb_long;
	c.extra_short = "f:";
	c.on_option = on_option;
	c.user = &fc;
	int st = cli_parse(&c, argc, argv);
	if (st != CLI_RUN)
		return st;
	const char *out = c.out ? c.out : "-";
	if (strncmp(out, "fb:", 3) == 0) {
		if (!out[3])
			return cli_fail(&c, 64, "-o fb: needs a framebuffer node, e.g. fb:/dev/fb0");
		if (cli_set_option(&c, "fb", out + 3))
			return 64;
		out = NULL;
	}
	if (fc.palette && (st = check_palette_file(&c, fc.palette)) != 0)
		return st;
	dev_job_t job = { c.in[0], out, ops, c.band_rows, c.budget, c.options[0] ? c.options : NULL };
	if (fc.palette && strcmp(fc.palette, "shared") == 0)
		return run_shared(&c, prog, &job);
	return run_job(prog, &job);
}
