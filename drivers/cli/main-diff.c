/* main-diff.c: locus-diff, compare two outputs of one kind (rasters, HP-GL, PostScript/PDF, meta). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli/cli.h"
#include "diff/diff.h"

static const char usage[] =
	"usage: locus-diff [-v] [--json] [--tolerance T] [--max-pixels N] [--psnr DB] [--scale]\n"
	"                  [--diff-image OUT.png] [--page N] [--semantic] [--render] [--dpi N]\n"
	"                  [--strict-order] [--hpgl-tolerance U] [-o OUT] A B\n"
	"Compare two outputs of one kind, told from their content: rasters (PNG, PPM, Locus RLE,\n"
	"PCX, BMP, DPX, Cineon), HP-GL, PostScript/EPS/PDF, or Locus meta files (rendered by the\n"
	"reference raster device, or statement by statement with --semantic). A one-line summary\n"
	"(to OUT, default stdout), details with -v, a JSON object with --json.\n"
	"Exit 0: same (or within the tolerances), 1: they differ, 2: trouble (usage, unreadable or\n"
	"bad input, out of memory, a write error), as cmp(1) and diff(1).\n"
	"  --tolerance T      channel differences up to T (or R,G,B each) count as equal\n"
	"  --max-diff D       the same as --tolerance D\n"
	"  --max-pixels N     accept up to N differing pixels\n"
	"  --psnr DB          accept when the PSNR is at least DB decibels\n"
	"  --scale            pictures of different sizes: B resampled (nearest) to A's size\n"
	"  --diff-image OUT.png   A faded, the differing pixels red\n"
	"  --page N           the page of meta, PostScript and PDF inputs (default 1)\n"
	"  --semantic         meta files: compare statements, not pixels\n"
	"  --render           PostScript/PDF: render both with Ghostscript (--dpi, default 72), compare pixels\n"
	"  --strict-order     HP-GL: stroke order and direction count\n"
	"  --hpgl-tolerance U HP-GL: points may move up to U plotter units (default 0.5)\n"
	"  --band-rows N, --mem-budget MIB   banding of the meta files' replay\n"
	"  -v, --verbose      details: where, the first differences\n"
	"  --help, --version\n";

/* The program's own options (cli.h). */
typedef struct {
	diff_opts_t d;
	unsigned long page, dpi;
	int semantic, render;
	const char *diff_image;
} opts_t;

enum { OPT_MAX_PIXELS = 0x2000, OPT_MAX_DIFF, OPT_PSNR, OPT_PAGE, OPT_TOL, OPT_SCALE, OPT_DIMG,
	OPT_JSON, OPT_SEM, OPT_RENDER, OPT_DPI, OPT_STRICT, OPT_HTOL };

static const struct option extra[] = {
	{ "max-pixels", required_argument, NULL, OPT_MAX_PIXELS },
	{ "max-diff", required_argument, NULL, OPT_MAX_DIFF },
	{ "psnr", required_argument, NULL, OPT_PSNR },
	{ "page", required_argument, NULL, OPT_PAGE },
	{ "tolerance", required_argument, NULL, OPT_TOL },
	{ "scale", no_argument, NULL, OPT_SCALE },
	{ "diff-image", required_argument, NULL, OPT_DIMG },
	{ "json", no_argument, NULL, OPT_JSON },
	{ "semantic", no_argument, NULL, OPT_SEM },
	{ "render", no_argument, NULL, OPT_RENDER },
	{ "dpi", required_argument, NULL, OPT_DPI },
	{ "strict-order", no_argument, NULL, OPT_STRICT },
	{ "hpgl-tolerance", required_argument, NULL, OPT_HTOL },
	{ "verbose", no_argument, NULL, 'v' },
	{ NULL, 0, NULL, 0 },
};

/* --tolerance T or R,G,B: 0 or -1. */
static int parse_tol(const char *arg, unsigned tol[3])
{
	unsigned long v[3];
	char buf[64];
	snprintf(buf, sizeof buf, "%s", arg);
	char *p = buf, *q;
	int n = 0;
	for (; n < 3; n++) {
		q = strchr(p, ',');
		if (q)
			*q = 0;
		if (cli_number(p, 0, 255, &v[n]))
			return -1;
		if (!q)
			break;
		p = q + 1;
	}
	if (n == 3 || (n != 0 && n != 2))
		return -1;
	for (int c = 0; c < 3; c++)
		tol[c] = (unsigned)(n ? v[c] : v[0]);
	return 0;
}

static int on_option(cli_t *c, int key, const char *arg)
{
	opts_t *o = c->user;
	char *e;
	switch (key) {
	case 'v': o->d.verbose = 1; return CLI_RUN;
	case OPT_SCALE: o->d.scale = 1; return CLI_RUN;
	case OPT_JSON: o->d.json = 1; return CLI_RUN;
	case OPT_SEM: o->semantic = 1; return CLI_RUN;
	case OPT_RENDER: o->render = 1; return CLI_RUN;
	case OPT_STRICT: o->d.strict_order = 1; return CLI_RUN;
	case OPT_DIMG: o->diff_image = arg; return CLI_RUN;
	case OPT_TOL:
	case OPT_MAX_DIFF:
		if (parse_tol(arg, o->d.tol))
			return cli_fail(c, 64, "bad tolerance '%s' for %s (0 to 255, or R,G,B)", arg,
				key == OPT_TOL ? "--tolerance" : "--max-diff");
		return CLI_RUN;
	case OPT_PSNR:
		o->d.psnr_min = strtod(arg, &e);
		if (*e || e == arg || !(o->d.psnr_min >= 0) || o->d.psnr_min > 1000)
			return cli_fail(c, 64, "bad number '%s' for --psnr", arg);
		return CLI_RUN;
	case OPT_HTOL:
		o->d.hpgl_tol = strtod(arg, &e);
		if (*e || e == arg || !(o->d.hpgl_tol >= 0) || o->d.hpgl_tol > 1e6)
			return cli_fail(c, 64, "bad number '%s' for --hpgl-tolerance", arg);
		return CLI_RUN;
	default: {
		unsigned long *v = key == OPT_MAX_PIXELS ? &o->d.maxpix : key == OPT_DPI ? &o->dpi : &o->page;
		const char *name = key == OPT_MAX_PIXELS ? "--max-pixels" : key == OPT_DPI ? "--dpi" : "--page";
		if (cli_number(arg, key != OPT_MAX_PIXELS, key == OPT_DPI ? 2400 : 4294967295UL, v))
			return cli_fail(c, 64, "bad number '%s' for %s", arg, name);
		return CLI_RUN;
	}
	}
}

#include "diff/diff_src.h"

/* Compare two pictures row by row, B resampled to A's size with --scale; the report goes to
 * rep; the optional difference picture to dimg. Returns the exit status. */
static int compare(dsrc_t *src, const char *const *file, const opts_t *o, FILE *rep, img_writer_t *dimg)
{
	unsigned wa = src[0].width, ha = src[0].height, wb = src[1].width, hb = src[1].height;
	if ((wa != wb || ha != hb) && !o->d.scale) {
		/* pictures of different sizes differ; but a broken input is trouble, not a difference,
		 * so both are still read to their end (rows stream: no memory beyond one row) */
		for (int k = 0; k < 2; k++) {
			const uint8_t *r;
			int st = 0;
			for (unsigned y = 0; y < src[k].height && !st; y++)
				st = dsrc_row(&src[k], &r);
			if (st || (st = dsrc_finish(&src[k])))
				return dsrc_fail(&src[k], st);
		}
		return diff_raster_sizes(file[0], file[1], wa, ha, wb, hb, &o->d, rep);
	}
	diff_raster_t *d = diff_raster_new(wa, ha, &o->d);
	uint8_t *brow = malloc((size_t)wa * 3), *mark = dimg ? malloc((size_t)wa * 3) : NULL;
	if (!d || !brow || (dimg && !mark)) {
		free(d), free(brow), free(mark);
		fprintf(stderr, "locus-diff: out of memory\n");
		return 70;
	}
	int st = 0;
	const uint8_t *rb = NULL;
	unsigned by = 0;            /* rows of B read */
	for (unsigned y = 0; y < ha && !st; y++) {
		const uint8_t *ra;
		if ((st = dsrc_row(&src[0], &ra))) {
			dsrc_fail(&src[0], st);
			break;
		}
		unsigned want = (unsigned)((uint64_t)y * hb / ha) + 1;   /* nearest row, top first */
		while (by < want && !st) {
			if ((st = dsrc_row(&src[1], &rb)))
				dsrc_fail(&src[1], st);
			by++;
		}
		if (st)
			break;
		const uint8_t *cmp = rb;
		if (wb != wa) {
			for (unsigned x = 0; x < wa; x++)
				memcpy(brow + 3 * x, rb + 3 * (size_t)((uint64_t)x * wb / wa), 3);
			cmp = brow;
		}
		diff_raster_row(d, y, ra, cmp, mark);
		if (dimg && img_writer_rows(dimg, mark, 0, 1)) {
			fprintf(stderr, "locus-diff: %s\n", img_writer_error(dimg));
			st = 74;
		}
	}
	while (!st && by < hb) {   /* --scale down: the rest of B is read and checked too */
		if ((st = dsrc_row(&src[1], &rb)))
			dsrc_fail(&src[1], st);
		by++;
	}
	for (int k = 0; k < 2 && !st; k++)
		if ((st = dsrc_finish(&src[k])))
			dsrc_fail(&src[k], st);
	free(brow);
	free(mark);
	if (st) {
		free(d);
		return st;
	}
	return diff_raster_report(d, file[0], file[1], rep);
}

/* Run the engine of a kind held in memory (HP-GL, meta statements, PostScript text). */
static int compare_mem(dsrc_t *src, const char *const *file, const opts_t *o, FILE *rep)
{
	unsigned char *buf[2] = { NULL, NULL };
	size_t len[2] = { 0, 0 };
	int st = 0;
	for (int k = 0; k < 2 && !st; k++)
		if ((st = dsrc_slurp(&src[k], &buf[k], &len[k])))
			dsrc_fail(&src[k], st);
	diff_opts_t d = o->d;
	if (!st && src[0].kind == DSRC_PDF)   /* uncompressed and renumbered by qpdf, where it is there */
		d.qdf = dsrc_qdf(&buf[0], &len[0]) == 0 && dsrc_qdf(&buf[1], &len[1]) == 0;
	if (!st) {
		char err[700] = "";
		int kind = src[0].kind;
		int rc = kind == DSRC_HPGL ? diff_hpgl(buf[0], len[0], file[0], buf[1], len[1], file[1], &d, rep, err, sizeof err)
			: kind == DSRC_META ? diff_meta(buf[0], len[0], file[0], buf[1], len[1], file[1], &d, rep, err, sizeof err)
			: diff_ps(buf[0], len[0], file[0], buf[1], len[1], file[1], &d, rep, err, sizeof err);
		if (rc < 0) {
			fprintf(stderr, "%s\n", err);
			st = 65;
		} else {
			st = rc;
		}
	}
	free(buf[0]);
	free(buf[1]);
	return st;
}

/* Write the report (in memory) to the output; 0 or 74. */
static int put_report(io_transport_t *out, const char *outname, const char *text, size_t n)
{
	if (io_write(out, text, n) || io_flush(out)) {
		fprintf(stderr, "locus-diff: %s\n", io_error(out));   /* names the output and the cause */
		io_close(out, IO_ABORT);
		return 74;
	}
	if (io_close(out, IO_COMMIT)) {   /* frees out: its message is gone, errno is the cause */
		fprintf(stderr, "locus-diff: %s: cannot finish writing the report: %s\n", outname, strerror(errno));
		return 74;
	}
	return 0;
}

/* The work; returns 0, 1 or a sysexits status (main turns it into 2). */
static int run(cli_t *c, opts_t *o)
{
	if (c->options[0])
		return cli_fail(c, 64, "locus-diff has no device options (-O)");
	if (c->nin != 2)
		return cli_fail(c, 64, "need two files to compare (try --help)");
	const char *file[2] = { c->in[0], c->in[1] };
	if (!strcmp(file[0], "-") && !strcmp(file[1], "-"))
		return cli_fail(c, 64, "standard input given twice");
	char err[600];
	io_transport_t *out = io_open_write(c->out ? c->out : "-", err, sizeof err);
	if (!out) {
		fprintf(stderr, "locus-diff: %s\n", err);
		return 74;
	}
	dsrc_t src[2];
	memset(src, 0, sizeof src);
	char *text = NULL;
	size_t ntext = 0;
	FILE *rep = open_memstream(&text, &ntext);
	io_transport_t *dout = NULL;
	img_writer_t *dimg = NULL;
	int st = rep ? 0 : 70;
	if (!rep)
		fprintf(stderr, "locus-diff: out of memory\n");
	for (int k = 0; k < 2 && st == 0; k++)
		if ((st = dsrc_sniff(&src[k], file[k], (unsigned)o->page)))
			dsrc_fail(&src[k], st);
	int kind = src[0].kind;
	/* pictures: rasters, meta files rendered, PostScript/PDF rendered, in any mix */
	int pic[2];
	for (int k = 0; k < 2; k++)
		pic[k] = src[k].kind == DSRC_RASTER || (src[k].kind == DSRC_META && !o->semantic) ||
			((src[k].kind == DSRC_PS || src[k].kind == DSRC_PDF) && o->render);
	if (!st && !(pic[0] && pic[1]) && kind != src[1].kind) {
		fprintf(stderr, "locus-diff: %s is %s, %s is %s: outputs of different kinds\n", src[0].name,
			dsrc_kind_name[kind], src[1].name, dsrc_kind_name[src[1].kind]);
		st = 65;
	}
	int mem = !(pic[0] && pic[1]);
	if (!st && mem)
		st = compare_mem(src, file, o, rep);
	else if (!st) {
		for (int k = 0; k < 2 && st == 0; k++) {
			int ps = src[k].kind == DSRC_PS || src[k].kind == DSRC_PDF;
			if (ps && (st = dsrc_ghostscript(&src[k], (unsigned)o->dpi)))
				dsrc_fail(&src[k], st);
			else if (!st && ps)
				src[k].kind = DSRC_RASTER;
			if (!st && (st = dsrc_open(&src[k], c->band_rows, c->budget)))
				dsrc_fail(&src[k], st);
		}
		if (!st && o->diff_image) {
			dout = io_open_write(o->diff_image, err, sizeof err);
			dimg = dout ? img_writer_new(IMG_FMT_PNG, dout, src[0].width, src[0].height, err, sizeof err) : NULL;
			if (!dimg) {
				fprintf(stderr, "locus-diff: %s\n", err);
				st = 74;
			}
		}
		if (!st)
			st = compare(src, file, o, rep, dimg);
	}
	dsrc_close(&src[0]);
	dsrc_close(&src[1]);
	if (dimg && st <= 1) {
		if (img_writer_finish(dimg) || io_close_err(dout, IO_COMMIT, err, sizeof err)) {
			fprintf(stderr, "locus-diff: %s: %s\n", o->diff_image, err);
			st = 74;
		}
		dimg = NULL, dout = NULL;
	}
	if (dimg)
		img_writer_abort(dimg);
	if (dout)
		io_close(dout, IO_ABORT);
	/* the report is built in memory: a failed write into it is running out of memory */
	/* (glibc's memstream leaves text unset when its last realloc, at fclose, fails) */
	if (rep && ((ferror(rep) | fclose(rep)) || !text) && st <= 1) {
		fprintf(stderr, "locus-diff: out of memory while writing the report\n");
		st = 70;
	}
	if (st > 1) {
		io_close(out, IO_ABORT);   /* no report, and no partial file */
		free(text);
		return st;
	}
	int wst = put_report(out, c->out ? c->out : "<stdout>", text ? text : "", ntext);
	free(text);
	return wst ? wst : st;
}

int main(int argc, char **argv)
{
	opts_t o;
	memset(&o, 0, sizeof o);
	diff_opts_default(&o.d);
	o.page = 1;
	o.dpi = 72;
	cli_t c = { .prog = "locus-diff", .usage = usage, .extra = extra, .extra_short = "v",
		.on_option = on_option, .user = &o, .max_inputs = 2 };
	int st = cli_parse(&c, argc, argv);
	if (st == CLI_RUN)
		st = run(&c, &o);
	return st > 1 ? 2 : st;   /* the status of each kind of trouble is in its message */
}
