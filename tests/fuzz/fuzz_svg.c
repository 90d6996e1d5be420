/* fuzz_svg.c: libFuzzer harness of the SVG importer: the same meta file twice, an error is one line "in:LINE:COL: ...", a success reads back as a valid meta file. */
#include "fuzz.h"
#include "import/svg_import.h"

#ifndef FUZZ_ENTRY
#define FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

/* Import buf into m with the options the first byte picks; the status, the message in err. */
static int import(const uint8_t *buf, size_t n, int mode, fuzz_buf_t *m, char *err, size_t errlen)
{
	svgimp_opts_t o = { .tol_mm = mode & 1 ? 0.5 : 0.0125, .dpi = 96, .dedupe = (mode >> 1) & 1,
		.dedupe_mm = 0.05, .pens_mode = (mode >> 2) % 3, .quiet = 1 };
	meta_writer_t *w = meta_writer_new(fuzz_buf_write, m, META_ENC_TEXT);
	if (!w)
		return -70;
	err[0] = 0;
	int rc = svgimp_import(buf, n, "in", &o, w, err, errlen);
	if (meta_writer_close(w) < 0 && rc == 0)
		rc = -100;
	return rc;
}

int FUZZ_ENTRY(const uint8_t *data, size_t size);
int FUZZ_ENTRY(const uint8_t *data, size_t size)
{
	/* a seed (starting with '<') is taken as it is; otherwise the first byte picks the options */
	int mode = 0;
	if (size && data[0] != '<') {
		mode = data[0];
		data++, size--;
	}
	fuzz_buf_t m1 = { 0 }, m2 = { 0 };
	char e1[700], e2[700];
	int r1 = import(data, size, mode, &m1, e1, sizeof e1);
	int r2 = import(data, size, mode, &m2, e2, sizeof e2);
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
		FUZZ_ASSERT(fuzz_one_line(e1) && !strncmp(e1, "in", 2), "error '%s'", e1);
		FUZZ_ASSERT(!strcmp(e1, e2), "two messages: '%s' / '%s'", e1, e2);
	}
	free(m1.p);
	free(m2.p);
	return 0;
}
