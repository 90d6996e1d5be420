/* hpgl_dev.h: the HP-GL device's state, shared by its collecting side (dev-hpgl.c) and its
 * page writer (hpgl_page.c). Internal to the driver. */
#ifndef LOCUS_HPGL_DEV_H
#define LOCUS_HPGL_DEV_H

#include "device/device.h"
#include "hpgl/hpgl.h"

enum { HPGL_FILL_HATCH, HPGL_FILL_NATIVE, HPGL_FILL_NONE, HPGL_FILL_OUTLINE };

/* A label kept for the end of the page (text=label). */
typedef struct {
	size_t pen;
	int32_t x, y;
	double height_mm, angle;
	char *s;
	size_t len;
} hpgl_label_t;

/* A native fill kept for the end of the page (fill=native: FP in HP-GL/2, RA in HP-GL). */
typedef struct {
	size_t pen;
	size_t first, ncont;        /* contours: starts[first .. first + ncont] into fpts */
	int even_odd;
} hpgl_nfill_t;

/* The device's private state (dev->priv): options, the page's mapping, the paths per pen. */
typedef struct {
	hpgl_profile_t prof;
	hpgl_pens_t pens;
	hpgl_place_t place;
	int optimise;
	popt_opts_t popt;
	int fill, outline, text_label, raster_skip, passes, dash_split, background;
	int pcl;                    /* 1: PCL framing around the HP-GL/2 (ESC %-1B ... ESC %0A) */
	double hatch_mm, hatch_angle;
	double knife, overcut;
	hpgl_emit_t *em;
	hpgl_map_t map;
	popt_set_t *sets;           /* one per carousel pen */
	hpgl_label_t *labels;
	size_t nlabels, caplabels;
	hpgl_nfill_t *fills;
	size_t nfills, capfills;
	popt_pt_t *fpts;
	size_t nfpts, capfpts;
	size_t *fstarts;
	size_t nfstarts, capfstarts;
	hpgl_dpt_t *tmp;
	size_t captmp;
	hpgl_dpt_t *mpts;           /* add_model: a piece mapped to plotter units */
	size_t capmpts;
	popt_pt_t *ipts;
	size_t capipts;
	size_t cur_pen;             /* the pen the current primitive goes to */
	size_t total_paths;         /* paths of the page, all pens */
	double line_width_pu;       /* the current stroke's width, 0 = a hairline */
	int line_cap;               /* the current stroke's cap (META_CAP_*): ends of wide passes */
	int warned, warned_bg;
	unsigned page_w, page_h;
	popt_pt_t at;               /* the pen's position while writing */
	hpgl_report_t *rep;         /* streaming (no optimiser): the page's report as it is written */
	size_t stream_pen;          /* streaming: the carousel pen selected, SIZE_MAX none */
	hpgl_pen_report_t *stream_pr;
	popt_pt_t *spts;            /* streaming: a path with room for its closing point */
	size_t capspts;
	hpgl_dpt_t *kpts;           /* the drag knife's input path */
	size_t capkpts;
	popt_pt_t *k_at;            /* emit_knife: the pen position and the pen's report */
	hpgl_pen_report_t *k_pr;
	/* per-pen settings and pauses (hpgl_pause.c) */
	hpgl_penset_t penset[HPGL_MAX_PENS + 1];   /* the profile's, then the options' */
	int pause_all;              /* a pause before every pen change (hand-fed) */
	int loaded;                 /* the slot in the pen holder across pages, -1 unknown */
	double vs_page, vs_now, fs_now, as_now;   /* VS at the page's start; VS/FS/AS in force (0: default) */
	uint64_t job_base;          /* job bytes written before this page's emitter (one in-place output) */
	char *layer[HPGL_MAX_PENS + 1];   /* layer names from "pen N: layer \"NAME\"" comments */
	int warned_pause;
	hpgl_profile_t tprof;       /* the time model's profile: v_down the selected pen's speed */
} hpgl_dev_t;

/* ---- hpgl_devutil.c: shared by dev_hpgl.c, hpgl_page.c and hpgl_pause.c ---- */

/* Hand a page's report (or a warning) to the program's reporter, if any. */
void hpgl_dev_report(const hpgl_report_t *r);
/* Grow *p (cap elements of size bytes) to hold need; 0 or -1. */
int hpgl_dev_grow(void **p, size_t *cap, size_t need, size_t size);
/* Record "hpgl: out of memory"; returns META_ENOMEM. */
int hpgl_dev_nomem(dev_device_t *d);
/* The scratch point buffer h->tmp with room for n points; 0 or -1. */
int hpgl_dev_need_tmp(hpgl_dev_t *h, size_t n);
/* Record the emitter's failure (a transport error) on the device; returns META_EIO. */
int hpgl_dev_emit_fail(dev_device_t *d);
/* One warning of a kind per run (*flag remembers it), through the reporter. */
void hpgl_dev_warn(int *flag, const char *msg);
/* Select carousel pen k for drawing: a pause first when the pen is to be loaded by hand (PU,
 * everything sent, the program's pauser asked; a stop ends the job resumably), then SP, PW
 * (HP-GL/2) and the pen's VS/FS/AS where they differ from those in force (hpgl_pause.c). */
int hpgl_dev_pen(dev_device_t *d, size_t k);
/* The device's comment op: keeps "pen N: layer \"NAME\"" for the pauses' question. */
int hpgl_dev_comment(dev_device_t *d, const char *text, size_t len);
/* Read the options pen=, pause=, over the profile's settings (h_open). */
int hpgl_dev_pen_options(dev_device_t *d);
/* Free the layer names. */
void hpgl_dev_pen_free(hpgl_dev_t *h);
/* ---- hpgl_page.c ---- */

/* Start a page after the emitter is made: IN, VS, the pen's position; without the optimiser
 * the page is streamed (h->rep collects its report). */
int hpgl_page_begin(dev_device_t *d, const dev_page_t *pg);
/* Streaming: select carousel pen k (SP, PW in HP-GL/2) when it is not the current one. */
int hpgl_page_pen(dev_device_t *d, size_t k);
/* Streaming: write one path of pen k now (closed: the segment back to the first point too). */
int hpgl_page_put(dev_device_t *d, size_t k, const popt_pt_t *pts, size_t n, int closed);
/* Write the collected page pen by pen, report it, and reset the page's labels (end_page). */
int hpgl_page_write(dev_device_t *d, const dev_page_t *pg);

#endif
