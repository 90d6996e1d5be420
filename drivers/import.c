/* import.c: `locus-meta import`: HP-GL through the HP-GL reader, plotutils metafiles, to meta. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hpgl_read.h"
#include "meta_import.h"
#include "plotmeta.h"
#include "transport.h"

/* hp2xx's default pen colours: 1 black, 2 red, 3 green, 4 blue, 5 cyan, 6 magenta, 7 yellow;
 * pen 0 (none selected) is drawn black as hp2xx does with pen 1; higher pens repeat 1..7. */
static meta_rgb_t pen_rgb(int pen)
{
	static const meta_rgb_t c[8] = { 0x000000, 0x000000, 0xff0000, 0x00ff00, 0x0000ff, 0x00ffff,
		0xff00ff, 0xffff00 };
	return pen <= 0 ? c[0] : c[(pen - 1) % 7 + 1];
}

#define CK(x) do { if ((rc = (x)) < 0) goto fail; } while (0)

int mimp_hpgl(const void *buf, size_t n, const char *name, double px_per_mm, meta_writer_t *w,
		char *err, size_t errlen)
{
	hpgl_doc_t d;
	if (hpgl_read_mem(buf, n, name, &d, err, errlen)) {
		hpgl_doc_free(&d);
		return -65;
	}
	/* the drawing's extent, plotter units */
	double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
	for (size_t k = 0; k < d.npts; k++) {
		x0 = fmin(x0, d.pts[k].x), x1 = fmax(x1, d.pts[k].x);
		y0 = fmin(y0, d.pts[k].y), y1 = fmax(y1, d.pts[k].y);
	}
	double ch = 0.27 * 400;   /* label capital height: SI's default 0.27 cm, plotter units */
	for (size_t k = 0; k < d.nlabels; k++) {
		const hpgl_rlabel_t *l = &d.labels[k];
		x0 = fmin(x0, l->x), x1 = fmax(x1, l->x + (double)l->len * ch * 0.75);
		y0 = fmin(y0, l->y - 2 * ch * (double)(memchr(l->text, '\n', l->len) != NULL));
		y0 = fmin(y0, l->y), y1 = fmax(y1, l->y + ch);
	}
	if (!(x0 <= x1)) {   /* nothing drawn: an empty A4 landscape sheet */
		x0 = y0 = 0;
		x1 = 297 * 40.0, y1 = 210 * 40.0;
	}
	double wu = x1 - x0, hu = y1 - y0, side = fmax(fmax(wu, hu), 40.0);
	double margin = 0.02 * side;
	wu += 2 * margin, hu += 2 * margin;
	x0 -= margin, y0 -= margin;
	double s = px_per_mm / 40.0;                          /* pixels per plotter unit */
	if (fmax(wu, hu) * s > 8000)
		s = 8000 / fmax(wu, hu);
	unsigned wpx = (unsigned)ceil(fmax(wu * s, 1)), hpx = (unsigned)ceil(fmax(hu * s, 1));
	int rc;
	CK(meta_page(w, wpx, hpx));
	CK(meta_page_size_mm(w, wpx / (s * 40), hpx / (s * 40)));
	CK(meta_clear(w, 0xffffff));
	CK(meta_cap(w, META_CAP_ROUND));
	CK(meta_join(w, META_JOIN_ROUND));
	CK(meta_width(w, fmax(0.3 * 40 * s, 1.0)));           /* a 0.3 mm pen */
	CK(meta_fill_rule(w, META_RULE_EVEN_ODD));
	int pen = -2;
	for (size_t k = 0; k < d.nstrokes; k++) {
		const hpgl_rstroke_t *st = &d.strokes[k];
		const hpgl_rpt_t *p = d.pts + st->start;
		if (st->pen != pen)
			CK(meta_colour(w, pen_rgb(pen = st->pen)));
		int fill = st->kind == HPGL_RS_FILL;
		CK(fill ? meta_fill(w) : meta_stroke(w));
		CK(meta_move(w, (p[0].x - x0) * s, (p[0].y - y0) * s));
		for (size_t i = 1; i < st->n; i++)
			CK(meta_draw(w, (p[i].x - x0) * s, (p[i].y - y0) * s));
		if (fill)
			CK(meta_close(w));
		CK(meta_end(w));
	}
	for (size_t k = 0; k < d.nlabels; k++) {
		const hpgl_rlabel_t *l = &d.labels[k];
		if (l->pen != pen)
			CK(meta_colour(w, pen_rgb(pen = l->pen)));
		/* LF starts a new line below (twice the character height), CR goes back to the
		 * label's start; other control bytes have no glyph and are left out */
		char *t = malloc(l->len + 1);
		if (!t) {
			rc = META_ENOMEM;
			goto fail;
		}
		double lx = l->x, ly = l->y;
		size_t i = 0;
		rc = 0;
		while (i <= l->len && rc >= 0) {
			size_t k = 0;
			while (i < l->len && l->text[i] != '\n' && l->text[i] != '\r') {
				if ((unsigned char)l->text[i] >= 32 && l->text[i] != 127)
					t[k++] = l->text[i];
				i++;
			}
			t[k] = 0;
			if (k)
				rc = meta_text(w, (lx - x0) * s, (ly - y0) * s, ch * s, 0, t);
			if (i < l->len && l->text[i] == '\n')
				ly -= 2 * ch;
			else if (i < l->len)
				lx = l->x;
			i++;
		}
		free(t);
		if (rc < 0)
			goto fail;
	}
	CK(meta_end_page(w));
	hpgl_doc_free(&d);
	return 0;
fail:
	snprintf(err, errlen, "%s", meta_writer_error(w));
	hpgl_doc_free(&d);
	return rc == META_ENOMEM ? -70 : rc == META_EIO ? -74 : -65;
}

static int out_write(void *user, const void *buf, size_t n)
{
	return io_write(user, buf, n);
}

int mimp_run(const char *in, const char *out)
{
	char err[700];
	io_transport_t *t = io_open_read(in, err, sizeof err);
	if (!t) {
		fprintf(stderr, "%s\n", err);
		return 66;
	}
	const char *name = strcmp(in, "-") ? in : "<stdin>";
	size_t cap = 1 << 16, n = 0;
	unsigned char *buf = malloc(cap);
	for (;;) {
		if (buf && n == cap) {
			unsigned char *q = realloc(buf, cap * 2);
			if (!q)
				free(buf);
			buf = q;
			cap *= 2;
		}
		if (!buf) {
			io_close(t, IO_ABORT);
			fprintf(stderr, "locus-meta: out of memory reading %s\n", name);
			return 70;
		}
		long k = io_read(t, buf + n, cap - n);
		if (k < 0) {
			fprintf(stderr, "%s\n", io_error(t));
			io_close(t, IO_ABORT);
			free(buf);
			return 74;
		}
		if (k == 0)
			break;
		n += (size_t)k;
	}
	io_close(t, IO_ABORT);
	io_transport_t *o = io_open_write(out ? out : "-", err, sizeof err);
	if (!o) {
		fprintf(stderr, "%s\n", err);
		free(buf);
		return 74;
	}
	meta_writer_t *w = meta_writer_new(out_write, o, META_ENC_TEXT);
	int rc = w ? 0 : -70;
	snprintf(err, sizeof err, "out of memory");
	if (w && plotmeta_is(buf, n))
		rc = plotmeta_import(buf, n, name, w, err, sizeof err);
	else if (w)
		rc = mimp_hpgl(buf, n, name, 4.0, w, err, sizeof err);
	free(buf);
	if (w) {
		int c = meta_writer_close(w);
		if (!rc && c < 0) {
			snprintf(err, sizeof err, "%s", io_failed(o) ? io_error(o) : "cannot finish the meta file");
			rc = -74;
		}
	}
	if (rc) {
		if (io_failed(o))
			snprintf(err, sizeof err, "%s", io_error(o));
		fprintf(stderr, "%s\n", err);
		io_close(o, IO_ABORT);   /* no partial output */
		return -rc;
	}
	if (io_close_err(o, IO_COMMIT, err, sizeof err)) {
		fprintf(stderr, "%s\n", err);
		return 74;
	}
	return 0;
}
