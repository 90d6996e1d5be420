/* main-diff.c: locus-diff, compare two pictures (PNG, PPM, RLE, or meta files rendered). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "device.h"
#include "image.h"

static void usage(FILE *f)
{
	fprintf(f,
		"usage: locus-diff [--max-pixels N] [--max-diff D] [--psnr DB] [--page N] A B\n"
		"Compare two pictures: PNG, PPM (P6), Locus RLE, or Locus meta files (rendered by the\n"
		"reference raster device; --page picks the page, default 1). Prints the number of\n"
		"differing pixels, the largest channel difference and the PSNR.\n"
		"Exit 0: same (or within the tolerances), 1: they differ, 65: bad input, 66: no input.\n"
		"  --max-pixels N   accept up to N differing pixels\n"
		"  --max-diff D     pixels whose channels differ by at most D count as equal\n"
		"  --psnr DB        accept when the PSNR is at least DB decibels\n"
		"  --help, --version\n");
}

/* Capture device: keeps the wanted page as an image. */
typedef struct {
	unsigned want, page;
	dev_image_t *img;
	int got;
} cap_t;

static int cap_begin(dev_device_t *d, const dev_page_t *pg)
{
	cap_t *c = d->user;
	c->page = pg->index + 1;
	if (c->page != c->want)
		return 0;
	c->img->width = pg->width;
	c->img->height = pg->height;
	c->img->pix = malloc((size_t)pg->width * pg->height * 3);
	return c->img->pix ? 0 : dev_fail(d, META_ENOMEM, "out of memory");
}

static int cap_band(dev_device_t *d, const dev_band_t *b)
{
	cap_t *c = d->user;
	if (c->page != c->want)
		return 0;
	for (unsigned k = 0; k < b->nrows; k++)
		memcpy(c->img->pix + (size_t)(b->y0 + k) * b->width * 3, b->pix + k * b->stride, (size_t)b->width * 3);
	c->got = 1;
	return 0;
}

static const dev_ops_t capture_ops = {
	.name = "capture", .description = "in-memory capture", .caps = DEV_CAP_RASTER,
	.begin_page = cap_begin, .write_band = cap_band,
};

static int render_meta(const unsigned char *b, size_t n, const char *name, unsigned page,
		dev_image_t *img, char *err, size_t errlen)
{
	meta_reader_t *r = meta_reader_mem(b, n, name);
	dev_device_t *d = r ? dev_new(&capture_ops, NULL) : NULL;
	if (!d) {
		meta_reader_free(r);
		snprintf(err, errlen, "out of memory");
		return -70;
	}
	cap_t c = { page, 0, img, 0 };
	d->user = &c;
	int rc = dev_play(r, d), st = 0;
	if (rc) {
		snprintf(err, errlen, "%s", dev_error(d));
		st = rc == META_ENOMEM ? -70 : -65;
	} else if (!c.got) {
		snprintf(err, errlen, "%s: has no page %u", name, page);
		st = -65;
	}
	if (st)
		dev_image_free(img);
	dev_free(d);
	meta_reader_free(r);
	return st;
}

static int load(const char *path, unsigned page, dev_image_t *img, char *err, size_t errlen)
{
	FILE *f = strcmp(path, "-") ? fopen(path, "rb") : stdin;
	if (!f) {
		snprintf(err, errlen, "%s: cannot open", path);
		return -66;
	}
	size_t cap = 1 << 16, n = 0;
	unsigned char *b = malloc(cap);
	while (b) {
		if (n == cap) {
			unsigned char *q = realloc(b, cap *= 2);
			if (!q) {
				free(b);
				b = NULL;
				break;
			}
			b = q;
		}
		size_t r = fread(b + n, 1, cap - n, f);
		if (r == 0)
			break;
		n += r;
	}
	int bad = ferror(f);
	if (f != stdin)
		fclose(f);
	if (!b || bad) {
		free(b);
		snprintf(err, errlen, "%s: %s", path, b ? "read error" : "out of memory");
		return -66;
	}
	const char *name = strcmp(path, "-") ? path : "<stdin>";
	int rc;
	if ((n >= 10 && memcmp(b, "LOCUS-META", 10) == 0) || (n >= 4 && memcmp(b, "\x8bLMB", 4) == 0))
		rc = render_meta(b, n, name, page, img, err, errlen);
	else
		rc = dev_image_decode(b, n, name, img, err, errlen);
	free(b);
	return rc;
}

int main(int argc, char **argv)
{
	const char *file[2] = { NULL, NULL };
	unsigned long maxpix = 0, maxdiff = 0, page = 1;
	double psnr_min = -1;
	int nf = 0;
	for (int k = 1; k < argc; k++) {
		const char *a = argv[k];
		char *e = NULL;
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			usage(stdout);
			return 0;
		} else if (!strcmp(a, "--version")) {
			printf("locus-diff %s\n", LOCUS_VERSION);
			return 0;
		} else if (!strcmp(a, "--max-pixels") && k + 1 < argc) {
			maxpix = strtoul(argv[++k], &e, 10);
		} else if (!strcmp(a, "--max-diff") && k + 1 < argc) {
			maxdiff = strtoul(argv[++k], &e, 10);
		} else if (!strcmp(a, "--page") && k + 1 < argc) {
			page = strtoul(argv[++k], &e, 10);
			if (page == 0)
				e = (char *)"x";
		} else if (!strcmp(a, "--psnr") && k + 1 < argc) {
			psnr_min = strtod(argv[++k], &e);
		} else if (a[0] == '-' && a[1]) {
			fprintf(stderr, "locus-diff: unknown or incomplete option '%s' (try --help)\n", a);
			return 64;
		} else if (nf < 2) {
			file[nf++] = a;
		} else {
			fprintf(stderr, "locus-diff: more than two files ('%s')\n", a);
			return 64;
		}
		if (e && (*e || e == argv[k])) {
			fprintf(stderr, "locus-diff: bad number '%s' for %s\n", argv[k], argv[k - 1]);
			return 64;
		}
	}
	if (nf != 2) {
		fprintf(stderr, "locus-diff: need two files to compare (try --help)\n");
		return 64;
	}
	dev_image_t img[2];
	char err[600];
	memset(img, 0, sizeof img);
	for (int k = 0; k < 2; k++) {
		int rc = load(file[k], (unsigned)page, &img[k], err, sizeof err);
		if (rc) {
			if (rc == -65)
				fprintf(stderr, "%s\n", err);   /* names the file and the place */
			else
				fprintf(stderr, "locus-diff: %s\n", err);
			dev_image_free(&img[0]);
			return -rc;
		}
	}
	if (img[0].width != img[1].width || img[0].height != img[1].height) {
		printf("%s %s: sizes differ: %ux%u vs %ux%u\n", file[0], file[1], img[0].width, img[0].height,
			img[1].width, img[1].height);
		dev_image_free(&img[0]);
		dev_image_free(&img[1]);
		return 1;
	}
	size_t npix = (size_t)img[0].width * img[0].height, ndiff = 0;
	unsigned maxc = 0;
	double sse = 0;
	for (size_t i = 0; i < npix; i++) {
		const uint8_t *p = img[0].pix + 3 * i, *q = img[1].pix + 3 * i;
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
	double mse = sse / ((double)npix * 3);
	double psnr = mse > 0 ? 10.0 * log10(255.0 * 255.0 / mse) : INFINITY;
	char ps[32];
	if (isinf(psnr))
		snprintf(ps, sizeof ps, "inf");
	else
		snprintf(ps, sizeof ps, "%.2f", psnr);
	printf("%s %s: %zu of %zu pixels differ, max channel difference %u, PSNR %s dB\n", file[0], file[1],
		ndiff, npix, maxc, ps);
	int same = ndiff <= maxpix || (psnr_min >= 0 && psnr >= psnr_min);
	if (psnr_min >= 0 && maxpix == 0)
		same = psnr >= psnr_min || ndiff == 0;
	dev_image_free(&img[0]);
	dev_image_free(&img[1]);
	return same ? 0 : 1;
}
