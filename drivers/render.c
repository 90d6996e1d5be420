/* render.c: banded raster rendering: paint directly, or spool and replay per band with culling. */
#include <errno.h>
#include <pthread.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "render.h"

enum { REC_CLEAR = 1, REC_FILL, REC_STROKE, REC_SPAN, REC_ROW };

/* Spool record header: kind, then the page rows [jlo, jhi) the record may touch, payload size. */
typedef struct {
	int32_t kind, jlo, jhi;
	uint32_t len;
} rec_t;

/* A painter's own reader of the spool (pread at its own offset, so that two painters replay
 * it at once): records skipped within the buffer cost no system call. */
typedef struct {
	unsigned char *buf;
	size_t cap, len, pos;   /* buf[pos, len) not consumed yet */
	uint64_t off;           /* file offset of buf[len] */
} reader_t;

/* What replaying records onto one band needs (one per painting thread). */
typedef struct {
	scan_band_t band;
	scan_ctx_t *ctx;
	scan_path_t path;       /* deserialised path */
	meta_run_t *runs;
	size_t cap_runs;
	reader_t rd;
	int err_no;             /* errno of a failed spool read (0: short), for the message */
	int read_failed;        /* the spool could not be read back */
} painter_t;

/* A block of spool records in memory, handed from the reading thread to the helper. */
typedef struct {
	unsigned char *buf;
	size_t len, cap;
} chunk_t;

/* Blocks queued for the split helpers: each helper replays them at its own pace, and the
 * caller's thread waits only when the slower one is this many blocks behind (two blocks made
 * the faster helper wait for the slower one at every block: workload c's bottom half has half
 * as much again to paint as its top half). */
#define RING 16
/* Records are handed to the helper in blocks of about this many bytes: small enough that the
 * helper starts at once (workload b's 10,000 fills spool 1.2 MB: in blocks of 1 MB the helper
 * waited for 80% of the input before its first block), large enough that hand-overs are rare. */
#define CHUNK_BYTES ((size_t)64 << 10)
/* Automatic banding of a page buffer larger than AUTO_WHOLE_MAX: bands of at most AUTO_BAND
 * bytes, even when the budget would hold the whole page. A band that stays in the last-level
 * cache paints and hands over faster than one big buffer that is faulted in, filled white and
 * painted from memory: anti-aliased 4 x 4 replays of workloads b and c (a 4096 x 3072 sample
 * page) took a third less CPU in bands of 8 MiB than whole, a about the same (docs/drivers.md). */
#define AUTO_WHOLE_MAX ((size_t)16 << 20)
#define AUTO_BAND ((size_t)8 << 20)
/* Pages with fewer rows are painted by one thread. */
#define SPLIT_MIN_ROWS 128
/* Automatic bands of a page painted by two threads have at least this many rows. */
#define PAIR_MIN_ROWS 32
/* A painter reads the spool in blocks of this many bytes. */
#define READ_BYTES ((size_t)256 << 10)

struct dev_render {
	unsigned width, height, band_rows, bands;
	uint8_t *pix;
	painter_t main;         /* its band: the whole page, a spooled band, or the split's top */
	FILE *spool;            /* NULL: single band, painted directly */
	uint64_t spooled, spool_max; /* bytes in the spool; its limit */
	char spool_dir[200];    /* where the (unlinked) spool file lives, for messages */
	char err[320];          /* the last failure (dev_render_error) */
	int clear_pending;      /* a spooled clear not written yet (with the next record) */
	meta_rgb_t clear_rgb;
	size_t budget;          /* bytes the page buffers may take */
	/* multi-band page painted by two threads: the caller's paints band 0 into pix, a helper
	 * band 1 into pix2, and each then the next band not taken, each replaying the spool with
	 * its own reader; finished bands go to the band function in order (the thread holding the
	 * next band calls it, the other one paints on meanwhile) */
	uint8_t *pix2;
	unsigned next_band;     /* the band to hand over next */
	unsigned next_paint;    /* the next band no painter has taken */
	int bstop, brc, bread;  /* stop painting; the first error; it was a spool read */
	dev_band_fn bfn;
	void *buser;
	/* split single-band page: two helper threads paint rows [0, mid) and [mid, height) from
	 * the records that the caller's thread queues as it reads the input; the two bands are
	 * disjoint rows painted in statement order each, so the pixels are those of one thread.
	 * Three threads on two cores: the system shares the cores between reading and painting
	 * as each page needs (reading is two thirds of the work of workload b's small fills, a
	 * quarter of workload a's thin polylines), which no fixed share of rows could */
	int split, started;
	unsigned mid;
	/* multi-band page: the two helpers also paint its first two bands (r->pix, r->pix2) from
	 * the records queued as they are spooled, so that reading and painting overlap there too;
	 * pre bands are painted so (0 or 2), pre_lo is their lowest row */
	unsigned pre, pre_lo;
	painter_t help, help2;  /* help: a multi-band page's second painter, or the split's bottom rows */
	chunk_t ring[RING];     /* blocks: block s (s = 0, 1, ...) is ring[s % RING] */
	unsigned head;          /* blocks handed over so far; ring[head % RING] is being filled */
	unsigned done[2];       /* blocks each helper has replayed */
	int quit, hrc;          /* stop when done; the first error */
	pthread_t thr, thr2;
	pthread_mutex_t mu;
	pthread_cond_t cv;
	struct helper_arg {
		struct dev_render *r;
		painter_t *pt;
		int idx;
	} harg[2];
};

/* What a split helper is told: its renderer and its painter. */
typedef struct helper_arg helper_arg_t;

static int replay_rec(painter_t *pt, const rec_t *h, const unsigned char *q);

/* A split helper: replay each block handed over onto its band until told to quit. */
static void *helper(void *arg)
{
	const helper_arg_t *ha = arg;
	dev_render_t *r = ha->r;
	unsigned *done = &r->done[ha->idx];
	pthread_mutex_lock(&r->mu);
	for (;;) {
		while (*done == r->head && !r->quit)
			pthread_cond_wait(&r->cv, &r->mu);
		if (*done == r->head)
			break;
		const chunk_t *w = &r->ring[*done % RING];
		pthread_mutex_unlock(&r->mu);
		int rc = 0;
		for (size_t at = 0; at < w->len && rc == 0;) {
			rec_t h;
			memcpy(&h, w->buf + at, sizeof h);
			rc = replay_rec(ha->pt, &h, w->buf + at + sizeof h);
			at += sizeof h + h.len;
		}
		pthread_mutex_lock(&r->mu);
		if (rc && !r->hrc)
			r->hrc = rc;
		++*done;
		pthread_cond_broadcast(&r->cv);
	}
	pthread_mutex_unlock(&r->mu);
	return NULL;
}

/* Set up the split (helper thread and its buffers); nonzero leaves the page to one thread. */
static int split_start(dev_render_t *r)
{
	r->help.ctx = scan_ctx_new();
	r->help2.ctx = scan_ctx_new();
	if (!r->help.ctx || !r->help2.ctx)
		return -1;
	if (pthread_mutex_init(&r->mu, NULL))
		return -1;
	if (pthread_cond_init(&r->cv, NULL)) {
		pthread_mutex_destroy(&r->mu);
		return -1;
	}
	r->harg[0] = (helper_arg_t){ r, &r->help, 0 };
	r->harg[1] = (helper_arg_t){ r, &r->help2, 1 };
	if (pthread_create(&r->thr, NULL, helper, &r->harg[0])) {
		pthread_cond_destroy(&r->cv);
		pthread_mutex_destroy(&r->mu);
		return -1;
	}
	if (pthread_create(&r->thr2, NULL, helper, &r->harg[1])) {
		pthread_mutex_lock(&r->mu);
		r->quit = 1;
		pthread_cond_broadcast(&r->cv);
		pthread_mutex_unlock(&r->mu);
		pthread_join(r->thr, NULL);
		r->quit = 0;
		pthread_cond_destroy(&r->cv);
		pthread_mutex_destroy(&r->mu);
		return -1;
	}
	r->started = 1;
	return 0;
}

/* Hand the filled block to the helpers, and wait until the next one is free (both helpers
 * have replayed the block that used it RING blocks ago). */
static int split_hand(dev_render_t *r)
{
	pthread_mutex_lock(&r->mu);
	if (r->ring[r->head % RING].len) {
		r->head++;
		pthread_cond_broadcast(&r->cv);
	}
	while (r->done[0] + RING <= r->head || r->done[1] + RING <= r->head)
		pthread_cond_wait(&r->cv, &r->mu);
	r->ring[r->head % RING].len = 0;
	int rc = r->hrc;
	pthread_mutex_unlock(&r->mu);
	return rc;
}

/* Hand over what is left, let the helper finish and end it; returns its first error or 0. */
static int split_stop(dev_render_t *r)
{
	if (!r->started)
		return r->hrc;
	split_hand(r);
	pthread_mutex_lock(&r->mu);
	r->quit = 1;
	pthread_cond_broadcast(&r->cv);
	pthread_mutex_unlock(&r->mu);
	pthread_join(r->thr, NULL);
	pthread_join(r->thr2, NULL);
	pthread_cond_destroy(&r->cv);
	pthread_mutex_destroy(&r->mu);
	r->started = 0;
	return r->hrc;
}

/* Append a record for the helper to the block being filled. */
static int split_put(dev_render_t *r, const rec_t *h, const void *a, size_t na, const void *b,
		size_t nb, const void *c, size_t nc)
{
	size_t need = sizeof *h + na + nb + nc;
	chunk_t *f = &r->ring[r->head % RING];
	if (f->len && f->len + need > f->cap) {
		int rc = split_hand(r);
		if (rc)
			return rc;
		f = &r->ring[r->head % RING];
	}
	if (need > f->cap) {   /* (a block is made on first use; a large record gets its own) */
		size_t cap = need > CHUNK_BYTES ? need : CHUNK_BYTES;
		unsigned char *n = realloc(f->buf, cap);
		if (!n)
			return META_ENOMEM;
		f->buf = n;
		f->cap = cap;
	}
	unsigned char *w = f->buf + f->len;
	memcpy(w, h, sizeof *h);
	w += sizeof *h;
	if (na)
		memcpy(w, a, na);
	if (nb)
		memcpy(w + na, b, nb);
	if (nc)
		memcpy(w + na + nb, c, nc);
	f->len += need;
	return 0;
}

uint64_t dev_render_spool_default(void)
{
	const char *e = getenv("LOCUS_SPOOL_MAX_MB");
	char *end;
	unsigned long long mb = e && *e ? strtoull(e, &end, 10) : 0;
	if (!e || !*e || *end || mb == 0 || mb > ((uint64_t)1 << 40))
		return DEV_SPOOL_MAX_DEFAULT;
	return (uint64_t)mb << 20;
}

void dev_render_set_spool_limit(dev_render_t *r, uint64_t bytes)
{
	r->spool_max = bytes;
}

const char *dev_render_error(const dev_render_t *r)
{
	return r->err;
}

/* Record why the spool failed (errno, or the limit when err_no is 0); returns META_EIO. */
static int spool_fail(dev_render_t *r, int err_no, const char *doing)
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

/* The spool: a file created in $TMPDIR (else /tmp) and unlinked at once, so that nothing is
 * left behind whatever happens to the process. */
static int spool_open(dev_render_t *r)
{
	const char *dir = getenv("TMPDIR");
	if (!dir || !*dir || strlen(dir) > sizeof r->spool_dir - 24)
		dir = "/tmp";
	snprintf(r->spool_dir, sizeof r->spool_dir, "%s", dir);
	char path[sizeof r->spool_dir + 32];
	snprintf(path, sizeof path, "%s/locus-spool-XXXXXX", dir);
	int fd = mkstemp(path);
	if (fd < 0)
		return spool_fail(r, errno, "cannot create it");
	unlink(path);
	r->spool = fdopen(fd, "w+b");
	if (!r->spool) {
		int e = errno;
		close(fd);
		return spool_fail(r, e, "cannot open it");
	}
	return 0;
}

dev_render_t *dev_render_new(unsigned width, unsigned height, unsigned band_rows, size_t budget,
		char *err, size_t errlen)
{
	dev_render_t *r = calloc(1, sizeof *r);
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
		if (height >= SPLIT_MIN_ROWS && split_start(r) == 0) {
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
		r->spool_max = dev_render_spool_default();
		if (spool_open(r)) {
			snprintf(err, errlen, "%s", r->err);
			dev_render_free(r);
			return NULL;
		}
		/* the first two bands painted as the records arrive, when two bands fit the budget */
		size_t bytes = row * band_rows;
		if (bytes <= r->budget / 2 && (r->pix2 = malloc(bytes)) && split_start(r) == 0) {
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
	dev_render_free(r);
	return NULL;
}

void dev_render_free(dev_render_t *r)
{
	if (!r)
		return;
	split_stop(r);
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

unsigned dev_render_bands(const dev_render_t *r)
{
	return r->bands;
}

/* ---- spool writing ---- */

static int spool(dev_render_t *r, int kind, int64_t jlo, int64_t jhi, const void *a, size_t na,
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
		return split_put(r, &h, a, na, b, nb, c, nc);
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
		return spool_fail(r, 0, NULL);
	errno = 0;
	if (fwrite(&h, sizeof h, 1, r->spool) != 1 || (na && fwrite(a, 1, na, r->spool) != na) ||
			(nb && fwrite(b, 1, nb, r->spool) != nb) || (nc && fwrite(c, 1, nc, r->spool) != nc))
		return spool_fail(r, errno ? errno : EIO, "cannot write it");
	r->spooled += need;
	if (r->pre && jhi > r->pre_lo)
		return split_put(r, &h, a, na, b, nb, c, nc);
	return 0;
}

/* Serialised path: npts (PACKED set when the points are int32 pairs), nsubs (uint64), subs,
 * points. Points within 32 bits (every path of the meta-language's range but wide text) take
 * half the spool. */
#define PACKED ((uint64_t)1 << 63)

static int spool_path(dev_render_t *r, int kind, int64_t ext, const void *head, size_t nhead,
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

/* Head of a stroke record; only the ndash entries in use are spooled (STROKE_HEAD(n) bytes), so
 * that a record costs the path and a few dozen bytes, not a whole dash array. */
typedef struct {
	meta_rgb_t rgb;
	int32_t cap, join;
	int64_t width, miter_limit;
	uint64_t ndash;
	int64_t dash[2 * META_MAX_DASH];
} stroke_head_t;
#define STROKE_HEAD(n) (offsetof(stroke_head_t, dash) + (size_t)(n) * sizeof(int64_t))

typedef struct {
	meta_rgb_t rgb;
	int32_t rule;
} fill_head_t;

int dev_render_clear(dev_render_t *r, meta_rgb_t rgb)
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

int dev_render_fill(dev_render_t *r, const scan_path_t *p, int rule, meta_rgb_t rgb)
{
	if (!r->spool && !r->split)
		return scan_fill(r->main.ctx, &r->main.band, p, rule, rgb);
	fill_head_t h;
	memset(&h, 0, sizeof h);
	h.rgb = rgb;
	h.rule = rule;
	return spool_path(r, REC_FILL, 0, &h, sizeof h, p);
}

int dev_render_stroke(dev_render_t *r, const scan_path_t *p, const scan_style_t *st, meta_rgb_t rgb)
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

int dev_render_span(dev_render_t *r, int64_t x, int64_t y, int64_t n, meta_rgb_t rgb)
{
	if (!r->spool && !r->split) {
		scan_span(&r->main.band, x, y, n, rgb);
		return 0;
	}
	int64_t v[3] = { x, y, n };
	return spool(r, REC_SPAN, y, y + 1, v, sizeof v, &rgb, sizeof rgb, NULL, 0);
}

static void paint_row(const scan_band_t *b, int64_t x, int64_t y, const meta_run_t *runs, size_t n)
{
	for (size_t k = 0; k < n; k++) {
		scan_span(b, x, y, runs[k].count, runs[k].rgb);
		x += runs[k].count;
	}
}

int dev_render_row(dev_render_t *r, int64_t x, int64_t y, const meta_run_t *runs, size_t nruns)
{
	if (!r->spool && !r->split) {
		paint_row(&r->main.band, x, y, runs, nruns);
		return 0;
	}
	int64_t v[2] = { x, y };
	return spool(r, REC_ROW, y, y + 1, v, sizeof v, runs, nruns * sizeof(meta_run_t), NULL, 0);
}

/* ---- replay ---- */

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
static int replay_rec(painter_t *pt, const rec_t *hp, const unsigned char *q)
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
		paint_row(&pt->band, v[0], v[1], pt->runs, n);
	}
	return rc;
}

/* Make at least need bytes of the spool available at d->buf + d->pos (reading on at d->off).
 * Returns 0, META_ENOMEM, or META_EIO with pt->err_no set (0 when the spool ended short). */
static int rd_need(int fd, painter_t *pt, size_t need)
{
	reader_t *d = &pt->rd;
	size_t have = d->len - d->pos;
	if (have >= need)
		return 0;
	if (d->pos && have)
		memmove(d->buf, d->buf + d->pos, have);
	d->len = have;
	d->pos = 0;
	if (need > d->cap) {
		size_t cap = need > READ_BYTES ? need : READ_BYTES;
		unsigned char *n = realloc(d->buf, cap);
		if (!n)
			return META_ENOMEM;
		d->buf = n;
		d->cap = cap;
	}
	while (d->len < need) {
		ssize_t n = pread(fd, d->buf + d->len, d->cap - d->len, (off_t)d->off);
		if (n < 0 && errno == EINTR)
			continue;
		if (n <= 0) {
			pt->err_no = n < 0 ? errno : 0;
			pt->read_failed = 1;
			return META_EIO;
		}
		d->len += (size_t)n;
		d->off += (uint64_t)n;
	}
	return 0;
}

/* Replay the whole spool onto pt's band, skipping records whose rows miss it. */
static int replay(dev_render_t *r, painter_t *pt)
{
	int fd = fileno(r->spool);
	reader_t *d = &pt->rd;
	d->len = d->pos = 0;
	d->off = 0;
	for (uint64_t at = 0; at < r->spooled;) {
		rec_t h;
		int rc = rd_need(fd, pt, sizeof h);
		if (rc)
			return rc;
		memcpy(&h, d->buf + d->pos, sizeof h);
		d->pos += sizeof h;
		at += sizeof h + h.len;
		if (h.jhi <= pt->band.jlo || h.jlo >= pt->band.jhi) {
			size_t have = d->len - d->pos;
			if (h.len <= have) {
				d->pos += h.len;
			} else {
				d->off += h.len - have;
				d->len = d->pos = 0;
			}
			continue;
		}
		if ((rc = rd_need(fd, pt, h.len)) || (rc = replay_rec(pt, &h, d->buf + d->pos)))
			return rc;
		d->pos += h.len;
	}
	return 0;
}

/* Paint bands of the spooled page into pix with painter pt, from band first on, and hand each
 * to the band function in its turn. With two painters (two) each takes the next band nobody
 * has taken when it has handed its own on (whoever is less busy paints more of the page), and
 * waits for the band before its own to be handed on first, so bands go out in order; the
 * first failure in band order is kept in r->brc and stops both. One painter takes them all. */
static int band_loop(dev_render_t *r, painter_t *pt, uint8_t *pix, unsigned first, int two)
{
	size_t row = (size_t)r->width * 3;
	for (unsigned k = first; k < r->bands;) {
		unsigned top = k * r->band_rows;
		unsigned n = r->height - top < r->band_rows ? r->height - top : r->band_rows;
		uint8_t *buf = k >= r->pre ? pix : k == 0 ? r->pix : r->pix2;
		int rc = 0;
		if (k >= r->pre) {   /* (the first bands were painted while the page was spooled) */
			pt->band.pix = pix;
			pt->band.jhi = (int)(r->height - top);
			pt->band.jlo = pt->band.jhi - (int)n;
			memset(pix, 0xff, row * n);
			rc = replay(r, pt);
		}
		if (two) {
			pthread_mutex_lock(&r->mu);
			while (!r->bstop && r->next_band != k)
				pthread_cond_wait(&r->cv, &r->mu);
			int stop = r->bstop;
			pthread_mutex_unlock(&r->mu);
			if (stop)
				return 0;
		}
		if (!rc) {
			dev_band_t out = { buf, row, r->width, top, n, r->height };
			rc = r->bfn(r->buser, &out);
		}
		if (!two) {
			if (rc)
				return rc;
			k++;
			continue;
		}
		pthread_mutex_lock(&r->mu);
		if (rc) {
			r->brc = rc;
			r->bread = pt->read_failed;
			r->bstop = 1;
		} else {
			r->next_band = k + 1;
			k = r->next_paint++;
		}
		pthread_cond_broadcast(&r->cv);
		pthread_mutex_unlock(&r->mu);
		if (rc)
			return rc;
	}
	return 0;
}

/* The helper of a two-painter multi-band page: band 1, then whichever comes next. */
static void *band_helper(void *arg)
{
	dev_render_t *r = arg;
	band_loop(r, &r->help, r->pix2, 1, 1);
	return NULL;
}

/* Start the helper for a multi-band page when a second band buffer fits the budget; nonzero
 * leaves the page to the caller's thread. */
static int bands_start(dev_render_t *r)
{
	size_t bytes = (size_t)r->width * 3 * r->band_rows;
	if (r->bands < 2 || bytes > r->budget / 2)
		return -1;
	if (!r->help.ctx && !(r->help.ctx = scan_ctx_new()))
		return -1;
	if (!r->pix2 && !(r->pix2 = malloc(bytes)))
		return -1;
	r->help.band = r->main.band;
	r->next_band = 0;
	r->next_paint = 2;
	r->bstop = r->brc = r->bread = 0;
	if (pthread_mutex_init(&r->mu, NULL))
		return -1;
	if (pthread_cond_init(&r->cv, NULL)) {
		pthread_mutex_destroy(&r->mu);
		return -1;
	}
	if (pthread_create(&r->thr, NULL, band_helper, r)) {
		pthread_cond_destroy(&r->cv);
		pthread_mutex_destroy(&r->mu);
		return -1;
	}
	return 0;
}

int dev_render_finish(dev_render_t *r, dev_band_fn fn, void *user)
{
	size_t row = (size_t)r->width * 3;
	dev_band_t out = { r->pix, row, r->width, 0, 0, r->height };
	if (!r->spool) {
		int rc = split_stop(r);
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
		int rc = split_stop(r);
		if (rc)
			return rc;
	}
	errno = 0;
	if (fflush(r->spool))
		return spool_fail(r, errno ? errno : EIO, "cannot write it");
	r->bfn = fn;
	r->buser = user;
	r->main.read_failed = r->help.read_failed = 0;
	int two = bands_start(r) == 0;
	int rc = band_loop(r, &r->main, r->pix, 0, two);
	int bread = r->main.read_failed;
	const painter_t *failed = &r->main;
	if (two) {
		pthread_join(r->thr, NULL);
		pthread_cond_destroy(&r->cv);
		pthread_mutex_destroy(&r->mu);
		rc = r->brc;
		bread = r->bread;
		failed = r->help.read_failed && !r->main.read_failed ? &r->help : &r->main;
	}
	if (rc == META_EIO && bread)
		return spool_fail(r, failed->err_no ? failed->err_no : EIO, "cannot read it back");
	return rc;
}
