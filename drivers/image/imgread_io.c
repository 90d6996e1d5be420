/* imgread_io.c: the image readers' input buffer (fill, take, skip, offsets) and their messages. */
#include <stdio.h>
#include <string.h>
#include "image/imgread_int.h"

uint64_t img_rd_offset(const img_reader_t *r)
{
	return r->base + r->pos;
}

int img_rd_bad(img_reader_t *r, uint64_t off, const char *what)
{
	snprintf(r->err, sizeof r->err, "%s: byte %llu: %s", r->name, (unsigned long long)off, what);
	return -65;
}

int img_rd_fill(img_reader_t *r)
{
	if (r->pos < r->len)
		return 1;
	if (r->eof || r->ioerr)
		return r->ioerr ? -74 : 0;
	r->base += r->len;
	r->pos = r->len = 0;
	long n = r->fn(r->user, r->buf, r->cap);
	if (n < 0) {
		r->ioerr = 1;
		snprintf(r->err, sizeof r->err, "%s: read error at byte %llu", r->name,
			(unsigned long long)r->base);
		return -74;
	}
	if (n == 0) {
		r->eof = 1;
		return 0;
	}
	r->len = (size_t)n;
	return 1;
}

long img_rd_take(img_reader_t *r, void *dst, size_t n)
{
	size_t got = 0;
	while (got < n) {
		int rc = img_rd_fill(r);
		if (rc <= 0)
			return rc < 0 ? rc : (long)got;
		size_t k = r->len - r->pos < n - got ? r->len - r->pos : n - got;
		memcpy((unsigned char *)dst + got, r->buf + r->pos, k);
		r->pos += k;
		got += k;
	}
	return (long)got;
}

int img_rd_skip(img_reader_t *r, uint64_t n, const char *what)
{
	while (n) {
		int rc = img_rd_fill(r);
		if (rc <= 0)
			return rc < 0 ? rc : img_rd_bad(r, img_rd_offset(r), what);
		size_t k = r->len - r->pos < n ? r->len - r->pos : (size_t)n;
		r->pos += k;
		n -= k;
	}
	return 0;
}

int img_rd_nomem(img_reader_t *r)
{
	snprintf(r->err, sizeof r->err, "%s: out of memory", r->name);
	return -70;
}
