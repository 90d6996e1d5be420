/* diff_ps.c: PostScript, EPS and PDF compared as text after normalising what carries no picture. */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include "diff/diff.h"

/* A line that carries no picture: creator, dates, titles, IDs, producer, the xref table. */
static int ignorable(const char *l, size_t n)
{
	static const char *const pre[] = { "%%Creator", "%%CreationDate", "%%Title", "%%For",
		"%%ModDate", "%%Producer", "%%DocumentData", "%% Original object ID", "%PDF-" };
	for (size_t k = 0; k < sizeof pre / sizeof *pre; k++)
		if (n >= strlen(pre[k]) && memcmp(l, pre[k], strlen(pre[k])) == 0)
			return 1;
	/* the xref table's entries move with any byte change before them; startxref too */
	if (n >= 18 && isdigit((unsigned char)l[0]) && l[10] == ' ' && l[16] == ' ' &&
			(l[17] == 'n' || l[17] == 'f'))
		return 1;
	return 0;
}

/* The picture-carrying text of one line, into out (dictionary keys /CreationDate, /ModDate,
 * /Producer, /Creator, /ID values blanked; the offset after startxref dropped). */
static size_t normal(const char *l, size_t n, char *out, size_t cap, int *after_startxref)
{
	size_t k = 0;
	if (*after_startxref) {
		*after_startxref = 0;
		return 0;
	}
	if (n >= 9 && memcmp(l, "startxref", 9) == 0)
		*after_startxref = 1;
	static const char *const keys[] = { "/CreationDate", "/ModDate", "/Producer", "/Creator", "/ID" };
	for (size_t i = 0; i < n && k + 1 < cap;) {
		size_t kl = 0;
		for (size_t j = 0; j < sizeof keys / sizeof *keys; j++) {
			size_t m = strlen(keys[j]);
			if (n - i >= m && memcmp(l + i, keys[j], m) == 0)
				kl = m;
		}
		if (!kl) {
			out[k++] = l[i++];
			continue;
		}
		for (size_t j = 0; j < kl && k + 1 < cap; j++)
			out[k++] = l[i++];
		while (i < n && l[i] == ' ')
			i++;
		/* skip one value: (string), <hex>, [array] */
		if (i < n && (l[i] == '(' || l[i] == '[' || l[i] == '<')) {
			char open = l[i], close = open == '(' ? ')' : open == '[' ? ']' : '>';
			int depth = 0;
			for (; i < n; i++) {
				if (l[i] == '\\' && open == '(') {
					i++;
					continue;
				}
				if (l[i] == open)
					depth++;
				else if (l[i] == close && --depth == 0) {
					i++;
					break;
				}
			}
		}
		if (k + 2 < cap)
			out[k++] = ' ', out[k++] = '?';
	}
	return k;
}

/* A side cut into normalised lines. */
typedef struct {
	const char *b;
	size_t n, at, line, after;
	char buf[4096];
	size_t len, lineno, offset;
} lines_t;

/* The next line that counts: 1 with buf/len/lineno/offset set, 0 at the end. */
static int next(lines_t *s)
{
	while (s->at < s->n) {
		size_t i = s->at, e = i;
		while (e < s->n && s->b[e] != '\n' && s->b[e] != '\r')
			e++;
		s->line++;
		s->at = e < s->n && s->b[e] == '\r' && e + 1 < s->n && s->b[e + 1] == '\n' ? e + 2 : e + 1;
		int aft = (int)s->after;
		if (ignorable(s->b + i, e - i))
			continue;
		s->len = normal(s->b + i, e - i, s->buf, sizeof s->buf, &aft);
		int was = s->after != 0;
		s->after = (size_t)aft;
		if (was)
			continue;   /* the number after startxref */
		s->lineno = s->line;
		s->offset = i;
		return 1;
	}
	return 0;
}

int diff_ps(const void *a, size_t na, const char *aname, const void *b, size_t nb,
		const char *bname, const diff_opts_t *o, FILE *out, char *err, size_t errlen)
{
	(void)err, (void)errlen;
	lines_t s[2];
	memset(s, 0, sizeof s);
	s[0].b = a, s[0].n = na, s[1].b = b, s[1].n = nb;
	size_t count = 0, ndiff = 0;
	size_t fl[2] = { 0, 0 }, fo[2] = { 0, 0 };
	char fa[200] = "", fb[200] = "";
	for (;;) {
		int ha = next(&s[0]), hb = next(&s[1]);
		if (!ha && !hb)
			break;
		count++;
		if (ha && hb && s[0].len == s[1].len && memcmp(s[0].buf, s[1].buf, s[0].len) == 0)
			continue;
		if (ndiff++ == 0) {
			fl[0] = ha ? s[0].lineno : s[0].line + 1, fo[0] = ha ? s[0].offset : na;
			fl[1] = hb ? s[1].lineno : s[1].line + 1, fo[1] = hb ? s[1].offset : nb;
			snprintf(fa, sizeof fa, "%.*s", ha ? (int)(s[0].len > 120 ? 120 : s[0].len) : 5, ha ? s[0].buf : "(end)");
			snprintf(fb, sizeof fb, "%.*s", hb ? (int)(s[1].len > 120 ? 120 : s[1].len) : 5, hb ? s[1].buf : "(end)");
		}
	}
	for (char *q = fa; *q; q++)   /* binary stream data shown as dots */
		*q = (unsigned char)*q < 32 || (unsigned char)*q > 126 ? '.' : *q;
	for (char *q = fb; *q; q++)
		*q = (unsigned char)*q < 32 || (unsigned char)*q > 126 ? '.' : *q;
	int pdf = na >= 5 && memcmp(a, "%PDF-", 5) == 0;
	if (o->json) {
		fprintf(out, "{\"kind\":\"%s\",\"qdf\":%s,\"a\":", pdf ? "pdf" : "postscript", o->qdf ? "true" : "false");
		diff_json_str(out, aname);
		fprintf(out, ",\"b\":");
		diff_json_str(out, bname);
		fprintf(out, ",\"same\":%s,\"lines_differing\":%zu", ndiff ? "false" : "true", ndiff);
		if (ndiff) {
			fprintf(out, ",\"first\":{\"a_line\":%zu,\"a_byte\":%zu,\"b_line\":%zu,\"b_byte\":%zu,\"a\":",
				fl[0], fo[0], fl[1], fo[1]);
			diff_json_str(out, fa);
			fprintf(out, ",\"b\":");
			diff_json_str(out, fb);
			fprintf(out, "}");
		}
		fprintf(out, "}\n");
	} else if (!ndiff) {
		fprintf(out, "%s %s: %s, the same after normalising (%zu lines)\n", aname, bname,
			pdf ? (o->qdf ? "PDF (qpdf's QDF form)" : "PDF") : "PostScript", count);
	} else {
		fprintf(out, "%s %s: %s, %zu of %zu normalised lines differ, the first at line %zu (byte %zu) "
			"and line %zu (byte %zu)\n", aname, bname, pdf ? (o->qdf ? "PDF (qpdf's QDF form)" : "PDF") : "PostScript", ndiff, count,
			fl[0], fo[0], fl[1], fo[1]);
		if (o->verbose)
			fprintf(out, "  A: %s\n  B: %s\n  (--render compares the pictures)\n", fa, fb);
	}
	return ndiff ? 1 : 0;
}
