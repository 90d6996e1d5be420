/* render_int.h: the renderer's internals shared by render.c, render_par.c and replay.c (not public). */
#ifndef LOCUS_RENDER_INT_H
#define LOCUS_RENDER_INT_H

#include <pthread.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "render/render.h"

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

struct render {
	unsigned width, height, band_rows, bands;
	uint8_t *pix;
	painter_t main;         /* its band: the whole page, a spooled band, or the split's top */
	FILE *spool;            /* NULL: single band, painted directly */
	uint64_t spooled, spool_max; /* bytes in the spool; its limit */
	char spool_dir[200];    /* where the (unlinked) spool file lives, for messages */
	char err[320];          /* the last failure (render_error) */
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
	render_band_fn bfn;
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
		struct render *r;
		painter_t *pt;
		int idx;
	} harg[2];
};

/* What a split helper is told: its renderer and its painter. */
typedef struct helper_arg helper_arg_t;

/* Serialised path: npts (PACKED set when the points are int32 pairs), nsubs (uint64), subs,
 * points. Points within 32 bits (every path of the meta-language's range but wide text) take
 * half the spool. */
#define PACKED ((uint64_t)1 << 63)

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

/* Paint the runs of one image row at page row y from x into the band. */
static inline void render_paint_row(const scan_band_t *b, int64_t x, int64_t y, const meta_run_t *runs,
		size_t n)
{
	for (size_t k = 0; k < n; k++) {
		scan_span(b, x, y, runs[k].count, runs[k].rgb);
		x += runs[k].count;
	}
}

/* Paint one spool record (header h, payload q) onto the painter's band (replay.c). Returns 0
 * or <0. */
int render_replay_rec(painter_t *pt, const rec_t *h, const unsigned char *q);
/* Record why the spool failed (errno, or the limit when err_no is 0) in r->err; returns
 * META_EIO (replay.c). */
int render_spool_fail(render_t *r, int err_no, const char *doing);
/* Start the two split helpers with their contexts; nonzero leaves the page to one thread
 * (the caller sets their bands before the first record). */
int render_split_start(render_t *r);
/* Hand over what is queued, let the helpers finish and end them; their first error or 0. */
int render_split_stop(render_t *r);
/* Queue a record (header and up to three parts of its payload) for the split helpers. Returns
 * 0 or <0 (a helper's error, or META_ENOMEM). */
int render_split_put(render_t *r, const rec_t *h, const void *a, size_t na, const void *b,
		size_t nb, const void *c, size_t nc);
/* Replay the flushed spool of a multi-band page band by band (by two painters when two band
 * buffers fit the budget) and hand each band to fn in order. Returns the first error in band
 * order, or 0. */
int render_par_bands(render_t *r, render_band_fn fn, void *user);

#endif
