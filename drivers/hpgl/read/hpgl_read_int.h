/* hpgl_read_int.h: the HP-GL reader's internal state and its drawing helpers (hpgl_read_draw.c),
 * shared by the parser (hpgl_read.c). Not a public header: use hpgl_read.h. */
#ifndef LOCUS_HPGL_READ_INT_H
#define LOCUS_HPGL_READ_INT_H

#include <stddef.h>
#include "util/grow.h"
#include "hpgl/read/hpgl_lex.h"
#include "hpgl/read/hpgl_read.h"

/* The parser's state: input, place, and the plotter state it tracks. */
typedef struct {
	const unsigned char *s;
	size_t n, i;
	const char *name;
	char *err;
	size_t errlen;
	hpgl_doc_t *doc;
	/* plotter state */
	int pen, down, rel, poly;   /* poly: inside PM0 .. PM2 */
	int newc;                   /* poly: the next pen-down point starts a contour */
	double x, y;                /* current position, plotter units */
	int sc;                     /* 0 none, 1 scaling on */
	double p1x, p1y, p2x, p2y;  /* IP */
	double sc_xmin, sc_xmax, sc_ymin, sc_ymax, sx, sy, ox, oy;
	double sc_v[5];             /* the SC in force, to map again when IP moves P1 and P2 */
	int sc_nv;
	unsigned char term;         /* label terminator */
	int open;                   /* 1 while a stroke is being drawn */
	size_t cmd, cmd_off;
	/* round 2: the line, fill, window and label state (hpgl_read_attr.c) */
	hpgl_rattr_t at;            /* in force (its width and colour come from pw, pal) */
	double pw[256];             /* PW per pen (pen & 255), mm; < 0 none */
	long pal[256];              /* PC per pen, 0xRRGGBB; < 0 none */
	double cr[6];               /* CR colour ranges: black and white reference per primary */
	int wu;                     /* WU 1: PW in percent of the P1-P2 diagonal */
	double ul[8][20];           /* UL: user line types 1 .. 8 (percent), ul_n[k] 0 = the fixed one */
	int ul_n[8];
	int lt_saved;               /* LT 99 restores it */
	double lt_saved_len;
	size_t group, ngroups;      /* polygon group of the figures being made; groups so far */
	int lsize, ldir;            /* 0 SI / DI absolute, 1 SR / DR relative to P1-P2 */
	double lsw, lsh, ldx, ldy;  /* their parameters as given */
	double slant, es_char, es_line;
	int lo;
	unsigned char sm;           /* SM symbol, 0 none */
	double crx, cry;            /* carriage-return point (CP, CR in labels) */
	unsigned char *bl;          /* BL's buffered label (PB draws it) */
	size_t nbl;
	double tl_p, tl_n;          /* TL: tick lengths, percent of P2 - P1 */
	/* the polygon buffer: contours of points */
	hpgl_rpt_t *pb;
	size_t npb, cappb;
	size_t *pbs;                /* contour starts */
	size_t npbs, cappbs;
	/* issue 22 */
	int tolerant;               /* HPGL_READ_TOLERANT */
	size_t fail_off;            /* the byte of the last hpgl_rd_fail, and its message */
	char fail_msg[160];
	int nomem;                  /* the failure was out of memory */
	size_t page;                /* the page being drawn (PG) */
	int page_used;              /* something was drawn on it */
	int ip_set;                 /* IP gave P1 (and P2) since IN: RO leaves them */
	int rotated;                /* an RO other than 0 was in force for something drawn */
} hpgl_rd_t;


/* A parameter as an int (pens, types, modes): clamped to +-2^30 first (a cast of a larger double
 * is undefined behaviour), fractions cut off. */
static inline int hpgl_rd_int(double v)
{
	return v >= 1073741824.0 ? 1073741824 : v <= -1073741824.0 ? -1073741824 : v == v ? (int)v : 0;
}

/* Record "NAME: byte OFF: message" in r->err; returns -1. */
int hpgl_rd_fail(hpgl_rd_t *r, size_t off, const char *fmt, ...)
#ifdef __GNUC__
	__attribute__((format(printf, 3, 4)))
#endif
	;
/* A warning of a tolerant read at byte off (kept in doc->warns). */
void hpgl_rd_warn(hpgl_rd_t *r, size_t off, const char *fmt, ...)
#ifdef __GNUC__
	__attribute__((format(printf, 3, 4)))
#endif
	;
/* Out of memory at the current byte; -1. */
int hpgl_rd_nomem(hpgl_rd_t *r);
/* Grow *p (cap elements of size bytes) to hold need; 0 or -1. Inline: it is on the path of
 * every point. */
static inline int hpgl_rd_grow(void **p, size_t *cap, size_t need, size_t size)
{
	return dev_grow(p, cap, need, size, 64);
}
/* End the stroke being drawn (a lone point is dropped). */
void hpgl_rd_end_stroke(hpgl_rd_t *r);
/* Append a point to the open stroke. */
int hpgl_rd_add_pt(hpgl_rd_t *r, double x, double y);
/* Begin a stroke of kind at the current position. */
int hpgl_rd_begin_stroke(hpgl_rd_t *r, int kind);
/* Polygon mode: start a contour at (x, y). */
int hpgl_rd_start_contour(hpgl_rd_t *r, double x, double y);
/* Move to (x, y) plotter units with the pen as it is (drawing, or into the polygon buffer). */
int hpgl_rd_move_to(hpgl_rd_t *r, double x, double y);
/* A figure of n points as a stroke of its own; the pen position is kept. */
int hpgl_rd_figure(hpgl_rd_t *r, const hpgl_rpt_t *p, size_t n, int kind);
/* User units to plotter units: a point, and a length (SC in force). */
void hpgl_rd_user_to_pu(const hpgl_rd_t *r, double u, double v, double *x, double *y);
void hpgl_rd_user_len(const hpgl_rd_t *r, double u, double v, double *x, double *y);
/* A chord angle (degrees) as the plotter takes it: its magnitude within 0.5 .. 180; 0 or none: 5. */
double hpgl_rd_chord(double chord);
/* An arc about (cx, cy) from angle a0 (radians) through sweep degrees in chord-degree steps. */
int hpgl_rd_arc_points(hpgl_rd_t *r, double cx, double cy, double rad, double a0, double sweep, double chord);
/* CI: a circle about the current position (a contour of its own in polygon mode), of radius rad
 * along x and rady along y (different under anisotropic scaling). */
int hpgl_rd_circle(hpgl_rd_t *r, double rad, double rady, double chord, int kind);
/* SC with nv parameters (none: scaling off). */
void hpgl_rd_set_scaling(hpgl_rd_t *r, const double *v, int nv);
/* P1 and P2 where IN (and IP without parameters) put them: the 7475A's A4 defaults. */
void hpgl_rd_default_p1p2(hpgl_rd_t *r);
/* IN (in = 1) or DF defaults. */
void hpgl_rd_defaults(hpgl_rd_t *r, int in);
/* Attribute and label state to its defaults: IN (in = 1, also PW PC WU) or DF. */
void hpgl_rd_attr_defaults(hpgl_rd_t *r, int in);
/* The index in doc->attrs of the attributes in force (appended when they changed); or
 * (size_t)-1 out of memory (the message set). */
size_t hpgl_rd_attr(hpgl_rd_t *r);
/* The state commands PW WU PC NP CR LT FT IW SI SR DI DR SL LO ES CP: 1 handled, 0 not one of
 * them, -1 failed (the message set). */
int hpgl_rd_state(hpgl_rd_t *r, const char *mn, const double *v, int nv);
/* LB (and an SM symbol when symbol = 1): record the label text[0, len) at the pen and move the
 * pen past it as the plotter does. 0 or -1. */
int hpgl_rd_label(hpgl_rd_t *r, const unsigned char *text, size_t len, int symbol);
/* PM n. */
int hpgl_rd_pm(hpgl_rd_t *r, const double *v, int nv);
/* FP / EP: the polygon buffer's contours as strokes of kind. */
int hpgl_rd_polygon_out(hpgl_rd_t *r, int kind);
/* EA ER RA RR rectangles; EW WG wedges. */
int hpgl_rd_rect(hpgl_rd_t *r, const char *mn, const double *v, int nv, int relative, int kind);
/* The same for each further corner given (EA ER RA RR with more than two numbers). */
int hpgl_rd_rects(hpgl_rd_t *r, const char *mn, const double *v, int nv, int relative, int kind);
int hpgl_rd_wedge(hpgl_rd_t *r, const char *mn, const double *v, int nv, int kind);

#endif
