/* fuzz_plotmeta.c: libFuzzer harness of the plotutils metafile reader (portable and binary; fuzz.h's fuzz_import_twice): the same statements twice, an error is one line naming the byte, and a success is a meta file the meta reader accepts. */
#include "fuzz.h"
#include "import/plotmeta.h"

#ifndef FUZZ_ENTRY
#define FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

static int import(const uint8_t *buf, size_t n, void *user, meta_writer_t *w, char *err, size_t errlen)
{
	(void)user;
	return plotmeta_import(buf, n, "in", w, err, errlen);
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
	fuzz_import_twice(import, NULL, b, n, "in: byte ", 1);
	free(b);
	return 0;
}
