/* writer.h: the one buffered writer of the text and document devices (SVG, PostScript/PDF,
 * HP-GL): a buffer over a borrowed transport that counts the bytes it has passed on (PDF's
 * cross-reference table and HP-GL's resume points need exact offsets) and keeps the first error.
 *
 * Errors are sticky: after the first failed write every call returns it and writes nothing, so
 * callers may check once at the end of a statement. The error is a code (META_EIO when the
 * transport or the sink refused bytes or a format did not fit, META_ENOMEM from a filter); the
 * transport's own message and errno stay with the transport (io_error, io_errno).
 *
 * Two hooks keep language-specific work above this file: a filter sees every byte written
 * (PostScript's Flate and ASCII85 stage, ps/psenc.c) and passes its output on with dev_w_raw; a
 * sink takes the drained bytes instead of the transport (EPS's spool file, a device with no
 * output that only counts). The fast path (bytes that fit, no filter) is inline. */
#ifndef LOCUS_DEVICE_WRITER_H
#define LOCUS_DEVICE_WRITER_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "io/transport.h"

#define DEV_W_BUF (1 << 16)

typedef struct dev_writer dev_writer_t;
/* A stage every byte given to dev_w_write goes through; it writes its output with dev_w_raw.
 * Returns 0 or the writer's error. */
typedef int (*dev_w_filter_fn)(dev_writer_t *w, const void *p, size_t n);
/* A destination for drained bytes in place of the transport: 0, or -1 on failure. */
typedef int (*dev_w_sink_fn)(void *user, const void *p, size_t n);

/* Members are private to writer.c except pos and err (read them) and filter_user (the filter's
 * state, for the filter's owner). */
struct dev_writer {
	io_transport_t *t;          /* borrowed */
	uint64_t pos;               /* bytes taken (after the filter) since dev_w_init / set_transport */
	int err;                    /* 0, or the first error (<0) */
	dev_w_filter_fn filter;     /* NULL: bytes go straight into the buffer */
	void *filter_user;
	dev_w_sink_fn sink;         /* NULL: drained bytes go to t */
	void *sink_user;
	size_t n;                   /* bytes in buf */
	unsigned char buf[DEV_W_BUF];
};

/* Start a writer over t (which may be NULL until the first write: dev_w_set_transport). */
void dev_w_init(dev_writer_t *w, io_transport_t *t);
/* Point the writer at another transport (after dev_w_flush). pos restarts at 0. */
void dev_w_set_transport(dev_writer_t *w, io_transport_t *t);
/* Drain to fn(user, ...) instead of the transport from now on (fn NULL: the transport again).
 * What is buffered is not drained first: call dev_w_drain before if it belongs to the old one. */
void dev_w_set_sink(dev_writer_t *w, dev_w_sink_fn fn, void *user);
/* Put a filter in front of the buffer (fn NULL: none). */
void dev_w_set_filter(dev_writer_t *w, dev_w_filter_fn fn, void *user);

/* Out of line: bytes that do not fit, and errors. */
int dev_w_raw_slow(dev_writer_t *w, const void *p, size_t n);

/* Append n bytes after the filter (the filter's own output). Returns 0 or the sticky error. */
static inline int dev_w_raw(dev_writer_t *w, const void *p, size_t n)
{
	if (w->err || n > DEV_W_BUF - w->n)
		return dev_w_raw_slow(w, p, n);
	memcpy(w->buf + w->n, p, n);
	w->n += n;
	w->pos += n;
	return 0;
}

/* Append n bytes (through the filter if one is set). Returns 0 or the sticky error. */
static inline int dev_w_write(dev_writer_t *w, const void *p, size_t n)
{
	if (w->err)
		return w->err;
	if (w->filter)
		return w->filter(w, p, n);
	return dev_w_raw(w, p, n);
}

/* Append a NUL-terminated string. */
int dev_w_puts(dev_writer_t *w, const char *s);
/* Append a signed decimal integer. */
int dev_w_int(dev_writer_t *w, long long v);
/* Append a number given in thousandths as the shortest decimal (12, 12.5, -0.001). */
int dev_w_fix(dev_writer_t *w, long long thousandths);
/* Append a real with up to `decimals` decimals, trailing zeros dropped, never -0. */
int dev_w_real(dev_writer_t *w, double v, int decimals);
/* printf-style output of at most 1023 bytes (longer: META_EIO), for headers and comments. */
int dev_w_printf(dev_writer_t *w, const char *fmt, ...)
#ifdef __GNUC__
	__attribute__((format(printf, 2, 3)))
#endif
	;
/* Pass everything buffered to the sink or the transport, without io_flush. 0 or the error. */
int dev_w_drain(dev_writer_t *w);
/* dev_w_drain, then io_flush the transport (not a sink). 0 or the error. */
int dev_w_flush(dev_writer_t *w);

/* The fixed-point value v / 10^scale (scale 0..6; meta values have scale 3) rounded to at most
 * decimals places (halves away from zero, in integers), trailing zeros dropped, and never "-0":
 * 1500,3,3 -> "1.5"; -1,3,2 -> "0"; -2500,3,0 -> "-3". buf needs DEV_FMT_SIZE bytes. */
const char *dev_fmt_fix(char *buf, int64_t v, int scale, int decimals);
#define DEV_FMT_SIZE 32

#endif
