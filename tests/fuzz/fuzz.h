/* fuzz.h: what the libFuzzer harnesses share: a growing buffer, a fatal assertion, the pending-fix guards. */
#ifndef LOCUS_FUZZ_H
#define LOCUS_FUZZ_H
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "locus_meta.h"

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

/* Estimated work of replaying the input (chords, dash pieces, glyph strokes), or < 0 when it
 * does not read or has a page of more than max_pixels; *pages (when not NULL): its pages. */
static inline double fuzz_work_dash(const uint8_t *data, size_t size, uint64_t max_pixels, unsigned *pages,
		int dash)
{
	meta_reader_t *r = meta_reader_mem(data, size, "in");
	meta_cmd_t c;
	double w = 0, period = 0, len = 0, x = 0, y = 0;
	int rc, stroke = 0;
	if (pages)
		*pages = 0;
	if (!r)
		return -1;
	while ((rc = meta_read(r, &c)) > 0) {
		switch (c.op) {
		case META_PAGE:
			if (pages)
				++*pages;
			if ((uint64_t)c.u[0] * c.u[1] > max_pixels)
				w = -1e30;
			period = 0;
			break;
		case META_DASH:
			period = 0;
			for (size_t i = 0; i < c.nlist; i++)
				period += c.list[i] / 1000.0;
			break;
		case META_STROKE: stroke = 1, len = 0; break;
		case META_FILL: stroke = 0, len = 0; break;
		case META_MOVE: x = c.f[0] / 1000.0, y = c.f[1] / 1000.0; w += 1; break;
		case META_DRAW:
			len += hypot(c.f[0] / 1000.0 - x, c.f[1] / 1000.0 - y) + 1;
			x = c.f[0] / 1000.0, y = c.f[1] / 1000.0;
			w += 1;
			break;
		case META_ARC: case META_CIRCLE: {
			double rr = c.f[2] / 1000.0;
			w += 9 * sqrt(rr) + 8;
			len += 2 * M_PI * rr;
			break;
		}
		case META_TEXT:   /* glyphs are stroked with the dash in force: about 4 sizes of path each */
			w += 20.0 * c.len;
			if (dash && period > 0)
				w += 4.0 * c.len * (c.f[2] / 1000.0) / period * 2;
			break;
		case META_END:
			/* (dash: count the pieces of the whole length, for the harnesses of devices that
			 * make them all; fuzz_vecdash asserts the vector devices do not) */
			if (dash && stroke && period > 0)
				w += len / period * 2;
			break;
		default: break;
		}
	}
	meta_reader_free(r);
	(void)stroke, (void)period;   /* read only by the guards */
	return w;
}

static inline double fuzz_work(const uint8_t *data, size_t size, uint64_t max_pixels, unsigned *pages)
{
	return fuzz_work_dash(data, size, max_pixels, pages, FUZZ_GUARDS);
}

#endif
