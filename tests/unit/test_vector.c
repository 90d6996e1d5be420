/* test_vector.c: what the framework supplies to vector devices by their capabilities: dash
 * pieces, stroke outlines, hatching, raw elements for text, the page on clear, clipped image
 * rows, minimum widths; and dev_fmt_fix. */
#include <stdlib.h>
#include "device/device.h"
#include "unit.h"

/* A recording vector device; the caps vary per test through a copy of the table. */
typedef struct {
	int strokes, fills, hatches, clears, rows;
	unsigned clear_w, clear_h;
	size_t last_nsubs, last_npts, last_nelems, row_runs;
	int64_t last_width, last_line_width;
	size_t last_ndash;
	int last_rule;
	unsigned row_sum, page_w_seen;
	int elems_ok;
} rec_t;

static void note_path(rec_t *r, const dev_path_t *p, const dev_state_t *st)
{
	r->last_nsubs = p->flat->nsubs;
	r->last_npts = p->flat->npts;
	r->last_nelems = p->nelems;
	r->last_width = st->width;
	r->last_line_width = st->line_width;
	r->last_ndash = st->ndash;
	r->last_rule = st->rule;
	r->elems_ok = p->elems != NULL && p->nelems >= p->flat->npts;
}

static int v_stroke(dev_device_t *d, const dev_path_t *p, const dev_state_t *st)
{
	rec_t *r = d->priv;
	r->strokes++;
	note_path(r, p, st);
	r->page_w_seen = d->page ? d->page->width : 0;
	return 0;
}

static int v_fill(dev_device_t *d, const dev_path_t *p, const dev_state_t *st)
{
	rec_t *r = d->priv;
	r->fills++;
	note_path(r, p, st);
	return 0;
}

static int v_hatch(dev_device_t *d, const dev_path_t *p, const dev_state_t *st)
{
	rec_t *r = d->priv;
	r->hatches++;
	note_path(r, p, st);
	return 0;
}

static int v_clear(dev_device_t *d, const dev_page_t *pg, meta_rgb_t rgb)
{
	rec_t *r = d->priv;
	(void)rgb;
	r->clears++;
	r->clear_w = pg->width;
	r->clear_h = pg->height;
	return 0;
}

static int v_row(dev_device_t *d, unsigned x, unsigned y, const meta_run_t *runs, size_t n)
{
	rec_t *r = d->priv;
	(void)y;
	r->rows++;
	r->row_runs = n;
	r->row_sum = x;
	for (size_t k = 0; k < n; k++)
		r->row_sum += runs[k].count;
	return 0;
}

static dev_ops_t ops = {
	.name = "vrec", .description = "recorder", .priv_size = sizeof(rec_t),
	.stroke_path = v_stroke, .fill_path = v_fill, .clear = v_clear, .put_image_row = v_row,
};

static rec_t run(unsigned caps, int with_hatch, const char *text, int *rc)
{
	ops.caps = DEV_CAP_VECTOR | caps;
	ops.hatch = with_hatch ? v_hatch : NULL;
	meta_reader_t *r = meta_reader_mem(text, strlen(text), "v.meta");
	dev_device_t *d = dev_new(&ops, NULL);
	*rc = dev_play(r, d);
	if (*rc)
		printf("# %s\n", dev_error(d));
	rec_t out = *(rec_t *)d->priv;
	dev_free(d);
	meta_reader_free(r);
	return out;
}

static const char *dashed =
	"LOCUS-META 1\npage 100 50\nwidth 3\ndash 10 5\nstroke\nmove 0 10\ndraw 95 10\nend\nend-page\n";

static void test_caps(void)
{
	int rc;
	rec_t r = run(0, 0, dashed, &rc);
	CHECK(rc == 0 && r.strokes == 1 && r.last_ndash == 2 && r.last_nsubs == 1 && r.last_width == 3000,
		"no DEV_CAP_ONLY: the device gets the path, its dash and width as they are");
	r = run(DEV_CAP_ONLY | DEV_CAP_FILL | DEV_CAP_WIDTH, 0, dashed, &rc);
	/* 95 pixels of 10 on, 5 off: dashes at 0, 15, 30, 45, 60, 75, 90 (the last 5 long) */
	CHECK(rc == 0 && r.strokes == 1 && r.last_ndash == 0 && r.last_nsubs == 7 && r.last_nelems == 0,
		"without DEV_CAP_DASH: seven dash pieces, no dash, no raw elements for a device without arcs (%zu subpaths)",
		r.last_nsubs);
	r = run(DEV_CAP_ONLY | DEV_CAP_ARCS | DEV_CAP_FILL | DEV_CAP_WIDTH, 0, dashed, &rc);
	CHECK(rc == 0 && r.strokes == 1 && r.last_nsubs == 7 && r.elems_ok && r.last_nelems == 14,
		"without DEV_CAP_DASH, with DEV_CAP_ARCS: the pieces' raw elements made (%zu)", r.last_nelems);
	r = run(DEV_CAP_ONLY | DEV_CAP_FILL | DEV_CAP_DASH, 0, dashed, &rc);
	CHECK(rc == 0 && r.strokes == 0 && r.fills == 1 && r.last_rule == META_RULE_NON_ZERO &&
		r.last_nsubs == 1 && r.last_npts == 4, "without DEV_CAP_WIDTH: the 3-pixel stroke reaches fill_path as its piece");
	r = run(DEV_CAP_ONLY | DEV_CAP_FILL, 0, dashed, &rc);
	CHECK(rc == 0 && r.strokes == 0 && r.fills == 1 && r.last_nsubs == 7,
		"without both: seven dash outlines, filled non-zero");
	r = run(DEV_CAP_ONLY | DEV_CAP_FILL, 0, "LOCUS-META 1\npage 100 50\nwidth 0.5\nstroke\nmove 0 10\ndraw 95 10\nend\nend-page\n", &rc);
	CHECK(rc == 0 && r.strokes == 1 && r.fills == 0 && r.last_width == 500 && r.last_line_width == 1000,
		"a thin line stays a line; line_width gives the width drawn (1 pixel for 0.5)");
	const char *fill = "LOCUS-META 1\npage 100 50\nwidth 2\nfill\nmove 10 10\ndraw 30 10\ndraw 30 20\ndraw 10 20\nend\nend-page\n";
	r = run(DEV_CAP_ONLY | DEV_CAP_WIDTH, 1, fill, &rc);
	CHECK(rc == 0 && r.fills == 0 && r.hatches == 1 && r.last_npts == 4, "without DEV_CAP_FILL: the device's hatch op gets the polygon");
	r = run(DEV_CAP_ONLY | DEV_CAP_WIDTH, 0, fill, &rc);
	/* outline (4 points) + lines through centres 10.5, 12.5 ... 18.5: every 2 pixels (width 2) */
	CHECK(rc == 0 && r.fills == 0 && r.strokes == 1 && r.last_nsubs == 1 + 5 && r.last_npts == 4 + 10,
		"without a hatch op: outline and 5 hatch lines 2 pixels apart, stroked (%zu subpaths)", r.last_nsubs);
}

static void test_misc(void)
{
	int rc;
	rec_t r = run(0, 0, "LOCUS-META 1\npage 40 30\nclear #ff0000\nimage 30 5 20 2\nrow 5 #000000 10 #ffffff 5 #000000\n"
		"row 20 #00ff00\nstroke\nmove 0 0\ndraw 4 4\nend\nend-page\n", &rc);
	CHECK(rc == 0 && r.clears == 1 && r.clear_w == 40 && r.clear_h == 30, "clear carries the page size");
	CHECK(r.rows == 2 && r.row_sum == 40 && r.row_runs == 1, "image rows reach put_image_row clipped to the page");
	CHECK(r.page_w_seen == 40, "d->page is the page being replayed");
	r = run(DEV_CAP_ARCS, 0, "LOCUS-META 1\npage 40 30\ntext 2 2 10 0 \"Hi\"\nend-page\n", &rc);
	CHECK(rc == 0 && r.strokes == 1 && r.elems_ok && r.last_nelems == r.last_npts,
		"text reaches a DEV_CAP_ARCS device with raw elements (%zu)", r.last_nelems);
	r = run(0, 0, "LOCUS-META 1\npage 40 30\ndash 0.001\nstroke\nmove 0 0\ndraw 40 0\nend\nend-page\n", &rc);
	CHECK(rc == 0 && r.last_ndash == 0, "a dash finer than a pixel reaches devices as solid");
	char b[DEV_FMT_SIZE];
	CHECK_STR(dev_fmt_fix(b, 1500, 3, 3), "1.5", "1.5");
	CHECK_STR(dev_fmt_fix(b, -1, 3, 2), "0", "-0.001 to 2 places is 0, not -0");
	CHECK_STR(dev_fmt_fix(b, -2500, 3, 0), "-3", "halves away from zero");
	CHECK_STR(dev_fmt_fix(b, -1000000000, 3, 3), "-1000000", "-1000000");
	CHECK_STR(dev_fmt_fix(b, 12345, 3, 2), "12.35", "12.345 to 2 places");
	CHECK_STR(dev_fmt_fix(b, 0, 3, 3), "0", "0");
	CHECK_STR(dev_fmt_fix(b, 7, 0, 0), "7", "integers");
}

int main(void)
{
	test_caps();
	test_misc();
	return UNIT_DONE();
}
