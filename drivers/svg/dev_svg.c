/* dev-svg.c: SVG 1.1 vector device, the worked vector example of docs/drivers.md. Image rows
 * become embedded PNG <image>s (docs/svg.md). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "device/device.h"
#include "image/image.h"

/* The raw bytes (3 a pixel) one <image> holds at most: a taller image is written as strips of
 * whole rows, so memory is one strip whatever the image, and the base64 attribute stays under
 * libxml2's 10 MB limit on one attribute value (4 MiB of pixels is at most about 5.6 MB of
 * base64 even where deflate gains nothing). */
#define SVG_STRIP_BYTES ((size_t)4 << 20)

/* Per-instance state: the writer, the page height, to turn y up into SVG's y down, and the
 * image strip being collected. */
typedef struct {
	dev_writer_t w;             /* over d->out for the page (first: it is large) */
	int64_t height;             /* thousandths */
	int crisp;                  /* -O crisp=1: shape-rendering="crispEdges" */
	/* the strip: consecutive rows of one image (same x and width, each row the one below the
	 * last), top row first; written out when the image ends, anything else is drawn, or it
	 * holds SVG_STRIP_BYTES */
	unsigned sx, sw;            /* its left column and width */
	int64_t stop;               /* page row (from the bottom) of its top row */
	unsigned nrows;
	uint8_t *pix;               /* nrows rows of sw * 3 bytes */
	size_t capbytes;            /* allocated, at most SVG_STRIP_BYTES or one row */
	/* base64 of the PNG on its way out */
	unsigned char carry[3];
	size_t ncarry, nout;
	char out[4096];
} svg_t;

static const dev_option_t svg_options[] = {
	{ "crisp", "1: no anti-aliasing in the viewer (shape-rendering crispEdges); default 0" },
	{ NULL, NULL }
};

/* A coordinate in pixels, exact to the thousandth, never -0. */
static const char *num(char *buf, int64_t v)
{
	return dev_fmt_fix(buf, v, 3, 3);
}

/* The writer's failure on the device: the transport's message and the code of its errno, or
 * (a format that did not fit) a device error. */
static int w_fail(dev_device_t *d)
{
	if (d->out && io_failed(d->out))
		return dev_fail(d, dev_code_of_errno(io_errno(d->out)), "%s", io_error(d->out));
	return dev_fail(d, DEV_EDEVICE, "svg: bad output format");
}

/* 0, or the writer's failure on the device. */
static int w_done(dev_device_t *d)
{
	svg_t *s = d->priv;
	return s->w.err ? w_fail(d) : 0;
}

static int s_open(dev_device_t *d)
{
	svg_t *s = d->priv;
	char v[8];
	const char *c = dev_option(d, "crisp", v, sizeof v);
	if (c && strcmp(c, "0") && strcmp(c, "1"))
		return dev_fail(d, DEV_EUSAGE, "svg: crisp must be 0 or 1, not '%s'", c);
	s->crisp = c && !strcmp(c, "1");
	return 0;
}

static int s_begin(dev_device_t *d, const dev_page_t *pg)
{
	svg_t *s = d->priv;
	char wb[DEV_FMT_SIZE], hb[DEV_FMT_SIZE];
	s->nrows = 0;
	s->height = (int64_t)pg->height * 1000;
	if (!d->out)
		return dev_fail(d, DEV_EDEVICE, "svg: no output");
	dev_w_init(&s->w, d->out);
	dev_writer_t *w = &s->w;
	dev_w_printf(w, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
		"<svg xmlns=\"http://www.w3.org/2000/svg\" "
		"xmlns:xlink=\"http://www.w3.org/1999/xlink\" version=\"1.1\" ");
	if (pg->has_size)
		dev_w_printf(w, "width=\"%smm\" height=\"%smm\" ", num(wb, pg->width_mm), num(hb, pg->height_mm));
	else
		dev_w_printf(w, "width=\"%u\" height=\"%u\" ", pg->width, pg->height);
	dev_w_printf(w, "viewBox=\"0 0 %u %u\"%s>\n<rect width=\"%u\" height=\"%u\" fill=\"#ffffff\"/>\n",
			pg->width, pg->height, s->crisp ? " shape-rendering=\"crispEdges\"" : "", pg->width, pg->height);
	return w_done(d);
}

/* Base64 (RFC 4648, no line breaks: a data: URI is one token) of the PNG as libpng hands it
 * over, through a 4 KB buffer into the output. */
static const char b64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

static int b64_drain(svg_t *s)
{
	int rc = s->nout ? dev_w_write(&s->w, s->out, s->nout) : s->w.err;
	s->nout = 0;
	return rc;
}

static int b64_quad(svg_t *s, const unsigned char *q, size_t n)
{
	if (s->nout + 4 > sizeof s->out && b64_drain(s))
		return -1;
	uint32_t v = (uint32_t)q[0] << 16 | (uint32_t)(n > 1 ? q[1] : 0) << 8 | (n > 2 ? q[2] : 0);
	char *o = s->out + s->nout;
	o[0] = b64[v >> 18];
	o[1] = b64[v >> 12 & 63];
	o[2] = n > 1 ? b64[v >> 6 & 63] : '=';
	o[3] = n > 2 ? b64[v & 63] : '=';
	s->nout += 4;
	return 0;
}

static int b64_write(void *user, const void *buf, size_t n)
{
	svg_t *s = user;
	const unsigned char *p = buf;
	while (n) {
		s->carry[s->ncarry++] = *p++;
		n--;
		if (s->ncarry == 3) {
			if (b64_quad(s, s->carry, 3))
				return -1;
			s->ncarry = 0;
		}
	}
	return 0;
}

/* Write the strip as <image x y width height> in page units (one sample on one pixel of the
 * viewBox) with its PNG inline; pixelated (CSS) where the viewer knows it, else optimizeSpeed
 * (SVG 1.1): a zoomed viewer shows square samples, not a blur. */
static int strip_flush(dev_device_t *d)
{
	svg_t *s = d->priv;
	if (!s->nrows)
		return 0;
	unsigned n = s->nrows;
	s->nrows = 0;
	int rc = dev_w_printf(&s->w, "<image x=\"%u\" y=\"%lld\" width=\"%u\" height=\"%u\" "
		"image-rendering=\"optimizeSpeed\" style=\"image-rendering:optimizeSpeed;"
		"image-rendering:pixelated\" xlink:href=\"data:image/png;base64,", s->sx,
		(long long)(s->height / 1000 - 1 - s->stop), s->sw, n);
	if (rc)
		return w_fail(d);
	char err[256];
	s->ncarry = s->nout = 0;
	img_writer_t *w = img_writer_new_png_fn(b64_write, s, 1, s->sw, n, err, sizeof err);
	if (!w)
		return s->w.err ? dev_fail(d, META_EIO, "%s", io_error(d->out))
			: dev_fail(d, META_ENOMEM, "svg: %s", err);
	if (img_writer_rows(w, s->pix, (size_t)s->sw * 3, n) || img_writer_finish(w)) {
		rc = s->w.err ? dev_fail(d, META_EIO, "%s", io_error(d->out))
			: dev_fail(d, strstr(img_writer_error(w), "memory") ? META_ENOMEM : DEV_EDEVICE,
				"svg: %s", img_writer_error(w));
		img_writer_abort(w);
		return rc;
	}
	if ((s->ncarry && b64_quad(s, s->carry, s->ncarry)) || b64_drain(s))
		return dev_fail(d, META_EIO, "%s", io_error(d->out));
	dev_w_puts(&s->w, "\"/>\n");
	return w_done(d);
}

static int s_clear(dev_device_t *d, const dev_page_t *pg, meta_rgb_t rgb)
{
	svg_t *s = d->priv;
	int rc = strip_flush(d);
	if (rc)
		return rc;
	dev_w_printf(&s->w, "<rect width=\"%u\" height=\"%u\" fill=\"#%06x\"/>\n", pg->width, pg->height, rgb);
	return w_done(d);
}

/* The path data: subpaths of the flattened path, y turned down. 0 or the writer's error. */
static int path_data(svg_t *s, const scan_path_t *p)
{
	dev_writer_t *w = &s->w;
	char x[DEV_FMT_SIZE], y[DEV_FMT_SIZE];
	int rc = dev_w_puts(w, "<path d=\"");
	for (size_t k = 0; k < p->nsubs && !rc; k++) {
		const scan_subpath_t *sub = &p->subs[k];
		for (size_t i = 0; i < sub->n && !rc; i++) {
			const scan_pt_t *q = &p->pts[sub->start + i];
			rc = dev_w_printf(w, "%s%s %s", i ? " L" : k ? " M" : "M", num(x, q->x), num(y, s->height - q->y));
		}
		if (!rc && sub->closed)
			rc = dev_w_puts(w, " Z");
	}
	return rc ? rc : dev_w_puts(w, "\"");
}

static int s_fill(dev_device_t *d, const dev_path_t *p, const dev_state_t *st)
{
	svg_t *s = d->priv;
	int rc = strip_flush(d);
	if (rc)
		return rc;
	if (!path_data(s, p->flat))
		dev_w_printf(&s->w, " fill=\"#%06x\" fill-rule=\"%s\"/>\n", st->colour,
			st->rule == META_RULE_EVEN_ODD ? "evenodd" : "nonzero");
	return w_done(d);
}

static int s_stroke(dev_device_t *d, const dev_path_t *p, const dev_state_t *st)
{
	static const char *const caps[] = { "butt", "round", "square" };
	static const char *const joins[] = { "miter", "round", "bevel" };
	svg_t *s = d->priv;
	char w[DEV_FMT_SIZE], m[DEV_FMT_SIZE];
	int rc = strip_flush(d);
	if (rc)
		return rc;
	if (!path_data(s, p->flat))
		dev_w_printf(&s->w, " fill=\"none\" stroke=\"#%06x\" stroke-width=\"%s\" stroke-linecap=\"%s\" "
			"stroke-linejoin=\"%s\" stroke-miterlimit=\"%s\"/>\n", st->colour, num(w, st->line_width),
			caps[st->cap % 3], joins[st->join % 3], num(m, st->miter_limit));
	return w_done(d);
}

/* A span is one run of one colour: a one-row <rect> is exact, and smaller than any PNG. */
static int s_span(dev_device_t *d, unsigned x, unsigned y, unsigned n, meta_rgb_t rgb)
{
	svg_t *s = d->priv;
	int rc = strip_flush(d);
	if (rc)
		return rc;
	dev_w_printf(&s->w, "<rect x=\"%u\" y=\"%lld\" width=\"%u\" height=\"1\" fill=\"#%06x\"/>\n", x,
		(long long)(s->height / 1000 - 1 - y), n, rgb);
	return w_done(d);
}

/* An image row joins the strip when it continues it (the row below, same x, same width), else
 * it starts a new one. */
static int s_row(dev_device_t *d, unsigned x, unsigned y, const meta_run_t *runs, size_t nruns)
{
	svg_t *s = d->priv;
	unsigned w = 0;
	for (size_t k = 0; k < nruns; k++)
		w += runs[k].count;
	if (!w)
		return 0;
	size_t rowbytes = (size_t)w * 3;
	unsigned maxrows = SVG_STRIP_BYTES / rowbytes ? (unsigned)(SVG_STRIP_BYTES / rowbytes) : 1;
	if (s->nrows && (x != s->sx || w != s->sw || (int64_t)y != s->stop - s->nrows ||
			s->nrows >= maxrows)) {
		int rc = strip_flush(d);
		if (rc)
			return rc;
	}
	if (!s->nrows) {
		s->sx = x;
		s->sw = w;
		s->stop = y;
	}
	size_t need = ((size_t)s->nrows + 1) * rowbytes;
	if (need > s->capbytes) {
		size_t cap = s->capbytes * 2 > need ? s->capbytes * 2 : need;
		if (cap > (size_t)maxrows * rowbytes)
			cap = (size_t)maxrows * rowbytes;
		uint8_t *p = realloc(s->pix, cap);
		if (!p)
			return dev_fail(d, META_ENOMEM, "out of memory");
		s->pix = p;
		s->capbytes = cap;
	}
	uint8_t *o = s->pix + (size_t)s->nrows * rowbytes;
	for (size_t k = 0; k < nruns; k++)
		for (uint32_t i = 0; i < runs[k].count; i++) {
			*o++ = (uint8_t)(runs[k].rgb >> 16);
			*o++ = (uint8_t)(runs[k].rgb >> 8);
			*o++ = (uint8_t)runs[k].rgb;
		}
	s->nrows++;
	return 0;
}

static int s_end(dev_device_t *d, const dev_page_t *pg)
{
	(void)pg;
	svg_t *s = d->priv;
	int rc = strip_flush(d);
	if (rc)
		return rc;
	/* everything to the transport (the framework flushes and closes it) */
	dev_w_puts(&s->w, "</svg>\n");
	dev_w_drain(&s->w);
	return w_done(d);
}

static int s_close(dev_device_t *d)
{
	svg_t *s = d->priv;
	free(s->pix);
	s->pix = NULL;
	s->capbytes = 0;
	return 0;
}

const dev_ops_t dev_svg_ops = {
	.name = "svg", .description = "SVG 1.1 vector file (paths, dash pieces from the framework, images as PNG)",
	.extension = ".svg",
	/* SVG fills and draws any width; its dashes differ from §5.3 at closed subpaths, so the
	 * framework hands over the dash pieces instead (DEV_CAP_ONLY without DEV_CAP_DASH) */
	.caps = DEV_CAP_VECTOR | DEV_CAP_ONLY | DEV_CAP_FILL | DEV_CAP_WIDTH,
	.priv_size = sizeof(svg_t), .option_list = svg_options,
	.open = s_open, .begin_page = s_begin, .clear = s_clear, .stroke_path = s_stroke,
	.fill_path = s_fill, .put_span = s_span, .put_image_row = s_row, .end_page = s_end,
	.close = s_close,
};
