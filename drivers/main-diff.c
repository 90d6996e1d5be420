/* main-diff.c: locus-diff, compare two outputs of one kind (rasters, HP-GL, PostScript/PDF, meta). */
#include <errno.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "device.h"
#include "diff.h"
#include "image.h"
#include "imgread_int.h"

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

/* What an input holds, told from its first bytes. */
enum { K_RASTER, K_META, K_HPGL, K_PS, K_PDF };
static const char *const kind_name[] = { "raster", "meta", "HP-GL", "PostScript", "PDF" };

/* One input, read a row at a time: an image file through the streaming reader, or a meta file
 * replayed by a thread of its own onto a capture device that hands over one band at a time, so
 * that memory stays one band (the device's budget) whatever the size of the page or the file. */
typedef struct {
	const char *name;
	io_transport_t *t;
	unsigned char head[64];
	int kind;
	uint64_t dump;              /* a framebuffer dump of this many bytes */
	FILE *pipe;                 /* Ghostscript's PPM (--render) */
	pid_t pid;
	size_t nhead, headpos;
	unsigned width, height;
	dev_imgr_t *img;
	uint8_t *row;
	/* meta files */
	int meta, started;
	meta_reader_t *mr;
	dev_device_t *dev;
	pthread_t thr;
	pthread_mutex_t mu;
	pthread_cond_t cv;
	unsigned want;
	int sized, done, quit, status;
	const dev_band_t *band;
	unsigned band_at;
	char tmp[64];                /* the temporary copy Ghostscript reads */
	char err[600];
} src_t;

static long src_read(void *user, void *buf, size_t n)
{
	src_t *s = user;
	if (s->headpos < s->nhead) {
		size_t k = s->nhead - s->headpos < n ? s->nhead - s->headpos : n;
		memcpy(buf, s->head + s->headpos, k);
		s->headpos += k;
		return (long)k;
	}
	if (s->pipe) {
		size_t k = fread(buf, 1, n, s->pipe);
		if (k == 0 && ferror(s->pipe))
			return -1;
		return (long)k;
	}
	return io_read(s->t, buf, n);
}

static int status_of(int rc)
{
	return rc == META_ENOMEM || rc == -70 ? 70 : rc == META_EIO || rc == -74 ? 74 : 65;
}

static int cap_begin(dev_device_t *d, const dev_page_t *pg)
{
	src_t *s = d->user;
	if (pg->index + 1 != s->want)
		return 0;
	pthread_mutex_lock(&s->mu);
	s->width = pg->width;
	s->height = pg->height;
	s->sized = 1;
	pthread_cond_broadcast(&s->cv);
	pthread_mutex_unlock(&s->mu);
	return 0;
}

/* Hand the band to the comparing thread and wait until it has taken every row. */
static int cap_band(dev_device_t *d, const dev_band_t *b)
{
	src_t *s = d->user;
	if (d->pages + 1 != s->want)
		return 0;
	pthread_mutex_lock(&s->mu);
	s->band = b;
	s->band_at = 0;
	pthread_cond_broadcast(&s->cv);
	while (s->band && !s->quit)
		pthread_cond_wait(&s->cv, &s->mu);
	int quit = s->quit;
	pthread_mutex_unlock(&s->mu);
	return quit ? dev_fail(d, DEV_EDEVICE, "comparison stopped") : 0;
}

static const dev_ops_t capture_ops = {
	.name = "capture", .description = "band-at-a-time capture", .caps = DEV_CAP_RASTER,
	.begin_page = cap_begin, .write_band = cap_band,
};

static void *player(void *arg)
{
	src_t *s = arg;
	int rc = dev_play(s->mr, s->dev);
	pthread_mutex_lock(&s->mu);
	s->done = 1;
	if (rc && !s->quit) {
		snprintf(s->err, sizeof s->err, "%s", dev_error(s->dev));
		s->status = status_of(rc);
	} else if (!rc && !s->sized) {
		snprintf(s->err, sizeof s->err, "%s: has no page %u", s->name, s->want);
		s->status = 65;
	}
	s->band = NULL;
	pthread_cond_broadcast(&s->cv);
	pthread_mutex_unlock(&s->mu);
	return NULL;
}

/* Is the head HP-GL: blanks, then ESC or a two-letter command followed by a parameter, ';' or
 * another command? */
static int is_hpgl(const unsigned char *h, size_t n)
{
	size_t i = 0;
	while (i < n && (h[i] == ' ' || h[i] == '\t' || h[i] == '\r' || h[i] == '\n' || h[i] == ';'))
		i++;
	if (i < n && h[i] == 27)
		return 1;
	if (i + 2 >= n)
		return 0;
	int a = h[i] | 32, b = h[i + 1] | 32, c = h[i + 2];
	return a >= 'a' && a <= 'z' && b >= 'a' && b <= 'z' && (c == ';' || c == '-' || c == '+' ||
		c == '.' || c == ' ' || c == ',' || c == '\r' || c == '\n' || (c >= '0' && c <= '9') ||
		((c | 32) >= 'a' && (c | 32) <= 'z'));
}

/* Open path and read its first bytes to tell its kind; 0 or an exit status with s->err. */
static int src_sniff(src_t *s, const char *path, unsigned page)
{
	memset(s, 0, sizeof *s);
	s->name = strcmp(path, "-") ? path : "<stdin>";
	s->want = page;
	if (!(s->t = io_open_read(path, s->err, sizeof s->err)))
		return 66;
	while (s->nhead < sizeof s->head) {
		long n = io_read(s->t, s->head + s->nhead, sizeof s->head - s->nhead);
		if (n < 0) {
			snprintf(s->err, sizeof s->err, "%s", io_error(s->t));
			return 74;
		}
		if (n == 0)
			break;
		s->nhead += (size_t)n;
	}
	const unsigned char *h = s->head;
	size_t n = s->nhead;
	struct stat sb;
	if ((n >= 10 && memcmp(h, "LOCUS-META", 10) == 0) || (n >= 4 && memcmp(h, "\x8bLMB", 4) == 0))
		s->kind = K_META;
	else if (n >= 5 && memcmp(h, "%PDF-", 5) == 0)
		s->kind = K_PDF;
	else if ((n >= 2 && memcmp(h, "%!", 2) == 0) || (n >= 4 && memcmp(h, "\xC5\xD0\xD3\xC6", 4) == 0))
		s->kind = K_PS;
	else if ((n >= 8 && memcmp(h, "\x89PNG", 4) == 0) || (n >= 2 && h[0] == 'P' && h[1] == '6') ||
			(n >= 4 && memcmp(h, DEV_RLE_MAGIC, 4) == 0) || imgr_is_pcx(h, n) || imgr_is_bmp(h, n) ||
			imgr_is_dpx(h, n) || imgr_is_cineon(h, n))
		s->kind = K_RASTER;
	else if (is_hpgl(h, n))
		s->kind = K_HPGL;
	else if (strcmp(path, "-") && !stat(path, &sb) && S_ISREG(sb.st_mode) &&
			imgr_fbdump_mode((uint64_t)sb.st_size) >= 0)
		s->kind = K_RASTER, s->dump = (uint64_t)sb.st_size;   /* headerless: told by its size */
	else
		s->kind = K_RASTER;   /* the image reader names what it expected */
	return 0;
}

/* Read the whole input into memory (*buf, malloc'd); 0 or an exit status. */
static int src_slurp(src_t *s, unsigned char **buf, size_t *len)
{
	size_t cap = 1 << 16, n = 0;
	unsigned char *b = malloc(cap);
	for (;;) {
		if (b && n == cap) {
			unsigned char *q = cap < ((size_t)1 << 40) ? realloc(b, cap * 2) : NULL;
			if (!q)
				free(b);
			b = q;
			cap *= 2;
		}
		if (!b) {
			snprintf(s->err, sizeof s->err, "out of memory reading %s", s->name);
			return 70;
		}
		long k = src_read(s, b + n, cap - n);
		if (k < 0) {
			free(b);
			snprintf(s->err, sizeof s->err, "%s", io_error(s->t));
			return 74;
		}
		if (k == 0)
			break;
		n += (size_t)k;
	}
	*buf = b;
	*len = n;
	return 0;
}

/* --render: Ghostscript turns page s->want of the input into a PPM read from a pipe; the input
 * reaches it on its standard input (a PDF is written to a temporary file first, which gs needs
 * to seek in). 0 or an exit status. */
static int src_ghostscript(src_t *s, unsigned dpi)
{
	unsigned char *buf;
	size_t n;
	int st = src_slurp(s, &buf, &n);
	if (st)
		return st;
	char tmp[] = "/tmp/locus-diff-XXXXXX";
	int fd = mkstemp(tmp);
	if (fd < 0 || write(fd, buf, n) != (ssize_t)n) {
		free(buf);
		if (fd >= 0)
			close(fd), unlink(tmp);
		snprintf(s->err, sizeof s->err, "cannot write a temporary copy of %s: %s", s->name, strerror(errno));
		return 74;
	}
	free(buf);
	close(fd);
	int p[2];
	if (pipe(p)) {
		unlink(tmp);
		snprintf(s->err, sizeof s->err, "cannot make a pipe: %s", strerror(errno));
		return 70;
	}
	char res[32], first[32], last[32], out[] = "-sOutputFile=-";
	snprintf(res, sizeof res, "-r%u", dpi);
	snprintf(first, sizeof first, "-dFirstPage=%u", s->want);
	snprintf(last, sizeof last, "-dLastPage=%u", s->want);
	s->pid = fork();
	if (s->pid == 0) {
		dup2(p[1], 1);
		close(p[0]);
		close(p[1]);
		int nul = open("/dev/null", O_WRONLY);
		if (nul >= 0)
			dup2(nul, 2);
		char *argv[] = { "gs", "-q", "-dSAFER", "-dBATCH", "-dNOPAUSE", "-sDEVICE=ppmraw", res,
			first, last, "-dEPSCrop", out, tmp, NULL };
		execvp("gs", argv);
		_exit(127);
	}
	close(p[1]);
	if (s->pid < 0) {
		close(p[0]);
		unlink(tmp);
		snprintf(s->err, sizeof s->err, "cannot start Ghostscript: %s", strerror(errno));
		return 70;
	}
	s->pipe = fdopen(p[0], "rb");
	/* gs has the file open once it writes its first byte; the name can go at the end */
	snprintf(s->tmp, sizeof s->tmp, "%s", tmp);
	s->nhead = s->headpos = 0;
	if (!s->pipe) {
		close(p[0]);
		snprintf(s->err, sizeof s->err, "out of memory");
		return 70;
	}
	return 0;
}

/* Start reading the picture of s: 0 or an exit status with the message in s->err. */
static int src_open(src_t *s, unsigned band_rows, size_t budget)
{
	if (s->kind == K_META) {
		s->meta = 1;
		s->mr = meta_reader_new(src_read, s, s->name);
		s->dev = s->mr ? dev_new(&capture_ops, NULL) : NULL;
		if (!s->dev) {
			snprintf(s->err, sizeof s->err, "out of memory");
			return 70;
		}
		s->dev->user = s;
		s->dev->band_rows = band_rows;
		if (budget)
			s->dev->mem_budget = budget;
		if (pthread_mutex_init(&s->mu, NULL) || pthread_cond_init(&s->cv, NULL) ||
				pthread_create(&s->thr, NULL, player, s)) {
			snprintf(s->err, sizeof s->err, "cannot start a thread to render %s", s->name);
			return 70;
		}
		s->started = 1;
		pthread_mutex_lock(&s->mu);
		while (!s->sized && !s->done)
			pthread_cond_wait(&s->cv, &s->mu);
		int st = s->sized ? 0 : s->status ? s->status : 70;
		pthread_mutex_unlock(&s->mu);
		return st;
	}
	int rc = s->dump ? imgr_open_fbdump(src_read, s, NULL, 0, s->name, s->dump, &s->img, s->err, sizeof s->err)
		: dev_imgr_open(src_read, s, NULL, 0, s->name, &s->img, s->err, sizeof s->err);
	if (rc)
		return status_of(rc);
	s->width = dev_imgr_width(s->img);
	s->height = dev_imgr_height(s->img);
	s->row = malloc((size_t)s->width * 3);
	if (!s->row) {
		snprintf(s->err, sizeof s->err, "out of memory");
		return 70;
	}
	return 0;
}

/* The next row (top first) in *row, valid until the next call; 0 or an exit status. */
static int src_row(src_t *s, const uint8_t **row)
{
	if (!s->meta) {
		int rc = dev_imgr_row(s->img, s->row);
		if (rc) {
			snprintf(s->err, sizeof s->err, "%s", dev_imgr_error(s->img));
			return status_of(rc);
		}
		*row = s->row;
		return 0;
	}
	pthread_mutex_lock(&s->mu);
	if (s->band && s->band_at >= s->band->nrows) {
		s->band = NULL;   /* every row of it taken: let the player go on */
		pthread_cond_broadcast(&s->cv);
	}
	while (!s->band && !s->done)
		pthread_cond_wait(&s->cv, &s->mu);
	int st = 0;
	if (s->band)
		*row = s->band->pix + (size_t)s->band_at++ * s->band->stride;
	else
		st = s->status ? s->status : 70;
	if (st == 70 && !s->err[0])
		snprintf(s->err, sizeof s->err, "%s: the page ended early", s->name);
	pthread_mutex_unlock(&s->mu);
	return st;
}

/* After the last row: the rest of the input must be good too. 0 or an exit status. */
static int src_finish(src_t *s)
{
	if (!s->meta) {
		int rc = dev_imgr_end(s->img);
		if (rc)
			snprintf(s->err, sizeof s->err, "%s", dev_imgr_error(s->img));
		return rc ? status_of(rc) : 0;
	}
	pthread_mutex_lock(&s->mu);
	s->band = NULL;
	pthread_cond_broadcast(&s->cv);
	while (!s->done)
		pthread_cond_wait(&s->cv, &s->mu);
	int st = s->status;
	pthread_mutex_unlock(&s->mu);
	return st;
}

static void src_close(src_t *s)
{
	if (s->started) {
		pthread_mutex_lock(&s->mu);
		s->quit = 1;
		pthread_cond_broadcast(&s->cv);
		pthread_mutex_unlock(&s->mu);
		pthread_join(s->thr, NULL);
		pthread_cond_destroy(&s->cv);
		pthread_mutex_destroy(&s->mu);
	}
	dev_free(s->dev);
	meta_reader_free(s->mr);
	dev_imgr_free(s->img);
	free(s->row);
	if (s->pipe) {
		fclose(s->pipe);
		int ws;
		waitpid(s->pid, &ws, 0);
	}
	if (s->tmp[0])
		unlink(s->tmp);
	if (s->t)
		io_close(s->t, IO_ABORT);
}

/* Print the error of a source: a bad-data message names the file and the place itself. */
static int src_fail(const src_t *s, int st)
{
	if (st == 65)
		fprintf(stderr, "%s\n", s->err);
	else
		fprintf(stderr, "locus-diff: %s\n", s->err);
	return st;
}

/* Compare two pictures row by row, B resampled to A's size with --scale; the report goes to
 * rep; the optional difference picture to dimg. Returns the exit status. */
static int compare(src_t *src, const char *const *file, const opts_t *o, FILE *rep, dev_imgw_t *dimg)
{
	unsigned wa = src[0].width, ha = src[0].height, wb = src[1].width, hb = src[1].height;
	if ((wa != wb || ha != hb) && !o->d.scale)
		return diff_raster_sizes(file[0], file[1], wa, ha, wb, hb, &o->d, rep);
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
		if ((st = src_row(&src[0], &ra))) {
			src_fail(&src[0], st);
			break;
		}
		unsigned want = (unsigned)((uint64_t)y * hb / ha) + 1;   /* nearest row, top first */
		while (by < want && !st) {
			if ((st = src_row(&src[1], &rb)))
				src_fail(&src[1], st);
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
		if (dimg && dev_imgw_rows(dimg, mark, 0, 1)) {
			fprintf(stderr, "locus-diff: %s\n", dev_imgw_error(dimg));
			st = 74;
		}
	}
	while (!st && by < hb) {   /* --scale down: the rest of B is read and checked too */
		if ((st = src_row(&src[1], &rb)))
			src_fail(&src[1], st);
		by++;
	}
	for (int k = 0; k < 2 && !st; k++)
		if ((st = src_finish(&src[k])))
			src_fail(&src[k], st);
	free(brow);
	free(mark);
	if (st) {
		free(d);
		return st;
	}
	return diff_raster_report(d, file[0], file[1], rep);
}

/* Run the engine of a kind held in memory (HP-GL, meta statements, PostScript text). */
static int compare_mem(src_t *src, const char *const *file, const opts_t *o, FILE *rep)
{
	unsigned char *buf[2] = { NULL, NULL };
	size_t len[2] = { 0, 0 };
	int st = 0;
	for (int k = 0; k < 2 && !st; k++)
		if ((st = src_slurp(&src[k], &buf[k], &len[k])))
			src_fail(&src[k], st);
	if (!st) {
		char err[700] = "";
		int kind = src[0].kind;
		int rc = kind == K_HPGL ? diff_hpgl(buf[0], len[0], file[0], buf[1], len[1], file[1], &o->d, rep, err, sizeof err)
			: kind == K_META ? diff_meta(buf[0], len[0], file[0], buf[1], len[1], file[1], &o->d, rep, err, sizeof err)
			: diff_ps(buf[0], len[0], file[0], buf[1], len[1], file[1], &o->d, rep, err, sizeof err);
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
	src_t src[2];
	memset(src, 0, sizeof src);
	char *text = NULL;
	size_t ntext = 0;
	FILE *rep = open_memstream(&text, &ntext);
	io_transport_t *dout = NULL;
	dev_imgw_t *dimg = NULL;
	int st = rep ? 0 : 70;
	if (!rep)
		fprintf(stderr, "locus-diff: out of memory\n");
	for (int k = 0; k < 2 && st == 0; k++)
		if ((st = src_sniff(&src[k], file[k], (unsigned)o->page)))
			src_fail(&src[k], st);
	int kind = src[0].kind;
	/* pictures: rasters, meta files rendered, PostScript/PDF rendered, in any mix */
	int pic[2];
	for (int k = 0; k < 2; k++)
		pic[k] = src[k].kind == K_RASTER || (src[k].kind == K_META && !o->semantic) ||
			((src[k].kind == K_PS || src[k].kind == K_PDF) && o->render);
	if (!st && !(pic[0] && pic[1]) && kind != src[1].kind) {
		fprintf(stderr, "locus-diff: %s is %s, %s is %s: outputs of different kinds\n", src[0].name,
			kind_name[kind], src[1].name, kind_name[src[1].kind]);
		st = 65;
	}
	int mem = !(pic[0] && pic[1]);
	if (!st && mem)
		st = compare_mem(src, file, o, rep);
	else if (!st) {
		for (int k = 0; k < 2 && st == 0; k++) {
			int ps = src[k].kind == K_PS || src[k].kind == K_PDF;
			if (ps && (st = src_ghostscript(&src[k], (unsigned)o->dpi)))
				src_fail(&src[k], st);
			else if (!st && ps)
				src[k].kind = K_RASTER;
			if (!st && (st = src_open(&src[k], c->band_rows, c->budget)))
				src_fail(&src[k], st);
		}
		if (!st && o->diff_image) {
			dout = io_open_write(o->diff_image, err, sizeof err);
			dimg = dout ? dev_imgw_new(DEV_FMT_PNG, dout, src[0].width, src[0].height, err, sizeof err) : NULL;
			if (!dimg) {
				fprintf(stderr, "locus-diff: %s\n", err);
				st = 74;
			}
		}
		if (!st)
			st = compare(src, file, o, rep, dimg);
	}
	src_close(&src[0]);
	src_close(&src[1]);
	if (dimg && st <= 1) {
		if (dev_imgw_finish(dimg) || io_close_err(dout, IO_COMMIT, err, sizeof err)) {
			fprintf(stderr, "locus-diff: %s: %s\n", o->diff_image, err);
			st = 74;
		}
		dimg = NULL, dout = NULL;
	}
	if (dimg)
		dev_imgw_abort(dimg);
	if (dout)
		io_close(dout, IO_ABORT);
	if (rep)
		fclose(rep);
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
