/* writer.c: the writer: validates each statement and encodes it as canonical text or binary into a buffered callback. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "meta_int.h"

static const char hexdig[] = "0123456789abcdef";

meta_writer_t *meta_writer_new(meta_write_fn fn, void *user, int encoding)
{
	meta_writer_t *w = calloc(1, sizeof *w);
	if (!w)
		return NULL;
	w->buf = malloc(META_WRITE_BUF);
	if (!w->buf) {
		free(w);
		return NULL;
	}
	w->fn = fn;
	w->user = user;
	w->enc = encoding == META_ENC_BINARY ? META_ENC_BINARY : META_ENC_TEXT;
	meta_wr_defaults(w);
	return w;
}

void meta_wr_defaults(meta_writer_t *w)
{
	w->colour = 0x000000;
	w->width = META_FIX_ONE;
	w->miter = 10 * META_FIX_ONE;
	w->cap = META_CAP_BUTT;
	w->join = META_JOIN_MITER;
	w->rule = META_RULE_NON_ZERO;
	w->ndash = 0;
}

int meta_wr_fail(meta_writer_t *w, int code, const char *what, const char *fmt, ...)
{
	char msg[400];
	va_list ap;
	va_start(ap, fmt);
	if (vsnprintf(msg, sizeof msg, fmt, ap) < 0)
		msg[0] = 0;
	va_end(ap);
	meta_fmt(w->err, sizeof w->err, "%s: %s", what, msg);
	return code;
}

static int flush(meta_writer_t *w)
{
	if (w->n && w->state == 0 && w->fn(w->user, w->buf, w->n) < 0) {
		w->state = META_EIO;
		meta_wr_fail(w, META_EIO, "meta writer", "write error");
	}
	w->n = 0;
	return w->state;
}

/* Make room for k more bytes (k <= META_WRITE_BUF). */
static inline int room(meta_writer_t *w, size_t k)
{
	if (w->n + k > META_WRITE_BUF)
		return flush(w);
	return 0;
}

static inline void put(meta_writer_t *w, const void *p, size_t k)
{
	memcpy(w->buf + w->n, p, k);
	w->n += k;
}

static inline void put_varint(meta_writer_t *w, uint32_t v)
{
	while (v >= 0x80) {
		w->buf[w->n++] = (unsigned char)(v | 0x80);
		v >>= 7;
	}
	w->buf[w->n++] = (unsigned char)v;
}

static inline void put_zigzag(meta_writer_t *w, int32_t v)
{
	put_varint(w, ((uint32_t)v << 1) ^ (uint32_t)(v >> 31));
}

static inline void put_uint_text(meta_writer_t *w, uint32_t v)
{
	char tmp[12];
	int k = 0;
	w->buf[w->n++] = ' ';
	do {
		tmp[k++] = (char)('0' + v % 10);
		v /= 10;
	} while (v);
	while (k)
		w->buf[w->n++] = (unsigned char)tmp[--k];
}

static inline void put_fix_text(meta_writer_t *w, meta_fix_t v)
{
	w->buf[w->n++] = ' ';
	w->n += (size_t)meta_fix_format(v, (char *)w->buf + w->n);
}

static inline void put_colour_text(meta_writer_t *w, meta_rgb_t c)
{
	unsigned char *b = w->buf + w->n;
	int i;
	b[0] = ' ';
	b[1] = '#';
	for (i = 0; i < 6; i++)
		b[2 + i] = (unsigned char)hexdig[(c >> (20 - 4 * i)) & 15];
	w->n += 8;
}

static void put_string_text(meta_writer_t *w, const unsigned char *s, size_t len)
{
	size_t i = 0;
	w->buf[w->n++] = ' ';
	w->buf[w->n++] = '"';
	while (i < len) {
		unsigned c = s[i];
		int k;
		if (c == '"' || c == '\\') {
			w->buf[w->n++] = '\\';
			w->buf[w->n++] = (unsigned char)c;
			i++;
		} else if (c >= 0x20 && c < 0x7f) {
			w->buf[w->n++] = (unsigned char)c;
			i++;
		} else if (c >= 0x80 && (k = meta_utf8_len(s + i, len - i)) > 0) {
			put(w, s + i, (size_t)k);
			i += (size_t)k;
		} else {
			w->buf[w->n++] = '\\';
			w->buf[w->n++] = 'x';
			w->buf[w->n++] = (unsigned char)hexdig[c >> 4];
			w->buf[w->n++] = (unsigned char)hexdig[c & 15];
			i++;
		}
	}
	w->buf[w->n++] = '"';
}

static int encode_text(meta_writer_t *w, const meta_cmd_t *cmd)
{
	const meta_opinfo_t *o = &meta_ops[cmd->op];
	const char *sig = o->sig;
	int i, fi = 0, ui = 0;
	size_t j;
	if (room(w, 4 * META_MAX_STRING + 64) < 0)
		return w->state;
	if (cmd->op == META_COMMENT) {
		w->buf[w->n++] = '#';
		if (cmd->len) {
			w->buf[w->n++] = ' ';
			put(w, cmd->str, cmd->len);
		}
		w->buf[w->n++] = '\n';
		return 0;
	}
	put(w, o->kw, o->kwlen);
	for (i = 0; sig[i]; i++) {
		switch (sig[i]) {
		case 'f': put_fix_text(w, cmd->f[fi++]); break;
		case 'u': put_uint_text(w, cmd->u[ui++]); break;
		case 'c': put_colour_text(w, cmd->rgb); break;
		case 'k':
			w->buf[w->n++] = ' ';
			put(w, o->words[cmd->k], strlen(o->words[cmd->k]));
			break;
		case 's': put_string_text(w, (const unsigned char *)cmd->str, cmd->len); break;
		case 'L':
			for (j = 0; j < cmd->nlist; j++)
				put_fix_text(w, cmd->list[j]);
			break;
		case 'R':
			for (j = 0; j < cmd->nruns; j++) {
				if (room(w, 32) < 0)
					return w->state;
				put_uint_text(w, cmd->runs[j].count);
				put_colour_text(w, cmd->runs[j].rgb);
			}
			break;
		}
	}
	w->buf[w->n++] = '\n';
	return 0;
}

static int encode_binary(meta_writer_t *w, const meta_cmd_t *cmd)
{
	const meta_opinfo_t *o = &meta_ops[cmd->op];
	const char *sig = o->sig;
	int i, fi = 0, ui = 0;
	size_t j;
	if (room(w, META_MAX_STRING + 64) < 0)
		return w->state;
	w->buf[w->n++] = o->code;
	if (cmd->op == META_MOVE || cmd->op == META_DRAW) {
		put_zigzag(w, cmd->f[0] - w->refx);
		put_zigzag(w, cmd->f[1] - w->refy);
		w->refx = cmd->f[0];
		w->refy = cmd->f[1];
		return 0;
	}
	if (cmd->op == META_PAGE)
		w->refx = w->refy = 0;
	for (i = 0; sig[i]; i++) {
		switch (sig[i]) {
		case 'f': put_zigzag(w, cmd->f[fi++]); break;
		case 'u': put_varint(w, cmd->u[ui++]); break;
		case 'c': {
			unsigned char b[3] = { (unsigned char)(cmd->rgb >> 16), (unsigned char)(cmd->rgb >> 8),
			                       (unsigned char)cmd->rgb };
			put(w, b, 3);
			break;
		}
		case 'k': w->buf[w->n++] = (unsigned char)cmd->k; break;
		case 's':
			put_varint(w, (uint32_t)cmd->len);
			put(w, cmd->str, cmd->len);
			break;
		case 'L':
			put_varint(w, (uint32_t)cmd->nlist);
			for (j = 0; j < cmd->nlist; j++)
				put_zigzag(w, cmd->list[j]);
			break;
		case 'R':
			put_varint(w, (uint32_t)cmd->nruns);
			for (j = 0; j < cmd->nruns; j++) {
				unsigned char b[3];
				meta_rgb_t c = cmd->runs[j].rgb;
				if (room(w, 16) < 0)
					return w->state;
				put_varint(w, cmd->runs[j].count);
				b[0] = (unsigned char)(c >> 16), b[1] = (unsigned char)(c >> 8), b[2] = (unsigned char)c;
				put(w, b, 3);
			}
			break;
		}
	}
	return 0;
}

/* Keep the convenience state in step with what was written. */
static void track(meta_writer_t *w, const meta_cmd_t *cmd)
{
	switch (cmd->op) {
	case META_PAGE: meta_wr_defaults(w); break;
	case META_COLOUR: w->colour = cmd->rgb; break;
	case META_WIDTH: w->width = cmd->f[0]; break;
	case META_MITER_LIMIT: w->miter = cmd->f[0]; break;
	case META_CAP: w->cap = cmd->k; break;
	case META_JOIN: w->join = cmd->k; break;
	case META_FILL_RULE: w->rule = cmd->k; break;
	case META_DASH:
		w->ndash = cmd->nlist;
		if (cmd->nlist)
			memcpy(w->dash, cmd->list, cmd->nlist * sizeof *cmd->list);
		break;
	default: break;
	}
}

int meta_write(meta_writer_t *w, const meta_cmd_t *cmd)
{
	char msg[400];
	int where, rc;
	if (w->state < 0)
		return w->state;
	if (!cmd)
		return meta_wr_fail(w, META_EARG, "meta_write", "expected a statement, found a null pointer");
	rc = meta_check_cmd(&w->chk, cmd, &where, msg, sizeof msg);
	if (rc) {
		if (where >= 0)
			return meta_wr_fail(w, rc, "meta_write", "'%s' operand %d: %s", meta_op_name(cmd->op), where + 1, msg);
		return meta_wr_fail(w, rc, "meta_write", "'%s': %s", meta_op_name(cmd->op), msg);
	}
	if (!w->started) {
		w->started = 1;
		if (w->enc == META_ENC_BINARY) {
			put(w, meta_magic, 8);
			w->buf[w->n++] = META_VERSION;
		} else {
			put(w, "LOCUS-META 1\n", 13);
		}
	}
	rc = w->enc == META_ENC_BINARY ? encode_binary(w, cmd) : encode_text(w, cmd);
	if (rc < 0)
		return rc;
	track(w, cmd);
	return 0;
}

int meta_writer_close(meta_writer_t *w)
{
	char msg[400];
	int rc;
	if (!w)
		return 0;
	rc = flush(w);
	if (rc == 0 && w->started && meta_check_eof(&w->chk, msg, sizeof msg))
		rc = META_ESTATE; /* the output is incomplete; the message is lost with the writer */
	free(w->runs);
	free(w->buf);
	free(w);
	return rc;
}

const char *meta_writer_error(const meta_writer_t *w)
{
	return w->err;
}
