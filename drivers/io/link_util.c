/* link_util.c: the bottom of io/: the transport's error lines (io_set_err, io_oom, io_link_fail,
 * io_link_tempfail), the query strings of link names, and the clock of the links' waits. The
 * links, the files, the journal glue and transport.c use it; it calls none of them. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "io/link.h"

int io_set_err(io_transport_t *t, const char *what)
{
	const char *name = t->std ? (t->writing ? "<stdout>" : "<stdin>") : t->name;
	t->io_errno = errno;
	snprintf(t->err, sizeof t->err, "%s: %s: %s", name, what, strerror(errno));
	t->failed = 1;
	return -1;
}

_Thread_local int io_open_errno;

int io_oom(char *err, size_t errlen, const char *name)
{
	snprintf(err, errlen, "%s: out of memory", name);
	io_open_errno = ENOMEM;
	return -1;
}

/* "NAME: message" into t->err; the transport has failed (temporary: the failure may pass). */
static int link_fail(io_transport_t *t, int temporary, const char *fmt, va_list ap)
{
	int n = snprintf(t->err, sizeof t->err, "%s: ", t->name);
	if (n > 0 && (size_t)n < sizeof t->err)
		vsnprintf(t->err + n, sizeof t->err - (size_t)n, fmt, ap);
	t->failed = 1;
	t->temporary |= temporary;   /* a later message does not make a passing failure final */
	t->io_errno = errno = EIO;
	return -1;
}

int io_link_tempfail(io_transport_t *t, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	int rc = link_fail(t, 1, fmt, ap);
	va_end(ap);
	return rc;
}

int io_link_fail(io_transport_t *t, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	int rc = link_fail(t, 0, fmt, ap);
	va_end(ap);
	return rc;
}

int tr_query_next(const char **p, char *key, size_t klen, char *val, size_t vlen)
{
	const char *s = *p;
	if (!*s)
		return 0;
	const char *amp = strchr(s, '&'), *end = amp ? amp : s + strlen(s);
	const char *eq = memchr(s, '=', (size_t)(end - s));
	*p = amp ? amp + 1 : end;
	if (!eq || eq == s || (size_t)(eq - s) >= klen || (size_t)(end - eq - 1) >= vlen)
		return -1;
	memcpy(key, s, (size_t)(eq - s));
	key[eq - s] = 0;
	memcpy(val, eq + 1, (size_t)(end - eq - 1));
	val[end - eq - 1] = 0;
	return 1;
}

int tr_parse_long(const char *s, long lo, long hi, long *out)
{
	char *e;
	errno = 0;
	long v = strtol(s, &e, 10);
	if (!*s || *e || errno || v < lo || v > hi)
		return -1;
	*out = v;
	return 0;
}

long long tr_now_ms(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (long long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}
