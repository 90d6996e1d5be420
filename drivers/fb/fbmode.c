/* fbmode.c: the framebuffer device shared by VGA and XGA: options, page buffer, palette, output. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fb/fbdev.h"
#include "fb/fbmode.h"
#include "fb/fbout.h"
#include "quant/quant.h"

enum { PAL_PAGE = 0, PAL_SHARED = 1, PAL_FIXED = 2, PAL_FILE = 3 };

typedef struct {
	const fbm_mode_t *mode;
	int format;                  /* FBOUT_*, FBOUT_UNKNOWN = from the output's suffix */
	int palkind, method, dither;
	unsigned dacbits;            /* 6 (the hardware) or 8 (adaptive palettes for files only) */
	quant_palette_t pal;         /* fixed, file, or the shared palette once made */
	int have_pal;
	quant_hist_t *hist;
	unsigned w, h;               /* the page buffer */
	uint8_t *rgb, *idx, *shown;
	uint16_t *pix;
	fbdev_t *fb;
	double hold;                 /* seconds each page stays on the framebuffer, then restored */
	char collect[512];           /* the first pass of --palette shared: the file to write */
} fbm_t;

_Static_assert(sizeof(fbm_t) <= FBM_PRIV_SIZE, "FBM_PRIV_SIZE too small");

const dev_option_t fbm_options[] = {
	{ "mode", "the display mode (--list-modes); default the device's first" },
	{ "format", "dump, png, pcx or bmp; default from the output's suffix, else png" },
	{ "palette", "page (adaptive per page, default), shared (the first page's for all; locus-vga/xga: one from all pages), vga, ega, cube, grey, or a FILE" },
	{ "quant", "adaptive palette method: best (median cut + k-means, default), median, octree" },
	{ "dither", "none, ordered (Bayer 8x8) or fs (serpentine Floyd-Steinberg, default)" },
	DEV_FIT_OPTIONS,
	{ "dac", "6 (the mode's DAC, default) or 8: adaptive palettes of 8-bit entries, for PNG/PCX/BMP files" },
	{ "collect", "FILE: count every page, write their one palette to FILE (#rrggbb lines), no pictures (--palette shared)" },
	{ "fb", "a Linux framebuffer node (/dev/fb0) to show the pages on instead of files" },
	{ "hold", "seconds each page stays on the framebuffer before the screen is restored (default 0: keep)" },
	{ NULL, NULL }
};

const fbm_mode_t *fbm_find_mode(const fbm_modes_t *ml, const char *name)
{
	for (size_t k = 0; k < ml->n; k++)
		if (strcmp(ml->modes[k].name, name) == 0 || (ml->modes[k].alias && strcmp(ml->modes[k].alias, name) == 0))
			return &ml->modes[k];
	return NULL;
}

void fbm_describe(const fbm_mode_t *m, char *buf, size_t n)
{
	char shape[32];
	if (m->pixel_aspect == 1)
		snprintf(shape, sizeof shape, "square pixels");
	else
		snprintf(shape, sizeof shape, "pixel aspect %.4g", m->pixel_aspect);
	snprintf(buf, n, "%-13s %4ux%-4u %5u colours  %s; %s", m->name, m->width, m->height, m->colours, shape,
		m->description);
}

/* ---- options ------------------------------------------------------------------------ */

static int load_palette_file(dev_device_t *d, fbm_t *f, const char *path, unsigned ncol)
{
	FILE *fp = fopen(path, "rb");
	if (!fp)
		return dev_fail(d, META_EIO, "palette file %s: cannot open", path);
	unsigned char buf[65536];
	size_t n = fread(buf, 1, sizeof buf, fp);
	int big = n == sizeof buf;
	fclose(fp);
	if (big)
		return dev_fail(d, META_ESYNTAX, "%s: byte 65536: too long for a palette file", path);
	char err[300];
	if (quant_parse_palette_bits(buf, n, path, ncol, f->dacbits, &f->pal, err, sizeof err))
		return dev_fail(d, META_ESYNTAX, "%s", err);
	return 0;
}

/* Colours of the palette the pages get: the mode's, or 256 on an 8-bit screen. */
static unsigned palette_colours(const fbm_t *f)
{
	if (f->fb && fbdev_info(f->fb)->pseudo)
		return 256;
	return f->mode->colours > 256 ? 0 : f->mode->colours;
}

int fbm_open(dev_device_t *d, const fbm_modes_t *ml)
{
	fbm_t *f = d->priv;
	char v[512];
	f->mode = &ml->modes[0];
	f->format = FBOUT_UNKNOWN;
	f->dither = QUANT_DITHER_FS;
	if (dev_option(d, "mode", v, sizeof v)) {
		f->mode = fbm_find_mode(ml, v);
		if (!f->mode) {
			char names[128] = "";
			for (size_t k = 0; k < ml->n; k++)
				snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", k ? ", " : "", ml->modes[k].name);
			return dev_fail(d, DEV_EUSAGE, "unknown mode '%s' (%s: %s)", v, d->ops->name, names);
		}
	}
	if (dev_option(d, "format", v, sizeof v) && (f->format = fbout_format_by_name(v)) == FBOUT_UNKNOWN)
		return dev_fail(d, DEV_EUSAGE, "unknown format '%s' (dump, png, pcx or bmp)", v);
	if (dev_option(d, "quant", v, sizeof v)) {
		if (!strcmp(v, "best") || !strcmp(v, "kmeans"))
			f->method = QUANT_BEST;
		else if (!strcmp(v, "median"))
			f->method = QUANT_MEDIAN;
		else if (!strcmp(v, "octree"))
			f->method = QUANT_OCTREE;
		else
			return dev_fail(d, DEV_EUSAGE, "unknown quant '%s' (best, median or octree)", v);
	}
	if (dev_option(d, "dither", v, sizeof v)) {
		if (!strcmp(v, "none"))
			f->dither = QUANT_DITHER_NONE;
		else if (!strcmp(v, "ordered") || !strcmp(v, "bayer"))
			f->dither = QUANT_DITHER_ORDERED;
		else if (!strcmp(v, "fs") || !strcmp(v, "floyd-steinberg"))
			f->dither = QUANT_DITHER_FS;
		else
			return dev_fail(d, DEV_EUSAGE, "unknown dither '%s' (none, ordered or fs)", v);
	}
	f->dacbits = 6;
	if (dev_option(d, "dac", v, sizeof v)) {
		if (strcmp(v, "6") && strcmp(v, "8"))
			return dev_fail(d, DEV_EUSAGE, "dac wants 6 or 8 bits, not '%s'", v);
		f->dacbits = (unsigned)atoi(v);
		if (f->dacbits == 8 && f->format == FBOUT_DUMP)
			return dev_fail(d, DEV_EUSAGE, "dac=8 is beyond the hardware: no dump (png, pcx or bmp)");
	}
	int frc = dev_fit_options(d);
	if (frc)
		return frc;
	if (dev_option(d, "hold", v, sizeof v)) {
		char *e;
		f->hold = strtod(v, &e);
		if (*e || !(f->hold >= 0 && f->hold <= 86400))
			return dev_fail(d, DEV_EUSAGE, "hold wants seconds (0 to 86400), not '%s'", v);
	}
	if (dev_option(d, "fb", v, sizeof v)) {
		char err[400];
		f->fb = fbdev_open(v, err, sizeof err);
		if (!f->fb)
			return dev_fail(d, DEV_EDEVICE, "%s", err);
	}
	if (dev_option(d, "collect", v, sizeof v))
		snprintf(f->collect, sizeof f->collect, "%s", v);
	unsigned ncol = palette_colours(f);
	if (f->collect[0] && ncol == 0)
		return dev_fail(d, DEV_EUSAGE, "mode %s is direct colour: it has no palette to collect", f->mode->name);
	if (dev_option(d, "palette", v, sizeof v) && strcmp(v, "page") && strcmp(v, "adaptive")) {
		int fixed = quant_fixed_by_name(v);
		if (!strcmp(v, "shared")) {
			f->palkind = PAL_SHARED;
		} else if (ncol == 0) {
			return dev_fail(d, DEV_EUSAGE, "mode %s is direct colour: it takes no palette '%s'", f->mode->name, v);
		} else if (fixed >= 0) {
			char err[200];
			if (quant_fixed(fixed, ncol, &f->pal, err, sizeof err))
				return dev_fail(d, DEV_EUSAGE, "%s", err);
			f->palkind = PAL_FIXED;
			f->have_pal = 1;
		} else {
			int rc = load_palette_file(d, f, v, ncol);
			if (rc)
				return rc;
			f->palkind = PAL_FILE;
			f->have_pal = 1;
		}
	}
	if (f->fb) {
		const fbdev_info_t *in = fbdev_info(f->fb);
		d->raster_width = in->width, d->raster_height = in->height, d->pixel_aspect = in->pixel_aspect;
	} else {
		d->raster_width = f->mode->width, d->raster_height = f->mode->height;
		d->pixel_aspect = f->mode->pixel_aspect;
	}
	f->hist = quant_hist_new();
	if (!f->hist)
		return dev_fail(d, META_ENOMEM, "out of memory");
	return 0;
}

/* ---- pages -------------------------------------------------------------------------- */

int fbm_begin_page(dev_device_t *d, const dev_page_t *pg)
{
	fbm_t *f = d->priv;
	if (!d->out && !f->fb && !f->collect[0])
		return dev_fail(d, DEV_EDEVICE, "%s: no output", d->ops->name);
	if (pg->width != f->w || pg->height != f->h || !f->rgb) {
		size_t px = (size_t)pg->width * pg->height;
		free(f->rgb), free(f->idx), free(f->pix), free(f->shown);
		f->rgb = malloc(px * 3);
		f->idx = malloc(px);
		f->pix = malloc(px * sizeof *f->pix);
		f->shown = f->fb ? malloc(px * 3) : NULL;
		f->w = pg->width, f->h = pg->height;
		if (!f->rgb || !f->idx || !f->pix || (f->fb && !f->shown)) {
			free(f->rgb), free(f->idx), free(f->pix), free(f->shown);
			f->rgb = f->idx = f->shown = NULL, f->pix = NULL, f->w = f->h = 0;
			return dev_fail(d, META_ENOMEM, "out of memory for a %ux%u page", pg->width, pg->height);
		}
	}
	return 0;
}

int fbm_write_band(dev_device_t *d, const render_band_t *b)
{
	fbm_t *f = d->priv;
	if (b->width != f->w || b->y0 + b->nrows > f->h)
		return dev_fail(d, DEV_EDEVICE, "band of %u rows at %u does not fit the %ux%u page", b->nrows, b->y0, f->w, f->h);
	for (unsigned k = 0; k < b->nrows; k++)
		memcpy(f->rgb + ((size_t)(b->y0 + k) * f->w) * 3, b->pix + k * b->stride, (size_t)f->w * 3);
	return 0;
}

static int show_on_fb(dev_device_t *d, fbm_t *f, unsigned ncol)
{
	char err[400];
	size_t px = (size_t)f->w * f->h;
	if (!fbdev_info(f->fb)->pseudo) {
		for (size_t k = 0; k < px; k++) {
			uint8_t *c = f->shown + 3 * k;
			if (ncol) {
				const uint8_t *dac = f->pal.dac[f->idx[k]];
				c[0] = (uint8_t)quant_show(&f->pal, dac[0]), c[1] = (uint8_t)quant_show(&f->pal, dac[1]);
				c[2] = (uint8_t)quant_show(&f->pal, dac[2]);
			} else {
				unsigned v = f->pix[k], r = v >> 11, g = v >> 5 & 63, b = v & 31;
				c[0] = (uint8_t)(r << 3 | r >> 2), c[1] = (uint8_t)(g << 2 | g >> 4), c[2] = (uint8_t)(b << 3 | b >> 2);
			}
		}
	}
	if (f->hold > 0)             /* Ctrl-C from here on: the old screen back, then exit 130 */
		fbdev_guard(f->fb);
	if (fbdev_show(f->fb, f->idx, &f->pal, f->shown, f->w, f->h, err, sizeof err)) {
		char e2[400];
		if (f->hold > 0)         /* put back what the failed show changed */
			fbdev_hold(f->fb, 0, e2, sizeof e2);
		return dev_fail(d, DEV_EDEVICE, "%s", err);
	}
	if (f->hold > 0 && fbdev_hold(f->fb, f->hold, err, sizeof err))
		return dev_fail(d, DEV_EDEVICE, "%s", err);
	return 0;
}

/* ---- writing the file while the page is mapped ---------------------------------------- */

/* Pages of at least this many pixels have their PNG written while they are mapped (smaller
 * ones: a thread costs more than it saves; the mapping splits at the same size). */
#define FBM_PIPE_PIXELS (1u << 18)

/* The rows of a page being mapped on this thread, written on another as they come. */
typedef struct {
	pthread_mutex_t mu;
	pthread_cond_t cv;
	uint8_t *done;              /* per row: final */
	int failed;                 /* the mapping gave up: no more rows will come */
	io_transport_t *out;
	int fmt, rc;
	fbout_picture_t p;
	char err[400];
} fbm_pipe_t;

static void pipe_done(void *ctx, unsigned y)
{
	fbm_pipe_t *pp = ctx;
	pthread_mutex_lock(&pp->mu);
	pp->done[y] = 1;
	pthread_cond_broadcast(&pp->cv);
	pthread_mutex_unlock(&pp->mu);
}

static int pipe_wait(void *ctx, unsigned y)
{
	fbm_pipe_t *pp = ctx;
	pthread_mutex_lock(&pp->mu);
	while (!pp->done[y] && !pp->failed)
		pthread_cond_wait(&pp->cv, &pp->mu);
	int rc = pp->done[y] ? 0 : -1;
	pthread_mutex_unlock(&pp->mu);
	return rc;
}

static void *pipe_write(void *arg)
{
	fbm_pipe_t *pp = arg;
	pp->rc = fbout_write(pp->out, pp->fmt, &pp->p, pp->err, sizeof pp->err);
	return NULL;
}

/* Map the page and write it as format fmt, the writer on a thread of its own taking each row
 * as soon as the mapping has made it (the same bytes as mapping, then writing: the PNG's
 * deflate, a quarter of a big page's colour work, runs beside the mapping). 1 when it could
 * not start (then nothing was done), else 0 or the failure. */
static int map_writing(dev_device_t *d, fbm_t *f, int fmt, const fbout_picture_t *pic)
{
	fbm_pipe_t pp;
	memset(&pp, 0, sizeof pp);
	pp.done = calloc(f->h ? f->h : 1, 1);
	if (!pp.done)
		return 1;
	if (pthread_mutex_init(&pp.mu, NULL)) {
		free(pp.done);
		return 1;
	}
	if (pthread_cond_init(&pp.cv, NULL)) {
		pthread_mutex_destroy(&pp.mu);
		free(pp.done);
		return 1;
	}
	pp.out = d->out, pp.fmt = fmt, pp.p = *pic;
	pp.p.wait_row = pipe_wait, pp.p.wait_ctx = &pp;
	pthread_t th;
	int rc = 1;
	if (pthread_create(&th, NULL, pipe_write, &pp) == 0) {
		int mrc = quant_map_rows(&f->pal, f->hist, f->rgb, f->w, f->h, (size_t)f->w * 3, f->dither, f->idx,
			pipe_done, &pp);
		if (mrc) {               /* no more rows: the writer gives up */
			pthread_mutex_lock(&pp.mu);
			pp.failed = 1;
			pthread_cond_broadcast(&pp.cv);
			pthread_mutex_unlock(&pp.mu);
		}
		pthread_join(th, NULL);
		rc = mrc ? dev_fail(d, META_ENOMEM, "out of memory") : pp.rc ? dev_fail(d, dev_code_of_errno(-pp.rc), "%s", pp.err) : 0;
	}
	pthread_cond_destroy(&pp.cv);
	pthread_mutex_destroy(&pp.mu);
	free(pp.done);
	return rc;
}

/* The output format of the pages: -f, else the output's suffix, else PNG. */
static int out_format(dev_device_t *d, const fbm_t *f)
{
	int fmt = f->format;
	if (fmt == FBOUT_UNKNOWN && !io_is_std(d->out))
		fmt = fbout_format_by_suffix(io_name(d->out));
	return fmt == FBOUT_UNKNOWN ? FBOUT_PNG : fmt;
}

int fbm_end_page(dev_device_t *d, const dev_page_t *pg)
{
	fbm_t *f = d->priv;
	char err[400];
	(void)pg;
	unsigned ncol = palette_colours(f);
	if (!f->collect[0])          /* collect: every page into one histogram, nothing out */
		quant_hist_clear(f->hist);
	quant_hist_add(f->hist, f->rgb, f->w, f->h, (size_t)f->w * 3);
	if (f->dacbits == 8 && ncol && !f->have_pal && quant_hist_exact(f->hist, f->rgb, f->w, f->h, (size_t)f->w * 3))
		return dev_fail(d, META_ENOMEM, "out of memory");
	if (f->collect[0])
		return 0;
	int fmt = f->fb ? FBOUT_UNKNOWN : out_format(d, f);
	fbout_picture_t p = { f->w, f->h, f->mode->layout, f->idx, f->pix, &f->pal, d->pixel_aspect, NULL, NULL };
	if (ncol && p.layout == FBOUT_DIRECT565)
		p.layout = FBOUT_LINEAR8;
	if (ncol == 0) {
		if (quant_map565(f->hist, f->rgb, f->w, f->h, (size_t)f->w * 3, f->dither, f->pix))
			return dev_fail(d, META_ENOMEM, "out of memory");
	} else {
		if (!f->have_pal) {
			if (quant_build_bits(f->hist, f->method, ncol, f->dacbits, &f->pal, err, sizeof err))
				return dev_fail(d, META_ENOMEM, "%s", err);
			f->have_pal = f->palkind == PAL_SHARED;
		}
		if (fmt == FBOUT_DUMP && f->pal.bits == 8)
			return dev_fail(d, DEV_EUSAGE, "dac=8 is beyond the hardware: no dump (png, pcx or bmp)");
		/* a big page's PNG written while the page is mapped, when a core is spare for it */
		int big = (size_t)f->w * f->h >= FBM_PIPE_PIXELS;
		int rc = fmt == FBOUT_PNG && big && quant_spare_core() ? map_writing(d, f, fmt, &p) : 1;
		if (rc != 1)
			return rc;
		if (quant_map(&f->pal, f->hist, f->rgb, f->w, f->h, (size_t)f->w * 3, f->dither, f->idx))
			return dev_fail(d, META_ENOMEM, "out of memory");
	}
	if (f->fb)
		return show_on_fb(d, f, ncol);
	int wrc = fbout_write(d->out, fmt, &p, err, sizeof err);
	if (wrc)
		return dev_fail(d, dev_code_of_errno(-wrc), "%s", err);
	return 0;
}

/* The collected palette of all pages as #rrggbb lines. */
static int write_collected(dev_device_t *d, fbm_t *f)
{
	char err[300];
	quant_palette_t pal;
	if (quant_build_bits(f->hist, f->method, palette_colours(f), f->dacbits, &pal, err, sizeof err))
		return dev_fail(d, META_ENOMEM, "%s", err);
	FILE *fp = fopen(f->collect, "w");
	if (!fp)
		return dev_fail(d, META_EIO, "%s: cannot write the palette", f->collect);
	for (unsigned k = 0; k < pal.n; k++)
		fprintf(fp, "#%02x%02x%02x\n", quant_show(&pal, pal.dac[k][0]), quant_show(&pal, pal.dac[k][1]),
			quant_show(&pal, pal.dac[k][2]));
	if (fclose(fp) != 0)
		return dev_fail(d, META_EIO, "%s: cannot write the palette", f->collect);
	return 0;
}

int fbm_close(dev_device_t *d)
{
	fbm_t *f = d->priv;
	int rc = 0;
	if (f->collect[0] && f->hist && quant_hist_colours(f->hist) > 0)
		rc = write_collected(d, f);
	free(f->rgb), free(f->idx), free(f->pix), free(f->shown);
	f->rgb = f->idx = f->shown = NULL, f->pix = NULL;
	quant_hist_free(f->hist);
	f->hist = NULL;
	fbdev_close(f->fb);
	f->fb = NULL;
	return rc;
}
