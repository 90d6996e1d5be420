/* lp_main.c: locus-printer, an IPP Everywhere printer application (PAPPL) for the Locus devices. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "hpgl/hpgl_link.h"
#include "printer/lp.h"

#ifndef LOCUS_VERSION
#define LOCUS_VERSION "0.0.0"
#endif

static char spool_dir[1024];
static char state_file[1100];
static int is_server;

static void usage(void *data)
{
	(void)data;
	fputs("usage: locus-printer SUBCOMMAND [OPTIONS] [FILES]\n"
		"An IPP Everywhere printer application for the Locus devices: HP-GL pen plotters and\n"
		"cutters, PostScript and PDF printers, film recorders and raster files (docs/printer.md).\n"
		"Subcommands (PAPPL's):\n"
		"  server              run the server in the foreground\n"
		"  add PRINTER         add a printer: -d DEVICE-URI -m DRIVER (locus-printer drivers)\n"
		"  delete              delete a printer: -d PRINTER\n"
		"  devices             list the devices found (usb:, socket:, serial:, hid:, locus-usb:)\n"
		"  drivers             list the drivers, one a line, name first\n"
		"  printers            list the printers\n"
		"  submit FILES        print files: -d PRINTER, -o NAME=VALUE job options\n"
		"  jobs, cancel, status, shutdown, default, modify, options, autoadd\n"
		"Server options (-o NAME=VALUE):\n"
		"  server-port=PORT        the TCP port (default: the first free one from 8000)\n"
		"  spool-directory=DIR     spool files, job journals and the state file (0700)\n"
		"  log-file=FILE           the log ('-' standard error, 'syslog')\n"
		"  log-level=LEVEL         fatal, error, warn (default), info, debug\n"
		"  listen-hostname=NAME    where to listen (default localhost; '*' every address)\n"
		"  admin-group=GROUP       who may add, change and delete printers (with auth-service)\n"
		"  auth-service=SERVICE    the PAM service that checks administrators' passwords\n"
		"  resume-wait=SECONDS     how long a serial:/hid:/locus-usb: job waits for its device (600)\n"
		"  max-document-size=SIZE  larger documents are refused (default 100M; k, M, G; 0 none)\n"
		"  server-options=LIST     PAPPL's: no-web-interface, web-security, no-tls, ...\n"
		"Formats: application/vnd.locus-meta (text and binary), image/svg+xml, application/vnd.hp-HPGL,\n"
		"image/pwg-raster and image/urf (IPP Everywhere), and each device's own format raw.\n"
		"  --help, --version\n", stdout);
}

/* The server options PAPPL's default system takes, with localhost as the place to listen. */
static pappl_soptions_t server_options(const char *value)
{
	pappl_soptions_t so = PAPPL_SOPTIONS_MULTI_QUEUE | PAPPL_SOPTIONS_WEB_INTERFACE;
	static const struct {
		const char *name;
		pappl_soptions_t set, clear;
	} opts[] = {
		{ "none", 0, (pappl_soptions_t)~0u },
		{ "no-multi-queue", 0, PAPPL_SOPTIONS_MULTI_QUEUE },
		{ "no-web-interface", 0, PAPPL_SOPTIONS_WEB_INTERFACE },
		{ "web-security", PAPPL_SOPTIONS_WEB_SECURITY, 0 },
		{ "web-log", PAPPL_SOPTIONS_WEB_LOG, 0 },
		{ "web-network", PAPPL_SOPTIONS_WEB_NETWORK, 0 },
		{ "web-remote", PAPPL_SOPTIONS_WEB_REMOTE, 0 },
		{ "raw-socket", PAPPL_SOPTIONS_RAW_SOCKET, 0 },
		{ "no-tls", PAPPL_SOPTIONS_NO_TLS, 0 },
		{ "dnssd-host", PAPPL_SOPTIONS_DNSSD_HOST, 0 },
	};
	for (const char *p = value; p && *p;) {
		size_t n = strcspn(p, ",");
		for (size_t k = 0; k < sizeof opts / sizeof opts[0]; k++)
			if (strlen(opts[k].name) == n && !strncmp(p, opts[k].name, n))
				so = (so & ~opts[k].clear) | opts[k].set;
		p += n + (p[n] == ',');
	}
	return so;
}

static pappl_loglevel_t log_level(const char *v)
{
	if (!v) return PAPPL_LOGLEVEL_WARN;
	if (!strcmp(v, "fatal")) return PAPPL_LOGLEVEL_FATAL;
	if (!strcmp(v, "error")) return PAPPL_LOGLEVEL_ERROR;
	if (!strcmp(v, "info")) return PAPPL_LOGLEVEL_INFO;
	if (!strcmp(v, "debug")) return PAPPL_LOGLEVEL_DEBUG;
	return PAPPL_LOGLEVEL_WARN;
}

/* The spool directory: the option, else $HOME/.config/locus-printer.d (root: PAPPL's own state
 * directory is not assumed; /var/spool/locus-printer), made 0700 so job data is not readable by
 * others. */
static int make_spool(const char *opt)
{
	const char *home = getenv("HOME");
	if (opt)
		snprintf(spool_dir, sizeof spool_dir, "%s", opt);
	else if (getuid() == 0)
		snprintf(spool_dir, sizeof spool_dir, "/var/spool/locus-printer");
	else if (home)
		snprintf(spool_dir, sizeof spool_dir, "%s/.config/locus-printer.d", home);
	else
		snprintf(spool_dir, sizeof spool_dir, "%s/locus-printer%d.d", papplGetTempDir(), (int)getuid());
	if (mkdir(spool_dir, 0700) && errno != EEXIST) {
		fprintf(stderr, "locus-printer: spool-directory %s: %s\n", spool_dir, strerror(errno));
		return -1;
	}
	chmod(spool_dir, 0700);
	snprintf(state_file, sizeof state_file, "%s/locus-printer.state", spool_dir);
	lp_set_spool_dir(spool_dir);
	return 0;
}

/* PAPPL's domain socket for the CLI: what PAPPL 1.3 calls it (mainloop-support.c), by uid. */
static void socket_path(char *buf, size_t n)
{
	const char *snap = getenv("SNAP_COMMON");
	if (getuid())
		snprintf(buf, n, "%s/locus-printer%d.sock", papplGetTempDir(), (int)getuid());
	else if (snap)
		snprintf(buf, n, "%s/locus-printer.sock", snap);
	else
		snprintf(buf, n, "/run/locus-printer.sock");
}

/* PAPPL makes its domain socket 0777 and trusts every connection on it with administration:
 * the server's owner only (root connects anyway), as soon as the server runs. */
static bool private_socket(pappl_system_t *sys, void *data)
{
	(void)data;
	char path[1100];
	socket_path(path, sizeof path);
	if (chmod(path, 0600))
		papplLog(sys, PAPPL_LOGLEVEL_WARN, "%s: cannot make the socket private: %s", path, strerror(errno));
	return false;   /* once */
}

/* A size: bytes, or with k, M or G (1024, 1024^2, 1024^3); 0 is no limit. -1 when malformed. */
static long long parse_size(const char *v)
{
	char *end;
	errno = 0;
	long long n = strtoll(v, &end, 10);
	if (end == v || n < 0 || errno)
		return -1;
	int shift = *end == 'k' || *end == 'K' ? 10 : *end == 'M' ? 20 : *end == 'G' ? 30 : 0;
	if (shift)
		end++;
	if (*end || n > (LLONG_MAX >> shift))
		return -1;
	return n << shift;
}

/* PAPPL's system for every subcommand that needs one; the server also listens (localhost unless
 * told otherwise) and keeps its state in the spool directory. */
static pappl_system_t *system_cb(int num_options, cups_option_t *options, void *data)
{
	(void)data;
	const char *v;
	int port = 0;
	if ((v = cupsGetOption("server-port", num_options, options))) {
		char *end;
		errno = 0;
		long p = strtol(v, &end, 10);
		if (end == v || *end || p < 0 || p > 65535 || errno) {
			fprintf(stderr, "locus-printer: server-port=%s: expected a port number 0-65535\n", v);
			return NULL;
		}
		port = (int)p;
	}
	long long maxdoc = LP_MAX_DOC_DEFAULT;
	if ((v = cupsGetOption("max-document-size", num_options, options)) && (maxdoc = parse_size(v)) < 0) {
		fprintf(stderr, "locus-printer: max-document-size=%s: expected a size in bytes (k, M or G after it), 0 for none\n", v);
		return NULL;
	}
	lp_set_max_document(maxdoc);
	if (is_server && make_spool(cupsGetOption("spool-directory", num_options, options)))
		return NULL;
	if (!is_server) {   /* a client subcommand: nothing is spooled here */
		snprintf(spool_dir, sizeof spool_dir, "%s", papplGetTempDir());
		lp_set_spool_dir(spool_dir);
	}
	pappl_system_t *sys = papplSystemCreate(server_options(cupsGetOption("server-options", num_options, options)),
		"locus-printer", port, "_print,_universal", spool_dir,
		cupsGetOption("log-file", num_options, options), log_level(cupsGetOption("log-level", num_options, options)),
		cupsGetOption("auth-service", num_options, options), false);
	if (!sys)
		return NULL;
	if ((v = cupsGetOption("resume-wait", num_options, options)))
		lp_set_resume_wait(atoi(v));
	if ((v = cupsGetOption("admin-group", num_options, options)))
		papplSystemSetAdminGroup(sys, v);
	if ((v = cupsGetOption("server-hostname", num_options, options)))
		papplSystemSetHostName(sys, v);
	pappl_version_t ver;
	memset(&ver, 0, sizeof ver);
	snprintf(ver.name, sizeof ver.name, "locus-printer");
	snprintf(ver.sversion, sizeof ver.sversion, "%s", LOCUS_VERSION);
	sscanf(LOCUS_VERSION, "%hu.%hu.%hu", ver.version, ver.version + 1, ver.version + 2);
	papplSystemSetVersions(sys, 1, &ver);
	/* filters before drivers, drivers before the state: a printer's formats are fixed when it
	 * is made, and the state makes the printers */
	lp_filters_add(sys);
	/* PAPPL keeps the table, and the system lives until the program ends */
	static pappl_pr_driver_t drv[64];
	size_t n = lp_driver_count() < 64 ? lp_driver_count() : 64;
	for (size_t k = 0; k < n; k++) {
		const lp_driver_t *d = lp_driver_at(k);
		drv[k].name = d->name;
		drv[k].description = d->description;
		drv[k].device_id = d->device_id[0] ? d->device_id : NULL;
	}
	papplSystemSetPrinterDrivers(sys, (int)n, drv, lp_autoadd_cb, lp_create_cb, lp_driver_cb, NULL);
	if (is_server) {
		const char *listen = cupsGetOption("listen-hostname", num_options, options);
		if (!cupsGetOption("private-server", num_options, options)
			&& !papplSystemAddListeners(sys, listen ? listen : "localhost")) {
			fprintf(stderr, "locus-printer: cannot listen on %s port %d (in use?)\n", listen ? listen : "localhost", port);
			papplSystemDelete(sys);
			return NULL;
		}
		papplSystemAddTimerCallback(sys, 0, 0, private_socket, NULL);
		papplSystemLoadState(sys, state_file);
		papplSystemSetSaveCallback(sys, (pappl_save_cb_t)papplSystemSaveState, state_file);
	}
	return sys;
}

/* `devices`: PAPPL's list, one device a URI with its description and IEEE-1284 ID indented below.
 * DNS-SD browsing is left out when the Avahi daemon is not running: PAPPL 1.3 goes on after
 * failing to reach it and Avahi's library aborts the program. */
static bool show_device(const char *info, const char *uri, const char *id, void *data)
{
	(void)data;
	printf("%s\n", uri);
	if (info && *info)
		printf("    %s\n", info);
	if (id && *id)
		printf("    %s\n", id);
	return false;
}

static void show_error(const char *message, void *data)
{
	(void)data;
	fprintf(stderr, "locus-printer: %s\n", message);
}

static int list_devices(void)
{
	pappl_devtype_t types = PAPPL_DEVTYPE_ALL;
	if (access("/run/avahi-daemon/socket", F_OK))
		types &= ~(pappl_devtype_t)PAPPL_DEVTYPE_DNS_SD;
	papplDeviceList(types, show_device, NULL, show_error, NULL);
	return fflush(stdout) ? 74 : 0;
}

/* The subcommand: the first word that is no option and no option's value. */
static const char *subcommand(int argc, char **argv)
{
	for (int i = 1; i < argc; i++) {
		if (argv[i][0] != '-')
			return argv[i];
		if (argv[i][1] && argv[i][1] != '-' && !argv[i][2] && strchr("adjmnouU", argv[i][1]))
			i++;   /* its value follows */
	}
	return NULL;
}

int main(int argc, char **argv)
{
	/* --version names the program as every Locus program does; an unknown long option is a
	 * usage error (64) as everywhere in Locus (PAPPL would say 1) */
	for (int i = 1; i < argc; i++) {
		if (!strcmp(argv[i], "--"))
			break;
		if (!strcmp(argv[i], "--version")) {
			printf("locus-printer %s\n", LOCUS_VERSION);
			return 0;
		}
		if (!strncmp(argv[i], "--", 2) && strcmp(argv[i], "--help")) {
			fprintf(stderr, "locus-printer: unknown option '%s' (locus-printer --help lists them)\n", argv[i]);
			return 64;
		}
	}
	hpgl_link_register();   /* the jobs its device links take are HP-GL (or refused by its journal) */
	const char *sub = subcommand(argc, argv);
	is_server = sub && !strcmp(sub, "server");
	lp_drivers_init();
	lp_links_add();
	if (sub && !strcmp(sub, "devices"))
		return list_devices();
	return papplMainloop(argc, argv, LOCUS_VERSION, NULL, 0, NULL, NULL, NULL, NULL, NULL, system_cb, usage, NULL);
}
