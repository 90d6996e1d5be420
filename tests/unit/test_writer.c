/* test_writer.c: the device writer (device/writer.h): bytes arrive in order whatever the write
 * sizes, pos counts every byte, drain and flush pass on exactly what is buffered, errors are
 * sticky codes, a filter sees every byte and a sink replaces the transport; the number helpers. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "device/writer.h"
#include "locus_meta.h"
#include "unit.h"

/* A sink that keeps what it is given, counts its calls, and fails from byte `fail_at` on. */
typedef struct {
	unsigned char *b;
	size_t n, cap, calls, fail_at;
} sink_t;

static int keep(void *user, const void *p, size_t n)
{
	sink_t *s = user;
	s->calls++;
	if (s->n + n > s->fail_at)
		return -1;
	if (s->n + n > s->cap) {
		size_t cap = (s->n + n) * 2;
		unsigned char *b = realloc(s->b, cap);
		if (!b)
			return -1;
		s->b = b;
		s->cap = cap;
	}
	memcpy(s->b + s->n, p, n);
	s->n += n;
	return 0;
}

static dev_writer_t *new_writer(sink_t *s)
{
	dev_writer_t *w = malloc(sizeof *w);
	if (!w)
		exit(2);
	memset(s, 0, sizeof *s);
	s->fail_at = SIZE_MAX;
	dev_w_init(w, NULL);
	dev_w_set_sink(w, keep, s);
	return w;
}

/* A filter that writes every byte twice. */
static int twice(dev_writer_t *w, const void *p, size_t n)
{
	const unsigned char *c = p;
	for (size_t k = 0; k < n; k++)
		if (dev_w_raw(w, c + k, 1) || dev_w_raw(w, c + k, 1))
			return w->err;
	return 0;
}

int main(void)
{
	sink_t s;
	dev_writer_t *w = new_writer(&s);

	/* writes of 1, 3, 9 ... 177147 bytes (more than the buffer), one pattern: the sink sees it in order */
	size_t total = 0;
	unsigned char *pat = malloc(5 * DEV_W_BUF);
	for (size_t k = 0; k < 5 * DEV_W_BUF; k++)
		pat[k] = (unsigned char)(k * 7 + k / 251);
	for (size_t n = 0, at = 0; at + n <= 5 * DEV_W_BUF; at += n, n = n ? n * 3 : 1) {
		dev_w_write(w, pat + at, n);
		total = at + n;
	}
	dev_w_write(w, pat + total, 5);   /* the last write passed straight on; this one waits */
	total += 5;
	CHECK(w->pos == total, "pos counts every byte (%llu of %zu)", (unsigned long long)w->pos, total);
	CHECK(s.n < total, "bytes wait in the buffer until drained (%zu passed on)", s.n);
	CHECK(dev_w_drain(w) == 0 && s.n == total && !memcmp(s.b, pat, total), "drain passes on all of it, in order");
	size_t calls = s.calls;
	CHECK(dev_w_drain(w) == 0 && s.calls == calls, "an empty buffer drains nothing");
	CHECK(dev_w_flush(w) == 0, "flush over a sink does not touch the (absent) transport");

	/* the formatting calls */
	s.n = 0;
	dev_w_set_transport(w, NULL);
	CHECK(w->pos == 0, "set_transport restarts pos");
	dev_w_puts(w, "a");
	dev_w_int(w, -9876543210LL);
	dev_w_puts(w, " ");
	dev_w_fix(w, 12500);
	dev_w_puts(w, " ");
	dev_w_fix(w, -1);
	dev_w_puts(w, " ");
	dev_w_real(w, -0.00001, 4);
	dev_w_puts(w, " ");
	dev_w_real(w, 0.07499941, 8);
	dev_w_printf(w, " %s=%d", "x", 42);
	dev_w_drain(w);
	const char *want = "a-9876543210 12.5 -0.001 0 0.07499941 x=42";
	CHECK(s.n == strlen(want) && !memcmp(s.b, want, s.n), "numbers: '%.*s'", (int)s.n, (const char *)s.b);

	/* a filter sees every byte; pos counts its output */
	s.n = 0;
	dev_w_set_transport(w, NULL);
	dev_w_set_filter(w, twice, NULL);
	dev_w_puts(w, "ab");
	dev_w_set_filter(w, NULL, NULL);
	dev_w_puts(w, "c");
	dev_w_drain(w);
	CHECK(s.n == 5 && !memcmp(s.b, "aabbc", 5) && w->pos == 5, "filter output, then plain bytes");

	/* errors are sticky codes */
	char big[2000];
	memset(big, 'x', sizeof big - 1);
	big[sizeof big - 1] = 0;
	s.n = 0;
	dev_w_set_transport(w, NULL);
	CHECK(dev_w_printf(w, "%s", big) == META_EIO, "printf longer than 1023 bytes: META_EIO");
	CHECK(dev_w_puts(w, "z") == META_EIO && w->pos == 0, "the error stays and nothing more is taken");
	free(w);
	free(s.b);

	w = new_writer(&s);
	s.fail_at = 10;
	dev_w_write(w, pat, 20);
	CHECK(dev_w_drain(w) == META_EIO, "a refused drain is META_EIO");
	CHECK(dev_w_write(w, pat, 1) == META_EIO && dev_w_flush(w) == META_EIO && s.n == 0,
		"and stays, writing nothing");
	free(w);

	/* no transport and no sink: the first drain fails */
	w = malloc(sizeof *w);
	dev_w_init(w, NULL);
	dev_w_write(w, "q", 1);
	CHECK(dev_w_flush(w) == META_EIO, "no output: META_EIO at the drain");
	free(w);

	/* dev_fmt_fix */
	char b[DEV_FMT_SIZE];
	CHECK_STR(dev_fmt_fix(b, -1500, 3, 3), "-1.5", "-1.5");
	CHECK_STR(dev_fmt_fix(b, -4, 3, 2), "0", "rounds to zero: 0, not -0");
	free(pat);
	free(s.b);
	return UNIT_DONE();
}
