/* lp_link.c: Locus's serial: and hid: device links as PAPPL device schemes, found as locus-play finds them. */
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "printer/lp.h"

/* The URI is the Locus output name itself (docs/transports.md): serial:/dev/ttyUSB0?baud=9600&
 * flow=escb, hid:10c4:ea80[:SERIAL]?baud=...; serial:///dev/X is taken too. */
int lp_link_name(const char *uri, char *name, size_t n)
{
	if (!uri)
		return 0;
	const char *scheme = !strncmp(uri, "serial:", 7) ? "serial:" : !strncmp(uri, "hid:", 4) ? "hid:" : NULL;
	if (!scheme)
		return 0;
	const char *rest = uri + strlen(scheme);
	if (!strncmp(rest, "//", 2))
		rest += 2;
	if (!strcmp(scheme, "hid:") && *rest == '/')
		rest++;
	return snprintf(name, n, "%s%s", scheme, rest) < (int)n;
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
		if (io_close_err(l->t, IO_COMMIT, err, sizeof err))
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
	if (!l->t && !(l->t = io_open_write(l->name, err, sizeof err))) {
		papplDeviceError(dev, "%s", err);
		return -1;
	}
	if (io_write(l->t, buf, n) < 0 || io_flush(l->t) < 0) {
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
	long k = io_read(l->t, buf, n);
	return k < 0 ? -1 : (ssize_t)k;
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

/* hid: the CP2110 bridges, listed by the code behind locus-play --list-devices (io_list_devices):
 * its "hid:..." lines, name first, then maker and product. */
static bool list_hid(pappl_device_cb_t cb, void *data, pappl_deverror_cb_t err_cb, void *err_data)
{
	char tmp[1200], err[512], line[1024];
	snprintf(tmp, sizeof tmp, "%s/locus-devices-XXXXXX", papplGetTempDir());
	int fd = mkstemp(tmp);
	if (fd < 0)
		return false;
	unlink(tmp);
	char out[32];
	snprintf(out, sizeof out, "/dev/fd/%d", fd);
	io_transport_t *t = io_open_write(out, err, sizeof err);
	if (!t || io_list_devices(t, err, sizeof err) < 0) {
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
		if (strncmp(line, "hid:", 4))
			continue;
		size_t k = strcspn(line, " \t");
		const char *info = line + k + strspn(line + k, " \t");
		line[k] = 0;
		stop = cb(*info ? info : "CP2110 HID UART bridge", line, NULL, data);
	}
	if (f)
		fclose(f);
	else
		close(fd);
	return stop;
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
}
