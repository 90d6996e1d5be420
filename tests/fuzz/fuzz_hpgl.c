/* fuzz_hpgl.c: libFuzzer harness of the HP-GL reader and `locus-meta import`: a read is the same twice, an error is one line naming the byte, and an import is a meta file the meta reader accepts. */
#include "fuzz.h"
#include "hpgl/read/hpgl_read.h"
#include "import/meta_import.h"

#ifndef FUZZ_ENTRY
#define FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

/* 0 when the text meta file m reads to its end, else -1 with the message in err. */
static int meta_valid(const fuzz_buf_t *m, char *err, size_t errlen)
{
	meta_reader_t *r = meta_reader_mem(m->p, m->n, "out");
	if (!r)
		return 0;   /* out of memory: nothing to judge */
	meta_cmd_t c;
	int rc;
	while ((rc = meta_read(r, &c)) > 0)
		;
	snprintf(err, errlen, "%s", meta_reader_error(r));
	meta_reader_free(r);
	return rc < 0 ? -1 : 0;
}

int FUZZ_ENTRY(const uint8_t *data, size_t size);
int FUZZ_ENTRY(const uint8_t *data, size_t size)
{
	hpgl_doc_t a, b;
	char e1[400], e2[400];
	e1[0] = e2[0] = 0;
	int r1 = hpgl_read_mem(data, size, "in", &a, e1, sizeof e1);
	int r2 = hpgl_read_mem(data, size, "in", &b, e2, sizeof e2);
	FUZZ_ASSERT(r1 == r2, "two reads: %d then %d", r1, r2);
	FUZZ_ASSERT(a.nstrokes == b.nstrokes && a.npts == b.npts && a.nlabels == b.nlabels, "two reads, two documents");
	for (size_t k = 0; k < a.nstrokes; k++) {
		const hpgl_rstroke_t *s = &a.strokes[k];
		FUZZ_ASSERT(s->n >= 2 && s->start + s->n <= a.npts, "stroke %zu: points %zu+%zu of %zu", k, s->start, s->n, a.npts);
		FUZZ_ASSERT(s->offset < size || size == 0, "stroke %zu at byte %zu of %zu", k, s->offset, size);
	}
	if (r1) {
		FUZZ_ASSERT(fuzz_one_line(e1) && !strncmp(e1, "in: byte ", 9), "error '%s'", e1);
		FUZZ_ASSERT(!strcmp(e1, e2), "two messages: '%s' / '%s'", e1, e2);
	}
	hpgl_doc_free(&a);
	hpgl_doc_free(&b);
	/* the import: 0 with a valid meta file, or -65 naming the byte */
	fuzz_buf_t m = { 0 };
	meta_writer_t *w = meta_writer_new(fuzz_buf_write, &m, META_ENC_TEXT);
	if (!w)
		return 0;
	char err[700] = "";
	int rc = mimp_hpgl(data, size, "in", 1.0, w, err, sizeof err);
	int c = meta_writer_close(w);
	FUZZ_ASSERT(rc == 0 || rc == -65 || rc == -70, "import answered %d (%s)", rc, err);
	if (rc == -65)
		FUZZ_ASSERT(r1 && fuzz_one_line(err) && !strncmp(err, "in: byte ", 9), "import refused what the reader read: '%s'", err);
	if (rc == 0) {
		FUZZ_ASSERT(!r1, "import of a bad file succeeded");
		FUZZ_ASSERT(c == 0, "the writer refused the import's end");
		FUZZ_ASSERT(meta_valid(&m, err, sizeof err) == 0, "import wrote a bad meta file: %s", err);
	}
	free(m.p);
	return 0;
}
