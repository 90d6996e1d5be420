/* fuzz_svg.c: libFuzzer harness of the SVG importer (fuzz.h's fuzz_import_twice): the same meta file twice, an error is one line "in:LINE:COL: ...", a success reads back as a valid meta file; the first byte picks tolerance, -O dedupe, -O occlude and the pens. */
#include "fuzz.h"
#include "import/svg_import.h"

#ifndef FUZZ_ENTRY
#define FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

static int import(const uint8_t *buf, size_t n, void *user, meta_writer_t *w, char *err, size_t errlen)
{
	int mode = *(const int *)user;
	svgimp_opts_t o = { .tol_mm = mode & 1 ? 0.5 : 0.0125, .dpi = 96, .dedupe = (mode >> 1) & 1,
		.dedupe_mm = 0.05, .pens_mode = (mode >> 2) % 3, .occlude = (mode >> 4) & 1, .quiet = 1 };
	return svgimp_import(buf, n, "in", &o, w, err, errlen);
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
	fuzz_import_twice(import, &mode, data, size, "in", 0);
	return 0;
}
