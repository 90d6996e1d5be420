/* test_devres.c: rendering at a device's own raster: fit rules, pixel aspect, thin lines, bars,
 * resampled images, banded against whole, and the identity. */
#include <math.h>
#include <stdlib.h>
#include "device/device.h"
#include "unit.h"

/* The raster the test device declares in open(). */
static unsigned cfg_w, cfg_h;
static double cfg_aspect;
static int cfg_fit;
static meta_rgb_t cfg_box = 0x123456;

/* A raster device that keeps the last page in memory, top row first. */
typedef struct {
	uint8_t *pix;
	unsigned w, h, mw, mh, rows_seen, bad_band;
} cap_t;

static int c_open(dev_device_t *d)
{
	d->raster_width = cfg_w;
	d->raster_height = cfg_h;
	d->pixel_aspect = cfg_aspect;
	d->fit = cfg_fit;
	d->letterbox = cfg_box;
	return d->options ? dev_fit_options(d) : 0;
}

static const dev_option_t cap_options[] = { DEV_FIT_OPTIONS, { NULL, NULL } };

static int c_begin(dev_device_t *d, const dev_page_t *pg)
{
	cap_t *c = d->priv;
	free(c->pix);
	c->w = pg->width;
	c->h = pg->height;
	c->mw = pg->model_width;
	c->mh = pg->model_height;
	c->rows_seen = 0;
	c->pix = calloc((size_t)pg->width * pg->height, 3);
	return c->pix ? 0 : dev_fail(d, META_ENOMEM, "out of memory");
}

static int c_band(dev_device_t *d, const render_band_t *b)
{
	cap_t *c = d->priv;
	if (b->width != c->w || b->page_height != c->h || b->y0 != c->rows_seen)
		c->bad_band = 1;
	for (unsigned k = 0; k < b->nrows && b->y0 + k < c->h; k++)
		memcpy(c->pix + (size_t)(b->y0 + k) * c->w * 3, b->pix + k * b->stride, (size_t)c->w * 3);
	c->rows_seen += b->nrows;
	return 0;
}

static const dev_ops_t cap_ops = {
	.name = "cap", .description = "test capture", .caps = DEV_CAP_RASTER, .priv_size = sizeof(cap_t),
	.option_list = cap_options, .open = c_open, .begin_page = c_begin, .write_band = c_band,
};

/* Replay text onto the capture device; returns its state (pix owned by the caller). */
static const char *cfg_options;
static unsigned cfg_aa;

static cap_t play(const char *text, unsigned band_rows, int *rc)
{
	cap_t out = { 0 };
	meta_reader_t *r = meta_reader_mem(text, strlen(text), "t.meta");
	dev_device_t *d = dev_new(&cap_ops, NULL);
	d->band_rows = band_rows;
	d->options = cfg_options;
	d->antialias = cfg_aa;
	*rc = dev_play(r, d);
	if (*rc)
		printf("# %s\n", dev_error(d));
	out = *(cap_t *)d->priv;
	((cap_t *)d->priv)->pix = NULL;
	dev_free(d);
	meta_reader_free(r);
	return out;
}

/* Colour of device pixel (u, v), v counted from the top. */
static meta_rgb_t px(const cap_t *c, unsigned u, unsigned v)
{
	const uint8_t *q = c->pix + ((size_t)v * c->w + u) * 3;
	return (meta_rgb_t)q[0] << 16 | (meta_rgb_t)q[1] << 8 | q[2];
}

/* Extents of the pixels of colour rgb. */
static void extents(const cap_t *c, meta_rgb_t rgb, int *x0, int *x1, int *y0, int *y1)
{
	*x0 = *y0 = 1 << 30;
	*x1 = *y1 = -1;
	for (unsigned v = 0; v < c->h; v++)
		for (unsigned u = 0; u < c->w; u++)
			if (px(c, u, v) == rgb) {
				if ((int)u < *x0) *x0 = (int)u;
				if ((int)u > *x1) *x1 = (int)u;
				if ((int)v < *y0) *y0 = (int)v;
				if ((int)v > *y1) *y1 = (int)v;
			}
}

/* DEVRES_DUMP=1 writes the pictures as PPM files in the current directory, to look at. */
static void dump(const cap_t *c, const char *name)
{
	if (!getenv("DEVRES_DUMP"))
		return;
	char fn[64];
	snprintf(fn, sizeof fn, "devres-%s.ppm", name);
	FILE *f = fopen(fn, "wb");
	if (!f)
		return;
	fprintf(f, "P6\n%u %u\n255\n", c->w, c->h);
	fwrite(c->pix, 3, (size_t)c->w * c->h, f);
	fclose(f);
}

static void set(unsigned w, unsigned h, double aspect, int fit)
{
	cfg_w = w;
	cfg_h = h;
	cfg_aspect = aspect;
	cfg_fit = fit;
}

static void test_aspect_circle(void)
{
	/* a 4:3 model page on mode 13h: 320 x 200 pixels of aspect 5:6 fill the 4:3 screen */
	set(320, 200, 5.0 / 6.0, DEV_FIT_ASPECT);
	int rc;
	cap_t c = play("LOCUS-META 1\npage 400 300\ncolour #ff0000\nfill\ncircle 200 150 100\nend\nend-page\n", 0, &rc);
	CHECK(rc == 0 && c.w == 320 && c.h == 200 && c.mw == 400 && c.mh == 300 && !c.bad_band,
		"13h page reaches the device at 320x200, model 400x300 in dev_page_t");
	int x0, x1, y0, y1;
	extents(&c, 0xff0000, &x0, &x1, &y0, &y1);
	int wx = x1 - x0 + 1, wy = y1 - y0 + 1;
	/* 200 model pixels: 160 device pixels across, 133.3 down; on the screen 160 * 5/6 = 133.3 */
	CHECK(abs(wx - 160) <= 1 && abs(wy - 133) <= 1, "circle spans %d x %d device pixels (160 x 133)", wx, wy);
	CHECK(fabs(wx * 5.0 / 6.0 - wy) <= 1.5, "circle stays round on the screen: %.1f x %d", wx * 5.0 / 6.0, wy);
	CHECK(px(&c, 0, 0) == 0xffffff && px(&c, 319, 199) == 0xffffff, "no bars: the page fills the mode");
	free(c.pix);
}

/* 1 if every device column in [a, b) (every row, when rows) holds a pixel of colour rgb. */
static int unbroken(const cap_t *c, meta_rgb_t rgb, unsigned a, unsigned b, int rows)
{
	for (unsigned i = a; i < b; i++) {
		int any = 0;
		for (unsigned k = 0; k < (rows ? c->w : c->h); k++)
			any |= (rows ? px(c, k, i) : px(c, i, k)) == rgb;
		if (!any)
			return 0;
	}
	return 1;
}

static void test_thin_lines(void)
{
	/* 1-pixel lines at a 4x shrink: every device column (row) the line crosses keeps a pixel */
	set(100, 100, 0, DEV_FIT_ASPECT);
	int rc1, rc2, rc3;
	cap_t h = play("LOCUS-META 1\npage 400 400\nwidth 0\nstroke\nmove 10 201.5\ndraw 390 201.5\nend\nend-page\n", 0, &rc1);
	cap_t v = play("LOCUS-META 1\npage 400 400\nstroke\nmove 123.2 10\ndraw 123.2 390\nend\nend-page\n", 0, &rc2);
	cap_t d = play("LOCUS-META 1\npage 400 400\nwidth 0.5\nstroke\nmove 20 30\ndraw 380 350\nend\nend-page\n", 0, &rc3);
	dump(&d, "thin");
	CHECK(rc1 == 0 && unbroken(&h, 0, 3, 97, 0), "a 1-pixel horizontal line survives a 4x shrink");
	CHECK(rc2 == 0 && unbroken(&v, 0, 3, 97, 1), "a 1-pixel vertical line survives a 4x shrink");
	CHECK(rc3 == 0 && unbroken(&d, 0, 6, 94, 0) && unbroken(&d, 0, 13, 92, 1),
		"a thin diagonal line survives a 4x shrink");
	int x0, x1, y0, y1;
	extents(&h, 0x000000, &x0, &x1, &y0, &y1);
	CHECK(y0 == y1 && y0 == 49, "the horizontal line is one device row (row %d..%d from the top)", y0, y1);
	extents(&v, 0x000000, &x0, &x1, &y0, &y1);
	CHECK(x0 == x1 && x0 == 30, "the vertical line is one device column (%d..%d)", x0, x1);
	free(h.pix);
	free(v.pix);
	free(d.pix);
}

static void test_wide_aspect(void)
{
	/* 13h: a 10-pixel model line is 10 * sy = 6.7 rows thick lying down and 10 * sx = 8 columns
	 * standing up, both 6.7 device pixel heights on the screen */
	set(320, 200, 5.0 / 6.0, DEV_FIT_ASPECT);
	int rc, x0, x1, y0, y1;
	cap_t c = play("LOCUS-META 1\npage 400 300\nwidth 10\ncolour #ff0000\nstroke\nmove 20 150\ndraw 180 150\nend\n"
		"colour #0000ff\nstroke\nmove 300 20\ndraw 300 280\nend\nend-page\n", 0, &rc);
	dump(&c, "wide");
	extents(&c, 0xff0000, &x0, &x1, &y0, &y1);
	int rows = y1 - y0 + 1;
	extents(&c, 0x0000ff, &x0, &x1, &y0, &y1);
	int cols = x1 - x0 + 1;
	CHECK(rc == 0 && rows >= 6 && rows <= 7 && cols == 8, "13h: a wide line is %d rows lying down and %d columns standing up "
		"(6.7 and 8: as thick on the screen)", rows, cols);
	free(c.pix);
}

static void test_dash_scaled(void)
{
	/* dashes are measured along the model path: at 2x, dash 10 10 is 20 device pixels on */
	set(200, 200, 0, DEV_FIT_ASPECT);
	int rc;
	cap_t c = play("LOCUS-META 1\npage 100 100\nwidth 2\ndash 10 10\nstroke\nmove 0 50\ndraw 100 50\nend\nend-page\n", 0, &rc);
	int runs = 0, ok = 1, len = 0;
	for (unsigned u = 0; u < 200; u++) {
		int black = px(&c, u, 99) == 0;
		if (black)
			len++;
		if ((!black || u == 199) && len) {
			runs++;
			ok &= len == 20;
			len = 0;
		}
	}
	CHECK(rc == 0 && runs == 5 && ok, "dash 10 10 at 2x: five dashes of 20 device pixels (%d runs)", runs);
	free(c.pix);
}

static const char *bars_page =
	"LOCUS-META 1\npage 100 100\nclear #00ff00\ncolour #ff0000\nwidth 4\n"
	"stroke\nmove -50 50\ndraw 150 50\nend\nstroke\nmove 50 -50\ndraw 50 150\nend\nend-page\n";

static void test_bars(void)
{
	int rc, ok = 1;
	/* aspect: a square page on 200 x 100 square pixels: bars left and right */
	set(200, 100, 0, DEV_FIT_ASPECT);
	cap_t c = play(bars_page, 0, &rc);
	dump(&c, "bars-aspect");
	for (unsigned v = 0; v < 100; v++)
		for (unsigned u = 0; u < 200; u++) {
			meta_rgb_t p = px(&c, u, v);
			if ((u < 50 || u >= 150) != (p == cfg_box))
				ok = 0;
		}
	CHECK(rc == 0 && ok, "aspect: bars of the letterbox colour exactly at columns 0-49 and 150-199, "
		"over what was drawn beyond the page");
	CHECK(px(&c, 60, 10) == 0x00ff00 && px(&c, 60, 49) == 0xff0000, "aspect: the page's clear and line inside");
	free(c.pix);
	/* aspect on a tall raster: bars top and bottom, the odd pixel to the top */
	set(100, 151, 0, DEV_FIT_ASPECT);
	c = play(bars_page, 0, &rc);
	ok = 1;
	for (unsigned v = 0; v < 151; v++)
		if ((v < 26 || v >= 126) != (px(&c, 10, v) == cfg_box))
			ok = 0;
	CHECK(rc == 0 && ok, "aspect: bars rows 0-25 and 126-150 (odd pixel at the top)");
	free(c.pix);
	/* fill: the square page covers 200 x 100, cropped top and bottom: no bar, line rows */
	set(200, 100, 0, DEV_FIT_FILL);
	c = play(bars_page, 0, &rc);
	int x0, x1, y0, y1;
	extents(&c, cfg_box, &x0, &x1, &y0, &y1);
	CHECK(rc == 0 && x1 < 0, "fill: no letterbox pixel");
	extents(&c, 0xff0000, &x0, &x1, &y0, &y1);
	CHECK(x0 == 0 && x1 == 199 && y0 == 0 && y1 == 99, "fill: the lines reach every edge (cropped)");
	CHECK(px(&c, 10, 46) == 0xff0000 && px(&c, 10, 53) == 0xff0000 && px(&c, 10, 45) == 0x00ff00 &&
		px(&c, 10, 54) == 0x00ff00, "fill: the horizontal line of 4 model pixels is 8 rows at the middle");
	free(c.pix);
	/* stretch: 100x100 onto 200x100, x doubled */
	set(200, 100, 0, DEV_FIT_STRETCH);
	c = play(bars_page, 0, &rc);
	extents(&c, cfg_box, &x0, &x1, &y0, &y1);
	CHECK(rc == 0 && x1 < 0, "stretch: no letterbox pixel");
	CHECK(px(&c, 97, 10) == 0xff0000 && px(&c, 102, 10) == 0xff0000 && px(&c, 95, 10) == 0x00ff00,
		"stretch: the vertical line is 8 columns, the horizontal 4 rows (lines stretch with the page)");
	free(c.pix);
}

static void test_images(void)
{
	int rc;
	/* a 2x2 checkerboard of black and white pixels, shrunk 2x: linear-light grey 188 */
	static char buf[65536];
	strcpy(buf, "LOCUS-META 1\npage 64 64\nimage 0 0 64 64\n");
	for (int k = 0; k < 64; k++) {
		strcat(buf, "row");
		for (int i = 0; i < 64; i++)
			strcat(buf, (i + k) % 2 ? " 1 #000000" : " 1 #ffffff");
		strcat(buf, "\n");
	}
	strcat(buf, "span 0 0 64 #ff8000\nspan 0 1 64 #ff8000\nend-page\n");
	set(32, 32, 0, DEV_FIT_ASPECT);
	cap_t c = play(buf, 0, &rc);
	int ok = 1;
	for (unsigned v = 0; v < 31; v++)
		for (unsigned u = 0; u < 32; u++)
			if (px(&c, u, v) != 0xbcbcbc)
				ok = 0;
	CHECK(rc == 0 && ok, "checkerboard shrunk 2x is linear-light grey #bcbcbc everywhere (%06x)", px(&c, 3, 3));
	CHECK(px(&c, 5, 31) == 0xff8000, "two model spans make one device row, colour exact");
	free(c.pix);
	/* enlargement 3x of a tiny image: flat colours stay exact, edges fall by the centre rule */
	set(30, 30, 0, DEV_FIT_ASPECT);
	c = play("LOCUS-META 1\npage 10 10\nimage 2 2 3 2\nrow 1 #ff0000 2 #0000ff\nrow 3 #00ff00\nend-page\n", 0, &rc);
	/* model columns 2..4 are device columns 6..14; the top row (red, blue, blue) device rows
	 * 18..20 from the top, the green one 21..23 */
	CHECK(rc == 0 && px(&c, 6, 18) == 0xff0000 && px(&c, 8, 20) == 0xff0000 && px(&c, 9, 18) == 0x0000ff &&
		px(&c, 14, 20) == 0x0000ff && px(&c, 6, 21) == 0x00ff00 && px(&c, 14, 23) == 0x00ff00 &&
		px(&c, 5, 19) == 0xffffff && px(&c, 15, 19) == 0xffffff && px(&c, 6, 17) == 0xffffff &&
		px(&c, 6, 24) == 0xffffff, "image enlarged 3x: pixels and edges");
	free(c.pix);
}

/* A page with everything, for banded against whole. */
static const char *all_page =
	"LOCUS-META 1\npage 300 200\nclear #e0e0ff\ncolour #204080\nwidth 3.5\njoin round\ncap round\n"
	"stroke\nmove 10 10\ndraw 290 190\narc 150 100 60 0 270\nend\ncolour #ff0000\ndash 7 3\n"
	"stroke\ncircle 150 100 80\nend\ncolour #008000\nfill\nmove 20 150\ndraw 120 190\ndraw 60 120\nend\n"
	"text 30 30 24 15 \"Locus devres\"\nimage 200 20 4 3\nrow 2 #ff00ff 2 #00ffff\nrow 4 #ffff00\n"
	"row 1 #000000 3 #808080\nspan 250 150 40 #00ff00\nend-page\n";

static void test_bands(void)
{
	int rc1, rc2, rc3;
	double aspects[2] = { 5.0 / 6.0, 1.25 };
	for (int k = 0; k < 2; k++) {
		set(160, 100, aspects[k], DEV_FIT_ASPECT);
		cap_t a = play(all_page, 0, &rc1), b = play(all_page, 7, &rc2), e = play(all_page, 1, &rc3);
		size_t n = (size_t)a.w * a.h * 3;
		dump(&a, k ? "all-125" : "all-083");
		CHECK(rc1 == 0 && rc2 == 0 && rc3 == 0 && a.w == 160 && b.w == 160 && !memcmp(a.pix, b.pix, n) &&
			!memcmp(a.pix, e.pix, n) && !b.bad_band && !e.bad_band,
			"aspect %.3f: bands of 1 and 7 rows agree with the whole page", aspects[k]);
		free(a.pix);
		free(b.pix);
		free(e.pix);
	}
}

static void test_identity(void)
{
	int rc1, rc2;
	set(0, 0, 0, 0);
	cap_t a = play(all_page, 0, &rc1);
	set(300, 200, 1.0, DEV_FIT_FILL);
	cap_t b = play(all_page, 0, &rc2);
	CHECK(rc1 == 0 && rc2 == 0 && b.w == 300 && !memcmp(a.pix, b.pix, (size_t)300 * 200 * 3),
		"a raster equal to the page is the model's own rendering");
	free(a.pix);
	free(b.pix);
	dev_map_t m;
	CHECK(dev_fit_map(&m, 10, 10, 20, 20, -1, 0) == DEV_EUSAGE && dev_fit_map(&m, 10, 10, 20, 20, 1, 7) == DEV_EUSAGE,
		"bad aspect or fit refused");
	CHECK(dev_fit_by_name("fill") == DEV_FIT_FILL && dev_fit_by_name("aspect") == DEV_FIT_ASPECT &&
		dev_fit_by_name("stretch") == DEV_FIT_STRETCH && dev_fit_by_name("crop") == -1, "fit names");
	set(100, 100, 0, 9);
	cap_t c = play(all_page, 0, &rc1);
	CHECK(rc1 == DEV_EUSAGE, "a device with an unknown fit is refused");
	free(c.pix);
}

static void test_options(void)
{
	int rc;
	set(200, 100, 0, DEV_FIT_FILL);
	cfg_options = "fit=aspect,letterbox=#ff00ff";
	cap_t c = play(bars_page, 0, &rc);
	CHECK(rc == 0 && px(&c, 0, 0) == 0xff00ff && px(&c, 199, 99) == 0xff00ff && px(&c, 60, 10) == 0x00ff00,
		"-O fit=aspect,letterbox=#ff00ff: magenta bars");
	free(c.pix);
	cfg_options = "fit=stretch";
	c = play(bars_page, 0, &rc);
	CHECK(rc == 0 && px(&c, 0, 0) == 0x00ff00, "-O fit=stretch: no bars");
	free(c.pix);
	const char *bad[3] = { "fit=crop", "letterbox=red", "letterbox=#12345g" };
	for (int k = 0; k < 3; k++) {
		cfg_options = bad[k];
		c = play(bars_page, 0, &rc);
		CHECK(rc == DEV_EUSAGE, "-O %s refused", bad[k]);
		free(c.pix);
	}
	cfg_options = NULL;
}

static void test_antialias(void)
{
	int rc1, rc2, rc3;
	const char *half = "LOCUS-META 1\npage 40 20\nfill\nmove 10.5 5\ndraw 20 5\ndraw 20 15.25\ndraw 10.5 15.25\nend\n"
		"colour #ff0000\nwidth 0.25\nstroke\nmove 30 0\ndraw 30 20\nend\nend-page\n";
	set(0, 0, 0, 0);
	cfg_aa = 4;
	cap_t a = play(half, 0, &rc1), b = play(half, 1, &rc2), c = play(half, 7, &rc3);
	dump(&a, "aa");
	CHECK(rc1 == 0 && a.w == 40 && a.h == 20 && px(&a, 10, 10) == 0xbcbcbc && px(&a, 11, 10) == 0 &&
		px(&a, 19, 10) == 0 && px(&a, 20, 10) == 0xffffff && px(&a, 9, 10) == 0xffffff,
		"antialias 4: a half-covered column is linear-light half grey #bcbcbc, full ones exact (%06x)", px(&a, 10, 10));
	/* the top edge at 15.25: row 4 from the top is covered 1/4 by the 4x4 grid */
	CHECK(px(&a, 15, 4) == 0xe1e1e1 && px(&a, 15, 5) == 0, "a quarter-covered row is 3/4 white in linear light, #e1e1e1 (%06x)", px(&a, 15, 4));
	/* widths below 1 draw as 1 (§5.3) here too: the line at x = 30 covers half of 29 and of 30 */
	CHECK(px(&a, 29, 10) == 0xffbcbc && px(&a, 30, 10) == 0xffbcbc && px(&a, 28, 10) == 0xffffff,
		"a 0.25-pixel red line is one pixel wide, split over two columns (%06x %06x)", px(&a, 29, 10), px(&a, 30, 10));
	size_t n = (size_t)a.w * a.h * 3;
	CHECK(rc2 == 0 && rc3 == 0 && !memcmp(a.pix, b.pix, n) && !memcmp(a.pix, c.pix, n) && !b.bad_band && !c.bad_band,
		"antialiased bands of 1 and 7 sample rows agree with the whole page");
	free(a.pix);
	free(b.pix);
	free(c.pix);
	set(160, 100, 5.0 / 6.0, DEV_FIT_ASPECT);
	cap_t e = play(all_page, 0, &rc1), f = play(all_page, 3, &rc2);
	dump(&e, "aa-083");
	CHECK(rc1 == 0 && rc2 == 0 && e.w == 160 && e.h == 100 && !memcmp(e.pix, f.pix, (size_t)160 * 100 * 3) &&
		px(&e, 0, 0) == cfg_box, "antialias on a raster of its own: device size, bars, bands agree");
	free(e.pix);
	free(f.pix);
	cfg_aa = 99;
	e = play(all_page, 0, &rc1);
	CHECK(rc1 == DEV_EUSAGE, "an anti-aliasing factor above %d is refused", DEV_AA_MAX);
	free(e.pix);
	cfg_aa = 0;
}

static unsigned rs = 777;
static int rn(int lo, int hi)
{
	rs = rs * 1103515245u + 12345u;
	return lo + (int)((rs >> 8) % (unsigned)(hi - lo + 1));
}

/* Random pages on random rasters, fits and aspects: bands of 1 and 5 rows agree with the whole
 * page, and nothing is painted outside the raster's bands. */
static void test_random(void)
{
	static char buf[16384];
	int ok = 1, rc0 = 0;
	for (int t = 0; t < 60; t++) {
		int w = rn(1, 90), h = rn(1, 90);
		int n = snprintf(buf, sizeof buf, "LOCUS-META 1\npage %d %d\n", w, h);
		for (int k = 0; k < 8; k++) {
			int kind = rn(0, 4);
			n += snprintf(buf + n, sizeof buf - n, "colour #%06x\n", (unsigned)rn(0, 0xffffff));
			if (kind == 0)
				n += snprintf(buf + n, sizeof buf - n, "width %d\ndash %d %d\nstroke\nmove %d %d\ndraw %d %d\n"
					"arc %d %d %d 0 %d\nend\n", rn(0, 6), rn(1, 9), rn(1, 9), rn(-20, w + 20), rn(-20, h + 20),
					rn(-20, w + 20), rn(-20, h + 20), rn(0, w), rn(0, h), rn(1, 40), rn(-360, 360));
			else if (kind == 1)
				n += snprintf(buf + n, sizeof buf - n, "fill\ncircle %d %d %d\nmove %d %d\ndraw %d %d\ndraw %d %d\nend\n",
					rn(0, w), rn(0, h), rn(1, 30), rn(-9, w), rn(-9, h), rn(0, w + 9), rn(0, h), rn(0, w), rn(0, h + 9));
			else if (kind == 2) {
				int iw = rn(1, 12), ih = rn(1, 12);
				n += snprintf(buf + n, sizeof buf - n, "image %d %d %d %d\n", rn(0, w), rn(0, h), iw, ih);
				for (int r = 0; r < ih; r++) {
					int left = iw;
					n += snprintf(buf + n, sizeof buf - n, "row");
					while (left > 0) {
						int c = rn(1, left);
						n += snprintf(buf + n, sizeof buf - n, " %d #%06x", c, (unsigned)rn(0, 0xffffff));
						left -= c;
					}
					n += snprintf(buf + n, sizeof buf - n, "\n");
				}
			} else if (kind == 3)
				n += snprintf(buf + n, sizeof buf - n, "span %d %d %d #%06x\n", rn(0, w), rn(0, h), rn(1, 30),
					(unsigned)rn(0, 0xffffff));
			else
				n += snprintf(buf + n, sizeof buf - n, "text %d %d %d %d \"Ab\"\n", rn(0, w), rn(0, h), rn(0, 20), rn(0, 90));
		}
		snprintf(buf + n, sizeof buf - n, "end-page\n");
		static const double aspects[4] = { 0, 5.0 / 6.0, 1.25, 0.5 };
		set((unsigned)rn(1, 120), (unsigned)rn(1, 120), aspects[rn(0, 3)], rn(0, 2));
		cfg_aa = rn(0, 3) == 0 ? (unsigned)rn(2, 3) : 0;
		int rc1, rc2, rc3;
		cap_t a = play(buf, 0, &rc1), b = play(buf, 1, &rc2), c = play(buf, 5, &rc3);
		size_t sz = (size_t)a.w * a.h * 3;
		rc0 |= rc1 | rc2 | rc3;
		if (rc1 || rc2 || rc3 || a.w != cfg_w || a.h != cfg_h || memcmp(a.pix, b.pix, sz) || memcmp(a.pix, c.pix, sz) ||
				b.bad_band || c.bad_band || a.rows_seen != a.h) {
			ok = 0;
			printf("# case %d differs: %s\n", t, buf);
		}
		free(a.pix);
		free(b.pix);
		free(c.pix);
	}
	cfg_aa = 0;
	CHECK(ok && rc0 == 0, "60 random pages on random rasters, fits, aspects (some anti-aliased): bands of 1 and 5 rows "
		"equal the whole page, every row handed over once");
}

int main(void)
{
	test_random();
	test_antialias();
	test_options();
	test_aspect_circle();
	test_dash_scaled();
	test_wide_aspect();
	test_thin_lines();
	test_bars();
	test_images();
	test_bands();
	test_identity();
	return UNIT_DONE();
}
