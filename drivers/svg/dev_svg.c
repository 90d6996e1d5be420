/* dev-svg.c: SVG 1.1 vector device, the worked vector example of docs/drivers.md. */
#include <stdio.h>
#include <string.h>
#include "device/device.h"

/* Per-instance state: the page height, to turn y up into SVG's y down. */
typedef struct {
	int64_t height;             /* thousandths */
	int crisp;                  /* -O crisp=1: shape-rendering="crispEdges" */
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
	char w[DEV_FMT_SIZE], h[DEV_FMT_SIZE];
	s->height = (int64_t)pg->height * 1000;
	int rc = dev_printf(d, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
		"<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" ");
	if (!rc && pg->has_size)
		rc = dev_printf(d, "width=\"%smm\" height=\"%smm\" ", num(w, pg->width_mm), num(h, pg->height_mm));
	else if (!rc)
		rc = dev_printf(d, "width=\"%u\" height=\"%u\" ", pg->width, pg->height);
	if (!rc)
		rc = dev_printf(d, "viewBox=\"0 0 %u %u\"%s>\n<rect width=\"%u\" height=\"%u\" fill=\"#ffffff\"/>\n",
			pg->width, pg->height, s->crisp ? " shape-rendering=\"crispEdges\"" : "", pg->width, pg->height);
	return rc;
}

static int s_clear(dev_device_t *d, const dev_page_t *pg, meta_rgb_t rgb)
{
	return dev_printf(d, "<rect width=\"%u\" height=\"%u\" fill=\"#%06x\"/>\n", pg->width, pg->height, rgb);
}

/* The path data: subpaths of the flattened path, y turned down. */
static int path_data(dev_device_t *d, const scan_path_t *p)
{
	svg_t *s = d->priv;
	char x[DEV_FMT_SIZE], y[DEV_FMT_SIZE];
	int rc = dev_printf(d, "<path d=\"");
	for (size_t k = 0; k < p->nsubs && !rc; k++) {
		const scan_subpath_t *sub = &p->subs[k];
		for (size_t i = 0; i < sub->n && !rc; i++) {
			const scan_pt_t *q = &p->pts[sub->start + i];
			rc = dev_printf(d, "%s%s %s", i ? " L" : k ? " M" : "M", num(x, q->x), num(y, s->height - q->y));
		}
		if (!rc && sub->closed)
			rc = dev_printf(d, " Z");
	}
	return rc ? rc : dev_printf(d, "\"");
}

static int s_fill(dev_device_t *d, const dev_path_t *p, const dev_state_t *st)
{
	int rc = path_data(d, p->flat);
	return rc ? rc : dev_printf(d, " fill=\"#%06x\" fill-rule=\"%s\"/>\n", st->colour,
		st->rule == META_RULE_EVEN_ODD ? "evenodd" : "nonzero");
}

static int s_stroke(dev_device_t *d, const dev_path_t *p, const dev_state_t *st)
{
	static const char *const caps[] = { "butt", "round", "square" };
	static const char *const joins[] = { "miter", "round", "bevel" };
	char w[DEV_FMT_SIZE], m[DEV_FMT_SIZE];
	int rc = path_data(d, p->flat);
	if (!rc)
		rc = dev_printf(d, " fill=\"none\" stroke=\"#%06x\" stroke-width=\"%s\" stroke-linecap=\"%s\" "
			"stroke-linejoin=\"%s\" stroke-miterlimit=\"%s\"/>\n", st->colour, num(w, st->line_width),
			caps[st->cap % 3], joins[st->join % 3], num(m, st->miter_limit));
	return rc;
}

static int s_span(dev_device_t *d, unsigned x, unsigned y, unsigned n, meta_rgb_t rgb)
{
	svg_t *s = d->priv;
	return dev_printf(d, "<rect x=\"%u\" y=\"%lld\" width=\"%u\" height=\"1\" fill=\"#%06x\"/>\n", x,
		(long long)(s->height / 1000 - 1 - y), n, rgb);
}

static int s_row(dev_device_t *d, unsigned x, unsigned y, const meta_run_t *runs, size_t nruns)
{
	int rc = 0;
	for (size_t k = 0; k < nruns && !rc; k++) {
		rc = s_span(d, x, y, runs[k].count, runs[k].rgb);
		x += runs[k].count;
	}
	return rc;
}

static int s_end(dev_device_t *d, const dev_page_t *pg)
{
	(void)pg;
	return dev_printf(d, "</svg>\n");
}

const dev_ops_t dev_svg_ops = {
	.name = "svg", .description = "SVG 1.1 vector file (paths, dash pieces from the framework)",
	.extension = ".svg",
	/* SVG fills and draws any width; its dashes differ from §5.3 at closed subpaths, so the
	 * framework hands over the dash pieces instead (DEV_CAP_ONLY without DEV_CAP_DASH) */
	.caps = DEV_CAP_VECTOR | DEV_CAP_ONLY | DEV_CAP_FILL | DEV_CAP_WIDTH,
	.priv_size = sizeof(svg_t), .option_list = svg_options,
	.open = s_open, .begin_page = s_begin, .clear = s_clear, .stroke_path = s_stroke,
	.fill_path = s_fill, .put_span = s_span, .put_image_row = s_row, .end_page = s_end,
};
