/* meta_import.h: `locus-meta import`: drawings made elsewhere (HP-GL, plotutils metafiles) to meta. */
#ifndef LOCUS_META_IMPORT_H
#define LOCUS_META_IMPORT_H

#include <stddef.h>
#include <stdio.h>
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

/* mimp_hpgl with a profile's carousel: pens (hpgl_pens_parse's syntax, as a profile's `pens`
 * line or `locus-hpgl --pens`: "1=black:0.5mm,2=red:0.25mm"; a pen without a width 0.3 mm)
 * give the colour of a pen the file sets no PC for and the width of one it sets no PW for.
 * NULL: as mimp_hpgl. A bad spec: -64, err "pens: ...". */
int mimp_hpgl_pens(const void *buf, size_t n, const char *name, double px_per_mm, const char *pens,
		meta_writer_t *w, char *err, size_t errlen);

/* mimp_hpgl_pens, reading strictly (strict = 1: junk between commands, unreadable parameters or
 * PE data refused) or tolerantly (0: skipped, each with a warning line naming the byte, printed
 * to warn when not NULL). Each PG that follows drawing starts a new meta page. */
int mimp_hpgl_read(const void *buf, size_t n, const char *name, double px_per_mm, const char *pens,
		int strict, FILE *warn, meta_writer_t *w, char *err, size_t errlen);

/* The subcommand: import the file in (HP-GL, or a GNU plotutils metafile, portable or binary:
 * told from its content) to out (NULL: stdout) in the text form; pens (NULL: none) as
 * mimp_hpgl_pens for HP-GL (refused for a plotutils metafile, which has no pens). Prints one
 * line on failure; returns the exit status (0, 64 bad pens, 65 bad input, 66 no input, 70, 74). */
int mimp_run(const char *in, const char *out, const char *pens);
/* mimp_run, HP-GL read strictly (strict = 1) or tolerantly with warnings on stderr (0, the
 * default of mimp_run). */
int mimp_run_strict(const char *in, const char *out, const char *pens, int strict);

/* mimp_run with SVG's options (svg_import.h; svg_only: refuse other kinds; strict as for
 * mimp_run_strict); and the whole
 * subcommand with its own options (import_svg_cli.c; argv[0] is "import"). */
struct svgimp_opts_s;
int mimp_run_svg(const char *in, const char *out, const char *pens, const struct svgimp_opts_s *svg,
		int svg_only, int strict);
int mimp_main(int argc, char **argv);

#endif
