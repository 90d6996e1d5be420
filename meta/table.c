/* table.c: the opcode table built from opcodes.def, keyword spellings, and fixed-point numbers. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "meta_int.h"

static const char *const cap_words[] = { "butt", "round", "square" };
static const char *const join_words[] = { "miter", "round", "bevel" };
static const char *const rule_words[] = { "even-odd", "non-zero" };

#define WORDS_OF(e) \
	(META_##e == META_CAP ? cap_words : META_##e == META_JOIN ? join_words : \
	 META_##e == META_FILL_RULE ? rule_words : NULL)
#define NWORDS_OF(e) \
	(META_##e == META_CAP ? 3 : META_##e == META_JOIN ? 3 : META_##e == META_FILL_RULE ? 2 : 0)

const meta_opinfo_t meta_ops[META_OP_COUNT] = {
#define META_OP(e, kw, code, sig) \
	[META_##e] = { kw, sizeof(kw) - 1, code, sig, WORDS_OF(e), NWORDS_OF(e) },
#include "opcodes.def"
#undef META_OP
};

const unsigned char meta_op_by_code[256] = {
#define META_OP(e, kw, code, sig) [code] = META_##e + 1,
#include "opcodes.def"
#undef META_OP
};

const unsigned char meta_magic[8] = { 0x8b, 'L', 'M', 'B', '\r', '\n', 0x1a, '\n' };

const char *meta_op_name(meta_op_t op)
{
	if ((unsigned)op >= META_OP_COUNT)
		return "?";
	return meta_ops[op].kw;
}

const char *meta_keyword_name(meta_op_t op, int k)
{
	if ((unsigned)op >= META_OP_COUNT || k < 0 || k >= meta_ops[op].nwords)
		return NULL;
	return meta_ops[op].words[k];
}

void meta_fmt(char *buf, size_t n, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	if (vsnprintf(buf, n, fmt, ap) < 0 && n)
		buf[0] = 0;
	va_end(ap);
}

int meta_fix_format(meta_fix_t v, char *buf)
{
	char tmp[16];
	int n = 0, len = 0;
	uint32_t mag = v < 0 ? (uint32_t)0 - (uint32_t)v : (uint32_t)v;
	uint32_t ip = mag / 1000, fp = mag % 1000;
	if (v < 0)
		buf[len++] = '-';
	do {
		tmp[n++] = (char)('0' + ip % 10);
		ip /= 10;
	} while (ip);
	while (n)
		buf[len++] = tmp[--n];
	if (fp) {
		buf[len++] = '.';
		buf[len++] = (char)('0' + fp / 100);
		fp %= 100;
		if (fp) {
			buf[len++] = (char)('0' + fp / 10);
			fp %= 10;
			if (fp)
				buf[len++] = (char)('0' + fp);
		}
	}
	buf[len] = 0;
	return len;
}

meta_fix_t meta_fix_from_double(double v, int *ok)
{
	double t;
	if (ok)
		*ok = 0;
	if (!isfinite(v))
		return 0;
	t = round(v * 1000.0); /* round() rounds halfway cases away from zero */
	if (t > META_MAX_COORD || t < -(double)META_MAX_COORD)
		return 0;
	if (ok)
		*ok = 1;
	return (meta_fix_t)t; /* (int)-0.0 == 0: never -0 */
}

static int is_digit(int c) { return c >= '0' && c <= '9'; }

/* Case-insensitive prefix test for "inf"/"nan" diagnostics. */
static int starts_ci(const char *p, const char *e, const char *w)
{
	for (; *w; p++, w++)
		if (p >= e || (*p | 0x20) != *w)
			return 0;
	return 1;
}

int meta_fix_parse(const char *p, const char *e, meta_fix_t *out, int *why)
{
	const char *s = p;
	int neg = 0, digits = 0;
	uint32_t ip = 0, fp = 0;
	*why = 0;
	if (p < e && (*p == '-' || *p == '+'))
		neg = *p++ == '-';
	for (; p < e && is_digit(*p); p++, digits++) {
		ip = ip * 10 + (uint32_t)(*p - '0');
		if (ip > META_MAX_COORD / META_FIX_ONE + 1)
			ip = META_MAX_COORD / META_FIX_ONE + 1; /* saturate: out of range below */
	}
	if (p < e && *p == '.') {
		int k = 0;
		for (p++; p < e && is_digit(*p); p++, digits++, k++) {
			if (k < 3)
				fp = fp * 10 + (uint32_t)(*p - '0');
			else if (k == 3 && *p >= '5')
				fp++; /* ties away from zero: the magnitude grows */
		}
		for (; k < 3; k++)
			fp *= 10;
	}
	if (p != e || !digits) {
		const char *q = s + (s < e && (*s == '-' || *s == '+'));
		if (starts_ci(q, e, "inf") || starts_ci(q, e, "nan"))
			*why = 2;
		else if (digits && p < e && (*p == 'e' || *p == 'E'))
			*why = 1;
		return -1;
	}
	{
		uint64_t mag = (uint64_t)ip * META_FIX_ONE + fp;
		if (mag > META_MAX_COORD)
			return -2;
		*out = neg ? -(meta_fix_t)mag : (meta_fix_t)mag;
	}
	return 0;
}

size_t meta_utf8_next(const void *buf, size_t n, uint32_t *cp)
{
	const unsigned char *s = buf;
	unsigned c = s[0], len, i;
	unsigned char lo = 0x80, hi = 0xbf;   /* the second byte's range (Unicode table 3-7) */
	uint32_t v;
	*cp = 0xfffd;
	if (c < 0x80) {
		*cp = c;
		return 1;
	}
	if (c >= 0xc2 && c <= 0xdf)
		len = 2, v = c & 0x1f;
	else if (c >= 0xe0 && c <= 0xef)
		len = 3, v = c & 0x0f, lo = c == 0xe0 ? 0xa0 : 0x80, hi = c == 0xed ? 0x9f : 0xbf;
	else if (c >= 0xf0 && c <= 0xf4)
		len = 4, v = c & 0x07, lo = c == 0xf0 ? 0x90 : 0x80, hi = c == 0xf4 ? 0x8f : 0xbf;
	else
		return 1;   /* a continuation byte, C0, C1 or F5-FF on its own */
	for (i = 1; i < len; i++) {
		if (i >= n || s[i] < (i == 1 ? lo : 0x80) || s[i] > (i == 1 ? hi : 0xbf))
			return i;   /* the maximal subpart so far is one ill-formed character */
		v = v << 6 | (s[i] & 0x3f);
	}
	*cp = v;
	return len;
}

int meta_utf8_len(const unsigned char *s, size_t n)
{
	uint32_t cp;
	size_t k = meta_utf8_next(s, n, &cp);
	/* a well-formed sequence of 2 to 4 bytes (an encoded U+FFFD is one too: EF BF BD) */
	return k > 1 && (cp != 0xfffd || (s[0] == 0xef && s[1] == 0xbf && s[2] == 0xbd)) ? (int)k : 0;
}
