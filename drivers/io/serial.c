/* serial.c: the serial link: termios set-up, XON/XOFF, RTS/CTS, and (flow=escb) the registered
 * language's own pacing (io/lang.h: for HP-GL, ESC.L buffer size and OI identification at the
 * open, ESC.B free space around each chunk, OE at the end) over the line's replies. */
#include <errno.h>
#include <fcntl.h>
#include <grp.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>
#include "io/link.h"

enum { FLOW_NONE, FLOW_XONXOFF, FLOW_RTSCTS, FLOW_ESCB };
static const char *const flow_names[] = { "none", "xonxoff", "rtscts", "escb" };

typedef struct {
	int fd;
	struct termios saved;  /* the line as we found it: put back when the open fails */
	int flow;
	long timeout_ms;      /* no progress for this long: the write fails */
	io_pace_t pace;       /* escb: the device's buffer, its free space, its identification */
} serial_t;

static const struct { long baud; speed_t code; } bauds[] = {
	{ 300, B300 }, { 600, B600 }, { 1200, B1200 }, { 1800, B1800 }, { 2400, B2400 },
	{ 4800, B4800 }, { 9600, B9600 }, { 19200, B19200 }, { 38400, B38400 },
	{ 57600, B57600 }, { 115200, B115200 }, { 230400, B230400 }, { 460800, B460800 },
	{ 921600, B921600 },
};

static void sleep_ms(long ms)
{
	struct timespec ts = { ms / 1000, (ms % 1000) * 1000000L };
	while (nanosleep(&ts, &ts) < 0 && errno == EINTR)
		;
}

/* Write all n bytes, waiting while the line is held (XOFF, CTS) up to the timeout. */
/* Write n bytes: all of them (0), or with once, those of the first write the line took (the
 * count): the job's bytes then reach the journal as the kernel takes them, so a sender killed
 * mid-job leaves a journal that knows what the device holds, to the byte. -1 (message set). */
static long put_n(io_transport_t *t, serial_t *s, const void *buf, size_t n, int once)
{
	const unsigned char *p = buf;
	long long last = tr_now_ms();
	while (n > 0) {
		ssize_t w = write(s->fd, p, n);
		if (w > 0 && once)
			return (long)w;
		if (w > 0) {
			p += w;
			n -= (size_t)w;
			last = tr_now_ms();
			continue;
		}
		if (w < 0 && errno != EAGAIN && errno != EINTR) {
			if (errno == EIO || errno == ENXIO)
				return io_link_tempfail(t, "the line went away mid-job (unplugged?): %s", strerror(errno));
			return io_link_fail(t, "write failed: %s", strerror(errno));
		}
		if (tr_check_interrupt(t))
			return -1;
		long left = s->timeout_ms - (long)(tr_now_ms() - last);
		if (left <= 0)
			return io_link_tempfail(t, "the device took nothing for %ld s (%s held: is it online "
				"and the flow control set as on the device?)", s->timeout_ms / 1000,
				s->flow == FLOW_XONXOFF ? "XOFF" : s->flow == FLOW_RTSCTS ? "CTS" : "the line");
		struct pollfd pf = { s->fd, POLLOUT, 0 };
		poll(&pf, 1, left < 200 ? (int)left : 200);
	}
	return 0;
}

static int put_all(io_transport_t *t, serial_t *s, const void *buf, size_t n)
{
	return (int)put_n(t, s, buf, n, 0);
}

/* Read one reply terminated by CR (or LF) into buf, within ms. 0, or -1 (message set). */
static int get_reply(io_transport_t *t, serial_t *s, const char *what, char *buf, size_t len, long ms)
{
	size_t n = 0;
	long long end = tr_now_ms() + ms;
	for (;;) {
		if (tr_check_interrupt(t))
			return -1;
		long left = (long)(end - tr_now_ms());
		if (left <= 0)
			return io_link_tempfail(t, "no answer to %s within %ld ms: is the plotter on, and "
				"does the cable carry its replies? (flow=xonxoff needs none)", what, ms);
		struct pollfd pf = { s->fd, POLLIN, 0 };
		if (poll(&pf, 1, (int)left) <= 0)
			continue;
		char c;
		ssize_t r = read(s->fd, &c, 1);
		if (r < 0 && (errno == EAGAIN || errno == EINTR))
			continue;
		if (r <= 0)
			return io_link_tempfail(t, "reading the answer to %s: %s", what, r ? strerror(errno) : "end of file");
		if (c == '\r' || c == '\n') {
			if (n == 0)
				continue;   /* a CR LF pair's second half */
			buf[n] = 0;
			return 0;
		}
		if (n + 1 < len)
			buf[n++] = c;
	}
}

/* Send a query and read its numeric answer. */
static int ask_number(io_transport_t *t, serial_t *s, const char *q, const char *what, long ms, long *out)
{
	char rep[64];
	tcflush(s->fd, TCIFLUSH);   /* nothing stale answers for this one */
	if (put_all(t, s, q, strlen(q)) || get_reply(t, s, what, rep, sizeof rep, ms))
		return -1;
	char *e;
	*out = strtol(rep, &e, 10);
	if (e == rep)
		return io_link_fail(t, "the answer to %s is no number: '%s'", what, rep);
	return 0;
}

/* The line as the language's handshakes use it (io/lang.h). */
static int chan_put(io_transport_t *t, const void *buf, size_t n)
{
	return put_all(t, t->link_state, buf, n);
}

static int chan_ask(io_transport_t *t, const char *q, const char *what, long ms, long *out)
{
	return ask_number(t, t->link_state, q, what, ms, out);
}

static int chan_reply(io_transport_t *t, const char *what, char *buf, size_t len, long ms)
{
	return get_reply(t, t->link_state, what, buf, len, ms);
}

static void chan_discard(io_transport_t *t)
{
	serial_t *s = t->link_state;
	tcflush(s->fd, TCIFLUSH);
}

static io_chan_t chan(io_transport_t *t, serial_t *s)
{
	return (io_chan_t){ t, chan_put, chan_ask, chan_reply, chan_discard, io_link_fail, s->timeout_ms };
}

/* 1 when path is the system console (/dev/console, /dev/tty, or a line the kernel writes its
 * console to, /sys/class/tty/console/active): a job is never sent there. */
static int is_console(const char *path)
{
	char real[4096], act[256];
	if (!realpath(path, real))
		return 0;
	const char *b = strrchr(real, '/') ? strrchr(real, '/') + 1 : real;
	if (!strcmp(b, "console") || !strcmp(b, "tty"))
		return 1;
	FILE *f = fopen("/sys/class/tty/console/active", "r");
	if (!f)
		return 0;
	int hit = 0;
	while (fscanf(f, "%255s", act) == 1)
		if (!strcmp(act, b))
			hit = 1;
	fclose(f);
	return hit;
}

static int open_fail(char *err, size_t errlen, const char *path, int e)
{
	if (e == ENOENT || e == ENODEV || e == ENXIO)
		snprintf(err, errlen, "serial:%s: no such serial device: is it plugged in and powered? "
			"(ls /dev/ttyUSB* /dev/ttyACM* /dev/ttyS*)", path);
	else if (e == EACCES || e == EPERM) {
		struct stat st;
		struct group *g = stat(path, &st) == 0 ? getgrgid(st.st_gid) : NULL;
		const char *gn = g ? g->gr_name : "dialout";
		snprintf(err, errlen, "serial:%s: permission denied: add yourself to the group '%s' "
			"(sudo usermod -aG %s $USER, then log in again)", path, gn, gn);
	} else if (e == EBUSY)
		snprintf(err, errlen, "serial:%s: the device is busy: another program holds it", path);
	else
		snprintf(err, errlen, "serial:%s: cannot open: %s", path, strerror(e));
	return -1;
}

/* Parse the query string into termios settings. */
static int parse(const char *q, const char *name, struct termios *tio, serial_t *s, char *err, size_t errlen)
{
	char key[32], val[64];
	long baud = 9600, bits = 8, stop = 1;
	int parity = 'n', r;
	while ((r = tr_query_next(&q, key, sizeof key, val, sizeof val)) != 0) {
		long v;
		if (r < 0) {
			snprintf(err, errlen, "%s: a setting is not KEY=VALUE (baud, parity, bits, stop, flow, timeout)", name);
			return -1;
		}
		if (!strcmp(key, "baud")) {
			if (tr_parse_long(val, 1, 4000000, &baud))
				goto bad;
		} else if (!strcmp(key, "bits")) {
			if (tr_parse_long(val, 5, 8, &bits))
				goto bad;
		} else if (!strcmp(key, "stop")) {
			if (tr_parse_long(val, 1, 2, &stop))
				goto bad;
		} else if (!strcmp(key, "timeout")) {
			if (tr_parse_long(val, 1, 3600, &v))
				goto bad;
			s->timeout_ms = v * 1000;
		} else if (!strcmp(key, "parity")) {
			if (!strcmp(val, "none") || !strcmp(val, "even") || !strcmp(val, "odd"))
				parity = val[0];
			else
				goto bad;
		} else if (!strcmp(key, "flow")) {
			int f = -1;
			for (int k = 0; k < 4; k++)
				if (!strcmp(val, flow_names[k]))
					f = k;
			if (f < 0)
				goto bad;
			s->flow = f;
		} else {
			snprintf(err, errlen, "%s: unknown setting '%s' (baud, parity, bits, stop, flow, timeout)", name, key);
			return -1;
		}
		continue;
bad:
		snprintf(err, errlen, "%s: bad %s '%s' (baud: 300 ... 921600; parity: none, even, odd; "
			"bits: 5-8; stop: 1, 2; flow: xonxoff, rtscts, escb, none; timeout: seconds)", name, key, val);
		return -1;
	}
	speed_t code = 0;
	for (size_t k = 0; k < sizeof bauds / sizeof bauds[0]; k++)
		if (bauds[k].baud == baud)
			code = bauds[k].code;
	if (!code) {
		snprintf(err, errlen, "%s: %ld baud is no standard rate (300, 600, 1200, 2400, 4800, "
			"9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600)", name, baud);
		return -1;
	}
	cfmakeraw(tio);
	tio->c_cflag &= ~(tcflag_t)(CSIZE | PARENB | PARODD | CSTOPB | CRTSCTS);
	tio->c_cflag |= CLOCAL | CREAD | (bits == 5 ? CS5 : bits == 6 ? CS6 : bits == 7 ? CS7 : CS8);
	if (parity != 'n')
		tio->c_cflag |= PARENB | (parity == 'o' ? PARODD : 0);
	if (stop == 2)
		tio->c_cflag |= CSTOPB;
	tio->c_iflag &= ~(tcflag_t)(IXON | IXOFF | IXANY);
	if (s->flow == FLOW_XONXOFF)
		tio->c_iflag |= IXON;          /* the device's XOFF stops our output */
	if (s->flow == FLOW_RTSCTS)
		tio->c_cflag |= CRTSCTS;
	tio->c_cc[VMIN] = 0;
	tio->c_cc[VTIME] = 0;
	cfsetispeed(tio, code);
	cfsetospeed(tio, code);
	return 0;
}

int tr_serial_open(io_transport_t *t, const char *rest, int writing, char *err, size_t errlen)
{
	(void)writing;
	char path[256];
	const char *q = strchr(rest, '?');
	size_t pl = q ? (size_t)(q - rest) : strlen(rest);
	if (pl == 0 || pl >= sizeof path) {
		snprintf(err, errlen, "%s: name a serial device: serial:/dev/ttyUSB0?baud=9600&flow=xonxoff", t->name);
		return -1;
	}
	memcpy(path, rest, pl);
	path[pl] = 0;
	serial_t *s = calloc(1, sizeof *s);
	if (!s) {
		io_oom(err, errlen, t->name);
		return -1;
	}
	s->flow = FLOW_XONXOFF;
	s->pace.space = -1;
	s->timeout_ms = 30000;
	struct termios tio;
	memset(&tio, 0, sizeof tio);
	if (parse(q ? q + 1 : "", t->name, &tio, s, err, errlen)) {
		free(s);
		return -1;
	}
	if (is_console(path)) {
		snprintf(err, errlen, "%s: %s is the system console (/sys/class/tty/console/active): "
			"a job is never sent there; name the plotter's own line", t->name, path);
		free(s);
		return -1;
	}
	s->fd = open(path, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
	if (s->fd < 0) {
		int e = errno;
		free(s);
		return open_fail(err, errlen, path, e);
	}
	struct termios old;
	if (tcgetattr(s->fd, &old) < 0) {
		snprintf(err, errlen, "%s: %s is not a serial line (write a file with -o PATH)", t->name, path);
		goto fail;
	}
	tio.c_line = old.c_line;
	s->saved = old;
	if (tcsetattr(s->fd, TCSANOW, &tio) < 0) {
		snprintf(err, errlen, "%s: cannot set the line up: %s", t->name, strerror(errno));
		goto fail;
	}
	struct termios now;
	if (tcgetattr(s->fd, &now) == 0 && cfgetospeed(&now) != cfgetospeed(&tio)) {
		snprintf(err, errlen, "%s: the device does not take that baud rate", t->name);
		goto fail;
	}
	ioctl(s->fd, TIOCEXCL);   /* no second program on this line while we send */
	tcflush(s->fd, TCIOFLUSH);
	t->link_state = s;
	if (s->flow == FLOW_ESCB) {
		/* the language's own handshake: learn the buffer, identify the device */
		io_chan_t c = chan(t, s);
		if (tr_pace_hello(&c, &s->pace))
			goto fail_t;
	}
	return 0;
fail_t:
	snprintf(err, errlen, "%s", t->err);
	t->link_state = NULL;
	t->failed = 0;
	tcsetattr(s->fd, TCSANOW, &s->saved);
fail:
	close(s->fd);
	free(s);
	return -1;
}

long tr_serial_write(io_transport_t *t, const void *buf, size_t n)
{
	serial_t *s = t->link_state;
	if (s->flow != FLOW_ESCB)
		return put_n(t, s, buf, n, 1);
	/* the language's room query before each chunk of at most half the buffer (pace.c) */
	io_chan_t c = chan(t, s);
	return tr_pace_write(&c, &s->pace, buf, n);
}

long tr_serial_read(io_transport_t *t, void *buf, size_t n)
{
	serial_t *s = t->link_state;
	struct pollfd pf = { s->fd, POLLIN, 0 };
	int r = poll(&pf, 1, (int)s->timeout_ms);
	if (r == 0)
		return io_link_tempfail(t, "no reply within %ld s", s->timeout_ms / 1000);
	if (r < 0)
		return -1;
	ssize_t g = read(s->fd, buf, n);
	return g < 0 && errno == EAGAIN ? 0 : (long)g;
}

int tr_serial_close(io_transport_t *t)
{
	serial_t *s = t->link_state;
	int rc = 0;
	if (!t->failed && t->writing && s->flow == FLOW_ESCB) {
		/* The device's own word on the job (HP-GL: OE's error), in words. */
		const io_lang_t *l = io_lang();
		io_chan_t c = chan(t, s);
		long code = 0;
		if (l->status(&c, &code))
			rc = -1;
		else if (code != 0)
			rc = io_link_fail(t, "the plotter (%s) reports error %ld: %s", s->pace.ident[0] ? s->pace.ident : "?",
				code, l->status_words(code));
	}
	if (!t->failed) {
		/* Wait, bounded, until the last bytes left the port (tcdrain could wait forever on XOFF). */
		long long end = tr_now_ms() + s->timeout_ms;
		int q;
		while (ioctl(s->fd, TIOCOUTQ, &q) == 0 && q > 0 && tr_now_ms() < end && !io_interrupted())
			sleep_ms(5);
	}
	if (close(s->fd) < 0 && rc == 0)
		rc = -1;
	free(s);
	t->link_state = NULL;
	return rc;
}
