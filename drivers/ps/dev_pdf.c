/* dev_pdf.c: the PDF 1.4 device: Flate content streams, image XObjects, exact xref offsets. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "ps/pdf_int.h"

/* ---- paths ---- */

static int pdf_stroke(dev_device_t *d, const dev_path_t *dp, const dev_state_t *st)
{
	pdf_t *s = d->priv;
	int rc = psd_paint_begin(&s->p, dp, st, 1);
	if (rc || (rc = pdf_paint(s, dp, st, 0)))
		return rc;
	return pdf_failed(s);
}

static int pdf_fill(dev_device_t *d, const dev_path_t *dp, const dev_state_t *st)
{
	pdf_t *s = d->priv;
	int rc = psd_paint_begin(&s->p, dp, st, 0);
	if (rc || (rc = pdf_paint(s, dp, st, 1)))
		return rc;
	return pdf_failed(s);
}

/* ---- rasters ---- */

/* q and the page's matrix (one unit a grid step), which everything but images is drawn in. */
static void grid_matrix(pdf_t *s)
{
	dev_w_puts(&s->p.out, "q ");
	dev_w_real(&s->p.out, s->p.sx / PSD_GRID, 8);
	dev_w_puts(&s->p.out, " 0 0 ");
	dev_w_real(&s->p.out, s->p.sy / PSD_GRID, 8);
	dev_w_puts(&s->p.out, " ");
	dev_w_real(&s->p.out, s->p.ox, 4);
	dev_w_puts(&s->p.out, " ");
	dev_w_real(&s->p.out, s->p.oy, 4);
	dev_w_puts(&s->p.out, " cm\n");
}

static int pdf_rect(psd_t *p, unsigned x, unsigned y, unsigned w, unsigned h, meta_rgb_t rgb)
{
	pdf_t *s = (pdf_t *)p;
	pdf_end_group(s);   /* page coordinates */
	pdf_fill_colour(s, rgb);
	psd_int(p, (long long)x * PSD_GRID);
	psd_int(p, (long long)y * PSD_GRID);
	psd_int(p, (long long)w * PSD_GRID);
	psd_int(p, (long long)h * PSD_GRID);
	psd_tok(p, "re f");
	psd_newline(p);
	return pdf_failed(s);
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
	int rows = s->rows;
	pdf_end_group(s);
	psd_newline(p);
	dev_w_puts(&p->out, "Q\n");   /* the grid matrix: images are placed in points (below) */
	if ((rc = pdf_close_stream(s)))
		goto done;
	unsigned obj = pdf_new_obj(s);
	if (!obj || pdf_list_add(p, &s->images, obj)) {
		rc = dev_fail(p->dev, META_ENOMEM, "out of memory");
		goto done;
	}
	pdf_begin_obj(s, obj);
	dev_w_printf(&p->out, "<< /Type /XObject /Subtype /Image /Width %u /Height %u /ColorSpace /Device%s\n"
		"/BitsPerComponent %d%s /Length %zu >>\nstream\n", sm.width, sm.height, sm.comps == 1 ? "Gray" : "RGB",
		sm.bpc, filter, nbest);
	dev_w_write(&p->out, best, nbest);
	dev_w_puts(&p->out, "\nendstream\nendobj\n");
	if ((rc = pdf_open_stream(s, rows)))
		goto done;
	/* The image's matrix in points, not through the page's grid matrix: a reader that
	 * multiplies matrices in single precision (MuPDF) finds 0.075 x 160 a little off 12 and
	 * then resamples the image across pixel rows; 12 0 0 12 6 30 lands each sample on one
	 * pixel. */
	dev_w_puts(&p->out, "q ");
	dev_w_real(&p->out, w * p->sx, 6);
	dev_w_puts(&p->out, " 0 0 ");
	dev_w_real(&p->out, h * p->sy, 6);
	dev_w_puts(&p->out, " ");
	dev_w_real(&p->out, p->ox + x * p->sx, 6);
	dev_w_puts(&p->out, " ");
	dev_w_real(&p->out, p->oy + y * p->sy, 6);
	dev_w_printf(&p->out, " cm /I%zu Do Q\n", s->images.n);
	grid_matrix(s);
	pdf_reset_state(s);   /* the Q undid colours and line state */
	rc = pdf_failed(s);
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
	dev_w_set_transport(&s->p.out, s->p.dev->out);
	dev_w_puts(&s->p.out, "%PDF-1.4\n%\xe2\xe3\xcf\xd3\n");
	/* 1: catalog, 2: page tree, both written at the end */
	if (!pdf_new_obj(s) || !pdf_new_obj(s))
		return META_ENOMEM;
	s->p.doc_open = 1;
	s->p.doc_pages = 0;
	return pdf_failed(s);
}

static int finish_doc(pdf_t *s)
{
	dev_writer_t *o = &s->p.out;
	pdf_begin_obj(s, 2);
	dev_w_puts(o, "<< /Type /Pages /Kids [");
	for (size_t k = 0; k < s->kids.n; k++)
		dev_w_printf(o, "%s%llu 0 R", k ? " " : "", (unsigned long long)s->kids.v[k]);
	dev_w_printf(o, "] /Count %zu >>\nendobj\n", s->kids.n);
	pdf_begin_obj(s, 1);
	dev_w_puts(o, "<< /Type /Catalog /Pages 2 0 R >>\nendobj\n");
	unsigned info = pdf_new_obj(s);
	if (!info)
		return META_ENOMEM;
	pdf_begin_obj(s, info);
	dev_w_puts(o, "<< /Producer (locus-ps " LOCUS_VERSION ")");
	if (s->p.title[0]) {
		dev_w_puts(o, " /Title ");
		psd_string(o, s->p.title);
	}
	if (s->p.date) {
		char b[40];
		psd_date(s->p.epoch, 1, b, sizeof b);
		dev_w_printf(o, " /CreationDate (%s)", b);
	}
	dev_w_puts(o, " >>\nendobj\n");
	uint64_t xref = o->pos;
	dev_w_printf(o, "xref\n0 %zu\n0000000000 65535 f \n", s->offsets.n + 1);
	for (size_t k = 0; k < s->offsets.n; k++)
		dev_w_printf(o, "%010llu 00000 n \n", (unsigned long long)s->offsets.v[k]);
	dev_w_printf(o, "trailer\n<< /Size %zu /Root 1 0 R /Info %u 0 R >>\nstartxref\n%llu\n%%%%EOF\n",
		s->offsets.n + 1, info, (unsigned long long)xref);
	s->p.doc_open = 0;
	dev_w_flush(o);
	return pdf_failed(s);
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
	dev_w_init(&s->p.out, d->out);
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
	pdf_reset_state(s);
	if (pdf_open_stream(s, 0))
		return dev_fail(d, META_ENOMEM, "out of memory");
	/* the clip of the page in points, outside the grid matrix's q ... Q (images leave it) */
	dev_w_puts(&s->p.out, "/G0 gs ");
	dev_w_real(&s->p.out, s->p.ox, 4);
	dev_w_puts(&s->p.out, " ");
	dev_w_real(&s->p.out, s->p.oy, 4);
	dev_w_puts(&s->p.out, " ");
	dev_w_real(&s->p.out, pg->width * s->p.sx, 6);
	dev_w_puts(&s->p.out, " ");
	dev_w_real(&s->p.out, pg->height * s->p.sy, 6);
	dev_w_puts(&s->p.out, " re W n\n");
	grid_matrix(s);
	return pdf_failed(s);
}

static int pdf_end(dev_device_t *d, const dev_page_t *pg)
{
	pdf_t *s = d->priv;
	dev_writer_t *o = &s->p.out;
	(void)pg;
	int rc = psd_flush(&s->p);
	if (rc)
		return rc;
	pdf_end_group(s);
	psd_newline(&s->p);
	dev_w_puts(o, "Q\n");   /* the grid matrix */
	if ((rc = pdf_close_stream(s)))
		return rc;
	unsigned page = pdf_new_obj(s);
	if (!page || pdf_list_add(&s->p, &s->kids, page))
		return dev_fail(d, META_ENOMEM, "out of memory");
	pdf_begin_obj(s, page);
	dev_w_puts(o, "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 ");
	dev_w_real(o, s->p.media_w, 4);
	dev_w_puts(o, " ");
	dev_w_real(o, s->p.media_h, 4);
	dev_w_puts(o, "]\n/Contents [");
	for (size_t k = 0; k < s->contents.n; k++)
		dev_w_printf(o, "%s%llu 0 R", k ? " " : "", (unsigned long long)s->contents.v[k]);
	dev_w_puts(o, "]\n/Resources << /ExtGState << /G0 << /SA false >> >>");
	if (s->images.n) {
		dev_w_puts(o, " /XObject <<");
		for (size_t k = 0; k < s->images.n; k++)
			dev_w_printf(o, " /I%zu %llu 0 R", k + 1, (unsigned long long)s->images.v[k]);
		dev_w_puts(o, " >>");
	}
	dev_w_puts(o, " >> >>\nendobj\n");
	if (s->p.per_page && (rc = finish_doc(s)))
		return rc;
	return pdf_failed(s);
}

static int pdf_close(dev_device_t *d)
{
	pdf_t *s = d->priv;
	int rc = 0;
	if (s->p.doc_open && !s->p.per_page && d->out && !s->stream_obj)
		rc = finish_doc(s);
	pse_deflate_end(&s->p.out, NULL);   /* frees a stream left open (nothing if none) */
	psd_release(&s->p);
	free(s->offsets.v);
	free(s->kids.v);
	free(s->contents.v);
	free(s->images.v);
	free(s->pts);
	s->pts = NULL;
	s->npts = s->cappts = 0;
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
