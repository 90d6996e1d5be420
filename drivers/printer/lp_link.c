/* lp_link.c: Locus's serial: and hid: device links as PAPPL device schemes, found as locus-play finds them. */
#include <dirent.h>
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include "printer/lp.h"

/* One device link open at a time in the whole server: the links' signal handling (they catch
 * SIGINT, SIGTERM and SIGHUP while open for writing, counted in process-wide state) is not
 * thread-safe, and a serial line or HID bridge takes one talker. Jobs (lp_job.c), status
 * probes and PAPPL's own writes through the serial:/hid: schemes all hold it. */
static pthread_mutex_t link_lock = PTHREAD_MUTEX_INITIALIZER;

void lp_link_lock(void)
{
	pthread_mutex_lock(&link_lock);
}

int lp_link_trylock(void)
{
	return pthread_mutex_trylock(&link_lock) == 0;
}

void lp_link_unlock(void)
{
	pthread_mutex_unlock(&link_lock);
}

/* The URI is the Locus output name itself (docs/transports.md): serial:/dev/ttyUSB0?baud=9600&
 * flow=escb, hid:10c4:ea80[:SERIAL]?baud=...; serial:///dev/X is taken too. */
int lp_link_name(const char *uri, char *name, size_t n)
{
	if (!uri)
		return 0;
	/* locus-usb:VID:PID[:SERIAL] is Locus's usb: link (PAPPL keeps usb: for its own code) */
	const char *scheme = !strncmp(uri, "serial:", 7) ? "serial:" : !strncmp(uri, "hid:", 4) ? "hid:"
		: !strncmp(uri, "locus-usb:", 10) ? "locus-usb:" : NULL;
	if (!scheme)
		return 0;
	const char *rest = uri + strlen(scheme);
	if (!strncmp(rest, "//", 2))
		rest += 2;
	if (strcmp(scheme, "serial:") && *rest == '/')
		rest++;
	return snprintf(name, n, "%s%s", strcmp(scheme, "locus-usb:") ? scheme : "usb:", rest) < (int)n;
}

/* A PAPPL device over a Locus link: opened on the first write (a job on such a printer goes
 * straight to the link with a journal, lp_job.c; this path serves PAPPL's own writes). */
typedef struct {
	char name[1024];
	io_transport_t *t;
} lp_link_t;

static bool link_open(pappl_device_t *dev, const char *uri, const char *job)
{
	(void)job;
	lp_link_t *l = calloc(1, sizeof *l);
	if (!l || !lp_link_name(uri, l->name, sizeof l->name)) {
		free(l);
		papplDeviceError(dev, "%s: not a Locus device link", uri);
		return false;
	}
	/* a serial line that is not there now fails the open, so PAPPL waits for it */
	if (!strncmp(l->name, "serial:", 7)) {
		char path[1024];
		snprintf(path, sizeof path, "%s", l->name + 7);
		path[strcspn(path, "?")] = 0;
		if (access(path, F_OK)) {
			papplDeviceError(dev, "%s: no such serial device: is it plugged in and powered?", path);
			free(l);
			return false;
		}
	}
	papplDeviceSetData(dev, l);
	return true;
}

static void link_close(pappl_device_t *dev)
{
	lp_link_t *l = papplDeviceGetData(dev);
	if (!l)
		return;
	if (l->t) {
		char err[1024];
		lp_link_lock();
		int bad = io_close_err(l->t, IO_COMMIT, err, sizeof err);
		lp_link_unlock();
		if (bad)
			papplDeviceError(dev, "%s", err);
	}
	free(l);
	papplDeviceSetData(dev, NULL);
}

static ssize_t link_write(pappl_device_t *dev, const void *buf, size_t n)
{
	lp_link_t *l = papplDeviceGetData(dev);
	char err[1024];
	if (!l)
		return -1;
	lp_link_lock();
	if (!l->t && !(l->t = io_open_write(l->name, err, sizeof err))) {
		lp_link_unlock();
		papplDeviceError(dev, "%s", err);
		return -1;
	}
	int bad = io_write(l->t, buf, n) < 0 || io_flush(l->t) < 0;
	lp_link_unlock();
	if (bad) {
		papplDeviceError(dev, "%s", io_error(l->t));
		return -1;
	}
	return (ssize_t)n;
}

static ssize_t link_read(pappl_device_t *dev, void *buf, size_t n)
{
	lp_link_t *l = papplDeviceGetData(dev);
	if (!l || !l->t)
		return -1;
	lp_link_lock();
	long k = io_read(l->t, buf, n);
	lp_link_unlock();
	return k < 0 ? -1 : (ssize_t)k;
}

/* ---- status: the language's state query (HP-GL ESC.O, OS, OE) asked of a plotter that answers (flow=escb) ---- */

/* The probe's link name: the printer's, its flow, journal, resume and timeout replaced by
 * flow=none (the few query bytes need no pacing) and a one-second wait for each answer. 0 when
 * the link does not answer queries (no flow=escb: a one-way cable, or a plotter set up for
 * XON/XOFF whose answers are not read). */
static int probe_name(const char *link, char *out, size_t n)
{
	const char *q = strchr(link, '?');
	if (!q || !strstr(q, "flow=escb"))
		return 0;
	size_t k = (size_t)(q - link);
	if (k + 1 >= n)
		return 0;
	memcpy(out, link, k);
	out[k] = 0;
	char sep = '?';
	for (const char *p = q + 1; *p;) {
		size_t m = strcspn(p, "&");
		if (strncmp(p, "flow=", 5) && strncmp(p, "journal=", 8) && strncmp(p, "resume=", 7) && strncmp(p, "timeout=", 8)) {
			size_t len = strlen(out);
			if (len + m + 2 >= n)
				return 0;
			out[len] = sep;
			memcpy(out + len + 1, p, m);
			out[len + 1 + m] = 0;
			sep = '&';
		}
		p += m + (p[m] == '&');
	}
	size_t len = strlen(out);
	return snprintf(out + len, n - len, "%cflow=none&timeout=1", sep) < (int)(n - len);
}

pappl_preason_t lp_state_reasons(const io_devstate_t *st)
{
	pappl_preason_t r = PAPPL_PREASON_NONE;
	if (st->flags & IO_DEV_NO_MEDIA)
		r |= PAPPL_PREASON_MEDIA_NEEDED;
	if (st->flags & (IO_DEV_PAUSED | IO_DEV_ERROR))
		r |= PAPPL_PREASON_OTHER;
	return r;
}

int lp_link_probe(const char *link, pappl_preason_t *reasons, char *msg, size_t n)
{
	char name[1100], err[512];
	*reasons = PAPPL_PREASON_NONE;
	msg[0] = 0;
	if (!probe_name(link, name, sizeof name))
		return 0;
	io_transport_t *t = io_open_write(name, err, sizeof err);
	if (!t) {
		snprintf(msg, n, "%s", err);
		return -1;
	}
	/* the registered language's state query (HP-GL: ESC.O, OS, OE), each answer within 1.5 s */
	io_devstate_t st;
	int rc = io_device_state(t, 1500, &st);
	io_close(t, IO_ABORT);
	snprintf(msg, n, "%s", st.words);
	if (rc > 0)
		*reasons = lp_state_reasons(&st);
	return rc;
}

/* PAPPL's status callback for a printer on a serial: or hid: link, called when a client asks
 * for the printer's attributes and no job runs (at most every two seconds): the plotter's own
 * state as printer-state-reasons, and offline when its device is not there. A link busy with
 * another printer's job is not waited for: the reasons stay as they were. */
bool lp_status_cb(pappl_printer_t *printer)
{
	char link[1024], msg[512];
	if (!lp_link_name(papplPrinterGetDeviceURI(printer), link, sizeof link) || !lp_link_trylock())
		return true;
	pappl_preason_t r;
	int rc = lp_link_probe(link, &r, msg, sizeof msg);
	lp_link_unlock();
	if (rc > 0) {
		papplPrinterSetReasons(printer, r, (LP_PLOT_REASONS | PAPPL_PREASON_OFFLINE) & ~r);
		if (r)
			papplLogPrinter(printer, PAPPL_LOGLEVEL_INFO, "status: %s", msg);
	} else if (rc < 0 && !strncmp(link, "serial:", 7)) {
		/* the line is not there (unplugged), or nothing answers on it */
		char path[1024];
		snprintf(path, sizeof path, "%s", link + 7);
		path[strcspn(path, "?")] = 0;
		if (access(path, F_OK))
			papplPrinterSetReasons(printer, PAPPL_PREASON_OFFLINE, PAPPL_PREASON_NONE);
	}
	return true;
}

static pappl_preason_t link_status(pappl_device_t *dev)
{
	(void)dev;
	return PAPPL_PREASON_NONE;
}

/* serial: the USB-serial adapters and modem-class ports that are there (ttyUSB*, ttyACM*),
 * offered at 9600 baud with ESC.B pacing, the setting every HP-GL plotter takes. */
static bool list_serial(pappl_device_cb_t cb, void *data, pappl_deverror_cb_t err_cb, void *err_data)
{
	(void)err_cb;
	(void)err_data;
	DIR *d = opendir("/dev");
	struct dirent *e;
	bool stop = false;
	while (d && !stop && (e = readdir(d))) {
		if (strncmp(e->d_name, "ttyUSB", 6) && strncmp(e->d_name, "ttyACM", 6))
			continue;
		char uri[300], info[300];
		snprintf(uri, sizeof uri, "serial:/dev/%s?baud=9600&flow=escb", e->d_name);
		snprintf(info, sizeof info, "Serial port %s", e->d_name);
		stop = cb(info, uri, NULL, data);
	}
	if (d)
		closedir(d);
	return stop;
}

/* The links io_list_devices finds (the code behind locus-play --list-devices): its lines for
 * prefix ("hid:" the CP2110 bridges, "usb:" USB printer-class devices), name first, then the
 * description; a usb: line's IEEE-1284 ID (from "MFG:") goes to PAPPL as the device ID. The URI
 * is the line's name, usb: ones as locus-usb:. */
static bool list_links(const char *prefix, pappl_device_cb_t cb, void *data, pappl_deverror_cb_t err_cb,
		void *err_data)
{
	char tmp[1200], err[512], line[1024];
	snprintf(tmp, sizeof tmp, "%s/locus-devices-XXXXXX", papplGetTempDir());
	int fd = mkstemp(tmp);
	if (fd < 0)
		return false;
	unlink(tmp);
	char out[32];
	snprintf(out, sizeof out, "/dev/fd/%d", fd);
	/* hidapi and libusb are not called while a job holds a link: in the server the list then
	 * leaves the devices out and says so (the `devices` subcommand runs in its own process) */
	if (!lp_link_trylock()) {
		close(fd);
		if (err_cb)
			err_cb("Locus links not listed: a job is using a device link", err_data);
		return false;
	}
	io_transport_t *t = io_open_write(out, err, sizeof err);
	int listed = t && io_list_devices(t, err, sizeof err) >= 0;
	lp_link_unlock();
	if (!listed) {
		if (t)
			io_close(t, IO_ABORT);
		if (err_cb && !strstr(err, "no "))
			err_cb(err, err_data);
		close(fd);
		return false;
	}
	io_close(t, IO_COMMIT);
	lseek(fd, 0, SEEK_SET);
	FILE *f = fdopen(fd, "r");
	bool stop = false;
	while (f && !stop && fgets(line, sizeof line, f)) {
		line[strcspn(line, "\n")] = 0;
		if (strncmp(line, prefix, strlen(prefix)))
			continue;
		size_t k = strcspn(line, " \t");
		char *info = line + k + strspn(line + k, " \t");
		line[k] = 0;
		char *id = strstr(info, "MFG:");
		char uri[1100];
		snprintf(uri, sizeof uri, "%s%s", strcmp(prefix, "usb:") ? "" : "locus-", line);
		if (id && id > info)
			id[-1] = 0;
		size_t m = strlen(info);
		while (m && (info[m - 1] == ' ' || info[m - 1] == '\t'))
			info[--m] = 0;
		char desc[600];
		if (!strcmp(prefix, "usb:"))
			snprintf(desc, sizeof desc, "USB printer-class device%s%s%s (Locus link: journaled, resumable)",
				*info ? " (" : "", info, *info ? ")" : "");
		else
			snprintf(desc, sizeof desc, "%s", *info ? info : "CP2110 HID UART bridge");
		stop = cb(desc, uri, id, data);
	}
	if (f)
		fclose(f);
	else
		close(fd);
	return stop;
}

static bool list_hid(pappl_device_cb_t cb, void *data, pappl_deverror_cb_t err_cb, void *err_data)
{
	return list_links("hid:", cb, data, err_cb, err_data);
}

static bool list_usb(pappl_device_cb_t cb, void *data, pappl_deverror_cb_t err_cb, void *err_data)
{
	return list_links("usb:", cb, data, err_cb, err_data);
}

void lp_links_add(void)
{
	/* PAPPL adds its own schemes (file, socket, usb, ...) only while it has none: ask it about
	 * one of them first, so that ours join them rather than replace them */
	papplDeviceIsSupported("socket://localhost");
	papplDeviceAddScheme("serial", PAPPL_DEVTYPE_CUSTOM_LOCAL, list_serial, link_open, link_close, link_read,
		link_write, link_status, NULL);
	papplDeviceAddScheme("hid", PAPPL_DEVTYPE_CUSTOM_LOCAL, list_hid, link_open, link_close, link_read,
		link_write, link_status, NULL);
	/* Locus's own USB printer-class link (libusb), journaled and resumable like serial: and hid:
	 * (PAPPL's usb: scheme sends without a journal) */
	papplDeviceAddScheme("locus-usb", PAPPL_DEVTYPE_CUSTOM_LOCAL, list_usb, link_open, link_close, link_read,
		link_write, link_status, NULL);
}
