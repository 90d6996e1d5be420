/* golden.h: an in-memory meta sink and the record-or-compare step of the byte-for-byte golden tests. */
#ifndef LOCUS_GOLDEN_H
#define LOCUS_GOLDEN_H
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "unit.h"

/* A growing buffer that a meta writer writes into (golden_write is its meta_write_fn). */
typedef struct {
	char *buf;
	size_t n, cap;
} golden_buf_t;

static int golden_write(void *user, const void *p, size_t n)
{
	golden_buf_t *m = user;
	if (m->n + n > m->cap) {
		size_t cap = (m->n + n) * 2;
		char *b = realloc(m->buf, cap);
		if (!b)
			return -1;
		m->buf = b;
		m->cap = cap;
	}
	memcpy(m->buf + m->n, p, n);
	m->n += n;
	return 0;
}

/* With LOCUS_RECORD set, (re)write the golden file from the buffer (then look at it before
 * committing); otherwise check that the buffer equals the golden byte for byte. Frees the buffer. */
static void golden_check(const char *path, golden_buf_t *m)
{
	if (getenv("LOCUS_RECORD")) {
		FILE *f = fopen(path, "wb");
		CHECK(f && fwrite(m->buf, 1, m->n, f) == m->n && fclose(f) == 0, "recorded %s (%zu bytes)", path, m->n);
	} else {
		FILE *f = fopen(path, "rb");
		char *want = malloc(m->n + 2);
		size_t n = f && want ? fread(want, 1, m->n + 1, f) : 0;
		if (f)
			fclose(f);
		CHECK(f != NULL, "golden %s is there", path);
		CHECK(n == m->n && memcmp(want, m->buf, n) == 0, "output equals %s (%zu bytes, golden %zu)", path, m->n, n);
		free(want);
	}
	free(m->buf);
	m->buf = NULL;
}
#endif
