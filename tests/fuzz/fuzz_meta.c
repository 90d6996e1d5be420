/* fuzz_meta.c: libFuzzer harness of the meta reader (text, or binary with -DFUZZ_META_BINARY): errors are one line, and what reads cleanly round-trips through both writers. */
#include "fuzz.h"
#include "locus_meta.h"

#ifndef FUZZ_ENTRY
#define FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

/* A stream that hands out its bytes a few at a time (the reader's refills at every boundary). */
typedef struct {
	const uint8_t *p;
	size_t n, at, chunk;
} trickle_t;

static long trickle_read(void *user, void *buf, size_t n)
{
	trickle_t *t = user;
	size_t k = t->n - t->at;
	if (k > t->chunk)
		k = t->chunk;
	if (k > n)
		k = n;
	memcpy(buf, t->p + t->at, k);
	t->at += k;
	return (long)k;
}

/* Read all of buf (from memory, or through a stream of chunk bytes a read when chunk > 0),
 * re-writing every statement into a text and a binary writer. Returns the reader's result (0
 * clean end, <0 error); *text and *bin hold the output (freed by the caller). */
static int rewrite_by(const void *buf, size_t n, size_t chunk, fuzz_buf_t *text, fuzz_buf_t *bin, char *err,
		size_t errlen, long *count)
{
	trickle_t tr = { buf, n, 0, chunk };
	meta_reader_t *r = chunk ? meta_reader_new(trickle_read, &tr, "in") : meta_reader_mem(buf, n, "in");
	meta_writer_t *wt = meta_writer_new(fuzz_buf_write, text, META_ENC_TEXT);
	meta_writer_t *wb = meta_writer_new(fuzz_buf_write, bin, META_ENC_BINARY);
	meta_cmd_t c;
	int rc;
	*count = 0;
	FUZZ_ASSERT(r && wt && wb, "out of memory at start");
	while ((rc = meta_read(r, &c)) > 0) {
		(*count)++;
		FUZZ_ASSERT(meta_write(wt, &c) == 0, "text writer refused statement %ld (%s) the reader accepted: %s",
				*count, meta_op_name(c.op), meta_writer_error(wt));
		FUZZ_ASSERT(meta_write(wb, &c) == 0, "binary writer refused statement %ld (%s) the reader accepted: %s",
				*count, meta_op_name(c.op), meta_writer_error(wb));
	}
	snprintf(err, errlen, "%s", meta_reader_error(r));
	if (rc < 0) {
		FUZZ_ASSERT(fuzz_one_line(err), "error message not one line: '%s'", err);
		FUZZ_ASSERT(!strncmp(err, "in:", 3), "error message does not name the input: '%s'", err);
	} else {
		FUZZ_ASSERT(*count > 0 && !*err, "a clean read of nothing, or a message after success: '%s'", err);
	}
	int ct = meta_writer_close(wt), cb = meta_writer_close(wb);
	if (rc == 0)
		FUZZ_ASSERT(ct == 0 && cb == 0, "writer refused to close a file the reader accepted whole");
	meta_reader_free(r);
	return rc;
}

static int rewrite(const void *buf, size_t n, fuzz_buf_t *text, fuzz_buf_t *bin, char *err, size_t errlen,
		long *count)
{
	return rewrite_by(buf, n, 0, text, bin, err, errlen, count);
}

int FUZZ_ENTRY(const uint8_t *data, size_t size);
int FUZZ_ENTRY(const uint8_t *data, size_t size)
{
	static const uint8_t magic[9] = { 0x8b, 0x4c, 0x4d, 0x42, 0x0d, 0x0a, 0x1a, 0x0a, 1 };
	const uint8_t *in = data;
	uint8_t *owned = NULL;
	fuzz_buf_t t1 = { 0 }, b1 = { 0 }, t2 = { 0 }, b2 = { 0 }, t3 = { 0 }, b3 = { 0 };
	char err[1024];
	long n1, n2, n3;
#ifdef FUZZ_META_BINARY
	/* the binary harness spends its effort after the header: the magic is added when absent */
	if (size < 9 || memcmp(data, magic, 9)) {
		owned = malloc(size + 9);
		if (!owned)
			return 0;
		memcpy(owned, magic, 9);
		memcpy(owned + 9, data, size);
		in = owned;
		size += 9;
	}
#else
	(void)magic;
#endif
	if (size > 1 << 20)  /* the reader streams; a bigger input finds nothing a smaller one does not */
		goto done;
	int r1 = rewrite(in, size, &t1, &b1, err, sizeof err, &n1);
	if (size <= 65536) {
		/* a stream of 1 to 8 bytes a read (by the input's first byte) reads the same statements
		 * with the same message as the whole buffer */
		fuzz_buf_t ts = { 0 }, bs = { 0 };
		char errs[1024];
		long ns;
		size_t chunk = 1 + (size ? data[0] % 8 : 0);
		int rs = rewrite_by(in, size, chunk, &ts, &bs, errs, sizeof errs, &ns);
		FUZZ_ASSERT(rs == r1 && ns == n1, "streamed %zu bytes a read: %d after %ld statements; from memory %d after %ld",
				chunk, rs, ns, r1, n1);
		FUZZ_ASSERT(!strcmp(errs, err), "streamed: '%s'; from memory: '%s'", errs, err);
		FUZZ_ASSERT(ts.n == t1.n && (!t1.n || !memcmp(ts.p, t1.p, t1.n)), "streamed input gives other statements");
		free(ts.p), free(bs.p);
	}
	if (r1 == 0) {
		/* canonical text and binary read back to the same statements (the same bytes again) */
		int r2 = rewrite(t1.p, t1.n, &t2, &b2, err, sizeof err, &n2);
		FUZZ_ASSERT(r2 == 0, "canonical text of an accepted file is refused: %s", err);
		FUZZ_ASSERT(n2 == n1, "text round trip: %ld statements, then %ld", n1, n2);
		FUZZ_ASSERT(t2.n == t1.n && !memcmp(t2.p, t1.p, t1.n), "text -> text is not stable");
		FUZZ_ASSERT(b2.n == b1.n && !memcmp(b2.p, b1.p, b1.n), "text -> binary differs from input -> binary");
		int r3 = rewrite(b1.p, b1.n, &t3, &b3, err, sizeof err, &n3);
		FUZZ_ASSERT(r3 == 0, "binary of an accepted file is refused: %s", err);
		FUZZ_ASSERT(n3 == n1, "binary round trip: %ld statements, then %ld", n1, n3);
		FUZZ_ASSERT(t3.n == t1.n && !memcmp(t3.p, t1.p, t1.n), "binary -> text differs from input -> text");
		FUZZ_ASSERT(b3.n == b1.n && !memcmp(b3.p, b1.p, b1.n), "binary -> binary is not stable");
	}
done:
	free(t1.p), free(b1.p), free(t2.p), free(b2.p), free(t3.p), free(b3.p);
	free(owned);
	return 0;
}
