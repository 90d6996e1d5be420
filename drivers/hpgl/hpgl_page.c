/* hpgl_page.c: the end of an HP-GL page: each pen's paths optimised (pathopt), written (with
 * drag-knife paths on cutters), timed by the plot-time model, and reported. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hpgl/hpgl_dev.h"

/* The knife's tool path: round and write it. */
static int emit_knife(void *user, const hpgl_dpt_t *pts, size_t n, int closed)
{
	dev_device_t *d = user;
	hpgl_dev_t *h = d->priv;
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
	hpgl_time_add(&h->k_pr->time, &h->tprof, sqrt(dx * dx + dy * dy), q, m);
	int rc = hpgl_emit_poly(h->em, q, m);
	*h->k_at = q[m - 1];
	free(q);
	return rc;
}

/* Write one path (n points, a closed one with its first point repeated at the end; room for one
 * more in pts) from the pen position *at: a dot gets a pen-down where it is, a cutter's path
 * becomes the drag knife's. Times it into pr. */
static int put_path(dev_device_t *d, hpgl_pen_report_t *pr, popt_pt_t *at, popt_pt_t *pts, size_t n, int closed)
{
	hpgl_dev_t *h = d->priv;
	if (n == 1)
		pts[n++] = pts[0];
	if (h->prof.cutter && h->knife > 0) {
		/* a buffer of its own: h->tmp may be holding the path being collected (streaming) */
		if (hpgl_dev_grow((void **)&h->kpts, &h->capkpts, n, sizeof *h->kpts))
			return hpgl_dev_nomem(d);
		for (size_t j = 0; j < n; j++)
			h->kpts[j] = (hpgl_dpt_t){ pts[j].x, pts[j].y };
		h->k_at = at;
		h->k_pr = pr;
		if (hpgl_knife_poly(h->kpts, closed ? n - 1 : n, closed, h->knife * HPGL_PU_PER_MM,
				h->overcut * HPGL_PU_PER_MM, emit_knife, d))
			return hpgl_dev_emit_fail(d);
		return 0;
	}
	double dx = (double)pts[0].x - at->x, dy = (double)pts[0].y - at->y, t = sqrt(dx * dx + dy * dy);
	hpgl_time_add(&pr->time, &h->tprof, t, pts, n);
	if (hpgl_emit_poly(h->em, pts, n))
		return hpgl_dev_emit_fail(d);
	*at = pts[n - 1];
	return 0;
}

/* Write one pen's share: native fills, then its paths in the optimised order, then labels. */
static int emit_pen(dev_device_t *d, size_t k, popt_pt_t *at, hpgl_report_t *r)
{
	hpgl_dev_t *h = d->priv;
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
	if (hpgl_dev_pen(d, k))
		return -1;
	r->pen_changes++;
	for (size_t i = 0; i < h->nfills; i++) {
		const hpgl_nfill_t *f = &h->fills[i];
		if (f->pen == k && hpgl_emit_fill(h->em, h->fpts, h->fstarts + f->first, f->ncont, 0, f->even_odd))
			return hpgl_dev_emit_fail(d);
	}
	popt_stats_t st;
	if (h->optimise) {
		/* the 2-opt budget is the page's: each pen gets its share by its number of paths */
		popt_opts_t o = h->popt;
		o.budget_s = h->total_paths ? h->popt.budget_s * (double)s->npaths / (double)h->total_paths : 0;
		if (popt_optimise(s, *at, &o, &st))
			return hpgl_dev_nomem(d);
	} else {
		if (popt_keep_order(s))
			return hpgl_dev_nomem(d);
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
	if (hpgl_dev_grow((void **)&h->ipts, &h->capipts, maxn + 2, sizeof *h->ipts))
		return hpgl_dev_nomem(d);
	for (size_t i = 0; i < s->npaths; i++) {
		size_t n = popt_get(s, i, h->ipts);
		if (put_path(d, pr, at, h->ipts, n, s->paths[s->order[i]].closed))
			return -1;
	}
	for (size_t i = 0; i < h->nlabels; i++) {
		const hpgl_label_t *l = &h->labels[i];
		if (l->pen == k && hpgl_emit_label(h->em, l->x, l->y, l->height_mm, l->angle, l->s, l->len))
			return hpgl_dev_emit_fail(d);
	}
	return 0;
}

static void report_init(hpgl_dev_t *h, hpgl_report_t *r, unsigned page)
{
	r->page = page;
	r->profile = h->prof.name;
	r->optimised = h->optimise;
	memcpy(r->box, h->map.clip, sizeof r->box);
}

int hpgl_page_begin(dev_device_t *d, const dev_page_t *pg)
{
	hpgl_dev_t *h = d->priv;
	/* the pen starts at the lower-left corner of the hard-clip limits (after IN) */
	h->at = (popt_pt_t){ h->prof.clip[h->place.paper][0], h->prof.clip[h->place.paper][1] };
	h->stream_pen = SIZE_MAX;
	free(h->rep);
	h->rep = NULL;
	/* PCL framing as AutoCAD's HP-GL/2 driver writes it (../shared/corpus/hpgl/): ESC %-1B enters
	 * HP-GL/2; ESC %0A at the end returns to PCL. (No ESC E reset: hp2xx reads it as a command.) */
	if ((h->pcl && hpgl_emit_raw(h->em, "\033%-1B", 5)) || hpgl_emit_cmd(h->em, "IN") ||
			(h->prof.v_down > 0 && !h->prof.cutter && hpgl_emit_cmd(h->em, "VS%g", h->prof.v_down)))
		return hpgl_dev_emit_fail(d);
	/* IN set the plotter's defaults: the speed just sent, its own force and acceleration */
	h->vs_page = h->vs_now = h->prof.v_down > 0 && !h->prof.cutter ? h->prof.v_down : 0;
	h->fs_now = h->as_now = 0;
	h->tprof = h->prof;   /* hpgl_dev_pen gives it each pen's own speed */
	if (h->optimise)
		return 0;
	h->rep = calloc(1, sizeof *h->rep);
	if (!h->rep)
		return hpgl_dev_nomem(d);
	report_init(h, h->rep, pg->index);
	return 0;
}

int hpgl_page_pen(dev_device_t *d, size_t k)
{
	hpgl_dev_t *h = d->priv;
	hpgl_report_t *r = h->rep;
	if (k == h->stream_pen)
		return 0;
	h->stream_pen = k;
	int slot = h->pens.pen[k].slot;
	if (hpgl_dev_pen(d, k))
		return -1;
	r->pen_changes++;
	for (h->stream_pr = r->pen; h->stream_pr < r->pen + r->npens && h->stream_pr->slot != slot; h->stream_pr++)
		;
	if (h->stream_pr == r->pen + r->npens) {
		memset(h->stream_pr, 0, sizeof *h->stream_pr);
		h->stream_pr->slot = slot;
		r->npens++;
	}
	return 0;
}

int hpgl_page_put(dev_device_t *d, size_t k, const popt_pt_t *pts, size_t n, int closed)
{
	hpgl_dev_t *h = d->priv;
	if (hpgl_page_pen(d, k))
		return -1;
	if (hpgl_dev_grow((void **)&h->spts, &h->capspts, n + 2, sizeof *h->spts))
		return hpgl_dev_nomem(d);
	memcpy(h->spts, pts, n * sizeof *pts);
	if (closed)
		h->spts[n++] = pts[0];
	h->stream_pr->paths_in++;
	h->stream_pr->paths_out++;
	return put_path(d, h->stream_pr, &h->at, h->spts, n, closed);
}

/* end_page: the pens in slot order from the lower-left corner of the clip limits (streamed pages
 * are written already), PU;SP0; last. */
int hpgl_page_write(dev_device_t *d, const dev_page_t *pg)
{
	hpgl_dev_t *h = d->priv;
	hpgl_report_t *r = calloc(1, sizeof *r);
	if (!r)
		return hpgl_dev_nomem(d);
	report_init(h, r, pg->index);
	popt_pt_t at = h->at;
	int rc = 0;
	h->total_paths = 0;
	for (size_t k = 0; k < h->pens.n; k++)
		h->total_paths += h->sets[k].npaths;
	if (h->rep) {   /* streamed: everything is written already */
		free(r);
		r = h->rep;
		h->rep = NULL;
		for (size_t k = 0; k < r->npens; k++)
			r->pen[k].travel_before_mm = r->pen[k].travel_greedy_mm = r->pen[k].travel_after_mm =
				r->pen[k].time.up_mm;
	} else {
		for (size_t k = 0; k < h->pens.n && !rc; k++)
			rc = emit_pen(d, k, &at, r);
	}
	if (!rc && (hpgl_emit_cmd(h->em, "PU") || hpgl_emit_pen(h->em, 0) ||
			(h->pcl && hpgl_emit_raw(h->em, "\033%0A", 4)) || hpgl_emit_flush(h->em)))
		rc = hpgl_dev_emit_fail(d);
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
		h->job_base += r->bytes;   /* (pauses look at it only on one in-place output) */
		hpgl_dev_report(r);
	}
	for (size_t i = 0; i < h->nlabels; i++)
		free(h->labels[i].s);
	h->nlabels = 0;
	hpgl_emit_free(h->em);
	h->em = NULL;
	free(r);
	return rc;
}
