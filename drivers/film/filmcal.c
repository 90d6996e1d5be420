/* filmcal.c: per-channel calibration curve files of a film recorder, parsed, checked, applied. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "film/filmenc.h"

#define CAL_MAX_POINTS 4096
#define CAL_MAGIC "locus-film-calibration"

struct film_cal {
	size_t n;                   /* points */
	double *in[3];              /* per channel n wanted values, increasing */
	double *out[3];             /* per channel n values to expose */
};

static const char *const chan_name[3] = { "red", "green", "blue" };

typedef struct {
	const char *name;
	const char *p, *end;        /* the current line, without its newline */
	unsigned line;
	const char *line_start;
	char *err;
	size_t errlen;
} cal_parse_t;

static int fail(cal_parse_t *cp, const char *at, const char *fmt, const char *what)
{
	char msg[200];
	snprintf(msg, sizeof msg, fmt, what);
	snprintf(cp->err, cp->errlen, "%s:%u:%u: %s", cp->name, cp->line,
		(unsigned)(at - cp->line_start) + 1, msg);
	return -65;
}

static const char *skip_blanks(const char *p, const char *end)
{
	while (p < end && (*p == ' ' || *p == '\t' || *p == '\r'))
		p++;
	return p;
}

/* the word at p (up to a blank), for messages */
static const char *word_at(const char *p, const char *end, char *buf, size_t n)
{
	size_t k = 0;
	while (p + k < end && p[k] != ' ' && p[k] != '\t' && p[k] != '\r' && k + 1 < n)
		k++;
	memcpy(buf, p, k);
	buf[k] = 0;
	return k ? buf : "end of line";
}

/* one number in [0, 1] at *pp; advances *pp */
static int number(cal_parse_t *cp, const char **pp, const char *what, double *v)
{
	const char *p = skip_blanks(*pp, cp->end);
	char buf[40], word[32];
	size_t k = 0;
	while (p + k < cp->end && p[k] != ' ' && p[k] != '\t' && p[k] != '\r' && p[k] != '#')
		k++;
	char *e = NULL;
	double x = 0;
	if (k && k < sizeof buf) {
		memcpy(buf, p, k);
		buf[k] = 0;
		errno = 0;
		x = strtod(buf, &e);
	} else
		buf[0] = 0;
	char msg[120];
	if (!k || k >= sizeof buf || *e || errno || !isfinite(x)) {
		snprintf(msg, sizeof msg, "expected a number for %s, found '%s'", what,
			word_at(p, cp->end, word, sizeof word));
		return fail(cp, p, "%s", msg);
	}
	if (x < 0 || x > 1) {
		snprintf(msg, sizeof msg, "%s value %s is outside [0, 1]", what, buf);
		return fail(cp, p, "%s", msg);
	}
	*v = x;
	*pp = p + k;
	return 0;
}

static int add_point(film_cal_t *c, const double v[4])
{
	if (c->n % 64 == 0) {
		size_t m = c->n + 64;
		for (int ch = 0; ch < 3; ch++) {
			double *a = realloc(c->in[ch], m * sizeof(double));
			if (!a)
				return -1;
			c->in[ch] = a;
			a = realloc(c->out[ch], m * sizeof(double));
			if (!a)
				return -1;
			c->out[ch] = a;
		}
	}
	for (int ch = 0; ch < 3; ch++) {
		c->in[ch][c->n] = v[0];
		c->out[ch][c->n] = v[ch + 1];
	}
	c->n++;
	return 0;
}

/* a response curve (what the recorder gave for what it was sent) becomes the correction
 * (what to send for what is wanted) by swapping the axes of each channel: the response
 * increases strictly, so its inverse is a curve too; wanted values beyond what the recorder
 * reaches are clamped to its ends */
static void invert(film_cal_t *c)
{
	for (int ch = 0; ch < 3; ch++) {
		double *t = c->in[ch];
		c->in[ch] = c->out[ch];
		c->out[ch] = t;
	}
}

int film_cal_parse(const char *text, size_t n, const char *name, film_cal_t **cal, char *err,
		size_t errlen)
{
	cal_parse_t cp = { name, text, text, 0, text, err, errlen };
	film_cal_t *c = calloc(1, sizeof *c);
	int rc = 0, seen_magic = 0, response = 0, seen_kind = 0;
	const char *end_all = text + n;
	if (!c) {
		snprintf(err, errlen, "%s: out of memory", name);
		return -70;
	}
	for (const char *p = text; rc == 0 && p < end_all;) {
		const char *nl = memchr(p, '\n', (size_t)(end_all - p));
		cp.end = nl ? nl : end_all;
		cp.line++;
		cp.line_start = p;
		const char *q = skip_blanks(p, cp.end);
		p = nl ? nl + 1 : end_all;
		if (memchr(cp.line_start, 0, (size_t)(cp.end - cp.line_start))) {
			rc = fail(&cp, cp.line_start, "%s", "a NUL byte: this is not a text file");
			break;
		}
		if (q == cp.end || *q == '#')
			continue;
		char word[32];
		if (!seen_magic) {
			size_t ml = strlen(CAL_MAGIC);
			const char *v = skip_blanks(q + ml, cp.end);
			if ((size_t)(cp.end - q) < ml || memcmp(q, CAL_MAGIC, ml) || v == q + ml) {
				rc = fail(&cp, q, "expected '" CAL_MAGIC " 1' as the first line, found '%s'",
					word_at(q, cp.end, word, sizeof word));
				break;
			}
			if (cp.end - v < 1 || *v != '1' || skip_blanks(v + 1, cp.end) != cp.end) {
				rc = fail(&cp, v, "expected version 1, found '%s'", word_at(v, cp.end, word, sizeof word));
				break;
			}
			seen_magic = 1;
			continue;
		}
		if (*q < '0' || *q > '9') {
			if (cp.end - q > 4 && !memcmp(q, "kind", 4) && (q[4] == ' ' || q[4] == '\t') && !seen_kind && !c->n) {
				const char *v = skip_blanks(q + 4, cp.end);
				word_at(v, cp.end, word, sizeof word);
				if (strcmp(word, "correction") && strcmp(word, "response")) {
					rc = fail(&cp, v, "expected 'correction' or 'response' after 'kind', found '%s'", word);
					break;
				}
				if (skip_blanks(v + strlen(word), cp.end) != cp.end) {
					rc = fail(&cp, skip_blanks(v + strlen(word), cp.end), "%s", "expected the end of the line");
					break;
				}
				response = word[0] == 'r';
				seen_kind = 1;
				continue;
			}
			rc = fail(&cp, q, "expected a point 'IN RED GREEN BLUE' or 'kind correction|response' "
				"before the first point, found '%s'", word_at(q, cp.end, word, sizeof word));
			break;
		}
		double v[4];
		const char *r = q;
		static const char *const what[4] = { "the input", "red", "green", "blue" };
		for (int k = 0; k < 4 && rc == 0; k++)
			rc = number(&cp, &r, what[k], &v[k]);
		if (rc)
			break;
		r = skip_blanks(r, cp.end);
		if (r != cp.end && *r != '#') {
			rc = fail(&cp, r, "expected the end of the line after four numbers, found '%s'",
				word_at(r, cp.end, word, sizeof word));
			break;
		}
		if (c->n == 0 && v[0] != 0) {
			rc = fail(&cp, q, "%s", "the first point must have input 0");
			break;
		}
		if (c->n && v[0] <= c->in[0][c->n - 1]) {
			rc = fail(&cp, q, "%s", "inputs must increase from point to point");
			break;
		}
		for (int ch = 0; ch < 3 && c->n; ch++) {
			double prev = c->out[ch][c->n - 1];
			if (response ? v[ch + 1] <= prev : v[ch + 1] < prev) {
				rc = fail(&cp, q, response ? "the %s response must increase (a recorder's response "
					"has to be invertible)" : "the %s correction must not decrease", chan_name[ch]);
				break;
			}
		}
		if (rc)
			break;
		if (c->n == CAL_MAX_POINTS) {
			rc = fail(&cp, q, "more than %s points", "4096");
			break;
		}
		if (add_point(c, v)) {
			snprintf(err, errlen, "%s: out of memory", name);
			rc = -70;
		}
	}
	if (rc == 0 && !seen_magic) {
		snprintf(err, errlen, "%s:1:1: expected '" CAL_MAGIC " 1', found an empty file", name);
		rc = -65;
	} else if (rc == 0 && (c->n < 2 || c->in[0][c->n - 1] != 1)) {
		snprintf(err, errlen, "%s:%u:1: the curve must end with a point at input 1 (it has %zu point%s)",
			name, cp.line ? cp.line : 1, c->n, c->n == 1 ? "" : "s");
		rc = -65;
	}
	if (rc == 0 && response)
		invert(c);
	if (rc) {
		film_cal_free(c);
		return rc;
	}
	*cal = c;
	return 0;
}

int film_cal_load(const char *path, film_cal_t **cal, char *err, size_t errlen)
{
	FILE *f = fopen(path, "rb");
	if (!f) {
		snprintf(err, errlen, "%s: cannot open calibration file: %s", path, strerror(errno));
		return -66;
	}
	size_t cap = 1 << 16, n = 0;
	char *buf = malloc(cap);
	int rc = 0;
	while (buf) {
		size_t k = fread(buf + n, 1, cap - n, f);
		n += k;
		if (n < cap)
			break;
		if (cap >= (size_t)1 << 24) {
			snprintf(err, errlen, "%s: calibration file larger than 16 MiB", path);
			rc = -65;
			break;
		}
		char *b = realloc(buf, cap *= 2);
		if (!b) {
			free(buf);
			buf = NULL;
		} else
			buf = b;
	}
	if (!buf) {
		snprintf(err, errlen, "%s: out of memory", path);
		rc = -70;
	} else if (ferror(f)) {
		snprintf(err, errlen, "%s: read error", path);
		rc = -66;
	}
	fclose(f);
	if (rc == 0)
		rc = film_cal_parse(buf, n, path, cal, err, errlen);
	free(buf);
	return rc;
}

double film_cal_apply(const film_cal_t *c, int ch, double x)
{
	const double *in = c->in[ch], *o = c->out[ch];
	if (x <= in[0])
		return o[0];
	if (x >= in[c->n - 1])
		return o[c->n - 1];
	size_t lo = 0, hi = c->n - 1;      /* in[lo] <= x < in[hi] */
	while (hi - lo > 1) {
		size_t mid = (lo + hi) / 2;
		if (in[mid] <= x)
			lo = mid;
		else
			hi = mid;
	}
	return o[lo] + (o[hi] - o[lo]) * (x - in[lo]) / (in[hi] - in[lo]);
}

void film_cal_free(film_cal_t *c)
{
	if (!c)
		return;
	for (int ch = 0; ch < 3; ch++) {
		free(c->in[ch]);
		free(c->out[ch]);
	}
	free(c);
}
