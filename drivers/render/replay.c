/* replay.c: painting the renderer's spooled records onto a band (both threads of render_par.c
 * read the spool through it) and the spool's failure message. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "render/render_int.h"

int render_spool_fail(render_t *r, int err_no, const char *doing)
{
	if (err_no)
		snprintf(r->err, sizeof r->err, "band spool (a temporary file in %s): %s: %s", r->spool_dir,
			doing, strerror(err_no));
	else
		snprintf(r->err, sizeof r->err, "band spool (a temporary file in %s): the page needs more "
			"than its limit of %llu %s (LOCUS_SPOOL_MAX_MB)", r->spool_dir,
			(unsigned long long)(r->spool_max >= 1 << 20 ? r->spool_max >> 20 : r->spool_max),
			r->spool_max >= 1 << 20 ? "MiB" : "bytes");
	return META_EIO;
}

static int load_path(painter_t *pt, const unsigned char *q)
{
	uint64_t cnt[2];
	memcpy(cnt, q, sizeof cnt);
	q += sizeof cnt;
	int packed = (cnt[0] & PACKED) != 0;
	cnt[0] &= ~PACKED;
	scan_path_t *p = &pt->path;
	if (cnt[0] > p->cappts) {
		scan_pt_t *n = realloc(p->pts, cnt[0] * sizeof(scan_pt_t));
		if (!n)
			return META_ENOMEM;
		p->pts = n;
		p->cappts = cnt[0];
	}
	if (cnt[1] > p->capsubs) {
		scan_subpath_t *n = realloc(p->subs, cnt[1] * sizeof(scan_subpath_t));
		if (!n)
			return META_ENOMEM;
		p->subs = n;
		p->capsubs = cnt[1];
	}
	p->npts = cnt[0];
	p->nsubs = cnt[1];
	memcpy(p->subs, q, cnt[1] * sizeof(scan_subpath_t));
	q += cnt[1] * sizeof(scan_subpath_t);
	if (!packed) {
		memcpy(p->pts, q, cnt[0] * sizeof(scan_pt_t));
		return 0;
	}
	for (size_t k = 0; k < cnt[0]; k++) {
		int32_t v[2];
		memcpy(v, q + 8 * k, sizeof v);
		p->pts[k].x = v[0];
		p->pts[k].y = v[1];
	}
	return 0;
}

/* Paint one record (header h, payload q) onto the painter's band. */
int render_replay_rec(painter_t *pt, const rec_t *hp, const unsigned char *q)
{
	rec_t h = *hp;
	int rc = 0;
	if (h.jhi <= pt->band.jlo || h.jlo >= pt->band.jhi)
		return 0;
	if (h.kind == REC_CLEAR) {
		meta_rgb_t c;
		memcpy(&c, q, sizeof c);
		scan_clear(&pt->band, c);
	} else if (h.kind == REC_FILL) {
		fill_head_t f;
		memcpy(&f, q, sizeof f);
		if (!(rc = load_path(pt, q + sizeof f)))
			rc = scan_fill(pt->ctx, &pt->band, &pt->path, f.rule, f.rgb);
	} else if (h.kind == REC_STROKE) {
		stroke_head_t s;
		memcpy(&s, q, STROKE_HEAD(0));
		memcpy(s.dash, q + STROKE_HEAD(0), s.ndash * sizeof(int64_t));
		scan_style_t st = { s.width, s.cap, s.join, s.miter_limit, s.dash, s.ndash };
		if (!(rc = load_path(pt, q + STROKE_HEAD(s.ndash))))
			rc = scan_stroke(pt->ctx, &pt->band, &pt->path, &st, s.rgb);
	} else if (h.kind == REC_SPAN) {
		int64_t v[3];
		meta_rgb_t c;
		memcpy(v, q, sizeof v);
		memcpy(&c, q + sizeof v, sizeof c);
		scan_span(&pt->band, v[0], v[1], v[2], c);
	} else if (h.kind == REC_ROW) {
		int64_t v[2];
		memcpy(v, q, sizeof v);
		size_t n = (h.len - sizeof v) / sizeof(meta_run_t);
		if (n > pt->cap_runs) {
			meta_run_t *m = realloc(pt->runs, n * sizeof *m);
			if (!m)
				return META_ENOMEM;
			pt->runs = m;
			pt->cap_runs = n;
		}
		memcpy(pt->runs, q + sizeof v, n * sizeof(meta_run_t));
		render_paint_row(&pt->band, v[0], v[1], pt->runs, n);
	}
	return rc;
}
