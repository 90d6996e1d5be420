/* hpgl_read.h: a reader of HP-GL and HP-GL/2 into strokes per pen in plotter units.
 *
 * It understands IN DF SP PU PD PA PR PE CI AA AR EA RA ER RR EW WG FT PT LT SC IP IW RO LB DT
 * SI SR DI DR SL LO ES CP SM BL PB XT YT TL VS PW WU PC NP CR UL LA FP PM EP and device-control (ESC.) and PCL/PJL framing, and skips every other
 * two-letter command with its parameters (listed in hpgl_doc_t.unknown). It is tolerant of what
 * real files contain: lower case, missing ';' between commands, blanks, CR/LF and control bytes
 * between commands, parameters separated by blanks, and bytes that are no command after the
 * last one. It is strict where guessing would draw something else: a malformed number, an odd
 * coordinate count, bad PE data, an unterminated label, a stray byte before a further command;
 * the error names the byte offset.
 *
 * Used by the tests (every stroke of a meta file drawn exactly once), and meant for locus-diff,
 * an import tool and the plotter emulator of the transports.
 */
#ifndef LOCUS_HPGL_READ_H
#define LOCUS_HPGL_READ_H

#include <stddef.h>
#include <stdio.h>

/* A point in plotter units (after SC scaling). */
typedef struct {
	double x, y;
} hpgl_rpt_t;

/* What drew a stroke. */
enum {
	HPGL_RS_LINE = 0,           /* pen-down moves: PD PA PR PE, CI AA AR */
	HPGL_RS_EDGE = 1,           /* outlines: EA ER EW EP */
	HPGL_RS_FILL = 2            /* the contour of a fill: RA RR WG FP (the fill itself) */
};

/* LT: no pattern (a solid line). */
#define HPGL_LT_SOLID 100

/* The line, fill and window state in force when a stroke or label began (PW WU PC NP LT FT IW
 * FP). Lengths are plotter units, resolved when the command was read. */
typedef struct {
	double width_mm;            /* PW of the pen, millimetres; < 0: the file gave none */
	long rgb;                   /* PC colour of the pen, 0xRRGGBB; < 0: none given */
	int lt;                     /* LT pattern -8 .. 8 (negative: adaptive), or HPGL_LT_SOLID */
	double lt_len;              /* the pattern's length, plotter units (> 0) */
	double lt_pat[20];          /* its dashes and gaps (dash first), percent of the length */
	int lt_n;                   /* how many (0 with HPGL_LT_SOLID; UL may redefine 1 .. 8) */
	int cap, join;              /* LA: ends 1 butt 2 square 3 triangular 4 round, joins 1 miter
	                             * 2 miter/bevel 3 triangular 4 round 5 bevel 6 none; 0 none given */
	int ft;                     /* FT: 1 2 solid, 3 hatch, 4 cross-hatch, 10 shading, 11 user (solid) */
	double ft_space;            /* FT 3 4: line spacing, plotter units (> 0) */
	double ft_angle;            /* FT 3 4: hatch angle, degrees */
	double ft_shade;            /* FT 10: shading, percent of the pen's colour (0 .. 100) */
	int nonzero;                /* FP's fill rule: 0 even-odd, 1 non-zero winding */
	int iw;                     /* 1: IW clips to the window below */
	double iw_x0, iw_y0, iw_x1, iw_y1;
	/* added for issue 22 */
	int ro;                     /* RO in force: 0 90 180 270 (already applied to the doc's points,
	                             * labels, window and hatch angle: they are on the paper's axes) */
	int cs, ca;                 /* CS / CA: the standard and alternate character sets */
} hpgl_rattr_t;

/* One stroke: a polyline of n >= 2 points drawn with one pen. */
typedef struct {
	int pen;                    /* SP number in force (0: none selected) */
	int kind;                   /* HPGL_RS_* */
	size_t start, n;            /* points pts[start .. start + n) */
	size_t cmd;                 /* index of the command that began it (0 = the first command) */
	size_t offset;              /* byte offset of that command */
	/* added in round 2 (the fields above are unchanged) */
	size_t attr;                /* its attributes: doc.attrs[attr] */
	size_t group;               /* > 0: the contours of one FP/EP polygon share it (holes) */
	size_t page;                /* issue 22: the page (PG advances it), 0 first */
} hpgl_rstroke_t;

/* One label (LB): its text and where it starts. */
typedef struct {
	int pen;
	double x, y;
	char *text;                 /* NUL-terminated copy, terminator not included */
	size_t len;
	size_t offset;
	/* added in round 2: how the plotter lays it out (x, y above is the pen's point) */
	size_t attr;                /* doc.attrs[attr]: colour, width, window */
	double cw, ch;              /* character width and cap height, plotter units (SI SR) */
	double dx, dy;              /* the run direction, a unit vector (DI DR) */
	double slant;               /* SL: tangent of the slant */
	double es_char, es_line;    /* ES: extra space, in cell widths and line heights */
	int origin;                 /* LO: 1 .. 9, 11 .. 19 */
	int symbol;                 /* 1: an SM symbol, centred on the point */
	double crx, cry;            /* the carriage-return point when it began (CR goes back there) */
	size_t page;                /* issue 22: the page (PG advances it) */
} hpgl_rlabel_t;

/* Lay label l out as the plotter does: a fixed-pitch cell of 1.5 character widths (plus ES) per
 * character, lines 2 cap heights apart (plus ES), each portion up to a CR or LF placed by LO by
 * its own length; CR returns to the carriage-return point, LF goes a line down (the
 * carriage-return point too), BS a cell back, SO and SI select the alternate (CA) and standard
 * (CS) character set. Calls fn (when not NULL) with each printable byte (plus 0x100 while SO is in
 * force) and the origin
 * of its cell (plotter units); the first non-zero fn returns ends the walk and is returned.
 * *px, *py: where the pen is after the label (the next character's origin). Used by the reader
 * for the pen after LB and by the import for drawing. */
int hpgl_label_walk(const hpgl_rlabel_t *l, int (*fn)(void *user, int ch, double x, double y),
		void *user, double *px, double *py);

/* A warning of a tolerant read: what was skipped, and where. */
typedef struct {
	size_t offset;              /* byte offset of what was skipped */
	char msg[400];              /* "NAME: byte N: ..." */
} hpgl_rwarn_t;

#define HPGL_MAX_WARNS 100

/* The result of a read. Read-only for the caller; free with hpgl_doc_free. */
typedef struct {
	hpgl_rpt_t *pts;
	size_t npts;
	hpgl_rstroke_t *strokes;
	size_t nstrokes;
	hpgl_rlabel_t *labels;
	size_t nlabels;
	size_t ncmds;               /* commands read */
	size_t nunknown;            /* commands skipped uninterpreted */
	char unknown[128];          /* their distinct mnemonics, space separated (as many as fit) */
	size_t nescapes;            /* device-control and PCL escapes skipped */
	unsigned pen_selects;       /* SP commands */
	int hpgl2;                  /* 1 when HP-GL/2 commands (PE FP PM PW ...) were seen */
	size_t trailing;            /* bytes after the last command that were no command */
	/* internal capacities */
	size_t cappts, capstrokes, caplabels;
	/* added in round 2 */
	hpgl_rattr_t *attrs;        /* attribute sets, referred to by strokes and labels */
	size_t nattrs, capattrs;
	double p1x, p1y, p2x, p2y;  /* P1 and P2 at the end of the file */
	/* added for issue 22 */
	size_t npages;              /* pages drawn on (PG after drawing starts the next one); >= 1 */
	hpgl_rwarn_t *warns;        /* tolerant reads: what was skipped, in file order */
	size_t nwarns, capwarns;
	size_t nwarns_more;         /* warnings beyond HPGL_MAX_WARNS, counted only */
} hpgl_doc_t;

/* Read len bytes of HP-GL. name is used in messages ("NAME: byte 123: ..."). Returns 0, or -1
 * with a one-line message in err (out of memory also). The doc is filled in either case (up
 * to the error) and must be freed. */
int hpgl_read_mem(const void *buf, size_t len, const char *name, hpgl_doc_t *doc, char *err,
		size_t errlen);
/* Flags of hpgl_read_mem_flags. */
#define HPGL_READ_TOLERANT 1   /* skip what a plotter would skip, with a warning in doc->warns:
                                * junk between commands, a command whose parameters or PE data
                                * cannot be read (to its ';'), trailing bytes; and warn of each
                                * unknown mnemonic. Without it (hpgl_read_mem) those are refused. */
/* hpgl_read_mem with flags. */
int hpgl_read_mem_flags(const void *buf, size_t len, const char *name, int flags, hpgl_doc_t *doc,
		char *err, size_t errlen);
/* Read a whole stream (it is read into memory first), as hpgl_read_mem. */
int hpgl_read_stream(FILE *f, const char *name, hpgl_doc_t *doc, char *err, size_t errlen);
/* Free what a read allocated (the struct itself is the caller's). */
void hpgl_doc_free(hpgl_doc_t *doc);
/* Total pen-down length of the strokes of kind (or all kinds with kind < 0), plotter units. */
double hpgl_doc_length(const hpgl_doc_t *doc, int kind);

#endif
