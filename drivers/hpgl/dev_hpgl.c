/* dev_hpgl.c: the HP-GL / HP-GL/2 pen-plotter and cutter device: options, and collecting a page's
 * paths per pen (the framework's dash pieces, wide lines as passes, fills hatched through the
 * hatch op, rasters hatched, text as strokes or LB); hpgl_page.c optimises and writes them at
 * the end of the page. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "util/grow.h"
#include "hpgl/hpgl_hatch.h"
#include "hpgl/hpgl_dev.h"

extern const dev_ops_t dev_hpgl_ops;

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
	{ "budget", "2-opt work budget, in seconds of a reference core: deterministic (default 0.2)" },
	{ "fill", "hatch|native|none|outline (native: HP-GL/2 FP; default hatch, outline on cutters)" },
	{ "hatch", "hatch spacing in mm (default: the pen width)" },
	{ "hatch-angle", "degrees (default 45)" },
	{ "outline", "yes|no: draw the outline of hatched fills (default yes)" },
	{ "text", "strokes|label (default strokes)" },
	{ "raster", "hatch|skip (default hatch)" },
	{ "background", "skip|hatch: a non-white clear (page background) (default skip, with a warning)" },
	{ "wide", "passes|single: lines wider than the pen as parallel passes (default passes)" },
	{ "dash", "split|solid (default split)" },
	{ "pcl", "no|yes: PCL framing around HP-GL/2 for printers that start in PCL (default no)" },
	{ "knife", "cutter blade offset in mm (default: the profile's)" },
	{ "overcut", "cutter overcut in mm (default: the profile's)" },
	{ "pen", "per-pen settings N:speed=CM/S;force=F;accel=A;pause/N:... (VS, FS, AS sent with SP)" },
	{ "pause", "pens to pause before (loaded by hand): N;M, all or none (default: the profile's)" },
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
	hpgl_dev_t *h = d->priv;
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
	h->fill = h->prof.cutter ? HPGL_FILL_OUTLINE : HPGL_FILL_HATCH;   /* a knife cuts outlines, never hatches */
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
			(rc = opt_num(d, "overcut", 0, 100, &h->overcut)) || (rc = opt_word(d, "background", bgs, &h->background)) ||
			(rc = opt_word(d, "pcl", yesno, &h->pcl)))
		return rc;
	/* what this instance leaves to the framework: dashes (its windowed pieces) unless dash=solid
	 * ignores them; fills go to the hatch op unless fill=native draws them (FP, RA). Widths stay
	 * the driver's: parallel passes, which outline pieces filled by hatching would not match. */
	d->caps = dev_hpgl_ops.caps | (h->dash_split ? 0 : DEV_CAP_DASH) | (h->fill == HPGL_FILL_NATIVE ? DEV_CAP_FILL : 0);
	if (h->pcl && h->prof.dialect != HPGL_DIALECT_2)
		return dev_fail(d, DEV_EUSAGE, "pcl=yes frames HP-GL/2; profile %s speaks HP-GL", h->prof.name);
	if (!h->prof.has_paper[h->place.paper])
		return dev_fail(d, DEV_EUSAGE, "profile %s has no paper %s", h->prof.name, hpgl_paper_name(h->place.paper));
	h->place.rotate = rot * 90;
	h->optimise = opt;
	h->popt = (popt_opts_t){ merge > 0, merge * HPGL_PU_PER_MM, simp * HPGL_PU_PER_MM, 1, budget, 0 };
	const char *pens = dev_option(d, "pens", buf, sizeof buf) ? buf : h->prof.pens;
	if (hpgl_pens_parse(pens, 0.3, &h->pens, err, sizeof err))
		return dev_fail(d, DEV_EUSAGE, "%s", err);
	if (h->pens.n > h->prof.npens || h->pens.pen[h->pens.n - 1].slot > (int)h->prof.npens)
		return dev_fail(d, DEV_EUSAGE, "pens: profile %s has %u pen slots, pen %d does not fit", h->prof.name,
			h->prof.npens, h->pens.pen[h->pens.n - 1].slot);
	if ((rc = hpgl_dev_pen_options(d)))
		return rc;
	h->sets = calloc(h->pens.n, sizeof *h->sets);
	if (!h->sets)
		return hpgl_dev_nomem(d);
	return 0;
}

/* A callback failed: its own message (a write error) or out of memory. */
static int cb_fail(dev_device_t *d)
{
	return d->err[0] ? META_EIO : hpgl_dev_nomem(d);
}

/* ---- collecting ---- */

/* A visible piece in plotter units: round and keep it for its pen. */
static int add_piece(void *user, const hpgl_dpt_t *pts, size_t n, int closed)
{
	dev_device_t *d = user;
	hpgl_dev_t *h = d->priv;
	if (hpgl_dev_grow((void **)&h->ipts, &h->capipts, n, sizeof *h->ipts))
		return -1;
	size_t m = 0;
	for (size_t i = 0; i < n; i++) {
		popt_pt_t q = { (int32_t)lround(pts[i].x), (int32_t)lround(pts[i].y) };
		if (m == 0 || q.x != h->ipts[m - 1].x || q.y != h->ipts[m - 1].y)
			h->ipts[m++] = q;
	}
	if (closed && m > 1 && h->ipts[0].x == h->ipts[m - 1].x && h->ipts[0].y == h->ipts[m - 1].y)
		m--;
	if (!h->optimise)   /* the file's order: written as it comes, nothing kept */
		return hpgl_page_put(d, h->cur_pen, h->ipts, m, closed && m > 2);
	return popt_add(&h->sets[h->cur_pen], h->ipts, m, closed && m > 2);
}

/* A piece in plotter units before clipping: as parallel passes when wider than the pen. */
static int add_mapped(void *user, const hpgl_dpt_t *pts, size_t n, int closed)
{
	dev_device_t *d = user;
	hpgl_dev_t *h = d->priv;
	double pen = h->pens.pen[h->cur_pen].width_mm * HPGL_PU_PER_MM;
	if (!h->passes || h->line_width_pu <= pen * 1.5 || n < 2)
		return hpgl_clip_poly(pts, n, closed, h->map.clip, add_piece, d);
	double kd = ceil(h->line_width_pu / pen);
	int k = kd > 64 ? 64 : (int)kd;   /* compared first: a huge width is no int */
	hpgl_dpt_t *off = malloc(2 * n * sizeof *off);
	if (!off)
		return -1;
	int rc = 0;
	for (int i = 0; i < k && !rc; i++) {
		double dist = (h->line_width_pu - pen) * (i / (double)(k - 1) - 0.5);
		size_t m = hpgl_offset_poly(pts, n, closed, dist, off);
		if (!closed)   /* issue 22: the passes cover round and square caps */
			hpgl_cap_pass(off, m, h->line_cap, h->line_width_pu / 2, pen, dist);
		rc = hpgl_clip_poly(off, m, closed, h->map.clip, add_piece, d);
	}
	free(off);
	return rc;
}

/* A piece in thousandths of a pixel: map it. */
static int add_model(void *user, const hpgl_dpt_t *pts, size_t n, int closed)
{
	dev_device_t *d = user;
	hpgl_dev_t *h = d->priv;
	/* a scratch of the device's (add_mapped and below do not come back here): no allocation a
	 * piece, which is most of a dash-heavy page's pieces' cost */
	if (hpgl_dev_grow((void **)&h->mpts, &h->capmpts, n ? n : 1, sizeof *h->mpts))
		return -1;
	hpgl_dpt_t *m = h->mpts;
	for (size_t i = 0; i < n; i++)
		hpgl_map_point(&h->map, (int64_t)pts[i].x, (int64_t)pts[i].y, &m[i].x, &m[i].y);
	return add_mapped(user, m, n, closed);
}

/* The carousel pen for a colour, or -1 for paper (hpgl_pens_pick). */
static long pen_for(hpgl_dev_t *h, meta_rgb_t rgb)
{
	return hpgl_pens_pick(&h->pens, rgb);
}

/* A stroke's subpaths, solid: the framework has dashed it already (dash pieces, windowed to
 * the page, as open subpaths), or the instance ignores dashes (dash=solid claims DEV_CAP_DASH). */
static int stroke_flat(dev_device_t *d, const scan_path_t *f, const dev_state_t *st)
{
	hpgl_dev_t *h = d->priv;
	long pen = pen_for(h, st->colour);
	if (pen < 0)
		return 0;
	h->cur_pen = (size_t)pen;
	/* width 1 (the default, and the minimum of spec 4) is a hairline: one pass of the pen */
	h->line_width_pu = st->width <= 1000 ? 0 : st->width / 1000.0 * h->map.pu_per_px;
	h->line_cap = st->cap;
	for (size_t s = 0; s < f->nsubs; s++) {
		const scan_subpath_t *sp = &f->subs[s];
		if (sp->n == 0)
			continue;
		if (hpgl_dev_need_tmp(h, sp->n + 1))
			return hpgl_dev_nomem(d);
		for (size_t i = 0; i < sp->n; i++)
			h->tmp[i] = (hpgl_dpt_t){ (double)f->pts[sp->start + i].x, (double)f->pts[sp->start + i].y };
		int rc;
		if (sp->n == 1)   /* a dot */
			rc = add_model(d, (hpgl_dpt_t[]){ h->tmp[0], h->tmp[0] }, 2, 0);
		else
			rc = add_model(d, h->tmp, sp->n, sp->closed);
		if (rc)
			return cb_fail(d);
	}
	return 0;
}

static int h_stroke(dev_device_t *d, const dev_path_t *p, const dev_state_t *st)
{
	return stroke_flat(d, p->flat, st);
}

static int hatch_seg(void *user, double x0, double y0, double x1, double y1)
{
	hpgl_dpt_t s[2] = { { x0, y0 }, { x1, y1 } };
	dev_device_t *d = user;
	hpgl_dev_t *h = d->priv;
	return hpgl_clip_poly(s, 2, 0, h->map.clip, add_piece, d);
}

static int fill_mapped(dev_device_t *d, const scan_path_t *f, int rule, meta_rgb_t rgb)
{
	hpgl_dev_t *h = d->priv;
	long pen = pen_for(h, rgb);
	if (pen < 0 || h->fill == HPGL_FILL_NONE)
		return 0;
	h->cur_pen = (size_t)pen;
	size_t n = f->npts;
	double *xy = malloc((2 * n + 2) * sizeof *xy);
	size_t *starts = malloc((f->nsubs + 1) * sizeof *starts), nc = 0, at = 0;
	if (!xy || !starts) {
		free(xy);
		free(starts);
		return hpgl_dev_nomem(d);
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
	/* native: HP-GL/2 fills any polygon (PM/FP); HP-GL only an axis-aligned rectangle (RA) */
	int rect = nc == 1 && at == 4;
	for (size_t i = 0; rect && i < 4; i++) {
		const double *p = xy + 2 * i, *q = xy + 2 * ((i + 1) % 4);
		rect = lround(p[0]) == lround(q[0]) || lround(p[1]) == lround(q[1]);
	}
	if (h->fill == HPGL_FILL_NATIVE && inside && nc && (h->prof.dialect == HPGL_DIALECT_2 || rect)) {
		if (hpgl_dev_grow((void **)&h->fills, &h->capfills, h->nfills + 1, sizeof *h->fills) ||
				hpgl_dev_grow((void **)&h->fstarts, &h->capfstarts, h->nfstarts + nc + 1, sizeof *h->fstarts) ||
				hpgl_dev_grow((void **)&h->fpts, &h->capfpts, h->nfpts + at, sizeof *h->fpts))
			rc = -1;
		else {
			h->fills[h->nfills++] = (hpgl_nfill_t){ (size_t)pen, h->nfstarts, nc, rule == META_RULE_EVEN_ODD };
			for (size_t k = 0; k <= nc; k++)
				h->fstarts[h->nfstarts + k] = h->nfpts + starts[k];
			h->nfstarts += nc + 1;
			for (size_t i = 0; i < at; i++)
				h->fpts[h->nfpts++] = (popt_pt_t){ (int32_t)lround(xy[2 * i]), (int32_t)lround(xy[2 * i + 1]) };
			if (!h->optimise) {   /* streaming: written now */
				const hpgl_nfill_t *nf = &h->fills[h->nfills - 1];
				rc = hpgl_page_pen(d, (size_t)pen) ? -1 : hpgl_emit_fill(h->em, h->fpts, h->fstarts + nf->first,
					nf->ncont, 0, nf->even_odd) ? (hpgl_dev_emit_fail(d), -1) : 0;
				h->nfills = h->nfstarts = h->nfpts = 0;
			}
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
		if (h->fill == HPGL_FILL_HATCH)
			rc = hatch_polygon(xy, starts, nc, rule == META_RULE_EVEN_ODD, h->hatch_angle, sp, 0, hatch_seg, d);
		for (size_t k = 0; k < nc && !rc && (h->outline || h->fill == HPGL_FILL_OUTLINE); k++) {
			size_t m = starts[k + 1] - starts[k];
			if (hpgl_dev_need_tmp(h, m)) {
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
	return rc ? cb_fail(d) : 0;
}

/* fill_path: claimed (DEV_CAP_FILL) only with fill=native: HP-GL/2 FP, HP-GL RA, else hatched */
static int h_fill(dev_device_t *d, const dev_path_t *p, const dev_state_t *st)
{
	return fill_mapped(d, p->flat, st->rule, st->colour);
}

/* The device's hatch op: the framework's way to a fill on an instance without native fills
 * (fill=hatch, outline or none): hpgl_hatch.c's lines by the path's rule, and the outline. */
static int h_hatch(dev_device_t *d, const dev_path_t *p, const dev_state_t *st)
{
	return fill_mapped(d, p->flat, st->rule, st->colour);
}

static int h_text(dev_device_t *d, const dev_text_t *t, const dev_state_t *st)
{
	hpgl_dev_t *h = d->priv;
	if (!h->text_label) {
		scan_path_t p = { 0 };
		int rc = scan_text_path(&p, t->str, t->len, t->x, t->y, t->size, t->angle) ? hpgl_dev_nomem(d)
			: stroke_flat(d, &p, st);
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
	double hmm = t->size / 1000.0 * h->map.pu_per_px / HPGL_PU_PER_MM, angle = t->angle / 1000.0 + h->place.rotate;
	if (!h->optimise) {
		if (hpgl_page_pen(d, (size_t)pen))
			return -1;
		return hpgl_emit_label(h->em, (int32_t)lround(X), (int32_t)lround(Y), hmm, angle, t->str, t->len)
			? hpgl_dev_emit_fail(d) : 0;
	}
	if (hpgl_dev_grow((void **)&h->labels, &h->caplabels, h->nlabels + 1, sizeof *h->labels))
		return hpgl_dev_nomem(d);
	hpgl_label_t *l = &h->labels[h->nlabels];
	l->s = malloc(t->len + 1);
	if (!l->s)
		return hpgl_dev_nomem(d);
	memcpy(l->s, t->str, t->len);
	l->len = t->len;
	l->pen = (size_t)pen;
	l->x = (int32_t)lround(X);
	l->y = (int32_t)lround(Y);
	l->height_mm = hmm;
	l->angle = angle;
	h->nlabels++;
	return 0;
}

static int raster_seg(void *user, double x0, double y0, double x1, double y1)
{
	hpgl_dpt_t s[2];
	dev_device_t *d = user;
	hpgl_dev_t *h = d->priv;
	hpgl_map_point(&h->map, (int64_t)x0, (int64_t)y0, &s[0].x, &s[0].y);
	hpgl_map_point(&h->map, (int64_t)x1, (int64_t)y1, &s[1].x, &s[1].y);
	return hpgl_clip_poly(s, 2, 0, h->map.clip, add_piece, d);
}

static int h_span(dev_device_t *d, unsigned x, unsigned y, unsigned n, meta_rgb_t rgb)
{
	hpgl_dev_t *h = d->priv;
	if (h->raster_skip) {
		hpgl_dev_warn(&h->warned, "raster content (spans, images) skipped (raster=skip)");
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
	double lr = px / pw < 1e6 ? round(px / pw) : 1e6, sr = pw / px < 1e6 ? round(pw / px) : 1e6;
	unsigned lines = (unsigned)lr, step = 1;
	if (lines == 0) {
		step = (unsigned)sr;
		lines = 1;
		if (y % step)
			return 0;
	}
	double *dk = malloc(n * sizeof *dk);
	if (!dk)
		return hpgl_dev_nomem(d);
	for (unsigned i = 0; i < n; i++)
		dk[i] = dark;
	int rc = hatch_row(dk, n, x * 1000.0, (x + n) * 1000.0, y * 1000.0, 1000.0 * step, lines, y / step,
		raster_seg, d);
	free(dk);
	return rc ? cb_fail(d) : 0;
}

static int h_clear(dev_device_t *d, const dev_page_t *pg, meta_rgb_t rgb)
{
	hpgl_dev_t *h = d->priv;
	(void)pg;   /* the page size came with begin_page */
	if (pen_for(h, rgb) < 0)
		return 0;
	if (!h->background) {
		hpgl_dev_warn(&h->warned_bg, "a non-white page background (clear) is not drawn (background=hatch draws it)");
		return 0;
	}
	scan_path_t r = { 0 };
	int64_t W = (int64_t)h->page_w * 1000, H = (int64_t)h->page_h * 1000;
	int rc = scan_path_move(&r, 0, 0) || scan_path_draw(&r, W, 0) || scan_path_draw(&r, W, H) ||
		scan_path_draw(&r, 0, H) ? hpgl_dev_nomem(d) : fill_mapped(d, &r, META_RULE_NON_ZERO, rgb);
	scan_path_free(&r);
	return rc;
}

static int h_begin(dev_device_t *d, const dev_page_t *pg)
{
	hpgl_dev_t *h = d->priv;
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
		return hpgl_dev_nomem(d);
	int pauses = h->pause_all;
	for (int k = 1; k <= HPGL_MAX_PENS && !pauses; k++)
		pauses = h->penset[k].pause;
	if (pauses && d->out && !io_in_place(d->out))
		hpgl_dev_warn(&h->warned_pause, "pauses before pens happen only when the job goes to a device "
			"(a file is plotted later, whole)");
	return hpgl_page_begin(d, pg);
}

static int h_close(dev_device_t *d)
{
	hpgl_dev_t *h = d->priv;
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
	free(h->mpts);
	free(h->kpts);
	free(h->spts);
	free(h->rep);
	free(h->ipts);
	hpgl_emit_free(h->em);
	hpgl_dev_pen_free(h);
	memset(h, 0, sizeof *h);
	return 0;
}

const dev_ops_t dev_hpgl_ops = {
	.name = "hpgl", .description = "HP-GL and HP-GL/2 pen plotters and cutters (profiles, pens, path optimisation)",
	.extension = ".hpgl", .caps = DEV_CAP_VECTOR | DEV_CAP_TEXT | DEV_CAP_WIDTH | DEV_CAP_ONLY,
	.priv_size = sizeof(hpgl_dev_t), .option_list = hpgl_options,
	.open = h_open, .begin_page = h_begin, .clear = h_clear, .stroke_path = h_stroke, .fill_path = h_fill,
	.hatch = h_hatch, .text = h_text, .put_span = h_span, .end_page = hpgl_page_write, .close = h_close,
	.comment = hpgl_dev_comment,
};
