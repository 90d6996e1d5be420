/* dev-pdf.c: the PDF 1.4 device: Flate content streams, image XObjects, exact xref offsets. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "psdev.h"

/* A growable list of numbers (object numbers, offsets). */
typedef struct {
	uint64_t *v;
	size_t n, cap;
} list_t;

typedef struct {
	psd_t p;
	int known;                   /* 0 at page start: everything must be set */
	meta_rgb_t stroke_rgb, fill_rgb;
	int have_stroke, have_fill;
	int64_t width, miter;
	int cap, join;
	int64_t dash[2 * META_MAX_DASH];
	size_t ndash;
	list_t offsets;              /* offsets[k]: object k + 1 */
	list_t kids;                 /* page objects */
	list_t contents;             /* this page's content streams */
	list_t images;               /* this page's image XObjects */
	long long org_x, org_y;      /* grid point the path's coordinates are relative to */
	unsigned stream_obj;         /* the open content stream (0: none) */
	uint64_t stream_start;
} pdf_t;

static int add(psd_t *p, list_t *l, uint64_t v)
{
	if (l->n == l->cap) {
		size_t n = l->cap ? l->cap * 2 : 16;
		uint64_t *q = realloc(l->v, n * sizeof *q);
		if (!q)
			return dev_fail(p->dev, META_ENOMEM, "out of memory");
		l->v = q;
		l->cap = n;
	}
	l->v[l->n++] = v;
	return 0;
}

/* Reserve the next object number (its offset is set when it is written). */
static unsigned new_obj(pdf_t *s)
{
	if (add(&s->p, &s->offsets, 0))
		return 0;
	return (unsigned)s->offsets.n;
}

static void begin_obj(pdf_t *s, unsigned n)
{
	s->offsets.v[n - 1] = s->p.out.pos;
	pse_printf(&s->p.out, "%u 0 obj\n", n);
}

static int failed(pdf_t *s)
{
	if (s->p.out.err)
		return psd_out_fail(&s->p);
	return 0;
}

/* ---- tokens (psdev.c's writer: one line per path, never wrapped inside one) ---- */

static void tok(pdf_t *s, const char *t)
{
	psd_tok(&s->p, t);
}

static void tok_int(pdf_t *s, long long v)
{
	psd_int(&s->p, v);
}

static void newline(pdf_t *s)
{
	psd_newline(&s->p);
}

/* A colour component v/255 with three decimals, shortest: 0, 1, .502 */
static void tok_unit(pdf_t *s, unsigned v)
{
	char b[16];
	psd_unit(v, b, sizeof b);
	tok(s, b);
}

static void colour(pdf_t *s, meta_rgb_t c, int fill)
{
	if (fill ? s->have_fill && s->fill_rgb == c : s->have_stroke && s->stroke_rgb == c)
		return;
	if (s->p.grey) {
		tok_unit(s, psd_luma(c));
		tok(s, fill ? "g" : "G");
	} else {
		tok_unit(s, c >> 16 & 255);
		tok_unit(s, c >> 8 & 255);
		tok_unit(s, c & 255);
		tok(s, fill ? "rg" : "RG");
	}
	if (fill)
		s->fill_rgb = c, s->have_fill = 1;
	else
		s->stroke_rgb = c, s->have_stroke = 1;
}

static void line_state(pdf_t *s, const dev_state_t *st)
{
	int64_t w = st->width > 1000 ? st->width : 1000;
	if (!s->known || s->width != w) {
		tok_int(s, psd_grid(w));
		tok(s, "w");
	}
	if (!s->known || s->cap != st->cap) {
		tok_int(s, st->cap);
		tok(s, "J");
	}
	if (!s->known || s->join != st->join) {
		tok_int(s, st->join);
		tok(s, "j");
	}
	if (!s->known || s->miter != st->miter_limit) {
		psd_sep(&s->p);
		pse_fix(&s->p.out, st->miter_limit);
		s->p.col += 6;
		tok(s, "M");
	}
	if (!s->known || s->ndash != st->ndash || memcmp(s->dash, st->dash, st->ndash * sizeof st->dash[0])) {
		tok(s, "[");
		for (size_t k = 0; k < st->ndash; k++) {
			psd_sep(&s->p);
			pse_real(&s->p.out, (double)st->dash[k] * PSD_GRID / 1000, 2);
			s->p.col += 6;
		}
		tok(s, "] 0 d");
	}
	s->width = w;
	s->cap = st->cap;
	s->join = st->join;
	s->miter = st->miter_limit;
	s->ndash = st->ndash;
	memcpy(s->dash, st->dash, st->ndash * sizeof st->dash[0]);
	s->known = 1;
}

/* ---- content streams ---- */

static int open_stream(pdf_t *s)
{
	unsigned n = new_obj(s);
	if (!n || add(&s->p, &s->contents, n) || !new_obj(s))
		return META_ENOMEM;
	begin_obj(s, n);
	pse_printf(&s->p.out, "<< /Length %u 0 R /Filter /FlateDecode >>\nstream\n", n + 1);
	s->stream_obj = n;
	s->stream_start = s->p.out.pos;
	s->p.col = 0;
	return pse_deflate_begin(&s->p.out, 0, PSE_TEXT);
}

static int close_stream(pdf_t *s)
{
	if (!s->stream_obj)
		return 0;
	newline(s);
	pse_deflate_end(&s->p.out, NULL);
	uint64_t len = s->p.out.pos - s->stream_start;
	pse_puts(&s->p.out, "\nendstream\nendobj\n");
	begin_obj(s, s->stream_obj + 1);
	pse_printf(&s->p.out, "%llu\nendobj\n", (unsigned long long)len);
	s->stream_obj = 0;
	return failed(s);
}

/* ---- paths ---- */

static void point(pdf_t *s, double x, double y, const char *op)
{
	tok_int(s, llround(x * PSD_GRID / 1000) - s->org_x);
	tok_int(s, llround(y * PSD_GRID / 1000) - s->org_y);
	if (op)
		tok(s, op);
}

/* An arc as cubic Bezier pieces of at most 90 degrees; joins or starts at its first point. */
static void arc(pdf_t *s, const dev_elem_t *e, int cur, int circle)
{
	double cx = e->f[0], cy = e->f[1], r = e->f[2];
	double a0 = circle ? 0 : e->f[3] / 180000.0 * M_PI;
	double sw = circle ? 2 * M_PI : e->f[4] / 180000.0 * M_PI;
	int n = (int)ceil(fabs(sw) / (M_PI / 2) - 1e-9);
	if (n < 1)
		n = 1;
	point(s, cx + r * cos(a0), cy + r * sin(a0), cur ? "l" : "m");
	double t = sw / n, k = 4.0 / 3.0 * tan(t / 4);
	for (int i = 0; i < n; i++) {
		double b0 = a0 + t * i, b1 = b0 + t;
		double x0 = cos(b0), y0 = sin(b0), x1 = cos(b1), y1 = sin(b1);
		point(s, cx + r * (x0 - k * y0), cy + r * (y0 + k * x0), NULL);
		point(s, cx + r * (x1 + k * y1), cy + r * (y1 - k * x1), NULL);
		point(s, cx + r * x1, cy + r * y1, "c");
	}
	if (circle)
		tok(s, "h");
}

/* The path's origin: its lower left grid point (x0, y0), moved down to the phase that most of its
 * coordinates share modulo ORG_MOD when there is one (a contour on a 2-pixel lattice, shapes on
 * whole pixels), so that those coordinates become round numbers (contours: 7% smaller). */
#define ORG_MOD 20
static void origin(pdf_t *s, const scan_path_t *f, long long x0, long long y0)
{
	size_t hx[ORG_MOD] = { 0 }, hy[ORG_MOD] = { 0 }, n = 0;
	for (size_t k = 0; k < f->nsubs; k++) {
		const scan_pt_t *q = f->pts + f->subs[k].start;
		for (size_t i = 0; i < f->subs[k].n; i++, n++) {
			long long x = psd_grid(q[i].x) - x0, y = psd_grid(q[i].y) - y0;   /* >= 0 */
			hx[x % ORG_MOD]++;
			hy[y % ORG_MOD]++;
		}
	}
	int bx = 0, by = 0;
	for (int r = 1; r < ORG_MOD; r++) {
		if (hx[r] > hx[bx])
			bx = r;
		if (hy[r] > hy[by])
			by = r;
	}
	/* a phase that a quarter of the points share (at random: a twentieth) */
	s->org_x = x0 + (bx && 4 * hx[bx] >= n ? bx - ORG_MOD : 0);
	s->org_y = y0 + (by && 4 * hy[by] >= n ? by - ORG_MOD : 0);
}

/* The path, inside q ... Q with the origin moved to its lower left corner: PDF has no relative
 * operators, and small positive numbers compress better (workload a: 28% smaller). */
static void write_path(pdf_t *s, const dev_path_t *dp, int fill)
{
	int64_t x0, y0, x1, y1;
	s->org_x = s->org_y = 0;
	if (scan_path_bbox(dp->flat, &x0, &y0, &x1, &y1))
		origin(s, dp->flat, psd_grid(x0), psd_grid(y0));
	tok(s, "q 1 0 0 1");
	tok_int(s, s->org_x);
	tok_int(s, s->org_y);
	tok(s, "cm");
	if (!psd_native(dp)) {
		const scan_path_t *f = dp->flat;
		for (size_t k = 0; k < f->nsubs; k++) {
			const scan_pt_t *q = f->pts + f->subs[k].start;
			for (size_t i = 0; i < f->subs[k].n; i++)
				point(s, (double)q[i].x, (double)q[i].y, i ? "l" : "m");
			if (f->subs[k].closed && f->subs[k].n && !fill)
				tok(s, "h");
		}
		return;
	}
	int cur = 0;
	for (size_t k = 0; k < dp->nelems; k++) {
		const dev_elem_t *e = &dp->elems[k];
		switch (e->op) {
		case META_MOVE: point(s, e->f[0], e->f[1], "m"); cur = 1; break;
		case META_DRAW: point(s, e->f[0], e->f[1], "l"); break;
		case META_ARC: arc(s, e, cur, 0); cur = 1; break;
		case META_CIRCLE: arc(s, e, 0, 1); cur = 0; break;
		case META_CLOSE:
			/* f closes every subpath itself: h only where a draw or arc goes on from it */
			if (!fill || (k + 1 < dp->nelems && (dp->elems[k + 1].op == META_DRAW || dp->elems[k + 1].op == META_ARC)))
				tok(s, "h");
			break;
		default: break;
		}
	}
}

static int pdf_stroke(dev_device_t *d, const dev_path_t *dp, const dev_state_t *st)
{
	pdf_t *s = d->priv;
	int rc = psd_paint_begin(&s->p, dp, st, 1);
	if (rc)
		return rc;
	colour(s, st->colour, 0);
	line_state(s, st);
	write_path(s, dp, 0);
	tok(s, "S Q");
	newline(s);
	return failed(s);
}

static int pdf_fill(dev_device_t *d, const dev_path_t *dp, const dev_state_t *st)
{
	pdf_t *s = d->priv;
	int rc = psd_paint_begin(&s->p, dp, st, 0);
	if (rc)
		return rc;
	colour(s, st->colour, 1);
	write_path(s, dp, 1);
	tok(s, st->rule == META_RULE_EVEN_ODD ? "f* Q" : "f Q");
	newline(s);
	return failed(s);
}

/* ---- rasters ---- */

static int pdf_rect(psd_t *p, unsigned x, unsigned y, unsigned w, unsigned h, meta_rgb_t rgb)
{
	pdf_t *s = (pdf_t *)p;
	colour(s, rgb, 1);
	tok_int(s, (long long)x * PSD_GRID);
	tok_int(s, (long long)y * PSD_GRID);
	tok_int(s, (long long)w * PSD_GRID);
	tok_int(s, (long long)h * PSD_GRID);
	tok(s, "re f");
	newline(s);
	return failed(s);
}

static int pdf_image(psd_t *p, unsigned x, unsigned y, unsigned w, unsigned h, const uint8_t *rgb)
{
	pdf_t *s = (pdf_t *)p;
	psd_samples_t sm;
	uint8_t *rle = NULL, *z = NULL;
	size_t nrle = 0, nz = 0;
	int rc = psd_samples(p, x, y, w, h, rgb, &sm);
	if (rc)
		return rc;
	const uint8_t *data = sm.data, *best = sm.data;
	size_t n = sm.n, nbest = sm.n;
	if (!(rle = malloc(pse_rle_bound(n))) || pse_flate_encode(data, n, 6, &z, &nz)) {
		rc = dev_fail(p->dev, META_ENOMEM, "out of memory");
		goto done;
	}
	nrle = pse_rle_encode(data, n, rle);
	const char *filter = "";
	if (nrle < nbest)
		best = rle, nbest = nrle, filter = " /Filter /RunLengthDecode";
	if (nz < nbest)
		best = z, nbest = nz, filter = " /Filter /FlateDecode";
	if ((rc = close_stream(s)))
		goto done;
	unsigned obj = new_obj(s);
	if (!obj || add(p, &s->images, obj)) {
		rc = dev_fail(p->dev, META_ENOMEM, "out of memory");
		goto done;
	}
	begin_obj(s, obj);
	pse_printf(&p->out, "<< /Type /XObject /Subtype /Image /Width %u /Height %u /ColorSpace /Device%s\n"
		"/BitsPerComponent %d%s /Length %zu >>\nstream\n", sm.width, sm.height, sm.comps == 1 ? "Gray" : "RGB",
		sm.bpc, filter, nbest);
	pse_write(&p->out, best, nbest);
	pse_puts(&p->out, "\nendstream\nendobj\n");
	if ((rc = open_stream(s)))
		goto done;
	pse_printf(&p->out, "q %lld 0 0 %lld %lld %lld cm /I%zu Do Q\n", (long long)w * PSD_GRID,
		(long long)h * PSD_GRID, (long long)x * PSD_GRID, (long long)y * PSD_GRID, s->images.n);
	rc = failed(s);
done:
	free(sm.owned);
	free(rle);
	free(z);
	return rc;
}

/* ---- document ---- */

static int start_doc(pdf_t *s)
{
	s->offsets.n = s->kids.n = 0;
	pse_set_transport(&s->p.out, s->p.dev->out);
	pse_puts(&s->p.out, "%PDF-1.4\n%\xe2\xe3\xcf\xd3\n");
	/* 1: catalog, 2: page tree, both written at the end */
	if (!new_obj(s) || !new_obj(s))
		return META_ENOMEM;
	s->p.doc_open = 1;
	s->p.doc_pages = 0;
	return failed(s);
}

static int finish_doc(pdf_t *s)
{
	pse_out_t *o = &s->p.out;
	begin_obj(s, 2);
	pse_puts(o, "<< /Type /Pages /Kids [");
	for (size_t k = 0; k < s->kids.n; k++)
		pse_printf(o, "%s%llu 0 R", k ? " " : "", (unsigned long long)s->kids.v[k]);
	pse_printf(o, "] /Count %zu >>\nendobj\n", s->kids.n);
	begin_obj(s, 1);
	pse_puts(o, "<< /Type /Catalog /Pages 2 0 R >>\nendobj\n");
	unsigned info = new_obj(s);
	if (!info)
		return META_ENOMEM;
	begin_obj(s, info);
	pse_puts(o, "<< /Producer (locus-ps " LOCUS_VERSION ")");
	if (s->p.title[0]) {
		pse_puts(o, " /Title ");
		psd_string(o, s->p.title);
	}
	if (s->p.date) {
		char b[40];
		psd_date(s->p.epoch, 1, b, sizeof b);
		pse_printf(o, " /CreationDate (%s)", b);
	}
	pse_puts(o, " >>\nendobj\n");
	uint64_t xref = o->pos;
	pse_printf(o, "xref\n0 %zu\n0000000000 65535 f \n", s->offsets.n + 1);
	for (size_t k = 0; k < s->offsets.n; k++)
		pse_printf(o, "%010llu 00000 n \n", (unsigned long long)s->offsets.v[k]);
	pse_printf(o, "trailer\n<< /Size %zu /Root 1 0 R /Info %u 0 R >>\nstartxref\n%llu\n%%%%EOF\n",
		s->offsets.n + 1, info, (unsigned long long)xref);
	s->p.doc_open = 0;
	pse_flush(o);
	return failed(s);
}

static int pdf_open(dev_device_t *d)
{
	pdf_t *s = d->priv;
	int rc = psd_options(&s->p, d);
	if (rc)
		return rc;
	s->p.form = PSD_PDF;
	s->p.hooks.image = pdf_image;
	s->p.hooks.rect = pdf_rect;
	s->p.per_page = d->out == NULL;
	s->p.wrap = 0;   /* content streams: one line per path, which compresses better */
	pse_init(&s->p.out, d->out);
	return 0;
}

static int pdf_begin(dev_device_t *d, const dev_page_t *pg)
{
	pdf_t *s = d->priv;
	int rc;
	if (!d->out)
		return dev_fail(d, DEV_EDEVICE, "pdf: no output");
	if (!s->p.doc_open && (rc = start_doc(s)))
		return rc == META_ENOMEM ? dev_fail(d, rc, "out of memory") : rc;
	psd_page(&s->p, pg);
	s->p.doc_pages++;
	s->contents.n = s->images.n = 0;
	s->known = s->have_fill = s->have_stroke = 0;
	if (open_stream(s))
		return dev_fail(d, META_ENOMEM, "out of memory");
	pse_real(&s->p.out, s->p.sx / PSD_GRID, 8);
	pse_puts(&s->p.out, " 0 0 ");
	pse_real(&s->p.out, s->p.sy / PSD_GRID, 8);
	pse_puts(&s->p.out, " ");
	pse_real(&s->p.out, s->p.ox, 4);
	pse_puts(&s->p.out, " ");
	pse_real(&s->p.out, s->p.oy, 4);
	pse_printf(&s->p.out, " cm /G0 gs 0 0 %lld %lld re W n\n", (long long)pg->width * PSD_GRID,
		(long long)pg->height * PSD_GRID);
	return failed(s);
}

static int pdf_end(dev_device_t *d, const dev_page_t *pg)
{
	pdf_t *s = d->priv;
	pse_out_t *o = &s->p.out;
	(void)pg;
	int rc = psd_flush(&s->p);
	if (rc || (rc = close_stream(s)))
		return rc;
	unsigned page = new_obj(s);
	if (!page || add(&s->p, &s->kids, page))
		return dev_fail(d, META_ENOMEM, "out of memory");
	begin_obj(s, page);
	pse_puts(o, "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 ");
	pse_real(o, s->p.media_w, 4);
	pse_puts(o, " ");
	pse_real(o, s->p.media_h, 4);
	pse_puts(o, "]\n/Contents [");
	for (size_t k = 0; k < s->contents.n; k++)
		pse_printf(o, "%s%llu 0 R", k ? " " : "", (unsigned long long)s->contents.v[k]);
	pse_puts(o, "]\n/Resources << /ExtGState << /G0 << /SA false >> >>");
	if (s->images.n) {
		pse_puts(o, " /XObject <<");
		for (size_t k = 0; k < s->images.n; k++)
			pse_printf(o, " /I%zu %llu 0 R", k + 1, (unsigned long long)s->images.v[k]);
		pse_puts(o, " >>");
	}
	pse_puts(o, " >> >>\nendobj\n");
	if (s->p.per_page && (rc = finish_doc(s)))
		return rc;
	return failed(s);
}

static int pdf_close(dev_device_t *d)
{
	pdf_t *s = d->priv;
	int rc = 0;
	if (s->p.doc_open && !s->p.per_page && d->out && !s->stream_obj)
		rc = finish_doc(s);
	if (s->p.out.z)
		pse_deflate_end(&s->p.out, NULL);
	psd_release(&s->p);
	free(s->offsets.v);
	free(s->kids.v);
	free(s->contents.v);
	free(s->images.v);
	memset(&s->offsets, 0, sizeof s->offsets);
	memset(&s->kids, 0, sizeof s->kids);
	memset(&s->contents, 0, sizeof s->contents);
	memset(&s->images, 0, sizeof s->images);
	return rc;
}

const dev_ops_t dev_pdf_ops = {
	.name = "pdf", .description = "PDF 1.4, one page per meta page, Flate streams",
	.extension = ".pdf",
	.caps = DEV_CAP_VECTOR | DEV_CAP_ARCS | DEV_CAP_FILL | DEV_CAP_DASH | DEV_CAP_WIDTH,
	.priv_size = sizeof(pdf_t), .option_list = psd_pdf_options,
	.open = pdf_open, .begin_page = pdf_begin, .clear = psd_dev_clear, .stroke_path = pdf_stroke,
	.fill_path = pdf_fill, .put_span = psd_dev_span, .put_image_row = psd_dev_row, .end_page = pdf_end,
	.close = pdf_close,
};
