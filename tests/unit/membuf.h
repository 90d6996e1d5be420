/* membuf.h: a growing memory buffer that a meta writer can write into, for tests. */
#ifndef LOCUS_MEMBUF_H
#define LOCUS_MEMBUF_H
#include <stdlib.h>
#include <string.h>

typedef struct {
	char *p;
	size_t n, cap;
} membuf_t;

/* A meta_write_fn: appends n bytes; -1 when out of memory. */
static int membuf_write(void *user, const void *buf, size_t n)
{
	membuf_t *m = user;
	if (m->n + n > m->cap) {
		size_t cap = (m->n + n) * 2;
		char *b = realloc(m->p, cap);
		if (!b)
			return -1;
		m->p = b;
		m->cap = cap;
	}
	memcpy(m->p + m->n, buf, n);
	m->n += n;
	return 0;
}
#endif
