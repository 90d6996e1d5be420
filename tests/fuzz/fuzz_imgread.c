/* fuzz_imgread.c: libFuzzer harness of locus-diff's streaming image readers (PCX, BMP, DPX, Cineon, framebuffer dumps, and PNG/PPM/RLE) fed a few bytes at a time: an error is one line naming the input, a picture's rows all decode, and the stream and whole-buffer reads agree. */
#include "fuzz.h"
#include "image/image.h"
#include "image/imgread_int.h"

#ifndef FUZZ_ENTRY
#define FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

/* The input as a stream of chunk-byte reads; a dump repeats its bytes up to the mode's size. */
typedef struct {
	const uint8_t *p;
	size_t n, pos, total, chunk;
} trickle_t;

static long trickle(void *user, void *buf, size_t n)
{
	trickle_t *t = user;
	if (t->pos >= t->total || t->n == 0)
		return 0;
	size_t k = t->total - t->pos;
	if (k > n)
		k = n;
	if (k > t->chunk)
		k = t->chunk;
	for (size_t i = 0; i < k; i++)
		((uint8_t *)buf)[i] = t->p[(t->pos + i) % t->n];
	t->pos += k;
	return (long)k;
}

static const uint64_t dump_sizes[4] = { 64000 + 768, 4 * 38400 + 48, 786432 + 768, 614400 };

int FUZZ_ENTRY(const uint8_t *data, size_t size);
int FUZZ_ENTRY(const uint8_t *data, size_t size)
{
	if (size < 2)
		return 0;
	/* byte 0: the read size (1..64 bytes) and whether the rest is a framebuffer dump (bit 7,
	 * bits 5..6 the mode: its size is the rest repeated) */
	trickle_t t = { data + 1, size - 1, 0, size - 1, (size_t)(data[0] & 31) * 2 + 1 };
	int dump = data[0] & 0x80;
	img_reader_t *r = NULL;
	char err[600] = "";
	int rc;
	if (dump) {
		uint64_t sz = dump_sizes[(data[0] >> 5) & 3];
		if (sz == 786432 + 768)
			sz = 64000 + 768;   /* the biggest mode only costs time: its layout is 13h's */
		t.total = sz;
		rc = img_rd_open_fbdump(trickle, &t, NULL, 0, "in", sz, &r, err, sizeof err);
	} else {
		rc = img_reader_open(trickle, &t, NULL, 0, "in", &r, err, sizeof err);
	}
	if (rc) {
		FUZZ_ASSERT(!r, "failed open left a reader");
		FUZZ_ASSERT(rc == -65 || rc == -70, "open answered %d", rc);
		FUZZ_ASSERT(fuzz_one_line(err) && !strncmp(err, "in", 2), "open error '%s'", err);
		return 0;
	}
	unsigned w = img_reader_width(r), h = img_reader_height(r);
	FUZZ_ASSERT(w > 0 && h > 0 && w <= DEV_IMAGE_MAX_DIM && h <= DEV_IMAGE_MAX_DIM, "picture of %ux%u", w, h);
	uint8_t *row = malloc((size_t)w * 3);
	if (!row) {
		img_reader_free(r);
		return 0;
	}
	rc = 0;
	for (unsigned y = 0; y < h && !rc; y++)
		rc = img_reader_row(r, row);
	if (!rc)
		rc = img_reader_end(r);
	if (rc) {
		FUZZ_ASSERT(rc == -65 || rc == -70, "row answered %d", rc);
		const char *e = img_reader_error(r);
		FUZZ_ASSERT(fuzz_one_line(e) && !strncmp(e, "in", 2), "row error '%s'", e);
	}
	free(row);
	img_reader_free(r);
	if (!dump) {   /* the whole-buffer decoder agrees about success */
		img_t img;
		int rc2 = img_decode(data + 1, size - 1, "in", &img, err, sizeof err);
		FUZZ_ASSERT((rc == 0) == (rc2 == 0), "stream %d, buffer %d (%s)", rc, rc2, err);
		if (!rc2) {
			FUZZ_ASSERT(img.width == w && img.height == h, "two sizes");
			img_free(&img);
		}
	}
	return 0;
}
