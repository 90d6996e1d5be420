/* main-ps.c: locus-ps, replay a meta file as EPS, printable PostScript or PDF. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli/cli.h"
#include "cli/run.h"

extern const dev_ops_t dev_eps_ops, dev_ps_ops, dev_pdf_ops;

static const char usage[] =
	"usage: locus-ps [-o OUT] [-f eps|ps|pdf] [--level 1|2|3] [--paper P] [OPTIONS] [IN]\n"
	"Replay a Locus meta file (IN, default stdin) as PostScript or PDF into OUT (default\n"
	"stdout). The form comes from -f, else from OUT's suffix (.eps, .ps, .pdf), else PS.\n"
	"PS and PDF hold every page in one file; EPS holds one page (several pages: OUT with\n"
	"-00k before its suffix).\n"
	"  -f, --form F        eps, ps or pdf\n"
	"  -l, --level N       PostScript language level 1, 2 or 3 (default; images: hex;\n"
	"                      ASCII85 or RunLength; level 3 compresses whole pages)\n"
	"  --paper P           page (default: the picture's own size), a4, a3, letter, legal, WxHmm\n"
	"  --orientation O     portrait (default) or landscape\n"
	"  --place fit|centre  on paper: fit inside the margins (default) or natural size centred\n"
	"  --scale F           natural size times F\n"
	"  --margin MM         margin with a paper (default 10)\n"
	"  --grey              grey levels (luminance) for monochrome printers\n"
	"  --dither DPI        images in black and white dots: an 8x8 ordered dither at DPI\n"
	"  --media             PostScript: ask for the paper with setpagedevice\n"
	"  --date              write a creation date (SOURCE_DATE_EPOCH if set, else now)\n"
	"  --title TEXT        document title\n"
	"  -O KEY=VALUE,...    the same as device options (locus-play -d eps|ps|pdf -O ...)\n"
	"  --help, --version\n";

enum { O_PAPER = 1000, O_ORIENT, O_PLACE, O_SCALE, O_MARGIN, O_GREY, O_MEDIA, O_DATE, O_TITLE, O_DITHER };

static const struct option longopts[] = {
	{ "form", required_argument, NULL, 'f' },
	{ "level", required_argument, NULL, 'l' },
	{ "paper", required_argument, NULL, O_PAPER },
	{ "orientation", required_argument, NULL, O_ORIENT },
	{ "place", required_argument, NULL, O_PLACE },
	{ "scale", required_argument, NULL, O_SCALE },
	{ "margin", required_argument, NULL, O_MARGIN },
	{ "grey", no_argument, NULL, O_GREY },
	{ "dither", required_argument, NULL, O_DITHER },
	{ "media", no_argument, NULL, O_MEDIA },
	{ "date", no_argument, NULL, O_DATE },
	{ "title", required_argument, NULL, O_TITLE },
	{ 0, 0, 0, 0 }
};

typedef struct {
	const char *form;
} prog_t;

static int on_option(cli_t *c, int key, const char *arg)
{
	prog_t *pr = c->user;
	switch (key) {
	case 'f':
		if (strcmp(arg, "eps") && strcmp(arg, "ps") && strcmp(arg, "pdf"))
			return cli_fail(c, 64, "unknown form '%s' (eps, ps or pdf)", arg);
		pr->form = arg;
		return CLI_RUN;
	case 'l': return cli_set_option(c, "level", arg) ? 64 : CLI_RUN;
	case O_PAPER: return cli_set_option(c, "paper", arg) ? 64 : CLI_RUN;
	case O_ORIENT: return cli_set_option(c, "orientation", arg) ? 64 : CLI_RUN;
	case O_PLACE: return cli_set_option(c, "place", arg) ? 64 : CLI_RUN;
	case O_SCALE: return cli_set_option(c, "scale", arg) ? 64 : CLI_RUN;
	case O_MARGIN: return cli_set_option(c, "margin", arg) ? 64 : CLI_RUN;
	case O_GREY: return cli_set_option(c, "grey", "yes") ? 64 : CLI_RUN;
	case O_DITHER: return cli_set_option(c, "dither", arg) ? 64 : CLI_RUN;
	case O_MEDIA: return cli_set_option(c, "media", "yes") ? 64 : CLI_RUN;
	case O_DATE: return cli_set_option(c, "date", "yes") ? 64 : CLI_RUN;
	case O_TITLE: return cli_set_option(c, "title", arg) ? 64 : CLI_RUN;
	default: return 64;
	}
}

static const char *suffix_form(const char *out)
{
	const char *dot = strrchr(out, '.');
	if (!dot || strchr(dot, '/'))
		return NULL;
	if (!strcmp(dot, ".eps") || !strcmp(dot, ".epsf") || !strcmp(dot, ".epsi"))
		return "eps";
	if (!strcmp(dot, ".ps"))
		return "ps";
	if (!strcmp(dot, ".pdf"))
		return "pdf";
	return NULL;
}

int main(int argc, char **argv)
{
	prog_t pr = { NULL };
	cli_t c;
	memset(&c, 0, sizeof c);
	c.prog = "locus-ps";
	c.usage = usage;
	c.extra = longopts;
	c.extra_short = "f:l:";
	c.on_option = on_option;
	c.user = &pr;
	int st = cli_parse(&c, argc, argv);
	if (st != CLI_RUN)
		return st;
	const char *out = c.out ? c.out : "-";
	const char *form = pr.form ? pr.form : strcmp(out, "-") ? suffix_form(out) : NULL;
	if (!form)
		form = "ps";
	const dev_ops_t *ops = !strcmp(form, "eps") ? &dev_eps_ops : !strcmp(form, "pdf") ? &dev_pdf_ops : &dev_ps_ops;
	/* PS and PDF hold every page in one output; EPS has a file per page */
	dev_job_t job = { c.in[0], out, ops, 0, 0, c.options[0] ? c.options : NULL };
	char err[600];
	st = ops == &dev_eps_ops ? dev_run(&job, err, sizeof err) : dev_run_document(&job, err, sizeof err);
	if (st == 65)
		fprintf(stderr, "%s\n", err);   /* already "FILE:LINE:COL: ..." or "FILE: line N: ..." */
	else if (st)
		fprintf(stderr, "locus-ps: %s\n", err);
	return st;
}
