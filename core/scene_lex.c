/* scene_lex.c: tokens, numbers and positioned error messages of the scene language. */
#include "scene_lex.h"
#include "expr.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

void scene_lex_init(scene_lex_t *lx, const char *text, const char *name, char *err, size_t errlen)
{
	memset(lx, 0, sizeof *lx);
	lx->text = text;
	lx->name = name;
	lx->err = err;
	lx->errlen = errlen;
	lx->line = 0;
	lx->pos = 0;
	lx->line_start = 0;
	if (errlen)
		err[0] = 0;
}

int scene_lex_line(scene_lex_t *lx)
{
	const char *s = lx->text;
	size_t p = lx->pos;
	if (lx->line > 0) {
		while (s[p] && s[p] != '\n')
			p++;
		if (s[p] == '\n')
			p++;
		else if (!s[p]) {
			lx->pos = p;
			return 0;
		}
	}
	for (;;) {
		lx->line++;
		lx->line_start = p;
		size_t q = p;
		while (blank(s[q]))
			q++;
		if (s[q] && s[q] != '\n' && s[q] != '#') {
			lx->pos = p;
			return 1;
		}
		while (s[q] && s[q] != '\n')
			q++;
		if (!s[q]) {
			lx->pos = q;
			return 0;
		}
		p = q + 1;
	}
}

int scene_lex_tok(scene_lex_t *lx, scene_tok_t *t)
{
	const char *s = lx->text;
	size_t p = lx->pos;
	while (blank(s[p]))
		p++;
	t->s = s + p;
	t->line = lx->line;
	t->col = (unsigned)(p - lx->line_start + 1);
	if (!s[p] || s[p] == '\n' || s[p] == '#') {
		t->len = 0;
		lx->pos = p;
		return 0;
	}
	size_t q = p;
	while (s[q] && !blank(s[q]) && s[q] != '\n' && s[q] != '#')
		q++;
	t->len = q - p;
	lx->pos = q;
	return 1;
}

void scene_lex_rest(scene_lex_t *lx, scene_tok_t *t)
{
	const char *s = lx->text;
	size_t p = lx->pos;
	while (blank(s[p]))
		p++;
	size_t q = p;
	while (s[q] && s[q] != '\n' && s[q] != '#')
		q++;
	size_t e = q;
	while (e > p && blank(s[e - 1]))
		e--;
	t->s = s + p;
	t->len = e - p;
	t->line = lx->line;
	t->col = (unsigned)(p - lx->line_start + 1);
	lx->pos = q;
}

int scene_tok_is(const scene_tok_t *t, const char *word)
{
	return t->len == strlen(word) && !memcmp(t->s, word, t->len);
}

size_t scene_escape(char *dst, size_t dstlen, const char *src)
{
	static const char hex[] = "0123456789abcdef";
	size_t n = 0;
	if (!dstlen)
		return 0;
	for (const unsigned char *p = (const unsigned char *)src; *p && n + 1 < dstlen; p++) {
		if (*p >= 0x20 && *p != 0x7f) {
			dst[n++] = (char)*p;
			continue;
		}
		if (n + 4 >= dstlen)
			break;
		dst[n++] = '\\';
		dst[n++] = 'x';
		dst[n++] = hex[*p >> 4];
		dst[n++] = hex[*p & 15];
	}
	dst[n] = 0;
	return n;
}

int scene_lex_error(scene_lex_t *lx, unsigned line, unsigned col, const char *msg)
{
	if (!lx->failed) {
		char raw[1024];
		lx->failed = 1;
		snprintf(raw, sizeof raw, "%s:%u:%u: %s", lx->name, line, col, msg);
		scene_escape(lx->err, lx->errlen, raw);
	}
	return -1;
}

int scene_lex_expected(scene_lex_t *lx, const scene_tok_t *t, const char *what)
{
	char msg[512];
	if (t->len)
		snprintf(msg, sizeof msg, "expected %s, found '%.*s'", what, (int)(t->len > 40 ? 40 : t->len), t->s);
	else
		snprintf(msg, sizeof msg, "expected %s, found the end of the line", what);
	return scene_lex_error(lx, t->line, t->col, msg);
}

static int ident_char(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; }

int scene_uses_t(const char *s, size_t n)
{
	for (size_t i = 0; i < n; i++)
		if (s[i] == 't' && (i == 0 || !ident_char(s[i - 1])) && (i + 1 == n || !ident_char(s[i + 1]))
		    && !(i > 0 && s[i - 1] == '.'))
			return 1;
	return 0;
}

int scene_subst_t(const char *s, size_t n, double t, char *dst, size_t dstlen)
{
	char val[40];
	int vl = snprintf(val, sizeof val, "(%.17g)", t);
	size_t o = 0;
	for (size_t i = 0; i < n; i++) {
		int is_t = s[i] == 't' && (i == 0 || !ident_char(s[i - 1])) && (i + 1 == n || !ident_char(s[i + 1]));
		if (is_t) {
			if (o + (size_t)vl >= dstlen)
				return -1;
			memcpy(dst + o, val, (size_t)vl);
			o += (size_t)vl;
		} else {
			if (o + 1 >= dstlen)
				return -1;
			dst[o++] = s[i];
		}
	}
	dst[o] = 0;
	return 0;
}

/* A number token that uses t: a constant expression at the frame's t. */
static int time_number(scene_lex_t *lx, const scene_tok_t *t, double *v, const char *what)
{
	char src[512], e[200], msg[400];
	expr_t *x = NULL;
	size_t at = 0;
	if (scene_subst_t(t->s, t->len, lx->t, src, sizeof src) < 0)
		return scene_lex_error(lx, t->line, t->col, "expected an expression in t of at most 200 bytes");
	if (expr_compile(src, &x, e, sizeof e, &at) < 0) {
		snprintf(msg, sizeof msg, "%s (in the expression in t '%.*s')", e, (int)(t->len > 60 ? 60 : t->len), t->s);
		return scene_lex_error(lx, t->line, t->col, msg);
	}
	if (!expr_is_constant(x)) {
		expr_free(x);
		snprintf(msg, sizeof msg, "expected %s: an expression in t alone (x, y, z have no value here), found '%.*s'",
		         what, (int)(t->len > 60 ? 60 : t->len), t->s);
		return scene_lex_error(lx, t->line, t->col, msg);
	}
	double y = expr_eval(x, 0, 0, 0);
	expr_free(x);
	if (!isfinite(y) || fabs(y) > EXPR_MAX_NUMBER) {
		snprintf(msg, sizeof msg, "expected %s between -1e6 and 1e6, found '%.*s' = %g at t = %g", what,
		         (int)(t->len > 60 ? 60 : t->len), t->s, y, lx->t);
		return scene_lex_error(lx, t->line, t->col, msg);
	}
	*v = y;
	return 0;
}

int scene_lex_number(scene_lex_t *lx, double *v, const char *what)
{
	scene_tok_t t;
	char buf[64], msg[128];
	snprintf(msg, sizeof msg, "%s (a finite number)", what);
	if (scene_lex_tok(lx, &t) && scene_uses_t(t.s, t.len))
		return time_number(lx, &t, v, what);
	if (!t.len || t.len >= sizeof buf)
		return scene_lex_expected(lx, &t, msg);
	memcpy(buf, t.s, t.len);
	buf[t.len] = 0;
	size_t sign = buf[0] == '-' || buf[0] == '+';
	if (expr_decimal_len(buf + sign) != t.len - sign) {
		char *end;
		double y = strtod(buf, &end);
		if (!*end && isfinite(y))   /* C would read it (0x10): say what the language reads */
			snprintf(msg, sizeof msg, "%s (a decimal number)", what);
		return scene_lex_expected(lx, &t, msg);
	}
	double x = strtod(buf, NULL);
	if (!isfinite(x) || fabs(x) > EXPR_MAX_NUMBER) {
		snprintf(msg, sizeof msg, "%s between -1e6 and 1e6 (the float kernels' range)", what);
		return scene_lex_expected(lx, &t, msg);
	}
	*v = x;
	return 0;
}

int scene_lex_numbers(scene_lex_t *lx, double *v, int n, const char *what)
{
	for (int i = 0; i < n; i++)
		if (scene_lex_number(lx, &v[i], what) < 0)
			return -1;
	return 0;
}

int scene_lex_points(scene_lex_t *lx, int dims, const char *const *stop, size_t max, const char *maxmsg,
                     double **pts, size_t *nnum)
{
	size_t cap = 0, k = 0;
	double *p = NULL;
	*pts = NULL;
	*nnum = 0;
	for (;;) {
		size_t save = lx->pos;
		scene_tok_t t;
		int more = scene_lex_tok(lx, &t);
		for (int i = 0; more && stop[i]; i++)
			more = !scene_tok_is(&t, stop[i]);
		lx->pos = save;
		if (!more)
			break;
		size_t at = 3 * (k / dims);
		if (max && k / dims >= max) {
			free(p);
			return scene_lex_error(lx, t.line, t.col, maxmsg);
		}
		if (at + 3 > cap) {
			cap = cap ? 2 * cap : 24;
			double *q = realloc(p, cap * sizeof *q);
			if (!q) {
				free(p);
				return scene_lex_error(lx, t.line, t.col, "out of memory");
			}
			p = q;
		}
		const char *what = dims == 3 ? "a coordinate" : k % 2 ? "a y coordinate" : "an x coordinate";
		if (scene_lex_number(lx, &p[at + k % dims], what) < 0) {
			free(p);
			return -1;
		}
		if (dims == 2)
			p[at + 2] = 0;
		k++;
	}
	*pts = p;
	*nnum = k;
	return 0;
}

int scene_lex_eol(scene_lex_t *lx)
{
	scene_tok_t t;
	if (scene_lex_tok(lx, &t))
		return scene_lex_expected(lx, &t, "the end of the line");
	return 0;
}

int scene_parse_colour(scene_lex_t *lx, double *c)
{
	if (scene_lex_numbers(lx, c, 3, "a colour component 0..1") < 0)
		return -1;
	for (int i = 0; i < 3; i++)
		if (c[i] < 0 || c[i] > 1)
			return scene_lex_error(lx, lx->line, 1, "expected colour components between 0 and 1");
	return 0;
}
