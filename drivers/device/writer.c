/* writer.c: the buffered device writer (writer.h) and its number formatting. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "locus_meta.h"
#include "device/writer.h"

void dev_w_init(dev_writer_t *w, io_transport_t *t)
{
	memset(w, 0, offsetof(dev_writer_t, buf));
	w->t = t;
}

void dev_w_set_transport(dev_writer_t *w, io_transport_t *t)
{
	w->t = t;
	w->pos = 0;
	w->n = 0;
}

void dev_w_set_sink(dev_writer_t *w, dev_w_sink_fn fn, void *user)
{
	w->sink = fn;
	w->sink_user = user;
}

void dev_w_set_filter(dev_writer_t *w, dev_w_filter_fn fn, void *user)
{
	w->filter = fn;
	w->filter_user = user;
}

/* Pass bytes on: to the sink or the transport. 0 or -1. */
static int pass(dev_writer_t *w, const void *p, size_t n)
{
	if (w->sink)
		return w->sink(w->sink_user, p, n);
	return w->t ? io_write(w->t, p, n) : -1;
}

int dev_w_raw_slow(dev_writer_t *w, const void *p, size_t n)
{
	if (w->err)
		return w->err;
	if (w->n + n > sizeof w->buf) {
		if (w->n && pass(w, w->buf, w->n))
			return w->err = META_EIO;
		w->n = 0;
		if (n > sizeof w->buf) {
			if (pass(w, p, n))
				return w->err = META_EIO;
			w->pos += n;
			return 0;
		}
	}
	memcpy(w->buf + w->n, p, n);
	w->n += n;
	w->pos += n;
	return 0;
}

int dev_w_puts(dev_writer_t *w, const char *s)
{
	return dev_w_write(w, s, strlen(s));
}

int dev_w_int(dev_writer_t *w, long long v)
{
	char b[24], *e = b + sizeof b, *p = e;
	unsigned long long u = v < 0 ? 0ULL - (unsigned long long)v : (unsigned long long)v;
	do {
		*--p = (char)('0' + u % 10);
		u /= 10;
	} while (u);
	if (v < 0)
		*--p = '-';
	return dev_w_write(w, p, (size_t)(e - p));
}

int dev_w_fix(dev_writer_t *w, long long t)
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
	return dev_w_write(w, b, (size_t)n);
}

int dev_w_real(dev_writer_t *w, double v, int decimals)
{
	char b[64];
	int n = snprintf(b, sizeof b, "%.*f", decimals, v);
	if (n <= 0 || (size_t)n >= sizeof b)
		return w->err = META_EIO;
	if (strchr(b, '.')) {
		while (b[n - 1] == '0')
			b[--n] = 0;
		if (b[n - 1] == '.')
			b[--n] = 0;
	}
	if (strcmp(b, "-0") == 0)
		return dev_w_write(w, "0", 1);
	return dev_w_write(w, b, (size_t)n);
}

int dev_w_printf(dev_writer_t *w, const char *fmt, ...)
{
	char b[1024];
	va_list ap;
	va_start(ap, fmt);
	int n = vsnprintf(b, sizeof b, fmt, ap);
	va_end(ap);
	if (n < 0 || (size_t)n >= sizeof b)
		return w->err = META_EIO;
	return dev_w_write(w, b, (size_t)n);
}

int dev_w_drain(dev_writer_t *w)
{
	if (w->err)
		return w->err;
	if (w->n && pass(w, w->buf, w->n))
		return w->err = META_EIO;
	w->n = 0;
	return 0;
}

int dev_w_flush(dev_writer_t *w)
{
	if (dev_w_drain(w))
		return w->err;
	if (!w->sink && w->t && io_flush(w->t))
		return w->err = META_EIO;
	return 0;
}

const char *dev_fmt_fix(char *buf, int64_t v, int scale, int decimals)
{
	static const int64_t pow10[7] = { 1, 10, 100, 1000, 10000, 100000, 1000000 };
	if (scale < 0)
		scale = 0;
	if (scale > 6)
		scale = 6;
	if (decimals < 0)
		decimals = 0;
	if (decimals > scale)
		decimals = scale;
	/* round v / 10^scale to decimals places, halves away from zero, in integers */
	int64_t drop = pow10[scale - decimals];
	int neg = v < 0;
	uint64_t a = neg ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
	a = (a + (uint64_t)drop / 2) / (uint64_t)drop;
	uint64_t unit = (uint64_t)pow10[decimals], ip = a / unit, fp = a % unit;
	char *o = buf;
	if (neg && a != 0)
		*o++ = '-';   /* a value that rounds to zero prints as 0, never -0 */
	o += sprintf(o, "%llu", (unsigned long long)ip);
	if (fp) {
		char f[24];
		snprintf(f, sizeof f, "%0*llu", decimals, (unsigned long long)fp);
		int len = decimals;
		while (len > 0 && f[len - 1] == '0')
			len--;
		f[len] = 0;
		sprintf(o, ".%s", f);
	} else {
		*o = 0;
	}
	return buf;
}
