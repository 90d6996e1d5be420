/* read_text.c: the text decoder: line splitting over the reader's buffer, a hand-written tokenizer and number parser. */
#include <string.h>
#include "meta_int.h"

#define BLANK(c) ((c) == ' ' || (c) == '\t')

/* Next line [*ls, *le) without its "\n" or "\r\n". 1 ok, 0 end of input, <0 error. */
static int get_line(meta_reader_t *r, const char **ls, const char **le)
{
	size_t scan = r->pos;
	for (;;) {
		const unsigned char *nl = memchr(r->buf + scan, '\n', r->end - scan);
		size_t rel;
		if (nl) {
			size_t len = (size_t)(nl - (r->buf + r->pos));
			r->line++;
			if (len > META_MAX_LINE)
				return meta_rd_fail(r, META_ELIMIT, META_MAX_LINE + 1,
				                    "expected a line of at most %d bytes, found %zu bytes",
				                    META_MAX_LINE, len);
			*ls = (const char *)r->buf + r->pos;
			*le = (const char *)nl;
			if (*le > *ls && (*le)[-1] == '\r')
				(*le)--;
			r->pos = (size_t)(nl - r->buf) + 1;
			return 1;
		}
		if (r->end - r->pos > (size_t)META_MAX_LINE + 1) {
			r->line++;
			return meta_rd_fail(r, META_ELIMIT, META_MAX_LINE + 1,
			                    "expected a line of at most %d bytes, found a longer one", META_MAX_LINE);
		}
		if (r->eof) {
			r->line++;
			if (r->pos == r->end)
				return 0;
			/* at the end of the input, LINE+1:1 as every end-of-input error (§6) */
			r->line++;
			return meta_rd_fail(r, META_ESYNTAX, 1, "expected a newline at the end of line %llu, found end of "
			                    "file (truncated?)", (unsigned long long)(r->line - 1));
		}
		rel = r->end - r->pos;
		if (meta_rd_fill(r) < 0)
			return r->state;
		scan = r->pos + rel;
	}
}

/* "'token'" (escaped, shortened) or "end of line", for messages. */
static const char *found(const char *p, const char *le, char *buf, size_t n)
{
	size_t k = 0, i;
	if (p >= le)
		return "end of line";
	buf[k++] = '\'';
	for (i = 0; p + i < le && !BLANK(p[i]) && k + 8 < n; i++) {
		unsigned char c = (unsigned char)p[i];
		if (i == 24) {
			memcpy(buf + k, "...", 3);
			k += 3;
			break;
		}
		if (c < 0x20 || c >= 0x7f) {
			static const char hex[] = "0123456789abcdef";
			buf[k++] = '\\', buf[k++] = 'x', buf[k++] = hex[c >> 4], buf[k++] = hex[c & 15];
		} else {
			buf[k++] = (char)c;
		}
	}
	buf[k++] = '\'';
	buf[k] = 0;
	return buf;
}

/* Context for operand messages: "after 'draw'" or "for operand 2 of 'draw'". */
static const char *ctx(const char *kw, int i, char *buf, size_t n)
{
	if (i == 0)
		meta_fmt(buf, n, "after '%s'", kw);
	else
		meta_fmt(buf, n, "for operand %d of '%s'", i + 1, kw);
	return buf;
}

static const char *tok_end(const char *p, const char *le)
{
	while (p < le && !BLANK(*p))
		p++;
	return p;
}

static int hexval(int c)
{
	if (c >= '0' && c <= '9')
		return c - '0';
	c |= 0x20;
	if (c >= 'a' && c <= 'f')
		return c - 'a' + 10;
	return -1;
}

/* Colour token "#rrggbb"; returns 0 and *rgb or -1. */
static int parse_colour(const char *p, const char *q, meta_rgb_t *rgb)
{
	meta_rgb_t v = 0;
	int i;
	if (q - p != 7 || *p != '#')
		return -1;
	for (i = 1; i < 7; i++) {
		int h = hexval((unsigned char)p[i]);
		if (h < 0)
			return -1;
		v = v << 4 | (meta_rgb_t)h;
	}
	*rgb = v;
	return 0;
}

/* Unsigned integer token; returns 0 and *v or -1 (syntax) or -2 (range). */
static int parse_uint(const char *p, const char *q, uint32_t *v)
{
	uint64_t x = 0;
	if (p == q)
		return -1;
	for (; p < q; p++) {
		if (*p < '0' || *p > '9')
			return -1;
		x = x * 10 + (uint64_t)(*p - '0');
		if (x > 0xffffffffu)
			x = 0x100000000u;
	}
	if (x > 0xffffffffu)
		return -2;
	*v = (uint32_t)x;
	return 0;
}

#define COL(p) ((uint64_t)((p) - ls) + 1)

/* The common case in one pass: [-]digits[.1-3 digits] followed by a blank
 * or the end of the line. Anything else takes the careful path. */
static inline int fast_number(const char **pp, const char *le, meta_fix_t *out)
{
	const char *p = *pp, *d;
	uint64_t ip = 0, fp = 0;
	int neg = 0, k = 0;
	if (p < le && *p == '-')
		neg = 1, p++;
	for (d = p; p < le && (unsigned)(*p - '0') < 10 && p - d < 7; p++)
		ip = ip * 10 + (unsigned)(*p - '0');
	if (p == d)
		return -1;
	if (p < le && *p == '.') {
		for (p++; p < le && (unsigned)(*p - '0') < 10 && k < 3; p++, k++)
			fp = fp * 10 + (unsigned)(*p - '0');
		if (k == 0)
			return -1;
		for (; k < 3; k++)
			fp *= 10;
	}
	if (p < le && !BLANK(*p))
		return -1;
	ip = ip * META_FIX_ONE + fp;
	if (ip > META_MAX_COORD)
		return -1;
	*out = neg ? -(meta_fix_t)ip : (meta_fix_t)ip;
	*pp = p;
	return 0;
}

static int number_slow(meta_reader_t *r, const char *ls, const char *p, const char *le, const char *kw, int i,
                       meta_fix_t *out, const char **next)
{
	char b1[64], b2[48];
	const char *q;
	int why, rc;
	q = tok_end(p, le);
	rc = meta_fix_parse(p, q, out, &why);
	if (rc == -2)
		return meta_rd_fail(r, META_ELIMIT, COL(p), "expected a number from -1000000 to 1000000 %s, found %s",
		                    ctx(kw, i, b1, sizeof b1), found(p, le, b2, sizeof b2));
	if (rc < 0)
		return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected a %snumber %s, found %s",
		                    why == 1 ? "plain (no exponent) " : why == 2 ? "finite " : "",
		                    ctx(kw, i, b1, sizeof b1), found(p, le, b2, sizeof b2));
	*next = q;
	return 0;
}

static inline int number(meta_reader_t *r, const char *ls, const char *p, const char *le, const char *kw, int i,
                         meta_fix_t *out, const char **next)
{
	if (fast_number(&p, le, out) == 0) {
		*next = p;
		return 0;
	}
	return number_slow(r, ls, p, le, kw, i, out, next);
}

static int string(meta_reader_t *r, const char *ls, const char *p, const char *le, const char *kw, int i,
                  meta_cmd_t *cmd, const char **next)
{
	char b1[64], b2[48];
	const char *s = p;
	size_t n = 0;
	if (p >= le || *p != '"')
		return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected a \"string\" %s, found %s",
		                    ctx(kw, i, b1, sizeof b1), found(p, le, b2, sizeof b2));
	for (p++;; p++) {
		unsigned char c;
		if (p >= le)
			return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected a closing '\"' of the string, found end of line");
		c = (unsigned char)*p;
		if (c == '"')
			break;
		if (c == '\\') {
			if (p + 1 < le && (p[1] == '\\' || p[1] == '"')) {
				c = (unsigned char)*++p;
			} else if (p + 3 < le && p[1] == 'x' && hexval((unsigned char)p[2]) >= 0 &&
			           hexval((unsigned char)p[3]) >= 0) {
				c = (unsigned char)(hexval((unsigned char)p[2]) << 4 | hexval((unsigned char)p[3]));
				if (c == 0)   /* reported at the escape, as every error at its own place (§6) */
					return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected no NUL byte in a string, found '\\x%.2s'", p + 2);
				p += 3;
			} else {
				return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected an escape \\\\, \\\" or \\xHH, found %s",
				                    found(p, le, b2, sizeof b2));
			}
		} else if (c < 0x20 || c == 0x7f) {
			return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected a printable character or an escape, found byte 0x%02x", c);
		}
		if (n == META_MAX_STRING)
			return meta_rd_fail(r, META_ELIMIT, COL(s), "expected a string of at most %d bytes, found a longer one",
			                    META_MAX_STRING);
		r->str[n++] = (char)c;
	}
	p++;
	if (p < le && !BLANK(*p))
		return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected a blank after the string, found %s",
		                    found(p, le, b2, sizeof b2));
	r->str[n] = 0;
	cmd->str = r->str;
	cmd->len = n;
	*next = p;
	return 0;
}

static int runs(meta_reader_t *r, const char *ls, const char *p, const char *le, meta_cmd_t *cmd)
{
	char b2[48];
	uint64_t sum = 0;
	uint32_t width = r->chk.rows_left ? r->chk.image_w : 0;
	size_t n = 0;
	const char *p0 = p;
	while (p0 < le && BLANK(*p0))
		p0++;
	for (;;) {
		const char *q;
		uint32_t count;
		meta_rgb_t rgb;
		while (p < le && BLANK(*p))
			p++;
		if (p >= le)
			break;
		q = tok_end(p, le);
		if (parse_uint(p, q, &count) < 0 || count == 0)
			return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected a run count (1 or more) in 'row', found %s",
			                    found(p, le, b2, sizeof b2));
		if (width && (sum += count) > width)
			return meta_rd_fail(r, META_ESYNTAX, COL(p),
			                    "expected runs adding up to the image width %u, found %llu by run %zu",
			                    width, (unsigned long long)sum, n + 1);
		for (p = q; p < le && BLANK(*p); p++)
			;
		q = tok_end(p, le);
		if (parse_colour(p, q, &rgb) < 0)
			return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected a colour #rrggbb after a run count, found %s",
			                    found(p, le, b2, sizeof b2));
		if (meta_rd_runs(r, n + 1, COL(p)) < 0)
			return r->state;
		r->runs[n].count = count;
		r->runs[n++].rgb = rgb;
		p = q;
	}
	if (width && sum != width)   /* a short row: at its run list, as in the binary form */
		return meta_rd_fail(r, META_ESYNTAX, COL(p0), "expected runs adding up to the image width %u, found %llu",
		                    width, (unsigned long long)sum);
	cmd->runs = r->runs;
	cmd->nruns = n;
	return 0;
}

static meta_op_t lookup(const char *p, size_t len)
{
	int i;
	size_t j;
	if (len == 4 && p[0] == 'd' && p[1] == 'r' && p[2] == 'a' && p[3] == 'w')
		return META_DRAW; /* the statement of most of any file */
	for (i = 0; i < META_OP_COUNT; i++) {
		if (meta_ops[i].kwlen != len || meta_ops[i].kw[0] != *p)
			continue;
		for (j = 1; j < len && meta_ops[i].kw[j] == p[j]; j++)
			;
		if (j == len)
			return (meta_op_t)i;
	}
	return META_OP_COUNT;
}

int meta_text_header(meta_reader_t *r)
{
	char b2[48];
	const char *ls, *le, *p, *q;
	uint32_t v = 0;
	int rc = get_line(r, &ls, &le);
	if (rc < 0)
		return rc;
	r->line = 1;
	if (rc == 0)
		return meta_rd_fail(r, META_EVERSION, 1, "expected 'LOCUS-META 1', found end of file");
	if (le - ls < 11 || memcmp(ls, "LOCUS-META", 10) != 0 || !BLANK(ls[10]))
		return meta_rd_fail(r, META_EVERSION, 1, "expected 'LOCUS-META 1', found %s",
		                    found(ls, le, b2, sizeof b2));
	for (p = ls + 10; p < le && BLANK(*p); p++)
		;
	q = tok_end(p, le);
	rc = parse_uint(p, q, &v);
	if (rc == -1)
		return meta_rd_fail(r, META_EVERSION, COL(p), "expected a version number after 'LOCUS-META', found %s",
		                    found(p, le, b2, sizeof b2));
	if (rc < 0 || v != META_VERSION) {
		if (rc < 0)
			return meta_rd_fail(r, META_EVERSION, COL(p), "unsupported meta-language version %.*s (this reader knows %d)",
			                    (int)(q - p > 20 ? 20 : q - p), p, META_VERSION);
		return meta_rd_fail(r, META_EVERSION, COL(p), "unsupported meta-language version %u (this reader knows %d)",
		                    v, META_VERSION);
	}
	for (p = q; p < le && BLANK(*p); p++)
		;
	if (p < le)
		return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected end of line after 'LOCUS-META 1', found %s",
		                    found(p, le, b2, sizeof b2));
	return 0;
}

int meta_read_text(meta_reader_t *r, meta_cmd_t *cmd)
{
	char b1[64], b2[48];
	const char *ls, *le, *p, *q, *sig, *kw;
	int rc, i, fi = 0, ui = 0;
	meta_op_t op;
	do {
		rc = get_line(r, &ls, &le);
		if (rc <= 0)
			return rc;
		for (p = ls; p < le && BLANK(*p); p++)
			;
	} while (p == le);
	memset(cmd, 0, sizeof *cmd);
	r->stmt_pos = r->line;
	r->opos[7] = COL(p);
	if (*p == '#') {
		size_t len;
		if (++p < le && *p == ' ')
			p++;
		len = (size_t)(le - p);
		if (len > META_MAX_STRING)
			return meta_rd_fail(r, META_ELIMIT, COL(p), "expected a comment of at most %d bytes, found %zu bytes",
			                    META_MAX_STRING, len);
		memcpy(r->str, p, len);
		r->str[len] = 0;
		cmd->op = META_COMMENT;
		cmd->str = r->str;
		cmd->len = len;
		r->opos[0] = COL(p);
		return 1;
	}
	q = tok_end(p, le);
	op = lookup(p, (size_t)(q - p));
	if (op == META_DRAW || op == META_MOVE) {
		/* the bulk of any file: two numbers, single blanks, end of line */
		const char *t = q + 1;
		if (q < le && *q == ' ' && fast_number(&t, le, &cmd->f[0]) == 0 && t < le && *t == ' ') {
			const char *u = t + 1;
			if (fast_number(&u, le, &cmd->f[1]) == 0 && u == le) {
				cmd->op = op;
				r->opos[0] = COL(q + 1);
				r->opos[1] = COL(t + 1);
				return 1;
			}
		}
	}
	if (op == META_OP_COUNT)
		return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected a statement keyword, found %s",
		                    found(p, le, b2, sizeof b2));
	cmd->op = op;
	kw = meta_ops[op].kw;
	sig = meta_ops[op].sig;
	p = q;
	for (i = 0; sig[i]; i++) {
		while (p < le && BLANK(*p))
			p++;
		r->opos[i] = COL(p);
		switch (sig[i]) {
		case 'f':
			if (number(r, ls, p, le, kw, i, &cmd->f[fi++], &p) < 0)
				return r->state;
			break;
		case 'u':
			q = tok_end(p, le);
			rc = parse_uint(p, q, &cmd->u[ui++]);
			if (rc < 0)
				return meta_rd_fail(r, rc == -2 ? META_ELIMIT : META_ESYNTAX, COL(p),
				                    "expected %s %s, found %s",
				                    rc == -2 ? "an integer below 2^32" : "an unsigned integer (digits)",
				                    ctx(kw, i, b1, sizeof b1), found(p, le, b2, sizeof b2));
			p = q;
			break;
		case 'c':
			q = tok_end(p, le);
			if (parse_colour(p, q, &cmd->rgb) < 0)
				return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected a colour #rrggbb %s, found %s",
				                    ctx(kw, i, b1, sizeof b1), found(p, le, b2, sizeof b2));
			p = q;
			break;
		case 'k': {
			const meta_opinfo_t *o = &meta_ops[op];
			int k;
			q = tok_end(p, le);
			for (k = 0; k < o->nwords; k++)
				if (strlen(o->words[k]) == (size_t)(q - p) && memcmp(o->words[k], p, (size_t)(q - p)) == 0)
					break;
			if (k == o->nwords) {
				if (o->nwords == 3)
					meta_fmt(b1, sizeof b1, "'%s', '%s' or '%s'", o->words[0], o->words[1], o->words[2]);
				else
					meta_fmt(b1, sizeof b1, "'%s' or '%s'", o->words[0], o->words[1]);
				return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected %s after '%s', found %s", b1, kw,
				                    found(p, le, b2, sizeof b2));
			}
			cmd->k = k;
			p = q;
			break;
		}
		case 's':
			if (string(r, ls, p, le, kw, i, cmd, &p) < 0)
				return r->state;
			break;
		case 'L':
			while (p < le) {
				const char *t = p;
				if (cmd->nlist == META_MAX_DASH)
					return meta_rd_fail(r, META_ELIMIT, COL(p), "expected at most %d dash lengths, found more",
					                    META_MAX_DASH);
				if (number(r, ls, p, le, kw, i, &r->list[cmd->nlist], &p) < 0)
					return r->state;
				if (r->list[cmd->nlist] <= 0)
					return meta_rd_fail(r, META_ESYNTAX, COL(t), "expected dash lengths > 0, found %s",
					                    found(t, le, b2, sizeof b2));
				cmd->nlist++;
				while (p < le && BLANK(*p))
					p++;
			}
			cmd->list = r->list;
			break;
		case 'R':
			if (runs(r, ls, p, le, cmd) < 0)
				return r->state;
			p = le;
			break;
		}
	}
	while (p < le && BLANK(*p))
		p++;
	if (p < le)
		return meta_rd_fail(r, META_ESYNTAX, COL(p), "expected end of line after the operands of '%s', found %s",
		                    kw, found(p, le, b2, sizeof b2));
	return 1;
}
