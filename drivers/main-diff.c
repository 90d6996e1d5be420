/* main-diff.c: locus-diff, compare two pictures (PNG, PPM, RLE, or meta files rendered). */
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "device.h"
#include "image.h"

static const char usage[] =
	"usage: locus-diff [--max-pixels N] [--max-diff D] [--psnr DB] [--page N] [-o OUT]\n"
	"                  [--band-rows N] [--mem-budget MIB] A B\n"
	"Compare two pictures: PNG, PPM (P6), Locus RLE, or Locus meta files (rendered by the\n"
	"reference raster device; --page picks the page, default 1). Prints the number of\n"
	"differing pixels, the largest channel difference and the PSNR (to OUT, default stdout).\n"
	"Inputs are read a row at a time (meta files a band at a time), so memory does not grow\n"
	"with the size of the pictures. Exit 0: same (or within the tolerances), 1: they differ,\n"
	"64: usage, 65: bad input, 66: no input, 70: out of memory, 74: read or write error.\n"
	"  --max-pixels N   accept up to N differing pixels\n"
	"  --max-diff D     pixels whose channels differ by at most D count as equal\n"
	"  --psnr DB        accept when the PSNR is at least DB decibels\n"
	"  --band-rows N, --mem-budget MIB   banding of the meta files' replay\n"
	"  --help, --version\n";

/* The program's own options (cli.h). */
typedef struct {
	unsigned long maxpix, maxdiff, page;
	double psnr_min;
} opts_t;

enum { OPT_MAX_PIXELS = 0x2000, OPT_MAX_DIFF, OPT_PSNR, OPT_PAGE };

static const struct option extra[] = {
	{ "max-pixels", required_argument, NULL, OPT_MAX_PIXELS },
	{ "max-diff", required_argument, NULL, OPT_MAX_DIFF },
	{ "psnr", required_argument, NULL, OPT_PSNR },
	{ "page", required_argument, NULL, OPT_PAGE },
	{ NULL, 0, NULL, 0 },
};

static int on_option(cli_t *c, int key, const char *arg)
{
	opts_t *o = c->user;
	const char *name = key == OPT_MAX_PIXELS ? "--max-pixels" : key == OPT_MAX_DIFF ? "--max-diff"
		: key == OPT_PSNR ? "--psnr" : "--page";
	int bad = 0;
	if (key == OPT_PSNR) {
		char *e;
		o->psnr_min = strtod(arg, &e);
		bad = *e || e == arg || !(o->psnr_min >= 0) || o->psnr_min > 1000;
	} else {
		unsigned long *v = key == OPT_MAX_PIXELS ? &o->maxpix : key == OPT_MAX_DIFF ? &o->maxdiff : &o->page;
		bad = cli_number(arg, key == OPT_PAGE, key == OPT_MAX_DIFF ? 255 : 4294967295UL, v) != 0;
	}
	return bad ? cli_fail(c, 64, "bad number '%s' for %s", arg, name) : CLI_RUN;
}

/* One input, read a row at a time: an image file through the streaming reader, or a meta file
 * replayed by a thread of its own onto a capture device that hands over one band at a time, so
 * that memory stays one band (the device's budget) whatever the size of the page or the file. */
typedef struct {
	const char *name;
	io_transport_t *t;
	unsigned char head[16];
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

/* Open path; 0 or an exit status with the message in s->err. */
static int src_open(src_t *s, const char *path, unsigned page, unsigned band_rows, size_t budget)
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
	if ((s->nhead >= 10 && memcmp(h, "LOCUS-META", 10) == 0) || (s->nhead >= 4 && memcmp(h, "\x8bLMB", 4) == 0)) {
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
	int rc = dev_imgr_open(src_read, s, NULL, 0, s->name, &s->img, s->err, sizeof s->err);
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

/* Compare row by row; the report line goes to line; returns the exit status. */
static int compare(src_t *src, const char *const *file, const opts_t *o, char *line, size_t n)
{
	unsigned long maxpix = o->maxpix, maxdiff = o->maxdiff;
	double psnr_min = o->psnr_min;
	if (src[0].width != src[1].width || src[0].height != src[1].height) {
		snprintf(line, n, "%s %s: sizes differ: %ux%u vs %ux%u\n", file[0], file[1], src[0].width,
			src[0].height, src[1].width, src[1].height);
		return 1;
	}
	size_t npix = (size_t)src[0].width * src[0].height, ndiff = 0;
	unsigned maxc = 0;
	double sse = 0;
	for (unsigned y = 0; y < src[0].height; y++) {
		const uint8_t *row[2];
		for (int k = 0; k < 2; k++) {
			int st = src_row(&src[k], &row[k]);
			if (st)
				return src_fail(&src[k], st);
		}
		for (unsigned x = 0; x < src[0].width; x++) {
			const uint8_t *p = row[0] + 3 * x, *q = row[1] + 3 * x;
			unsigned m = 0;
			for (int c = 0; c < 3; c++) {
				int d = p[c] - q[c];
				unsigned ad = (unsigned)(d < 0 ? -d : d);
				sse += (double)d * d;
				if (ad > m)
					m = ad;
			}
			if (m > maxc)
				maxc = m;
			if (m > maxdiff)
				ndiff++;
		}
	}
	for (int k = 0; k < 2; k++) {
		int st = src_finish(&src[k]);
		if (st)
			return src_fail(&src[k], st);
	}
	double mse = sse / ((double)npix * 3);
	double psnr = mse > 0 ? 10.0 * log10(255.0 * 255.0 / mse) : INFINITY;
	char ps[32];
	if (isinf(psnr))
		snprintf(ps, sizeof ps, "inf");
	else
		snprintf(ps, sizeof ps, "%.2f", psnr);
	snprintf(line, n, "%s %s: %zu of %zu pixels differ, max channel difference %u, PSNR %s dB\n",
		file[0], file[1], ndiff, npix, maxc, ps);
	int same = ndiff <= maxpix || (psnr_min >= 0 && psnr >= psnr_min);
	if (psnr_min >= 0 && maxpix == 0)
		same = psnr >= psnr_min || ndiff == 0;
	return same ? 0 : 1;
}

int main(int argc, char **argv)
{
	opts_t o = { 0, 0, 1, -1 };
	cli_t c = { .prog = "locus-diff", .usage = usage, .extra = extra, .on_option = on_option,
		.user = &o, .max_inputs = 2 };
	int st = cli_parse(&c, argc, argv);
	if (st != CLI_RUN)
		return st;
	if (c.options[0])
		return cli_fail(&c, 64, "locus-diff has no device options (-O)");
	if (c.nin != 2)
		return cli_fail(&c, 64, "need two files to compare (try --help)");
	const char *file[2] = { c.in[0], c.in[1] };
	if (!strcmp(file[0], "-") && !strcmp(file[1], "-"))
		return cli_fail(&c, 64, "standard input given twice");
	char err[600];
	io_transport_t *out = io_open_write(c.out ? c.out : "-", err, sizeof err);
	if (!out) {
		fprintf(stderr, "locus-diff: %s\n", err);
		return 74;
	}
	src_t src[2];
	char line[2200] = "";
	memset(src, 0, sizeof src);
	st = 0;
	for (int k = 0; k < 2 && st == 0; k++)
		if ((st = src_open(&src[k], file[k], (unsigned)o.page, c.band_rows, c.budget)))
			src_fail(&src[k], st);
	if (st == 0)
		st = compare(src, file, &o, line, sizeof line);
	src_close(&src[0]);
	src_close(&src[1]);
	if (st > 1) {
		io_close(out, IO_ABORT);   /* no report, and no partial file */
		return st;
	}
	if (io_write(out, line, strlen(line)) || io_flush(out)) {
		fprintf(stderr, "locus-diff: %s\n", io_error(out));   /* names the output and the cause */
		io_close(out, IO_ABORT);
		return 74;
	}
	const char *name = c.out ? c.out : "<stdout>";
	if (io_close(out, IO_COMMIT)) {   /* frees out: its message is gone, errno is the cause */
		fprintf(stderr, "locus-diff: %s: cannot finish writing the report: %s\n", name, strerror(errno));
		return 74;
	}
	return st;
}
