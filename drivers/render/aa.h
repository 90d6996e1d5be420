/* aa.h: anti-aliased raster output by k x k supersampling (framework internals). */
#ifndef LOCUS_DEVAA_H
#define LOCUS_DEVAA_H

#include "render/band.h"

typedef struct devaa render_aa_t;
/* Where finished output bands go (the device's write_band, through the framework). */
typedef int (*render_aa_fn)(void *user, const render_band_t *band);

/* A downsampler from a raster of (k * width) x (k * height) samples to width x height pixels,
 * each the mean of its k x k samples in linear light (sRGB decoded, averaged, encoded to the
 * nearest byte). Returns NULL when out of memory. */
render_aa_t *render_aa_new(unsigned k, unsigned width, unsigned height);
/* Take the next rows of samples (top first, in order) and hand each finished run of output
 * rows to fn. Returns 0 or fn's error. */
int render_aa_band(render_aa_t *a, const render_band_t *in, render_aa_fn fn, void *user);
/* Free it (NULL is fine). */
void render_aa_free(render_aa_t *a);

#endif
