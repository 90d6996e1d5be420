/* diff.h: locus-diff's comparison engines: rasters, HP-GL strokes, meta statements, PostScript/PDF.
 *
 * Each engine compares two inputs of one kind and writes its report to a stdio stream: one line
 * by default, details with verbose, a JSON object with json. It returns 0 (same within the
 * tolerances), 1 (different) or -1 with a one-line message in err (the inputs could not be
 * read: the message names the file and the place). Nothing here exits.
 */
#ifndef LOCUS_DIFF_H
#define LOCUS_DIFF_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* What the user asked for. */
typedef struct {
	int verbose, json;
	unsigned tol[3];            /* per-channel tolerance: |a - b| <= tol[c] counts as equal */
	unsigned long maxpix;       /* accept up to this many differing pixels */
	double psnr_min;            /* accept at this PSNR or above (< 0: not asked) */
	int scale;                  /* rasters of different sizes: B resampled to A's size */
	int strict_order;           /* HP-GL: stroke order and direction count */
	double hpgl_tol;            /* HP-GL: how far a point may move, plotter units */
	unsigned nfirst;            /* differing pixels / strokes listed with verbose */
	int qdf;                    /* PDF: both given in qpdf's QDF form (lines and bytes are of it) */
} diff_opts_t;

/* Defaults: exact, one-line report, 0.5 plotter units, 10 listed. */
void diff_opts_default(diff_opts_t *o);

/* ---- rasters (diff_raster.c), fed a row pair at a time ---- */
typedef struct diff_raster diff_raster_t;
/* An accumulator for two width x height pictures. NULL when out of memory. */
diff_raster_t *diff_raster_new(unsigned width, unsigned height, const diff_opts_t *o);
/* Compare row y of A and B (3 bytes a pixel); when mark is not NULL it gets the row of the
 * difference picture: A faded towards white, differing pixels red. */
void diff_raster_row(diff_raster_t *d, unsigned y, const uint8_t *a, const uint8_t *b, uint8_t *mark);
/* Write the report on A and B (names) to out; 0 same (within the tolerances) or 1. Frees d. */
int diff_raster_report(diff_raster_t *d, const char *a, const char *b, FILE *out);
/* The report of two pictures whose sizes differ (no --scale): returns 1. */
int diff_raster_sizes(const char *a, const char *b, unsigned wa, unsigned ha, unsigned wb,
		unsigned hb, const diff_opts_t *o, FILE *out);

/* ---- HP-GL (diff_hpgl.c) ---- */
/* Compare two HP-GL files held in memory (names for messages and the report). */
int diff_hpgl(const void *a, size_t na, const char *aname, const void *b, size_t nb,
		const char *bname, const diff_opts_t *o, FILE *out, char *err, size_t errlen);

/* ---- meta files (diff_meta.c) ---- */
/* Semantic diff of two meta files (text or binary, either against either), statement by
 * statement: the first differing statement with its line (text) or byte offset (binary). */
int diff_meta(const void *a, size_t na, const char *aname, const void *b, size_t nb,
		const char *bname, const diff_opts_t *o, FILE *out, char *err, size_t errlen);

/* ---- PostScript, EPS, PDF (diff_ps.c) ---- */
/* Compare after normalising what carries no picture (creator, dates, IDs, renumbered objects):
 * the first differing line of each. */
int diff_ps(const void *a, size_t na, const char *aname, const void *b, size_t nb,
		const char *bname, const diff_opts_t *o, FILE *out, char *err, size_t errlen);

/* JSON string of s (quoted, escaped) to out. */
void diff_json_str(FILE *out, const char *s);

#endif
