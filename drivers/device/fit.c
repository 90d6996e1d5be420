/* fit.c: a model page mapped onto a device raster: fit rules, paths, spans, resampled images. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "device/fit.h"

/* ---- the mapping ---- */

int dev_fit_by_name(const char *s)
{
	if (!s)
		return -1;
	if (!strcmp(s, "aspect"))
		return DEV_FIT_ASPECT;
	if (!strcmp(s, "fill"))
		return DEV_FIT_FILL;
	if (!strcmp(s, "stretch"))
		return DEV_FIT_STRETCH;
	return -1;
}

int dev_fit_options(dev_device_t *d)
{
	char buf[64];
	d->fit = DEV_FIT_ASPECT;
	d->letterbox = 0x000000;
	if (dev_option(d, "fit", buf, sizeof buf) && (d->fit = dev_fit_by_name(buf)) < 0)
		return dev_fail(d, DEV_EUSAGE, "%s: fit must be aspect, fill or stretch, not '%s'", d->ops->name, buf);
	if (dev_option(d, "letterbox", buf, sizeof buf)) {
		char *e;
		unsigned long v = buf[0] == '#' && strlen(buf) == 7 ? strtoul(buf + 1, &e, 16) : 0;
		if (buf[0] != '#' || strlen(buf) != 7 || *e || strspn(buf + 1, "0123456789abcdefABCDEF") != 6)
			return dev_fail(d, DEV_EUSAGE, "%s: letterbox must be a colour #rrggbb, not '%s'", d->ops->name, buf);
		d->letterbox = (meta_rgb_t)v;
	}
	return 0;
}

static int64_t clamp_size(double v, int64_t lo, int64_t hi)
{
	int64_t n = (int64_t)llround(v);
	return n < lo ? lo : n > hi ? hi : n;
}

int dev_fit_map(dev_map_t *m, unsigned model_w, unsigned model_h, unsigned dev_w, unsigned dev_h,
		double pixel_aspect, int fit)
{
	memset(m, 0, sizeof *m);
	m->model_w = model_w;
	m->model_h = model_h;
	double pa = pixel_aspect == 0 ? 1.0 : pixel_aspect;
	if (!(pa > 0) || !isfinite(pa) || fit < DEV_FIT_ASPECT || fit > DEV_FIT_STRETCH ||
			model_w == 0 || model_h == 0)
		return DEV_EUSAGE;
	if (dev_w == 0 || dev_h == 0 || (dev_w == model_w && dev_h == model_h &&
			(pa == 1.0 || fit == DEV_FIT_STRETCH))) {
		m->width = model_w;
		m->height = model_h;
		m->pw = model_w;
		m->ph = model_h;
		m->sx = m->sy = m->wscale = 1.0;
		m->identity = 1;
		return 0;
	}
	m->width = dev_w;
	m->height = dev_h;
	/* s: device pixel heights per model pixel; a model pixel is s/pa device pixels wide */
	double sa = (double)dev_w * pa / model_w, sb = (double)dev_h / model_h;
	if (fit == DEV_FIT_STRETCH) {
		m->pw = dev_w;
		m->ph = dev_h;
	} else if (fit == DEV_FIT_ASPECT) {
		double s = sa < sb ? sa : sb;
		m->pw = clamp_size(model_w * s / pa, 1, dev_w);
		m->ph = clamp_size(model_h * s, 1, dev_h);
	} else {
		double s = sa > sb ? sa : sb;
		m->pw = clamp_size(model_w * s / pa, dev_w, INT64_C(1) << 40);
		m->ph = clamp_size(model_h * s, dev_h, INT64_C(1) << 40);
	}
	/* centred; an odd pixel left over goes to the right and top bar (or crop) */
	m->ox = m->pw <= dev_w ? ((int64_t)dev_w - m->pw) / 2 : -((m->pw - (int64_t)dev_w) / 2);
	m->oy = m->ph <= dev_h ? ((int64_t)dev_h - m->ph) / 2 : -((m->ph - (int64_t)dev_h) / 2);
	m->sx = (double)m->pw / model_w;
	m->sy = (double)m->ph / model_h;
	m->wscale = sqrt(m->sx * m->sy);
	return 0;
}

void dev_fit_path(const dev_map_t *m, scan_path_t *p)
{
	int64_t ox = m->ox * 1000, oy = m->oy * 1000;
	for (size_t k = 0; k < p->npts; k++) {
		p->pts[k].x = ox + scan_round((double)p->pts[k].x * m->sx);
		p->pts[k].y = oy + scan_round((double)p->pts[k].y * m->sy);
	}
}

int64_t dev_fit_width(const dev_map_t *m, int64_t w)
{
	return scan_round((double)(w < 1000 ? 1000 : w) * m->wscale);
}

int64_t dev_fit_chord_radius(const dev_map_t *m, int64_t r)
{
	double s = m->sx > m->sy ? m->sx : m->sy;
	double v = (double)r * s;
	return v > 1e15 ? (int64_t)1e15 : v < 1 ? 1 : (int64_t)v;
}

/* Floor division of a by b > 0. */
static int64_t fdiv(int64_t a, int64_t b)
{
	int64_t q = a / b;
	return (a % b != 0 && a < 0) ? q - 1 : q;
}

/* The first device column (relative to the page's origin) whose centre lies at or right of the
 * model edge a (whole model pixels): the smallest u with (u + 1/2) * n >= a * pw... in integers,
 * so that adjacent model pixels share their device pixels without gap or overlap. */
static int64_t first_at(int64_t a, int64_t pw, int64_t n)
{
	/* smallest u with (2u + 1) * n >= 2 a pw  <=>  u >= (2 a pw - n) / (2 n) */
	int64_t num = 2 * a * pw - n, den = 2 * n;
	return -fdiv(-num, den);
}

static int64_t col_at(const dev_map_t *m, int64_t a)
{
	return m->ox + first_at(a, m->pw, m->model_w);
}

static int64_t row_at(const dev_map_t *m, int64_t a)
{
	return m->oy + first_at(a, m->ph, m->model_h);
}

static int rect(render_t *rr, int64_t x0, int64_t y0, int64_t x1, int64_t y1, meta_rgb_t rgb)
{
	if (x0 >= x1 || y0 >= y1)
		return 0;
	scan_path_t r = { 0 };
	int rc = META_ENOMEM;
	if (!scan_path_move(&r, x0 * 1000, y0 * 1000) && !scan_path_draw(&r, x1 * 1000, y0 * 1000) &&
			!scan_path_draw(&r, x1 * 1000, y1 * 1000) && !scan_path_draw(&r, x0 * 1000, y1 * 1000))
		rc = render_fill(rr, &r, META_RULE_NON_ZERO, rgb);
	scan_path_free(&r);
	return rc;
}

int dev_fit_bars(const dev_map_t *m, render_t *rr, meta_rgb_t rgb)
{
	int64_t w = m->width, h = m->height;
	int64_t x0 = m->ox < 0 ? 0 : m->ox, x1 = m->ox + m->pw > w ? w : m->ox + m->pw;
	int64_t y0 = m->oy < 0 ? 0 : m->oy, y1 = m->oy + m->ph > h ? h : m->oy + m->ph;
	int rc = rect(rr, 0, 0, x0, h, rgb);
	if (!rc)
		rc = rect(rr, x1, 0, w, h, rgb);
	if (!rc)
		rc = rect(rr, x0, 0, x1, y0, rgb);
	if (!rc)
		rc = rect(rr, x0, y1, x1, h, rgb);
	return rc;
}

int dev_fit_span(const dev_map_t *m, render_t *rr, int64_t x, int64_t y, int64_t n, meta_rgb_t rgb)
{
	int64_t xe = x + n;
	if (x < 0)
		x = 0;
	if (xe > m->model_w)
		xe = m->model_w;
	if (x >= xe || y < 0 || y >= m->model_h)
		return 0;
	int64_t u0 = col_at(m, x), u1 = col_at(m, xe), v0 = row_at(m, y), v1 = row_at(m, y + 1);
	if (v0 < 0)
		v0 = 0;
	if (v1 > m->height)
		v1 = m->height;
	for (int64_t v = v0; v < v1 && u0 < u1; v++) {
		int rc = render_span(rr, u0, v, u1 - u0, rgb);
		if (rc)
			return rc;
	}
	return 0;
}

int dev_fit_stroke_aniso(const dev_map_t *m, render_t *rr, scan_ctx_t *ctx, const scan_path_t *p,
		const scan_style_t *st, meta_rgb_t rgb, scan_path_t *iso, scan_path_t *pieces)
{
	/* iso: device coordinates with x in units of a device pixel's height (x * sy / sx), where
	 * the model is scaled alike in both axes, so §5.3's pieces keep the model's shape */
	double k = m->sy / m->sx;
	int64_t ox = scan_round((double)m->ox * 1000.0 * k), oy = m->oy * 1000;
	scan_path_reset(iso);
	for (size_t s = 0; s < p->nsubs; s++) {
		const scan_subpath_t *sub = &p->subs[s];
		for (size_t i = 0; i < sub->n; i++) {
			const scan_pt_t *q = &p->pts[sub->start + i];
			int64_t x = ox + scan_round((double)q->x * m->sy), y = oy + scan_round((double)q->y * m->sy);
			if (i ? scan_path_draw(iso, x, y) : scan_path_move(iso, x, y))
				return META_ENOMEM;
		}
		if (sub->closed)
			scan_path_close(iso);
	}
	iso->open = 0;
	scan_style_t is = *st;
	is.width = scan_round((double)(st->width < 1000 ? 1000 : st->width) * m->sy);
	is.dash = NULL;
	is.ndash = 0;
	scan_path_reset(pieces);
	double wi = ceil((double)m->width * k) + 1;
	int rc = scan_stroke_pieces(ctx, iso, &is, wi > 1e9 ? 1000000000 : (int)wi, (int)m->height, pieces);
	if (rc || pieces->npts == 0)
		return rc;
	for (size_t i = 0; i < pieces->npts; i++)
		pieces->pts[i].x = scan_round((double)pieces->pts[i].x / k);
	return render_fill(rr, pieces, META_RULE_NON_ZERO, rgb);
}

/* ---- images ---- */

struct dev_fit_img {
	const dev_map_t *m;
	int64_t x;                  /* the image's left model column */
	int64_t cx0, cx1, cy0, cy1; /* the image clipped to the model page (pixels) */
	int64_t u0, u1, v0, v1;     /* device pixels it covers, clipped to the raster */
	double *fa, *fb;            /* per device column: its footprint in model x, clipped */
	float *lin_row;             /* one model row in linear light, columns cx0 .. cx1 */
	double *hs, *acc, *accw;    /* one row resampled in x; the pending device row */
	int64_t pend;               /* the device row in acc, or -1 */
	meta_run_t *runs;
	float lin[256];             /* sRGB byte -> linear light */
	float mid[255];             /* linear light halfway between consecutive bytes */
};

static float srgb_to_linear(double c)
{
	c /= 255.0;
	return (float)(c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4));
}

/* The byte whose linear value is nearest (in linear light) to v. */
static unsigned to_byte(const dev_fit_img_t *im, double v)
{
	unsigned lo = 0, hi = 255;   /* answer in [lo, hi] */
	while (lo < hi) {
		unsigned md = (lo + hi) / 2;
		if (v > im->mid[md])
			lo = md + 1;
		else
			hi = md;
	}
	return lo;
}

dev_fit_img_t *dev_fit_image_new(const dev_map_t *m, int64_t x, int64_t y, int64_t w, int64_t h)
{
	dev_fit_img_t *im = calloc(1, sizeof *im);
	if (!im)
		return NULL;
	im->m = m;
	im->x = x;
	im->pend = -1;
	im->cx0 = x < 0 ? 0 : x;
	im->cx1 = x + w > m->model_w ? m->model_w : x + w;
	im->cy0 = y < 0 ? 0 : y;
	im->cy1 = y + h > m->model_h ? m->model_h : y + h;
	if (im->cx0 >= im->cx1 || im->cy0 >= im->cy1)
		return im;   /* off the page */
	im->u0 = col_at(m, im->cx0);
	im->u1 = col_at(m, im->cx1);
	im->v0 = row_at(m, im->cy0);
	im->v1 = row_at(m, im->cy1);
	if (im->u0 < 0)
		im->u0 = 0;
	if (im->u1 > m->width)
		im->u1 = m->width;
	if (im->v0 < 0)
		im->v0 = 0;
	if (im->v1 > m->height)
		im->v1 = m->height;
	if (im->u0 >= im->u1 || im->v0 >= im->v1) {
		im->cx1 = im->cx0;   /* nothing to paint */
		return im;
	}
	size_t nu = (size_t)(im->u1 - im->u0), nx = (size_t)(im->cx1 - im->cx0);
	im->fa = malloc(nu * sizeof *im->fa);
	im->fb = malloc(nu * sizeof *im->fb);
	im->lin_row = malloc(nx * 3 * sizeof *im->lin_row);
	im->hs = malloc(nu * 3 * sizeof *im->hs);
	im->acc = malloc(nu * 3 * sizeof *im->acc);
	im->accw = malloc(nu * sizeof *im->accw);
	im->runs = malloc(nu * sizeof *im->runs);
	if (!im->fa || !im->fb || !im->lin_row || !im->hs || !im->acc || !im->accw || !im->runs) {
		dev_fit_image_free(im);
		return NULL;
	}
	for (size_t k = 0; k < nu; k++) {
		double u = (double)(im->u0 + (int64_t)k - m->ox);
		double a = u / m->sx, b = (u + 1) / m->sx;
		im->fa[k] = a < im->cx0 ? (double)im->cx0 : a;
		im->fb[k] = b > im->cx1 ? (double)im->cx1 : b;
	}
	for (int c = 0; c < 256; c++)
		im->lin[c] = srgb_to_linear(c);
	for (int c = 0; c < 255; c++)
		im->mid[c] = (float)(((double)im->lin[c] + im->lin[c + 1]) / 2.0);
	return im;
}

void dev_fit_image_free(dev_fit_img_t *im)
{
	if (!im)
		return;
	free(im->fa);
	free(im->fb);
	free(im->lin_row);
	free(im->hs);
	free(im->acc);
	free(im->accw);
	free(im->runs);
	free(im);
}

/* Hand the pending device row to the renderer, colours merged into runs. */
static int emit(dev_fit_img_t *im, render_t *rr)
{
	size_t nu = (size_t)(im->u1 - im->u0), nr = 0;
	for (size_t k = 0; k < nu; k++) {
		double w = im->accw[k];
		meta_rgb_t c = 0;
		if (w > 0)
			c = (meta_rgb_t)to_byte(im, im->acc[3 * k] / w) << 16 |
				(meta_rgb_t)to_byte(im, im->acc[3 * k + 1] / w) << 8 |
				(meta_rgb_t)to_byte(im, im->acc[3 * k + 2] / w);
		if (nr && im->runs[nr - 1].rgb == c) {
			im->runs[nr - 1].count++;
		} else {
			im->runs[nr].rgb = c;
			im->runs[nr].count = 1;
			nr++;
		}
	}
	int64_t v = im->pend;
	im->pend = -1;
	return render_row(rr, im->u0, v, im->runs, nr);
}

int dev_fit_image_row(dev_fit_img_t *im, render_t *rr, int64_t y, const meta_run_t *runs, size_t nruns)
{
	const dev_map_t *m = im->m;
	if (im->cx0 >= im->cx1 || y < im->cy0 || y >= im->cy1)
		return 0;
	/* the row in linear light, clipped to the page */
	int64_t x = im->x;
	for (size_t k = 0; k < nruns; k++) {
		int64_t a = x < im->cx0 ? im->cx0 : x, b = x + runs[k].count;
		if (b > im->cx1)
			b = im->cx1;
		float r = im->lin[runs[k].rgb >> 16 & 255], g = im->lin[runs[k].rgb >> 8 & 255];
		float bl = im->lin[runs[k].rgb & 255];
		for (int64_t i = a; i < b; i++) {
			float *q = im->lin_row + 3 * (i - im->cx0);
			q[0] = r;
			q[1] = g;
			q[2] = bl;
		}
		x += runs[k].count;
	}
	/* resampled in x: each device column the sum over its footprint, weighted by overlap */
	size_t nu = (size_t)(im->u1 - im->u0);
	for (size_t k = 0; k < nu; k++) {
		double a = im->fa[k], b = im->fb[k], s0 = 0, s1 = 0, s2 = 0;
		for (int64_t i = (int64_t)floor(a); (double)i < b; i++) {
			double lo = (double)i > a ? (double)i : a, hi = (double)(i + 1) < b ? (double)(i + 1) : b;
			double w = hi - lo;
			if (w <= 0 || i < im->cx0 || i >= im->cx1)
				continue;
			const float *q = im->lin_row + 3 * (i - im->cx0);
			s0 += w * q[0];
			s1 += w * q[1];
			s2 += w * q[2];
		}
		im->hs[3 * k] = s0;
		im->hs[3 * k + 1] = s1;
		im->hs[3 * k + 2] = s2;
	}
	/* the device rows whose footprints meet model row y, top first; only the lowest can go on
	 * into the next model row, and it stays pending */
	int64_t vt = (int64_t)ceil((double)m->oy + (double)(y + 1) * m->sy) - 1;
	int64_t vb = (int64_t)floor((double)m->oy + (double)y * m->sy);
	if (vt > im->v1 - 1)
		vt = im->v1 - 1;
	if (vb < im->v0)
		vb = im->v0;
	for (int64_t v = vt; v >= vb; v--) {
		double fb = (double)(v - m->oy) / m->sy, ft = (double)(v + 1 - m->oy) / m->sy;
		if (fb < im->cy0)
			fb = (double)im->cy0;
		if (ft > im->cy1)
			ft = (double)im->cy1;
		double lo = fb > (double)y ? fb : (double)y, hi = ft < (double)(y + 1) ? ft : (double)(y + 1);
		double wy = hi - lo;
		if (wy <= 0)
			continue;
		if (im->pend != v) {
			if (im->pend >= 0) {
				int rc = emit(im, rr);
				if (rc)
					return rc;
			}
			memset(im->acc, 0, nu * 3 * sizeof *im->acc);
			memset(im->accw, 0, nu * sizeof *im->accw);
			im->pend = v;
		}
		for (size_t k = 0; k < nu; k++) {
			im->acc[3 * k] += wy * im->hs[3 * k];
			im->acc[3 * k + 1] += wy * im->hs[3 * k + 1];
			im->acc[3 * k + 2] += wy * im->hs[3 * k + 2];
			im->accw[k] += wy * (im->fb[k] - im->fa[k]);
		}
		if (fb >= (double)y) {
			int rc = emit(im, rr);
			if (rc)
				return rc;
		}
	}
	return 0;
}
