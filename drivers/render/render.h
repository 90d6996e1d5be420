/* render.h: the banded raster page renderer behind every raster device (drivers only). */
#ifndef LOCUS_RENDER_H
#define LOCUS_RENDER_H

#include "locus_meta.h"
#include "geom/scan.h"
#include "render/band.h"

typedef struct render render_t;

/* Called with each finished band, top band first. */
typedef int (*render_band_fn)(void *user, const render_band_t *band);

/* A renderer for one page of width x height. band_rows 0 = whole page when width*height*3 fits
 * budget bytes and 16 MiB, else bands of half the budget (at most 8 MiB; the whole budget when
 * half would hold fewer than 32 rows); band_rows >= height = whole page. A single-band page
 * is painted as the statements arrive (from 128 rows on by two helper threads, the top and the
 * bottom half, from the statements the caller's thread queues in memory, joined by
 * render_finish or render_free); a multi-band page spools them to a temporary file and
 * replays it once per band, skipping statements whose rows miss the band: in render_finish,
 * by two threads when two band buffers fit the budget (the first two bands painted by two
 * helpers while the page is spooled, then each thread the next band not taken, each handing its
 * band to fn in turn, so fn sees the bands in order, one call at a time, from either thread).
 * Returns NULL with a message in err on failure. */
render_t *render_new(unsigned width, unsigned height, unsigned band_rows, size_t budget,
		char *err, size_t errlen);
/* The spool of a multi-band page is a temporary file in $TMPDIR (else /tmp), unlinked as soon as
 * it is created; it may grow to this many bytes (environment: LOCUS_SPOOL_MAX_MB) before the
 * page is refused with a message naming the spool and the limit. A failed write names the cause
 * (strerror: "No space left on device"). */
#define DEV_SPOOL_MAX_DEFAULT ((uint64_t)4 << 30)
/* The spool limit of new renderers: LOCUS_SPOOL_MAX_MB MiB if set to a positive number, else
 * DEV_SPOOL_MAX_DEFAULT. */
uint64_t render_spool_default(void);
/* Change the spool limit of r (bytes). */
void render_set_spool_limit(render_t *r, uint64_t bytes);
/* The message of the last failure ("band spool (a temporary file in /tmp): ..."), or "" when
 * the failure was not the renderer's own (out of memory: the caller says so). */
const char *render_error(const render_t *r);
/* Free the renderer and its spool. */
void render_free(render_t *r);
/* Number of bands the page is rendered in. */
unsigned render_bands(const render_t *r);

/* The painting statements. Each returns 0 or <0 (META_ENOMEM, META_EIO). */
int render_clear(render_t *r, meta_rgb_t rgb);
int render_fill(render_t *r, const scan_path_t *p, int rule, meta_rgb_t rgb);
int render_stroke(render_t *r, const scan_path_t *p, const scan_style_t *st, meta_rgb_t rgb);
int render_span(render_t *r, int64_t x, int64_t y, int64_t n, meta_rgb_t rgb);
/* One image row at pixel row y (bottom-up page row) from x. */
int render_row(render_t *r, int64_t x, int64_t y, const meta_run_t *runs, size_t nruns);
/* Render (if spooled) and hand every band to fn, top first (fn may be called from the helper
 * thread, never twice at once). Returns the first error in band order, fn's or the replay's, or 0. */
int render_finish(render_t *r, render_band_fn fn, void *user);

#endif
