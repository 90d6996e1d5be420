/* dev-hpgl.c: the HP-GL / HP-GL/2 pen-plotter and cutter device: collects a page's paths per
 * pen (dashes split, wide lines as passes, fills and rasters hatched, text as strokes or LB),
 * optimises each pen's order and writes them pen by pen. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "device.h"
#include "hatch.h"
#include "hpgl.h"

enum { FILL_HATCH, FILL_NATIVE, FILL_NONE, FILL_OUTLINE };

/* A label kept for the end of the page (text=label). */
typedef struct {
	size_t pen;
	int32_t x, y;
	double height_mm, angle;
	char *s;
	size_t len;
} label_t;

/* A native fill kept for the end of the page (HP-GL/2 fill=native). */
typedef struct {
	size_t pen;
	size_t first, ncont;        /* contours: starts[first .. first + ncont] into fpts */
	int even_odd;
} nfill_t;

typedef struct {
	hpgl_profile_t prof;
	hpgl_pens_t pens;
	hpgl_place_t place;
	int optimise;
	popt_opts_t popt;
	int fill, outline, text_label, raster_skip, passes, dash_split, background;
	double hatch_mm, hatch_angle;
	double knife, overcut;
	hpgl_emit_t *em;
	hpgl_map_t map;
	popt_set_t *sets;           /* one per carousel pen */
	label_t *labels;
	size_t nlabels, caplabels;
	nfill_t *fills;
	size_t nfills, capfills;
	popt_pt_t *fpts;
	size_t nfpts, capfpts;
	size_t *fstarts;
	size_t nfstarts, capfstarts;
	hpgl_dpt_t *tmp, *tmp2;
	size_t captmp;
	popt_pt_t *ipts;
	size_t capipts;
	size_t cur_pen;             /* the pen the current primitive goes to */
	int warned, warned_bg;
	unsigned page_w, page_h;
	popt_pt_t *k_at;            /* emit_knife: the pen position and the pen's report */
	hpgl_pen_report_t *k_pr;
} hp_t;

static void (*reporter)(void *, const hpgl_report_t *);
static void *reporter_user;

void hpgl_set_reporter(void (*fn)(void *user, const hpgl_report_t *r), void *user)
{
	reporter = fn;
	reporter_user = user;
}

static int grow(void **p, size_t *cap, size_t need, size_t size)
{
	if (need <= *cap)
		return 0;
	size_t n = *cap ? *cap : 64;
	while (n < need)
		n *= 2;
	void *q = realloc(*p, n * size);
	if (!q)
		return -1;
	*p = q;
	*cap = n;
	return 0;
}

static int nomem(dev_device_t *d)
{
	return dev_fail(d, META_ENOMEM, "hpgl: out of memory");
}

/* ---- options ---- */

static const dev_option_t hpgl_options[] = {
	{ "profile", "7475a|7550a|draftpro|hpgl2|cutter or a profile file (default 7475a)" },
	{ "paper", "a4|a3|letter|b (default: the profile's)" },
	{ "rotate", "0|90|180|270 degrees (default 0)" },
	{ "mirror", "none|x|y (default none)" },
	{ "fit", "auto|yes|no: shrink when too big, fill the paper, or physical size (default auto)" },
	{ "scale", "factor on the physical size (default 1)" },
	{ "pens", "carousel 1=black;2=red:0.3mm;... (default: the profile's)" },
	{ "optimize", "yes|no (default yes)" },
	{ "merge", "tolerance in mm for joining path ends, 0 = off (default 0.05)" },
	{ "simplify", "tolerance in mm, 0 = only repeated points (default 0)" },
	{ "budget", "2-opt time budget in seconds (default 0.2)" },
	{ "fill", "hatch|native|none|outline (native: HP-GL/2 FP; default hatch, outline on cutters)" },
	{ "hatch", "hatch spacing in mm (default: the pen width)" },
	{ "hatch-angle", "degrees (default 45)" },
	{ "outline", "yes|no: draw the outline of hatched fills (default yes)" },
	{ "text", "strokes|label (default strokes)" },
	{ "raster", "hatch|skip (default hatch)" },
	{ "background", "skip|hatch: a non-white clear (page background) (default skip, with a warning)" },
	{ "wide", "passes|single: lines wider than the pen as parallel passes (default passes)" },
	{ "dash", "split|solid (default split)" },
	{ "knife", "cutter blade offset in mm (default: the profile's)" },
	{ "overcut", "cutter overcut in mm (default: the profile's)" },
	{ NULL, NULL }
};

static int opt_num(dev_device_t *d, const char *key, double lo, double hi, double *v)
{
	char buf[64], *e;
	if (!dev_option(d, key, buf, sizeof buf))
		return 0;
	double x = strtod(buf, &e);
	if (e == buf || *e || !(x >= lo && x <= hi))
		return dev_fail(d, DEV_EUSAGE, "option %s: expected a number in [%g, %g], not '%s'", key, lo, hi, buf);
	*v = x;
	return 0;
}

static int opt_word(dev_device_t *d, const char *key, const char *const *words, int *v)
{
	char buf[64];
	if (!dev_option(d, key, buf, sizeof buf))
		return 0;
	for (int k = 0; words[k]; k++)
		if (!strcmp(buf, words[k])) {
			*v = k;
			return 0;
		}
	char list[200] = "";
	for (int k = 0; words[k]; k++)
		snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? ", " : "", words[k]);
	return dev_fail(d, DEV_EUSAGE, "option %s: expected one of %s, not '%s'", key, list, buf);
}

static int h_open(dev_device_t *d)
{
	hp_t *h = d->priv;
	char buf[1024], err[300];
	const char *name = dev_option(d, "profile", buf, sizeof buf) ? buf : "7475a";
	const hpgl_profile_t *p = hpgl_profile_find(name);
	if (p)
		h->prof = *p;
	else if (strchr(name, '/') || strchr(name, '.')) {
		if (hpgl_profile_load(name, &h->prof, err, sizeof err))
			return dev_fail(d, DEV_EUSAGE, "%s", err);
	} else
		return dev_fail(d, DEV_EUSAGE, "unknown profile '%s' (7475a, 7550a, draftpro, hpgl2, cutter, or a "
			"profile file's path)", name);
	h->place = (hpgl_place_t){ h->prof.paper, 0, 0, 1, 1.0 };
	static const char *const papers[] = { "a4", "a3", "letter", "b", NULL };
	static const char *const rots[] = { "0", "90", "180", "270", NULL };
	static const char *const mirrors[] = { "none", "x", "y", NULL };
	static const char *const fits[] = { "no", "auto", "yes", NULL };
	static const char *const yesno[] = { "no", "yes", NULL };
	static const char *const fills[] = { "hatch", "native", "none", "outline", NULL };
	static const char *const texts[] = { "strokes", "label", NULL };
	static const char *const rasters[] = { "hatch", "skip", NULL };
	static const char *const wides[] = { "single", "passes", NULL };
	static const char *const dashes[] = { "solid", "split", NULL };
	static const char *const bgs[] = { "skip", "hatch", NULL };
	int rot = 0, opt = 1;
	double merge = 0.05, simp = 0, budget = 0.2;
	h->outline = 1;
	h->passes = !h->prof.cutter;   /* a knife cuts the centre line of a wide line */
	h->dash_split = 1;
	h->hatch_angle = 45;
	h->fill = h->prof.cutter ? FILL_OUTLINE : FILL_HATCH;   /* a knife cuts outlines, never hatches */
	h->knife = h->prof.knife_offset;
	h->overcut = h->prof.overcut;
	int rc = 0;
	if ((rc = opt_word(d, "paper", papers, &h->place.paper)) || (rc = opt_word(d, "rotate", rots, &rot)) ||
			(rc = opt_word(d, "mirror", mirrors, &h->place.mirror)) || (rc = opt_word(d, "fit", fits, &h->place.fit)) ||
			(rc = opt_num(d, "scale", 1e-3, 1e3, &h->place.scale)) || (rc = opt_word(d, "optimize", yesno, &opt)) ||
			(rc = opt_num(d, "merge", 0, 10, &merge)) || (rc = opt_num(d, "simplify", 0, 10, &simp)) ||
			(rc = opt_num(d, "budget", 0, 60, &budget)) || (rc = opt_word(d, "fill", fills, &h->fill)) ||
			(rc = opt_num(d, "hatch", 0.01, 100, &h->hatch_mm)) ||
			(rc = opt_num(d, "hatch-angle", -360, 360, &h->hatch_angle)) ||
			(rc = opt_word(d, "outline", yesno, &h->outline)) || (rc = opt_word(d, "text", texts, &h->text_label)) ||
			(rc = opt_word(d, "raster", rasters, &h->raster_skip)) || (rc = opt_word(d, "wide", wides, &h->passes)) ||
			(rc = opt_word(d, "dash", dashes, &h->dash_split)) || (rc = opt_num(d, "knife", 0, 10, &h->knife)) ||
			(rc = opt_num(d, "overcut", 0, 100, &h->overcut)) || (rc = opt_word(d, "background", bgs, &h->background)))
		return rc;
	if (!h->prof.has_paper[h->place.paper])
		return dev_fail(d, DEV_EUSAGE, "profile %s has no paper %s", h->prof.name, hpgl_paper_name(h->place.paper));
	if (h->fill == FILL_NATIVE && h->prof.dialect != HPGL_DIALECT_2)
		return dev_fail(d, DEV_EUSAGE, "fill=native needs an HP-GL/2 profile (FP/PM); %s speaks HP-GL: use fill=hatch",
			h->prof.name);
	h->place.rotate = rot * 90;
	h->optimise = opt;
	h->popt = (popt_opts_t){ merge > 0, merge * HPGL_PU_PER_MM, simp * HPGL_PU_PER_MM, 1, budget, 0 };
	const char *pens = dev_option(d, "pens", buf, sizeof buf) ? buf : h->prof.pens;
	if (hpgl_pens_parse(pens, 0.3, &h->pens, err, sizeof err))
		return dev_fail(d, DEV_EUSAGE, "%s", err);
	if (h->pens.n > h->prof.npens || h->pens.pen[h->pens.n - 1].slot > (int)h->prof.npens)
		return dev_fail(d, DEV_EUSAGE, "pens: profile %s has %u pen slots, pen %d does not fit", h->prof.name,
			h->prof.npens, h->pens.pen[h->pens.n - 1].slot);
	h->sets = calloc(h->pens.n, sizeof *h->sets);
	if (!h->sets)
		return nomem(d);
	return 0;
}

/* ---- collecting ---- */

static int need_tmp(hp_t *h, size_t n)
{
	if (n <= h->captmp)
		return 0;
	size_t c = h->captmp;
	if (grow((void **)&h->tmp, &c, n, sizeof *h->tmp))
		return -1;
	c = h->captmp;
	if (grow((void **)&h->tmp2, &c, n, sizeof *h->tmp2))
		return -1;
	h->captmp = c;
	return 0;
}

/* A visible piece in plotter units: round and keep it for its pen. */
static int add_piece(void *user, const hpgl_dpt_t *pts, size_t n, int closed)
{
	dev_device_t *d = user;
	hp_t *h = d->priv;
	if (grow((void **)&h->ipts, &h->capipts, n, sizeof *h->ipts))
		return -1;
	size_t m = 0;
	for (size_t i = 0; i < n; i++) {
		popt_pt_t q = { (int32_t)lround(pts[i].x), (int32_t)lround(pts[i].y) };
		if (m == 0 || q.x != h->ipts[m - 1].x || q.y != h->ipts[m - 1].y)
			h->ipts[m++] = q;
	}
	if (closed && m > 1 && h->ipts[0].x == h->ipts[m - 1].x && h->ipts[0].y == h->ipts[m - 1].y)
		m--;
	return popt_add(&h->sets[h->cur_pen], h->ipts, m, closed && m > 2);
}

/* A piece in plotter units before clipping: as parallel passes when wider than the pen. */
static double line_width_pu;
static int add_mapped(void *user, const hpgl_dpt_t *pts, size_t n, int closed)
{
	dev_device_t *d = user;
	hp_t *h = d->priv;
	double pen = h->pens.pen[h->cur_pen].width_mm * HPGL_PU_PER_MM;
	if (!h->passes || line_width_pu <= pen * 1.5 || n < 2)
		return hpgl_clip_poly(pts, n, closed, h->map.clip, add_piece, d);
	int k = (int)ceil(line_width_pu / pen);
	if (k > 64)
		k = 64;
	hpgl_dpt_t *off = malloc(2 * n * sizeof *off);
	if (!off)
		return -1;
	int rc = 0;
	for (int i = 0; i < k && !rc; i++) {
		double dist = (line_width_pu - pen) * (i / (double)(k - 1) - 0.5);
		size_t m = hpgl_offset_poly(pts, n, closed, dist, off);
		rc = hpgl_clip_poly(off, m, closed, h->map.clip, add_piece, d);
	}
	free(off);
	return rc;
}

/* A piece in thousandths of a pixel: map it. */
static int add_model(void *user, const hpgl_dpt_t *pts, size_t n, int closed)
{
	dev_device_t *d = user;
	hp_t *h = d->priv;
	hpgl_dpt_t *m = malloc((n ? n : 1) * sizeof *m);
	if (!m)
		return -1;
	for (size_t i = 0; i < n; i++)
		hpgl_map_point(&h->map, (int64_t)pts[i].x, (int64_t)pts[i].y, &m[i].x, &m[i].y);
	int rc = add_mapped(user, m, n, closed);
	free(m);
	return rc;
}

/* The carousel pen for a colour, or -1 for paper (hpgl_pens_pick). */
static long pen_for(hp_t *h, meta_rgb_t rgb)
{
	return hpgl_pens_pick(&h->pens, rgb);
}

static int stroke_flat(dev_device_t *d, const scan_path_t *f, const dev_state_t *st, int solid)
{
	hp_t *h = d->priv;
	long pen = pen_for(h, st->colour);
	if (pen < 0)
		return 0;
	h->cur_pen = (size_t)pen;
	/* width 1 (the default, and the minimum of spec 4) is a hairline: one pass of the pen */
	line_width_pu = st->width <= 1000 ? 0 : st->width / 1000.0 * h->map.pu_per_px;
	double pat[2 * META_MAX_DASH];
	size_t npat = solid || !h->dash_split ? 0 : st->ndash;
	for (size_t k = 0; k < npat; k++)
		pat[k] = (double)st->dash[k];
	for (size_t s = 0; s < f->nsubs; s++) {
		const scan_subpath_t *sp = &f->subs[s];
		if (sp->n == 0)
			continue;
		if (need_tmp(h, sp->n + 1))
			return nomem(d);
		for (size_t i = 0; i < sp->n; i++)
			h->tmp[i] = (hpgl_dpt_t){ (double)f->pts[sp->start + i].x, (double)f->pts[sp->start + i].y };
		int rc;
		if (sp->n == 1)   /* a dot */
			rc = add_model(d, (hpgl_dpt_t[]){ h->tmp[0], h->tmp[0] }, 2, 0);
		else
			rc = hpgl_dash_poly(h->tmp, sp->n, sp->closed, pat, npat, add_model, d);
		if (rc)
			return nomem(d);
	}
	return 0;
}

static int h_stroke(dev_device_t *d, const dev_path_t *p, const dev_state_t *st)
{
	return stroke_flat(d, p->flat, st, 0);
}

static int hatch_seg(void *user, double x0, double y0, double x1, double y1)
{
	hpgl_dpt_t s[2] = { { x0, y0 }, { x1, y1 } };
	dev_device_t *d = user;
	hp_t *h = d->priv;
	return hpgl_clip_poly(s, 2, 0, h->map.clip, add_piece, d);
}

static int fill_mapped(dev_device_t *d, const scan_path_t *f, int rule, meta_rgb_t rgb)
{
	hp_t *h = d->priv;
	long pen = pen_for(h, rgb);
	if (pen < 0 || h->fill == FILL_NONE)
		return 0;
	h->cur_pen = (size_t)pen;
	size_t n = f->npts;
	double *xy = malloc((2 * n + 2) * sizeof *xy);
	size_t *starts = malloc((f->nsubs + 1) * sizeof *starts), nc = 0, at = 0;
	if (!xy || !starts) {
		free(xy);
		free(starts);
		return nomem(d);
	}
	int inside = 1;
	const double *c = h->map.clip;
	for (size_t s = 0; s < f->nsubs; s++) {
		const scan_subpath_t *sp = &f->subs[s];
		if (sp->n < 2)
			continue;
		starts[nc++] = at;
		for (size_t i = 0; i < sp->n; i++, at++) {
			hpgl_map_point(&h->map, f->pts[sp->start + i].x, f->pts[sp->start + i].y, &xy[2 * at], &xy[2 * at + 1]);
			inside &= xy[2 * at] >= c[0] && xy[2 * at] <= c[2] && xy[2 * at + 1] >= c[1] && xy[2 * at + 1] <= c[3];
		}
	}
	starts[nc] = at;
	int rc = 0;
	if (h->fill == FILL_NATIVE && inside && nc) {
		if (grow((void **)&h->fills, &h->capfills, h->nfills + 1, sizeof *h->fills) ||
				grow((void **)&h->fstarts, &h->capfstarts, h->nfstarts + nc + 1, sizeof *h->fstarts) ||
				grow((void **)&h->fpts, &h->capfpts, h->nfpts + at, sizeof *h->fpts))
			rc = -1;
		else {
			h->fills[h->nfills++] = (nfill_t){ (size_t)pen, h->nfstarts, nc, rule == META_RULE_EVEN_ODD };
			for (size_t k = 0; k <= nc; k++)
				h->fstarts[h->nfstarts + k] = h->nfpts + starts[k];
			h->nfstarts += nc + 1;
			for (size_t i = 0; i < at; i++)
				h->fpts[h->nfpts++] = (popt_pt_t){ (int32_t)lround(xy[2 * i]), (int32_t)lround(xy[2 * i + 1]) };
		}
	} else if (nc) {
		/* spacing: the pen width, opened up for colours lighter than the pen's ink */
		double lab[3], sp = h->hatch_mm * HPGL_PU_PER_MM;
		if (!(sp > 0)) {
			hpgl_rgb_to_lab(rgb, lab);
			double lp = h->pens.pen[pen].lab[0], dk = lp < 99 ? (100 - lab[0]) / (100 - lp) : 1;
			dk = dk > 1 ? 1 : dk < 0.1 ? 0.1 : dk;
			sp = h->pens.pen[pen].width_mm * HPGL_PU_PER_MM / dk;
		}
		if (h->fill == FILL_HATCH)
			rc = hatch_polygon(xy, starts, nc, rule == META_RULE_EVEN_ODD, h->hatch_angle, sp, 0, hatch_seg, d);
		for (size_t k = 0; k < nc && !rc && (h->outline || h->fill == FILL_OUTLINE); k++) {
			size_t m = starts[k + 1] - starts[k];
			if (need_tmp(h, m)) {
				rc = -1;
				break;
			}
			for (size_t i = 0; i < m; i++)
				h->tmp[i] = (hpgl_dpt_t){ xy[2 * (starts[k] + i)], xy[2 * (starts[k] + i) + 1] };
			rc = hpgl_clip_poly(h->tmp, m, 1, h->map.clip, add_piece, d);
		}
	}
	free(xy);
	free(starts);
	return rc ? nomem(d) : 0;
}

static int h_fill(dev_device_t *d, const dev_path_t *p, const dev_state_t *st)
{
	return fill_mapped(d, p->flat, st->rule, st->colour);
}

static int h_text(dev_device_t *d, const dev_text_t *t, const dev_state_t *st)
{
	hp_t *h = d->priv;
	if (!h->text_label) {
		scan_path_t p = { 0 };
		int rc = scan_text_path(&p, t->str, t->len, t->x, t->y, t->size, t->angle) ? nomem(d)
			: stroke_flat(d, &p, st, 1);
		scan_path_free(&p);
		return rc;
	}
	long pen = pen_for(h, st->colour);
	if (pen < 0)
		return 0;
	double X, Y;
	hpgl_map_point(&h->map, t->x, t->y, &X, &Y);
	if (X < h->map.clip[0] || X > h->map.clip[2] || Y < h->map.clip[1] || Y > h->map.clip[3])
		return 0;
	if (grow((void **)&h->labels, &h->caplabels, h->nlabels + 1, sizeof *h->labels))
		return nomem(d);
	label_t *l = &h->labels[h->nlabels];
	l->s = malloc(t->len + 1);
	if (!l->s)
		return nomem(d);
	memcpy(l->s, t->str, t->len);
	l->len = t->len;
	l->pen = (size_t)pen;
	l->x = (int32_t)lround(X);
	l->y = (int32_t)lround(Y);
	l->height_mm = t->size / 1000.0 * h->map.pu_per_px / HPGL_PU_PER_MM;
	l->angle = t->angle / 1000.0 + h->place.rotate;
	h->nlabels++;
	return 0;
}

/* One warning of a kind per run, through the reporter. */
static void warn(hp_t *h, int *flag, const char *msg)
{
	(void)h;
	if (!*flag && reporter) {
		hpgl_report_t *r = calloc(1, sizeof *r);
		if (r) {
			r->warning = msg;
			reporter(reporter_user, r);
			free(r);
		}
	}
	*flag = 1;
}

static int raster_seg(void *user, double x0, double y0, double x1, double y1)
{
	hpgl_dpt_t s[2];
	dev_device_t *d = user;
	hp_t *h = d->priv;
	hpgl_map_point(&h->map, (int64_t)x0, (int64_t)y0, &s[0].x, &s[0].y);
	hpgl_map_point(&h->map, (int64_t)x1, (int64_t)y1, &s[1].x, &s[1].y);
	return hpgl_clip_poly(s, 2, 0, h->map.clip, add_piece, d);
}

static int h_span(dev_device_t *d, unsigned x, unsigned y, unsigned n, meta_rgb_t rgb)
{
	hp_t *h = d->priv;
	if (h->raster_skip) {
		warn(h, &h->warned, "raster content (spans, images) skipped (raster=skip)");
		return 0;
	}
	/* the nearest pen, with ink in proportion to the darkness (nearly white: none) */
	size_t pen = hpgl_pens_nearest(&h->pens, rgb);
	double lab[3];
	hpgl_rgb_to_lab(rgb, lab);
	double dark = 1 - lab[0] / 100;
	if (dark < 1.0 / 16)
		return 0;
	h->cur_pen = pen;
	double px = h->map.pu_per_px, pw = h->pens.pen[pen].width_mm * HPGL_PU_PER_MM;
	unsigned lines = (unsigned)lround(px / pw), step = 1;
	if (lines == 0) {
		step = (unsigned)lround(pw / px);
		lines = 1;
		if (y % step)
			return 0;
	}
	double *dk = malloc(n * sizeof *dk);
	if (!dk)
		return nomem(d);
	for (unsigned i = 0; i < n; i++)
		dk[i] = dark;
	int rc = hatch_row(dk, n, x * 1000.0, (x + n) * 1000.0, y * 1000.0, 1000.0 * step, lines, y / step,
		raster_seg, d);
	free(dk);
	return rc ? nomem(d) : 0;
}

static int h_clear(dev_device_t *d, meta_rgb_t rgb)
{
	hp_t *h = d->priv;
	if (pen_for(h, rgb) < 0)
		return 0;
	if (!h->background) {
		warn(h, &h->warned_bg, "a non-white page background (clear) is not drawn (background=hatch draws it)");
		return 0;
	}
	scan_path_t r = { 0 };
	int64_t W = (int64_t)h->page_w * 1000, H = (int64_t)h->page_h * 1000;
	int rc = scan_path_move(&r, 0, 0) || scan_path_draw(&r, W, 0) || scan_path_draw(&r, W, H) ||
		scan_path_draw(&r, 0, H) ? nomem(d) : fill_mapped(d, &r, META_RULE_NON_ZERO, rgb);
	scan_path_free(&r);
	return rc;
}

/* ---- pages ---- */

static int emit_fail(dev_device_t *d)
{
	hp_t *h = d->priv;
	const char *e = hpgl_emit_error(h->em);
	return dev_fail(d, META_EIO, "%s", e[0] ? e : "hpgl: out of memory");
}

static int h_begin(dev_device_t *d, const dev_page_t *pg)
{
	hp_t *h = d->priv;
	char err[256];
	h->page_w = pg->width;
	h->page_h = pg->height;
	if (hpgl_map_page(&h->prof, &h->place, pg->width, pg->height, pg->has_size ? pg->width_mm / 1000.0 : 0,
			pg->has_size ? pg->height_mm / 1000.0 : 0, &h->map, err, sizeof err))
		return dev_fail(d, DEV_EUSAGE, "%s", err);
	for (size_t k = 0; k < h->pens.n; k++)
		popt_reset(&h->sets[k]);
	h->nfills = h->nfstarts = h->nfpts = 0;
	hpgl_emit_free(h->em);
	h->em = hpgl_emit_new(d->out, &h->prof);
	if (!h->em)
		return nomem(d);
	return hpgl_emit_cmd(h->em, "IN") ? emit_fail(d) : 0;
}

/* The knife's tool path: round and write it. */
static int emit_knife(void *user, const hpgl_dpt_t *pts, size_t n, int closed)
{
	dev_device_t *d = user;
	hp_t *h = d->priv;
	(void)closed;
	popt_pt_t *q = malloc(n * sizeof *q);
	if (!q)
		return -1;
	size_t m = 0;
	for (size_t i = 0; i < n; i++) {
		popt_pt_t v = { (int32_t)lround(pts[i].x), (int32_t)lround(pts[i].y) };
		if (!m || v.x != q[m - 1].x || v.y != q[m - 1].y)
			q[m++] = v;
	}
	if (m == 1)
		q[m++] = q[0];
	double dx = (double)q[0].x - h->k_at->x, dy = (double)q[0].y - h->k_at->y;
	hpgl_time_add(&h->k_pr->time, &h->prof, sqrt(dx * dx + dy * dy), q, m);
	int rc = hpgl_emit_poly(h->em, q, m);
	*h->k_at = q[m - 1];
	free(q);
	return rc;
}

/* Write one pen's share: native fills, then its paths in the optimised order, then labels. */
static int emit_pen(dev_device_t *d, size_t k, popt_pt_t *at, hpgl_report_t *r)
{
	hp_t *h = d->priv;
	popt_set_t *s = &h->sets[k];
	int has_fill = 0, has_label = 0;
	for (size_t i = 0; i < h->nfills && !has_fill; i++)
		has_fill = h->fills[i].pen == k;
	for (size_t i = 0; i < h->nlabels && !has_label; i++)
		has_label = h->labels[i].pen == k;
	if (!s->npaths && !has_fill && !has_label)
		return 0;
	hpgl_pen_report_t *pr = &r->pen[r->npens++];
	memset(pr, 0, sizeof *pr);
	pr->slot = h->pens.pen[k].slot;
	pr->paths_in = s->npaths;
	if (hpgl_emit_pen(h->em, pr->slot))
		return emit_fail(d);
	r->pen_changes++;
	if (h->prof.dialect == HPGL_DIALECT_2 && hpgl_emit_cmd(h->em, "PW%.2f,%d", h->pens.pen[k].width_mm, pr->slot))
		return emit_fail(d);
	for (size_t i = 0; i < h->nfills; i++) {
		const nfill_t *f = &h->fills[i];
		if (f->pen == k && hpgl_emit_fill(h->em, h->fpts, h->fstarts + f->first, f->ncont, 0, f->even_odd))
			return emit_fail(d);
	}
	popt_stats_t st;
	if (h->optimise) {
		if (popt_optimise(s, *at, &h->popt, &st))
			return nomem(d);
	} else {
		if (popt_keep_order(s))
			return nomem(d);
		memset(&st, 0, sizeof st);
		st.travel_before = st.travel_greedy = st.travel_after = popt_travel(s, *at);
	}
	r->optimise_s += st.seconds;
	pr->paths_out = s->npaths;
	pr->travel_before_mm = st.travel_before / HPGL_PU_PER_MM;
	pr->travel_greedy_mm = st.travel_greedy / HPGL_PU_PER_MM;
	pr->travel_after_mm = st.travel_after / HPGL_PU_PER_MM;
	size_t maxn = 0;
	for (size_t i = 0; i < s->npaths; i++)
		if (s->paths[i].n > maxn)
			maxn = s->paths[i].n;
	if (grow((void **)&h->ipts, &h->capipts, maxn + 2, sizeof *h->ipts))
		return nomem(d);
	for (size_t i = 0; i < s->npaths; i++) {
		size_t n = popt_get(s, i, h->ipts);
		if (n == 1)
			h->ipts[n++] = h->ipts[0];   /* a dot: pen down where it is */
		popt_pt_t f = h->ipts[0];
		if (h->prof.cutter && h->knife > 0) {
			/* the tool path of a drag knife; a closed path is cut on past its start */
			const popt_path_t *pp = &s->paths[s->order[i]];
			if (need_tmp(h, n))
				return nomem(d);
			for (size_t j = 0; j < n; j++)
				h->tmp[j] = (hpgl_dpt_t){ h->ipts[j].x, h->ipts[j].y };
			h->k_at = at;
			h->k_pr = pr;
			if (hpgl_knife_poly(h->tmp, pp->closed ? n - 1 : n, pp->closed, h->knife * HPGL_PU_PER_MM,
					h->overcut * HPGL_PU_PER_MM, emit_knife, d))
				return emit_fail(d);
			continue;
		}
		double dx = (double)f.x - at->x, dy = (double)f.y - at->y;
		hpgl_time_add(&pr->time, &h->prof, sqrt(dx * dx + dy * dy), h->ipts, n);
		if (hpgl_emit_poly(h->em, h->ipts, n))
			return emit_fail(d);
		*at = h->ipts[n - 1];
	}
	for (size_t i = 0; i < h->nlabels; i++) {
		const label_t *l = &h->labels[i];
		if (l->pen == k && hpgl_emit_label(h->em, l->x, l->y, l->height_mm, l->angle, l->s, l->len))
			return emit_fail(d);
	}
	return 0;
}

static int h_end(dev_device_t *d, const dev_page_t *pg)
{
	hp_t *h = d->priv;
	hpgl_report_t *r = calloc(1, sizeof *r);
	if (!r)
		return nomem(d);
	r->page = pg->index;
	r->profile = h->prof.name;
	r->optimised = h->optimise;
	memcpy(r->box, h->map.clip, sizeof r->box);
	/* the pen starts at the lower-left corner of the hard-clip limits (after IN) */
	popt_pt_t at = { h->prof.clip[h->place.paper][0], h->prof.clip[h->place.paper][1] };
	int rc = 0;
	if (h->prof.v_down > 0 && !h->prof.cutter)
		rc = hpgl_emit_cmd(h->em, "VS%g", h->prof.v_down) ? emit_fail(d) : 0;
	for (size_t k = 0; k < h->pens.n && !rc; k++)
		rc = emit_pen(d, k, &at, r);
	if (!rc && (hpgl_emit_cmd(h->em, "PU") || hpgl_emit_pen(h->em, 0) || hpgl_emit_flush(h->em)))
		rc = emit_fail(d);
	if (!rc) {
		for (size_t k = 0; k < r->npens; k++) {
			const hpgl_pen_report_t *p = &r->pen[k];
			r->travel_before_mm += p->travel_before_mm;
			r->travel_greedy_mm += p->travel_greedy_mm;
			r->travel_after_mm += p->travel_after_mm;
			r->pen_lifts += p->time.lifts;
			r->plot_s += p->time.down_s + p->time.up_s + p->time.lift_s;
		}
		r->plot_s += r->pen_changes * h->prof.t_change;
		r->bytes = hpgl_emit_bytes(h->em);
		if (reporter)
			reporter(reporter_user, r);
	}
	for (size_t i = 0; i < h->nlabels; i++)
		free(h->labels[i].s);
	h->nlabels = 0;
	hpgl_emit_free(h->em);
	h->em = NULL;
	free(r);
	return rc;
}

static int h_close(dev_device_t *d)
{
	hp_t *h = d->priv;
	for (size_t k = 0; h->sets && k < h->pens.n; k++)
		popt_free(&h->sets[k]);
	free(h->sets);
	for (size_t i = 0; i < h->nlabels; i++)
		free(h->labels[i].s);
	free(h->labels);
	free(h->fills);
	free(h->fpts);
	free(h->fstarts);
	free(h->tmp);
	free(h->tmp2);
	free(h->ipts);
	hpgl_emit_free(h->em);
	memset(h, 0, sizeof *h);
	return 0;
}

const dev_ops_t dev_hpgl_ops = {
	.name = "hpgl", .description = "HP-GL and HP-GL/2 pen plotters and cutters (profiles, pens, path optimisation)",
	.extension = ".hpgl", .caps = DEV_CAP_VECTOR | DEV_CAP_TEXT | DEV_CAP_FILL | DEV_CAP_DASH | DEV_CAP_WIDTH,
	.priv_size = sizeof(hp_t), .option_list = hpgl_options,
	.open = h_open, .begin_page = h_begin, .clear = h_clear, .stroke_path = h_stroke, .fill_path = h_fill,
	.text = h_text, .put_span = h_span, .end_page = h_end, .close = h_close,
};
