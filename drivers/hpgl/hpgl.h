/* hpgl.h: the HP-GL pen-plotter and cutter driver's parts: profiles, pens, page mapping, path
 * geometry (clipping, dashes, wide-line passes, drag-knife offset), the HP-GL/HP-GL/2 emitter
 * and the plot-time model. The device itself is dev-hpgl.c (ops table dev_hpgl_ops); the
 * reader of HP-GL is hpgl_read.h, path ordering pathopt.h, hatching hpgl_hatch.h.
 *
 * Units: plotter units (1 pu = 0.025 mm, 40 per mm) everywhere below unless a name says mm.
 * Every function returns 0 or <0 with a one-line message in err; none prints.
 */
#ifndef LOCUS_HPGL_H
#define LOCUS_HPGL_H

#include <stddef.h>
#include <stdint.h>
#include "hpgl/pathopt.h"
#include "io/transport.h"

#define HPGL_PU_PER_MM 40.0
#define HPGL_MAX_PENS 256

/* Paper sizes every profile may define (its hard-clip limits). */
enum { HPGL_PAPER_A4, HPGL_PAPER_A3, HPGL_PAPER_LETTER, HPGL_PAPER_B, HPGL_NPAPER };

/* Dialects. */
enum { HPGL_DIALECT_1 = 1, HPGL_DIALECT_2 = 2 };

/* Settings of one pen slot, sent when the pen is selected (SP): speed (VS, cm/s), force (FS)
 * and acceleration (AS) in the plotter's own units (7550A: force levels 1-8, acceleration
 * levels 1-4), 0 = not set (the profile's speed, the plotter's default force and
 * acceleration); pause: the sender stops with the pen up before this pen is loaded and asks
 * for it (docs/hpgl.md, "Per-pen settings and pauses"). */
typedef struct {
	double speed, force, accel;
	int pause;
} hpgl_penset_t;

/* A device description: built in (hpgl_profile_find) or read from a profile file. */
typedef struct {
	char name[32];
	char description[96];
	int dialect;                /* HPGL_DIALECT_* */
	int cutter;                 /* 1: a drag-knife cutter (knife offset, overcut) */
	int has_paper[HPGL_NPAPER];
	int32_t clip[HPGL_NPAPER][4]; /* hard-clip limits x0 y0 x1 y1 per paper, plotter units */
	int paper;                  /* the default paper */
	unsigned max_pairs;         /* coordinate pairs per PU/PD/PE command a receiver takes */
	unsigned buffer;            /* input buffer bytes (documentation and --estimate) */
	unsigned npens;             /* carousel slots */
	char pens[256];             /* default carousel, "1=black;2=red:0.3mm" syntax */
	double v_down;              /* pen-down speed, cm/s (VS) */
	double v_up;                /* pen-up speed, cm/s */
	double accel;               /* acceleration, m/s^2 */
	double t_lift;              /* seconds per pen lift or drop */
	double t_change;            /* seconds per pen change */
	double knife_offset;        /* mm, cutters */
	double overcut;             /* mm, cutters: closed paths are cut on past their start */
	int newline;                /* 1: a newline after every command (USB printer-class cutters) */
	int has_fs, has_as;         /* 1: takes FS (force select) / AS (acceleration select) */
	int pause_all;              /* 1: hand-fed: a pause before every pen change */
	hpgl_penset_t penset[HPGL_MAX_PENS + 1];   /* per slot (pen.N = ... in a profile file) */
} hpgl_profile_t;

/* Built-in profiles: count, k-th, and lookup by name (NULL when unknown). */
size_t hpgl_profile_count(void);
const hpgl_profile_t *hpgl_profile_builtin(size_t k);
const hpgl_profile_t *hpgl_profile_find(const char *name);
/* Parse a profile file's text (docs/hpgl.md, "Profile files") into p. name is the file's name
 * for messages ("NAME:LINE:COL: ..."). Returns 0 or -1 with err set. */
int hpgl_profile_parse(const char *text, size_t len, const char *name, hpgl_profile_t *p,
		char *err, size_t errlen);
/* Load a profile file from disk (reads it whole, then hpgl_profile_parse). -1 also when the
 * file cannot be read (err says so). */
int hpgl_profile_load(const char *path, hpgl_profile_t *p, char *err, size_t errlen);
/* Per-pen settings: "N:speed=V;force=F;accel=A;pause/N:..." (pens apart by '/' or blanks,
 * settings by ';' or ','; "pause" alone or pause=yes|no) merged into set[1..HPGL_MAX_PENS].
 * Returns 0 or -1 with err naming the item. */
int hpgl_penset_parse(const char *spec, hpgl_penset_t *set, char *err, size_t errlen);
/* One pen's settings "speed=V,force=F,accel=A,pause" merged into *one. 0 or -1 with err. */
int hpgl_penset_items(const char *items, hpgl_penset_t *one, char *err, size_t errlen);
/* Pens to pause before: "2;3" or "2,3" or "all" (*all set) or "none" merged into set. 0 or -1. */
int hpgl_pause_parse(const char *spec, hpgl_penset_t *set, int *all, char *err, size_t errlen);
/* 0 when the profile takes every setting given in set (FS only with has_fs, AS with has_as,
 * a speed within (0, 1000]), else -1 with err saying which pen and what. */
int hpgl_penset_check(const hpgl_profile_t *prof, const hpgl_penset_t *set, char *err, size_t errlen);

/* A pause before a pen (the program asks for the pen to be loaded). */
typedef struct {
	int slot;                   /* the pen to load */
	const char *layer;          /* its layer's name from the meta file (import --pens by-layer), or NULL */
	unsigned page;              /* 0-based */
} hpgl_pause_t;
/* A program's hook for pauses: ask for the pen; return 0 to go on, 1 to stop (the job then
 * ends as a temporary failure, its journal at the pen change: resumable), with a few words
 * why in why. Process-wide; NULL removes it: every pause is then a stop. */
void hpgl_set_pauser(int (*fn)(void *user, const hpgl_pause_t *p, char *why, size_t whylen), void *user);

/* The paper index of a name ("a4", "a3", "letter", "b"), or -1. */
int hpgl_paper_find(const char *name);
/* The paper's name. */
const char *hpgl_paper_name(int paper);

/* One pen of the carousel. */
typedef struct {
	int slot;                   /* 1 .. HPGL_MAX_PENS */
	uint32_t rgb;               /* 0xRRGGBB */
	double width_mm;            /* tip width */
	double lab[3];              /* CIELAB of rgb (D65) */
} hpgl_pen_t;

/* A carousel: the pens in slot order. */
typedef struct {
	hpgl_pen_t pen[HPGL_MAX_PENS];
	size_t n;
} hpgl_pens_t;

/* Parse "1=black,2=red:0.3mm,3=#00ff00" (',' or ';' or newlines between pens; '#' starts a
 * comment in files only after blanks). default_width_mm is used where no width is given.
 * Returns 0 or -1 with err ("pens: ..." naming the item). */
int hpgl_pens_parse(const char *spec, double default_width_mm, hpgl_pens_t *pens,
		char *err, size_t errlen);
/* The carousel index (into pens->pen) nearest to rgb in CIELAB by the CIE94 difference. */
size_t hpgl_pens_nearest(const hpgl_pens_t *pens, uint32_t rgb);
/* The pen a colour is drawn with: the nearest pen, or -1 when the colour is paper (light,
 * L* >= 80, and nearer to white than to any pen). */
long hpgl_pens_pick(const hpgl_pens_t *pens, uint32_t rgb);
/* CIELAB (D65, sRGB) of a colour. */
void hpgl_rgb_to_lab(uint32_t rgb, double lab[3]);

/* How a model page maps onto the plotter: X = a*x + b*y + c, Y = d*x + e*y + f with (x, y) in
 * thousandths of a pixel, and the clip rectangle (the page's image inside the hard-clip
 * limits). */
typedef struct {
	double a, b, c, d, e, f;
	double clip[4];             /* x0 y0 x1 y1 */
	double pu_per_px;           /* plotter units per pixel (scale) */
} hpgl_map_t;

/* Mapping parameters (device options). */
typedef struct {
	int paper;                  /* HPGL_PAPER_* */
	int rotate;                 /* 0, 90, 180, 270 (degrees counter-clockwise) */
	int mirror;                 /* 0 none, 1 mirror x, 2 mirror y */
	int fit;                    /* 0 physical size (clipped), 1 shrink to fit when too big, 2 fill */
	double scale;               /* extra factor on the physical size (1 = as is) */
} hpgl_place_t;

/* Build the mapping of a page of w x h pixels, of physical size wmm x hmm (0 = 96 pixels per
 * inch), placed by pl onto the profile's paper (centred in its hard-clip limits). */
int hpgl_map_page(const hpgl_profile_t *prof, const hpgl_place_t *pl, unsigned w, unsigned h,
		double wmm, double hmm, hpgl_map_t *m, char *err, size_t errlen);
/* Map one point (thousandths) to plotter units (not rounded). */
void hpgl_map_point(const hpgl_map_t *m, int64_t x, int64_t y, double *X, double *Y);

/* ---- geometry on polylines in plotter units (hpgl_geom.c) ---- */

/* A double point. */
typedef struct {
	double x, y;
} hpgl_dpt_t;

/* Called with each finished polyline of n >= 2 points (closed: the last segment back to the
 * first is implied). Returns 0 or <0 to stop. */
typedef int (*hpgl_poly_fn)(void *user, const hpgl_dpt_t *pts, size_t n, int closed);

/* Clip the polyline to the rectangle r (x0 y0 x1 y1), Liang-Barsky per segment, handing on
 * the visible pieces (a closed polyline that stays whole is handed on closed). */
int hpgl_clip_poly(const hpgl_dpt_t *pts, size_t n, int closed, const double r[4],
		hpgl_poly_fn fn, void *user);
/* Offset a polyline sideways by dist (left positive): mitred joins (at most 4 x dist), bevelled
 * on the outer side of turns sharper than 120 degrees. Writes up to 2n points to out and returns the count. */
size_t hpgl_offset_poly(const hpgl_dpt_t *pts, size_t n, int closed, double dist, hpgl_dpt_t *out);
/* The caps of one parallel pass of an open wide line: the pass at dist from the centre line
 * (of a line of half width r, drawn by a pen of width pen, round-tipped) is lengthened at both
 * ends along its end segments so that the pen's ink reaches the cap as the model raster draws
 * it: square caps r beyond the ends, round caps to the circle of radius r about them
 * (sqrt(r^2 - dist^2)), less the pen's own half width; butt caps (META_CAP_BUTT) leave it. */
void hpgl_cap_pass(hpgl_dpt_t *pts, size_t n, int cap, double r, double pen, double dist);
/* Drag-knife compensation: the tool path that makes a blade trailing offset behind the tool
 * cut the polyline: each segment is shifted forward along its direction by offset, and each
 * corner is swung as an arc of radius offset about the corner; a closed path is cut on for
 * overcut past its start. Calls fn once with the tool path (open). */
int hpgl_knife_poly(const hpgl_dpt_t *pts, size_t n, int closed, double offset, double overcut,
		hpgl_poly_fn fn, void *user);

/* ---- the emitter (hpgl_emit.c) ---- */

typedef struct hpgl_emit hpgl_emit_t;

/* A writer of HP-GL or HP-GL/2 over a borrowed transport (NULL: count bytes only). */
hpgl_emit_t *hpgl_emit_new(io_transport_t *out, const hpgl_profile_t *prof);
void hpgl_emit_free(hpgl_emit_t *e);
/* A raw command text, e.g. "IN" (the terminator ';' and newline are added). */
int hpgl_emit_cmd(hpgl_emit_t *e, const char *fmt, ...)
#ifdef __GNUC__
	__attribute__((format(printf, 2, 3)))
#endif
	;
/* Select pen slot (0 = put the pen away). Nothing when it is already selected. */
int hpgl_emit_pen(hpgl_emit_t *e, int slot);
/* One polyline of integer points, pen up to its start then pen down along it (relative or
 * absolute, whichever is shorter; PE in HP-GL/2), lists split at the profile's max_pairs. */
int hpgl_emit_poly(hpgl_emit_t *e, const popt_pt_t *pts, size_t n);
/* A label at (x, y): DI from the angle, SI from the capital height (mm), LB text ETX. */
int hpgl_emit_label(hpgl_emit_t *e, int32_t x, int32_t y, double height_mm, double angle_deg,
		const char *s, size_t len);
/* Native fill of one polygon, contours as integer polylines: HP-GL/2 PM0 ... PM2 FP (FP0
 * even-odd, FP1 non-zero); HP-GL only one axis-aligned rectangle of 4 points (FT1, RA to its
 * third corner). -1 for anything else or a write error. */
int hpgl_emit_fill(hpgl_emit_t *e, const popt_pt_t *pts, const size_t *starts, size_t ncont,
		size_t npts, int even_odd);
/* Bytes written as they are (PCL framing escapes), closing an open PE first. */
int hpgl_emit_raw(hpgl_emit_t *e, const char *s, size_t n);
/* Pass buffered bytes to the transport (io_write; the caller io_flushes when it must). */
int hpgl_emit_flush(hpgl_emit_t *e);
/* Bytes written so far. */
uint64_t hpgl_emit_bytes(const hpgl_emit_t *e);
/* The transport's message when a write failed, else "". */
const char *hpgl_emit_error(const hpgl_emit_t *e);

/* ---- the plot-time model (hpgl_time.c) ---- */

/* Accumulated plot time of one pen. */
typedef struct {
	double down_s, up_s, lift_s;  /* drawing, travel, pen lifts and drops */
	double down_mm, up_mm;
	uint64_t lifts;
} hpgl_time_t;

/* Seconds for one straight move of len_mm at top speed v (cm/s) with acceleration a (m/s^2),
 * starting and ending at rest (trapezoid or triangle profile). */
double hpgl_move_time(double len_mm, double v_cms, double a_ms2);
/* Add one polyline drawn after a pen-up travel of travel_pu to t: the travel at pen-up speed,
 * one lift and one drop, and the polyline at pen-down speed, stopping at every corner sharper
 * than 30 degrees. */
void hpgl_time_add(hpgl_time_t *t, const hpgl_profile_t *prof, double travel_pu,
		const popt_pt_t *pts, size_t n);

/* ---- what the device reports (dev-hpgl.c) ---- */

/* One pen's share of a page. */
typedef struct {
	int slot;
	size_t paths_in, paths_out;
	double travel_before_mm, travel_greedy_mm, travel_after_mm;
	hpgl_time_t time;
} hpgl_pen_report_t;

/* A page's report, handed to the reporter after the page is written. */
typedef struct {
	unsigned page;                  /* 0-based */
	size_t npens;                   /* pens used, in drawing order */
	hpgl_pen_report_t pen[HPGL_MAX_PENS];
	double travel_before_mm, travel_greedy_mm, travel_after_mm;
	uint64_t pen_lifts, pen_changes;
	double optimise_s;              /* wall time of the optimiser */
	double plot_s;                  /* estimated plot time, pen changes included */
	uint64_t bytes;                 /* HP-GL bytes of the page */
	int optimised;
	double box[4];                  /* the page's image on the paper x0 y0 x1 y1, plotter units */
	const char *profile;
	const char *warning;            /* NULL, or one line (e.g. raster content skipped) */
} hpgl_report_t;

/* A program's hook for reports (the library never prints): called once per page with the
 * page's figures, and with warnings. Process-wide; NULL removes it. */
void hpgl_set_reporter(void (*fn)(void *user, const hpgl_report_t *r), void *user);

#endif
