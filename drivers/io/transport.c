/* transport.c: the buffered transport object (write, printf, read, flush, close) over stdio,
 * files (file.c) and device links (the io_link_t table: serial.c, tcp.c, usb.c, hid.c; their
 * journal in link_journal.c, signals during a job in signals.c), and the device listing, a
 * per-link operation. The top of io/: the links and the files below it use link_util.c (error
 * lines, query strings, the clock) and call nothing here. */
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "io/journal.h"
#include "io/link.h"

#define IOBUF (1 << 16)

void io_set_resume_command(const char *cmd)
{
	jn_set_command(cmd);
}

int io_is_link_name(const char *name)
{
	static const char *const schemes[] = { "serial:", "tcp:", "usb:", "hid:" };
	for (size_t k = 0; k < sizeof schemes / sizeof schemes[0]; k++)
		if (strncmp(name, schemes[k], strlen(schemes[k])) == 0)
			return 1;
	return 0;
}

/* The device links (a NULL open: reserved, "not supported yet"). */
static const io_link_t links[] = {
	{ "serial:", tr_serial_open, tr_serial_write, tr_serial_read, tr_serial_close, NULL, NULL, NULL },
	{ "tcp:", tr_tcp_open, tr_tcp_write, tr_tcp_read, tr_tcp_close, tr_tcp_acked, tr_tcp_drain, NULL },
	{ "usb:", tr_usb_open, tr_usb_write, tr_usb_read, tr_usb_close, NULL, NULL, tr_usb_list },
	{ "hid:", tr_hid_open, tr_hid_write, tr_hid_read, tr_hid_close, NULL, NULL, tr_hid_list },
};

/* A listing line of a link, formatted whole and written to the transport (user). */
static void list_put(void *user, const char *fmt, ...)
{
	va_list ap, aq;
	va_start(ap, fmt);
	va_copy(aq, ap);
	int n = vsnprintf(NULL, 0, fmt, aq);
	va_end(aq);
	char *line = n >= 0 ? malloc((size_t)n + 1) : NULL;
	if (line) {
		vsnprintf(line, (size_t)n + 1, fmt, ap);
		io_write(user, line, (size_t)n);
		free(line);
	} else if (!io_failed(user)) {   /* as io_printf fails */
		if (n >= 0)
			errno = ENOMEM;
		io_set_err(user, "cannot format");
	}
	va_end(ap);
}

int io_list_devices(io_transport_t *out, char *err, size_t errlen)
{
	for (size_t k = 0; k < sizeof links / sizeof links[0]; k++)
		if (links[k].list && links[k].list(list_put, out, err, errlen) < 0)
			return -1;
	return 0;
}

static const io_link_t *link_of(const char *name)
{
	for (size_t k = 0; k < sizeof links / sizeof links[0]; k++)
		if (strncmp(name, links[k].scheme, strlen(links[k].scheme)) == 0)
			return &links[k];
	return NULL;
}

static io_transport_t *alloc(const char *name, int writing, char *err, size_t errlen)
{
	io_transport_t *t = calloc(1, sizeof *t);
	if (t) {
		t->name = strdup(name);
		t->buf = malloc(IOBUF);
		t->cap = IOBUF;
		t->writing = writing;
		t->fd = -1;
		if (t->name && t->buf)
			return t;
		free(t->name);
		free(t->buf);
		free(t);
	}
	io_oom(err, errlen, name);
	return NULL;
}

static void destroy(io_transport_t *t)
{
	io_file_discard(t);
	free(t->name);
	free(t->target);
	free(t->buf);
	free(t->pend);
	free(t);
}

/* A device link: its open, or "not supported yet". */
static io_transport_t *open_link(const io_link_t *l, const char *name, int writing, char *err, size_t errlen)
{
	if (!l->open) {
		snprintf(err, errlen, "%s: %.*s transports are not supported yet", name,
			(int)strlen(l->scheme) - 1, l->scheme);
		return NULL;
	}
	io_transport_t *t = alloc(name, writing, err, errlen);
	if (!t)
		return NULL;
	t->link = l;
	t->in_place = 1;
	/* journal=FILE and resume=FILE are the transport's; the rest of the name is the link's. */
	char rest[1024], key[32], val[512], jpath[512] = "";
	int resume = 0, r;
	const char *q = strchr(name, '?');
	size_t hl = q ? (size_t)(q - name) : strlen(name), n;
	if (hl >= sizeof rest) {
		snprintf(err, errlen, "%s: name too long", name);
		destroy(t);
		return NULL;
	}
	n = (size_t)snprintf(rest, sizeof rest, "%.*s", (int)(hl - strlen(l->scheme)), name + strlen(l->scheme));
	for (const char *s = q ? q + 1 : "", *pair = s; (r = tr_query_next(&s, key, sizeof key, val, sizeof val)) != 0; pair = s) {
		if (r > 0 && (!strcmp(key, "journal") || !strcmp(key, "resume"))) {
			snprintf(jpath, sizeof jpath, "%s", val);
			resume = key[0] == 'r';
			continue;
		}
		size_t pl = strcspn(pair, "&");
		n += (size_t)snprintf(rest + n, n < sizeof rest ? sizeof rest - n : 0, "%c%.*s",
			n > hl - strlen(l->scheme) ? '&' : '?', (int)pl, pair);
	}
	if (n >= sizeof rest) {
		snprintf(err, errlen, "%s: name too long", name);
		destroy(t);
		return NULL;
	}
	if (jpath[0] && writing) {
		t->journal = resume ? jn_resume(jpath, name, err, errlen) : jn_create(jpath, name, err, errlen);
		if (!t->journal) {
			io_open_errno = errno == ENOMEM ? ENOMEM : EIO;
			destroy(t);
			return NULL;
		}
	}
	if (l->open(t, rest, writing, err, errlen) < 0) {
		t->link = NULL;   /* nothing to close */
		jn_close(t->journal, 0);
		t->journal = NULL;
		destroy(t);
		return NULL;
	}
	if (writing)
		tr_signals_take();
	return t;
}

static io_transport_t *open_write(const char *name, char *err, size_t errlen)
{
	const io_link_t *l = link_of(name);
	if (l)
		return open_link(l, name, 1, err, errlen);
	io_transport_t *t = alloc(name, 1, err, errlen);
	if (!t)
		return NULL;
	if (strcmp(name, "-") == 0) {
		t->std = t->in_place = 1;
		t->fd = 1;
		return t;
	}
	if (io_file_open(t, err, errlen) < 0) {
		int e = errno;   /* the cause the file's open met */
		destroy(t);
		if (!io_open_errno)
			io_open_errno = e;
		return NULL;
	}
	return t;
}

io_transport_t *io_open_write(const char *name, char *err, size_t errlen)
{
	io_open_errno = 0;
	io_transport_t *t = open_write(name, err, errlen);
	if (!t)
		errno = io_open_errno ? io_open_errno : EIO;
	return t;
}

io_transport_t *io_open_read(const char *name, char *err, size_t errlen)
{
	const io_link_t *l = link_of(name);
	if (l)
		return open_link(l, name, 0, err, errlen);
	io_transport_t *t = alloc(name, 0, err, errlen);
	if (!t)
		return NULL;
	if (strcmp(name, "-") == 0) {
		t->std = 1;
		t->fd = 0;
		return t;
	}
	t->fd = open(name, O_RDONLY | O_CLOEXEC);
	if (t->fd < 0) {
		snprintf(err, errlen, "%s: cannot open: %s", name, strerror(errno));
		destroy(t);
		return NULL;
	}
	return t;
}

/* Send bytes that are no part of the job (a resume's state restore) through the link. */
static int send_all(io_transport_t *t, const char *p, size_t n)
{
	while (n > 0) {
		long w = t->link->write(t, p, n);
		if (w <= 0) {
			if (!t->failed)
				io_set_err(t, "write failed");
			return -1;
		}
		t->link_out += (unsigned long long)w;
		p += w;
		n -= (size_t)w;
	}
	return 0;
}

int io_flush(io_transport_t *t)
{
	if (!t->writing || t->failed)
		return t->failed ? -1 : 0;
	size_t off = 0;
	while (off < t->nbuf) {
		if (t->link && tr_check_interrupt(t))
			return tr_journal_where(t);
		if (t->journal && jn_language(t->journal, t->buf + off, t->nbuf - off, t->err, sizeof t->err)) {
			t->failed = 1;
			return -1;
		}
		if (t->journal && jn_skipping(t->journal)) {
			/* resuming: the device has these bytes; then the state is restored */
			const char *restore;
			long k = jn_skip(t->journal, t->buf + off, t->nbuf - off, &restore, t->err, sizeof t->err);
			if (k < 0) {
				t->failed = 1;
				return -1;
			}
			off += (size_t)k;
			if (restore && send_all(t, restore, strlen(restore)))
				return tr_journal_where(t);
			continue;
		}
		ssize_t w = t->link ? t->link->write(t, t->buf + off, t->nbuf - off)
			: write(t->fd, t->buf + off, t->nbuf - off);
		if (w > 0 && t->link && tr_took(t, t->buf + off, (size_t)w) < 0)
			return -1;
		if (w < 0) {
			if (errno == EINTR)
				continue;
			if (t->link && t->failed)
				return tr_journal_where(t);   /* the link said it in its own words */
			return io_set_err(t, "write failed");
		}
		if (w == 0) {
			errno = EIO;
			return io_set_err(t, "write failed");
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
	if (t->link && t->writing && tr_check_interrupt(t))
		return tr_journal_where(t);
	while (n > 0) {
		if (t->nbuf == t->cap && io_flush(t))
			return -1;
		size_t c = t->cap - t->nbuf < n ? t->cap - t->nbuf : n;
		memcpy(t->buf + t->nbuf, p, c);
		t->nbuf += c;
		p += c;
		n -= c;
	}
	return 0;
}

int io_printf(io_transport_t *t, const char *fmt, ...)
{
	va_list ap;
	int rc = -1;
	if (t->failed)
		return -1;
	va_start(ap, fmt);
	for (;;) {
		va_list aq;
		size_t room = t->cap - t->nbuf;
		va_copy(aq, ap);
		int n = vsnprintf((char *)t->buf + t->nbuf, room, fmt, aq);
		va_end(aq);
		if (n < 0) {
			io_set_err(t, "cannot format");
			break;
		}
		if ((size_t)n < room) {   /* it fitted, with vsnprintf's NUL after it */
			t->nbuf += (size_t)n;
			rc = 0;
			break;
		}
		if (t->nbuf) {
			if (io_flush(t))
				break;
			continue;
		}
		unsigned char *b = realloc(t->buf, (size_t)n + 1);
		if (!b) {
			errno = ENOMEM;
			io_set_err(t, "cannot format");
			break;
		}
		t->buf = b;
		t->cap = (size_t)n + 1;
	}
	va_end(ap);
	return rc;
}

long io_read(io_transport_t *t, void *buf, size_t n)
{
	for (;;) {
		ssize_t r = t->link ? t->link->read(t, buf, n) : read(t->fd, buf, n);
		if (r >= 0)
			return (long)r;
		if (t->link && t->failed)
			return -1;
		if (errno != EINTR)
			return io_set_err(t, "read failed");
	}
}

int io_drain(io_transport_t *t)
{
	if (io_flush(t))
		return -1;
	if (!t->link || !t->writing || t->drained)
		return 0;
	t->drained = 1;
	if (t->link->drain && t->link->drain(t) < 0)
		return tr_journal_where(t);
	if (tr_confirm(t) < 0)
		return -1;
	if (t->link && tr_check_interrupt(t))
		return tr_journal_where(t);
	return 0;
}

/* Flush (unless aborting) and close the descriptor; standard output stays open, but a close
 * of a copy of it still reports what a close would (NFS reports late write errors there). */
static int finish_fd(io_transport_t *t, int how)
{
	int rc = 0;
	if (t->writing && how != IO_ABORT)
		rc = io_drain(t);
	if (rc == 0 && how != IO_ABORT && t->journal && jn_skipping(t->journal))
		rc = io_link_fail(t, "the job ended before the point the journal reached: resume with the "
			"same input and options");
	if (t->link) {
		if (how == IO_ABORT && !t->failed)
			tr_confirm(t);   /* the journal as far as the device got */
		if (t->link->close(t) < 0 && rc == 0 && how != IO_ABORT)
			rc = t->failed ? -1 : io_set_err(t, "close failed");
		t->link = NULL;
		if (t->writing)
			tr_signals_give();
		if (t->journal && jn_close(t->journal, rc == 0 && how != IO_ABORT && !t->failed) < 0 && rc == 0) {
			int e = errno;
			rc = io_link_fail(t, "cannot write the job journal: %s", strerror(e));
			t->io_errno = e;
		}
		t->journal = NULL;
		return rc;
	}
	if (t->fd < 0)
		return rc;
	if (t->std) {
		if (t->writing && how != IO_ABORT && rc == 0) {
			int d = dup(t->fd);
			if (d >= 0 && close(d) < 0)
				rc = io_set_err(t, "close failed");
		}
	} else if (close(t->fd) < 0 && rc == 0 && how != IO_ABORT) {
		rc = io_set_err(t, "close failed");
	}
	t->fd = -1;
	return rc;
}

/* The end of a job whose link is closed (rc its result so far): a temporary file is renamed
 * over the target when commit and rc == 0, else removed; the message into err; t freed. */
static int settle(io_transport_t *t, int commit, const char *target, int rc, char *err, size_t errlen)
{
	if (t->tmp) {   /* only writing makes a temporary */
		if (commit && rc == 0)
			rc = io_file_commit(t, target);
		else
			io_file_discard(t);
	}
	if (rc && err)
		snprintf(err, errlen, "%s", t->err);
	int e = rc ? io_errno(t) : 0;
	destroy(t);
	if (rc)
		errno = e ? e : EIO;   /* the failure's code outlives the transport */
	return rc;
}

int io_close_err(io_transport_t *t, int how, char *err, size_t errlen)
{
	if (!t)
		return 0;
	int rc = finish_fd(t, how);
	if (how == IO_KEEP)
		return rc;
	return settle(t, how == IO_COMMIT, NULL, rc, err, errlen);
}

int io_close(io_transport_t *t, int how)
{
	return io_close_err(t, how, NULL, 0);
}

int io_finish(io_transport_t *t, int commit, const char *target, char *err, size_t errlen)
{
	if (!t)
		return 0;
	return settle(t, commit && !t->failed, target, 0, err, errlen);
}

const char *io_error(const io_transport_t *t)
{
	return t->err;
}

int io_failed(const io_transport_t *t)
{
	return t->failed;
}

int io_temporary(const io_transport_t *t)
{
	return t->failed && t->temporary;
}

int io_errno(const io_transport_t *t)
{
	return t->failed ? (t->io_errno ? t->io_errno : EIO) : 0;
}

const char *io_name(const io_transport_t *t)
{
	return t->name;
}

int io_is_std(const io_transport_t *t)
{
	return t->std;
}

int io_in_place(const io_transport_t *t)
{
	return t->in_place;
}
