/* frames.c: frame records (an animation's "# frame N t=T" ... "# end frame N" comments) and
 * frame lists ("0-99x2,150"), for locus-render --frames/--skip-existing and locus-meta cat. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "meta_frames.h"

int meta_frame_begin(meta_writer_t *w, long n, double t)
{
	char s[64];
	snprintf(s, sizeof s, "frame %ld t=%.9g", n, t);
	return meta_comment(w, s);
}

int meta_frame_end(meta_writer_t *w, long n)
{
	char s[40];
	snprintf(s, sizeof s, "end frame %ld", n);
	return meta_comment(w, s);
}

static void say(char *err, size_t errlen, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	if (err && errlen)
		vsnprintf(err, errlen, fmt, ap);
	va_end(ap);
}

/* "frame N t=T" (1, *n) or "end frame N" (2, *n); 0 for any other comment. A record that starts
 * right but is malformed (-1) is an error: it would otherwise hide a frame. */
static int record_of(const char *s, long *n)
{
	int kind = 0;
	if (!strncmp(s, "frame ", 6))
		kind = 1, s += 6;
	else if (!strncmp(s, "end frame ", 10))
		kind = 2, s += 10;
	else
		return 0;
	if (*s < '0' || *s > '9')
		return 0;     /* a comment that only starts like one ("# frame of the title") */
	char *end;
	errno = 0;
	long v = strtol(s, &end, 10);
	if (errno || v < 0 || v > META_FRAME_MAX)
		return -1;
	if (kind == 1 && strncmp(end, " t=", 3) != 0)
		return -1;
	if (kind == 2 && *end)
		return -1;
	*n = v;
	return kind;
}

static int push(meta_frames_t *f, long v)
{
	if (f->n == f->cap) {
		size_t cap = f->cap ? 2 * f->cap : 16;
		long *p = realloc(f->frames, cap * sizeof *p);
		if (!p)
			return -1;
		f->frames = p, f->cap = cap;
	}
	f->frames[f->n++] = v;
	return 0;
}

int meta_frames_scan(const char *path, meta_frames_t *out, char *err, size_t errlen)
{
	memset(out, 0, sizeof *out);
	meta_reader_t *r = meta_reader_open(path, err, errlen);
	if (!r)
		return errno == ENOMEM ? -70 : -66;
	meta_cmd_t c;
	int rc, status = 0;
	long open = -1;             /* the frame whose records are open, -1 none */
	unsigned long pages = 0, pages_in = 0;   /* pages in the file, in the open frame */
	while ((rc = meta_read(r, &c)) > 0) {
		uint64_t at = meta_reader_position(r);
		const char *where = meta_reader_is_binary(r) ? "byte" : "line";
		if (c.op == META_PAGE) {
			pages++, pages_in++;
			out->pages++;
			if (open < 0 && out->records) {
				say(err, errlen, "%s: %s %llu: expected a frame record '# frame N' before the page, found none",
					path, where, (unsigned long long)at);
				status = -65;
				break;
			}
			continue;
		}
		if (c.op != META_COMMENT)
			continue;
		long n;
		int k = record_of(c.str, &n);
		if (k == 0)
			continue;
		if (k < 0) {
			say(err, errlen, "%s: %s %llu: expected a frame record '# frame N t=T' or '# end frame N', found '# %.60s'",
				path, where, (unsigned long long)at, c.str);
			status = -65;
			break;
		}
		if (!out->records && pages) {
			say(err, errlen, "%s: %s %llu: expected a frame record before the first page, found it after",
				path, where, (unsigned long long)at);
			status = -65;
			break;
		}
		out->records = 1;
		if (k == 1 && open >= 0) {
			say(err, errlen, "%s: %s %llu: expected '# end frame %ld', found frame %ld begun inside it",
				path, where, (unsigned long long)at, open, n);
			status = -65;
			break;
		}
		if (k == 2 && open != n) {
			if (open < 0)
				say(err, errlen, "%s: %s %llu: expected '# frame %ld' before '# end frame %ld', found none",
					path, where, (unsigned long long)at, n, n);
			else
				say(err, errlen, "%s: %s %llu: expected '# end frame %ld', found '# end frame %ld'",
					path, where, (unsigned long long)at, open, n);
			status = -65;
			break;
		}
		if (k == 2 && !pages_in) {
			say(err, errlen, "%s: %s %llu: expected the pages of frame %ld, found none", path, where,
				(unsigned long long)at, n);
			status = -65;
			break;
		}
		if (k == 1) {
			if (push(out, n)) {
				say(err, errlen, "%s: out of memory", path);
				status = -70;
				break;
			}
			open = n, pages_in = 0;
		} else {
			open = -1;
		}
	}
	if (!status && rc < 0) {
		say(err, errlen, "%s", meta_reader_error(r));
		status = rc == META_ENOMEM ? -70 : rc == META_EIO ? -74 : -65;
	}
	if (!status && open >= 0) {
		say(err, errlen, "%s: expected '# end frame %ld', found the end of the file (frame %ld is not complete)",
			path, open, open);
		status = -65;
	}
	if (!status && !pages) {
		say(err, errlen, "%s: expected a page, found none", path);
		status = -65;
	}
	out->binary = meta_reader_is_binary(r);
	meta_reader_free(r);
	if (status)
		meta_frames_free(out);
	return status;
}

int meta_frames_probe(const char *path)
{
	meta_reader_t *r = meta_reader_open(path, NULL, 0);
	if (!r)
		return 0;
	meta_cmd_t c;
	long n;
	int found = 0;
	while (meta_read(r, &c) > 0 && c.op == META_COMMENT)
		if (record_of(c.str, &n) == 1) {
			found = 1;
			break;
		}
	meta_reader_free(r);
	return found;
}

void meta_frames_free(meta_frames_t *f)
{
	free(f->frames);
	f->frames = NULL;
	f->n = f->cap = 0;
}

/* an unsigned decimal number 0..META_FRAME_MAX at *s; advances *s; -1 if none or too large */
static long number(const char **s)
{
	const char *p = *s;
	long v = 0;
	if (*p < '0' || *p > '9')
		return -1;
	while (*p >= '0' && *p <= '9') {
		v = v * 10 + (*p++ - '0');
		if (v > META_FRAME_MAX)
			return -1;
	}
	*s = p;
	return v;
}

static int cmp_long(const void *a, const void *b)
{
	long x = *(const long *)a, y = *(const long *)b;
	return x < y ? -1 : x > y;
}

int meta_frame_list_parse(const char *spec, size_t max_frames, long **list, size_t *n, char *err,
		size_t errlen)
{
	*list = NULL, *n = 0;
	const char *s = spec;
	/* "N" alone: a count */
	long count = number(&s);
	if (count >= 0 && !*s) {
		if (count < 1 || (size_t)count > max_frames) {
			say(err, errlen, "expected a frame count from 1 to %zu, found '%s'", max_frames, spec);
			return -1;
		}
		long *l = malloc((size_t)count * sizeof *l);
		if (!l) {
			say(err, errlen, "out of memory for %ld frames", count);
			return -3;
		}
		for (long k = 0; k < count; k++)
			l[k] = k;
		*list = l, *n = (size_t)count;
		return 0;
	}
	/* a comma list: count first, then fill */
	size_t total = 0;
	for (int pass = 0; pass < 2; pass++) {
		size_t k = 0;
		s = spec;
		for (;;) {
			const char *item = s;
			long a = number(&s), b, step = 1;
			if (a < 0)
				goto bad;
			b = a;
			if (*s == '-') {
				s++;
				if ((b = number(&s)) < 0 || b < a)
					goto bad;
				if (*s == 'x') {
					s++;
					if ((step = number(&s)) < 1)
						goto bad;
				}
			}
			if (*s && *s != ',')
				goto bad;
			size_t m = (size_t)((b - a) / step) + 1;
			if (pass == 0) {
				if (m > max_frames - total) {
					say(err, errlen, "'%s': expected at most %zu frames, found more", spec, max_frames);
					return -1;
				}
				total += m;
			} else {
				for (long v = a; v <= b; v += step)
					(*list)[k++] = v;
			}
			if (!*s)
				break;
			s++;
			continue;
		bad:
			say(err, errlen, "expected N, or a comma list of A, A-B and A-BxS (0 <= A <= B <= %ld, S >= 1), "
				"found '%.*s'", META_FRAME_MAX, (int)strcspn(item, ","), item);
			free(*list);
			*list = NULL;
			return -1;
		}
		if (pass == 0 && !(*list = malloc(total * sizeof **list))) {
			say(err, errlen, "out of memory for %zu frames", total);
			return -3;
		}
	}
	qsort(*list, total, sizeof **list, cmp_long);
	for (size_t k = 1; k < total; k++)
		if ((*list)[k] == (*list)[k - 1]) {
			say(err, errlen, "'%s': frame %ld is named twice", spec, (*list)[k]);
			free(*list);
			*list = NULL;
			return -1;
		}
	*n = total;
	return 0;
}

/* ---- Frame patterns: OUT with one %d or %0Nd (N 1..9) and any %% */

/* 1 when out is a frame pattern, 0 when it holds no '%', -1 (message in err) when it is malformed */
int meta_frame_pattern_check(const char *out, char *err, size_t errlen)
{
	int conv = 0;
	for (const char *p = out; *p; p++) {
		if (*p != '%')
			continue;
		if (p[1] == '%') {
			p++;
			continue;
		}
		const char *q = p + 1;
		if (*q == '0')
			q++;
		if (*q >= '1' && *q <= '9')
			q++;
		if (*q != 'd') {
			say(err, errlen, "-o '%s': expected a frame pattern %%d or %%0Nd (N 1 to 9), or %%%% for a"
				" percent sign, found '%.*s'", out, (int)(q - p + (*q != 0)), p);
			return -1;
		}
		if (conv++) {
			say(err, errlen, "-o '%s': expected one frame number in the pattern, found two", out);
			return -1;
		}
		p = q;
	}
	return conv;
}

/* The file name of frame fr (malloc'd), or NULL when out of memory. */
char *meta_frame_pattern_name(const char *pat, long fr)
{
	size_t n = strlen(pat) + 16;
	char *s = malloc(n), *o = s;
	if (!s)
		return NULL;
	for (const char *p = pat; *p; p++) {
		if (*p != '%') {
			*o++ = *p;
			continue;
		}
		if (p[1] == '%') {
			*o++ = '%';
			p++;
			continue;
		}
		int zero = 0, width = 0;
		p++;
		if (*p == '0')
			zero = 1, p++;
		if (*p >= '1' && *p <= '9')
			width = *p++ - '0';
		o += sprintf(o, zero ? "%0*ld" : "%*ld", width, fr);
	}
	*o = 0;
	return s;
}
