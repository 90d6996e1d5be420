/* vecsupply.c: vector devices get what they cannot draw built from §5.3's pieces and §5.1's rule. */
#include <stdlib.h>
#include <string.h>
#include "device/vecsupply.h"

static unsigned caps_of(const dev_device_t *d)
{
	unsigned c = dev_caps(d);
	return c & DEV_CAP_ONLY ? c : c | DEV_CAP_FILL | DEV_CAP_DASH | DEV_CAP_WIDTH;
}

/* Raw elements for a path the framework made (dash pieces, outlines, text, rectangles), so that
 * a DEV_CAP_ARCS device reading elems draws it too (no other device reads them: call() makes them
 * for those devices only, and hands the others the meta file's own elements or none). */
static int synth(dev_vec_t *v, const scan_path_t *p, size_t *n)
{
	size_t need = p->npts + p->nsubs;
	if (need > v->cap_elems) {
		dev_elem_t *e = realloc(v->elems, need * sizeof *e);
		if (!e)
			return META_ENOMEM;
		v->elems = e;
		v->cap_elems = need;
	}
	size_t k = 0;
	for (size_t s = 0; s < p->nsubs; s++) {
		const scan_subpath_t *sub = &p->subs[s];
		for (size_t i = 0; i < sub->n; i++) {
			dev_elem_t *e = &v->elems[k++];
			memset(e, 0, sizeof *e);
			e->op = i ? META_DRAW : META_MOVE;
			e->f[0] = p->pts[sub->start + i].x;
			e->f[1] = p->pts[sub->start + i].y;
		}
		if (sub->closed) {
			memset(&v->elems[k], 0, sizeof v->elems[k]);
			v->elems[k++].op = META_CLOSE;
		}
	}
	*n = k;
	return 0;
}

static int call(dev_device_t *d, dev_vec_t *v, int (*op)(dev_device_t *, const dev_path_t *, const dev_state_t *),
		const scan_path_t *path, const dev_elem_t *elems, size_t nelems, const dev_state_t *st)
{
	if (!op)
		return 0;
	if (!elems)
		nelems = 0;
	if (!elems && (dev_caps(d) & DEV_CAP_ARCS)) {   /* only such devices read elems */
		int rc = synth(v, path, &nelems);
		if (rc)
			return dev_fail(d, rc, "out of memory");
		elems = v->elems;
	}
	dev_path_t dp = { path, elems, nelems };
	return op(d, &dp, st);
}

int dev_vec_fill(dev_device_t *d, dev_vec_t *v, const scan_path_t *path, const dev_elem_t *elems,
		size_t nelems, const dev_state_t *st)
{
	if (caps_of(d) & DEV_CAP_FILL)
		return call(d, v, d->ops->fill_path, path, elems, nelems, st);
	if (d->ops->hatch)
		return call(d, v, d->ops->hatch, path, elems, nelems, st);
	/* the outline, each subpath closed, and hatch lines one line width apart through pixel
	 * centres, drawn with the device's own line (no dash, round caps and joins) */
	scan_path_t *h = &v->hatch;
	scan_path_reset(h);
	for (size_t s = 0; s < path->nsubs; s++) {
		const scan_subpath_t *sub = &path->subs[s];
		for (size_t i = 0; i < sub->n; i++) {
			const scan_pt_t *q = &path->pts[sub->start + i];
			if ((i ? scan_path_draw(h, q->x, q->y) : scan_path_move(h, q->x, q->y)))
				return dev_fail(d, META_ENOMEM, "out of memory");
		}
		scan_path_close(h);
	}
	int64_t step = (st->line_width + 500) / 1000 * 1000;
	if (scan_hatch(path, st->rule, 500, step < 1000 ? 1000 : step, h))
		return dev_fail(d, META_ENOMEM, "out of memory");
	dev_state_t s = *st;
	s.ndash = 0;
	s.cap = META_CAP_ROUND;
	s.join = META_JOIN_ROUND;
	return call(d, v, d->ops->stroke_path, h, NULL, 0, &s);
}

int dev_vec_stroke(dev_device_t *d, dev_vec_t *v, const scan_path_t *path, const dev_elem_t *elems,
		size_t nelems, const dev_state_t *st)
{
	unsigned caps = caps_of(d);
	dev_state_t s = *st;
	if (s.ndash && !(caps & DEV_CAP_DASH)) {
		scan_path_reset(&v->dashed);
		/* pieces only where the page can show them (with the stroke's reach: half the width,
		 * times the miter limit, and a margin), as the raster path makes them: a dash pattern
		 * on a line that runs far off the page costs what the page shows, not its length */
		double lim = (double)s.miter_limit / 1000.0;
		double reach = (double)(s.line_width < 1000 ? 1000 : s.line_width) / 2.0 * (lim > 1.5 ? lim : 1.5) + 2000.0;
		int64_t ext = reach > 1e15 ? (int64_t)1e15 : (int64_t)reach;
		int64_t pw = d->page ? (int64_t)d->page->width * 1000 : INT64_C(32768000);
		int64_t ph = d->page ? (int64_t)d->page->height * 1000 : INT64_C(32768000);
		if (scan_dash_path_box(path, s.dash, s.ndash, -ext, -ext, pw + ext, ph + ext, &v->dashed))
			return dev_fail(d, META_ENOMEM, "out of memory");
		path = &v->dashed;
		elems = NULL;
		s.ndash = 0;
	}
	if (!(caps & DEV_CAP_WIDTH) && s.line_width > 1000) {
		if (!v->ctx && !(v->ctx = scan_ctx_new()))
			return dev_fail(d, META_ENOMEM, "out of memory");
		scan_style_t ss = { s.width, s.cap, s.join, s.miter_limit, NULL, 0 };
		unsigned w = d->page ? d->page->width : 32768, h = d->page ? d->page->height : 32768;
		scan_path_reset(&v->outline);
		if (scan_stroke_pieces(v->ctx, path, &ss, (int)w, (int)h, &v->outline))
			return dev_fail(d, META_ENOMEM, "out of memory");
		if (v->outline.npts == 0)
			return 0;
		s.rule = META_RULE_NON_ZERO;
		s.width = 0;
		s.line_width = 1000;
		return dev_vec_fill(d, v, &v->outline, NULL, 0, &s);
	}
	return call(d, v, d->ops->stroke_path, path, elems, nelems, &s);
}

int dev_vec_row(dev_device_t *d, dev_vec_t *v, int64_t x, int64_t y, const meta_run_t *runs, size_t nruns)
{
	unsigned w = d->page->width;
	if (y < 0 || y >= d->page->height || x >= w)
		return 0;
	if (nruns > v->cap_runs) {
		meta_run_t *r = realloc(v->runs, nruns * sizeof *r);
		if (!r)
			return dev_fail(d, META_ENOMEM, "out of memory");
		v->runs = r;
		v->cap_runs = nruns;
	}
	size_t n = 0;
	int64_t at = x;
	for (size_t k = 0; k < nruns && at < w; k++) {
		int64_t e = at + runs[k].count > w ? w : at + runs[k].count;
		v->runs[n] = runs[k];
		v->runs[n++].count = (uint32_t)(e - at);
		at += runs[k].count;
	}
	return n ? d->ops->put_image_row(d, (unsigned)x, (unsigned)y, v->runs, n) : 0;
}

void dev_vec_free(dev_vec_t *v)
{
	scan_ctx_free(v->ctx);
	scan_path_free(&v->dashed);
	scan_path_free(&v->outline);
	scan_path_free(&v->hatch);
	free(v->elems);
	free(v->runs);
	memset(v, 0, sizeof *v);
}
