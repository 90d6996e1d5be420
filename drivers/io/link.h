/* link.h: the device links (serial:, tcp:, usb:, hid:) as transport.c calls them, and the
 * helpers they share (not public: programs use transport.h). */
#ifndef LOCUS_TR_LINK_H
#define LOCUS_TR_LINK_H

#include <stddef.h>
#include "io/lang.h"
#include "io/transport_int.h"

/* serial.c: "serial:/dev/X?baud=N&parity=none|even|odd&bits=5..8&stop=1|2
 * &flow=xonxoff|rtscts|escb|none&timeout=S" (termios; escb: the registered language's
 * pacing, io/lang.h). */
int tr_serial_open(io_transport_t *t, const char *rest, int writing, char *err, size_t errlen);
long tr_serial_write(io_transport_t *t, const void *buf, size_t n);
long tr_serial_read(io_transport_t *t, void *buf, size_t n);
int tr_serial_close(io_transport_t *t);

/* tcp.c: "tcp:HOST[:PORT][?timeout=S]" (raw AppSocket/JetDirect, port 9100). */
int tr_tcp_open(io_transport_t *t, const char *rest, int writing, char *err, size_t errlen);
long tr_tcp_write(io_transport_t *t, const void *buf, size_t n);
long tr_tcp_read(io_transport_t *t, void *buf, size_t n);
int tr_tcp_close(io_transport_t *t);
/* The bytes the peer acknowledged (SIOCOUTQ: sent less what waits in the send queue). */
long long tr_tcp_acked(io_transport_t *t);
/* Half-close, then wait (bounded) for the peer's close; -1 (message set) when it did not take
 * every byte, or reset the connection before it had them all. */
int tr_tcp_drain(io_transport_t *t);

/* usb.c: "usb:VID:PID[:SERIAL]" or "usb:any" (USB printer class through libusb-1.0). */
int tr_usb_open(io_transport_t *t, const char *rest, int writing, char *err, size_t errlen);
long tr_usb_write(io_transport_t *t, const void *buf, size_t n);
long tr_usb_read(io_transport_t *t, void *buf, size_t n);
int tr_usb_close(io_transport_t *t);
/* One line per attached USB printer-class device (io_link_t.list); -1 when libusb cannot start. */
int tr_usb_list(io_list_put_fn *put, void *user, char *err, size_t errlen);

/* link_util.c: the link's own error line, "NAME: " + the formatted words; sets failed. Returns -1. */
int io_link_fail(io_transport_t *t, const char *fmt, ...)
#ifdef __GNUC__
	__attribute__((format(printf, 2, 3)))
#endif
	;
/* hid.c: "hid:VID:PID[:SERIAL]?baud=N&parity=..&bits=..&stop=..&flow=none|rtscts|escb" (a CP2110
 * HID UART bridge through hidapi). */
int tr_hid_open(io_transport_t *t, const char *rest, int writing, char *err, size_t errlen);
long tr_hid_write(io_transport_t *t, const void *buf, size_t n);
long tr_hid_read(io_transport_t *t, void *buf, size_t n);
int tr_hid_close(io_transport_t *t);
/* One line per attached CP2110 bridge, as --list-devices prints them (io_link_t.list). */
int tr_hid_list(io_list_put_fn *put, void *user, char *err, size_t errlen);

/* io_link_fail for a failure that may pass (a device unplugged, off, busy, out of paper, a
 * dropped connection): io_temporary() is 1 afterwards. Returns -1. */
int io_link_tempfail(io_transport_t *t, const char *fmt, ...)
#ifdef __GNUC__
	__attribute__((format(printf, 2, 3)))
#endif
	;
/* signals.c: a device link opens for writing: catch SIGINT, SIGTERM and SIGHUP where the
 * program left them at their default (nested opens count); the last one closed gives them back. */
void tr_signals_take(void);
void tr_signals_give(void);
/* link_journal.c: the link took w job bytes p; the journal hears of them when the device
 * confirms them (at once for a link without acked). 0, or -1 (message set). */
int tr_took(io_transport_t *t, const unsigned char *p, size_t w);
/* Feed the journal what the device has confirmed so far (links with acked). 0, or -1. */
int tr_confirm(io_transport_t *t);
/* A link failed mid-job: the journal brought to what the device confirmed, and its point (or,
 * after a signal, that no journal was kept) added to the transport's line. Returns -1. */
int tr_journal_where(io_transport_t *t);
/* A signal arrived during the job (io_interrupted): a temporary failure "interrupted by SIGINT
 * after N bytes" (io_errno EINTR) and -1; else 0. Links call it in every wait. */
int tr_check_interrupt(io_transport_t *t);
/* One "key=value" of a query string "a=1&b=2": copies them out and advances *p past the '&'.
 * Returns 1 for a pair, 0 at the end, -1 for a malformed pair (no '=' or too long). */
int tr_query_next(const char **p, char *key, size_t klen, char *val, size_t vlen);
/* Parse a whole decimal number in [lo, hi] into *out: 0, or -1. */
int tr_parse_long(const char *s, long lo, long hi, long *out);
/* pace.c: flow=escb, the registered language's pacing (io/lang.h) on a link that reads the
 * device's replies (serial, HID): send at most half the buffer of buf/n, after the language's
 * room query says there is room for it (p->space: the last answer not yet used, or -1; waiting
 * while there is none, up to c->timeout_ms), then ask again: the answer, read behind the chunk,
 * confirms the chunk reached the device (the journal counts what this returns) and is left in
 * p->space for the next chunk. Bytes sent, or -1. */
long tr_pace_write(const io_chan_t *c, io_pace_t *p, const void *buf, size_t n);
/* flow=escb at the open: the registered language's handshake (buffer size, identification);
 * -1 with the message set, also when no language that paces is registered. */
int tr_pace_hello(const io_chan_t *c, io_pace_t *p);
/* Milliseconds since an arbitrary start (CLOCK_MONOTONIC). */
long long tr_now_ms(void);

#endif
