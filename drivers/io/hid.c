/* hid.c: the HID UART bridge link (Silicon Labs CP2110 and work-alikes) through hidapi:
 * the UART enabled and set up by feature reports (0x41 enable, 0x50 configuration, 0x43 purge),
 * data sent in interrupt reports whose report ID is the byte count (1..63), replies read back;
 * with flow=escb the registered language's own pacing through the bridge's replies (io/lang.h;
 * HP-GL: ESC.L and OI once, ESC.B before each chunk of at most half the buffer and after it, OE
 * at the end, as on a serial line). */
#include <errno.h>
#include <hidapi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <wchar.h>
#include "io/link.h"

typedef struct {
	hid_device *dev;
	long timeout_ms;
	long long sent;
	unsigned char in[64];   /* a reply report's bytes not yet read */
	size_t nin, pos;
	int escb;               /* flow=escb: the language's pacing */
	io_pace_t pace;         /* its buffer size, last room answer (-1: used), identification */
} hid_t_;

/* Send all n bytes in reports of at most 63 (report ID = count). 0, or -1 (message set). */
static int hid_put(io_transport_t *t, hid_t_ *s, const void *buf, size_t n)
{
	const unsigned char *p = buf;
	while (n > 0) {
		unsigned char rep[64];
		size_t k = n < 63 ? n : 63;
		rep[0] = (unsigned char)k;
		memcpy(rep + 1, p, k);
		if (hid_write(s->dev, rep, k + 1) < 0)
			return io_link_tempfail(t, "the bridge went away after %lld bytes (unplugged?)", s->sent);
		p += k;
		n -= k;
	}
	return 0;
}

/* Read one reply up to CR (or LF) within ms, through the bridge's input reports. */
static int hid_reply(io_transport_t *t, hid_t_ *s, const char *what, char *buf, size_t len, long ms)
{
	size_t n = 0;
	long long end = tr_now_ms() + ms;
	for (;;) {
		if (tr_check_interrupt(t))
			return -1;
		while (s->pos < s->nin) {
			char c = (char)s->in[s->pos++];
			if (c == '\r' || c == '\n') {
				if (n == 0)
					continue;
				buf[n] = 0;
				return 0;
			}
			if (n + 1 < len)
				buf[n++] = c;
		}
		long left = (long)(end - tr_now_ms());
		if (left <= 0)
			return io_link_tempfail(t, "no answer to %s within %ld ms through the bridge: is the plotter "
				"on, and does the cable carry its replies?", what, ms);
		unsigned char rep[64];
		int r = hid_read_timeout(s->dev, rep, sizeof rep, left < 200 ? (int)left : 200);
		if (r < 0)
			return io_link_tempfail(t, "reading from the bridge failed (unplugged?)");
		if (r > 0) {
			size_t c = rep[0] < (size_t)r ? rep[0] : (size_t)r - 1;
			memcpy(s->in, rep + 1, c);
			s->nin = c;
			s->pos = 0;
		}
	}
}

/* A query and its numeric answer (stale replies read first are dropped). */
static int hid_ask(io_transport_t *t, hid_t_ *s, const char *q, const char *what, long ms, long *out)
{
	char rep[64], *e;
	s->pos = s->nin = 0;
	if (hid_put(t, s, q, strlen(q)) || hid_reply(t, s, what, rep, sizeof rep, ms))
		return -1;
	*out = strtol(rep, &e, 10);
	if (e == rep)
		return io_link_fail(t, "the answer to %s is no number: '%s'", what, rep);
	return 0;
}

/* The bridge as the language's handshakes use it (io/lang.h); the pacing counts what it sends. */
static int chan_put(io_transport_t *t, const void *buf, size_t n)
{
	hid_t_ *s = t->link_state;
	if (hid_put(t, s, buf, n))
		return -1;
	s->sent += (long long)n;
	return 0;
}

static int hello_put(io_transport_t *t, const void *buf, size_t n)
{
	return hid_put(t, t->link_state, buf, n);
}

static int chan_ask(io_transport_t *t, const char *q, const char *what, long ms, long *out)
{
	return hid_ask(t, t->link_state, q, what, ms, out);
}

static int chan_reply(io_transport_t *t, const char *what, char *buf, size_t len, long ms)
{
	return hid_reply(t, t->link_state, what, buf, len, ms);
}

static void chan_discard(io_transport_t *t)
{
	hid_t_ *s = t->link_state;
	s->pos = s->nin = 0;
}

static io_chan_t chan(io_transport_t *t, hid_t_ *s)
{
	return (io_chan_t){ t, chan_put, chan_ask, chan_reply, chan_discard, io_link_fail, s->timeout_ms };
}

static int parse_hex4(const char *s, size_t n, unsigned *v)
{
	char tmp[5];
	char *e;
	if (n != 4)
		return -1;
	memcpy(tmp, s, 4);
	tmp[4] = 0;
	*v = (unsigned)strtoul(tmp, &e, 16);
	return *e ? -1 : 0;
}

int tr_hid_open(io_transport_t *t, const char *rest, int writing, char *err, size_t errlen)
{
	(void)writing;
	unsigned vid, pid;
	char serial[64] = "", key[32], val[64];
	long baud = 9600, bits = 8, stop = 1, timeout = 30;
	int parity = 0, rtscts = 0, escb = 0;
	const char *q = strchr(rest, '?'), *end = q ? q : rest + strlen(rest);
	const char *c1 = memchr(rest, ':', (size_t)(end - rest));
	const char *c2 = c1 ? memchr(c1 + 1, ':', (size_t)(end - c1 - 1)) : NULL;
	if (!c1 || parse_hex4(rest, (size_t)(c1 - rest), &vid) || parse_hex4(c1 + 1, (size_t)((c2 ? c2 : end) - c1 - 1), &pid)
		|| (c2 && ((size_t)(end - c2 - 1) >= sizeof serial || end == c2 + 1))) {
		snprintf(err, errlen, "%s: name the bridge as hid:VID:PID[:SERIAL] in hex (a CP2110 is hid:10c4:ea80)", t->name);
		return -1;
	}
	if (c2)
		snprintf(serial, sizeof serial, "%.*s", (int)(end - c2 - 1), c2 + 1);
	for (const char *s = q ? q + 1 : ""; ; ) {
		int r = tr_query_next(&s, key, sizeof key, val, sizeof val);
		if (r == 0)
			break;
		int bad = r < 0;
		if (!bad && !strcmp(key, "baud"))
			bad = tr_parse_long(val, 300, 1000000, &baud);
		else if (!bad && !strcmp(key, "bits"))
			bad = tr_parse_long(val, 5, 8, &bits);
		else if (!bad && !strcmp(key, "stop"))
			bad = tr_parse_long(val, 1, 2, &stop);
		else if (!bad && !strcmp(key, "timeout"))
			bad = tr_parse_long(val, 1, 3600, &timeout);
		else if (!bad && !strcmp(key, "parity")) {
			parity = !strcmp(val, "none") ? 0 : !strcmp(val, "odd") ? 1 : !strcmp(val, "even") ? 2 : -1;
			bad = parity < 0;
		} else if (!bad && !strcmp(key, "flow")) {
			escb = !strcmp(val, "escb");
			rtscts = escb || !strcmp(val, "none") ? 0 : !strcmp(val, "rtscts") ? 1 : -1;
			bad = rtscts < 0;
		} else
			bad = 1;
		if (bad) {
			snprintf(err, errlen, "%s: bad setting '%s' (baud 300-1000000, parity none|odd|even, bits 5-8, "
				"stop 1|2, flow none|rtscts|escb, timeout seconds)", t->name, key);
			return -1;
		}
	}
	if (hid_init() < 0) {
		snprintf(err, errlen, "%s: cannot start hidapi", t->name);
		return -1;
	}
	wchar_t wsn[64];
	if (serial[0])
		mbstowcs(wsn, serial, sizeof wsn / sizeof wsn[0] - 1), wsn[63] = 0;
	hid_device *dev = hid_open((unsigned short)vid, (unsigned short)pid, serial[0] ? wsn : NULL);
	if (!dev) {
		struct hid_device_info *l = hid_enumerate((unsigned short)vid, (unsigned short)pid);
		if (l)
			snprintf(err, errlen, "%s: cannot open the bridge (permission denied? install docs/60-locus-usb.rules "
				"in /etc/udev/rules.d, then replug it%s)", t->name, serial[0] ? "; or no such serial number" : "");
		else
			snprintf(err, errlen, "%s: no HID bridge with that VID:PID: is it plugged in?", t->name);
		hid_free_enumeration(l);
		hid_exit();
		return -1;
	}
	/* Enable the UART, set it up, purge both FIFOs. */
	unsigned char en[2] = { 0x41, 0x01 };
	unsigned char cfg[9] = { 0x50, (unsigned char)(baud >> 24), (unsigned char)(baud >> 16),
		(unsigned char)(baud >> 8), (unsigned char)baud, (unsigned char)parity, (unsigned char)rtscts,
		(unsigned char)(bits - 5), (unsigned char)(stop == 2) };
	unsigned char purge[2] = { 0x43, 0x03 };
	if (hid_send_feature_report(dev, en, sizeof en) < 0 || hid_send_feature_report(dev, cfg, sizeof cfg) < 0
		|| hid_send_feature_report(dev, purge, sizeof purge) < 0) {
		snprintf(err, errlen, "%s: the bridge refused its UART set-up (is it a CP2110?)", t->name);
		hid_close(dev);
		hid_exit();
		return -1;
	}
	hid_t_ *s = calloc(1, sizeof *s);
	if (!s) {
		hid_close(dev);
		hid_exit();
		io_oom(err, errlen, t->name);
		return -1;
	}
	s->dev = dev;
	s->timeout_ms = timeout * 1000;
	s->escb = escb;
	s->pace.space = -1;
	t->link_state = s;
	if (escb) {
		/* the language's own handshake through the bridge: learn the buffer, identify the device
		 * (its bytes are not counted in sent, as the pacing's are) */
		io_chan_t c = chan(t, s);
		c.put = hello_put;
		if (tr_pace_hello(&c, &s->pace)) {
			snprintf(err, errlen, "%s", t->err);
			t->failed = 0;
			t->link_state = NULL;
			hid_close(dev);
			hid_exit();
			free(s);
			return -1;
		}
	}
	return 0;
}

static long escb_write(io_transport_t *t, hid_t_ *s, const void *buf, size_t n)
{
	io_chan_t c = chan(t, s);
	return tr_pace_write(&c, &s->pace, buf, n);
}

long tr_hid_write(io_transport_t *t, const void *buf, size_t n)
{
	hid_t_ *s = t->link_state;
	if (s->escb)
		return escb_write(t, s, buf, n);
	unsigned char rep[64];
	size_t k = n < 63 ? n : 63;
	rep[0] = (unsigned char)k;   /* the report ID is the byte count */
	memcpy(rep + 1, buf, k);
	if (hid_write(s->dev, rep, k + 1) < 0)
		return io_link_tempfail(t, "the bridge went away after %lld bytes (unplugged?)", s->sent);
	s->sent += (long long)k;
	return (long)k;
}

long tr_hid_read(io_transport_t *t, void *buf, size_t n)
{
	hid_t_ *s = t->link_state;
	if (s->pos == s->nin) {
		unsigned char rep[64];
		int r = hid_read_timeout(s->dev, rep, sizeof rep, (int)s->timeout_ms);
		if (r < 0)
			return io_link_tempfail(t, "reading from the bridge failed (unplugged?)");
		if (r == 0)
			return io_link_tempfail(t, "no reply within %ld s", s->timeout_ms / 1000);
		size_t c = rep[0] < (size_t)r ? rep[0] : (size_t)r - 1;
		memcpy(s->in, rep + 1, c);
		s->nin = c;
		s->pos = 0;
	}
	size_t c = s->nin - s->pos < n ? s->nin - s->pos : n;
	memcpy(buf, s->in + s->pos, c);
	s->pos += c;
	return (long)c;
}

int tr_hid_close(io_transport_t *t)
{
	hid_t_ *s = t->link_state;
	int rc = 0;
	long code = 0;
	io_chan_t c = chan(t, s);
	if (s->escb && !t->failed && t->writing && io_lang()->status(&c, &code) == 0 && code != 0)
		rc = io_link_fail(t, "the plotter (%s) reports error %ld after the job", s->pace.ident[0] ? s->pace.ident : "?", code);
	else if (t->failed)
		rc = -1;
	hid_close(s->dev);
	hid_exit();
	free(s);
	t->link_state = NULL;
	return rc;
}

int tr_hid_list(io_list_put_fn *put, void *user, char *err, size_t errlen)
{
	(void)err, (void)errlen;
	if (hid_init() < 0)
		return 0;   /* no hidapi here: no bridge to list */
	struct hid_device_info *l = hid_enumerate(0x10c4, 0xea80), *d;   /* CP2110 */
	for (d = l; d; d = d->next)
		put(user, "hid:%04x:%04x%s%ls  HID UART bridge  %ls %ls\n", d->vendor_id, d->product_id,
			d->serial_number && d->serial_number[0] ? ":" : "", d->serial_number ? d->serial_number : L"",
			d->manufacturer_string ? d->manufacturer_string : L"", d->product_string ? d->product_string : L"");
	hid_free_enumeration(l);
	hid_exit();
	return 0;
}
