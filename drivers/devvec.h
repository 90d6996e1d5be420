/* devvec.h: what the framework supplies to vector devices: dash pieces, stroke outlines,
 * hatching, synthesised raw elements and clipped image rows (framework internals). */
#ifndef LOCUS_DEVVEC_H
#define LOCUS_DEVVEC_H

#include "device.h"

/* Scratch reused from one statement to the next. */
typedef struct {
	scan_ctx_t *ctx;
	scan_path_t dashed, outline, hatch;
	dev_elem_t *elems;
	size_t cap_elems;
	meta_run_t *runs;
	size_t cap_runs;
} devvec_t;

/* Stroke path (raw elements elems, or NULL to synthesise move/draw/close ones from the path)
 * onto the vector device d with state st, supplying dashes and widths it cannot draw. */
int devvec_stroke(dev_device_t *d, devvec_t *v, const scan_path_t *path, const dev_elem_t *elems,
		size_t nelems, const dev_state_t *st);
/* Fill path by st->rule, supplying hatching for a device that cannot fill. */
int devvec_fill(dev_device_t *d, devvec_t *v, const scan_path_t *path, const dev_elem_t *elems,
		size_t nelems, const dev_state_t *st);
/* put_image_row with the runs clipped to the page; rows off the page are dropped. */
int devvec_row(dev_device_t *d, devvec_t *v, int64_t x, int64_t y, const meta_run_t *runs, size_t nruns);
/* scan_dash_path with the pieces made only where they meet the box x0..x1, y0..y1
 * (thousandths; dash.c): a dashed line that runs far off the page costs what the page shows. */
int scan_dash_path_box(const scan_path_t *p, const int64_t *dash, size_t ndash, int64_t x0, int64_t y0,
		int64_t x1, int64_t y1, scan_path_t *out);
/* Free the scratch. */
void devvec_free(devvec_t *v);

#endif
