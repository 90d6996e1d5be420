/* plotmeta.h: a reader of GNU plotutils graphics metafiles ("#PLOT 1" binary, "#PLOT 2" portable). */
#ifndef LOCUS_PLOTMETA_H
#define LOCUS_PLOTMETA_H

#include <stddef.h>
#include "locus_meta.h"

/* 1 when buf starts with a plotutils metafile's magic ("#PLOT 1\n" or "#PLOT 2\n"). */
int plotmeta_is(const void *buf, size_t n);

/* Turn the metafile buf/n (name for messages) into meta statements on w: each openpl .. closepl
 * a page of 570 x 570 pixels (plot -T png's default) onto which the user space (space, fspace,
 * fsetmatrix, fconcat) maps as libplot maps it onto its unit square; lines, arcs, circles,
 * ellipses, boxes and Bezier curves flattened to polylines in user space and transformed, filled
 * (filltype) in the fill colour and stroked in the pen colour, labels in the stroke font. The
 * binary and portable forms of one drawing give the same statements. Returns 0, or -65 with
 * "NAME: byte N: what was expected" in err, -70/-74 from the writer. */
int plotmeta_import(const void *buf, size_t n, const char *name, meta_writer_t *w, char *err,
		size_t errlen);

#endif
