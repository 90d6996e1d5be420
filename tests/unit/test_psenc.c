/* test_psenc.c: the PostScript/PDF encoders decode back to their input; sizes are exact. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>
#include "ps/psdev.h"
#include "ps/psenc.h"
#include "unit.h"

static char path[64];

/* Run fn on a writer over a fresh file; return the file's bytes (malloc'd) and length. */
static uint8_t *written(void (*fn)(dev_writer_t *, void *), void *arg, size_t *len)
{
	char err[256];
	strcpy(path, "/tmp/locus-psenc-XXXXXX");
	int fd = mkstemp(path);
	if (fd < 0)
		return NULL;
	close(fd);
	io_transport_t *t = io_open_write(path, err, sizeof err);
	dev_writer_t *o = malloc(sizeof *o);
	if (!t || !o)
		return NULL;
	dev_w_init(o, t);
	fn(o, arg);
	dev_w_flush(o);
	int bad = o->err;
	io_close(t, IO_COMMIT);
	free(o);
	FILE *f = fopen(path, "rb");
	uint8_t *b = malloc(1 << 22);
	*len = f && b ? fread(b, 1, 1 << 22, f) : 0;
	if (f)
		fclose(f);
	unlink(path);
	if (bad) {
		free(b);
		return NULL;
	}
	return b;
}

/* An ASCII85 decoder (PLRM 3.13.3), skipping white space, up to ~>. Returns the length. */
static long a85_decode(const uint8_t *s, size_t n, uint8_t *out)
{
	long o = 0;
	uint32_t v = 0;
	int k = 0;
	for (size_t i = 0; i < n; i++) {
		int c = s[i];
		if (c == '\n' || c == ' ')
			continue;
		if (c == '~')
			break;
		if (c == 'z' && k == 0) {
			memset(out + o, 0, 4);
			o += 4;
			continue;
		}
		if (c < '!' || c > 'u')
			return -1;
		v = v * 85 + (uint32_t)(c - '!');
		if (++k == 5) {
			for (int j = 0; j < 4; j++)
				out[o++] = (uint8_t)(v >> (24 - 8 * j));
			v = 0;
			k = 0;
		}
	}
	if (k) {
		int got = k - 1;
		for (; k < 5; k++)
			v = v * 85 + 84;
		for (int j = 0; j < got; j++)
			out[o++] = (uint8_t)(v >> (24 - 8 * j));
	}
	return o;
}

static long rle_decode(const uint8_t *s, size_t n, uint8_t *out)
{
	long o = 0;
	for (size_t i = 0; i < n;) {
		int c = s[i++];
		if (c == 128)
			return o;
		if (c < 128) {
			memcpy(out + o, s + i, (size_t)c + 1);
			o += c + 1;
			i += (size_t)c + 1;
		} else {
			memset(out + o, s[i++], (size_t)(257 - c));
			o += 257 - c;
		}
	}
	return -1;   /* no EOD */
}

typedef struct {
	const uint8_t *p;
	size_t n;
} buf_t;

static void write_a85(dev_writer_t *o, void *arg)
{
	buf_t *b = arg;
	pse_a85_write(o, b->p, b->n);
}

static void write_hex(dev_writer_t *o, void *arg)
{
	buf_t *b = arg;
	pse_hex_write(o, b->p, b->n);
}

static void write_packed(dev_writer_t *o, void *arg)
{
	buf_t *b = arg;
	dev_w_puts(o, "head\n");
	pse_deflate_begin(o, 1, 1);
	dev_w_write(o, b->p, b->n / 2);
	pse_deflate_level(o, 6);
	dev_w_write(o, b->p + b->n / 2, b->n - b->n / 2);
	pse_deflate_end(o, NULL);
	dev_w_puts(o, "tail\n");
}

static void write_numbers(dev_writer_t *o, void *arg)
{
	(void)arg;
	dev_w_fix(o, 12000); dev_w_puts(o, " ");
	dev_w_fix(o, 12500); dev_w_puts(o, " ");
	dev_w_fix(o, -1); dev_w_puts(o, " ");
	dev_w_fix(o, 0); dev_w_puts(o, " ");
	dev_w_int(o, -9876543210LL); dev_w_puts(o, " ");
	dev_w_real(o, 0.07499941, 8); dev_w_puts(o, " ");
	dev_w_real(o, -0.00001, 4);
}

/* Contour-like records, one per 12-byte sample, with text between and a padded sample. */
static void write_rows(dev_writer_t *o, void *arg)
{
	buf_t *b = arg;   /* gets the plain text the stream must decode to */
	static char plain[200000];
	size_t n = 0;
	pse_deflate_begin(o, 0, PSE_ROWS);
	pse_rows_begin(o, 12, 64);
	for (int k = 0; k < 3000; k++) {
		char rec[16];
		if (k % 500 == 0) {   /* a path head: text of any length, then padded to a sample */
			int m = snprintf(rec, sizeof rec, "q %d cm ", k);
			dev_w_write(o, rec, (size_t)m);
			memcpy(plain + n, rec, (size_t)m);
			n += (size_t)m;
			unsigned col = pse_rows_col(o);
			pse_rows_pad(o, ' ');
			if (col) {
				memset(plain + n, ' ', 12 - col);
				n += 12 - col;
			}
		}
		snprintf(rec, sizeof rec, "%4d %4d l\n", 20 * (k % 40), 7 * k % 1000);
		dev_w_write(o, rec, 12);
		memcpy(plain + n, rec, 12);
		n += 12;
	}
	pse_rows_end(o, ' ');
	size_t row = 12 * 64;
	memset(plain + n, ' ', (row - n % row) % row);
	n += (row - n % row) % row;
	pse_deflate_end(o, NULL);
	b->p = (const uint8_t *)plain;
	b->n = n;
}

int main(void)
{
	static uint8_t data[70000], back[80000];
	uint32_t x = 12345;
	/* runs and noise, with zero groups for ASCII85's z */
	for (size_t k = 0; k < sizeof data; k++) {
		x = x * 1103515245u + 12345u;
		data[k] = k % 1000 < 300 ? 0 : k % 1000 < 600 ? (uint8_t)(k / 1000) : (uint8_t)(x >> 24);
	}
	size_t len;
	uint8_t *f;

	buf_t man = { (const uint8_t *)"Man ", 4 };
	f = written(write_a85, &man, &len);
	CHECK(f && len == 8 && !memcmp(f, "9jqo^~>\n", 8), "ASCII85 of 'Man ' is 9jqo^ (PLRM's example)");
	free(f);
	int good = 1;
	for (size_t n = 0; n < 300 && good; n += 7) {
		buf_t b = { data + 290, n };
		f = written(write_a85, &b, &len);
		good = f && len == pse_a85_size(b.p, n) && a85_decode(f, len, back) == (long)n && !memcmp(back, b.p, n);
		for (size_t i = 0, col = 0; f && i < len; i++, col++) {
			if (f[i] == '\n')
				col = 0;
			else if (col >= 75)
				good = 0;
		}
		free(f);
	}
	CHECK(good, "ASCII85 of 0..300 bytes decodes back, pse_a85_size is exact, lines at most 75");

	uint8_t *r = malloc(pse_rle_bound(sizeof data));
	size_t nr = pse_rle_encode(data, sizeof data, r);
	CHECK(nr <= pse_rle_bound(sizeof data) && r[nr - 1] == 128, "RunLength: within its bound, ends with EOD");
	CHECK(rle_decode(r, nr, back) == (long)sizeof data && !memcmp(back, data, sizeof data), "RunLength decodes back");
	CHECK(nr < sizeof data * 8 / 10, "RunLength shrinks runs (%zu of %zu bytes)", nr, sizeof data);
	uint8_t one = 7;
	nr = pse_rle_encode(&one, 1, r);
	CHECK(nr == 3 && r[0] == 0 && r[1] == 7 && r[2] == 128, "RunLength of one byte");
	free(r);

	buf_t hb = { data + 700, 100 };
	f = written(write_hex, &hb, &len);
	int hexok = f && len == pse_hex_size(100) && f[78] == '\n' && f[len - 1] == '\n';
	for (size_t i = 0; hexok && i < 78; i += 2) {
		unsigned v;
		hexok = sscanf((const char *)f + i, "%2x", &v) == 1 && v == data[700 + i / 2];
	}
	CHECK(hexok, "hex: the bytes, size exact, 78 digits a line");
	free(f);

	uint8_t *z;
	size_t nz;
	CHECK(pse_flate_encode(data, sizeof data, 6, &z, &nz) == 0, "Flate encodes");
	uLongf nb = sizeof back;
	CHECK(uncompress(back, &nb, z, nz) == Z_OK && nb == sizeof data && !memcmp(back, data, nb), "Flate decodes back (zlib)");
	free(z);

	buf_t pb = { data, 20000 };
	f = written(write_packed, &pb, &len);
	int pk = 0;
	if (f && len > 10 && !memcmp(f, "head\n", 5) && !memcmp(f + len - 5, "tail\n", 5)) {
		static uint8_t zz[80000];
		long n85 = a85_decode(f + 5, len - 10, zz);
		uLongf nu = sizeof back;
		pk = n85 > 0 && uncompress(back, &nu, zz, (uLong)n85) == Z_OK && nu == 20000 && !memcmp(back, data, nu);
	}
	CHECK(pk, "streaming Flate + ASCII85 with a level change decodes back");
	free(f);

	buf_t want_rows;
	f = written(write_rows, &want_rows, &len);
	int rows_ok = 0, zeros = 0;
	static uint8_t dec[200000];
	uLongf nd = sizeof dec;
	if (f && uncompress(dec, &nd, f, len) == Z_OK && nd == want_rows.n && nd % (12 * 64) == 0) {
		for (size_t i = 0; i < nd; i++)
			zeros += dec[i] == 0;
		/* TIFF predictor 2, 12 colours of 8 bits, 64 columns: each byte but a row's first
		 * sample adds the same byte of the sample before */
		for (size_t r = 0; r < nd; r += 12 * 64)
			for (size_t i = 12; i < 12 * 64; i++)
				dec[r + i] = (uint8_t)(dec[r + i] + dec[r + i - 12]);
		rows_ok = !memcmp(dec, want_rows.p, nd);
	}
	CHECK(rows_ok, "predictor rows: Flate then TIFF predictor 2 (12 x 64) give back the text, heads padded, rows whole");
	CHECK(zeros > (int)nd / 3, "predictor rows: the columns that repeat become zeros (%d of %lu bytes)", zeros,
		(unsigned long)nd);
	free(f);

	f = written(write_numbers, NULL, &len);
	const char *want = "12 12.5 -0.001 0 -9876543210 0.07499941 0";
	CHECK(f && len == strlen(want) && !memcmp(f, want, len), "numbers: %.*s", f ? (int)len : 0, f ? (char *)f : "");
	free(f);

	char u[16];
	psd_unit(128, u, sizeof u);
	CHECK_STR(u, ".503", "colour component 128 is .503 (128.27 / 255)");
	psd_unit(255, u, sizeof u);
	CHECK_STR(u, "1", "colour component 255 is 1");
	int exact = 1;
	for (unsigned v = 0; v < 256; v++) {
		psd_unit(v, u, sizeof u);
		double d = atof(u) * 255;
		exact &= (unsigned)(d + 0.5) == v;
	}
	CHECK(exact, "every colour component maps back to its 8-bit value");
	/* issue 22: MuPDF truncates d x 255 (in single precision); .188 gave it 47 for 48 */
	int trunc = 1, trunc_f = 1, cairo = 1;
	unsigned worst = 0, worst_c = 0;
	for (unsigned v = 0; v < 256; v++) {
		psd_unit(v, u, sizeof u);
		trunc &= (unsigned)(atof(u) * 255) == v;
		float f = strtof(u, NULL) * 255.0f;
		if ((unsigned)f != v)
			trunc_f = 0, worst = v;
		/* cairo (pdftocairo): a 16-bit component floor(d x 65535 + 1/2), its high byte */
		if (((unsigned)(atof(u) * 65535 + 0.5) >> 8) != v)
			cairo = 0, worst_c = v;
	}
	CHECK(trunc && trunc_f, "every colour component survives a truncating reader, double and float (fails at %u)", worst);
	CHECK(cairo, "every colour component survives cairo's 16-bit conversion (fails at %u)", worst_c);
	psd_unit(48, u, sizeof u);
	CHECK(strcmp(u, ".188") && (unsigned)(atof(u) * 255) == 48, "48 is not .188 (47.94 truncated): %s", u);
	CHECK(psd_luma(0xffffff) == 255 && psd_luma(0) == 0 && psd_luma(0xff0000) == 76 && psd_luma(0x00ff00) == 150 &&
		psd_luma(0x0000ff) == 29, "luminance by BT.601");
	CHECK(psd_grid(-150) == -2 && psd_grid(149) == 1 && psd_grid(150) == 2, "grid rounding, ties away from zero");
	return UNIT_DONE();
}
