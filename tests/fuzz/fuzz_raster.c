/* fuzz_raster.c: libFuzzer harness of replay through the raster framework on small pages: the whole-page and the banded replay give the same pixels, pages and message. */
#include <math.h>
#include "fuzz.h"
#include "device/device.h"

#ifndef FUZZ_ENTRY
#define FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

#define MAX_PIXELS (96 * 96)     /* small pages keep each run short */
#define MAX_WORK 200000.0        /* estimated chords + dash pieces in one input */

/* What the collecting device keeps: every page's pixels, one after the other. */
typedef struct {
	fuzz_buf_t pix;
	unsigned rows;               /* rows received on the current page */
	unsigned bands;
} collect_t;

static int c_begin(dev_device_t *d, const dev_page_t *pg)
{
	collect_t *c = d->user;
	if ((uint64_t)pg->width * pg->height > MAX_PIXELS)
		return dev_fail(d, DEV_EDEVICE, "page too big for the harness");
	c->rows = 0;
	return 0;
}

static int c_band(dev_device_t *d, const render_band_t *b)
{
	collect_t *c = d->user;
	FUZZ_ASSERT(b->y0 == c->rows, "band starts at row %u, %u rows written", b->y0, c->rows);
	FUZZ_ASSERT(b->y0 + b->nrows <= b->page_height, "band past the page");
	for (unsigned k = 0; k < b->nrows; k++)
		if (fuzz_buf_write(&c->pix, b->pix + k * b->stride, (size_t)b->width * 3))
			return dev_fail(d, META_ENOMEM, "out of memory");
	c->rows += b->nrows;
	c->bands++;
	return 0;
}

static int c_end(dev_device_t *d, const dev_page_t *pg)
{
	collect_t *c = d->user;
	FUZZ_ASSERT(c->rows == pg->height, "page of %u rows got %u", pg->height, c->rows);
	return 0;
}

static const dev_ops_t collect_ops = {
	.name = "collect", .description = "fuzz: keeps the pixels", .extension = "",
	.caps = DEV_CAP_RASTER, .begin_page = c_begin, .write_band = c_band, .end_page = c_end,
};

static int replay(const uint8_t *data, size_t size, unsigned band_rows, collect_t *c, char *err, size_t errlen,
		unsigned *pages)
{
	meta_reader_t *r = meta_reader_mem(data, size, "in");
	dev_device_t *d = dev_new(&collect_ops, NULL);
	FUZZ_ASSERT(r && d, "out of memory at start");
	d->user = c;
	d->band_rows = band_rows;
	int rc = dev_play(r, d);
	snprintf(err, errlen, "%s", rc < 0 ? dev_error(d) : "");
	if (rc < 0)
		FUZZ_ASSERT(fuzz_one_line(err), "error not one line: '%s'", err);
	*pages = d->pages;
	dev_free(d);
	meta_reader_free(r);
	return rc;
}

int FUZZ_ENTRY(const uint8_t *data, size_t size);
int FUZZ_ENTRY(const uint8_t *data, size_t size)
{
	collect_t whole = { { 0 }, 0, 0 }, band = { { 0 }, 0, 0 };
	char e1[600], e2[600];
	unsigned p1, p2;
	double w;
	if (size > 65536 || (w = fuzz_work(data, size, MAX_PIXELS, NULL)) < 0 || w > MAX_WORK)
		return 0;
	int r1 = replay(data, size, 0, &whole, e1, sizeof e1, &p1);
	/* bands of 1 to 8 rows, chosen by the input so both small and odd heights are covered */
	unsigned rows = 1 + (size ? data[size - 1] % 8 : 0);
	int r2 = replay(data, size, rows, &band, e2, sizeof e2, &p2);
	FUZZ_ASSERT((r1 < 0) == (r2 < 0), "whole replay %d, banded (%u rows) %d: '%s' / '%s'", r1, rows, r2, e1, e2);
	FUZZ_ASSERT(!strcmp(e1, e2), "messages differ: '%s' / '%s'", e1, e2);
	FUZZ_ASSERT(p1 == p2, "whole replay %u pages, banded %u", p1, p2);
	FUZZ_ASSERT(whole.pix.n == band.pix.n, "whole replay %zu bytes of pixels, banded %zu", whole.pix.n, band.pix.n);
	for (size_t i = 0; i < whole.pix.n; i++)
		FUZZ_ASSERT(whole.pix.p[i] == band.pix.p[i], "pixel byte %zu differs (bands of %u rows)", i, rows);
	free(whole.pix.p);
	free(band.pix.p);
	return 0;
}
