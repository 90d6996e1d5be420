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

/* An importer under test: buf/n to meta statements through w; its status (0, -65 with a
 * one-line message in err, ...). */
typedef int (*fuzz_import_fn)(const uint8_t *buf, size_t n, void *user, meta_writer_t *w,
		char *err, size_t errlen);

/* The importers' common check: imp run twice on buf gives the same status and the same meta
 * bytes, or the same one-line message starting with prefix (-65); a success reads back as a
 * valid meta file; with only70 any other status must be -70 (out of memory). */
static inline void fuzz_import_twice(fuzz_import_fn imp, void *user, const uint8_t *buf, size_t n,
		const char *prefix, int only70)
{
	fuzz_buf_t m[2] = { { 0 }, { 0 } };
	char e[2][700];
	int r[2];
	for (int k = 0; k < 2; k++) {
		meta_writer_t *w = meta_writer_new(fuzz_buf_write, &m[k], META_ENC_TEXT);
		e[k][0] = 0;
		r[k] = -70;
		if (w) {
			r[k] = imp(buf, n, user, w, e[k], sizeof e[k]);
			if (meta_writer_close(w) < 0 && r[k] == 0)
				r[k] = -100;
		}
	}
	FUZZ_ASSERT(r[0] == r[1], "two imports: %d then %d", r[0], r[1]);
	FUZZ_ASSERT(r[0] != -100, "the writer refused the end of a successful import");
	if (r[0] == 0) {
		FUZZ_ASSERT(m[0].n == m[1].n && !memcmp(m[0].p, m[1].p, m[0].n), "two imports, two meta files");
		meta_reader_t *rd = meta_reader_mem(m[0].p, m[0].n, "out");
		if (rd) {
			meta_cmd_t c;
			int rc;
			while ((rc = meta_read(rd, &c)) > 0)
				;
			FUZZ_ASSERT(rc == 0, "import wrote a bad meta file: %s", meta_reader_error(rd));
			meta_reader_free(rd);
		}
	} else if (r[0] == -65) {
		FUZZ_ASSERT(fuzz_one_line(e[0]) && !strncmp(e[0], prefix, strlen(prefix)), "error '%s'", e[0]);
		FUZZ_ASSERT(!strcmp(e[0], e[1]), "two messages: '%s' / '%s'", e[0], e[1]);
	} else if (only70) {
		FUZZ_ASSERT(r[0] == -70, "import answered %d (%s)", r[0], e[0]);
	}
	free(m[0].p);
	free(m[1].p);
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
