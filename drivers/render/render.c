/* render.c: banded raster rendering: paint directly, or spool and replay per band with culling. */
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "render/render_int.h"

/* The painters' threads are in render_par.c, the replay of a spooled record in replay.c; what
 * the files share is in render_int.h. */

uint64_t render_spool_default(void)
{
	const char *e = getenv("LOCUS_SPOOL_MAX_MB");
	char *end;
	unsigned long long mb = e && *e ? strtoull(e, &end, 10) : 0;
	if (!e || !*e || *end || mb == 0 || mb > ((uint64_t)1 << 40))
		return DEV_SPOOL_MAX_DEFAULT;
	return (uint64_t)mb << 20;
}

void render_set_spool_limit(render_t *r, uint64_t bytes)
{
	r->spool_max = bytes;
}

const char *render_error(const render_t *r)
{
	return r->err;
}

/* The spool: a file created in $TMPDIR (else /tmp) and unlinked at once, so that nothing is
 * left behind whatever happens to the process. */
static int spool_open(render_t *r)
{
	const char *dir = getenv("TMPDIR");
	if (!dir || !*dir || strlen(dir) > sizeof r->spool_dir - 24)
		dir = "/tmp";
	snprintf(r->spool_dir, sizeof r->spool_dir, "%s", dir);
	char path[sizeof r->spool_dir + 32];
	snprintf(path, sizeof path, "%s/locus-spool-XXXXXX", dir);
	int fd = mkstemp(path);
	if (fd < 0)
		return render_spool_fail(r, errno, "cannot create it");
	unlink(path);
	r->spool = fdopen(fd, "w+b");
	if (!r->spool) {
		int e = errno;
		close(fd);
		return render_spool_fail(r, e, "cannot open it");
	}
	return 0;
}

render_t *render_new(unsigned width, unsigned height, unsigned band_rows, size_t budget,
		char *err, size_t errlen)
{
	render_t *r = calloc(1, sizeof *r);
	if (!r)
		goto nomem;
	r->width = width;
	r->height = height;
	r->budget = budget;
	size_t row = (size_t)width * 3;
	if (band_rows == 0) {
		/* a page that is banded is painted by two threads, each band in half the budget
		 * (two bands of AUTO_BAND at most), unless those halves would be thin slices */
		if (row * height > AUTO_WHOLE_MAX && budget > 2 * AUTO_BAND)
			budget = 2 * AUTO_BAND;
		size_t fit = budget / row, half = budget / 2 / row;
		if (fit >= height)
			band_rows = height;
		else
			band_rows = half >= PAIR_MIN_ROWS ? (unsigned)half : fit < 1 ? 1 : (unsigned)fit;
	}
	if (band_rows > height)
		band_rows = height;
	r->band_rows = band_rows;
	r->bands = (height + band_rows - 1) / band_rows;
	r->pix = malloc(row * band_rows);
	r->main.ctx = scan_ctx_new();
	if (!r->pix || !r->main.ctx)
		goto nomem;
	scan_band_t *b = &r->main.band;
	b->pix = r->pix;
	b->stride = row;
	b->width = (int)width;
	b->height = (int)height;
	if (r->bands == 1) {
		b->jlo = 0;
		b->jhi = (int)height;
		memset(r->pix, 0xff, row * height);
		if (height >= SPLIT_MIN_ROWS && render_split_start(r) == 0) {
			r->split = 1;
			r->mid = height / 2;
			r->help.band = *b;
			r->help.band.pix = r->pix + (size_t)(height - r->mid) * row;
			r->help.band.jlo = 0;
			r->help.band.jhi = (int)r->mid;
			r->help2.band = *b;
			r->help2.band.jlo = (int)r->mid;
		}
	} else {
		r->spool_max = render_spool_default();
		if (spool_open(r)) {
			snprintf(err, errlen, "%s", r->err);
			render_free(r);
			return NULL;
		}
		/* the first two bands painted as the records arrive, when two bands fit the budget */
		size_t bytes = row * band_rows;
		if (bytes <= r->budget / 2 && (r->pix2 = malloc(bytes)) && render_split_start(r) == 0) {
			r->pre = 2;
			r->pre_lo = height > 2 * band_rows ? height - 2 * band_rows : 0;
			memset(r->pix, 0xff, bytes);
			memset(r->pix2, 0xff, bytes);
			r->help.band = *b;
			r->help.band.jhi = (int)height;
			r->help.band.jlo = (int)(height - band_rows);
			r->help2.band = *b;
			r->help2.band.pix = r->pix2;
			r->help2.band.jhi = (int)(height - band_rows);
			r->help2.band.jlo = (int)r->pre_lo;
		}
	}
	return r;
nomem:
	snprintf(err, errlen, "out of memory for a %ux%u page buffer", width, band_rows ? band_rows : height);
	render_free(r);
	return NULL;
}

void render_free(render_t *r)
{
	if (!r)
		return;
	render_split_stop(r);
	if (r->spool)
		fclose(r->spool);
	free(r->pix);
	free(r->pix2);
	painter_t *pt[3] = { &r->main, &r->help, &r->help2 };
	for (int k = 0; k < 3; k++) {
		scan_ctx_free(pt[k]->ctx);
		scan_path_free(&pt[k]->path);
		free(pt[k]->runs);
		free(pt[k]->rd.buf);
	}
	for (int k = 0; k < RING; k++)
		free(r->ring[k].buf);
	free(r);
}

unsigned render_bands(const render_t *r)
{
	return r->bands;
}

/* ---- spool writing ---- */

static int spool(render_t *r, int kind, int64_t jlo, int64_t jhi, const void *a, size_t na,
		const void *b, size_t nb, const void *c, size_t nc)
{
	if (jlo < 0)
		jlo = 0;
	if (jhi > r->height)
		jhi = r->height;
	if (jlo >= jhi)
		return 0;   /* entirely off the page (or the helper's rows) */
	rec_t h = { kind, (int32_t)jlo, (int32_t)jhi, (uint32_t)(na + nb + nc) };
	if (r->split)
		return render_split_put(r, &h, a, na, b, nb, c, nc);
	if (r->err[0])
		return META_EIO;   /* sticky */
	if (r->clear_pending) {
		r->clear_pending = 0;
		int rc = spool(r, REC_CLEAR, 0, r->height, &r->clear_rgb, sizeof r->clear_rgb, NULL, 0, NULL, 0);
		if (rc)
			return rc;
	}
	uint64_t need = sizeof h + na + nb + nc;
	if (r->spooled + need > r->spool_max)
		return render_spool_fail(r, 0, NULL);
	errno = 0;
	if (fwrite(&h, sizeof h, 1, r->spool) != 1 || (na && fwrite(a, 1, na, r->spool) != na) ||
			(nb && fwrite(b, 1, nb, r->spool) != nb) || (nc && fwrite(c, 1, nc, r->spool) != nc))
		return render_spool_fail(r, errno ? errno : EIO, "cannot write it");
	r->spooled += need;
	if (r->pre && jhi > r->pre_lo)
		return render_split_put(r, &h, a, na, b, nb, c, nc);
	return 0;
}

static int spool_path(render_t *r, int kind, int64_t ext, const void *head, size_t nhead,
		const scan_path_t *p)
{
	int64_t x0, y0, x1, y1;
	if (!scan_path_bbox(p, &x0, &y0, &x1, &y1))
		return 0;
	int64_t jlo = (y0 - ext) / 1000 - 2, jhi = (y1 + ext) / 1000 + 2;
	int packed = x0 >= INT32_MIN && y0 >= INT32_MIN && x1 <= INT32_MAX && y1 <= INT32_MAX;
	uint64_t cnt[2] = { p->npts | (packed ? PACKED : 0), p->nsubs };
	size_t nsz = sizeof cnt + p->nsubs * sizeof(scan_subpath_t);
	size_t npt = p->npts * (packed ? 2 * sizeof(int32_t) : sizeof(scan_pt_t));
	unsigned char *meta = malloc(nhead + nsz + (packed ? npt : 0));
	if (!meta)
		return META_ENOMEM;
	memcpy(meta, head, nhead);
	memcpy(meta + nhead, cnt, sizeof cnt);
	memcpy(meta + nhead + sizeof cnt, p->subs, p->nsubs * sizeof(scan_subpath_t));
	const void *pts = p->pts;
	if (packed) {
		int32_t *q = (int32_t *)(void *)(meta + nhead + nsz);
		for (size_t k = 0; k < p->npts; k++) {
			q[2 * k] = (int32_t)p->pts[k].x;
			q[2 * k + 1] = (int32_t)p->pts[k].y;
		}
		pts = q;
	}
	int rc = spool(r, kind, jlo, jhi, meta, nhead + nsz, pts, npt, NULL, 0);
	free(meta);
	return rc;
}

int render_clear(render_t *r, meta_rgb_t rgb)
{
	if (!r->spool && !r->split) {
		scan_clear(&r->main.band, rgb);
		return 0;
	}
	if (r->spool) {
		/* written with the next record (or at the finish): a clear has no failure of its own
		 * to report, so a spool write that fails is reported, as such, by what follows */
		r->clear_pending = 1;
		r->clear_rgb = rgb;
		return 0;
	}
	return spool(r, REC_CLEAR, 0, r->height, &rgb, sizeof rgb, NULL, 0, NULL, 0);
}

int render_fill(render_t *r, const scan_path_t *p, int rule, meta_rgb_t rgb)
{
	if (!r->spool && !r->split)
		return scan_fill(r->main.ctx, &r->main.band, p, rule, rgb);
	fill_head_t h;
	memset(&h, 0, sizeof h);
	h.rgb = rgb;
	h.rule = rule;
	return spool_path(r, REC_FILL, 0, &h, sizeof h, p);
}

int render_stroke(render_t *r, const scan_path_t *p, const scan_style_t *st, meta_rgb_t rgb)
{
	if (!r->spool && !r->split)
		return scan_stroke(r->main.ctx, &r->main.band, p, st, rgb);
	stroke_head_t h;
	memset(&h, 0, sizeof h);
	h.rgb = rgb;
	h.cap = st->cap;
	h.join = st->join;
	h.width = st->width;
	h.miter_limit = st->miter_limit;
	h.ndash = st->dash ? st->ndash : 0;
	if (h.ndash > 2 * META_MAX_DASH)
		h.ndash = 2 * META_MAX_DASH;
	for (size_t k = 0; k < h.ndash; k++)
		h.dash[k] = st->dash[k];
	int64_t w = st->width < 1000 ? 1000 : st->width;
	int64_t lim = st->miter_limit < 1500 ? 1500 : st->miter_limit;
	int64_t ext = (int64_t)((double)w / 2.0 * ((double)lim / 1000.0)) + 2000;
	return spool_path(r, REC_STROKE, ext, &h, STROKE_HEAD(h.ndash), p);
}

int render_span(render_t *r, int64_t x, int64_t y, int64_t n, meta_rgb_t rgb)
{
	if (!r->spool && !r->split) {
		scan_span(&r->main.band, x, y, n, rgb);
		return 0;
	}
	int64_t v[3] = { x, y, n };
	return spool(r, REC_SPAN, y, y + 1, v, sizeof v, &rgb, sizeof rgb, NULL, 0);
}

int render_row(render_t *r, int64_t x, int64_t y, const meta_run_t *runs, size_t nruns)
{
	if (!r->spool && !r->split) {
		render_paint_row(&r->main.band, x, y, runs, nruns);
		return 0;
	}
	int64_t v[2] = { x, y };
	return spool(r, REC_ROW, y, y + 1, v, sizeof v, runs, nruns * sizeof(meta_run_t), NULL, 0);
}

int render_finish(render_t *r, render_band_fn fn, void *user)
{
	size_t row = (size_t)r->width * 3;
	render_band_t out = { r->pix, row, r->width, 0, 0, r->height };
	if (!r->spool) {
		int rc = render_split_stop(r);
		if (rc)
			return rc;
		out.nrows = r->height;
		return fn(user, &out);
	}
	if (r->clear_pending) {
		int rc = spool(r, REC_CLEAR, 0, r->height, &r->clear_rgb, sizeof r->clear_rgb, NULL, 0, NULL, 0);
		if (rc)
			return rc;
	}
	if (r->err[0])
		return META_EIO;
	if (r->started) {
		int rc = render_split_stop(r);
		if (rc)
			return rc;
	}
	errno = 0;
	if (fflush(r->spool))
		return render_spool_fail(r, errno ? errno : EIO, "cannot write it");
	return render_par_bands(r, fn, user);
}
