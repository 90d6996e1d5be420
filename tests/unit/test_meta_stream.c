/* test_meta_stream.c: the streaming reader over a callback that returns a few bytes at a time, and long lines across refills. */
#include <stdlib.h>
#include <string.h>
#include "membuf.h"
#include "unit.h"
#include "locus_meta.h"

typedef struct {
	const char *p;
	size_t n, pos;
	unsigned step; /* bytes per call cycle 1..step */
	unsigned k;
} src_t;

static long dribble(void *user, void *buf, size_t n)
{
	src_t *s = user;
	size_t k = 1 + (s->k++ % s->step);
	if (k > n)
		k = n;
	if (k > s->n - s->pos)
		k = s->n - s->pos;
	memcpy(buf, s->p + s->pos, k);
	s->pos += k;
	return (long)k;
}

static long failing(void *user, void *buf, size_t n)
{
	(void)user, (void)buf, (void)n;
	return -1;
}

/* Re-encode everything r reads as text; returns the statement count or <0. */
static long recode(meta_reader_t *r, membuf_t *out)
{
	meta_writer_t *w = meta_writer_new(membuf_write, out, META_ENC_TEXT);
	meta_cmd_t c;
	long n = 0;
	int rc;
	while ((rc = meta_read(r, &c)) > 0) {
		if (meta_write(w, &c) < 0)
			rc = -100;
		n++;
	}
	if (meta_writer_close(w) < 0 && rc == 0)
		rc = -101;
	return rc < 0 ? rc : n;
}

/* A page with a maximal-width image whose row lines are ~330 KB (beyond one read chunk). */
static char *big_text(size_t *len)
{
	size_t cap = 2 * 1024 * 1024, n = 0;
	char *p = malloc(cap);
	int row, i;
	n += (size_t)sprintf(p + n, "LOCUS-META 1\npage 32768 2\nimage 0 0 32768 2\n");
	for (row = 0; row < 2; row++) {
		n += (size_t)sprintf(p + n, "row");
		for (i = 0; i < 32768; i++)
			n += (size_t)sprintf(p + n, " 1 #%06x", (unsigned)(i * 2654435761u) & 0xffffff);
		p[n++] = '\n';
	}
	n += (size_t)sprintf(p + n, "stroke\nmove 1.5 2\ndraw -3 4.25\nend\nend-page\n");
	*len = n;
	return p;
}

static void test_dribble(const char *what, const char *data, size_t len, int binary)
{
	unsigned steps[] = { 1, 3, 7, 64 };
	membuf_t ref = { 0 };
	meta_reader_t *r = meta_reader_mem(data, len, "mem");
	long nref = recode(r, &ref), n;
	size_t i;
	CHECK(nref > 0, "%s: memory reader reads it (%ld statements: %s)", what, nref, meta_reader_error(r));
	CHECK(meta_reader_is_binary(r) == binary, "%s: encoding detected", what);
	meta_reader_free(r);
	for (i = 0; i < sizeof steps / sizeof *steps; i++) {
		src_t s = { data, len, 0, steps[i], 0 };
		membuf_t out = { 0 };
		r = meta_reader_new(dribble, &s, "cb");
		n = recode(r, &out);
		CHECK(n == nref && out.n == ref.n && memcmp(out.p, ref.p, ref.n) == 0,
		      "%s: same statements when the callback gives 1..%u bytes a call (%ld)", what, steps[i], n);
		meta_reader_free(r);
		free(out.p);
	}
	free(ref.p);
}

int main(void)
{
	size_t len;
	char *text = big_text(&len);
	membuf_t bin = { 0 };
	meta_reader_t *r;
	meta_writer_t *w;
	meta_cmd_t c;
	int rc;

	test_dribble("text with 330 KB lines", text, len, 0);

	r = meta_reader_mem(text, len, "mem");
	w = meta_writer_new(membuf_write, &bin, META_ENC_BINARY);
	while ((rc = meta_read(r, &c)) > 0)
		meta_write(w, &c);
	CHECK(rc == 0 && meta_writer_close(w) == 0, "binary copy written");
	meta_reader_free(r);
	test_dribble("binary with 32768-run rows", bin.p, bin.n, 1);

	/* truncations of the binary at every length near the end are errors, never crashes */
	{
		size_t cut, errors = 0, tries = 0;
		for (cut = bin.n - 40; cut < bin.n; cut++, tries++) {
			r = meta_reader_mem(bin.p, cut, "cut");
			while ((rc = meta_read(r, &c)) > 0)
				;
			errors += rc < 0 && strncmp(meta_reader_error(r), "cut: byte ", 10) == 0;
			meta_reader_free(r);
		}
		CHECK(errors == tries, "every truncated binary is an error with a byte offset (%zu of %zu)", errors, tries);
	}
	free(bin.p);
	free(text);

	r = meta_reader_new(failing, NULL, "bad");
	CHECK(meta_read(r, &c) == META_EIO, "a failing callback gives META_EIO");
	CHECK(strstr(meta_reader_error(r), "read error") != NULL, "read error message: %s", meta_reader_error(r));
	meta_reader_free(r);

	r = meta_reader_open("/nonexistent/x.meta", NULL, 0);
	CHECK(r == NULL, "open of a missing file fails");
	{
		char err[200];
		r = meta_reader_open("/nonexistent/x.meta", err, sizeof err);
		CHECK(r == NULL && strstr(err, "/nonexistent/x.meta: cannot open") == err, "open error: %s", err);
	}
	return UNIT_DONE();
}
