/* dev-ps.c: the PostScript devices: EPS (one embeddable page) and printable multi-page PS. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "psdev.h"

#define CHUNK 200          /* relative lineto pairs per L (Level 1 operand stack: 500) */

/* The device's state: the shared part plus what was last set in the graphics state. */
typedef struct {
	psd_t p;
	int known;             /* 0 at page start: everything must be set */
	meta_rgb_t colour;
	int64_t width, miter;
	int cap, join;
	int64_t dash[2 * META_MAX_DASH];
	size_t ndash;
	int col;               /* output column, to keep lines short */
	int packed;            /* level 3: the page body is Flate-compressed and executed */
	void *spool;           /* EPS: the body while its box is not known */
	long long *dx;         /* pending relative draws, grid units */
	size_t ndx, capdx;
} ps_t;

/* Short procedures defined once; the page draws with these names only. */
static const char prolog[] =
	"/M /moveto load def /D /lineto load def /l /rlineto load def\n"
	"/L {{rlineto} repeat} bind def /Z /closepath load def\n"
	"/A /arc load def /N /arcn load def\n"
	"/C {3 copy 3 -1 roll add exch moveto 0 360 arc closepath} bind def\n"
	"/S /stroke load def /F /fill load def /E /eofill load def\n"
	"/K {{255 div} forall setrgbcolor} bind def /G {255 div setgray} bind def\n"
	"/W /setlinewidth load def\n"
	"/J /setlinecap load def /j /setlinejoin load def /X /setmiterlimit load def\n"
	"/B {newpath 4 2 roll moveto 1 index 0 rlineto 0 exch rlineto neg 0 rlineto closepath fill} bind def\n";

static ps_t *st_of(dev_device_t *d)
{
	return d->priv;
}

/* A separator before the next token: a newline now and then (DSC lines stay under 255). */
static void sep(ps_t *s)
{
	if (s->col > 120) {
		pse_write(&s->p.out, "\n", 1);
		s->col = 0;
	} else if (s->col) {
		pse_write(&s->p.out, " ", 1);
		s->col++;
	}
}

static void tok_int(ps_t *s, long long v)
{
	sep(s);
	pse_int(&s->p.out, v);
	s->col += v < 0 ? 2 : 1;
	for (long long a = v < 0 ? -v : v; a >= 10; a /= 10)
		s->col++;
}

static void tok(ps_t *s, const char *t)
{
	sep(s);
	pse_puts(&s->p.out, t);
	s->col += (int)strlen(t);
}

static void newline(ps_t *s)
{
	if (s->col) {
		pse_write(&s->p.out, "\n", 1);
		s->col = 0;
	}
}


/* Colours as 8-bit values, exactly: RGB as a hex string <rrggbb> K, grey as an integer G. */
static void set_colour(ps_t *s, meta_rgb_t c)
{
	char b[16];
	if (s->known && s->colour == c)
		return;
	if (s->p.grey) {
		tok_int(s, psd_luma(c));
		tok(s, "G");
	} else {
		snprintf(b, sizeof b, "<%06x>", (unsigned)c & 0xffffff);
		tok(s, b);
		tok(s, "K");
	}
	s->colour = c;
}

static void set_line(ps_t *s, const dev_state_t *st)
{
	int64_t w = st->width > 1000 ? st->width : 1000;
	if (!s->known || s->width != w) {
		tok_int(s, psd_grid(w));
		tok(s, "W");
		s->width = w;
	}
	if (!s->known || s->cap != st->cap) {
		tok_int(s, st->cap);
		tok(s, "J");
		s->cap = st->cap;
	}
	if (!s->known || s->join != st->join) {
		tok_int(s, st->join);
		tok(s, "j");
		s->join = st->join;
	}
	if (!s->known || s->miter != st->miter_limit) {
		sep(s);
		pse_fix(&s->p.out, st->miter_limit);
		s->col += 6;
		tok(s, "X");
		s->miter = st->miter_limit;
	}
	if (!s->known || s->ndash != st->ndash || memcmp(s->dash, st->dash, st->ndash * sizeof st->dash[0])) {
		tok(s, "[");
		for (size_t k = 0; k < st->ndash; k++) {
			sep(s);
			pse_real(&s->p.out, (double)st->dash[k] * PSD_GRID / 1000, 2);
			s->col += 6;
		}
		tok(s, "] 0 setdash");
		s->ndash = st->ndash;
		memcpy(s->dash, st->dash, st->ndash * sizeof st->dash[0]);
	}
}

/* ---- paths: absolute moves, relative integer draws in reversed chunks ---- */

static int push_draw(ps_t *s, long long dx, long long dy)
{
	if (s->ndx + 2 > s->capdx) {
		size_t n = s->capdx ? s->capdx * 2 : 256;
		long long *q = realloc(s->dx, n * sizeof *q);
		if (!q)
			return dev_fail(s->p.dev, META_ENOMEM, "out of memory");
		s->dx = q;
		s->capdx = n;
	}
	s->dx[s->ndx++] = dx;
	s->dx[s->ndx++] = dy;
	return 0;
}

static void flush_draws(ps_t *s)
{
	size_t n = s->ndx / 2;
	for (size_t at = 0; at < n;) {
		size_t k = n - at > CHUNK ? CHUNK : n - at;
		if (k < 3) {
			for (size_t i = at; i < at + k; i++) {
				tok_int(s, s->dx[2 * i]);
				tok_int(s, s->dx[2 * i + 1]);
				tok(s, "l");
			}
		} else {
			for (size_t i = at + k; i-- > at;) {
				tok_int(s, s->dx[2 * i]);
				tok_int(s, s->dx[2 * i + 1]);
			}
			tok_int(s, (long long)k);
			tok(s, "L");
		}
		at += k;
	}
	s->ndx = 0;
}

/* The path walker's position: the last grid point, when the interpreter's current point is
 * exactly on it (not after an arc). */
typedef struct {
	long long x, y, sx, sy;
	int on_grid, start_on_grid, cur;   /* cur: the meta path has a current point */
} walk_t;

static void move_abs(ps_t *s, walk_t *w, long long x, long long y, const char *op)
{
	flush_draws(s);
	tok_int(s, x);
	tok_int(s, y);
	tok(s, op);
	w->x = x, w->y = y;
	w->on_grid = 1;
}

static int draw_to(ps_t *s, walk_t *w, long long x, long long y)
{
	if (!w->on_grid) {
		move_abs(s, w, x, y, "D");
		return 0;
	}
	int rc = push_draw(s, x - w->x, y - w->y);
	w->x = x, w->y = y;
	return rc;
}

static void arc_start(ps_t *s, const dev_elem_t *e)
{
	double a = e->f[3] / 180000.0 * M_PI;
	sep(s);
	pse_real(&s->p.out, (e->f[0] + e->f[2] * cos(a)) * PSD_GRID / 1000.0, 2);
	sep(s);
	pse_real(&s->p.out, (e->f[1] + e->f[2] * sin(a)) * PSD_GRID / 1000.0, 2);
	s->col += 20;
	tok(s, "M");
}

static int path_elems(ps_t *s, const dev_path_t *dp, int fill)
{
	walk_t w = { 0, 0, 0, 0, 0, 0, 0 };
	int ps_cur = 0;     /* the interpreter has a current point */
	for (size_t k = 0; k < dp->nelems; k++) {
		const dev_elem_t *e = &dp->elems[k];
		long long x = psd_grid(e->f[0]), y = psd_grid(e->f[1]);
		switch (e->op) {
		case META_MOVE:
			move_abs(s, &w, x, y, "M");
			w.sx = x, w.sy = y;
			w.start_on_grid = 1;
			w.cur = ps_cur = 1;
			break;
		case META_DRAW:
			if (draw_to(s, &w, x, y))
				return META_ENOMEM;
			break;
		case META_ARC:
			flush_draws(s);
			if (!w.cur && ps_cur)
				arc_start(s, e);
			if (!w.cur)
				w.start_on_grid = 0;
			tok_int(s, x);
			tok_int(s, y);
			tok_int(s, psd_grid(e->f[2]) > 0 ? psd_grid(e->f[2]) : 1);
			sep(s);
			pse_fix(&s->p.out, e->f[3]);
			sep(s);
			pse_fix(&s->p.out, (long long)e->f[3] + e->f[4]);
			s->col += 16;
			tok(s, e->f[4] >= 0 ? "A" : "N");
			w.on_grid = 0;
			w.cur = ps_cur = 1;
			break;
		case META_CIRCLE:
			flush_draws(s);
			tok_int(s, x);
			tok_int(s, y);
			tok_int(s, psd_grid(e->f[2]) > 0 ? psd_grid(e->f[2]) : 1);
			tok(s, "C");
			w.on_grid = 0;
			w.cur = 0;
			ps_cur = 1;
			break;
		case META_CLOSE:
			flush_draws(s);
			/* fill closes every subpath itself: Z only where a draw or arc goes on from it */
			if (!fill || (k + 1 < dp->nelems && (dp->elems[k + 1].op == META_DRAW || dp->elems[k + 1].op == META_ARC)))
				tok(s, "Z");
			w.on_grid = w.start_on_grid;
			w.x = w.sx, w.y = w.sy;
			break;
		default:
			break;
		}
	}
	flush_draws(s);
	return 0;
}

static int path_flat(ps_t *s, const scan_path_t *f, int fill)
{
	walk_t w = { 0, 0, 0, 0, 0, 0, 0 };
	for (size_t k = 0; k < f->nsubs; k++) {
		const scan_pt_t *q = f->pts + f->subs[k].start;
		size_t n = f->subs[k].n;
		if (!n)
			continue;
		move_abs(s, &w, psd_grid(q[0].x), psd_grid(q[0].y), "M");
		for (size_t i = 1; i < n; i++)
			if (draw_to(s, &w, psd_grid(q[i].x), psd_grid(q[i].y)))
				return META_ENOMEM;
		flush_draws(s);
		if (f->subs[k].closed && !fill)
			tok(s, "Z");
	}
	return 0;
}

static int write_path(ps_t *s, const dev_path_t *dp, int fill)
{
	return psd_native(dp) ? path_elems(s, dp, fill) : path_flat(s, dp->flat, fill);
}

static int ps_stroke(dev_device_t *d, const dev_path_t *dp, const dev_state_t *st)
{
	ps_t *s = st_of(d);
	int rc = psd_flush(&s->p);
	if (rc)
		return rc;
	psd_grow_path(&s->p, dp, st, 1);
	set_colour(s, st->colour);
	set_line(s, st);
	s->known = 1;
	if ((rc = write_path(s, dp, 0)))
		return rc;
	tok(s, "S");
	newline(s);
	return s->p.out.err ? dev_fail(d, META_EIO, "%s: write failed", io_name(d->out)) : 0;
}

static int ps_fill(dev_device_t *d, const dev_path_t *dp, const dev_state_t *st)
{
	ps_t *s = st_of(d);
	int rc = psd_flush(&s->p);
	if (rc)
		return rc;
	psd_grow_path(&s->p, dp, st, 0);
	set_colour(s, st->colour);
	if ((rc = write_path(s, dp, 1)))
		return rc;
	tok(s, st->rule == META_RULE_EVEN_ODD ? "E" : "F");
	newline(s);
	return s->p.out.err ? dev_fail(d, META_EIO, "%s: write failed", io_name(d->out)) : 0;
}

/* ---- rasters ---- */

static int ps_rect(psd_t *p, unsigned x, unsigned y, unsigned w, unsigned h, meta_rgb_t rgb)
{
	ps_t *s = (ps_t *)p;
	set_colour(s, rgb);
	s->known |= 0;   /* the line state is untouched */
	tok_int(s, (long long)x * PSD_GRID);
	tok_int(s, (long long)y * PSD_GRID);
	tok_int(s, (long long)w * PSD_GRID);
	tok_int(s, (long long)h * PSD_GRID);
	tok(s, "B");
	newline(s);
	return 0;
}

static int ps_image(psd_t *p, unsigned x, unsigned y, unsigned w, unsigned h, const uint8_t *rgb)
{
	ps_t *s = (ps_t *)p;
	pse_out_t *o = &p->out;
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
	newline(s);
	pse_printf(o, "gsave %lld %lld translate %lld %lld scale\n", (long long)x * PSD_GRID,
		(long long)y * PSD_GRID, (long long)w * PSD_GRID, (long long)h * PSD_GRID);
	if (s->packed) {
		/* inside the compressed body: the samples as they are, compressed harder */
		pse_printf(o, "/Device%s setcolorspace\n<< /ImageType 1 /Width %u /Height %u /BitsPerComponent %d\n"
			"/Decode [%s] /ImageMatrix [%u 0 0 -%u 0 %u] /DataSource currentfile >> image\n",
			space, iw, ih, sm.bpc, decode, iw, ih, ih);
		pse_deflate_level(o, 6);
		pse_write(o, data, n);
		pse_deflate_level(o, PSE_HUFFMAN);
		pse_puts(o, "\n");
	} else if (pick == HEX) {
		pse_printf(o, "/picstr %zu string def\n%u %u %d [%u 0 0 -%u 0 %u]\n"
			"{currentfile picstr readhexstring pop} %s\n", n / ih, iw, ih, sm.bpc, iw, ih, ih,
			sm.comps == 1 ? "image" : "false 3 colorimage");
		pse_hex_write(o, data, n);
	} else {
		pse_printf(o, "/Device%s setcolorspace\n<< /ImageType 1 /Width %u /Height %u /BitsPerComponent %d\n"
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
	pse_puts(o, "grestore\n");
	s->known = 0;   /* setcolorspace reset the colour */
	if (o->err)
		rc = dev_fail(p->dev, META_EIO, "%s: write failed", io_name(p->dev->out));
done:
	free(sm.owned);
	free(rle);
	free(z);
	return rc;
}

static int ps_span(dev_device_t *d, unsigned x, unsigned y, unsigned n, meta_rgb_t rgb)
{
	return psd_span(d->priv, x, y, n, rgb);
}

static int ps_row(dev_device_t *d, unsigned x, unsigned y, const meta_run_t *runs, size_t nruns)
{
	return psd_row(d->priv, x, y, runs, nruns);
}

static int ps_clear(dev_device_t *d, meta_rgb_t rgb)
{
	ps_t *s = st_of(d);
	int rc = psd_flush(&s->p);
	if (rc)
		return rc;
	psd_grow(&s->p, 0, 0, (int64_t)s->p.page.width * 1000, (int64_t)s->p.page.height * 1000);
	return ps_rect(&s->p, 0, 0, s->p.page.width, s->p.page.height, rgb);
}

/* ---- document structure (DSC 3.0) ---- */

static void ps_string(pse_out_t *o, const char *t)
{
	pse_puts(o, "(");
	for (; *t; t++) {
		if (*t == '(' || *t == ')' || *t == '\\')
			pse_puts(o, "\\");
		pse_write(o, t, 1);
	}
	pse_puts(o, ")");
}

/* The header comments up to %%EndComments; box NULL: (atend) (PostScript only). */
static void comments(ps_t *s, const double *box, int have)
{
	psd_t *p = &s->p;
	pse_out_t *o = &p->out;
	int eps = p->form == PSD_EPS;
	pse_puts(o, eps ? "%!PS-Adobe-3.0 EPSF-3.0\n" : "%!PS-Adobe-3.0\n");
	if (!box) {
		pse_puts(o, "%%BoundingBox: (atend)\n%%HiResBoundingBox: (atend)\n%%Pages: (atend)\n");
	} else if (have) {
		pse_printf(o, "%%%%BoundingBox: %.0f %.0f %.0f %.0f\n", floor(box[0] + 1e-6), floor(box[1] + 1e-6), ceil(box[2] - 1e-6), ceil(box[3] - 1e-6));
		pse_printf(o, "%%%%HiResBoundingBox: %.4f %.4f %.4f %.4f\n", box[0], box[1], box[2], box[3]);
	} else {
		pse_puts(o, "%%BoundingBox: 0 0 0 0\n%%HiResBoundingBox: 0 0 0 0\n");
	}
	pse_puts(o, "%%Creator: locus-ps " LOCUS_VERSION "\n");
	if (p->title[0]) {
		pse_puts(o, "%%Title: ");
		ps_string(o, p->title);
		pse_puts(o, "\n");
	}
	if (p->date) {
		char b[40];
		psd_date(p->epoch, 0, b, sizeof b);
		pse_printf(o, "%%%%CreationDate: (%s)\n", b);
	}
	pse_printf(o, "%%%%LanguageLevel: %d\n", p->level);
	if (eps)
		pse_puts(o, "%%Pages: 1\n");
	if (!eps && p->media)
		pse_printf(o, "%%%%DocumentMedia: Plain %.0f %.0f 0 () ()\n", p->media_w, p->media_h);
	pse_puts(o, "%%EndComments\n");
}

/* The prolog. EPS: the definitions live in a dictionary of their own inside a save (undone in
 * the trailer), so that the page it is placed on finds its state and dictionaries as they were. */
static void prolog_section(ps_t *s)
{
	pse_out_t *o = &s->p.out;
	int eps = s->p.form == PSD_EPS;
	pse_puts(o, "%%BeginProlog\n");
	pse_puts(o, eps ? "save\n40 dict begin\n" : "/LocusDict 40 dict def LocusDict begin\n");
	pse_puts(o, prolog);
	pse_puts(o, eps ? "%%EndProlog\n" : "end\n%%EndProlog\n");
}

static void start_page(ps_t *s)
{
	psd_t *p = &s->p;
	pse_out_t *o = &p->out;
	int eps = p->form == PSD_EPS;
	p->doc_pages++;
	pse_printf(o, "%%%%Page: %u %u\n", p->doc_pages, p->doc_pages);
	if (!eps)
		pse_puts(o, "%%PageBoundingBox: (atend)\n");
	pse_puts(o, "%%BeginPageSetup\n");
	if (!eps && p->media && p->level >= 2)
	{
		pse_puts(o, "<< /PageSize [");
		pse_real(o, p->media_w, 4);
		pse_puts(o, " ");
		pse_real(o, p->media_h, 4);
		pse_puts(o, "] >> setpagedevice\n");
	}
	pse_puts(o, eps ? "gsave\n" : "save LocusDict begin\n");
	pse_real(o, p->ox, 4);
	pse_puts(o, " ");
	pse_real(o, p->oy, 4);
	pse_puts(o, " translate ");
	pse_real(o, p->sx / PSD_GRID, 8);
	pse_puts(o, " ");
	pse_real(o, p->sy / PSD_GRID, 8);
	/* exact geometry: the meta-language's pixels, not widths snapped for thin-line looks */
	pse_puts(o, " scale\n/setstrokeadjust where {pop false setstrokeadjust} if\n");
	/* everything is clipped to the page (meta-language 1) */
	pse_printf(o, "0 0 M %lld 0 l 0 %lld l %lld 0 l Z clip newpath\n%%%%EndPageSetup\n",
		(long long)p->page.width * PSD_GRID, (long long)p->page.height * PSD_GRID,
		-(long long)p->page.width * PSD_GRID);
	/* level 3: the page body is executed from a Flate-compressed ASCII85 stream (3 to 4 times
	 * smaller than the plain body; DSC comments stay outside, readable) */
	s->packed = p->level >= 3;
	if (s->packed) {
		pse_puts(o, "currentfile /ASCII85Decode filter /FlateDecode filter cvx exec\n");
		pse_deflate_begin(o, 1, PSE_HUFFMAN);
	}
	s->known = 0;
	s->col = 0;
}

static void box_line(pse_out_t *o, const char *what, int have, const double *b)
{
	if (!have) {
		pse_printf(o, "%%%%%sBoundingBox: 0 0 0 0\n", what);
		return;
	}
	pse_printf(o, "%%%%%sBoundingBox: %.0f %.0f %.0f %.0f\n", what, floor(b[0] + 1e-6), floor(b[1] + 1e-6), ceil(b[2] - 1e-6), ceil(b[3] - 1e-6));
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
	p->per_page = d->out == NULL;
	pse_init(&p->out, d->out);
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
		pse_set_transport(&p->out, d->out);
		p->doc_open = 1;
		p->doc_pages = 0;
		p->ddrawn = 0;
		/* EPS: prolog and page go to a spool; the header with the box is written at the end */
		if (p->form == PSD_EPS && pse_spool(&p->out))
			return dev_fail(d, META_EIO, "cannot create a temporary file for the EPS body");
		if (p->form != PSD_EPS)
			comments(s, NULL, 0);
		prolog_section(s);
	}
	start_page(s);
	return p->out.err ? dev_fail(d, META_EIO, "%s: write failed", io_name(d->out)) : 0;
}

static int finish_doc(ps_t *s)
{
	psd_t *p = &s->p;
	pse_out_t *o = &p->out;
	double b[4] = { p->dbx0, p->dby0, p->dbx1, p->dby1 };
	if (p->form == PSD_EPS) {
		pse_puts(o, "%%Trailer\nend restore\n%%EOF\n");
		void *body = pse_spool_end(o);
		comments(s, b, p->ddrawn);
		if (body)
			pse_spool_copy(o, body);
	} else {
		pse_puts(o, "%%Trailer\n");
		pse_printf(o, "%%%%Pages: %u\n", p->doc_pages);
		box_line(o, "", p->ddrawn, b);
		if (p->ddrawn)
			pse_printf(o, "%%%%HiResBoundingBox: %.4f %.4f %.4f %.4f\n", b[0], b[1], b[2], b[3]);
		else
			pse_puts(o, "%%HiResBoundingBox: 0 0 0 0\n");
		pse_puts(o, "%%EOF\n");
	}
	p->doc_open = 0;
	pse_flush(o);
	return o->err;
}

static int ps_end(dev_device_t *d, const dev_page_t *pg)
{
	ps_t *s = st_of(d);
	psd_t *p = &s->p;
	pse_out_t *o = &p->out;
	(void)pg;
	int rc = psd_flush(p);
	if (rc)
		return rc;
	newline(s);
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
		pse_puts(o, "grestore\nshowpage\n%%PageTrailer\n");
	} else {
		pse_puts(o, "end restore showpage\n%%PageTrailer\n");
		box_line(o, "Page", have, b);
	}
	if (p->per_page || p->form == PSD_EPS)
		rc = finish_doc(s);
	if (rc || o->err)
		return dev_fail(d, META_EIO, "%s: write failed", io_name(d->out));
	return 0;
}

static int ps_close(dev_device_t *d)
{
	ps_t *s = st_of(d);
	psd_t *p = &s->p;
	int rc = 0;
	if (p->doc_open && !p->per_page && d->out && p->form != PSD_EPS && p->out.t) {
		if (finish_doc(s))
			rc = dev_fail(d, META_EIO, "%s: write failed", io_name(d->out));
	}
	if (p->out.z)
		pse_deflate_end(&p->out, NULL);   /* after a failure mid-page */
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
	.open = ps_open, .begin_page = ps_begin, .clear = ps_clear, .stroke_path = ps_stroke,
	.fill_path = ps_fill, .put_span = ps_span, .put_image_row = ps_row, .end_page = ps_end,
	.close = ps_close,
};

const dev_ops_t dev_ps_ops = {
	.name = "ps", .description = "printable PostScript, one page per meta page (DSC 3.0)",
	.extension = ".ps",
	.caps = DEV_CAP_VECTOR | DEV_CAP_ARCS | DEV_CAP_FILL | DEV_CAP_DASH | DEV_CAP_WIDTH,
	.priv_size = sizeof(ps_t), .option_list = psd_ps_options,
	.open = ps_open, .begin_page = ps_begin, .clear = ps_clear, .stroke_path = ps_stroke,
	.fill_path = ps_fill, .put_span = ps_span, .put_image_row = ps_row, .end_page = ps_end,
	.close = ps_close,
};
