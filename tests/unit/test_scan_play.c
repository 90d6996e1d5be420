/* test_scan_play.c: dev_play drives a vector device: paths, state, defaults, page hooks, errors. */
#include <stdlib.h>
#include "device/device.h"
#include "unit.h"

/* A recording vector device. */
typedef struct {
	char log[4096];
	int strokes, fills, spans, pages_begun, pages_ended, closed;
	unsigned page_w, page_h;
	int had_size;
	int last_cap, last_join;
	size_t last_npts, last_nelems;
	meta_rgb_t last_colour;
	int64_t last_width, first_x, first_y;
	size_t ndash;
} rec_t;

static void note(dev_device_t *d, const char *what)
{
	rec_t *r = d->priv;
	strncat(r->log, what, sizeof r->log - strlen(r->log) - 1);
	strncat(r->log, " ", sizeof r->log - strlen(r->log) - 1);
}

static int v_begin(dev_device_t *d, const dev_page_t *pg)
{
	rec_t *r = d->priv;
	r->pages_begun++;
	r->page_w = pg->width;
	r->page_h = pg->height;
	r->had_size = pg->has_size && pg->width_mm == 50000;
	note(d, "begin");
	return 0;
}

static int v_path(dev_device_t *d, const dev_path_t *p, const dev_state_t *st, int fill)
{
	rec_t *r = d->priv;
	fill ? r->fills++ : r->strokes++;
	r->last_cap = st->cap;
	r->last_join = st->join;
	r->last_npts = p->flat->npts;
	r->last_nelems = p->nelems;
	r->last_colour = st->colour;
	r->last_width = st->width;
	r->ndash = st->ndash;
	r->first_x = p->flat->npts ? p->flat->pts[0].x : -1;
	r->first_y = p->flat->npts ? p->flat->pts[0].y : -1;
	note(d, fill ? "fill" : "stroke");
	return 0;
}

static int v_stroke(dev_device_t *d, const dev_path_t *p, const dev_state_t *st) { return v_path(d, p, st, 0); }
static int v_fill(dev_device_t *d, const dev_path_t *p, const dev_state_t *st) { return v_path(d, p, st, 1); }

static int v_span(dev_device_t *d, unsigned x, unsigned y, unsigned n, meta_rgb_t rgb)
{
	rec_t *r = d->priv;
	char b[64];
	r->spans++;
	snprintf(b, sizeof b, "span(%u,%u,%u,%06x)", x, y, n, (unsigned)rgb);
	note(d, b);
	return 0;
}

static int v_end(dev_device_t *d, const dev_page_t *pg)
{
	rec_t *r = d->priv;
	(void)pg;
	r->pages_ended++;
	note(d, "end");
	return 0;
}

static int v_close(dev_device_t *d)
{
	((rec_t *)d->priv)->closed++;
	return 0;
}

static const dev_ops_t vec_ops = {
	.name = "rec", .description = "recorder", .caps = DEV_CAP_VECTOR, .priv_size = sizeof(rec_t),
	.begin_page = v_begin, .stroke_path = v_stroke, .fill_path = v_fill, .put_span = v_span,
	.end_page = v_end, .close = v_close,
};

static int play(const char *text, dev_device_t **out)
{
	meta_reader_t *r = meta_reader_mem(text, strlen(text), "mem.meta");
	dev_device_t *d = dev_new(&vec_ops, NULL);
	int rc = dev_play(r, d);
	meta_reader_free(r);
	*out = d;
	return rc;
}

int main(void)
{
	dev_device_t *d;
	rec_t *r;
	int rc = play("LOCUS-META 1\npage 100 50\nsize 50 25\nclear #123456\ncolour #ff0000\nwidth 3\n"
		"dash 2\ncap square\nstroke\nmove 1 2\ndraw 3 4\narc 10 10 5 0 90\nend\n"
		"text 5 5 12 0 \"Hi\"\nspan 95 3 10 #00ff00\nimage 1 1 3 2\nrow 3 #0000ff\nrow 1 #000001 2 #000002\n"
		"end-page\n", &d);
	r = d->priv;
	CHECK(rc == 0, "a valid file plays (%s)", dev_error(d));
	CHECK(r->pages_begun == 1 && r->pages_ended == 1 && r->closed == 1 && r->page_w == 100 && r->page_h == 50,
		"begin_page/end_page/close once, with the page size");
	CHECK(r->had_size, "begin_page already knows the physical size");
	CHECK(strncmp(r->log, "begin fill stroke stroke span(95,3,5,00ff00)", 44) == 0,
		"clear without a clear op becomes a page fill; then the stroke and the text (%s)", r->log);
	CHECK(strstr(r->log, "span(1,2,3,0000ff) span(1,1,1,000001) span(2,1,2,000002)") != NULL,
		"image rows become spans, top row first (row 0 at y = Y + H - 1)");
	CHECK(r->strokes == 2 && r->fills == 1, "one stroke, the text as a stroke, one fill");
	CHECK(r->last_cap == META_CAP_ROUND && r->last_join == META_JOIN_ROUND && r->ndash == 0 &&
		r->last_width == 3000 && r->last_colour == 0xff0000,
		"text: round caps and joins, no dash, current width and colour");
	dev_free(d);

	rc = play("LOCUS-META 1\npage 10 10\ndash 2\ncap square\nstroke\nmove 1 2\ndraw 3 4\narc 10 10 5 0 90\nend\nend-page\n", &d);
	r = d->priv;
	CHECK(rc == 0 && r->last_cap == META_CAP_SQUARE && r->ndash == 2 && r->last_nelems == 3 &&
		r->first_x == 1000 && r->first_y == 2000, "stroke: state, odd dash doubled, raw elements kept");
	CHECK(r->last_npts == 2 + 1 + (size_t)((90 * scan_circle_chords(5000) + 359) / 360),
		"the flattened path has the arc's chords (%zu points)", r->last_npts);
	dev_free(d);

	rc = play("LOCUS-META 1\npage 10 10\ncolour #00ff00\nend-page\npage 10 10\nstroke\nmove 0 0\ndraw 1 1\nend\nend-page\n", &d);
	r = d->priv;
	CHECK(rc == 0 && r->pages_begun == 2 && r->last_colour == 0, "state does not carry over to the next page");
	CHECK(d->pages == 2, "the instance counts pages");
	dev_free(d);

	rc = play("LOCUS-META 1\npage 10 10\nstroke\nmove 0 0\ndraw 1 x\n", &d);
	CHECK(rc == META_ESYNTAX && strncmp(dev_error(d), "mem.meta:5:", 11) == 0,
		"a reader error comes back verbatim: %s", dev_error(d));
	CHECK(((rec_t *)d->priv)->closed == 1, "close is called after an error too");
	dev_free(d);
	return UNIT_DONE();
}
