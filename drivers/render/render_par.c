/* render_par.c: the renderer's painting threads: split pages queued to two helpers, banded pages
 * replayed from the spool by two painters that hand their bands on in order. */
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "render/render_int.h"

/* A split helper: replay each block handed over onto its band until told to quit. */
static void *helper(void *arg)
{
	const helper_arg_t *ha = arg;
	render_t *r = ha->r;
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
			rc = render_replay_rec(ha->pt, &h, w->buf + at + sizeof h);
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
int render_split_start(render_t *r)
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
static int split_hand(render_t *r)
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
int render_split_stop(render_t *r)
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
int render_split_put(render_t *r, const rec_t *h, const void *a, size_t na, const void *b,
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
static int replay(render_t *r, painter_t *pt)
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
		if ((rc = rd_need(fd, pt, h.len)) || (rc = render_replay_rec(pt, &h, d->buf + d->pos)))
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
static int band_loop(render_t *r, painter_t *pt, uint8_t *pix, unsigned first, int two)
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
			render_band_t out = { buf, row, r->width, top, n, r->height };
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
	render_t *r = arg;
	band_loop(r, &r->help, r->pix2, 1, 1);
	return NULL;
}

/* Start the helper for a multi-band page when a second band buffer fits the budget; nonzero
 * leaves the page to the caller's thread. */
static int bands_start(render_t *r)
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

int render_par_bands(render_t *r, render_band_fn fn, void *user)
{
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
		return render_spool_fail(r, failed->err_no ? failed->err_no : EIO, "cannot read it back");
	return rc;
}
