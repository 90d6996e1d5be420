/* tcp.c: the network link: a raw job on a TCP port (AppSocket/JetDirect, 9100 by default). */
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <linux/tcp.h>   /* its tcp_info has tcpi_snd_wnd (glibc's does not) */
#include <poll.h>
#include <signal.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <linux/sockios.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>
#include "io/link.h"

typedef struct {
	int fd;
	long timeout_ms;
	long long sent;
	int fin;              /* the half-close went out (its FIN counts in the send queue) */
	long long acked;      /* the last count the peer had acknowledged */
	long long maxwnd;     /* the largest receive window the peer advertised */
	int consumed_all;     /* the peer closed cleanly having acknowledged every byte: read it all */
} tcp_t;

/* What the peer's TCP acknowledged: sent less what waits in the send queue (SIOCOUTQ, readable
 * after a reset too; the half-close's FIN counted out). */
static long long tcp_acked(tcp_t *s)
{
	int q = 0;
	if (ioctl(s->fd, SIOCOUTQ, &q) < 0 || q < 0)
		return s->acked;
	long long a = s->sent - q + s->fin;
	if (a > s->sent)
		a = s->sent;
	if (a > s->acked)
		s->acked = a;
	return s->acked;
}

/* The peer's advertised receive window now (TCP_INFO tcpi_snd_wnd), -1 when the kernel does not
 * say; the largest one seen is kept in maxwnd. */
static long long tcp_window(tcp_t *s)
{
	struct tcp_info ti;
	socklen_t tl = sizeof ti;
	memset(&ti, 0, sizeof ti);
	if (getsockopt(s->fd, IPPROTO_TCP, TCP_INFO, &ti, &tl) < 0
		|| tl < offsetof(struct tcp_info, tcpi_snd_wnd) + sizeof ti.tcpi_snd_wnd)
		return -1;
	if ((long long)ti.tcpi_snd_wnd > s->maxwnd)
		s->maxwnd = ti.tcpi_snd_wnd;
	return ti.tcpi_snd_wnd;
}

/* Connect to one address within ms: the descriptor, or -1 with errno. */
static int connect_one(const struct addrinfo *a, long ms)
{
	int fd = socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC | SOCK_NONBLOCK, a->ai_protocol);
	if (fd < 0)
		return -1;
	if (connect(fd, a->ai_addr, a->ai_addrlen) < 0) {
		if (errno != EINPROGRESS) {
			int e = errno;
			close(fd);
			errno = e;
			return -1;
		}
		struct pollfd pf = { fd, POLLOUT, 0 };
		int e = 0;
		socklen_t el = sizeof e;
		if (poll(&pf, 1, (int)ms) <= 0)
			e = ETIMEDOUT;
		else if (getsockopt(fd, SOL_SOCKET, SO_ERROR, &e, &el) < 0)
			e = errno;
		if (e) {
			close(fd);
			errno = e;
			return -1;
		}
	}
	return fd;
}

int tr_tcp_open(io_transport_t *t, const char *rest, int writing, char *err, size_t errlen)
{
	(void)writing;
	char host[256], port[16] = "9100", key[32], val[32];
	long timeout = 30, p;
	const char *q = strchr(rest, '?');
	size_t hl = q ? (size_t)(q - rest) : strlen(rest);
	const char *colon = NULL;
	for (size_t k = 0; k < hl; k++)
		if (rest[k] == ':')
			colon = rest + k;
	if (rest[0] == '[') {   /* [v6 address]:port */
		const char *rb = memchr(rest, ']', hl);
		colon = rb && rb + 1 < rest + hl && rb[1] == ':' ? rb + 1 : NULL;
	}
	size_t nl = colon ? (size_t)(colon - rest) : hl;
	if (colon) {
		size_t pl = hl - nl - 1;
		if (pl == 0 || pl >= sizeof port)
			goto bad_port;
		memcpy(port, colon + 1, pl);
		port[pl] = 0;
		if (tr_parse_long(port, 1, 65535, &p))
			goto bad_port;
	}
	if (rest[0] == '[' && nl >= 2) {
		rest++;
		nl -= 2;
	}
	if (nl == 0 || nl >= sizeof host) {
		snprintf(err, errlen, "%s: name a host: tcp:HOST[:PORT] (port 9100 by default)", t->name);
		return -1;
	}
	memcpy(host, rest, nl);
	host[nl] = 0;
	for (const char *s = q ? q + 1 : ""; ; ) {
		int r = tr_query_next(&s, key, sizeof key, val, sizeof val);
		if (r == 0)
			break;
		if (r < 0 || strcmp(key, "timeout") || tr_parse_long(val, 1, 3600, &timeout)) {
			snprintf(err, errlen, "%s: the one setting is timeout=SECONDS", t->name);
			return -1;
		}
	}
	struct addrinfo hints = { .ai_socktype = SOCK_STREAM }, *res;
	int g = getaddrinfo(host, port, &hints, &res);
	if (g) {
		snprintf(err, errlen, "%s: cannot find host '%s': %s", t->name, host, gai_strerror(g));
		return -1;
	}
	int fd = -1, e = 0;
	for (struct addrinfo *a = res; a && fd < 0; a = a->ai_next)
		if ((fd = connect_one(a, timeout * 1000)) < 0)
			e = errno;
	freeaddrinfo(res);
	if (fd < 0) {
		snprintf(err, errlen, "%s: cannot connect to %s port %s: %s%s", t->name, host, port, strerror(e),
			e == ECONNREFUSED ? " (is the printer on, and is raw printing on that port enabled?)" : "");
		return -1;
	}
	signal(SIGPIPE, SIG_IGN);   /* a dropped connection is an error to report, not a death */
	tcp_t *s = calloc(1, sizeof *s);
	if (!s) {
		close(fd);
		io_oom(err, errlen, t->name);
		return -1;
	}
	s->fd = fd;
	s->timeout_ms = timeout * 1000;
	t->link_state = s;
	if (t->journal) {
		/* what waits unacknowledged is kept for the journal: keep that queue modest */
		int sb = 65536;
		setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &sb, sizeof sb);
	}
	return 0;
bad_port:
	snprintf(err, errlen, "%s: bad port: tcp:HOST[:PORT] with PORT 1-65535", t->name);
	return -1;
}

/* 10 ms. */
static void sleep_brief(void)
{
	struct timespec ts = { 0, 10000000L };
	nanosleep(&ts, NULL);
}

long tr_tcp_write(io_transport_t *t, const void *buf, size_t n)
{
	tcp_t *s = t->link_state;
	for (;;) {
		ssize_t w = send(s->fd, buf, n, MSG_NOSIGNAL);
		if (w > 0) {
			s->sent += w;
			return (long)w;
		}
		if (w < 0 && errno != EAGAIN && errno != EINTR) {
			if (errno == EPIPE || errno == ECONNRESET)
				return io_link_tempfail(t, "the printer dropped the connection having taken %lld of "
					"%lld bytes sent", tcp_acked(s), s->sent);
			return io_link_fail(t, "send failed: %s", strerror(errno));
		}
		if (tr_check_interrupt(t))
			return -1;
		/* wait for room; a printer that closes its side meanwhile has dropped the job */
		struct pollfd pf = { s->fd, POLLOUT | POLLIN, 0 };
		int r = poll(&pf, 1, (int)s->timeout_ms);
		char c;
		ssize_t g = 1;
		if (r > 0 && (pf.revents & (POLLIN | POLLHUP | POLLERR)) && !(pf.revents & POLLOUT))
			g = recv(s->fd, &c, 1, MSG_PEEK | MSG_DONTWAIT);
		if (g == 0 || (g < 0 && errno != EAGAIN && errno != EINTR))
			return io_link_tempfail(t, "the printer closed the connection having taken %lld of %lld "
				"bytes sent", tcp_acked(s), s->sent);
		if (r > 0 && !(pf.revents & POLLOUT))
			sleep_brief();   /* a reply waits unread: no busy loop while the queue is full */
		if (r == 0)
			return io_link_tempfail(t, "the printer took nothing for %ld s after %lld bytes (busy or "
				"out of paper?)", s->timeout_ms / 1000, s->sent);
	}
}

long tr_tcp_read(io_transport_t *t, void *buf, size_t n)
{
	tcp_t *s = t->link_state;
	struct pollfd pf = { s->fd, POLLIN, 0 };
	if (poll(&pf, 1, (int)s->timeout_ms) == 0)
		return io_link_tempfail(t, "no reply within %ld s", s->timeout_ms / 1000);
	ssize_t r = recv(s->fd, buf, n, 0);
	return r < 0 && errno == EAGAIN ? 0 : (long)r;
}

/* Acknowledged is not consumed: bytes the peer's TCP acknowledged may still sit unread in its
 * receive buffer, and a printer that drops the connection (or is switched off) throws them
 * away. What the journal may count is the conservative point: the acknowledged bytes less what
 * the peer's receive buffer can hold. That buffer is bounded by twice the largest window the
 * peer advertised (Linux advertises at most the buffer's free space, and keeps at least half
 * the buffer's memory for its own overhead); when the kernel does not say, 256 KiB. Once the
 * peer closed cleanly after acknowledging everything (a socket closed with unread data resets
 * instead), it has read it all. */
long long tr_tcp_acked(io_transport_t *t)
{
	tcp_t *s = t->link_state;
	long long a = tcp_acked(s);
	if (s->consumed_all)
		return a;
	long long w = tcp_window(s);
	long long back = w < 0 && s->maxwnd == 0 ? 262144 : 2 * s->maxwnd;
	return a > back ? a - back : 0;
}

int tr_tcp_drain(io_transport_t *t)
{
	tcp_t *s = t->link_state;
	/* Half-close, then wait for the printer's close: a printer that closes cleanly has read
	 * everything (a socket closed with unread data answers with a reset). A reset or an error at
	 * any point, even after every byte was acknowledged, is a drop: the printer may have thrown
	 * away what waited in its buffer. */
	if (shutdown(s->fd, SHUT_WR) == 0)
		s->fin = 1;
	char tmp[512];
	int closed = 0, err = 0;
	long long last = tr_now_ms(), had = tcp_acked(s);
	for (;;) {
		if (tr_check_interrupt(t))
			return -1;
		long long a = tcp_acked(s);
		tcp_window(s);
		if (a > had)
			had = a, last = tr_now_ms();   /* progress: the wait starts again */
		long left = (long)(last + s->timeout_ms - tr_now_ms());
		struct pollfd pf = { s->fd, POLLIN, 0 };
		if (left <= 0)
			break;
		int r = poll(&pf, 1, left < 200 ? (int)left : 200);
		if (r <= 0)
			continue;
		ssize_t g = recv(s->fd, tmp, sizeof tmp, 0);
		if (g == 0) {
			closed = 1;
			break;
		}
		if (g < 0 && errno != EAGAIN && errno != EINTR) {
			err = errno;
			break;
		}
	}
	long long a = tcp_acked(s);
	if (err == ECONNRESET || err == EPIPE)
		return io_link_tempfail(t, "the printer dropped the connection having taken %lld of %lld "
			"bytes sent%s", a, s->sent, a == s->sent ? " (a reset after the last byte: what it had "
			"not read yet is lost)" : "");
	if (err)
		return io_link_tempfail(t, "waiting for the printer to confirm the job: %s", strerror(err));
	if (a < s->sent)
		return io_link_tempfail(t, "the printer %s having taken %lld of %lld bytes sent",
			closed ? "closed the connection" : "stopped acknowledging", a, s->sent);
	if (closed) {
		s->consumed_all = 1;
		return 0;
	}
	/* acknowledged all, still open: taken only when its receive buffer is empty again, that is,
	 * its window is back to the largest it advertised */
	long long w = tcp_window(s);
	if (w >= 0 && w >= s->maxwnd) {
		s->consumed_all = 1;
		return 0;
	}
	return io_link_tempfail(t, "the printer acknowledged all %lld bytes but did not read them "
		"(or close the connection) within %ld s", s->sent, s->timeout_ms / 1000);
}

int tr_tcp_close(io_transport_t *t)
{
	tcp_t *s = t->link_state;
	int rc = 0;
	close(s->fd);
	free(s);
	t->link_state = NULL;
	return rc;
}
