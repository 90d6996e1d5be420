/* test_meta_fuzz.c: seeded random mutations of valid text and binary files: the reader never crashes, errors are one line. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "membuf.h"
#include "unit.h"
#include "locus_meta.h"

static const char seed_text[] =
	"LOCUS-META 1\n# seed\npage 40 30\nsize 10.583 7.938\nclear #e8e8e8\ncolour #ff0000\nwidth 2.5\n"
	"dash 3 1.5\ncap round\njoin bevel\nfill-rule even-odd\nmiter-limit 4\nstroke\nmove 1 2\n"
	"draw 10 -0.5\narc 20 20 5 0 90\nclose\ncircle 30 30 4\nend\nfill\nmove 0 0\ndraw 5 0\ndraw 5 5\nend\n"
	"text 5 5 8 0 \"Hi \\\"x\\\" \\\\ \\x01\"\nspan 1 2 3 #00ff00\nimage 2 3 4 2\nrow 4 #0000ff\n"
	"row 1 #000000 3 #ffffff\nend-page\npage 8 8\nend-page\n";

static uint64_t rng = 0x9e3779b97f4a7c15u;
static unsigned rnd(unsigned n)
{
	rng ^= rng >> 12, rng ^= rng << 25, rng ^= rng >> 27;
	return (unsigned)((rng * 2685821657736338717u) >> 33) % n;
}

/* Mutate src into dst (room for n + 16 bytes); returns the new length. */
static size_t mutate(const char *src, size_t n, char *dst)
{
	size_t len = n, k, m = 1 + rnd(4), i;
	memcpy(dst, src, n);
	for (k = 0; k < m && len; k++) {
		i = rnd((unsigned)len);
		switch (rnd(4)) {
		case 0: dst[i] = (char)rnd(256); break;
		case 1: dst[i] = "0123456789 -.#\n\"\\x\x80\xff"[rnd(20)]; break;
		case 2: memmove(dst + i, dst + i + 1, len - i - 1), len--; break;
		default: len = i; break;
		}
	}
	return len;
}

int main(void)
{
	membuf_t bin = { 0 };
	meta_reader_t *r = meta_reader_mem(seed_text, sizeof seed_text - 1, "seed");
	meta_writer_t *w = meta_writer_new(membuf_write, &bin, META_ENC_BINARY);
	meta_cmd_t c;
	char *buf;
	int rc, it, which;
	long valid = 0, bad = 0, badmsg = 0, rewritten = 0;
	while ((rc = meta_read(r, &c)) > 0)
		meta_write(w, &c);
	CHECK(rc == 0, "seed text is valid (%s)", meta_reader_error(r));
	CHECK(meta_writer_close(w) == 0, "seed binary written");
	meta_reader_free(r);
	buf = malloc(sizeof seed_text + bin.n + 16);
	for (which = 0; which < 2; which++) {
		const char *src = which ? bin.p : seed_text;
		size_t n = which ? bin.n : sizeof seed_text - 1;
		for (it = 0; it < 4000; it++) {
			size_t len = mutate(src, n, buf);
			membuf_t out = { 0 };
			const char *e;
			r = meta_reader_mem(buf, len, "m");
			w = meta_writer_new(membuf_write, &out, which ? META_ENC_TEXT : META_ENC_BINARY);
			while ((rc = meta_read(r, &c)) > 0)
				if (meta_write(w, &c) < 0)
					rewritten = -1000000; /* the writer refused what the reader accepted */
			e = meta_reader_error(r);
			if (rc == 0) {
				valid++;
				rewritten += meta_writer_close(w) == 0;
			} else {
				bad++;
				meta_writer_close(w);
				badmsg += strchr(e, '\n') == NULL && (strncmp(e, "m:", 2) == 0) && strlen(e) < 600;
			}
			meta_reader_free(r);
			free(out.p);
		}
	}
	CHECK(valid + bad == 8000, "8000 mutated inputs read to the end or to an error");
	CHECK(valid > 0 && bad > 1000, "both outcomes happen (%ld valid, %ld errors)", valid, bad);
	CHECK(badmsg == bad, "every error is one line naming the input (%ld of %ld)", badmsg, bad);
	CHECK(rewritten == valid, "the writer accepts and completes whatever the reader accepted (%ld of %ld)", rewritten, valid);
	free(buf);
	free(bin.p);
	return UNIT_DONE();
}
