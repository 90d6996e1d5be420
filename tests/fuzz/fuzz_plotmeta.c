/* fuzz_plotmeta.c: libFuzzer harness of the plotutils metafile reader (portable and binary): the same statements twice, an error is one line naming the byte, and a success is a meta file the meta reader accepts. */
#include "fuzz.h"
#include "import/plotmeta.h"

#ifndef FUZZ_ENTRY
#define FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

/* Import buf into m; the status, the message in err. */
static int import(const uint8_t *buf, size_t n, fuzz_buf_t *m, char *err, size_t errlen)
{
	meta_writer_t *w = meta_writer_new(fuzz_buf_write, m, META_ENC_TEXT);
	if (!w)
		return -70;
	err[0] = 0;
	int rc = plotmeta_import(buf, n, "in", w, err, errlen);
	if (meta_writer_close(w) < 0 && rc == 0)
		rc = -100;
	return rc;
}

int FUZZ_ENTRY(const uint8_t *data, size_t size);
int FUZZ_ENTRY(const uint8_t *data, size_t size)
{
	/* the harness feeds both forms: the first byte picks the magic put before the rest */
	/* (a real metafile, a seed, is taken as it is) */
	if (size < 1)
		return 0;
	int real = plotmeta_is(data, size);
	size_t n = real ? size : size - 1 + 8;
	uint8_t *b = malloc(n ? n : 1);
	if (!b)
		return 0;
	if (real) {
		memcpy(b, data, size);
	} else {
		memcpy(b, data[0] & 1 ? "#PLOT 1\n" : "#PLOT 2\n", 8);
		memcpy(b + 8, data + 1, size - 1);
	}
	FUZZ_ASSERT(plotmeta_is(b, n), "magic not recognised");
	fuzz_buf_t m1 = { 0 }, m2 = { 0 };
	char e1[700], e2[700];
	int r1 = import(b, n, &m1, e1, sizeof e1);
	int r2 = import(b, n, &m2, e2, sizeof e2);
	FUZZ_ASSERT(r1 == r2, "two imports: %d then %d", r1, r2);
	FUZZ_ASSERT(r1 != -100, "the writer refused the end of a successful import");
	if (r1 == 0) {
		FUZZ_ASSERT(m1.n == m2.n && !memcmp(m1.p, m2.p, m1.n), "two imports, two meta files");
		meta_reader_t *r = meta_reader_mem(m1.p, m1.n, "out");
		if (r) {
			meta_cmd_t c;
			int rc;
			while ((rc = meta_read(r, &c)) > 0)
				;
			FUZZ_ASSERT(rc == 0, "import wrote a bad meta file: %s", meta_reader_error(r));
			meta_reader_free(r);
		}
	} else if (r1 == -65) {
		FUZZ_ASSERT(fuzz_one_line(e1) && !strncmp(e1, "in: byte ", 9), "error '%s'", e1);
		FUZZ_ASSERT(!strcmp(e1, e2), "two messages: '%s' / '%s'", e1, e2);
	} else {
		FUZZ_ASSERT(r1 == -70, "import answered %d (%s)", r1, e1);
	}
	free(m1.p);
	free(m2.p);
	free(b);
	return 0;
}
