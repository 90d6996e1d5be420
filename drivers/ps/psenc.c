/* psenc.c: PostScript/PDF encoders over the device writer: streaming Flate and ASCII85, RunLength and hex. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>
#include "locus_meta.h"
#include "ps/psenc.h"

#define A85_COLS 75

/* The compressed stream's state, the writer's filter_user between pse_deflate_begin and
 * pse_deflate_end. */
typedef struct {
	z_stream z;
	int a85;                    /* 1: compressed bytes go through ASCII85 */
	uint32_t tuple;             /* ASCII85: bytes of the open group */
	int ntuple, col;            /* ASCII85: bytes in the group, output column */
	uint64_t zout;              /* bytes the compressor produced (before ASCII85) */
	size_t nzin;                /* bytes in zin, waiting for the compressor */
	unsigned rows;              /* TIFF predictor samples of this many bytes (0: none), see pse_rows_begin */
	size_t rowlen;              /* bytes of a predictor row */
	size_t rowpos;              /* bytes of the current row written */
	unsigned char prev[PSE_ROW_MAX];  /* the last sample's bytes (by position in the sample) */
	unsigned char zin[1 << 16]; /* what is to be compressed, gathered for fewer deflate calls */
} pse_z_t;

static int zfilter(dev_writer_t *o, const void *p, size_t n);

/* The stream's state while compressing, else NULL. */
static pse_z_t *zstate(const dev_writer_t *o)
{
	return o->filter == zfilter ? o->filter_user : NULL;
}

/* ---- ASCII85: one state machine for streaming, whole buffers and size counting ---- */

typedef struct {
	uint32_t tuple;
	int ntuple, col;
	size_t count;         /* bytes produced (counting) */
	dev_writer_t *o;         /* NULL: only count */
	int nl;               /* characters in line (a line is passed on whole) */
	char line[96];
} a85_t;

static void a85_out(a85_t *a)
{
	if (a->o && a->nl)
		dev_w_raw(a->o, a->line, (size_t)a->nl);
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

int pse_a85_write(dev_writer_t *o, const uint8_t *in, size_t n)
{
	a85_t a = { 0, 0, 0, 0, o, 0, { 0 } };
	a85_bytes(&a, in, n);
	a85_end(&a);
	return o->err;
}

/* ---- compressed output ---- */

/* Pass compressed bytes on: raw, or through the stream's ASCII85 state. */
static void zsink(dev_writer_t *o, pse_z_t *s, const uint8_t *p, size_t n)
{
	s->zout += n;
	if (!s->a85) {
		dev_w_raw(o, p, n);
		return;
	}
	a85_t a = { s->tuple, s->ntuple, s->col, 0, o, 0, { 0 } };
	a85_bytes(&a, p, n);
	s->tuple = a.tuple;
	s->ntuple = a.ntuple;
	s->col = a.col;
}

static int zpump(dev_writer_t *o, pse_z_t *s, const void *p, size_t n, int flush)
{
	z_stream *z = &s->z;
	uint8_t tmp[1 << 15];
	z->next_in = (Bytef *)p;
	z->avail_in = (uInt)n;
	do {
		z->next_out = tmp;
		z->avail_out = sizeof tmp;
		int rc = deflate(z, flush);
		if (rc == Z_STREAM_ERROR)
			return o->err = META_EIO;
		zsink(o, s, tmp, sizeof tmp - z->avail_out);
	} while (z->avail_out == 0 || (flush == Z_FINISH && z->avail_in));
	return o->err;
}

/* Compress what is gathered in zin. */
static int zstage(dev_writer_t *o, pse_z_t *s)
{
	size_t n = s->nzin;
	s->nzin = 0;
	return n ? zpump(o, s, s->zin, n, Z_NO_FLUSH) : o->err;
}

int pse_deflate_begin(dev_writer_t *o, int a85, int level)
{
	if (o->err)
		return o->err;
	pse_z_t *s = calloc(1, sizeof *s);
	int huff = level == PSE_HUFFMAN, text = level == PSE_TEXT || level == PSE_ROWS;
	if (!s || deflateInit2(&s->z, huff ? 1 : text ? 9 : level, Z_DEFLATED, 15, text ? 9 : 8,
			huff ? Z_HUFFMAN_ONLY : text ? Z_FILTERED : Z_DEFAULT_STRATEGY) != Z_OK) {
		free(s);
		return o->err = META_ENOMEM;
	}
	if (level == PSE_TEXT)
		deflateTune(&s->z, 8, 8, 24, 40);
	else if (level == PSE_ROWS)
		deflateTune(&s->z, 8, 16, 128, 64);
	s->a85 = a85;
	dev_w_set_filter(o, zfilter, s);
	return 0;
}

int pse_deflate_level(dev_writer_t *o, int level)
{
	pse_z_t *s = zstate(o);
	uint8_t tmp[1 << 15];
	int rc;
	if (!s || o->err || zstage(o, s))
		return o->err;
	z_stream *z = &s->z;
	do {
		z->next_in = NULL;
		z->avail_in = 0;
		z->next_out = tmp;
		z->avail_out = sizeof tmp;
		rc = deflateParams(z, level == PSE_HUFFMAN ? 1 : level,
			level == PSE_HUFFMAN ? Z_HUFFMAN_ONLY : Z_DEFAULT_STRATEGY);
		zsink(o, s, tmp, sizeof tmp - z->avail_out);
	} while (rc == Z_BUF_ERROR && z->avail_out == 0);
	return rc == Z_OK || rc == Z_BUF_ERROR ? o->err : (o->err = META_EIO);
}

int pse_deflate_end(dev_writer_t *o, uint64_t *zlen)
{
	pse_z_t *s = zstate(o);
	if (!s)
		return o->err;
	dev_w_set_filter(o, NULL, NULL);
	if (!o->err) {
		zstage(o, s);
		zpump(o, s, NULL, 0, Z_FINISH);
	}
	deflateEnd(&s->z);
	if (s->a85) {
		a85_t a = { s->tuple, s->ntuple, s->col, 0, o, 0, { 0 } };
		a85_end(&a);
	}
	if (zlen)
		*zlen = s->zout;
	free(s);
	return o->err;
}

/* ---- the filter: bytes into the compressor ---- */

/* Bytes for the compressor, gathered in zin. */
static int zput(dev_writer_t *o, pse_z_t *s, const void *p, size_t n)
{
	if (s->nzin + n > sizeof s->zin && zstage(o, s))
		return o->err;
	if (n > sizeof s->zin)
		return zpump(o, s, p, n, Z_NO_FLUSH);
	memcpy(s->zin + s->nzin, p, n);
	s->nzin += n;
	return 0;
}

/* Bytes into TIFF predictor 2 rows: each byte less the one a sample (rows bytes) before it in
 * the same row; a row's first sample stays as it is. */
static int rows_put(dev_writer_t *o, pse_z_t *s, const uint8_t *p, size_t n)
{
	uint8_t b[4096];
	size_t m = 0;
	for (size_t k = 0; k < n; k++) {
		unsigned j = s->rowpos % s->rows;
		b[m++] = (uint8_t)(s->rowpos < s->rows ? p[k] : p[k] - s->prev[j]);
		s->prev[j] = p[k];
		if (++s->rowpos == s->rowlen)
			s->rowpos = 0;
		if (m == sizeof b) {
			zput(o, s, b, m);
			m = 0;
		}
	}
	if (m)
		zput(o, s, b, m);
	return o->err;
}

static int zfilter(dev_writer_t *o, const void *p, size_t n)
{
	pse_z_t *s = o->filter_user;
	return s->rows ? rows_put(o, s, p, n) : zput(o, s, p, n);
}

int pse_rows_begin(dev_writer_t *o, unsigned w, unsigned columns)
{
	pse_z_t *s = zstate(o);
	if (!s || w == 0 || w > PSE_ROW_MAX || columns == 0 || columns > (1u << 20))
		return o->err ? o->err : (o->err = META_EIO);
	s->rows = w;
	s->rowlen = (size_t)w * columns;
	s->rowpos = 0;
	return o->err;
}

unsigned pse_rows_col(const dev_writer_t *o)
{
	const pse_z_t *s = zstate(o);
	return s && s->rows ? (unsigned)(s->rowpos % s->rows) : 0;
}

/* Write c until the position is a multiple of `unit` bytes into the row. */
static int rows_fill(dev_writer_t *o, pse_z_t *s, char c, size_t unit)
{
	uint8_t b[256];
	memset(b, (unsigned char)c, sizeof b);
	while (!o->err && s->rowpos % unit) {
		size_t k = unit - s->rowpos % unit;
		rows_put(o, s, b, k < sizeof b ? k : sizeof b);
	}
	return o->err;
}

int pse_rows_pad(dev_writer_t *o, char c)
{
	pse_z_t *s = zstate(o);
	return s && s->rows ? rows_fill(o, s, c, s->rows) : o->err;
}

int pse_rows_end(dev_writer_t *o, char c)
{
	pse_z_t *s = zstate(o);
	return s && s->rows ? rows_fill(o, s, c, s->rowlen) : o->err;
}

/* ---- the EPS spool: a temporary file as the writer's sink ---- */

static int spool_sink(void *user, const void *p, size_t n)
{
	return fwrite(p, 1, n, user) == n ? 0 : -1;
}

int pse_spool(dev_writer_t *o)
{
	if (o->err || dev_w_flush(o))
		return o->err;
	FILE *f = tmpfile();
	if (!f)
		return o->err = META_EIO;
	dev_w_set_sink(o, spool_sink, f);
	return 0;
}

void *pse_spool_end(dev_writer_t *o)
{
	if (o->sink != spool_sink)
		return NULL;
	FILE *f = o->sink_user;
	dev_w_drain(o);
	o->n = 0;
	dev_w_set_sink(o, NULL, NULL);
	return f;
}

int pse_spool_copy(dev_writer_t *o, void *spool)
{
	FILE *f = spool;
	uint8_t b[1 << 15];
	size_t got;
	if (!o->err && (fflush(f) || fseek(f, 0, SEEK_SET)))
		o->err = META_EIO;
	while (!o->err && (got = fread(b, 1, sizeof b, f)) > 0)
		dev_w_raw(o, b, got);
	if (!o->err && ferror(f))
		o->err = META_EIO;
	fclose(f);
	return o->err;
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

int pse_hex_write(dev_writer_t *o, const uint8_t *in, size_t n)
{
	static const char hx[] = "0123456789abcdef";
	char line[80];
	size_t k = 0;
	if (n == 0)
		return dev_w_write(o, "\n", 1);
	while (k < n) {
		size_t m = 0;
		for (; m < 78 && k < n; k++) {
			line[m++] = hx[in[k] >> 4];
			line[m++] = hx[in[k] & 15];
		}
		line[m++] = '\n';
		dev_w_write(o, line, m);
	}
	return o->err;
}
