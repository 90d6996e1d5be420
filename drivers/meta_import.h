/* meta_import.h: `locus-meta import`: drawings made elsewhere (HP-GL, plotutils metafiles) to meta. */
#ifndef LOCUS_META_IMPORT_H
#define LOCUS_META_IMPORT_H

#include <stddef.h>
#include "locus_meta.h"

/* Write the HP-GL or HP-GL/2 drawing buf/n (name for messages) to w as one page: plotter units
 * (0.025 mm) to the page at px_per_mm (the drawing's extent with a margin of 2 %, its size in mm
 * kept), pens to their PC colours or hp2xx's default ones, PW widths (0.3 mm, HP-GL/2 0.35 mm
 * where the file gives none), LT line types as dashes, fills (RA RR WG FP) by FT: solid with
 * FP's rule, hatched, cross-hatched or shaded, all clipped to IW, and labels (LB, SM symbols) in
 * the stroke font at the plotter's size, direction, slant, spacing and origin. Returns 0, -65
 * (bad input, err names the byte), -70 or -74 (writer). */
int mimp_hpgl(const void *buf, size_t n, const char *name, double px_per_mm, meta_writer_t *w,
		char *err, size_t errlen);

/* The subcommand: import the file in (HP-GL, or a GNU plotutils metafile, portable or binary:
 * told from its content) to out (NULL: stdout) in the text form. Prints one line on failure;
 * returns the exit status (0, 65 bad input, 66 no input, 70, 74). */
int mimp_run(const char *in, const char *out);

#endif
