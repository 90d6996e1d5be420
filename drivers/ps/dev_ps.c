/* dev_ps.c: the PostScript devices: EPS (one embeddable page) and printable multi-page PS. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "ps/ps_int.h"

/* Short procedures defined once; the page draws with these names only (K: prolog_section). */
static const char prolog_head[] =
	"/M /moveto load def /D /lineto load def /l /rlineto load def\n"
	"/L {{rlineto} repeat} bind def /Z /closepath load def\n"
	"/A /arc load def /N /arcn load def\n"
	"/C {3 copy 3 -1 roll add exch moveto 0 360 arc closepath} bind def\n"
	"/S /stroke load def /F /fill load def /E /eofill load def\n";
static const char prolog_tail[] =
	"/W /setlinewidth load def\n"
	"/J /setlinecap load def /j /setlinejoin load def /X /setmiterlimit load def\n"
	"/B {newpath 4 2 roll moveto 1 index 0 rlineto 0 exch rlineto neg 0 rlineto closepath fill} bind def\n";

static ps_t *st_of(dev_device_t *d)
{
	return d->priv;
}

static int ps_stroke(dev_device_t *d, const dev_path_t *dp, const dev_state_t *st)
{
	ps_t *s = st_of(d);
	int rc = psd_paint_begin(&s->p, dp, st, 1);
	if (rc)
		return rc;
	psp_colour(s, st->colour);
	psp_line(s, st);
	s->known = 1;
	if ((rc = psp_path(s, dp, 0)))
		return rc;
	psd_tok(&s->p, "S");
	psd_newline(&s->p);
	return s->p.out.err ? psd_out_fail(&s->p) : 0;
}

static int ps_fill(dev_device_t *d, const dev_path_t *dp, const dev_state_t *st)
{
	ps_t *s = st_of(d);
	int rc = psd_paint_begin(&s->p, dp, st, 0);
	if (rc)
		return rc;
	psp_colour(s, st->colour);
	if ((rc = psp_path(s, dp, 1)))
		return rc;
	psd_tok(&s->p, st->rule == META_RULE_EVEN_ODD ? "E" : "F");
	psd_newline(&s->p);
	return s->p.out.err ? psd_out_fail(&s->p) : 0;
}

/* ---- rasters ---- */

static int ps_rect(psd_t *p, unsigned x, unsigned y, unsigned w, unsigned h, meta_rgb_t rgb)
{
	ps_t *s = (ps_t *)p;
	psp_colour(s, rgb);
	psd_int(&s->p, (long long)x * PSD_GRID);
	psd_int(&s->p, (long long)y * PSD_GRID);
	psd_int(&s->p, (long long)w * PSD_GRID);
	psd_int(&s->p, (long long)h * PSD_GRID);
	psd_tok(&s->p, "B");
	psd_newline(&s->p);
	return 0;
}

static int ps_image(psd_t *p, unsigned x, unsigned y, unsigned w, unsigned h, const uint8_t *rgb)
{
	ps_t *s = (ps_t *)p;
	dev_writer_t *o = &p->out;
	psd_samples_t sm;
	uint8_t *rle = NULL, *z = NULL;
	size_t nrle = 0, nz = 0;
	int rc = psd_samples(p, x, y, w, h, rgb, &sm);
	if (rc)
		return rc;
	const uint8_t *data = sm.data;
	size_t n = sm.n;
	unsigned iw = sm.width, ih = sm.height;
	const char *space = sm.comps == 1 ? "Gray" : "RGB", *decode = sm.comps == 1 ? "0 1" : "0 1 0 1 0 1";
	/* the smallest encoding this level can read */
	enum { HEX, A85, RL, FL } pick = p->level == 1 ? HEX : A85;
	size_t best = p->level == 1 ? pse_hex_size(n) : pse_a85_size(data, n);
	if (p->level >= 2 && !s->packed) {
		if (!(rle = malloc(pse_rle_bound(n)))) {
			rc = dev_fail(p->dev, META_ENOMEM, "out of memory");
			goto done;
		}
		nrle = pse_rle_encode(data, n, rle);
		size_t a = pse_a85_size(rle, nrle);
		if (a < best)
			best = a, pick = RL;
	}
	if (p->level >= 3 && !s->packed) {
		if (pse_flate_encode(data, n, 6, &z, &nz)) {
			rc = dev_fail(p->dev, META_ENOMEM, "out of memory");
			goto done;
		}
		size_t a = pse_a85_size(z, nz);
		if (a < best)
			best = a, pick = FL;
	}
	psd_newline(&s->p);
	dev_w_printf(o, "gsave %lld %lld translate %lld %lld scale\n", (long long)x * PSD_GRID,
		(long long)y * PSD_GRID, (long long)w * PSD_GRID, (long long)h * PSD_GRID);
	if (s->packed) {
		/* inside the compressed body: the samples as they are, compressed harder */
		dev_w_printf(o, "/Device%s setcolorspace\n<< /ImageType 1 /Width %u /Height %u /BitsPerComponent %d\n"
			"/Decode [%s] /ImageMatrix [%u 0 0 -%u 0 %u] /DataSource currentfile >> image\n",
			space, iw, ih, sm.bpc, decode, iw, ih, ih);
		pse_deflate_level(o, 6);
		dev_w_write(o, data, n);
		pse_deflate_level(o, PSE_HUFFMAN);
		dev_w_puts(o, "\n");
	} else if (pick == HEX) {
		dev_w_printf(o, "/picstr %zu string def\n%u %u %d [%u 0 0 -%u 0 %u]\n"
			"{currentfile picstr readhexstring pop} %s\n", n / ih, iw, ih, sm.bpc, iw, ih, ih,
			sm.comps == 1 ? "image" : "CI");
		if (sm.comps == 3)
			s->colorimage = 1;
		pse_hex_write(o, data, n);
	} else {
		dev_w_printf(o, "/Device%s setcolorspace\n<< /ImageType 1 /Width %u /Height %u /BitsPerComponent %d\n"
			"/Decode [%s] /ImageMatrix [%u 0 0 -%u 0 %u]\n"
			"/DataSource currentfile /ASCII85Decode filter%s >> image\n",
			space, iw, ih, sm.bpc, decode, iw, ih, ih,
			pick == RL ? " /RunLengthDecode filter" : pick == FL ? " /FlateDecode filter" : "");
		if (pick == A85)
			pse_a85_write(o, data, n);
		else if (pick == RL)
			pse_a85_write(o, rle, nrle);
		else
			pse_a85_write(o, z, nz);
	}
	dev_w_puts(o, "grestore\n");
	s->known = 0;   /* setcolorspace reset the colour */
	if (o->err)
		rc = psd_out_fail(p);
done:
	free(sm.owned);
	free(rle);
	free(z);
	return rc;
}

/* ---- document structure (DSC 3.0) ---- */

/* The header comments up to %%EndComments; box NULL: (atend) (PostScript only). */
static void comments(ps_t *s, const double *box, int have)
{
	psd_t *p = &s->p;
	dev_writer_t *o = &p->out;
	int eps = p->form == PSD_EPS;
	dev_w_puts(o, eps ? "%!PS-Adobe-3.0 EPSF-3.0\n" : "%!PS-Adobe-3.0\n");
	if (!box) {
		dev_w_puts(o, "%%BoundingBox: (atend)\n%%HiResBoundingBox: (atend)\n%%Pages: (atend)\n");
	} else if (have) {
		dev_w_printf(o, "%%%%BoundingBox: %.0f %.0f %.0f %.0f\n", floor(box[0] + 1e-6), floor(box[1] + 1e-6), ceil(box[2] - 1e-6), ceil(box[3] - 1e-6));
		dev_w_printf(o, "%%%%HiResBoundingBox: %.4f %.4f %.4f %.4f\n", box[0], box[1], box[2], box[3]);
	} else {
		dev_w_puts(o, "%%BoundingBox: 0 0 0 0\n%%HiResBoundingBox: 0 0 0 0\n");
	}
	dev_w_puts(o, "%%Creator: locus-ps " LOCUS_VERSION "\n");
	if (p->title[0]) {
		dev_w_puts(o, "%%Title: ");
		psd_string(o, p->title);
		dev_w_puts(o, "\n");
	}
	if (p->date) {
		char b[40];
		psd_date(p->epoch, 0, b, sizeof b);
		dev_w_printf(o, "%%%%CreationDate: (%s)\n", b);
	}
	dev_w_printf(o, "%%%%LanguageLevel: %d\n", p->level);
	/* colorimage is Level 1's CMYK extension: CI falls back to grey where it is missing, which
	 * is no full emulation, so the document says it wants it (EPSF 3.0, section 2.2). EPS
	 * knows whether it drew a colour image when its header is written; PostScript's header
	 * comes first, so a colour Level 1 document declares it always. */
	if (p->level == 1 && !p->grey && (eps ? s->colorimage : 1))
		dev_w_puts(o, "%%Extensions: CMYK\n");
	if (eps)
		dev_w_puts(o, "%%Pages: 1\n");
	if (!eps && p->media)
		dev_w_printf(o, "%%%%DocumentMedia: Plain %.0f %.0f 0 () ()\n", p->media_w, p->media_h);
	dev_w_puts(o, "%%EndComments\n");
}

/* The prolog. EPS: the definitions live in a dictionary of their own inside a save (undone in
 * the trailer), so that the page it is placed on finds its state and dictionaries as they were. */
static void prolog_section(ps_t *s)
{
	dev_writer_t *o = &s->p.out;
	int eps = s->p.form == PSD_EPS;
	dev_w_puts(o, "%%BeginProlog\n");
	dev_w_puts(o, eps ? "save\n40 dict begin\n" : "/LocusDict 40 dict def LocusDict begin\n");
	dev_w_puts(o, prolog_head);
	/* K: at level 2 and 3 the page keeps DeviceRGB (start_page) and K sets the colour only.
	 * setrgbcolor installs the colour space again at every call: in Ghostscript 10 that is a
	 * third of the operator's cost, 23 M of 643 M instructions on workload b's 10,000 fills. */
	dev_w_printf(o, "/K {{255 div} forall %s} bind def /G {255 div setgray} bind def\n",
		s->p.level >= 2 ? "setcolor" : "setrgbcolor");
	dev_w_puts(o, prolog_tail);
	/* CI: a colour image through colorimage, which a Level 1 interpreter has only with the CMYK
	 * extension; without it each row of RGB samples is turned into luminance (BT.601, as
	 * --grey) and drawn by image */
	if (s->p.level == 1 && !s->p.grey)
		dev_w_puts(o, "/CI {/colorimage where {pop false 3 colorimage} {/Lp exch def /Lg 4 index string def\n"
			"{Lp dup length 3 idiv 0 1 3 -1 roll 1 sub {2 copy 3 mul 3 getinterval {} forall .114 mul exch\n"
			".587 mul add exch .299 mul add round cvi Lg 3 1 roll put} for pop Lg} image} ifelse} bind def\n");
	if (s->p.level >= 3)   /* H: draws from a binary number array (pspath.c) */
		dev_w_puts(o, "/H {aload length 2 idiv {rlineto} repeat} bind def\n");
	dev_w_puts(o, eps ? "%%EndProlog\n" : "end\n%%EndProlog\n");
}

static void start_page(ps_t *s)
{
	psd_t *p = &s->p;
	dev_writer_t *o = &p->out;
	int eps = p->form == PSD_EPS;
	p->doc_pages++;
	dev_w_printf(o, "%%%%Page: %u %u\n", p->doc_pages, p->doc_pages);
	if (!eps)
		dev_w_puts(o, "%%PageBoundingBox: (atend)\n");
	dev_w_puts(o, "%%BeginPageSetup\n");
	if (!eps && p->media && p->level >= 2)
	{
		dev_w_puts(o, "<< /PageSize [");
		dev_w_real(o, p->media_w, 4);
		dev_w_puts(o, " ");
		dev_w_real(o, p->media_h, 4);
		dev_w_puts(o, "] >> setpagedevice\n");
	}
	dev_w_puts(o, eps ? "gsave\n" : "save LocusDict begin\n");
	dev_w_real(o, p->ox, 4);
	dev_w_puts(o, " ");
	dev_w_real(o, p->oy, 4);
	dev_w_puts(o, " translate ");
	dev_w_real(o, p->sx / PSD_GRID, 8);
	dev_w_puts(o, " ");
	dev_w_real(o, p->sy / PSD_GRID, 8);
	/* exact geometry: the meta-language's pixels, not widths snapped for thin-line looks */
	dev_w_puts(o, " scale\n/setstrokeadjust where {pop false setstrokeadjust} if\n");
	if (p->level >= 2 && !p->grey)   /* for K (prolog_section); images set theirs in a gsave */
		dev_w_puts(o, "/DeviceRGB setcolorspace\n");
	/* everything is clipped to the page (meta-language 1) */
	dev_w_printf(o, "0 0 M %lld 0 l 0 %lld l %lld 0 l Z clip newpath\n%%%%EndPageSetup\n",
		(long long)p->page.width * PSD_GRID, (long long)p->page.height * PSD_GRID,
		-(long long)p->page.width * PSD_GRID);
	/* level 3: the page body is executed from a Flate-compressed ASCII85 stream (3 to 4 times
	 * smaller than the plain body; DSC comments stay outside, readable) */
	s->packed = p->level >= 3;
	if (s->packed) {
		dev_w_puts(o, "currentfile /ASCII85Decode filter /FlateDecode filter cvx exec\n");
		pse_deflate_begin(o, 1, PSE_HUFFMAN);
	}
	s->known = 0;
	s->p.col = 0;
}

static void box_line(dev_writer_t *o, const char *what, int have, const double *b)
{
	if (!have) {
		dev_w_printf(o, "%%%%%sBoundingBox: 0 0 0 0\n", what);
		return;
	}
	dev_w_printf(o, "%%%%%sBoundingBox: %.0f %.0f %.0f %.0f\n", what, floor(b[0] + 1e-6), floor(b[1] + 1e-6), ceil(b[2] - 1e-6), ceil(b[3] - 1e-6));
}

static int ps_open(dev_device_t *d)
{
	ps_t *s = st_of(d);
	psd_t *p = &s->p;
	int rc = psd_options(p, d);
	if (rc)
		return rc;
	p->form = strcmp(d->ops->name, "eps") ? PSD_PS : PSD_EPS;
	if (p->form == PSD_EPS && p->paper_w)
		return dev_fail(d, DEV_EUSAGE, "option paper: an EPS file has the size of its picture (use -f ps for paper)");
	if (p->media && p->level < 2)
		return dev_fail(d, DEV_EUSAGE, "option media: setpagedevice needs level 2 or 3");
	p->hooks.image = ps_image;
	p->hooks.rect = ps_rect;
	p->wrap = 120;   /* DSC lines stay under 255 characters */
	p->per_page = d->out == NULL;
	dev_w_init(&p->out, d->out);
	return 0;
}

static int ps_begin(dev_device_t *d, const dev_page_t *pg)
{
	ps_t *s = st_of(d);
	psd_t *p = &s->p;
	if (!d->out)
		return dev_fail(d, DEV_EDEVICE, "%s: no output", d->ops->name);
	if (p->form == PSD_EPS && p->doc_pages && !p->per_page)
		return dev_fail(d, META_ESTATE, "an EPS file holds one page: write to a file (one EPS per page) or use -f ps");
	psd_page(p, pg);
	if (!p->doc_open) {
		dev_w_set_transport(&p->out, d->out);
		p->doc_open = 1;
		p->doc_pages = 0;
		s->colorimage = 0;
		p->ddrawn = 0;
		/* EPS: prolog and page go to a spool; the header with the box is written at the end */
		if (p->form == PSD_EPS && pse_spool(&p->out))
			return dev_fail(d, META_EIO, "cannot create a temporary file for the EPS body");
		if (p->form != PSD_EPS)
			comments(s, NULL, 0);
		prolog_section(s);
	}
	start_page(s);
	return p->out.err ? psd_out_fail(p) : 0;
}

static int finish_doc(ps_t *s)
{
	psd_t *p = &s->p;
	dev_writer_t *o = &p->out;
	double b[4] = { p->dbx0, p->dby0, p->dbx1, p->dby1 };
	if (p->form == PSD_EPS) {
		dev_w_puts(o, "%%Trailer\nend restore\n%%EOF\n");
		void *body = pse_spool_end(o);
		comments(s, b, p->ddrawn);
		if (body)
			pse_spool_copy(o, body);
	} else {
		dev_w_puts(o, "%%Trailer\n");
		dev_w_printf(o, "%%%%Pages: %u\n", p->doc_pages);
		box_line(o, "", p->ddrawn, b);
		if (p->ddrawn)
			dev_w_printf(o, "%%%%HiResBoundingBox: %.4f %.4f %.4f %.4f\n", b[0], b[1], b[2], b[3]);
		else
			dev_w_puts(o, "%%HiResBoundingBox: 0 0 0 0\n");
		dev_w_puts(o, "%%EOF\n");
	}
	p->doc_open = 0;
	dev_w_flush(o);
	return o->err;
}

static int ps_end(dev_device_t *d, const dev_page_t *pg)
{
	ps_t *s = st_of(d);
	psd_t *p = &s->p;
	dev_writer_t *o = &p->out;
	(void)pg;
	int rc = psd_flush(p);
	if (rc)
		return rc;
	psd_newline(&s->p);
	if (s->packed) {
		pse_deflate_end(o, NULL);
		s->packed = 0;
	}
	double b[4];
	int have = psd_page_box(p, &b[0], &b[1], &b[2], &b[3]);
	if (have) {
		if (!p->ddrawn) {
			p->dbx0 = b[0], p->dby0 = b[1], p->dbx1 = b[2], p->dby1 = b[3];
			p->ddrawn = 1;
		} else {
			p->dbx0 = fmin(p->dbx0, b[0]), p->dby0 = fmin(p->dby0, b[1]);
			p->dbx1 = fmax(p->dbx1, b[2]), p->dby1 = fmax(p->dby1, b[3]);
		}
	}
	if (p->form == PSD_EPS) {
		dev_w_puts(o, "grestore\nshowpage\n%%PageTrailer\n");
	} else {
		dev_w_puts(o, "end restore showpage\n%%PageTrailer\n");
		box_line(o, "Page", have, b);
	}
	if (p->per_page || p->form == PSD_EPS)
		rc = finish_doc(s);
	if (rc || o->err)
		return o->err ? psd_out_fail(p) : dev_fail(d, META_EIO, "%s: write failed", io_name(d->out));
	return 0;
}

static int ps_close(dev_device_t *d)
{
	ps_t *s = st_of(d);
	psd_t *p = &s->p;
	int rc = 0;
	if (p->doc_open && !p->per_page && d->out && p->form != PSD_EPS && p->out.t) {
		if (finish_doc(s))
			rc = p->out.err ? psd_out_fail(p) : dev_fail(d, META_EIO, "%s: write failed", io_name(d->out));
	}
	pse_deflate_end(&p->out, NULL);   /* a stream left open by a failure mid-page (nothing if none) */
	void *sp = pse_spool_end(&p->out);
	if (sp)
		fclose(sp);
	psd_release(p);
	free(s->dx);
	s->dx = NULL;
	return rc;
}

const dev_ops_t dev_eps_ops = {
	.name = "eps", .description = "Encapsulated PostScript, one embeddable page (DSC 3.0, EPSF 3.0)",
	.extension = ".eps",
	.caps = DEV_CAP_VECTOR | DEV_CAP_ARCS | DEV_CAP_FILL | DEV_CAP_DASH | DEV_CAP_WIDTH,
	.priv_size = sizeof(ps_t), .option_list = psd_ps_options,
	.open = ps_open, .begin_page = ps_begin, .clear = psd_dev_clear, .stroke_path = ps_stroke,
	.fill_path = ps_fill, .put_span = psd_dev_span, .put_image_row = psd_dev_row, .end_page = ps_end,
	.close = ps_close,
};

const dev_ops_t dev_ps_ops = {
	.name = "ps", .description = "printable PostScript, one page per meta page (DSC 3.0)",
	.extension = ".ps",
	.caps = DEV_CAP_VECTOR | DEV_CAP_ARCS | DEV_CAP_FILL | DEV_CAP_DASH | DEV_CAP_WIDTH,
	.priv_size = sizeof(ps_t), .option_list = psd_ps_options,
	.open = ps_open, .begin_page = ps_begin, .clear = psd_dev_clear, .stroke_path = ps_stroke,
	.fill_path = ps_fill, .put_span = psd_dev_span, .put_image_row = psd_dev_row, .end_page = ps_end,
	.close = ps_close,
};
