/* fuzz.h: what the libFuzzer harnesses share: a growing buffer, a fatal assertion, the pending-fix guards. */
#ifndef LOCUS_FUZZ_H
#define LOCUS_FUZZ_H
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* FUZZ_GUARDS=1 (the default) makes a harness skip inputs that reach a finding of issue 6
 * that is being fixed in another branch (each guard says which); build with
 * -DFUZZ_GUARDS=0 to fuzz without them once the fixes are merged. */
#ifndef FUZZ_GUARDS
#define FUZZ_GUARDS 1
#endif

/* An assertion beyond "no crash": a message on stderr, then abort() (libFuzzer keeps the input). */
#define FUZZ_ASSERT(cond, ...) do { \
	if (!(cond)) { \
		fprintf(stderr, "%s:%d: assertion failed: %s: ", __FILE__, __LINE__, #cond); \
		fprintf(stderr, __VA_ARGS__); fputc('\n', stderr); abort(); \
	} \
} while (0)

/* A growing memory buffer that is a meta_write_fn. */
typedef struct {
	char *p;
	size_t n, cap;
} fuzz_buf_t;

static inline int fuzz_buf_write(void *user, const void *buf, size_t n)
{
	fuzz_buf_t *m = user;
	if (m->n + n > m->cap) {
		size_t cap = (m->n + n) * 2 + 64;
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

/* A one-line message: no newline, not empty, of sane length. */
static inline int fuzz_one_line(const char *e)
{
	return e && *e && !strchr(e, '\n') && strlen(e) < 1024;
}

#endif
