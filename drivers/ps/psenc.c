/* psenc.c: buffered PostScript/PDF writer, streaming Flate and ASCII85, RunLength and hex. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>
#include "locus_meta.h"
#include "ps/psenc.h"

#define A85_COLS 75

void pse_init(pse_out_t *o, io_transport_t *t)
{
	memset(o, 0, offsetof(pse_out_t, buf));
	o->t = t;
}

void pse_set_transport(pse_out_t *o, io_transport_t *t)
{
	o->t = t;
	o->pos = 0;
	o->n = 0;
}

/* Pass the buffer on: to the spool file or the transport. */
static int drain(pse_out_t *o, const void *p, size_t n)
{
	if (o->spool)
		return fwrite(p, 1, n, o->spool) == n ? 0 : -1;
	return o->t ? io_write(o->t, p, n) : -1;
}

/* Bytes that reach the transport (after any compression). */
static int raw(pse_out_t *o, const void *p, size_t n)
{
	if (o->err)
		return o->err;
	if (o->n + n > sizeof o->buf) {
		if (o->n && drain(o, o->buf, o->n))
			return o->err = META_EIO;
		o->n = 0;
		if (n > sizeof o->buf) {
			if (drain(o, p, n))
				return o->err = META_EIO;
			o->pos += n;
			return 0;
		}
	}
	memcpy(o->buf + o->n, p, n);
	o->n += n;
	o->pos += n;
	return 0;
}

/* ---- ASCII85: one state machine for streaming, whole buffers and size counting ---- */

typedef struct {
	uint32_t tuple;
	int ntuple, col;
	size_t count;         /* bytes produced (counting) */
	pse_out_t *o;         /* NULL: only count */
	int nl;               /* characters in line (a line is passed on whole) */
	char line[96];
} a85_t;

static void a85_out(a85_t *a)
{
	if (a->o && a->nl)
		raw(a->o, a->line, (size_t)a->nl);
	a->nl = 0;
}

static void a85_emit(a85_t *a, const char *s, int n)
{
	if (a->col + n > A85_COLS) {
		a->count++;
		a->line[a->nl++] = '\n';
		a85_out(a);
		a->col = 0;
	}
	a->count += (size_t)n;
	a->col += n;
	memcpy(a->line + a->nl, s, (size_t)n);
	a->nl += n;
}

/* Encode the open group of ntuple (1..4) bytes: 'z' for a full zero group. */
static void a85_group(a85_t *a)
{
	char c[5];
	uint32_t v = a->tuple;
	if (a->ntuple == 4 && v == 0) {
		a85_emit(a, "z", 1);
	} else {
		for (int k = 4; k >= 0; k--) {
			c[k] = (char)('!' + v % 85);
			v /= 85;
		}
		a85_emit(a, c, a->ntuple + 1);
	}
	a->tuple = 0;
	a->ntuple = 0;
}

static void a85_bytes(a85_t *a, const uint8_t *in, size_t n)
{
	size_t k = 0;
	for (; k < n && a->ntuple; k++) {
		a->tuple |= (uint32_t)in[k] << (24 - 8 * a->ntuple);
		if (++a->ntuple == 4)
			a85_group(a);
	}
	for (; k + 4 <= n; k += 4) {
		a->tuple = (uint32_t)in[k] << 24 | (uint32_t)in[k + 1] << 16 | (uint32_t)in[k + 2] << 8 | in[k + 3];
		a->ntuple = 4;
		a85_group(a);
	}
	for (; k < n; k++) {
		a->tuple |= (uint32_t)in[k] << (24 - 8 * a->ntuple);
		if (++a->ntuple == 4)
			a85_group(a);
	}
	a85_out(a);
}

static void a85_end(a85_t *a)
{
	if (a->ntuple)
		a85_group(a);
	a85_emit(a, "~>", 2);
	a->count++;
	a->line[a->nl++] = '\n';
	a85_out(a);
	a->col = 0;
}

size_t pse_a85_size(const uint8_t *in, size_t n)
{
	a85_t a = { 0, 0, 0, 0, NULL, 0, { 0 } };
	a85_bytes(&a, in, n);
	a85_end(&a);
	return a.count;
}

int pse_a85_write(pse_out_t *o, const uint8_t *in, size_t n)
{
	a85_t a = { 0, 0, 0, 0, o, 0, { 0 } };
	a85_bytes(&a, in, n);
	a85_end(&a);
	return o->err;
}

/* ---- compressed output ---- */

/* Pass compressed bytes on: raw, or through the writer's ASCII85 state. */
static void zsink(pse_out_t *o, const uint8_t *p, size_t n)
{
	o->zout += n;
	if (!o->a85) {
		raw(o, p, n);
		return;
	}
	a85_t a = { o->tuple, o->ntuple, o->col, 0, o, 0, { 0 } };
	a85_bytes(&a, p, n);
	o->tuple = a.tuple;
	o->ntuple = a.ntuple;
	o->col = a.col;
}

static int zpump(pse_out_t *o, const void *p, size_t n, int flush)
{
	z_stream *z = o->z;
	uint8_t tmp[1 << 15];
	z->next_in = (Bytef *)p;
	z->avail_in = (uInt)n;
	do {
		z->next_out = tmp;
		z->avail_out = sizeof tmp;
		int rc = deflate(z, flush);
		if (rc == Z_STREAM_ERROR)
			return o->err = META_EIO;
		zsink(o, tmp, sizeof tmp - z->avail_out);
	} while (z->avail_out == 0 || (flush == Z_FINISH && z->avail_in));
	return o->err;
}

/* Compress what is gathered in zin. */
static int zstage(pse_out_t *o)
{
	size_t n = o->nzin;
	o->nzin = 0;
	return n ? zpump(o, o->zin, n, Z_NO_FLUSH) : o->err;
}

int pse_deflate_begin(pse_out_t *o, int a85, int level)
{
	if (o->err)
		return o->err;
	z_stream *z = calloc(1, sizeof *z);
	int huff = level == PSE_HUFFMAN, text = level == PSE_TEXT || level == PSE_ROWS;
	if (!z || deflateInit2(z, huff ? 1 : text ? 9 : level, Z_DEFLATED, 15, text ? 9 : 8,
			huff ? Z_HUFFMAN_ONLY : text ? Z_FILTERED : Z_DEFAULT_STRATEGY) != Z_OK) {
		free(z);
		return o->err = META_ENOMEM;
	}
	if (level == PSE_TEXT)
		deflateTune(z, 8, 8, 24, 40);
	else if (level == PSE_ROWS)
		deflateTune(z, 8, 16, 128, 64);
	o->z = z;
	o->a85 = a85;
	o->tuple = 0;
	o->ntuple = 0;
	o->col = 0;
	o->zout = 0;
	o->rows = 0;
	return 0;
}

int pse_deflate_level(pse_out_t *o, int level)
{
	z_stream *z = o->z;
	uint8_t tmp[1 << 15];
	int rc;
	if (!z || o->err || zstage(o))
		return o->err;
	do {
		z->next_in = NULL;
		z->avail_in = 0;
		z->next_out = tmp;
		z->avail_out = sizeof tmp;
		rc = deflateParams(z, level == PSE_HUFFMAN ? 1 : level,
			level == PSE_HUFFMAN ? Z_HUFFMAN_ONLY : Z_DEFAULT_STRATEGY);
		zsink(o, tmp, sizeof tmp - z->avail_out);
	} while (rc == Z_BUF_ERROR && z->avail_out == 0);
	return rc == Z_OK || rc == Z_BUF_ERROR ? o->err : (o->err = META_EIO);
}

int pse_deflate_end(pse_out_t *o, uint64_t *zlen)
{
	z_stream *z = o->z;
	if (!z)
		return o->err;
	o->z = NULL;
	if (!o->err) {
		o->z = z;
		zstage(o);
		zpump(o, NULL, 0, Z_FINISH);
		o->z = NULL;
	}
	o->nzin = 0;
	o->rows = 0;
	deflateEnd(z);
	free(z);
	if (o->a85) {
		a85_t a = { o->tuple, o->ntuple, o->col, 0, o, 0, { 0 } };
		a85_end(&a);
		o->a85 = 0;
	}
	if (zlen)
		*zlen = o->zout;
	return o->err;
}

/* ---- the writer's formatting calls ---- */

/* Bytes for the compressor, gathered in zin. */
static int zput(pse_out_t *o, const void *p, size_t n)
{
	if (o->nzin + n > sizeof o->zin && zstage(o))
		return o->err;
	if (n > sizeof o->zin)
		return zpump(o, p, n, Z_NO_FLUSH);
	memcpy(o->zin + o->nzin, p, n);
	o->nzin += n;
	return 0;
}

/* Bytes into TIFF predictor 2 rows: each byte less the one a sample (rows bytes) before it in
 * the same row; a row's first sample stays as it is. */
static int rows_put(pse_out_t *o, const uint8_t *p, size_t n)
{
	uint8_t b[4096];
	size_t m = 0;
	for (size_t k = 0; k < n; k++) {
		unsigned j = o->rowpos % o->rows;
		b[m++] = (uint8_t)(o->rowpos < o->rows ? p[k] : p[k] - o->prev[j]);
		o->prev[j] = p[k];
		if (++o->rowpos == o->rowlen)
			o->rowpos = 0;
		if (m == sizeof b) {
			zput(o, b, m);
			m = 0;
		}
	}
	if (m)
		zput(o, b, m);
	return o->err;
}

int pse_rows_begin(pse_out_t *o, unsigned w, unsigned columns)
{
	if (!o->z || w == 0 || w > PSE_ROW_MAX || columns == 0 || columns > (1u << 20))
		return o->err ? o->err : (o->err = META_EIO);
	o->rows = w;
	o->rowlen = (size_t)w * columns;
	o->rowpos = 0;
	return o->err;
}

unsigned pse_rows_col(const pse_out_t *o)
{
	return o->rows ? (unsigned)(o->rowpos % o->rows) : 0;
}

/* Write c until the position is a multiple of `unit` bytes into the row. */
static int rows_fill(pse_out_t *o, char c, size_t unit)
{
	uint8_t b[256];
	memset(b, (unsigned char)c, sizeof b);
	while (!o->err && o->rowpos % unit) {
		size_t k = unit - o->rowpos % unit;
		rows_put(o, b, k < sizeof b ? k : sizeof b);
	}
	return o->err;
}

int pse_rows_pad(pse_out_t *o, char c)
{
	return o->rows ? rows_fill(o, c, o->rows) : o->err;
}

int pse_rows_end(pse_out_t *o, char c)
{
	return o->rows ? rows_fill(o, c, o->rowlen) : o->err;
}

int pse_write(pse_out_t *o, const void *p, size_t n)
{
	if (o->err)
		return o->err;
	if (o->z)
		return o->rows ? rows_put(o, p, n) : zput(o, p, n);
	return raw(o, p, n);
}

int pse_puts(pse_out_t *o, const char *s)
{
	return pse_write(o, s, strlen(s));
}

int pse_int(pse_out_t *o, long long v)
{
	char b[24], *e = b + sizeof b, *p = e;
	unsigned long long u = v < 0 ? 0ULL - (unsigned long long)v : (unsigned long long)v;
	do {
		*--p = (char)('0' + u % 10);
		u /= 10;
	} while (u);
	if (v < 0)
		*--p = '-';
	return pse_write(o, p, (size_t)(e - p));
}

int pse_fix(pse_out_t *o, long long t)
{
	char b[32];
	unsigned long long u = t < 0 ? 0ULL - (unsigned long long)t : (unsigned long long)t;
	unsigned frac = (unsigned)(u % 1000);
	int n;
	if (frac == 0)
		n = snprintf(b, sizeof b, "%s%llu", t < 0 ? "-" : "", u / 1000);
	else if (frac % 100 == 0)
		n = snprintf(b, sizeof b, "%s%llu.%u", t < 0 ? "-" : "", u / 1000, frac / 100);
	else if (frac % 10 == 0)
		n = snprintf(b, sizeof b, "%s%llu.%02u", t < 0 ? "-" : "", u / 1000, frac / 10);
	else
		n = snprintf(b, sizeof b, "%s%llu.%03u", t < 0 ? "-" : "", u / 1000, frac);
	return pse_write(o, b, (size_t)n);
}

int pse_real(pse_out_t *o, double v, int decimals)
{
	char b[64];
	int n = snprintf(b, sizeof b, "%.*f", decimals, v);
	if (n <= 0 || (size_t)n >= sizeof b)
		return o->err = META_EIO;
	if (strchr(b, '.')) {
		while (b[n - 1] == '0')
			b[--n] = 0;
		if (b[n - 1] == '.')
			b[--n] = 0;
	}
	if (strcmp(b, "-0") == 0)
		return pse_write(o, "0", 1);
	return pse_write(o, b, (size_t)n);
}

int pse_printf(pse_out_t *o, const char *fmt, ...)
{
	char b[1024];
	va_list ap;
	va_start(ap, fmt);
	int n = vsnprintf(b, sizeof b, fmt, ap);
	va_end(ap);
	if (n < 0 || (size_t)n >= sizeof b)
		return o->err = META_EIO;
	return pse_write(o, b, (size_t)n);
}

int pse_spool(pse_out_t *o)
{
	if (o->err || pse_flush(o))
		return o->err;
	o->spool = tmpfile();
	return o->spool ? 0 : (o->err = META_EIO);
}

void *pse_spool_end(pse_out_t *o)
{
	FILE *f = o->spool;
	if (!f)
		return NULL;
	if (!o->err && o->n && fwrite(o->buf, 1, o->n, f) != o->n)
		o->err = META_EIO;
	o->n = 0;
	o->spool = NULL;
	return f;
}

int pse_spool_copy(pse_out_t *o, void *spool)
{
	FILE *f = spool;
	uint8_t b[1 << 15];
	size_t got;
	if (!o->err && (fflush(f) || fseek(f, 0, SEEK_SET)))
		o->err = META_EIO;
	while (!o->err && (got = fread(b, 1, sizeof b, f)) > 0)
		raw(o, b, got);
	if (!o->err && ferror(f))
		o->err = META_EIO;
	fclose(f);
	return o->err;
}

int pse_flush(pse_out_t *o)
{
	if (o->err)
		return o->err;
	if (o->n && drain(o, o->buf, o->n))
		return o->err = META_EIO;
	o->n = 0;
	if (!o->spool && o->t && io_flush(o->t))
		return o->err = META_EIO;
	return 0;
}

/* ---- RunLength, Flate, hex on whole buffers ---- */

size_t pse_rle_bound(size_t n)
{
	return n + n / 128 + 2;
}

size_t pse_rle_encode(const uint8_t *in, size_t n, uint8_t *out)
{
	size_t i = 0, o = 0;
	while (i < n) {
		size_t run = 1;
		while (i + run < n && run < 128 && in[i + run] == in[i])
			run++;
		if (run >= 2) {
			out[o++] = (uint8_t)(257 - run);
			out[o++] = in[i];
			i += run;
			continue;
		}
		/* literal: up to 128 bytes, stopping before a run of 3 (a run of 2 inside a literal
		 * costs no more than breaking it) */
		size_t lit = 1;
		while (i + lit < n && lit < 128 &&
				!(i + lit + 2 < n && in[i + lit] == in[i + lit + 1] && in[i + lit] == in[i + lit + 2]))
			lit++;
		out[o++] = (uint8_t)(lit - 1);
		memcpy(out + o, in + i, lit);
		o += lit;
		i += lit;
	}
	out[o++] = 128;
	return o;
}

int pse_flate_encode(const uint8_t *in, size_t n, int level, uint8_t **out, size_t *outlen)
{
	uLongf cap = compressBound((uLong)n);
	uint8_t *b = malloc(cap ? cap : 1);
	if (!b)
		return META_ENOMEM;
	if (compress2(b, &cap, in, (uLong)n, level) != Z_OK) {
		free(b);
		return META_ENOMEM;
	}
	*out = b;
	*outlen = cap;
	return 0;
}

size_t pse_hex_size(size_t n)
{
	return 2 * n + (2 * n + 77) / 78 + (n == 0);
}

int pse_hex_write(pse_out_t *o, const uint8_t *in, size_t n)
{
	static const char hx[] = "0123456789abcdef";
	char line[80];
	size_t k = 0;
	if (n == 0)
		return pse_write(o, "\n", 1);
	while (k < n) {
		size_t m = 0;
		for (; m < 78 && k < n; k++) {
			line[m++] = hx[in[k] >> 4];
			line[m++] = hx[in[k] & 15];
		}
		line[m++] = '\n';
		pse_write(o, line, m);
	}
	return o->err;
}
