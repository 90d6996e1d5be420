/* device.c: the meta replay loop dev_play() and defaults for vector devices (the instances and their
 * errors are in instance.c, below this file and every other file of device/). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "device/device.h"
#include "render/aa.h"
#include "device/fit.h"
#include "device/vecsupply.h"
#include "render/render.h"

/* Memory guard: a path's points after flattening (16 bytes each): the spec's limit (§6), which
 * the reader already checks; kept here for paths built by the framework itself. */
#define DEV_MAX_FLAT_POINTS META_MAX_FLAT_POINTS

/* Everything one replay needs. */
typedef struct {
	meta_reader_t *rd;
	dev_device_t *d;
	dev_page_t page;
	dev_state_t st;
	int in_page, path_kind;          /* path_kind: 0, META_STROKE or META_FILL */
	scan_path_t path;
	dev_elem_t *elems;
	size_t nelems, cap_elems;
	render_t *rr;                /* raster devices */
	unsigned img_x, img_y, img_h, img_row;   /* current image */
	dev_map_t map;                   /* raster devices: the page on the device's raster */
	int mapped;                      /* 1: a raster of its own, not the identity */
	dev_fit_img_t *img;               /* mapped: the image being resampled */
	scan_path_t pieces;              /* raster, mapped: dash pieces */
	dev_vec_t vec;                    /* vector devices: scratch for what the framework supplies */
	render_aa_t *aa;                     /* raster, anti-aliased: the downsampler */
	scan_ctx_t *sctx;                /* mapped, non-square pixels: stroke pieces */
	scan_path_t iso, outline;        /* and their scratch paths */
} play_t;

static void default_state(dev_state_t *s)
{
	memset(s, 0, sizeof *s);
	s->colour = 0x000000;
	s->width = 1000;
	s->line_width = 1000;
	s->cap = META_CAP_BUTT;
	s->join = META_JOIN_MITER;
	s->miter_limit = 10000;
	s->rule = META_RULE_NON_ZERO;
}

static void style_of(const play_t *p, scan_style_t *st, int text)
{
	const dev_state_t *s = &p->st;
	st->width = p->mapped ? dev_fit_width(&p->map, s->width) : s->width;
	st->cap = text ? META_CAP_ROUND : s->cap;
	st->join = text ? META_JOIN_ROUND : s->join;
	st->miter_limit = s->miter_limit;
	st->dash = text ? NULL : s->dash;
	st->ndash = text ? 0 : s->ndash;
}

static int is_raster(const dev_device_t *d)
{
	return (d->ops->caps & DEV_CAP_RASTER) != 0;
}

static int write_band(void *user, const render_band_t *b)
{
	dev_device_t *d = user;
	if (!d->ops->write_band)
		return 0;
	return d->ops->write_band(d, b);
}

/* A band from the renderer: to the device, or through the anti-aliasing downsampler. */
static int emit_band(void *user, const render_band_t *b)
{
	play_t *p = user;
	return p->aa ? render_aa_band(p->aa, b, write_band, p->d) : write_band(p->d, b);
}

static int nomem(play_t *p)
{
	return dev_fail(p->d, META_ENOMEM, "out of memory");
}

/* A failure of the page renderer: its own message (the band spool, naming the file's directory
 * and the cause) when it has one, else out of memory. */
static int render_fail(play_t *p, int rc)
{
	const char *m = p->rr ? render_error(p->rr) : "";
	return dev_fail(p->d, rc, "%s", m[0] ? m : "out of memory while rendering");
}

/* A filled rectangle of pixels for vector devices without put_span. */
static int rect_path(play_t *p, int64_t x0, int64_t y0, int64_t x1, int64_t y1, meta_rgb_t rgb)
{
	scan_path_t r = { 0 };
	int rc = 0;
	if (scan_path_move(&r, x0, y0) || scan_path_draw(&r, x1, y0) || scan_path_draw(&r, x1, y1) ||
			scan_path_draw(&r, x0, y1)) {
		scan_path_free(&r);
		return nomem(p);
	}
	dev_state_t s = p->st;
	s.colour = rgb;
	s.rule = META_RULE_NON_ZERO;
	rc = dev_vec_fill(p->d, &p->vec, &r, NULL, 0, &s);
	scan_path_free(&r);
	return rc;
}

static int do_span(play_t *p, int64_t x, int64_t y, int64_t n, meta_rgb_t rgb)
{
	if (p->mapped)
		return dev_fit_span(&p->map, p->rr, x, y, n, rgb);
	if (is_raster(p->d))
		return render_span(p->rr, x, y, n, rgb);
	if (x >= p->page.width || y >= p->page.height)
		return 0;
	if (x + n > p->page.width)
		n = p->page.width - x;
	if (p->d->ops->put_span)
		return p->d->ops->put_span(p->d, (unsigned)x, (unsigned)y, (unsigned)n, rgb);
	return rect_path(p, x * 1000, y * 1000, (x + n) * 1000, (y + 1) * 1000, rgb);
}

static int do_row(play_t *p, const meta_cmd_t *c)
{
	int64_t y = (int64_t)p->img_y + p->img_h - 1 - p->img_row++;
	if (p->mapped)
		return p->img ? dev_fit_image_row(p->img, p->rr, y, c->runs, c->nruns) : 0;
	if (is_raster(p->d))
		return render_row(p->rr, p->img_x, y, c->runs, c->nruns);
	if (p->d->ops->put_image_row)
		return dev_vec_row(p->d, &p->vec, p->img_x, y, c->runs, c->nruns);
	int64_t x = p->img_x;
	for (size_t k = 0; k < c->nruns; k++) {
		int rc = do_span(p, x, y, c->runs[k].count, c->runs[k].rgb);
		if (rc)
			return rc;
		x += c->runs[k].count;
	}
	return 0;
}

static int path_elem(play_t *p, const meta_cmd_t *c)
{
	if (p->nelems == p->cap_elems) {
		size_t n = p->cap_elems ? p->cap_elems * 2 : 64;
		dev_elem_t *e = realloc(p->elems, n * sizeof *e);
		if (!e)
			return nomem(p);
		p->elems = e;
		p->cap_elems = n;
	}
	dev_elem_t *e = &p->elems[p->nelems++];
	e->op = c->op;
	memcpy(e->f, c->f, sizeof e->f);
	int rc = 0;
	switch (c->op) {
	case META_MOVE: rc = scan_path_move(&p->path, c->f[0], c->f[1]); break;
	case META_DRAW:
		if (!scan_path_has_current(&p->path))
			return dev_fail(p->d, META_ESTATE, "draw without a current point");
		rc = scan_path_draw(&p->path, c->f[0], c->f[1]);
		break;
	case META_ARC:
		rc = scan_path_arc_res(&p->path, c->f[0], c->f[1], c->f[2], c->f[3], c->f[4],
			p->mapped ? dev_fit_chord_radius(&p->map, c->f[2]) : c->f[2]);
		break;
	case META_CIRCLE:
		rc = scan_path_circle_res(&p->path, c->f[0], c->f[1], c->f[2],
			p->mapped ? dev_fit_chord_radius(&p->map, c->f[2]) : c->f[2]);
		break;
	case META_CLOSE: rc = scan_path_close(&p->path); break;
	default: break;
	}
	if (rc)
		return nomem(p);
	if (p->path.npts > DEV_MAX_FLAT_POINTS)
		return dev_fail(p->d, META_ELIMIT, "path flattens to more than %d points (arcs or circles of "
			"huge radius); this driver refuses it", DEV_MAX_FLAT_POINTS);
	return 0;
}

static int paint_path(play_t *p, int kind, int text)
{
	dev_device_t *d = p->d;
	int rc = 0;
	if (p->path.npts == 0)
		return 0;
	if (is_raster(d)) {
		scan_style_t st;
		style_of(p, &st, text);
		scan_path_t *path = &p->path;
		if (p->mapped && kind != META_FILL && st.ndash) {
			/* dashes are measured along the model path: dash there, then map the pieces */
			scan_path_reset(&p->pieces);
			if (scan_dash_path(&p->path, st.dash, st.ndash, &p->pieces))
				return nomem(p);
			path = &p->pieces;
			st.dash = NULL;
			st.ndash = 0;
		}
		if (p->mapped && kind != META_FILL && p->map.sx != p->map.sy && st.width > 1000) {
			/* wide lines on non-square pixels: pieces built where the model is isotropic */
			if (!p->sctx && !(p->sctx = scan_ctx_new()))
				return nomem(p);
			scan_style_t ms = st;
			ms.width = p->st.width;   /* the model width: the pieces are scaled by sy */
			rc = dev_fit_stroke_aniso(&p->map, p->rr, p->sctx, path, &ms, p->st.colour, &p->iso, &p->outline);
			return rc ? render_fail(p, rc) : 0;
		}
		if (p->mapped)
			dev_fit_path(&p->map, path);
		rc = kind == META_FILL ? render_fill(p->rr, path, p->st.rule, p->st.colour)
			: render_stroke(p->rr, path, &st, p->st.colour);
		return rc ? render_fail(p, rc) : 0;
	}
	/* text has no raw elements of its own: NULL makes them from its strokes */
	const dev_elem_t *el = text ? NULL : p->elems;
	if (kind == META_FILL)
		return dev_vec_fill(d, &p->vec, &p->path, el, p->nelems, &p->st);
	if (text) {
		dev_state_t s = p->st;
		s.cap = META_CAP_ROUND;
		s.join = META_JOIN_ROUND;
		s.ndash = 0;
		return dev_vec_stroke(d, &p->vec, &p->path, NULL, 0, &s);
	}
	return dev_vec_stroke(d, &p->vec, &p->path, el, p->nelems, &p->st);
}

static int do_text(play_t *p, const meta_cmd_t *c)
{
	if (!is_raster(p->d) && (p->d->ops->caps & DEV_CAP_TEXT) && p->d->ops->text) {
		dev_text_t t = { c->f[0], c->f[1], c->f[2], c->f[3], c->str, c->len };
		return p->d->ops->text(p->d, &t, &p->st);
	}
	scan_path_reset(&p->path);
	p->nelems = 0;
	if (scan_text_path(&p->path, c->str, c->len, c->f[0], c->f[1], c->f[2], c->f[3]))
		return nomem(p);
	return paint_path(p, META_STROKE, 1);
}

static int begin_page(play_t *p, const meta_cmd_t *c)
{
	dev_device_t *d = p->d;
	memset(&p->page, 0, sizeof p->page);
	p->page.width = c->u[0];
	p->page.height = c->u[1];
	p->page.index = d->pages;
	p->page.model_width = p->page.width;
	p->page.model_height = p->page.height;
	default_state(&p->st);
	p->in_page = 1;
	d->page = &p->page;
	p->mapped = 0;
	if (is_raster(d)) {
		char err[256];
		/* anti-aliased: render k x k samples per device pixel, then average them */
		unsigned k = d->antialias > 1 ? d->antialias : 1;
		unsigned dw = d->raster_width && d->raster_height ? d->raster_width : p->page.width;
		unsigned dh = d->raster_width && d->raster_height ? d->raster_height : p->page.height;
		if (k > DEV_AA_MAX || (uint64_t)dw * k > 1u << 20 || (uint64_t)dh * k > 1u << 20)
			return dev_fail(d, DEV_EUSAGE, "%s: anti-aliasing factor %u too large for %ux%u (at most %d)",
				d->ops->name, k, dw, dh, DEV_AA_MAX);
		if (dev_fit_map(&p->map, p->page.width, p->page.height, k > 1 ? dw * k : d->raster_width,
				k > 1 ? dh * k : d->raster_height, d->pixel_aspect, d->fit))
			return dev_fail(d, DEV_EUSAGE, "%s: bad device raster (fit %d, pixel aspect %g)",
				d->ops->name, d->fit, d->pixel_aspect);
		p->mapped = !p->map.identity;
		p->page.width = k > 1 ? dw : p->map.width;
		p->page.height = k > 1 ? dh : p->map.height;
		render_aa_free(p->aa);
		p->aa = NULL;
		if (k > 1 && !(p->aa = render_aa_new(k, dw, dh)))
			return nomem(p);
		p->rr = render_new(p->map.width, p->map.height, d->band_rows, d->mem_budget, err, sizeof err);
		if (!p->rr)
			return dev_fail(d, META_ENOMEM, "%s", err);
		d->bands = render_bands(p->rr);
	}
	return 0;
}

/* begin_page of the device is deferred to the first statement after `page` so that `size`
 * is known to it. */
static int device_page(play_t *p)
{
	if (p->in_page != 1)
		return 0;
	p->in_page = 2;
	if (p->d->on_page) {
		int rc = p->d->on_page(p->d, &p->page, 0);
		if (rc)
			return rc;
	}
	return p->d->ops->begin_page ? p->d->ops->begin_page(p->d, &p->page) : 0;
}

static int end_page(play_t *p)
{
	dev_device_t *d = p->d;
	int rc = device_page(p);
	dev_fit_image_free(p->img);
	p->img = NULL;
	if (!rc && p->mapped && (rc = dev_fit_bars(&p->map, p->rr, d->letterbox)) != 0)
		render_fail(p, rc);
	if (!rc && is_raster(d)) {
		rc = render_finish(p->rr, emit_band, p);
		if (rc && !d->err[0])
			render_fail(p, rc);
		render_free(p->rr);
		p->rr = NULL;
	}
	if (!rc && d->ops->end_page)
		rc = d->ops->end_page(d, &p->page);
	if (!rc && d->on_page)
		rc = d->on_page(d, &p->page, 1);
	p->in_page = 0;
	d->page = NULL;
	d->pages++;
	return rc;
}

static int statement(play_t *p, const meta_cmd_t *c)
{
	dev_state_t *s = &p->st;
	if (c->op == META_PAGE)
		return begin_page(p, c);
	if (c->op == META_SIZE) {
		p->page.has_size = 1;
		p->page.width_mm = c->f[0];
		p->page.height_mm = c->f[1];
		return 0;
	}
	if (c->op == META_COMMENT)
		return p->d->ops->comment ? p->d->ops->comment(p->d, c->str, c->len) : 0;
	int rc = device_page(p);
	if (rc)
		return rc;
	switch (c->op) {
	case META_CLEAR:
		if (is_raster(p->d))
			return render_clear(p->rr, c->rgb) ? nomem(p) : 0;
		if (p->d->ops->clear)
			return p->d->ops->clear(p->d, &p->page, c->rgb);
		return rect_path(p, 0, 0, (int64_t)p->page.width * 1000, (int64_t)p->page.height * 1000, c->rgb);
	case META_END_PAGE: return end_page(p);
	case META_COLOUR: s->colour = c->rgb; return 0;
	case META_WIDTH:
		s->width = c->f[0];
		s->line_width = c->f[0] < 1000 ? 1000 : c->f[0];
		return 0;
	case META_DASH:
		s->ndash = 0;
		for (int rep = 0; rep < (c->nlist % 2 ? 2 : 1); rep++)
			for (size_t k = 0; k < c->nlist; k++)
				s->dash[s->ndash++] = c->list[k];
		if (scan_dash_period(s->dash, s->ndash) < SCAN_DASH_MIN_PERIOD)
			s->ndash = 0;   /* finer than a pixel: solid (§5.3), for every device */
		return 0;
	case META_CAP: s->cap = c->k; return 0;
	case META_JOIN: s->join = c->k; return 0;
	case META_FILL_RULE: s->rule = c->k; return 0;
	case META_MITER_LIMIT: s->miter_limit = c->f[0]; return 0;
	case META_STROKE:
	case META_FILL:
		p->path_kind = c->op;
		scan_path_reset(&p->path);
		p->nelems = 0;
		return 0;
	case META_MOVE: case META_DRAW: case META_ARC: case META_CIRCLE: case META_CLOSE:
		return path_elem(p, c);
	case META_END:
		rc = paint_path(p, p->path_kind, 0);
		p->path_kind = 0;
		return rc;
	case META_TEXT: return do_text(p, c);
	case META_SPAN: return do_span(p, c->u[0], c->u[1], c->u[2], c->rgb);
	case META_IMAGE:
		p->img_x = c->u[0];
		p->img_y = c->u[1];
		p->img_h = c->u[3];
		p->img_row = 0;
		if (p->mapped) {
			dev_fit_image_free(p->img);
			if (!(p->img = dev_fit_image_new(&p->map, c->u[0], c->u[1], c->u[2], c->u[3])))
				return nomem(p);
		}
		return 0;
	case META_ROW: return do_row(p, c);
	default: return 0;
	}
}

/* Take the framework's own -O keys (raster devices: antialias=K) out of d->options into the
 * device's fields; the rest is copied into buf for the device. Returns 1 when buf holds the
 * options to use, 0 when d->options is left as it is, or DEV_EUSAGE. */
static int framework_options(dev_device_t *d, char *buf, size_t n)
{
	size_t used = 0;
	if (!d->options || !is_raster(d))
		return 0;   /* nothing taken: d->options stays as it is */
	buf[0] = 0;
	for (const char *q = d->options; *q;) {
		const char *end = strchr(q, ',');
		size_t len = end ? (size_t)(end - q) : strlen(q);
		if (len > 10 && !strncmp(q, "antialias=", 10)) {
			char v[8] = "";
			char *e;
			if (len - 10 < sizeof v)
				memcpy(v, q + 10, len - 10);
			unsigned long k = strtoul(v, &e, 10);
			if (!v[0] || *e || v[0] < '0' || v[0] > '9' || k > DEV_AA_MAX)
				return dev_fail(d, DEV_EUSAGE, "antialias must be 0 (exact), or 2 to %d samples a side, not '%.*s'",
					DEV_AA_MAX, (int)(len - 10), q + 10);
			d->antialias = (unsigned)k;
		} else if (used + len + 2 > n) {
			return dev_fail(d, DEV_EUSAGE, "device options longer than %zu bytes", n - 2);
		} else {
			if (used)
				buf[used++] = ',';
			memcpy(buf + used, q, len);
			used += len;
			buf[used] = 0;
		}
		q += len + (end != NULL);
	}
	return 1;
}

int dev_play(meta_reader_t *r, dev_device_t *d)
{
	play_t p;
	memset(&p, 0, sizeof p);
	p.rd = r;
	p.d = d;
	d->err[0] = 0;
	d->reader_error = 0;
	const char *given = d->options;
	char rest[1024];
	int rc = framework_options(d, rest, sizeof rest);
	if (rc == 1)
		d->options = rest;
	if (rc >= 0)
		rc = dev_check_options(d);
	if (rc == 0 && d->ops->open)
		rc = d->ops->open(d);
	meta_cmd_t c;
	while (rc == 0) {
		int k = meta_read(r, &c);
		if (k < 0) {
			rc = dev_fail(d, k, "%s", meta_reader_error(r));
			d->reader_error = 1;
			break;
		}
		if (k == 0)
			break;
		rc = statement(&p, &c);
		if (rc == META_ESYNTAX || rc == META_ELIMIT || rc == META_ESTATE || rc == META_EVERSION) {
			char msg[sizeof d->err];
			snprintf(msg, sizeof msg, "%s", d->err[0] ? d->err : "device error");
			dev_fail(d, rc, "%s %llu: %s", meta_reader_is_binary(r) ? "byte" : "line",
				(unsigned long long)meta_reader_position(r), msg);
		} else if (rc && !d->err[0]) {
			dev_fail(d, rc, "device error");
		}
	}
	if (rc == 0 && p.in_page)
		rc = dev_fail(d, META_ESTATE, "input ended inside a page");
	if (d->ops->close) {
		int c2 = d->ops->close(d);
		if (rc == 0)
			rc = c2;
	}
	render_free(p.rr);
	dev_fit_image_free(p.img);
	scan_path_free(&p.path);
	scan_path_free(&p.pieces);
	dev_vec_free(&p.vec);
	render_aa_free(p.aa);
	scan_ctx_free(p.sctx);
	scan_path_free(&p.iso);
	scan_path_free(&p.outline);
	d->options = given;
	d->page = NULL;
	free(p.elems);
	return rc;
}
