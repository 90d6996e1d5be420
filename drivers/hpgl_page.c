/* hpgl_page.c: the end of an HP-GL page: each pen's paths optimised (pathopt), written (with
 * drag-knife paths on cutters), timed by the plot-time model, and reported. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hpgl_dev.h"

static void (*reporter)(void *, const hpgl_report_t *);
static void *reporter_user;

void hpgl_set_reporter(void (*fn)(void *user, const hpgl_report_t *r), void *user)
{
	reporter = fn;
	reporter_user = user;
}

void hpgl_dev_warn(int *flag, const char *msg)
{
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

int hpgl_dev_emit_fail(dev_device_t *d)
{
	hpgl_dev_t *h = d->priv;
	const char *e = hpgl_emit_error(h->em);
	return dev_fail(d, META_EIO, "%s", e[0] ? e : "hpgl: out of memory");
}

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
	hpgl_time_add(&h->k_pr->time, &h->prof, sqrt(dx * dx + dy * dy), q, m);
	int rc = hpgl_emit_poly(h->em, q, m);
	*h->k_at = q[m - 1];
	free(q);
	return rc;
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
	if (hpgl_emit_pen(h->em, pr->slot))
		return hpgl_dev_emit_fail(d);
	r->pen_changes++;
	if (h->prof.dialect == HPGL_DIALECT_2 && hpgl_emit_cmd(h->em, "PW%.2f,%d", h->pens.pen[k].width_mm, pr->slot))
		return hpgl_dev_emit_fail(d);
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
		if (n == 1)
			h->ipts[n++] = h->ipts[0];   /* a dot: pen down where it is */
		popt_pt_t f = h->ipts[0];
		if (h->prof.cutter && h->knife > 0) {
			/* the tool path of a drag knife; a closed path is cut on past its start */
			const popt_path_t *pp = &s->paths[s->order[i]];
			if (hpgl_dev_need_tmp(h, n))
				return hpgl_dev_nomem(d);
			for (size_t j = 0; j < n; j++)
				h->tmp[j] = (hpgl_dpt_t){ h->ipts[j].x, h->ipts[j].y };
			h->k_at = at;
			h->k_pr = pr;
			if (hpgl_knife_poly(h->tmp, pp->closed ? n - 1 : n, pp->closed, h->knife * HPGL_PU_PER_MM,
					h->overcut * HPGL_PU_PER_MM, emit_knife, d))
				return hpgl_dev_emit_fail(d);
			continue;
		}
		double dx = (double)f.x - at->x, dy = (double)f.y - at->y;
		hpgl_time_add(&pr->time, &h->prof, sqrt(dx * dx + dy * dy), h->ipts, n);
		if (hpgl_emit_poly(h->em, h->ipts, n))
			return hpgl_dev_emit_fail(d);
		*at = h->ipts[n - 1];
	}
	for (size_t i = 0; i < h->nlabels; i++) {
		const hpgl_label_t *l = &h->labels[i];
		if (l->pen == k && hpgl_emit_label(h->em, l->x, l->y, l->height_mm, l->angle, l->s, l->len))
			return hpgl_dev_emit_fail(d);
	}
	return 0;
}

/* end_page: the pens in slot order from the lower-left corner of the clip limits, PU;SP0; last. */
int hpgl_page_write(dev_device_t *d, const dev_page_t *pg)
{
	hpgl_dev_t *h = d->priv;
	hpgl_report_t *r = calloc(1, sizeof *r);
	if (!r)
		return hpgl_dev_nomem(d);
	r->page = pg->index;
	r->profile = h->prof.name;
	r->optimised = h->optimise;
	memcpy(r->box, h->map.clip, sizeof r->box);
	/* the pen starts at the lower-left corner of the hard-clip limits (after IN) */
	popt_pt_t at = { h->prof.clip[h->place.paper][0], h->prof.clip[h->place.paper][1] };
	int rc = 0;
	h->total_paths = 0;
	for (size_t k = 0; k < h->pens.n; k++)
		h->total_paths += h->sets[k].npaths;
	if (h->prof.v_down > 0 && !h->prof.cutter)
		rc = hpgl_emit_cmd(h->em, "VS%g", h->prof.v_down) ? hpgl_dev_emit_fail(d) : 0;
	for (size_t k = 0; k < h->pens.n && !rc; k++)
		rc = emit_pen(d, k, &at, r);
	if (!rc && (hpgl_emit_cmd(h->em, "PU") || hpgl_emit_pen(h->em, 0) || hpgl_emit_flush(h->em)))
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
