/* usb.c: the USB printer-class link through libusb-1.0: find interface class 7 (protocol 2
 * preferred over 1), detach and re-attach the kernel driver, set the configuration only when it
 * differs, read the IEEE-1284 device ID and port status, bulk writes that advance by what was
 * sent, stall clearing with one retry, timeouts that keep the partial count, a back-channel. */
#include <errno.h>
#include <libusb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "io/link.h"

#define USB_CHUNK 16384

typedef struct {
	libusb_context *ctx;
	libusb_device_handle *h;
	int iface, alt, detached;
	unsigned char ep_out, ep_in;   /* ep_in 0: one-way (protocol 1) */
	long timeout_ms;               /* no progress for this long: the write fails */
	long long sent;
	char id[1024];                 /* the IEEE-1284 device ID */
} usb_t;

/* The printer interface of dev: 0 with iface, alt, config value and endpoints, or -1. */
static int find_printer(libusb_device *dev, int *iface, int *alt, int *cfgval,
		unsigned char *out, unsigned char *in)
{
	struct libusb_config_descriptor *cfg;
	int best = -1;
	if (libusb_get_active_config_descriptor(dev, &cfg) < 0 && libusb_get_config_descriptor(dev, 0, &cfg) < 0)
		return -1;
	for (int i = 0; i < cfg->bNumInterfaces; i++)
		for (int a = 0; a < cfg->interface[i].num_altsetting; a++) {
			const struct libusb_interface_descriptor *d = &cfg->interface[i].altsetting[a];
			if (d->bInterfaceClass != 7 || d->bInterfaceSubClass != 1
				|| (d->bInterfaceProtocol != 1 && d->bInterfaceProtocol != 2) || d->bInterfaceProtocol <= best)
				continue;
			unsigned char o = 0, n = 0;
			for (int e = 0; e < d->bNumEndpoints; e++) {
				const struct libusb_endpoint_descriptor *ep = &d->endpoint[e];
				if ((ep->bmAttributes & 3) != LIBUSB_TRANSFER_TYPE_BULK)
					continue;
				if (ep->bEndpointAddress & LIBUSB_ENDPOINT_IN)
					n = n ? n : ep->bEndpointAddress;
				else
					o = o ? o : ep->bEndpointAddress;
			}
			if (!o)
				continue;
			best = d->bInterfaceProtocol;
			*iface = d->bInterfaceNumber;
			*alt = d->bAlternateSetting;
			*cfgval = cfg->bConfigurationValue;
			*out = o;
			*in = best == 2 ? n : 0;
		}
	libusb_free_config_descriptor(cfg);
	return best < 0 ? -1 : 0;
}

/* GET_DEVICE_ID into buf (NUL-terminated): length in the first two bytes, big-endian as the
 * class says, little-endian as some printers send it. 0, or a libusb error. */
static int device_id(libusb_device_handle *h, int iface, int alt, char *buf, size_t len)
{
	unsigned char raw[1024];
	int r = libusb_control_transfer(h, 0xA1, 0, 0, (uint16_t)(iface << 8 | alt), raw, sizeof raw, 5000);
	if (r == LIBUSB_ERROR_PIPE) {
		libusb_clear_halt(h, 0);
		r = libusb_control_transfer(h, 0xA1, 0, 0, (uint16_t)(iface << 8 | alt), raw, sizeof raw, 5000);
	}
	if (r < 0)
		return r;
	size_t n = 0;
	if (r >= 2) {
		size_t be = (size_t)raw[0] << 8 | raw[1], le = (size_t)raw[1] << 8 | raw[0];
		n = be >= 2 && be <= (size_t)r ? be : le >= 2 && le <= (size_t)r ? le : (size_t)r;
		n -= 2;
	}
	if (n >= len)
		n = len - 1;
	memcpy(buf, raw + 2, n);
	buf[n] = 0;
	return 0;
}

/* GET_PORT_STATUS in words ("" when all is well); NULL when it cannot be read. */
static const char *port_words(libusb_device_handle *h, int iface)
{
	unsigned char st;
	if (libusb_control_transfer(h, 0xA1, 1, 0, (uint16_t)(iface << 8), &st, 1, 2000) != 1)
		return NULL;
	if (st & 0x20)
		return "paper empty";
	if (!(st & 0x10))
		return "offline";
	if (!(st & 0x08))
		return "error";
	return "";
}

static int parse_hex4(const char *s, size_t n, unsigned *v)
{
	if (n != 4)
		return -1;
	*v = 0;
	for (size_t k = 0; k < 4; k++) {
		int c = s[k], d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
			: c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
		if (d < 0)
			return -1;
		*v = *v << 4 | (unsigned)d;
	}
	return 0;
}

static void sleep_ms(long ms)
{
	struct timespec ts = { ms / 1000, (ms % 1000) * 1000000L };
	nanosleep(&ts, NULL);
}

int tr_usb_open(io_transport_t *t, const char *rest, int writing, char *err, size_t errlen)
{
	(void)writing;
	unsigned vid = 0, pid = 0;
	int any = 0, reset = 0;
	long wait = 0, timeout = 30, v;
	char serial[128] = "", key[32], val[128];
	const char *q = strchr(rest, '?'), *end = q ? q : rest + strlen(rest);
	const char *c1 = memchr(rest, ':', (size_t)(end - rest));
	const char *c2 = c1 ? memchr(c1 + 1, ':', (size_t)(end - c1 - 1)) : NULL;
	if ((size_t)(end - rest) == 3 && !strncmp(rest, "any", 3))
		any = 1;
	else if (!c1 || parse_hex4(rest, (size_t)(c1 - rest), &vid)
		|| parse_hex4(c1 + 1, (size_t)((c2 ? c2 : end) - c1 - 1), &pid)
		|| (c2 && ((size_t)(end - c2 - 1) >= sizeof serial || end == c2 + 1))) {
		snprintf(err, errlen, "%s: name the printer as usb:VID:PID[:SERIAL] in hex (e.g. usb:03f0:0107) "
			"or usb:any; locus-play --list-devices lists them", t->name);
		return -1;
	}
	if (c2) {
		memcpy(serial, c2 + 1, (size_t)(end - c2 - 1));
		serial[end - c2 - 1] = 0;
	}
	for (const char *s = q ? q + 1 : ""; ; ) {
		int r = tr_query_next(&s, key, sizeof key, val, sizeof val);
		if (r == 0)
			break;
		if (r > 0 && !strcmp(key, "wait") && !tr_parse_long(val, 0, 86400, &v))
			wait = v;
		else if (r > 0 && !strcmp(key, "timeout") && !tr_parse_long(val, 1, 3600, &v))
			timeout = v;
		else if (r > 0 && !strcmp(key, "reset") && !tr_parse_long(val, 0, 1, &v))
			reset = (int)v;
		else {
			snprintf(err, errlen, "%s: settings are wait=SECONDS, timeout=SECONDS, reset=0|1", t->name);
			return -1;
		}
	}
	usb_t *s = calloc(1, sizeof *s);
	if (!s || libusb_init(&s->ctx) < 0) {
		snprintf(err, errlen, "%s: cannot start libusb", t->name);
		free(s);
		return -1;
	}
	s->timeout_ms = timeout * 1000;
	/* Find it; a printer that is off or unplugged is waited for when wait= says so. */
	long long give_up = tr_now_ms() + wait * 1000;
	int found = 0, denied = 0;
	for (;;) {
		libusb_device **list;
		ssize_t n = libusb_get_device_list(s->ctx, &list);
		for (ssize_t k = 0; k < n && !s->h; k++) {
			struct libusb_device_descriptor dd;
			int iface, alt, cfgval;
			unsigned char o, in;
			if (libusb_get_device_descriptor(list[k], &dd) < 0 || (!any && (dd.idVendor != vid || dd.idProduct != pid))
				|| find_printer(list[k], &iface, &alt, &cfgval, &o, &in))
				continue;
			found = 1;
			libusb_device_handle *h;
			int r = libusb_open(list[k], &h);
			if (r == LIBUSB_ERROR_ACCESS) {
				denied = 1;
				continue;
			}
			if (r < 0)
				continue;
			if (serial[0]) {
				unsigned char sn[128];
				if (!dd.iSerialNumber || libusb_get_string_descriptor_ascii(h, dd.iSerialNumber, sn, sizeof sn) < 0
					|| strcmp((char *)sn, serial)) {
					libusb_close(h);
					continue;
				}
			}
			s->h = h;
			s->iface = iface;
			s->alt = alt;
			s->ep_out = o;
			s->ep_in = in;
			int cur = -1;
			if (libusb_get_configuration(h, &cur) == 0 && cur != cfgval)
				libusb_set_configuration(h, cfgval);   /* only when it differs: some lose jobs */
		}
		libusb_free_device_list(list, 1);
		if (s->h || tr_now_ms() >= give_up || denied)
			break;
		sleep_ms(1000);
	}
	if (!s->h) {
		if (denied)
			snprintf(err, errlen, "%s: permission denied: install docs/60-locus-usb.rules in "
				"/etc/udev/rules.d (then: udevadm control --reload; replug the printer) or join group lp", t->name);
		else if (found)
			snprintf(err, errlen, "%s: no printer with serial number '%s' there (locus-play --list-devices)", t->name, serial);
		else
			snprintf(err, errlen, "%s: no USB printer-class device %s: is it plugged in and on? "
				"(locus-play --list-devices; wait=SECONDS waits for it)", t->name, any ? "attached" : "with that VID:PID");
		libusb_exit(s->ctx);
		free(s);
		return -1;
	}
	if (libusb_kernel_driver_active(s->h, s->iface) == 1 && libusb_detach_kernel_driver(s->h, s->iface) == 0)
		s->detached = 1;
	int r = libusb_claim_interface(s->h, s->iface);
	if (r == 0 && s->alt)
		r = libusb_set_interface_alt_setting(s->h, s->iface, s->alt);
	if (r < 0) {
		snprintf(err, errlen, "%s: cannot claim the printer interface: %s (another program using it?)",
			t->name, libusb_strerror(r));
		goto fail;
	}
	if (reset)
		libusb_control_transfer(s->h, 0x21, 2, 0, (uint16_t)(s->iface << 8 | s->alt), NULL, 0, 5000);
	device_id(s->h, s->iface, s->alt, s->id, sizeof s->id);
	t->link_state = s;
	return 0;
fail:
	if (s->detached)
		libusb_attach_kernel_driver(s->h, s->iface);
	libusb_close(s->h);
	libusb_exit(s->ctx);
	free(s);
	return -1;
}

long tr_usb_write(io_transport_t *t, const void *buf, size_t n)
{
	usb_t *s = t->link_state;
	int len = n > USB_CHUNK ? USB_CHUNK : (int)n, stalls = 0;
	long long start = tr_now_ms();
	for (;;) {
		int sent = 0;
		int r = libusb_bulk_transfer(s->h, s->ep_out, (unsigned char *)buf, len, &sent, 1000);
		if (r == LIBUSB_ERROR_PIPE)
			libusb_clear_halt(s->h, s->ep_out);   /* a stalled endpoint takes nothing until cleared */
		if (sent > 0) {   /* what went, went: a timeout or a stall keeps its partial count */
			s->sent += sent;
			return sent;
		}
		if (r == 0)
			r = LIBUSB_ERROR_TIMEOUT;   /* nothing taken: busy */
		if (r == LIBUSB_ERROR_PIPE && stalls++ == 0)
			continue;   /* a stall with nothing sent: try once more */
		/* a signal first: it can end the transfer's wait, which libusb may then report as an I/O
		 * error (seen under umockdev), and what the user did is what the message must say */
		if (tr_check_interrupt(t))
			return -1;
		if (r == LIBUSB_ERROR_NO_DEVICE || r == LIBUSB_ERROR_IO)
			return io_link_tempfail(t, "the printer went away after %lld bytes (unplugged or off): %s",
				s->sent, libusb_strerror(r));
		if (r == LIBUSB_ERROR_TIMEOUT && tr_now_ms() - start < s->timeout_ms)
			continue;   /* busy: wait for it */
		const char *w = port_words(s->h, s->iface);
		return io_link_tempfail(t, "the printer took nothing for %ld s after %lld bytes (%s): %s",
			(long)((tr_now_ms() - start) / 1000), s->sent, w && w[0] ? w : "no status",
			libusb_strerror(r));
	}
}

long tr_usb_read(io_transport_t *t, void *buf, size_t n)
{
	usb_t *s = t->link_state;
	if (!s->ep_in)
		return 0;   /* a one-way printer says nothing */
	int got = 0;
	int r = libusb_bulk_transfer(s->h, s->ep_in, buf, n > 65536 ? 65536 : (int)n, &got, (unsigned)s->timeout_ms);
	if (r < 0 && r != LIBUSB_ERROR_TIMEOUT && got == 0)
		return io_link_fail(t, "back-channel read failed: %s", libusb_strerror(r));
	return got;
}

int tr_usb_close(io_transport_t *t)
{
	usb_t *s = t->link_state;
	libusb_release_interface(s->h, s->iface);
	if (s->detached)
		libusb_attach_kernel_driver(s->h, s->iface);   /* give usblp its printer back */
	libusb_close(s->h);
	libusb_exit(s->ctx);
	free(s);
	t->link_state = NULL;
	return 0;
}

int tr_usb_list(io_list_put_fn *put, void *user, char *err, size_t errlen)
{
	libusb_context *ctx;
	if (libusb_init(&ctx) < 0) {
		snprintf(err, errlen, "cannot start libusb");
		return -1;
	}
	libusb_device **list;
	ssize_t n = libusb_get_device_list(ctx, &list);
	for (ssize_t k = 0; k < n; k++) {
		struct libusb_device_descriptor dd;
		int iface, alt, cfgval;
		unsigned char o, in;
		if (libusb_get_device_descriptor(list[k], &dd) < 0 || find_printer(list[k], &iface, &alt, &cfgval, &o, &in))
			continue;
		libusb_device_handle *h;
		char id[1024] = "", sn[128] = "";
		int r = libusb_open(list[k], &h);
		if (r == 0) {
			if (dd.iSerialNumber)
				libusb_get_string_descriptor_ascii(h, dd.iSerialNumber, (unsigned char *)sn, sizeof sn);
			int det = libusb_kernel_driver_active(h, iface) == 1 && libusb_detach_kernel_driver(h, iface) == 0;
			if (libusb_claim_interface(h, iface) == 0) {
				device_id(h, iface, alt, id, sizeof id);
				libusb_release_interface(h, iface);
			}
			if (det)
				libusb_attach_kernel_driver(h, iface);
			libusb_close(h);
		}
		put(user, "usb:%04x:%04x%s%s  %s  %s\n", dd.idVendor, dd.idProduct, sn[0] ? ":" : "", sn,
			in ? "bidirectional" : "one-way",
			r == LIBUSB_ERROR_ACCESS ? "(no permission to read its device ID: see docs/60-locus-usb.rules)"
			: id[0] ? id : "(no device ID)");
	}
	if (n >= 0)
		libusb_free_device_list(list, 1);
	libusb_exit(ctx);
	return 0;
}
