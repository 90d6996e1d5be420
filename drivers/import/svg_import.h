/* svg_import.h: SVG to meta for `locus-meta import`: the parts' shared types (reader, paths, CSS). */
#ifndef LOCUS_SVG_IMPORT_H
#define LOCUS_SVG_IMPORT_H

#include <stddef.h>
#include <stdio.h>
#include <stdint.h>
#include "locus_meta.h"

/* ---- options (import_svg_cli.c parses them) ---- */

enum { SVGP_NONE, SVGP_LAYER, SVGP_COLOUR };   /* --pens by-layer | by-colour */

typedef struct svgimp_opts_s {
	double tol_mm;          /* flattening tolerance, mm on the page (default 0.0125: half a plotter unit) */
	double dpi;             /* meta pixels per inch (default 96: one meta pixel is one CSS px) */
	int pens_mode;          /* SVGP_* */
	const char *carousel;   /* --pens SPEC: the pens' colours (NULL: the 7475a profile's) */
	const char *pen_map[32];/* --pen LAYER=N */
	int npen_map;
	int dedupe;             /* -O dedupe */
	double dedupe_mm;       /* its tolerance (default 0.05 mm) */
	int occlude;            /* -O occlude: hidden lines under later fills removed */
	int stats, json, verbose;
	const char *profile;    /* --profile NAME for the time estimate (default 7475a) */
	FILE *stats_out;        /* where --stats and -v go (NULL: stderr) */
	int quiet;              /* no warnings (the fuzzing harness) */
} svgimp_opts_t;

/* Is buf an XML document (blanks and a BOM, then '<')? HP-GL and plotutils never start so. */
int svgimp_is(const void *buf, size_t n);

/* Import the SVG document buf/n (name for messages) to w as one page. Warnings go to stderr,
 * one per kind of feature left out. Returns 0, -65 (err "NAME:LINE:COL: ..."), -64 (a bad
 * option value), -70 or -74. */
int svgimp_import(const void *buf, size_t n, const char *name, const svgimp_opts_t *o,
		meta_writer_t *w, char *err, size_t errlen);

/* ---- 2-D affine maps: x' = a x + c y + e, y' = b x + d y + f (SVG's matrix(a b c d e f)) ---- */
typedef struct { double a, b, c, d, e, f; } svg_mat_t;
svg_mat_t svg_mat_mul(svg_mat_t m, svg_mat_t n);   /* m then n applied after: n * m */
/* Parse a transform list into *m (identity first); -1 on a syntax error (SVG: then identity). */
int svg_transform_parse(const char *s, svg_mat_t *m);

/* ---- flattened geometry in page pixels (y down) ---- */
typedef struct { double x, y; } svg_pt_t;

typedef struct {
	svg_pt_t *pt;
	size_t n, cap;
	size_t *sub;            /* start index of each subpath */
	unsigned char *closed;  /* per subpath */
	size_t nsub, subcap;
	double tol;             /* flattening tolerance in pixels */
	svg_mat_t m;            /* user space to page pixels */
	int oom;
	size_t limit;           /* points at most (an absurd file): oom set to 2 beyond it */
} svg_geom_t;

int svg_geom_move(svg_geom_t *g, double x, double y);         /* user coordinates */
int svg_geom_line(svg_geom_t *g, double x, double y);
void svg_geom_close(svg_geom_t *g);
void svg_geom_cubic(svg_geom_t *g, double x0, double y0, double x1, double y1, double x2,
		double y2, double x3, double y3);
void svg_geom_quad(svg_geom_t *g, double x0, double y0, double x1, double y1, double x2, double y2);
/* The SVG arc from (x0,y0) to (x,y) by the implementation notes (F.6), radii corrected. */
void svg_geom_arc(svg_geom_t *g, double x0, double y0, double rx, double ry, double phi_deg,
		int large, int sweep, double x, double y);
void svg_geom_ellipse(svg_geom_t *g, double cx, double cy, double rx, double ry);
void svg_geom_free(svg_geom_t *g);
/* Path data into g; 0, or 1 when it stopped at an error (what came before it is kept). */
int svg_path_data(svg_geom_t *g, const char *d);
/* A points list (polyline, polygon); 1 when odd or bad (the pairs before kept). */
int svg_points(svg_geom_t *g, const char *s, int close);
/* Parse one number at *s (SVG/CSS syntax); 0 and *s past it, or -1. */
int svg_number(const char **s, double *v);

/* ---- colours and CSS (import_svg_css.c) ---- */
/* A colour: 0 ok (*rgb, *alpha 0..1), -1 not a colour. Keywords handled by the caller. */
int svg_colour(const char *s, uint32_t *rgb, double *alpha);

enum {
	SP_FILL, SP_FILL_OPACITY, SP_FILL_RULE, SP_STROKE, SP_STROKE_WIDTH, SP_STROKE_OPACITY,
	SP_DASHARRAY, SP_DASHOFFSET, SP_LINECAP, SP_LINEJOIN, SP_MITERLIMIT, SP_COLOR, SP_DISPLAY,
	SP_VISIBILITY, SP_OPACITY, SP_FONT_SIZE, SP_CLIP_PATH, SP_MASK, SP_FILTER, SP_MARKER_START,
	SP_MARKER_MID, SP_MARKER_END, SP_TRANSFORM_ORIGIN, SP_TRANSFORM, SP_TEXT_ANCHOR, SP_LETTER_SPACING,
	SP_WORD_SPACING, SP_NPROP
};
extern const char *const svg_prop_name[SP_NPROP];
int svg_prop_find(const char *name, size_t len);   /* SP_* or -1 */

typedef struct svg_sheet svg_sheet_t;
struct _xmlNode;
/* Parse style sheet text (all <style> elements' text in order); warn(user, kind) is called for
 * what it skips (@import, unsupported selectors). NULL only when out of memory. */
svg_sheet_t *svg_sheet_parse(svg_sheet_t *s, const char *text, void (*warn)(void *, const char *),
		void *user);
void svg_sheet_free(svg_sheet_t *s);
/* The declared value of each property for element el (presentation attribute, sheet, style
 * attribute, by origin, !important and specificity), into val[SP_NPROP] (malloc'ed strings or
 * NULL; the caller frees them). */
void svg_cascade(const svg_sheet_t *s, struct _xmlNode *el, char **val);

/* ---- what the reader collects (import_svg.c) and writes (import_svg_out.c) ---- */
enum { SVGI_FILL, SVGI_STROKE, SVGI_TEXT };   /* SVGI_TEXT: a meta text statement, g empty */

typedef struct {
	int kind;               /* SVGI_* */
	uint32_t rgb;           /* the colour drawn (opacity blended over white) */
	uint32_t src_rgb;       /* the file's colour (by-colour pens) */
	double width;           /* stroke width, pixels */
	int cap, join, rule;    /* META_CAP_*, META_JOIN_*, META_RULE_* */
	double miter;
	int layer;              /* index into the layers, -1: outside every layer */
	int pen;                /* pen number given by --pens, 0: none */
	int stroked;            /* a fill whose element is stroked too (-O occlude: the stroke draws its edge) */
	svg_geom_t g;           /* the subpaths, page pixels, y down (dashes already split) */
	char *text;             /* SVGI_TEXT: the string (malloc'ed), drawn in the stroke font */
	double tx, ty;          /* its baseline origin, page pixels, y down */
	double tsize, tangle;   /* capital height in page pixels; angle in degrees, counter-clockwise on the page */
	double tadv;            /* its advance in the user units of its element (text-anchor shifts) */
} svg_item_t;

typedef struct {
	char *label;            /* inkscape:label, or id */
	int pen;                /* assigned pen */
	long line;
} svg_layer_t;

typedef struct {
	const char *name;
	const svgimp_opts_t *o;
	svg_item_t *it;
	size_t n, cap;
	svg_layer_t *layer;
	int nlayer, laycap;
	double W, H;            /* page pixels */
	double px_per_mm;
	unsigned pw, ph;
	double wmm, hmm;
} svg_doc_t;

/* Assign pens, dedupe, report stats and write the page: 0 or the negated status. */
int svg_doc_write(svg_doc_t *d, meta_writer_t *w, char *err, size_t errlen);
/* Split g's subpaths into dash pieces (lengths in pixels, offset from the start). */
int svg_dash_split(svg_geom_t *g, const double *dash, int n, double offset);
/* -O occlude (import_svg_occlude.c): strokes and fill outlines under later fills cut away,
 * fills turned into their outlines. 0, or -1 out of memory. */
int svg_occlude(svg_doc_t *d);

#endif
