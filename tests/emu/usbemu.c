/* usbemu.c: a USB printer-class device (a pen plotter, 03f0:0107) emulated through umockdev: a
 * testbed with its descriptors and an ioctl handler that plays the kernel's usbdevfs (URBs,
 * claim/release, the usblp driver bound until detached), answering GET_DEVICE_ID, GET_PORT_STATUS,
 * string descriptors and bulk OUT. It runs one command under umockdev-wrapper, so the program's
 * real libusb code drives it, then reports what arrived and compares it with the expected HP-GL.
 *
 *   emu-usb [options] -- CMD ARGS...
 *   --stall-at N     the bulk URB that reaches byte N stalls once (after taking up to N)
 *   --short-at N     the URB that reaches byte N completes short, at N
 *   --hold-at N MS   the device takes nothing from byte N on for MS milliseconds (busy)
 *   --unplug-at N    the device is gone from byte N on (every URB fails with ENODEV)
 *   --status B       the port status byte (0x18: selected, no error; 0x38 adds paper empty)
 *   --id-le          send the device ID length little-endian
 *   --cp2110         be a Silicon Labs CP2110 HID UART bridge (10c4:ea80) instead: feature
 *                    reports 0x41/0x50/0x43 set up its UART, interrupt OUT reports carry data;
 *                    behind it a plotter answering ESC.B, ESC.L, OI; and OE; (sent in reports
 *                    of their own) through interrupt IN reports; with --pen-rate B/S its pen
 *                    drains a 1024-byte buffer that drops what overflows it at that rate
 *                    (without, the buffer never fills: a bridge holding by RTS/CTS)
 *   --record FILE, --expect FILE   as emu-plotter
 *   --pcap FILE      write the session as a usbmon capture (link type 220, as Wireshark or
 *                    usbmon record it), for umockdev-run -p to replay
 * Prints one line "child=S received=N stalls=N clears=N detached=N attached=N ... bytes=same";
 * exits 0 when the child exited 0 and what arrived is what was expected. */
#include <errno.h>
#include <glib.h>
#include <linux/usbdevice_fs.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <time.h>
#include <umockdev.h>
#include <unistd.h>

#define DEVNODE "/dev/bus/usb/001/002"
/* CP2110 mode: a vendor-defined report descriptor, 63-byte input and output reports. */
static const unsigned char report_desc[] = {
	0x06, 0x00, 0xFF, 0x09, 0x01, 0xA1, 0x01, 0x85, 0x01, 0x95, 0x3F, 0x75, 0x08, 0x15, 0x00,
	0x26, 0xFF, 0x00, 0x09, 0x01, 0x81, 0x02, 0x09, 0x01, 0x91, 0x02, 0xC0,
};
static const char device_id_str[] = "MFG:Locus;MDL:Emulated 7475A;CMD:HPGL;CLS:PRINTER;DES:Locus test plotter;";

typedef struct {
	long long stall_at, short_at, hold_at, unplug_at;
	long hold_ms;
	int status, id_le;
	/* state */
	unsigned char *rec;
	size_t nrec, caprec;
	int stalled, shorted, driver_bound, halted;
	double hold_until;
	long stalls, clears, detaches, attaches, claims, releases, setconfigs, idreads, statusreads, resets;
	int cp2110, uart_on, purges;
	unsigned char uart[9];    /* the last 0x50 configuration report */
	/* the plotter behind the bridge */
	double pen_rate, used, drained_at;
	long peak, dropped, escapes;
	unsigned char reply[256];  /* answers not yet sent in an IN report */
	size_t nreply;
} dev_t_;

static double now_s(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static void take(dev_t_ *d, const unsigned char *p, size_t n)
{
	if (d->nrec + n > d->caprec) {
		d->caprec = (d->nrec + n) * 2;
		d->rec = realloc(d->rec, d->caprec);
		if (!d->rec)
			exit(70);
	}
	memcpy(d->rec + d->nrec, p, n);
	d->nrec += n;
}

/* The answer to a control request (setup in s); returns its length, or -1 for a stall. */
static int control(dev_t_ *d, const unsigned char *s, unsigned char *out, int cap)
{
	int type = s[0], req = s[1], value = s[2] | s[3] << 8, len = s[6] | s[7] << 8;
	(void)value;
	if (d->cp2110 && type == 0x81 && req == 6 && s[3] == 0x22) {   /* the HID report descriptor */
		int n = (int)sizeof report_desc;
		memcpy(out, report_desc, sizeof report_desc);
		return n < len ? n : len;
	}
	if (d->cp2110 && type == 0x21 && req == 0x09) {   /* SET_REPORT (feature) */
		const unsigned char *p = s + 8;
		if (p[0] == 0x41)
			d->uart_on = p[1];
		else if (p[0] == 0x50 && len >= 9)
			memcpy(d->uart, p, 9);
		else if (p[0] == 0x43)
			d->purges++;
		else
			return -1;
		return 0;
	}
	if (d->cp2110 && type == 0x21 && req == 0x0A)   /* SET_IDLE */
		return 0;
	if (type == 0x80 && req == 6 && s[3] == 3) {   /* string descriptors */
		static const char *const pstr[] = { NULL, "Locus", "Emulated 7475A", "LT0001" };
		static const char *const hstr[] = { NULL, "Silicon Labs", "CP2110 HID USB-to-UART Bridge", "0001ABCD" };
		const char *const *str = d->cp2110 ? hstr : pstr;
		int idx = s[2], n;
		if (idx == 0) {
			n = 4;
			out[0] = 4, out[1] = 3, out[2] = 0x09, out[3] = 0x04;
		} else if (idx < 4) {
			int l = (int)strlen(str[idx]);
			n = 2 + 2 * l;
			out[0] = (unsigned char)n, out[1] = 3;
			for (int k = 0; k < l; k++)
				out[2 + 2 * k] = (unsigned char)str[idx][k], out[3 + 2 * k] = 0;
		} else
			return -1;
		return n < len ? n : len;
	}
	if (type == 0xA1 && req == 0) {   /* GET_DEVICE_ID */
		int l = (int)strlen(device_id_str) + 2;
		d->idreads++;
		out[d->id_le ? 1 : 0] = (unsigned char)(l >> 8);
		out[d->id_le ? 0 : 1] = (unsigned char)l;
		memcpy(out + 2, device_id_str, (size_t)l - 2);
		return l < len ? l : len;
	}
	if (type == 0xA1 && req == 1) {   /* GET_PORT_STATUS */
		d->statusreads++;
		out[0] = (unsigned char)d->status;
		return 1;
	}
	if (type == 0x21 && req == 2) {   /* SOFT_RESET */
		d->resets++;
		return 0;
	}
	(void)cap;
	return -1;
}

/* A bulk OUT URB of n bytes: how many the device takes now (sets *st to its status). */
static int bulk_out(dev_t_ *d, const unsigned char *p, int n, int *st)
{
	long long at = (long long)d->nrec;
	*st = 0;
	if (d->halted) {   /* a halted endpoint takes nothing until CLEAR_HALT */
		*st = -EPIPE;
		return 0;
	}
	if (d->unplug_at >= 0 && at + n > d->unplug_at) {
		int k = (int)(d->unplug_at > at ? d->unplug_at - at : 0);
		take(d, p, (size_t)k);
		*st = -ENODEV;
		return k;
	}
	if (d->hold_until > 0 && now_s() < d->hold_until)
		return -1;   /* still busy: held, nothing taken */
	if (d->hold_at >= 0 && at + n > d->hold_at && d->hold_until == 0) {
		int k = (int)(d->hold_at - at);
		d->hold_until = now_s() + d->hold_ms / 1000.0;
		take(d, p, (size_t)k);
		return -1 - k;   /* held: it completes only when discarded (a timeout), with k taken */
	}
	if (d->stall_at >= 0 && !d->stalled && at + n > d->stall_at) {
		int k = (int)(d->stall_at - at);
		d->stalled = d->halted = 1;
		d->stalls++;
		take(d, p, (size_t)k);
		*st = -EPIPE;
		return k;
	}
	if (d->short_at >= 0 && !d->shorted && at + n > d->short_at) {
		int k = (int)(d->short_at - at);
		d->shorted = 1;
		take(d, p, (size_t)k);
		return k;
	}
	take(d, p, (size_t)n);
	return n;
}

/* The plotter behind the bridge: its pen has drained the buffer until now. */
static void drain(dev_t_ *d)
{
	double now = now_s();
	if (d->drained_at > 0) {
		d->used -= (now - d->drained_at) * d->pen_rate;
		if (d->used < 0)
			d->used = 0;
	}
	d->drained_at = now;
}

static void answer(dev_t_ *d, const char *s)
{
	size_t n = strlen(s);
	if (d->nreply + n <= sizeof d->reply) {
		memcpy(d->reply + d->nreply, s, n);
		d->nreply += n;
	}
}

/* A data report of k bytes through the bridge: a query of the link (in a report of its own:
 * ESC.B, ESC.L, OI;, OE;) is answered; anything else goes into the plotter's buffer, and what
 * does not fit is lost as on a real 7475A. */
static void bridge_data(dev_t_ *d, const unsigned char *p, int k)
{
	char tmp[32];
	drain(d);
	if (k == 3 && p[0] == 27 && p[1] == '.') {
		d->escapes++;
		snprintf(tmp, sizeof tmp, "%ld\r", p[2] == 'L' ? 1024L : p[2] == 'B' ? 1024L - (long)d->used : 0L);
		answer(d, tmp);
		return;
	}
	if (k == 3 && (!memcmp(p, "OI;", 3) || !memcmp(p, "OE;", 3))) {
		answer(d, p[1] == 'I' ? "7475A\r" : "0\r");
		return;
	}
	if (d->pen_rate <= 0) {
		take(d, p, (size_t)k);
		return;
	}
	int fit = (int)(1024 - d->used) < k ? (int)(1024 - d->used) : k;
	if (fit < 0)
		fit = 0;
	d->dropped += k - fit;
	d->used += fit;
	if ((long)d->used > d->peak)
		d->peak = (long)d->used;
	take(d, p, (size_t)fit);
}

/* The usbmon capture being written (--pcap), or NULL. */
static FILE *pcap;

/* One usbmon record: 'S' (submit) or 'C' (complete) of urb u; data of len bytes (may be 0). */
static void pcap_rec(char what, const struct usbdevfs_urb *u, gulong id, const unsigned char *setup,
		int status, unsigned length, const unsigned char *data, unsigned len)
{
	if (!pcap)
		return;
	unsigned char h[64];
	memset(h, 0, sizeof h);
	struct timespec ts;
	clock_gettime(CLOCK_REALTIME, &ts);
	guint64 id64 = id;
	memcpy(h, &id64, 8);
	h[8] = (unsigned char)what;
	h[9] = u->type == USBDEVFS_URB_TYPE_CONTROL ? 2 : u->type == USBDEVFS_URB_TYPE_BULK ? 3
		: u->type == USBDEVFS_URB_TYPE_INTERRUPT ? 1 : 0;
	h[10] = u->endpoint;
	h[11] = 2;                          /* devnum */
	guint16 bus = 1;
	memcpy(h + 12, &bus, 2);
	h[14] = setup ? 0 : '-';            /* flag_setup */
	h[15] = len ? 0 : (what == 'S' ? '<' : '>');
	gint64 sec = ts.tv_sec;
	gint32 usec = (gint32)(ts.tv_nsec / 1000);
	memcpy(h + 16, &sec, 8);
	memcpy(h + 24, &usec, 4);
	memcpy(h + 28, &status, 4);
	memcpy(h + 32, &length, 4);
	memcpy(h + 36, &len, 4);
	if (setup)
		memcpy(h + 40, setup, 8);
	guint32 rec[4] = { (guint32)sec, (guint32)usec, 64 + len, 64 + len };
	fwrite(rec, 4, 4, pcap);
	fwrite(h, 1, 64, pcap);
	if (len)
		fwrite(data, 1, len, pcap);
}

typedef struct {
	UMockdevIoctlData *urb;   /* the submitted urb (its buffer a child of it) */
	UMockdevIoctlData *buf;   /* an interrupt IN urb's buffer, filled when a reply is due */
	int actual, status, held;
	unsigned char reply[1100];   /* control IN: the reply, for the capture */
	int in;                      /* a control IN request */
	double ready_at;
} flying_t;

static GList *flying;

static gboolean on_ioctl(UMockdevIoctlBase *h, UMockdevIoctlClient *c, dev_t_ *d)
{
	(void)h;
	gulong req = umockdev_ioctl_client_get_request(c);
	UMockdevIoctlData *arg = umockdev_ioctl_client_get_arg(c);
	switch (req) {
	case USBDEVFS_GET_CAPABILITIES: {
		UMockdevIoctlData *x = umockdev_ioctl_data_resolve(arg, 0, sizeof(guint32), NULL);
		guint32 caps = USBDEVFS_CAP_BULK_CONTINUATION | USBDEVFS_CAP_NO_PACKET_SIZE_LIM | USBDEVFS_CAP_REAP_AFTER_DISCONNECT;
		memcpy(x->data, &caps, sizeof caps);
		umockdev_ioctl_data_unref(x);
		umockdev_ioctl_client_complete(c, 0, 0);
		return TRUE;
	}
	case USBDEVFS_GETDRIVER: {
		if (!d->driver_bound) {
			umockdev_ioctl_client_complete(c, -1, ENODATA);
			return TRUE;
		}
		UMockdevIoctlData *x = umockdev_ioctl_data_resolve(arg, 0, sizeof(struct usbdevfs_getdriver), NULL);
		struct usbdevfs_getdriver *g = (void *)x->data;
		snprintf(g->driver, sizeof g->driver, "usblp");
		umockdev_ioctl_data_unref(x);
		umockdev_ioctl_client_complete(c, 0, 0);
		return TRUE;
	}
	case USBDEVFS_IOCTL: {
		UMockdevIoctlData *x = umockdev_ioctl_data_resolve(arg, 0, sizeof(struct usbdevfs_ioctl), NULL);
		struct usbdevfs_ioctl *io = (void *)x->data;
		if (io->ioctl_code == USBDEVFS_DISCONNECT) {
			d->driver_bound = 0;
			d->detaches++;
		} else if (io->ioctl_code == USBDEVFS_CONNECT) {
			d->driver_bound = 1;
			d->attaches++;
		}
		umockdev_ioctl_data_unref(x);
		umockdev_ioctl_client_complete(c, 0, 0);
		return TRUE;
	}
	case USBDEVFS_SETCONFIGURATION:
		d->setconfigs++;
		umockdev_ioctl_client_complete(c, 0, 0);
		return TRUE;
	case USBDEVFS_CLAIMINTERFACE:
		d->claims++;
		umockdev_ioctl_client_complete(c, d->driver_bound ? -1 : 0, d->driver_bound ? EBUSY : 0);
		return TRUE;
	case USBDEVFS_RELEASEINTERFACE:
		d->releases++;
		umockdev_ioctl_client_complete(c, 0, 0);
		return TRUE;
	case USBDEVFS_CLEAR_HALT:
		d->clears++;
		d->halted = 0;
		umockdev_ioctl_client_complete(c, 0, 0);
		return TRUE;
	case USBDEVFS_RESETEP:
	case USBDEVFS_SETINTERFACE:
		umockdev_ioctl_client_complete(c, 0, 0);
		return TRUE;
	case USBDEVFS_SUBMITURB: {
		UMockdevIoctlData *u = umockdev_ioctl_data_resolve(arg, 0, sizeof(struct usbdevfs_urb), NULL);
		struct usbdevfs_urb *urb = (void *)u->data;
		UMockdevIoctlData *b = umockdev_ioctl_data_resolve(u, G_STRUCT_OFFSET(struct usbdevfs_urb, buffer),
			(gsize)urb->buffer_length, NULL);
		flying_t *f = g_new0(flying_t, 1);
		f->urb = u;
		if (urb->type == USBDEVFS_URB_TYPE_CONTROL) {
			const unsigned char *st = b->data;
			int in = st[0] & 0x80;
			f->in = in != 0;
			unsigned wl = (unsigned)(st[6] | st[7] << 8);
			pcap_rec('S', urb, u->client_addr, st, -EINPROGRESS, wl, st + 8, in ? 0 : wl);
		} else {
			int in = urb->endpoint & 0x80;
			pcap_rec('S', urb, u->client_addr, NULL, -EINPROGRESS, (unsigned)urb->buffer_length, b->data,
				in ? 0 : (unsigned)urb->buffer_length);
		}
		if (urb->type == USBDEVFS_URB_TYPE_CONTROL) {
			int r = control(d, b->data, b->data + 8, urb->buffer_length - 8);
			f->actual = r < 0 ? 0 : r;
			if (r > 0 && (size_t)r <= sizeof f->reply && (((unsigned char *)b->data)[0] & 0x80))
				memcpy(f->reply, (unsigned char *)b->data + 8, (size_t)r);
			f->status = r < 0 ? -EPIPE : 0;
		} else if (urb->type == USBDEVFS_URB_TYPE_BULK && !(urb->endpoint & 0x80)) {
			if (d->unplug_at >= 0 && (long long)d->nrec >= d->unplug_at) {
				umockdev_ioctl_data_unref(b);
				umockdev_ioctl_data_unref(u);
				g_free(f);
				umockdev_ioctl_client_complete(c, -1, ENODEV);
				return TRUE;
			}
			int st, k = bulk_out(d, b->data, urb->buffer_length, &st);
			if (k < 0) {
				f->held = 1;
				f->actual = -1 - k;
			} else {
				f->actual = k;
				f->status = st;
			}
		} else if (d->cp2110 && urb->type == USBDEVFS_URB_TYPE_INTERRUPT && !(urb->endpoint & 0x80)) {
			const unsigned char *p = b->data;   /* report ID = count, then the data */
			int k = urb->buffer_length > 0 ? p[0] : 0;
			if (k > urb->buffer_length - 1 || !d->uart_on)
				f->status = -EPIPE;   /* a bad report, or data before the UART is enabled */
			else
				bridge_data(d, p + 1, k);
			f->actual = urb->buffer_length;
		} else if (d->cp2110 && urb->type == USBDEVFS_URB_TYPE_INTERRUPT) {
			f->held = 1;   /* IN: completed when the plotter has something to say */
			f->buf = umockdev_ioctl_data_ref(b);
		} else {
			f->held = 1;   /* IN: nothing to say; it times out or is discarded at close */
		}
		umockdev_ioctl_data_unref(b);
		flying = g_list_append(flying, f);
		umockdev_ioctl_client_complete(c, 0, 0);
		return TRUE;
	}
	case USBDEVFS_DISCARDURB: {   /* the argument is the urb's own address */
		for (GList *l = flying; l; l = l->next) {
			flying_t *f = l->data;
			if (f->urb->client_addr == *(gulong *)arg->data) {
				f->held = 0;
				f->status = -ENOENT;
				umockdev_ioctl_client_complete(c, 0, 0);
				return TRUE;
			}
		}
		umockdev_ioctl_client_complete(c, -1, EINVAL);
		return TRUE;
	}
	case USBDEVFS_REAPURB:
	case USBDEVFS_REAPURBNDELAY:
		for (GList *l = flying; l && d->nreply; l = l->next) {   /* a reply for a waiting IN report */
			flying_t *f = l->data;
			if (!f->held || !f->buf)
				continue;
			struct usbdevfs_urb *urb = (void *)f->urb->data;
			size_t k = d->nreply < 63 ? d->nreply : 63;
			if ((int)k + 1 > urb->buffer_length)
				k = (size_t)urb->buffer_length - 1;
			unsigned char *q = f->buf->data;
			q[0] = (unsigned char)k;
			memcpy(q + 1, d->reply, k);
			memcpy(f->reply, q, k + 1);
			memmove(d->reply, d->reply + k, d->nreply - k);
			d->nreply -= k;
			f->actual = (int)k + 1;
			f->in = 1;
			f->held = 0;
			break;
		}
		for (GList *l = flying; l; l = l->next) {
			flying_t *f = l->data;
			if (f->held)
				continue;
			struct usbdevfs_urb *urb = (void *)f->urb->data;
			urb->actual_length = f->actual;
			urb->status = f->status;
			pcap_rec('C', urb, f->urb->client_addr, NULL, f->status, (unsigned)f->actual, f->reply,
				f->in ? (unsigned)f->actual : 0);
			UMockdevIoctlData *p = umockdev_ioctl_data_resolve(arg, 0, sizeof(gpointer), NULL);
			umockdev_ioctl_data_set_ptr(p, 0, f->urb);
			umockdev_ioctl_data_unref(p);
			if (f->buf)
				umockdev_ioctl_data_unref(f->buf);
			umockdev_ioctl_data_unref(f->urb);
			flying = g_list_delete_link(flying, l);
			g_free(f);
			umockdev_ioctl_client_complete(c, 0, 0);
			return TRUE;
		}
		umockdev_ioctl_client_complete(c, -1, EAGAIN);
		return TRUE;
	default:
		return FALSE;
	}
}

/* (upper-case hex: umockdev 0.17 refuses lower case in the N: node contents) */
static const char descriptors[] =
	/* device: USB 2.0, 64-byte EP0, 03f0:0107, strings 1 2 3, one configuration */
	"1201000200000040F00307010001010203" "01"
	/* configuration 1, 32 bytes, one interface, self-powered */
	"09022000010100C032"
	/* interface 0: class 7 printer, subclass 1, protocol 2 (bidirectional), two endpoints */
	"090400000207010200"
	/* bulk OUT 0x01 and bulk IN 0x82, 512 bytes */
	"0705010200020007058202000200";

static const char hid_descriptors[] =
	/* device 10c4:ea80, strings 1 2 3 */
	"1201000200000040C41080EA0001010203" "01"
	/* configuration: 41 bytes, one interface, bus-powered 100 mA */
	"0902290001010080" "32"
	/* interface 0: class 3 (HID), two endpoints; HID descriptor with a 27-byte report descriptor */
	"090400000203000000" "092111010001221B00"
	/* interrupt IN 0x81 and OUT 0x02, 64 bytes, every frame */
	"07058103400001" "07050203400001";

int main(int argc, char **argv)
{
	dev_t_ d;
	memset(&d, 0, sizeof d);
	d.stall_at = d.short_at = d.hold_at = d.unplug_at = -1;
	d.status = 0x18;
	d.driver_bound = 1;
	const char *rec_path = NULL, *expect = NULL;
	int i;
	for (i = 1; i < argc && strcmp(argv[i], "--"); i++) {
		const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "0";
		if (!strcmp(a, "--stall-at")) d.stall_at = atoll(v), i++;
		else if (!strcmp(a, "--short-at")) d.short_at = atoll(v), i++;
		else if (!strcmp(a, "--unplug-at")) d.unplug_at = atoll(v), i++;
		else if (!strcmp(a, "--hold-at") && i + 2 < argc) d.hold_at = atoll(v), d.hold_ms = atol(argv[i + 2]), i += 2;
		else if (!strcmp(a, "--status")) d.status = (int)strtol(v, NULL, 0), i++;
		else if (!strcmp(a, "--id-le")) d.id_le = 1;
		else if (!strcmp(a, "--cp2110")) d.cp2110 = 1;
		else if (!strcmp(a, "--pen-rate")) d.pen_rate = atof(v), i++;
		else if (!strcmp(a, "--pcap")) {
			pcap = fopen(v, "wb");
			i++;
			guint32 gh[6] = { 0xa1b2c3d4, 0x00040002, 0, 0, 65535, 220 };
			if (!pcap || fwrite(gh, 4, 6, pcap) != 6) {
				perror(v);
				return 74;
			}
		}
		else if (!strcmp(a, "--record")) rec_path = v, i++;
		else if (!strcmp(a, "--expect")) expect = v, i++;
		else {
			fprintf(stderr, "emu-usb: unknown option %s\n", a);
			return 64;
		}
	}
	if (i + 1 >= argc) {
		fprintf(stderr, "usage: emu-usb [options] -- CMD ARGS... (see tests/emu/usbemu.c)\n");
		return 64;
	}
	UMockdevTestbed *tb = umockdev_testbed_new();
	UMockdevIoctlBase *handler = umockdev_ioctl_base_new();
	g_signal_connect(handler, "handle-ioctl", G_CALLBACK(on_ioctl), &d);
	GError *err = NULL;
	if (!umockdev_testbed_attach_ioctl(tb, DEVNODE, handler, &err)) {
		fprintf(stderr, "emu-usb: attach_ioctl: %s\n", err ? err->message : "?");
		return 70;
	}
	char *desc = g_strdup_printf(
		"P: /devices/pci0000:00/0000:00:14.0/usb1/1-1\n"
		"N: bus/usb/001/002=%s\n"
		"E: DEVNAME=" DEVNODE "\nE: DEVTYPE=usb_device\nE: DRIVER=usb\nE: SUBSYSTEM=usb\n"
		"E: BUSNUM=001\nE: DEVNUM=002\nE: MAJOR=189\nE: MINOR=1\n"
		"A: busnum=1\\n\nA: devnum=2\\n\nA: bConfigurationValue=1\\n\nA: speed=480\\n\n"
		"A: idVendor=%s\\n\nA: idProduct=%s\\n\n"
		"H: descriptors=%s\n", d.cp2110 ? hid_descriptors : descriptors, d.cp2110 ? "10c4" : "03f0",
		d.cp2110 ? "ea80" : "0107", d.cp2110 ? hid_descriptors : descriptors);
	if (!umockdev_testbed_add_from_string(tb, desc, &err)) {
		fprintf(stderr, "emu-usb: add device: %s\n", err ? err->message : "?");
		return 70;
	}
	g_free(desc);
	pid_t pid = fork();
	if (pid == 0) {
		char **cv = calloc((size_t)(argc - i) + 1, sizeof *cv);
		cv[0] = "umockdev-wrapper";
		for (int k = i + 1; k < argc; k++)
			cv[k - i] = argv[k];
		execvp(cv[0], cv);
		perror("umockdev-wrapper");
		_exit(127);
	}
	int status = 0;
	double start = now_s();
	for (;;) {
		while (g_main_context_iteration(NULL, FALSE))
			;
		if (d.hold_until > 0 && now_s() >= d.hold_until)
			d.hold_at = -1;   /* the printer is back */
		if (waitpid(pid, &status, WNOHANG) == pid)
			break;
		if (now_s() - start > 60) {
			kill(pid, SIGKILL);
			fprintf(stderr, "emu-usb: the command ran past 60 s: killed\n");
		}
		g_usleep(200);
	}
	int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
	printf("child=%d received=%zu stalls=%ld clears=%ld detached=%ld attached=%ld claims=%ld releases=%ld "
		"setconfig=%ld idreads=%ld statusreads=%ld resets=%ld driver=%s", code, d.nrec, d.stalls, d.clears,
		d.detaches, d.attaches, d.claims, d.releases, d.setconfigs, d.idreads, d.statusreads, d.resets,
		d.driver_bound ? (d.cp2110 ? "usbhid" : "usblp") : "none");
	if (d.cp2110)
		printf(" uart=%s baud=%ld parity=%d flow=%d bits=%d stop=%d purges=%d", d.uart_on ? "on" : "off",
			(long)d.uart[1] << 24 | (long)d.uart[2] << 16 | (long)d.uart[3] << 8 | d.uart[4], d.uart[5],
			d.uart[6], d.uart[7] + 5, d.uart[8] + 1, d.purges);
	if (d.cp2110)
		printf(" escapes=%ld dropped=%ld peak=%ld", d.escapes, d.dropped, d.peak);
	int bad = code != 0;
	if (rec_path) {
		FILE *f = fopen(rec_path, "wb");
		if (f) {
			if (d.nrec)
				fwrite(d.rec, 1, d.nrec, f);
			fclose(f);
		}
	}
	if (expect) {
		gchar *want = NULL;
		gsize nw = 0;
		if (!g_file_get_contents(expect, &want, &nw, NULL)) {
			printf(" expect=unreadable");
			bad = 1;
		} else if (nw == d.nrec && (nw == 0 || !memcmp(want, d.rec, nw))) {
			printf(" bytes=same");
		} else {
			size_t k = 0;
			while (k < nw && k < d.nrec && want[k] == (char)d.rec[k])
				k++;
			printf(" bytes=differ@%zu(expected %zu, got %zu)", k, (size_t)nw, d.nrec);
			bad = 1;
		}
		g_free(want);
	}
	printf("\n");
	if (pcap)
		fclose(pcap);
	g_object_unref(handler);
	g_object_unref(tb);
	free(d.rec);
	return bad;
}
