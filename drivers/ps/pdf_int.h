/* pdf_int.h: the PDF device's state, its objects (pdfobj.c) and its content streams and path
 * writer (pdfpath.c), shared by dev_pdf.c, pdfobj.c and pdfpath.c only. */
#ifndef LOCUS_PDF_INT_H
#define LOCUS_PDF_INT_H

#include "ps/psdev.h"

#define PDF_ROW 12         /* bytes of a predictor sample: one point "xxxx yyyy l\n" */
#define PDF_COLUMNS 1024   /* samples of a predictor row */
#define PDF_GROUP 32       /* paths whose origins chain by relative cm inside one q ... Q */

/* A growable list of numbers (object numbers, offsets). */
typedef struct {
	uint64_t *v;
	size_t n, cap;
} pdf_list_t;

/* What was last set in the graphics state (saved by q, restored by Q). */
typedef struct {
	int known;                   /* 0 at page start: everything must be set */
	meta_rgb_t stroke_rgb, fill_rgb;
	int have_stroke, have_fill;
	int64_t width, miter;
	int cap, join;
	int64_t dash[2 * META_MAX_DASH];
	size_t ndash;
} pdf_gs_t;

/* One point of a path without arcs, relative to the path's origin: op 'm', 'l' or 'h' (a
 * closepath, no point). */
typedef struct {
	long long x, y;
	char op;
} pdf_pt_t;

typedef struct {
	psd_t p;
	pdf_gs_t g;                  /* in force */
	pdf_gs_t saved;              /* at the open group's q */
	pdf_list_t offsets;          /* offsets[k]: object k + 1 */
	pdf_list_t kids;             /* page objects */
	pdf_list_t contents;         /* this page's content streams */
	pdf_list_t images;           /* this page's image XObjects */
	long long org_x, org_y;      /* grid point the path's coordinates are relative to */
	unsigned group;              /* paths in the open q ... Q group (0: none open) */
	long long gx, gy;            /* the translation in force inside the group */
	int group_far;               /* the group's origin is far off the page: it ends at the next path */
	int rows;                    /* the open stream has the predictor */
	size_t packed_run;           /* points of text paths in the predicted stream since the last predicted path */
	pdf_pt_t *pts;               /* the path being written */
	size_t npts, cappts;
	unsigned stream_obj;         /* the open content stream (0: none) */
	uint64_t stream_start;
} pdf_t;

/* The objects (pdfobj.c). Append v to the list l; 0 or META_ENOMEM with a message. */
int pdf_list_add(psd_t *p, pdf_list_t *l, uint64_t v);
/* Reserve the next object number (its offset is set when it is written); 0 when out of memory. */
unsigned pdf_new_obj(pdf_t *s);
/* Start object n at the current output offset ("n 0 obj"). */
void pdf_begin_obj(pdf_t *s, unsigned n);
/* 0, or the output's error (recorded on the device) when writing failed. */
int pdf_failed(pdf_t *s);

/* The content streams and paths (pdfpath.c). Open a content stream (rows = 1: Flate with TIFF predictor rows of PDF_COLUMNS samples of
 * PDF_ROW bytes). 0 or <0. */
int pdf_open_stream(pdf_t *s, int rows);
/* Close the open content stream (and its group), if any. 0 or <0 with a message. */
int pdf_close_stream(pdf_t *s);
/* End the open q ... Q group: Q, and the graphics state as it was at q. */
void pdf_end_group(pdf_t *s);
/* Forget the graphics state (page start). */
void pdf_reset_state(pdf_t *s);
/* Stroke (fill = 0) or fill the path with the state st: colour, line state, origin, points,
 * paint operator, switching between plain and predicted streams where that pays. 0 or <0. */
int pdf_paint(pdf_t *s, const dev_path_t *dp, const dev_state_t *st, int fill);
/* Set the fill colour (for rectangles of the image blocks) unless it is in force. */
void pdf_fill_colour(pdf_t *s, meta_rgb_t c);

#endif
