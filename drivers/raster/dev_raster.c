/* dev_raster.c: the reference raster devices (PNG, PPM, RLE at 24 bits) and the null device. */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include "device/device.h"
#include "image/image.h"

typedef struct {
	img_writer_t *w;
} raster_t;

static int fmt_of(const dev_device_t *d)
{
	return img_format_by_name(d->ops->name);
}

static int r_begin(dev_device_t *d, const dev_page_t *pg)
{
	raster_t *r = d->priv;
	char err[256];
	if (!d->out)
		return dev_fail(d, DEV_EDEVICE, "%s: no output", d->ops->name);
	r->w = img_writer_new(fmt_of(d), d->out, pg->width, pg->height, err, sizeof err);
	if (!r->w)
		return dev_fail(d, dev_code_of_errno(errno), "%s", err);
	if (pg->has_size)
		img_writer_physical(r->w, pg->width_mm / 1000.0, pg->height_mm / 1000.0);
	return 0;
}

static int r_band(dev_device_t *d, const render_band_t *b)
{
	raster_t *r = d->priv;
	if (img_writer_rows(r->w, b->pix, b->stride, b->nrows))
		return dev_fail(d, dev_code_of_errno(img_writer_errno(r->w)), "%s", img_writer_error(r->w));
	return 0;
}

static int r_end(dev_device_t *d, const dev_page_t *pg)
{
	raster_t *r = d->priv;
	(void)pg;
	if (img_writer_finish(r->w)) {
		int rc = dev_fail(d, dev_code_of_errno(img_writer_errno(r->w)), "%s", img_writer_error(r->w));
		img_writer_abort(r->w);
		r->w = NULL;
		return rc;
	}
	r->w = NULL;
	return 0;
}

static int r_close(dev_device_t *d)
{
	raster_t *r = d->priv;
	img_writer_abort(r->w);   /* only after a failure */
	r->w = NULL;
	return 0;
}

const dev_ops_t dev_png_ops = {
	.name = "png", .description = "24-bit PNG raster file (libpng), the reference rendering",
	.extension = ".png", .caps = DEV_CAP_RASTER, .priv_size = sizeof(raster_t),
	.begin_page = r_begin, .write_band = r_band, .end_page = r_end, .close = r_close,
};

const dev_ops_t dev_ppm_ops = {
	.name = "ppm", .description = "24-bit binary PPM (P6) raster file",
	.extension = ".ppm", .caps = DEV_CAP_RASTER, .priv_size = sizeof(raster_t),
	.begin_page = r_begin, .write_band = r_band, .end_page = r_end, .close = r_close,
};

const dev_ops_t dev_rle_ops = {
	.name = "rle", .description = "24-bit run-length raster file of the thesis (docs/rle-format.md)",
	.extension = ".rle", .caps = DEV_CAP_RASTER, .priv_size = sizeof(raster_t),
	.begin_page = r_begin, .write_band = r_band, .end_page = r_end, .close = r_close,
};

const dev_ops_t dev_null_ops = {
	.name = "null", .description = "renders every page and discards it (timing, validation)",
	.extension = "", .caps = DEV_CAP_RASTER,
};
