/* psdev.h: what the PostScript (EPS, PS) and PDF devices share: options, page placement on
 * paper, the box of what is drawn, grey conversion, and spans and image rows merged into images.
 *
 * Both devices write the page on an integer grid of PSD_GRID units per pixel (coordinates are
 * rounded to it; 1/10 pixel is finer than a 600 dpi printer dot at the default 96 pixels per
 * inch). A page of W x H pixels has a natural size: its `size` statement, else 96 pixels per
 * inch. Without a paper option the medium is exactly that size; with one the picture is placed
 * on the paper inside the margins (fitted, centred at natural size, or scaled).
 */
#ifndef LOCUS_PSDEV_H
#define LOCUS_PSDEV_H

#include <stdint.h>
#include "device/device.h"
#include "ps/psenc.h"

#define PSD_GRID 10          /* grid units per pixel */

enum { PSD_EPS, PSD_PS, PSD_PDF };
enum { PSD_PLACE_FIT, PSD_PLACE_CENTRE, PSD_PLACE_SCALE };

typedef struct psd psd_t;

/* A run of image rows being merged from put_span / put_image_row calls: the rows tile the
 * columns [x0, x0 + w) exactly, each next row directly below (dir -1) or above (dir +1). */
typedef struct {
	int active;
	unsigned x0, w;          /* w = 0 while the first row is still growing */
	unsigned y0;             /* page row of the first row */
	int dir;                 /* -1, +1, or 0 while there is one row */
	unsigned nrows;          /* rows begun (the last may be partial) */
	unsigned fill;           /* pixels in the last row */
	uint8_t *pix;            /* rows in arrival order, 3 bytes a pixel */
	size_t cap;
} psd_block_t;

/* The device's hooks for what the shared code emits. */
typedef struct {
	/* an image of w x h pixels (RGB, h rows top row first) with bottom-left pixel (x, y) */
	int (*image)(psd_t *p, unsigned x, unsigned y, unsigned w, unsigned h, const uint8_t *rgb);
	/* a filled rectangle of pixels [x, x + w) x [y, y + h) in one colour */
	int (*rect)(psd_t *p, unsigned x, unsigned y, unsigned w, unsigned h, meta_rgb_t rgb);
} psd_hooks_t;

struct psd {
	dev_writer_t out;                  /* the writer (first: it is large) */
	dev_device_t *dev;
	int form;                       /* PSD_* */
	psd_hooks_t hooks;
	/* options */
	int level;                      /* PostScript language level 1, 2, 3 */
	int grey;                       /* 1: grey levels only */
	unsigned dither;                /* dots per inch of an ordered dither of images, 0: none */
	int date;                       /* 1: write a creation date */
	int media;                      /* 1: PostScript asks for the medium (setpagedevice) */
	double paper_w, paper_h;        /* pt; 0 = the page's natural size */
	int landscape;                  /* swap the paper's sides */
	int place;                      /* PSD_PLACE_* */
	double scale;                   /* for PSD_PLACE_SCALE */
	double margin;                  /* pt */
	char title[128];                /* %%Title / Info Title, may be empty */
	/* document */
	int per_page;                   /* one document per page (a transport per page) */
	int doc_open;
	unsigned doc_pages;             /* pages in the current document */
	long long epoch;                /* creation time (seconds) when date is 1 */
	/* the page */
	dev_page_t page;
	double media_w, media_h;        /* pt */
	double ox, oy, sx, sy;          /* pixel (x, y) lands at (ox + sx x, oy + sy y) pt */
	int64_t bx0, by0, bx1, by1;     /* drawn box, thousandths of a pixel */
	int drawn;
	double dbx0, dby0, dbx1, dby1;  /* union of the pages' boxes, pt */
	int ddrawn;
	psd_block_t blk;
	void *form_state;               /* the device's own (PDF: objects) */
	/* tokens */
	int col;                        /* output column of the current line */
	int wrap;                       /* start a new line past this column (0: only at psd_newline) */
};

/* Read the -O options shared by both devices into p (form set by the caller). 0 or
 * DEV_EUSAGE with a message naming the option. */
int psd_options(psd_t *p, dev_device_t *d);
/* The option table both devices declare (the level key is PostScript's only). */
extern const dev_option_t psd_ps_options[];
extern const dev_option_t psd_pdf_options[];

/* Start a page: compute the medium and placement, empty the drawn box. */
void psd_page(psd_t *p, const dev_page_t *pg);
/* Grow the drawn box by the rectangle [x0, x1] x [y0, y1] (thousandths of a pixel). */
void psd_grow(psd_t *p, int64_t x0, int64_t y0, int64_t x1, int64_t y1);
/* Grow the drawn box by what stroking or filling the path paints (stroke = 1: with the width,
 * caps, joins and miter limit of st). */
void psd_grow_path(psd_t *p, const dev_path_t *dp, const dev_state_t *st, int stroke);
/* The page's drawn box in points, clipped to the page; 0 when nothing was drawn. */
int psd_page_box(const psd_t *p, double *x0, double *y0, double *x1, double *y1);

/* 1 when the path is written from its raw elements (native arcs), 0 when from its flattened
 * points: text, and paths with arcs so large (radius or centre beyond 2^16 pixels) that
 * interpreters working in fixed point overflow on them (Ghostscript's bbox device does). */
int psd_native(const dev_path_t *dp);
/* Merge a span (x, y, n pixels of rgb; y counted from the bottom) into the open image block,
 * emitting the block first when the span does not continue it. */
int psd_span(psd_t *p, unsigned x, unsigned y, unsigned n, meta_rgb_t rgb);
/* The same for an image row of runs starting at x. */
int psd_row(psd_t *p, unsigned x, unsigned y, const meta_run_t *runs, size_t nruns);
/* ---- what both devices' hooks share ---- */

/* Before a path is painted: emit the open image block, then grow the drawn box by what the path
 * paints (stroke = 1: with the line state of st). 0 or <0. */
int psd_paint_begin(psd_t *p, const dev_path_t *dp, const dev_state_t *st, int stroke);
/* The devices' put_span, put_image_row and clear (d->priv starts with a psd_t): spans and rows
 * merge into image blocks; a clear is a rectangle of the whole page through hooks.rect. */
int psd_dev_span(dev_device_t *d, unsigned x, unsigned y, unsigned n, meta_rgb_t rgb);
int psd_dev_row(dev_device_t *d, unsigned x, unsigned y, const meta_run_t *runs, size_t nruns);
int psd_dev_clear(dev_device_t *d, const dev_page_t *pg, meta_rgb_t rgb);

/* Write a separator before the next token: a space, or a newline past the wrap column. */
void psd_sep(psd_t *p);
/* Write a token after a separator. */
void psd_tok(psd_t *p, const char *t);
/* Write an integer token. */
void psd_int(psd_t *p, long long v);
/* End the current line, if any. */
void psd_newline(psd_t *p);
/* Write a string literal (...) with ( ) and \ escaped (titles). */
void psd_string(dev_writer_t *o, const char *t);

/* Emit the open block (before anything else paints, and at the end of the page). */
int psd_flush(psd_t *p);
/* Free the block's memory. */
void psd_release(psd_t *p);
/* Report the writer's failure (p->out.err) on the device: out of memory as META_ENOMEM, a failed
 * transport with its own line (the output and strerror), else "OUTPUT: write failed". */
int psd_out_fail(psd_t *p);

/* An image's samples as the device writes them: RGB, grey (luminance) or, with a dither,
 * one bit a printer dot (1 = white), rows top first, each row padded to whole bytes. */
typedef struct {
	const uint8_t *data;
	size_t n;                        /* bytes */
	unsigned width, height;          /* samples */
	int bpc, comps;                  /* bits per component (8 or 1), components (3 or 1) */
	uint8_t *owned;                  /* what to free */
} psd_samples_t;

/* The samples for an image of w x h page pixels at (x, y), by the grey and dither options.
 * 0, or META_ENOMEM with a message. */
int psd_samples(psd_t *p, unsigned x, unsigned y, unsigned w, unsigned h, const uint8_t *rgb, psd_samples_t *out);

/* Luminance of a colour, 0..255: (299 R + 587 G + 114 B) / 1000 rounded (ITU-R BT.601). */
unsigned psd_luma(meta_rgb_t rgb);
/* A colour component v (0..255) as the shortest decimal of at most three places whose
 * product with 255 lies in [v, v + 1/2), so that readers that round and readers that truncate
 * both recover v (0, 1, .189 for 48) into buf. */
void psd_unit(unsigned v, char *buf, size_t n);
/* Round thousandths of a pixel to the grid (ties away from zero). */
long long psd_grid(int64_t thousandths);
/* 1 when a draw by (vx, vy) goes straight on from one by (ux, uy), both not zero, so that the
 * point between them turns no corner and the two are one draw (PostScript and PDF paths drop
 * such points, and points equal to the one before); 0 also when a delta is too large (2^30 grid
 * units) to multiply exactly. */
int psd_straight(long long ux, long long uy, long long vx, long long vy);
/* "D:YYYYMMDDHHMMSSZ" (pdf = 1) or "YYYY-MM-DDTHH:MM:SSZ" for epoch seconds into buf. */
void psd_date(long long epoch, int pdf, char *buf, size_t n);

#endif
