/* fit.h: rendering at a device's own resolution: the model-to-device mapping applied to
 * paths, widths, spans and images (framework internals, used by device.c; not for drivers).
 *
 * The public part (dev_map_t, dev_fit_map) is in device.h; docs/drivers.md describes the rules.
 */
#ifndef LOCUS_DEVRES_H
#define LOCUS_DEVRES_H

#include "device/device.h"
#include "render/render.h"

/* Map every point of p (model thousandths) to device thousandths, in place. */
void dev_fit_path(const dev_map_t *m, scan_path_t *p);
/* The device width (thousandths) a stroke of model width w gets: max(w, 1000) scaled by
 * m->wscale and rounded; §5.3 at the device then makes it at least one device pixel. */
int64_t dev_fit_width(const dev_map_t *m, int64_t w);
/* The radius (device thousandths) whose §5.4 chord count flattens a model arc of radius r
 * (model thousandths) finely enough for the device: r times the larger scale. */
int64_t dev_fit_chord_radius(const dev_map_t *m, int64_t r);
/* A stroke on non-square device pixels (sx != sy) wider than a device pixel: its §5.3 pieces
 * are built where the model is scaled alike in x and y (width W * sy, in units of a device
 * pixel's height), then x is scaled to device pixels and the pieces are filled non-zero, so the
 * line is as thick on the screen across as along. p is in model thousandths, solid (dash it
 * first); iso and pieces are scratch. Returns 0 or <0. */
int dev_fit_stroke_aniso(const dev_map_t *m, render_t *rr, scan_ctx_t *ctx, const scan_path_t *p,
		const scan_style_t *st, meta_rgb_t rgb, scan_path_t *iso, scan_path_t *pieces);
/* Paint the letterbox bars (the raster outside the mapped page) with rgb; called last on each
 * page, so that it also clips what was drawn beyond the page's edges. Returns 0 or <0. */
int dev_fit_bars(const dev_map_t *m, render_t *rr, meta_rgb_t rgb);
/* A model span: the device pixels whose centres lie in its mapped rectangle. */
int dev_fit_span(const dev_map_t *m, render_t *rr, int64_t x, int64_t y, int64_t n, meta_rgb_t rgb);

/* An image being resampled: area average in linear light over each device pixel's footprint,
 * rows streamed top first with one pending device row of accumulators. */
typedef struct dev_fit_img dev_fit_img_t;
/* Start an image of w x h model pixels at (x, y) (its bottom-left pixel). Returns NULL when out
 * of memory. An image entirely off the page is accepted and paints nothing. */
dev_fit_img_t *dev_fit_image_new(const dev_map_t *m, int64_t x, int64_t y, int64_t w, int64_t h);
/* Resample the image's next row (model page row y, rows arrive top first). Returns 0 or <0. */
int dev_fit_image_row(dev_fit_img_t *im, render_t *rr, int64_t y, const meta_run_t *runs, size_t nruns);
/* Free the image (NULL is fine). */
void dev_fit_image_free(dev_fit_img_t *im);

#endif
