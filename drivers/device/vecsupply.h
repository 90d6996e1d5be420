/* devvec.h: what the framework supplies to vector devices: dash pieces, stroke outlines,
 * hatching, synthesised raw elements and clipped image rows (framework internals). */
#ifndef LOCUS_DEVVEC_H
#define LOCUS_DEVVEC_H

#include "device/device.h"

/* Scratch reused from one statement to the next. */
typedef struct {
	scan_ctx_t *ctx;
	scan_path_t dashed, outline, hatch;
	dev_elem_t *elems;
	size_t cap_elems;
	meta_run_t *runs;
	size_t cap_runs;
} dev_vec_t;

/* Stroke path (raw elements elems, or NULL to synthesise move/draw/close ones from the path)
 * onto the vector device d with state st, supplying dashes and widths it cannot draw. */
int dev_vec_stroke(dev_device_t *d, dev_vec_t *v, const scan_path_t *path, const dev_elem_t *elems,
		size_t nelems, const dev_state_t *st);
/* Fill path by st->rule, supplying hatching for a device that cannot fill. */
int dev_vec_fill(dev_device_t *d, dev_vec_t *v, const scan_path_t *path, const dev_elem_t *elems,
		size_t nelems, const dev_state_t *st);
/* put_image_row with the runs clipped to the page; rows off the page are dropped. */
int dev_vec_row(dev_device_t *d, dev_vec_t *v, int64_t x, int64_t y, const meta_run_t *runs, size_t nruns);
/* Free the scratch. */
void dev_vec_free(dev_vec_t *v);

#endif
