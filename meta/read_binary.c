/* read_binary.c: the binary decoder: LEB128 and zigzag varints, delta-coded points, byte-offset errors. */
#include <string.h>
#include <stdio.h>
#include "meta_int.h"

#define AT() (r->base + r->pos)

/* Make one byte available: 1 ok, 0 end of input, <0 error. */
static int need_slow(meta_reader_t *r)
{
	while (r->pos >= r->end) {
		if (r->eof)
			return 0;
		if (meta_rd_fill(r) < 0)
			return r->state;
	}
	return 1;
}

static int truncated(meta_reader_t *r, const char *kw)
{
	return meta_rd_fail(r, META_ESYNTAX, r->base + r->end,
	                    "expected the rest of '%s', found end of file (truncated?)", kw);
}

/* Next byte into *c, or the error/truncation code. */
static inline int byte(meta_reader_t *r, const char *kw, unsigned *c)
{
	if (r->pos >= r->end) {
		int k = need_slow(r);
		if (k <= 0)
			return k < 0 ? k : truncated(r, kw);
	}
	*c = r->buf[r->pos++];
	return 0;
}

static int varint_slow(meta_reader_t *r, const char *kw, uint32_t *out)
{
	uint64_t at = AT();
	uint32_t v = 0;
	unsigned c = 0;
	int i, rc;
	for (i = 0;; i++) {
		if ((rc = byte(r, kw, &c)) < 0)
			return rc;
		if (i == 4 && c > 0x0f)
			return meta_rd_fail(r, META_ESYNTAX, at, "expected a varint of at most 32 bits in '%s', found a longer one", kw);
		v |= (uint32_t)(c & 0x7f) << (7 * i);
		if (!(c & 0x80))
			break;
	}
	if (c == 0 && i > 0)
		return meta_rd_fail(r, META_ESYNTAX, at, "expected a canonical (shortest) varint in '%s', found %d bytes", kw, i + 1);
	*out = v;
	return 0;
}

/* Varints of up to 3 bytes straight from the buffer; the rest byte by byte. */
static inline int varint(meta_reader_t *r, const char *kw, uint32_t *out)
{
	if (r->end - r->pos >= 3) {
		const unsigned char *b = r->buf + r->pos;
		if (b[0] < 0x80) {
			*out = b[0];
			r->pos += 1;
			return 0;
		}
		if (b[1] < 0x80 && b[1]) {
			*out = (uint32_t)(b[0] & 0x7f) | (uint32_t)b[1] << 7;
			r->pos += 2;
			return 0;
		}
		if (b[1] >= 0x80 && b[2] < 0x80 && b[2]) {
			*out = (uint32_t)(b[0] & 0x7f) | (uint32_t)(b[1] & 0x7f) << 7 | (uint32_t)b[2] << 14;
			r->pos += 3;
			return 0;
		}
	}
	return varint_slow(r, kw, out);
}

static int32_t unzigzag(uint32_t u)
{
	uint32_t v = (u >> 1) ^ (0u - (u & 1));
	return (int32_t)v;
}

/* A value of thousandths in the canonical text form of §2 (how §6 shows values found). */
static const char *fix64(int64_t v, char *buf)
{
	uint64_t m = v < 0 ? (uint64_t)-(v + 1) + 1 : (uint64_t)v;
	unsigned frac = (unsigned)(m % 1000);
	int k = snprintf(buf, 32, "%s%llu", v < 0 ? "-" : "", (unsigned long long)(m / 1000));
	if (frac) {
		k += snprintf(buf + k, 32 - (size_t)k, ".%03u", frac);
		while (buf[k - 1] == '0')
			buf[--k] = 0;
	}
	return buf;
}

static int number(meta_reader_t *r, const char *kw, meta_fix_t *out)
{
	char vb[32];
	uint64_t at = AT();
	uint32_t u;
	int rc = varint(r, kw, &u);
	int32_t v;
	if (rc < 0)
		return rc;
	v = unzigzag(u);
	if (v > META_MAX_COORD || v < -META_MAX_COORD)
		return meta_rd_fail(r, META_ELIMIT, at, "expected a number from -1000000 to 1000000 in '%s', found '%s'",
		                    kw, fix64(v, vb));
	*out = v;
	return 0;
}

/* A delta-coded coordinate: the reference plus the stored difference. */
static inline int delta(meta_reader_t *r, const char *kw, int32_t *ref, meta_fix_t *out)
{
	char vb[32];
	uint64_t at = AT();
	uint32_t u;
	int rc = varint(r, kw, &u);
	int64_t v;
	if (rc < 0)
		return rc;
	v = (int64_t)*ref + unzigzag(u);
	if (v > META_MAX_COORD || v < -META_MAX_COORD)
		return meta_rd_fail(r, META_ELIMIT, at, "expected a coordinate from -1000000 to 1000000 in '%s', found '%s' (reference plus delta)",
		                    kw, fix64(v, vb));
	*out = *ref = (int32_t)v;
	return 0;
}

static int colour(meta_reader_t *r, const char *kw, meta_rgb_t *rgb)
{
	unsigned a = 0, b = 0, c = 0;
	int rc;
	if ((rc = byte(r, kw, &a)) < 0 || (rc = byte(r, kw, &b)) < 0 || (rc = byte(r, kw, &c)) < 0)
		return rc;
	*rgb = (meta_rgb_t)(a << 16 | b << 8 | c);
	return 0;
}

static int string(meta_reader_t *r, const char *kw, meta_cmd_t *cmd)
{
	uint64_t at = AT();
	uint32_t len, got = 0;
	int rc = varint(r, kw, &len);
	if (rc < 0)
		return rc;
	if (len > META_MAX_STRING)
		return meta_rd_fail(r, META_ELIMIT, at, "expected a string of at most %d bytes in '%s', found %u bytes",
		                    META_MAX_STRING, kw, len);
	while (got < len) {
		size_t k;
		if (r->pos >= r->end && (rc = need_slow(r)) <= 0)
			return rc < 0 ? rc : truncated(r, kw);
		k = r->end - r->pos;
		if (k > len - got)
			k = len - got;
		memcpy(r->str + got, r->buf + r->pos, k);
		/* a byte no string may hold is reported at its own offset (§6) */
		int comment = cmd->op == META_COMMENT;
		for (size_t j = 0; j < k; j++) {
			unsigned char c = r->buf[r->pos + j];
			if (c == 0 || (comment && (c == '\n' || c == '\r')))
				return meta_rd_fail(r, META_ESYNTAX, AT() + j, "expected no %s byte in a %s, found 0x%02x",
				                    c ? "line-break" : "NUL", comment ? "comment" : "string", c);
		}
		r->pos += k;
		got += (uint32_t)k;
	}
	r->str[len] = 0;
	cmd->str = r->str;
	cmd->len = len;
	return 0;
}

static int runs(meta_reader_t *r, meta_cmd_t *cmd)
{
	uint64_t at = AT();
	uint32_t n, i, width = r->chk.rows_left ? r->chk.image_w : 0;
	uint64_t sum = 0;
	int rc = varint(r, "row", &n);
	if (rc < 0)
		return rc;
	if (n > META_MAX_DIM || (width && n > width))
		return meta_rd_fail(r, META_ELIMIT, at, "expected at most %u runs in 'row', found %u runs",
		                    width ? width : META_MAX_DIM, n);
	if (meta_rd_runs(r, n, at) < 0)
		return r->state;
	for (i = 0; i < n; i++) {
		uint64_t rat = AT();
		if ((rc = varint(r, "row", &r->runs[i].count)) < 0 || (rc = colour(r, "row", &r->runs[i].rgb)) < 0)
			return rc;
		if (r->runs[i].count == 0)
			return meta_rd_fail(r, META_ESYNTAX, rat, "expected a run count of 1 or more in 'row', found '0'");
		sum += r->runs[i].count;
		if (width && sum > width)
			return meta_rd_fail(r, META_ESYNTAX, rat, "expected runs adding up to the image width %u, found %llu by run %u",
			                    width, (unsigned long long)sum, i + 1);
	}
	if (width && sum != width)
		return meta_rd_fail(r, META_ESYNTAX, at, "expected runs adding up to the image width %u, found %llu",
		                    width, (unsigned long long)sum);
	cmd->runs = r->runs;
	cmd->nruns = n;
	return 0;
}

int meta_binary_header(meta_reader_t *r)
{
	size_t i;
	r->binary = 1;
	while (r->end - r->pos < 9 && !r->eof)
		if (meta_rd_fill(r) < 0)
			return r->state;
	for (i = 0; i < 8; i++) {
		if (r->pos + i >= r->end)
			return meta_rd_fail(r, META_EVERSION, r->base + r->end, "expected the binary magic 8b 4c 4d 42 0d 0a 1a 0a, found end of file");
		if (r->buf[r->pos + i] != meta_magic[i])
			return meta_rd_fail(r, META_EVERSION, r->base + r->pos + i,
			                    "expected the binary magic 8b 4c 4d 42 0d 0a 1a 0a, found 0x%02x here (damaged by a text-mode transfer?)",
			                    r->buf[r->pos + i]);
	}
	if (r->pos + 8 >= r->end)
		return meta_rd_fail(r, META_EVERSION, r->base + r->end, "expected the version byte, found end of file");
	if (r->buf[r->pos + 8] != META_VERSION)
		return meta_rd_fail(r, META_EVERSION, r->base + r->pos + 8,
		                    "unsupported meta-language version %u (this reader knows %d)", r->buf[r->pos + 8], META_VERSION);
	r->pos += 9;
	return 0;
}

int meta_read_binary(meta_reader_t *r, meta_cmd_t *cmd)
{
	const char *sig, *kw;
	unsigned c = 0;
	int i, rc, fi = 0, ui = 0;
	meta_op_t op;
	if (r->pos >= r->end && (rc = need_slow(r)) <= 0)
		return rc;
	r->stmt_pos = r->opos[7] = AT();
	c = r->buf[r->pos++];
	if (!meta_op_by_code[c])
		return meta_rd_fail(r, META_ESYNTAX, r->stmt_pos, "unknown opcode 0x%02x", c);
	op = (meta_op_t)(meta_op_by_code[c] - 1);
	memset(cmd, 0, sizeof *cmd);
	cmd->op = op;
	kw = meta_ops[op].kw;
	sig = meta_ops[op].sig;
	if (op == META_MOVE || op == META_DRAW) {
		r->opos[0] = AT();
		if ((rc = delta(r, kw, &r->refx, &cmd->f[0])) < 0)
			return rc;
		r->opos[1] = AT();
		return (rc = delta(r, kw, &r->refy, &cmd->f[1])) < 0 ? rc : 1;
	}
	if (op == META_PAGE)
		r->refx = r->refy = 0;
	for (i = 0; sig[i]; i++) {
		r->opos[i] = AT();
		switch (sig[i]) {
		case 'f':
			rc = number(r, kw, &cmd->f[fi++]);
			break;
		case 'u':
			rc = varint(r, kw, &cmd->u[ui++]);
			break;
		case 'c':
			rc = colour(r, kw, &cmd->rgb);
			break;
		case 'k':
			if ((rc = byte(r, kw, &c)) == 0) {
				if ((int)c >= meta_ops[op].nwords)
					return meta_rd_fail(r, META_ESYNTAX, r->opos[i], "expected a keyword index below %d in '%s', found '%u'",
					                    meta_ops[op].nwords, kw, c);
				cmd->k = (int)c;
			}
			break;
		case 's':
			rc = string(r, kw, cmd);
			break;
		case 'L': {
			uint32_t n, j;
			if ((rc = varint(r, kw, &n)) < 0)
				return rc;
			if (n > META_MAX_DASH)
				return meta_rd_fail(r, META_ELIMIT, r->opos[i], "expected at most %d dash lengths, found %u lengths",
				                    META_MAX_DASH, n);
			for (j = 0; j < n && rc == 0; j++) {
				uint64_t at = AT();
				char vb[32];
				if ((rc = number(r, kw, &r->list[j])) == 0 && r->list[j] <= 0)
					return meta_rd_fail(r, META_ESYNTAX, at, "expected dash lengths > 0, found '%s'",
					                    fix64(r->list[j], vb));
			}
			cmd->list = r->list;
			cmd->nlist = n;
			break;
		}
		case 'R':
			rc = runs(r, cmd);
			break;
		default:
			rc = 0;
		}
		if (rc < 0)
			return rc;
	}
	return 1;
}
