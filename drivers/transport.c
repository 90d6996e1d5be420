/* transport.c: file and stdio transports with atomic temp+rename; device links reserved. */
#include <errno.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "transport.h"

#define IOBUF (1 << 16)

struct io_transport {
	int fd;
	int std;          /* stdin/stdout: never closed, never renamed */
	int writing;
	char *name;       /* as given */
	char *tmp;        /* temporary path (files being written) */
	unsigned char *buf;
	size_t nbuf;
	int failed;
	char err[512];
};

static int set_err(io_transport_t *t, const char *what)
{
	snprintf(t->err, sizeof t->err, "%s: %s: %s", t->std ? (t->writing ? "<stdout>" : "<stdin>") :
		t->name, what, strerror(errno));
	t->failed = 1;
	return -1;
}

static int reserved(const char *name, char *err, size_t errlen)
{
	static const char *const schemes[] = { "serial:", "usb:", "hid:" };
	for (size_t k = 0; k < 3; k++)
		if (strncmp(name, schemes[k], strlen(schemes[k])) == 0) {
			snprintf(err, errlen, "%s: %.*s transports are not supported yet", name,
				(int)strlen(schemes[k]) - 1, schemes[k]);
			return 1;
		}
	return 0;
}

static io_transport_t *alloc(const char *name, int writing)
{
	io_transport_t *t = calloc(1, sizeof *t);
	if (!t)
		return NULL;
	t->name = strdup(name);
	t->buf = malloc(IOBUF);
	t->writing = writing;
	t->fd = -1;
	if (!t->name || !t->buf) {
		free(t->name);
		free(t->buf);
		free(t);
		return NULL;
	}
	return t;
}

static void destroy(io_transport_t *t)
{
	free(t->name);
	free(t->tmp);
	free(t->buf);
	free(t);
}

io_transport_t *io_open_write(const char *name, char *err, size_t errlen)
{
	if (reserved(name, err, errlen))
		return NULL;
	io_transport_t *t = alloc(name, 1);
	if (!t) {
		snprintf(err, errlen, "%s: out of memory", name);
		return NULL;
	}
	if (strcmp(name, "-") == 0) {
		t->std = 1;
		t->fd = 1;
		return t;
	}
	size_t n = strlen(name) + 16;
	t->tmp = malloc(n);
	if (!t->tmp) {
		snprintf(err, errlen, "%s: out of memory", name);
		destroy(t);
		return NULL;
	}
	snprintf(t->tmp, n, "%s.tmpXXXXXX", name);
	t->fd = mkstemp(t->tmp);
	if (t->fd < 0) {
		snprintf(err, errlen, "%s: cannot create: %s", name, strerror(errno));
		destroy(t);
		return NULL;
	}
	fchmod(t->fd, 0644);
	return t;
}

io_transport_t *io_open_read(const char *name, char *err, size_t errlen)
{
	if (reserved(name, err, errlen))
		return NULL;
	io_transport_t *t = alloc(name, 0);
	if (!t) {
		snprintf(err, errlen, "%s: out of memory", name);
		return NULL;
	}
	if (strcmp(name, "-") == 0) {
		t->std = 1;
		t->fd = 0;
		return t;
	}
	t->fd = open(name, O_RDONLY);
	if (t->fd < 0) {
		snprintf(err, errlen, "%s: cannot open: %s", name, strerror(errno));
		destroy(t);
		return NULL;
	}
	return t;
}

int io_flush(io_transport_t *t)
{
	if (!t->writing || t->failed)
		return t->failed ? -1 : 0;
	size_t off = 0;
	while (off < t->nbuf) {
		ssize_t w = write(t->fd, t->buf + off, t->nbuf - off);
		if (w < 0) {
			if (errno == EINTR)
				continue;
			return set_err(t, "write failed");
		}
		off += (size_t)w;
	}
	t->nbuf = 0;
	return 0;
}

int io_write(io_transport_t *t, const void *buf, size_t n)
{
	const unsigned char *p = buf;
	if (t->failed)
		return -1;
	while (n > 0) {
		if (t->nbuf == IOBUF && io_flush(t))
			return -1;
		size_t c = IOBUF - t->nbuf < n ? IOBUF - t->nbuf : n;
		memcpy(t->buf + t->nbuf, p, c);
		t->nbuf += c;
		p += c;
		n -= c;
	}
	return 0;
}

long io_read(io_transport_t *t, void *buf, size_t n)
{
	for (;;) {
		ssize_t r = read(t->fd, buf, n);
		if (r >= 0)
			return (long)r;
		if (errno != EINTR)
			return set_err(t, "read failed");
	}
}

int io_close(io_transport_t *t, int how)
{
	int rc = 0;
	if (!t)
		return 0;
	if (t->writing && how != IO_ABORT)
		rc = io_flush(t);
	if (!t->std && t->fd >= 0) {
		if (close(t->fd) < 0 && rc == 0 && how != IO_ABORT)
			rc = set_err(t, "close failed");
	}
	t->fd = -1;
	if (t->writing && t->tmp) {
		if (how == IO_KEEP && rc == 0)
			return 0;
		if (how == IO_COMMIT && rc == 0) {
			if (rename(t->tmp, t->name) < 0)
				rc = set_err(t, "cannot rename into place");
		}
		if (how != IO_COMMIT || rc != 0)
			unlink(t->tmp);
	}
	if (rc && how == IO_KEEP)
		return rc;   /* caller still owns t for io_error; io_finish(t, 0) frees it */
	destroy(t);
	return rc;
}

int io_finish(io_transport_t *t, int commit, const char *target)
{
	int rc = 0;
	if (!t)
		return 0;
	if (t->tmp) {
		if (commit && rename(t->tmp, target ? target : t->name) < 0) {
			rc = -1;
			unlink(t->tmp);
		} else if (!commit) {
			unlink(t->tmp);
		}
	}
	destroy(t);
	return rc;
}

const char *io_error(const io_transport_t *t)
{
	return t->err;
}

const char *io_name(const io_transport_t *t)
{
	return t->name;
}

int io_is_std(const io_transport_t *t)
{
	return t->std;
}
