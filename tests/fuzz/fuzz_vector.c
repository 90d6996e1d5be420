/* fuzz_vector.c: libFuzzer harness of replay through the PostScript and PDF devices: a failure is
 * one line, and what is written is whole: PDF with a cross-reference table whose every offset
 * is its object, PS and EPS with their DSC frame; a PDF written twice is the same bytes. */
#include <unistd.h>
#include "fuzz.h"
#include "device/device.h"
#include "io/transport.h"

#ifndef FUZZ_ENTRY
#define FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

#define MAX_PIXELS (96 * 96)     /* small pages keep each run short (and their images small) */
#define MAX_WORK 200000.0        /* estimated chords, dash pieces and glyph strokes in one input */

extern const dev_ops_t dev_eps_ops, dev_ps_ops, dev_pdf_ops;

/* The output file's bytes (NUL-terminated), or NULL. */
static char *slurp(const char *path, size_t *n)
{
	fuzz_buf_t b = { 0 };
	char tmp[4096];
	size_t got;
	FILE *f = fopen(path, "rb");
	FUZZ_ASSERT(f, "the committed output %s is missing", path);
	while ((got = fread(tmp, 1, sizeof tmp, f)) > 0)
		FUZZ_ASSERT(!fuzz_buf_write(&b, tmp, got), "out of memory");
	fclose(f);
	FUZZ_ASSERT(!fuzz_buf_write(&b, "", 1), "out of memory");
	*n = b.n - 1;
	return b.p;
}

/* The PDF's frame: header, startxref pointing at "xref", every in-use entry at "K 0 obj". */
static void check_pdf(const char *p, size_t n)
{
	FUZZ_ASSERT(n > 20 && !memcmp(p, "%PDF-1.4\n", 9), "no PDF header");
	FUZZ_ASSERT(!memcmp(p + n - 6, "%%EOF\n", 6), "the PDF does not end with %%%%EOF");
	const char *sx = p + n - 6;
	while (sx > p && memcmp(sx, "startxref\n", 10))
		sx--;
	FUZZ_ASSERT(sx > p, "no startxref");
	unsigned long long at = strtoull(sx + 10, NULL, 10);
	FUZZ_ASSERT(at < n && !memcmp(p + at, "xref\n0 ", 7), "startxref %llu is not at the xref table", at);
	char *end;
	unsigned long count = strtoul(p + at + 7, &end, 10);
	FUZZ_ASSERT(*end == '\n' && count >= 1, "xref subsection header");
	const char *e = end + 1;
	for (unsigned long k = 0; k < count; k++, e += 20) {
		FUZZ_ASSERT(e + 20 <= p + n, "xref entry %lu past the end", k);
		unsigned long long off = strtoull(e, NULL, 10);
		if (e[17] != 'n')
			continue;
		char want[32];
		int w = snprintf(want, sizeof want, "%lu 0 obj", k);
		FUZZ_ASSERT(off + (size_t)w < n && !memcmp(p + off, want, (size_t)w), "object %lu is not at %llu", k, off);
	}
}

/* One replay of the input into path; returns dev_play's status (the output is committed only
 * on success) and the message in err. */
static int replay(const uint8_t *data, size_t size, const dev_ops_t *ops, const char *options, const char *path,
		char *err, size_t errlen)
{
	meta_reader_t *r = meta_reader_mem(data, size, "in");
	io_transport_t *t = io_open_write(path, err, errlen);
	FUZZ_ASSERT(r && t, "cannot start: %s", err);
	dev_device_t *d = dev_new(ops, t);
	FUZZ_ASSERT(d, "out of memory at start");
	d->options = options;
	int rc = dev_play(r, d);
	snprintf(err, errlen, "%s", rc < 0 ? dev_error(d) : "");
	if (rc < 0)
		FUZZ_ASSERT(fuzz_one_line(err), "error not one line: '%s'", err);
	char cerr[600];
	int crc = io_close_err(t, rc < 0 ? IO_ABORT : IO_COMMIT, cerr, sizeof cerr);
	FUZZ_ASSERT(rc < 0 || crc == 0, "closing the output failed: %s", cerr);
	dev_free(d);
	meta_reader_free(r);
	return rc;
}

int FUZZ_ENTRY(const uint8_t *data, size_t size);
int FUZZ_ENTRY(const uint8_t *data, size_t size)
{
	static const char *levels[] = { "level=1", "level=2", "level=3", "level=3,grey=yes" };
	char path[96], err[600];
	unsigned pages;
	double w;
	if (size > 65536 || (w = fuzz_work(data, size, MAX_PIXELS, &pages)) < 0 || w > MAX_WORK)
		return 0;
	snprintf(path, sizeof path, "/tmp/locus-fuzz-vector-%ld.out", (long)getpid());
	/* the options by the input's last byte, so that every level and grey are reached */
	unsigned k = size ? data[size - 1] % 4 : 0;
	const char *opt = levels[k], *pdf_opt = k == 3 ? "grey=yes" : NULL;
	size_t n1, n2;
	if (replay(data, size, &dev_pdf_ops, pdf_opt, path, err, sizeof err) >= 0) {
		char *a = slurp(path, &n1);
		check_pdf(a, n1);
		FUZZ_ASSERT(replay(data, size, &dev_pdf_ops, pdf_opt, path, err, sizeof err) >= 0,
			"the second PDF failed: %s", err);
		char *b = slurp(path, &n2);
		FUZZ_ASSERT(n1 == n2 && !memcmp(a, b, n1), "the PDF differs when written again (%zu / %zu bytes)", n1, n2);
		free(a);
		free(b);
	}
	if (replay(data, size, &dev_ps_ops, opt, path, err, sizeof err) >= 0) {
		char *a = slurp(path, &n1);
		FUZZ_ASSERT(!strncmp(a, "%!PS-Adobe-3.0\n", 15), "no PS header");
		FUZZ_ASSERT(n1 >= 6 && !memcmp(a + n1 - 6, "%%EOF\n", 6), "the PS does not end with %%%%EOF");
		free(a);
	}
	if (pages == 1 && replay(data, size, &dev_eps_ops, opt, path, err, sizeof err) >= 0) {
		char *a = slurp(path, &n1);
		FUZZ_ASSERT(!strncmp(a, "%!PS-Adobe-3.0 EPSF-3.0\n%%BoundingBox: ", 39), "no EPS header with its box");
		free(a);
	}
	unlink(path);
	return 0;
}
