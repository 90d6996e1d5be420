/* test_diff_fuzz.c: seeded mutations of PCX, BMP, DPX, Cineon, dumps, HP-GL and plotutils inputs: no crash, one-line errors. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "diff/diff.h"
#include "image/image.h"
#include "image/imgread_int.h"
#include "locus_meta.h"
#include "import/plotmeta.h"
#include "unit.h"

static uint64_t rng = 0x243f6a8885a308d3u;
static unsigned rnd(unsigned n)
{
	rng ^= rng >> 12, rng ^= rng << 25, rng ^= rng >> 27;
	return (unsigned)((rng * 2685821657736338717u) >> 33) % n;
}

/* Mutate src (n bytes) into dst (room for n + 64): flipped, replaced, cut, duplicated bytes. */
static size_t mutate(const unsigned char *src, size_t n, unsigned char *dst)
{
	size_t len = n;
	memcpy(dst, src, n);
	for (unsigned k = 0, m = 1 + rnd(4); k < m && len > 1; k++) {
		size_t i = rnd((unsigned)len);
		switch (rnd(5)) {
		case 0: dst[i] ^= (unsigned char)(1u << rnd(8)); break;
		case 1: dst[i] = (unsigned char)rnd(256); break;
		case 2: len = i + 1; break;
		case 3: dst[i] = (unsigned char)(rnd(2) ? 0xff : 0); break;
		default:
			if (len + 8 <= n + 64) {
				memmove(dst + i + 8, dst + i, len - i);
				len += 8;
			}
		}
	}
	return len;
}

static size_t put16(unsigned char *b, size_t at, unsigned v) { b[at] = (unsigned char)v; b[at + 1] = (unsigned char)(v >> 8); return at + 2; }
static void put32(unsigned char *b, size_t at, uint32_t v, int be)
{
	for (int k = 0; k < 4; k++)
		b[at + (size_t)k] = (unsigned char)(be ? v >> (24 - 8 * k) : v >> (8 * k));
}

/* Seeds: small valid files of each format, built here. */
static size_t seed_pcx(unsigned char *b)
{
	memset(b, 0, 128);
	b[0] = 10, b[1] = 5, b[2] = 1, b[3] = 8;
	put16(b, 8, 3), put16(b, 10, 1);   /* 4 x 2 */
	b[65] = 1, put16(b, 66, 4);
	size_t n = 128;
	for (int k = 0; k < 2; k++)
		b[n++] = 0xC4, b[n++] = (unsigned char)(k + 1);
	b[n++] = 12;
	for (int k = 0; k < 768; k++)
		b[n++] = (unsigned char)k;
	return n;
}

static size_t seed_bmp(unsigned char *b)
{
	memset(b, 0, 54 + 24);
	b[0] = 'B', b[1] = 'M';
	put32(b, 10, 54, 0), put32(b, 14, 40, 0), put32(b, 18, 3, 0), put32(b, 22, 2, 0);
	put16(b, 26, 1), put16(b, 28, 24);
	for (int k = 0; k < 24; k++)
		b[54 + k] = (unsigned char)(k * 10);
	return 54 + 24;
}

static size_t seed_dpx(unsigned char *b, int cineon)
{
	memset(b, 0, 2048 + 16);
	if (cineon) {
		put32(b, 0, 0x802A5FD7, 1), put32(b, 4, 2048, 1);
		b[193] = 3, b[198] = 10, b[226] = 10, b[254] = 10;
		put32(b, 200, 2, 1), put32(b, 204, 2, 1);
		b[681] = 5;
	} else {
		memcpy(b, "SDPX", 4), put32(b, 4, 2048, 1);
		b[770 + 1] = 1;   /* one element (big-endian 16 bits) */
		put32(b, 772, 2, 1), put32(b, 776, 2, 1);
		b[800] = 50, b[803] = 10, b[805] = 1;
		put32(b, 808, 2048, 1);
	}
	for (int k = 0; k < 16; k++)
		b[2048 + k] = (unsigned char)(k * 17);
	return 2048 + 16;
}

/* A writer's sink that drops the bytes. */
static int sink(void *user, const void *b, size_t n)
{
	(void)user, (void)b, (void)n;
	return 0;
}

static int check_line(const char *e)
{
	return e[0] && !strchr(e, '\n');
}

int main(void)
{
	unsigned char seed[4096], buf[4096 + 64];
	const char *names[] = { "pcx", "bmp", "dpx", "cineon" };
	for (int f = 0; f < 4; f++) {
		size_t n = f == 0 ? seed_pcx(seed) : f == 1 ? seed_bmp(seed) : seed_dpx(seed, f == 3);
		img_t img;
		char err[600];
		int rc = img_decode(seed, n, names[f], &img, err, sizeof err);
		CHECK(rc == 0 && img.width > 0, "%s seed decodes (%s)", names[f], rc ? err : "");
		img_free(&img);
		int bad = 0, lines = 1;
		for (int k = 0; k < 3000; k++) {
			size_t m = mutate(seed, n, buf);
			rc = img_decode(buf, m, names[f], &img, err, sizeof err);
			if (rc && !check_line(err))
				lines = 0;
			if (rc && rc != -65 && rc != -70)
				bad++;
			img_free(&img);
		}
		CHECK(bad == 0 && lines, "%s: 3000 mutations, no crash, each error one line", names[f]);
	}
	/* HP-GL through the diff engine, plotutils through the importer */
	static const char hpgl[] = "IN;SP1;PU0,0;PD100,0,100,100;CI50;SP2;PA200,200;PD300,300;LBHi\003;EA400,400;";
	static const char plot[] = "#PLOT 2\no\n- 65535 0 0\n* 0 0 100 100\n$ 10 10\n) 90 10\n) 90 90\nE\n5 50 50 20\nTct x\nx\n";
	int ok = 1;
	for (int k = 0; k < 3000; k++) {
		size_t m = mutate((const unsigned char *)hpgl, sizeof hpgl - 1, buf);
		char err[600] = "";
		diff_opts_t o;
		diff_opts_default(&o);
		FILE *out = fopen("/dev/null", "w");
		int rc = out ? diff_hpgl(hpgl, sizeof hpgl - 1, "a", buf, m, "b", &o, out, err, sizeof err) : 0;
		if (out)
			fclose(out);
		if (rc < 0 && !check_line(err))
			ok = 0;
	}
	CHECK(ok, "HP-GL diff: 3000 mutations, no crash, one-line errors");
	ok = 1;
	for (int k = 0; k < 3000; k++) {
		size_t m = mutate((const unsigned char *)plot, sizeof plot - 1, buf);
		char err[600] = "";
		meta_writer_t *w = meta_writer_new(sink, NULL, META_ENC_TEXT);
		if (!w)
			break;
		int rc = plotmeta_import(buf, m, "p", w, err, sizeof err);
		meta_writer_close(w);
		if (rc < 0 && !check_line(err))
			ok = 0;
	}
	CHECK(ok, "plotutils import: 3000 mutations, no crash, one-line errors");
	return UNIT_DONE();
}
