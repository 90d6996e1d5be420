/* ps_int.h: the PostScript device's state and its path and state writer (pspath.c), shared by
 * dev_ps.c and pspath.c only. */
#ifndef LOCUS_PS_INT_H
#define LOCUS_PS_INT_H

#include "ps/psdev.h"

#define PSP_CHUNK 200      /* relative lineto pairs per L (Level 1 operand stack: 500) */

/* The device's state: the shared part plus what was last set in the graphics state. */
typedef struct {
	psd_t p;
	int known;             /* 0 at page start: everything must be set */
	meta_rgb_t colour;
	int64_t width, miter;
	int cap, join;
	int64_t dash[2 * META_MAX_DASH];
	size_t ndash;
	int packed;            /* level 3: the page body is Flate-compressed and executed */
	int colorimage;        /* level 1: a colour image was written (CI: colorimage, or grey) */
	void *spool;           /* EPS: the body while its box is not known */
	long long *dx;         /* pending relative draws, grid units */
	size_t ndx, capdx;
} ps_t;

/* Set the colour (exact 8-bit: <rrggbb> K, or a grey level G) unless it is in force. */
void psp_colour(ps_t *s, meta_rgb_t c);
/* Set width, cap, join, miter limit and dash as the state says, where they changed. */
void psp_line(ps_t *s, const dev_state_t *st);
/* Write the path (fill = 1: closepaths that a fill makes anyway are left out). 0 or <0. */
int psp_path(ps_t *s, const dev_path_t *dp, int fill);

#endif
