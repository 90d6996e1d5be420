/* hpgl_read.h: a reader of HP-GL and HP-GL/2 into strokes per pen in plotter units.
 *
 * It understands IN DF SP PU PD PA PR PE CI AA AR EA RA ER RR EW WG FT PT LT SC IP IW RO LB DT
 * SI DI VS PW FP PM EP and device-control (ESC.) and PCL/PJL framing, and skips every other
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

/* One stroke: a polyline of n >= 2 points drawn with one pen. */
typedef struct {
	int pen;                    /* SP number in force (0: none selected) */
	int kind;                   /* HPGL_RS_* */
	size_t start, n;            /* points pts[start .. start + n) */
	size_t cmd;                 /* index of the command that began it (0 = the first command) */
	size_t offset;              /* byte offset of that command */
} hpgl_rstroke_t;

/* One label (LB): its text and where it starts. */
typedef struct {
	int pen;
	double x, y;
	char *text;                 /* NUL-terminated copy, terminator not included */
	size_t len;
	size_t offset;
} hpgl_rlabel_t;

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
} hpgl_doc_t;

/* Read len bytes of HP-GL. name is used in messages ("NAME: byte 123: ..."). Returns 0, or -1
 * with a one-line message in err (out of memory also). The doc is filled in either case (up
 * to the error) and must be freed. */
int hpgl_read_mem(const void *buf, size_t len, const char *name, hpgl_doc_t *doc, char *err,
		size_t errlen);
/* Read a whole stream (it is read into memory first), as hpgl_read_mem. */
int hpgl_read_stream(FILE *f, const char *name, hpgl_doc_t *doc, char *err, size_t errlen);
/* Free what a read allocated (the struct itself is the caller's). */
void hpgl_doc_free(hpgl_doc_t *doc);
/* Total pen-down length of the strokes of kind (or all kinds with kind < 0), plotter units. */
double hpgl_doc_length(const hpgl_doc_t *doc, int kind);

#endif
