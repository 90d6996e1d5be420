/* read_buf.c: the reader's input buffer, its positioned errors and its run array, used by
 * reader.c and by both decoders (read_text.c, read_binary.c); it calls none of them. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "meta_int.h"

long meta_rd_fill(meta_reader_t *r)
{
	long k;
	if (r->eof || r->mem)
		return 0;
	if (r->pos) {
		memmove(r->buf, r->buf + r->pos, r->end - r->pos);
		r->base += r->pos;
		r->end -= r->pos;
		r->pos = 0;
	}
	if (r->end == r->cap) {
		size_t ncap = r->cap * 2;
		unsigned char *nb;
		if (ncap > 2 * (size_t)META_MAX_LINE + META_READ_CHUNK)
			return 0; /* callers bound what they ask for; never reached */
		nb = realloc(r->buf, ncap);
		if (!nb)
			return meta_rd_fail(r, META_ENOMEM, r->binary ? r->base + r->end : 1, "out of memory");
		r->buf = nb;
		r->cap = ncap;
	}
	k = r->fn(r->user, r->buf + r->end, r->cap - r->end);
	if (k < 0)
		return meta_rd_fail(r, META_EIO, r->binary ? r->base + r->end : 1, "read error: %s",
		                    errno ? strerror(errno) : "callback failed");
	if (k == 0)
		r->eof = 1;
	r->end += (size_t)k;
	return k;
}

int meta_rd_fail(meta_reader_t *r, int code, uint64_t where, const char *fmt, ...)
{
	char msg[480];
	va_list ap;
	va_start(ap, fmt);
	if (vsnprintf(msg, sizeof msg, fmt, ap) < 0)
		msg[0] = 0;
	va_end(ap);
	if (r->binary)
		meta_fmt(r->err, sizeof r->err, "%s: byte %llu: %s", r->name, (unsigned long long)where, msg);
	else
		meta_fmt(r->err, sizeof r->err, "%s:%llu:%llu: %s", r->name, (unsigned long long)r->line,
		         (unsigned long long)where, msg);
	r->state = code;
	return code;
}

int meta_rd_runs(meta_reader_t *r, size_t n, uint64_t where)
{
	size_t ncap;
	meta_run_t *nr;
	if (n <= r->runs_cap)
		return 0;
	ncap = r->runs_cap ? r->runs_cap : 64;
	while (ncap < n)
		ncap *= 2;
	nr = realloc(r->runs, ncap * sizeof *nr);
	if (!nr)
		return meta_rd_fail(r, META_ENOMEM, where, "out of memory");
	r->runs = nr;
	r->runs_cap = ncap;
	return 0;
}
