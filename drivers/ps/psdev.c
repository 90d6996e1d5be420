/* psdev.c: shared by the PostScript and PDF devices: options, placement, drawn box, images. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include "ps/psdev.h"

#define MM_PT (72.0 / 25.4)
#define BLOCK_MAX ((size_t)4 << 20)    /* bytes of merged image rows held before emitting */

#define SHARED_OPTIONS \
	{ "paper", "page | a4 | a3 | letter | legal | WxHmm: the medium (default page: the picture's own size)" }, \
	{ "orientation", "portrait | landscape: landscape swaps the paper's sides (default portrait)" }, \
	{ "place", "fit | centre: fit inside the margins or natural size centred (default fit)" }, \
	{ "scale", "F: natural size times F, centred (overrides place)" }, \
	{ "margin", "MM: margin on every side with a paper (default 10)" }, \
	{ "grey", "yes | no: grey levels by luminance for monochrome printers (default no)" }, \
	{ "dither", "DPI: images as an 8x8 ordered dither in black and white at DPI dots per inch (implies grey)" }, \
	{ "date", "yes | no: write a creation date, SOURCE_DATE_EPOCH or now (default no)" }, \
	{ "title", "TEXT: the document title (default none)" }

const dev_option_t psd_ps_options[] = {
	{ "level", "1 | 2 | 3: PostScript language level (default 3: compressed pages and images)" },
	{ "media", "yes | no: ask the printer for the paper with setpagedevice (default no)" },
	SHARED_OPTIONS,
	{ NULL, NULL }
};

const dev_option_t psd_pdf_options[] = {
	SHARED_OPTIONS,
	{ NULL, NULL }
};

static int yes_no(dev_device_t *d, const char *key, int *v)
{
	char b[16];
	if (!dev_option(d, key, b, sizeof b))
		return 0;
	if (!strcmp(b, "yes") || !strcmp(b, "1"))
		*v = 1;
	else if (!strcmp(b, "no") || !strcmp(b, "0"))
		*v = 0;
	else
		return dev_fail(d, DEV_EUSAGE, "option %s: expected yes or no, found '%s'", key, b);
	return 0;
}

static int positive(dev_device_t *d, const char *key, const char *s, double lo, double hi, double *v)
{
	char *e;
	*v = strtod(s, &e);
	if (e == s || *e || !(*v >= lo && *v <= hi))
		return dev_fail(d, DEV_EUSAGE, "option %s: expected a number from %g to %g, found '%s'", key, lo, hi, s);
	return 0;
}

static int paper(psd_t *p, dev_device_t *d, const char *s)
{
	static const struct { const char *name; double w, h; } known[] = {
		{ "a4", 210 * MM_PT, 297 * MM_PT }, { "a3", 297 * MM_PT, 420 * MM_PT },
		{ "letter", 612, 792 }, { "legal", 612, 1008 },
	};
	if (!strcasecmp(s, "page")) {
		p->paper_w = p->paper_h = 0;
		return 0;
	}
	for (size_t k = 0; k < sizeof known / sizeof known[0]; k++)
		if (!strcasecmp(s, known[k].name)) {
			p->paper_w = known[k].w;
			p->paper_h = known[k].h;
			return 0;
		}
	double w, h;
	char mm[4];
	int used = 0;
	if (sscanf(s, "%lfx%lf%2[m]%n", &w, &h, mm, &used) == 3 && (size_t)used == strlen(s) &&
			!strcmp(mm, "mm") && w >= 10 && h >= 10 && w <= 5000 && h <= 5000) {
		p->paper_w = w * MM_PT;
		p->paper_h = h * MM_PT;
		return 0;
	}
	return dev_fail(d, DEV_EUSAGE, "option paper: expected page, a4, a3, letter, legal or WxHmm "
		"(10 to 5000 mm), found '%s'", s);
}

int psd_options(psd_t *p, dev_device_t *d)
{
	char b[160];
	int rc;
	p->dev = d;
	p->level = 3;
	p->place = PSD_PLACE_FIT;
	p->margin = 10 * MM_PT;
	if (dev_option(d, "level", b, sizeof b)) {
		if (strlen(b) != 1 || b[0] < '1' || b[0] > '3')
			return dev_fail(d, DEV_EUSAGE, "option level: expected 1, 2 or 3, found '%s'", b);
		p->level = b[0] - '0';
	}
	if ((rc = yes_no(d, "media", &p->media)) || (rc = yes_no(d, "grey", &p->grey)) ||
			(rc = yes_no(d, "date", &p->date)))
		return rc;
	if (dev_option(d, "dither", b, sizeof b)) {
		double dpi;
		if ((rc = positive(d, "dither", b, 72, 2400, &dpi)))
			return rc;
		p->dither = (unsigned)dpi;
		p->grey = 1;
	}
	if (dev_option(d, "paper", b, sizeof b) && (rc = paper(p, d, b)))
		return rc;
	if (dev_option(d, "orientation", b, sizeof b)) {
		if (strcmp(b, "portrait") && strcmp(b, "landscape"))
			return dev_fail(d, DEV_EUSAGE, "option orientation: expected portrait or landscape, found '%s'", b);
		p->landscape = !strcmp(b, "landscape");
	}
	if (dev_option(d, "place", b, sizeof b)) {
		if (!strcmp(b, "fit"))
			p->place = PSD_PLACE_FIT;
		else if (!strcmp(b, "centre") || !strcmp(b, "center"))
			p->place = PSD_PLACE_CENTRE;
		else
			return dev_fail(d, DEV_EUSAGE, "option place: expected fit or centre, found '%s'", b);
	}
	if (dev_option(d, "scale", b, sizeof b)) {
		if ((rc = positive(d, "scale", b, 0.001, 1000, &p->scale)))
			return rc;
		p->place = PSD_PLACE_SCALE;
	}
	if (dev_option(d, "margin", b, sizeof b)) {
		double mm;
		if ((rc = positive(d, "margin", b, 0, 1000, &mm)))
			return rc;
		p->margin = mm * MM_PT;
	}
	if (p->paper_w && (p->paper_w <= 2 * p->margin || p->paper_h <= 2 * p->margin))
		return dev_fail(d, DEV_EUSAGE, "option margin: the margins leave no room on the paper");
	char t[1024];
	if (dev_option(d, "title", t, sizeof t)) {
		if (strlen(t) >= sizeof p->title)
			return dev_fail(d, DEV_EUSAGE, "option title: at most %zu characters", sizeof p->title - 1);
		for (const char *c = t; *c; c++)
			if ((unsigned char)*c < 0x20 || (unsigned char)*c > 0x7e)
				return dev_fail(d, DEV_EUSAGE, "option title: printable ASCII only");
		memcpy(p->title, t, strlen(t) + 1);   /* fits: checked above */
	}
	if (p->date) {
		const char *e = getenv("SOURCE_DATE_EPOCH");
		char *end;
		p->epoch = e && *e ? strtoll(e, &end, 10) : (long long)time(NULL);
		if (e && *e && (*end || p->epoch < 0))
			return dev_fail(d, DEV_EUSAGE, "SOURCE_DATE_EPOCH: expected seconds since 1970, found '%s'", e);
	}
	return 0;
}

void psd_page(psd_t *p, const dev_page_t *pg)
{
	p->page = *pg;
	double nw = pg->has_size ? pg->width_mm / 1000.0 * MM_PT : pg->width * 0.75;
	double nh = pg->has_size ? pg->height_mm / 1000.0 * MM_PT : pg->height * 0.75;
	double f = 1;
	if (!p->paper_w) {
		if (p->place == PSD_PLACE_SCALE)
			f = p->scale;
		p->media_w = nw * f;
		p->media_h = nh * f;
		p->ox = p->oy = 0;
	} else {
		p->media_w = p->landscape ? p->paper_h : p->paper_w;
		p->media_h = p->landscape ? p->paper_w : p->paper_h;
		double aw = p->media_w - 2 * p->margin, ah = p->media_h - 2 * p->margin;
		if (p->place == PSD_PLACE_FIT)
			f = fmin(aw / nw, ah / nh);
		else if (p->place == PSD_PLACE_SCALE)
			f = p->scale;
		p->ox = (p->media_w - nw * f) / 2;
		p->oy = (p->media_h - nh * f) / 2;
	}
	p->sx = nw * f / pg->width;
	p->sy = nh * f / pg->height;
	p->drawn = 0;
}

void psd_grow(psd_t *p, int64_t x0, int64_t y0, int64_t x1, int64_t y1)
{
	if (!p->drawn) {
		p->bx0 = x0, p->by0 = y0, p->bx1 = x1, p->by1 = y1;
		p->drawn = 1;
		return;
	}
	if (x0 < p->bx0) p->bx0 = x0;
	if (y0 < p->by0) p->by0 = y0;
	if (x1 > p->bx1) p->bx1 = x1;
	if (y1 > p->by1) p->by1 = y1;
}

/* How far a miter join at v reaches from it, in half-widths (1 when it is a bevel). */
static double miter_reach(scan_pt_t a, scan_pt_t v, scan_pt_t b, double limit)
{
	double d1x = (double)(v.x - a.x), d1y = (double)(v.y - a.y);
	double d2x = (double)(b.x - v.x), d2y = (double)(b.y - v.y);
	double l1 = hypot(d1x, d1y), l2 = hypot(d2x, d2y);
	if (l1 == 0 || l2 == 0)
		return 1;
	double c = (d1x * d2x + d1y * d2y) / (l1 * l2);
	if ((1 + c) * limit * limit < 2)
		return 1;
	return sqrt(2 / (1 + c));
}

void psd_grow_path(psd_t *p, const dev_path_t *dp, const dev_state_t *st, int stroke)
{
	const scan_path_t *f = dp->flat;
	int64_t slack = 2;
	for (size_t k = 0; k < dp->nelems; k++)
		if (dp->elems[k].op == META_ARC || dp->elems[k].op == META_CIRCLE)
			slack = 260;    /* native arcs bulge past their chords by at most 1/4 pixel */
	double h = stroke ? (st->width > 1000 ? st->width : 1000) / 2.0 : 0;
	double base = h * (stroke && st->cap == META_CAP_SQUARE ? sqrt(2.0) : 1);
	double limit = st->miter_limit / 1000.0;
	/* the farthest any point can reach; points whose reach stays inside the box so far (after
	 * a clear, the page) cannot grow it, and cost no join geometry */
	double far = base;
	if (stroke && st->join == META_JOIN_MITER && h * limit > far)
		far = h * limit;
	int64_t fi = (int64_t)ceil(far) + slack;
	for (size_t s = 0; s < f->nsubs; s++) {
		const scan_pt_t *q = f->pts + f->subs[s].start;
		size_t n = f->subs[s].n;
		for (size_t k = 0; k < n; k++) {
			if (p->drawn && q[k].x - fi >= p->bx0 && q[k].x + fi <= p->bx1 && q[k].y - fi >= p->by0 &&
					q[k].y + fi <= p->by1)
				continue;
			double e = base;
			if (stroke && st->join == META_JOIN_MITER && n > 2 && (f->subs[s].closed || (k > 0 && k + 1 < n))) {
				/* neighbours, skipping repeated points */
				size_t i = k, j = k;
				do i = i ? i - 1 : n - 1; while (i != k && q[i].x == q[k].x && q[i].y == q[k].y);
				do j = j + 1 < n ? j + 1 : 0; while (j != k && q[j].x == q[k].x && q[j].y == q[k].y);
				double r = h * miter_reach(q[i], q[k], q[j], limit);
				if (r > e)
					e = r;
			}
			int64_t ei = (int64_t)ceil(e) + slack;
			psd_grow(p, q[k].x - ei, q[k].y - ei, q[k].x + ei, q[k].y + ei);
		}
	}
}

int psd_page_box(const psd_t *p, double *x0, double *y0, double *x1, double *y1)
{
	if (!p->drawn)
		return 0;
	int64_t w = (int64_t)p->page.width * 1000, h = (int64_t)p->page.height * 1000;
	/* whole pixels: the box is then also a crop of the raster picture */
	int64_t a = p->bx0 < 0 ? 0 : p->bx0 / 1000 * 1000, b = p->by0 < 0 ? 0 : p->by0 / 1000 * 1000;
	int64_t c = p->bx1 > w ? w : (p->bx1 + 999) / 1000 * 1000, e = p->by1 > h ? h : (p->by1 + 999) / 1000 * 1000;
	if (a >= c || b >= e)
		return 0;
	*x0 = p->ox + p->sx * (double)a / 1000;
	*y0 = p->oy + p->sy * (double)b / 1000;
	*x1 = p->ox + p->sx * (double)c / 1000;
	*y1 = p->oy + p->sy * (double)e / 1000;
	return 1;
}

int psd_native(const dev_path_t *dp)
{
	const int64_t lim = (int64_t)65536 * 1000;
	if (!dp->nelems)
		return 0;
	for (size_t k = 0; k < dp->nelems; k++) {
		const dev_elem_t *e = &dp->elems[k];
		if ((e->op == META_ARC || e->op == META_CIRCLE) &&
				(e->f[2] > lim || e->f[0] > lim || e->f[0] < -lim || e->f[1] > lim || e->f[1] < -lim))
			return 0;
	}
	return 1;
}

/* ---- image blocks ---- */

static int emit(psd_t *p, unsigned x, unsigned y, unsigned w, unsigned h, const uint8_t *rgb)
{
	size_t n = (size_t)w * h * 3;
	size_t k = 3;
	while (k < n && rgb[k] == rgb[0] && rgb[k + 1] == rgb[1] && rgb[k + 2] == rgb[2])
		k += 3;
	if (k >= n)
		return p->hooks.rect(p, x, y, w, h, (meta_rgb_t)rgb[0] << 16 | (meta_rgb_t)rgb[1] << 8 | rgb[2]);
	return p->hooks.image(p, x, y, w, h, rgb);
}

int psd_out_fail(psd_t *p)
{
	io_transport_t *t = p->dev->out;
	if (p->out.err == META_ENOMEM)
		return dev_fail(p->dev, META_ENOMEM, "out of memory");
	if (t && io_failed(t)) {
		return dev_fail(p->dev, dev_code_of_errno(io_errno(t)), "%s", io_error(t));
	}
	return dev_fail(p->dev, META_EIO, "%s: write failed", t ? io_name(t) : "<output>");
}

int psd_flush(psd_t *p)
{
	psd_block_t *b = &p->blk;
	if (!b->active)
		return 0;
	b->active = 0;
	unsigned w = b->w ? b->w : b->fill;
	unsigned full = b->w && b->fill < b->w ? b->nrows - 1 : b->nrows;
	int rc = 0;
	if (full) {
		size_t row = (size_t)w * 3;
		if (b->dir > 0)   /* rows went up: put the top row first */
			for (unsigned i = 0, j = full - 1; i < j; i++, j--)
				for (size_t k = 0; k < row; k++) {
					uint8_t t = b->pix[i * row + k];
					b->pix[i * row + k] = b->pix[j * row + k];
					b->pix[j * row + k] = t;
				}
		unsigned ybot = b->dir > 0 ? b->y0 : b->y0 - (full - 1);
		rc = emit(p, b->x0, ybot, w, full, b->pix);
	}
	if (!rc && full < b->nrows) {
		unsigned y = b->y0 + (unsigned)((int)(b->nrows - 1) * b->dir);
		rc = emit(p, b->x0, y, b->fill, 1, b->pix + (size_t)(b->nrows - 1) * w * 3);
	}
	return rc;
}

static int room(psd_t *p, size_t need)
{
	psd_block_t *b = &p->blk;
	if (need <= b->cap)
		return 0;
	size_t n = b->cap ? b->cap : 4096;
	while (n < need)
		n *= 2;
	uint8_t *q = realloc(b->pix, n);
	if (!q)
		return dev_fail(p->dev, META_ENOMEM, "out of memory");
	b->pix = q;
	b->cap = n;
	return 0;
}

int psd_span(psd_t *p, unsigned x, unsigned y, unsigned n, meta_rgb_t rgb)
{
	psd_block_t *b = &p->blk;
	int rc;
	psd_grow(p, (int64_t)x * 1000, (int64_t)y * 1000, (int64_t)(x + n) * 1000, (int64_t)(y + 1) * 1000);
	if (b->active) {
		unsigned cury = b->y0 + (unsigned)((int)(b->nrows - 1) * b->dir);
		int complete = b->w ? b->fill == b->w : 0;
		size_t used = (size_t)(b->nrows - 1) * (b->w ? b->w : 0) * 3 + (size_t)b->fill * 3;
		if (!complete && y == cury && x == b->x0 + b->fill && (!b->w || b->fill + n <= b->w)) {
			/* continues the row */
		} else if ((complete || (!b->w && b->nrows == 1)) && x == b->x0 && (b->w ? n <= b->w : 1) &&
				used + (size_t)(b->w ? b->w : b->fill) * 3 <= BLOCK_MAX &&
				(b->dir ? (long)y == (long)cury + b->dir : (y + 1 == cury || y == cury + 1)) &&
				(b->w || n <= b->fill)) {
			if (!b->w)
				b->w = b->fill;
			if (!b->dir)
				b->dir = y < cury ? -1 : 1;
			b->nrows++;
			b->fill = 0;
		} else {
			if ((rc = psd_flush(p)))
				return rc;
		}
	}
	if (!b->active) {
		b->active = 1;
		b->x0 = x;
		b->w = 0;
		b->y0 = y;
		b->dir = 0;
		b->nrows = 1;
		b->fill = 0;
	}
	size_t at = ((size_t)(b->nrows - 1) * (b->w ? b->w : 0) + b->fill) * 3;
	if ((rc = room(p, at + (size_t)n * 3)))
		return rc;
	uint8_t *q = b->pix + at;
	for (unsigned k = 0; k < n; k++, q += 3) {
		q[0] = (uint8_t)(rgb >> 16);
		q[1] = (uint8_t)(rgb >> 8);
		q[2] = (uint8_t)rgb;
	}
	b->fill += n;
	return 0;
}

int psd_row(psd_t *p, unsigned x, unsigned y, const meta_run_t *runs, size_t nruns)
{
	for (size_t k = 0; k < nruns && x < p->page.width; k++) {
		unsigned n = runs[k].count;
		if (n > p->page.width - x)
			n = p->page.width - x;
		int rc = psd_span(p, x, y, n, runs[k].rgb);
		if (rc)
			return rc;
		x += n;
	}
	return 0;
}

int psd_dev_span(dev_device_t *d, unsigned x, unsigned y, unsigned n, meta_rgb_t rgb)
{
	return psd_span(d->priv, x, y, n, rgb);
}

int psd_dev_row(dev_device_t *d, unsigned x, unsigned y, const meta_run_t *runs, size_t nruns)
{
	return psd_row(d->priv, x, y, runs, nruns);
}

int psd_dev_clear(dev_device_t *d, const dev_page_t *pg, meta_rgb_t rgb)
{
	psd_t *p = d->priv;
	(void)pg;   /* the page came with begin_page */
	int rc = psd_flush(p);
	if (rc)
		return rc;
	psd_grow(p, 0, 0, (int64_t)p->page.width * 1000, (int64_t)p->page.height * 1000);
	return p->hooks.rect(p, 0, 0, p->page.width, p->page.height, rgb);
}

int psd_paint_begin(psd_t *p, const dev_path_t *dp, const dev_state_t *st, int stroke)
{
	int rc = psd_flush(p);
	if (rc)
		return rc;
	psd_grow_path(p, dp, st, stroke);
	return 0;
}

void psd_release(psd_t *p)
{
	free(p->blk.pix);
	p->blk.pix = NULL;
	p->blk.cap = 0;
	p->blk.active = 0;
}

/* ---- samples: grey and dither ---- */

/* Bayer's 8 x 8 threshold matrix (0..63): M2n = [4M 4M+2; 4M+3 4M+1], the finest 2 x 2 step
 * in the highest bits, so that neighbouring dots have the most different thresholds. */
static unsigned bayer(unsigned x, unsigned y)
{
	unsigned v = 0;
	for (int k = 0; k < 3; k++) {
		unsigned a = x >> k & 1, b = y >> k & 1;
		v = v << 2 | ((a ^ b) << 1 | b);
	}
	return v;
}

int psd_samples(psd_t *p, unsigned x, unsigned y, unsigned w, unsigned h, const uint8_t *rgb, psd_samples_t *out)
{
	memset(out, 0, sizeof *out);
	out->width = w, out->height = h, out->bpc = 8, out->comps = p->grey ? 1 : 3;
	if (!p->grey) {
		out->data = rgb;
		out->n = (size_t)w * h * 3;
		return 0;
	}
	size_t npx = (size_t)w * h;
	if (!p->dither) {
		if (!(out->owned = malloc(npx ? npx : 1)))
			return dev_fail(p->dev, META_ENOMEM, "out of memory");
		for (size_t k = 0; k < npx; k++)
			out->owned[k] = (uint8_t)psd_luma((meta_rgb_t)rgb[3 * k] << 16 | (meta_rgb_t)rgb[3 * k + 1] << 8 | rgb[3 * k + 2]);
		out->data = out->owned;
		out->n = npx;
		return 0;
	}
	/* printer dots covering the image, counted from the page's corner so that neighbouring
	 * images continue one pattern */
	double k = p->dither / 72.0;
	long dx0 = lround((p->ox + p->sx * x) * k), dx1 = lround((p->ox + p->sx * (x + w)) * k);
	long dy0 = lround((p->oy + p->sy * y) * k), dy1 = lround((p->oy + p->sy * (y + h)) * k);
	unsigned dw = dx1 > dx0 ? (unsigned)(dx1 - dx0) : 1, dh = dy1 > dy0 ? (unsigned)(dy1 - dy0) : 1;
	size_t row = (dw + 7) / 8;
	if (!(out->owned = calloc(row * dh, 1)))
		return dev_fail(p->dev, META_ENOMEM, "out of memory (a dither of %u x %u dots)", dw, dh);
	for (unsigned r = 0; r < dh; r++) {
		unsigned sy = (unsigned)((uint64_t)r * h / dh);
		unsigned long Y = (unsigned long)(dy1 - 1 - r);
		for (unsigned c = 0; c < dw; c++) {
			const uint8_t *q = rgb + 3 * ((size_t)sy * w + (size_t)((uint64_t)c * w / dw));
			unsigned g = psd_luma((meta_rgb_t)q[0] << 16 | (meta_rgb_t)q[1] << 8 | q[2]);
			unsigned long X = (unsigned long)(dx0 + c);
			/* white when the level is above the dot's threshold (0.5 .. 63.5)/64 of 255 */
			if (g * 128 > (2 * bayer((unsigned)(X & 7), (unsigned)(Y & 7)) + 1) * 255)
				out->owned[r * row + c / 8] |= (uint8_t)(0x80 >> (c % 8));
		}
	}
	out->data = out->owned;
	out->n = row * dh;
	out->width = dw, out->height = dh, out->bpc = 1, out->comps = 1;
	return 0;
}

/* ---- tokens ---- */

void psd_sep(psd_t *p)
{
	if (p->wrap && p->col > p->wrap) {
		dev_w_write(&p->out, "\n", 1);
		p->col = 0;
	} else if (p->col) {
		dev_w_write(&p->out, " ", 1);
		p->col++;
	}
}

void psd_tok(psd_t *p, const char *t)
{
	psd_sep(p);
	dev_w_puts(&p->out, t);
	p->col += (int)strlen(t);
}

void psd_int(psd_t *p, long long v)
{
	psd_sep(p);
	dev_w_int(&p->out, v);
	p->col += v < 0 ? 2 : 1;
	for (long long a = v < 0 ? -v : v; a >= 10; a /= 10)
		p->col++;
}

void psd_newline(psd_t *p)
{
	if (p->col) {
		dev_w_write(&p->out, "\n", 1);
		p->col = 0;
	}
}

void psd_string(dev_writer_t *o, const char *t)
{
	dev_w_puts(o, "(");
	for (; *t; t++) {
		if (*t == '(' || *t == ')' || *t == '\\')
			dev_w_puts(o, "\\");
		dev_w_write(o, t, 1);
	}
	dev_w_puts(o, ")");
}

/* ---- small helpers ---- */

unsigned psd_luma(meta_rgb_t c)
{
	unsigned r = c >> 16 & 255, g = c >> 8 & 255, b = c & 255;
	return (299 * r + 587 * g + 114 * b + 500) / 1000;
}

void psd_unit(unsigned v, char *buf, size_t n)
{
	if (v == 0 || v >= 255) {
		snprintf(buf, n, "%s", v ? "1" : "0");
		return;
	}
	/* Readers turn the number d into a byte three ways: rounding d x 255 (Ghostscript,
	 * poppler's splash), truncating it (MuPDF), and cairo's floor(d x 65535 + 1/2) >> 8
	 * (pdftocairo), which truncates d x 255 x 257/256. All three give v back when
	 * d x 255 lies in [v, v + w), w = min(1/2, (255.5 - v) / 257): 1/2 up to 127, then down
	 * to 0.006 for 254. v/255 to three places (.188 for 48: 47.94) missed a third of the
	 * bytes in MuPDF. Written: the fewest decimals that put a value inside the middle four
	 * fifths of that range (a margin for readers in single precision), the one nearest its
	 * middle. */
	double w = fmin(0.5, (255.5 - v) / 257.0), lo = v + 0.1 * w, hi = v + 0.9 * w;
	unsigned scale = 10;
	for (int digits = 1; digits <= 6; digits++, scale *= 10) {
		unsigned m = (unsigned)((v + 0.5 * w) * scale / 255 + 0.5);
		double back = (double)m * 255 / scale;
		if ((back >= lo && back <= hi) || digits == 6) {
			snprintf(buf, n, ".%0*u", digits, m);
			size_t k = strlen(buf);
			while (k > 1 && buf[k - 1] == '0')
				buf[--k] = 0;
			return;
		}
	}
}

long long psd_grid(int64_t t)
{
	const int64_t q = 1000 / PSD_GRID;
	return t >= 0 ? (t + q / 2) / q : -((-t + q / 2) / q);
}

int psd_straight(long long ux, long long uy, long long vx, long long vy)
{
	const long long lim = 1LL << 30;
	if (ux <= -lim || ux >= lim || uy <= -lim || uy >= lim || vx <= -lim || vx >= lim ||
			vy <= -lim || vy >= lim)
		return 0;
	return ux * vy == uy * vx && ux * vx + uy * vy > 0;
}

void psd_date(long long epoch, int pdf, char *buf, size_t n)
{
	time_t t = (time_t)epoch;
	struct tm tm;
	gmtime_r(&t, &tm);
	strftime(buf, n, pdf ? "D:%Y%m%d%H%M%SZ" : "%Y-%m-%dT%H:%M:%SZ", &tm);
}
