/* lp.h: locus-printer's parts: the driver table, the job filters, the raster path, device links.
 *
 * Calls go one way: lp_main (the program, the system) -> lp_caps (IPP capabilities, PAPPL's
 * driver callbacks) -> lp_raster (raster jobs) -> lp_job (filters, replay, sending) ->
 * lp_drivers (the table), lp_link (serial:/hid: schemes, status, the link lock), lp_state
 * (spool directory, replay lock); no file calls one above it.
 *
 * locus-printer is a PAPPL printer application (papplMainloop): every Locus device is a driver
 * (lp_drivers.c), a job in a Locus format is replayed onto the printer's device through the same
 * device framework as the locus-* programs (lp_job.c), IPP Everywhere raster (PWG raster, Apple
 * raster) becomes a meta image first (lp_raster.c), and Locus's own device links, serial: and
 * hid:, are PAPPL device schemes (lp_link.c). docs/printer.md describes it for users.
 */
#ifndef LOCUS_LP_H
#define LOCUS_LP_H

#include <pappl/pappl.h>
#include "device/device.h"
#include "io/status.h"

/* The formats Locus reads (each a filter in lp_job.c, lp_filters_add; "Adding a format" in
 * docs/printer.md). */
#define LP_FMT_META "application/vnd.locus-meta"
#define LP_FMT_HPGL "application/vnd.hp-HPGL"
#define LP_FMT_SVG "image/svg+xml"

/* The families of drivers: what the device writes, and so which native format PAPPL sends raw. */
enum { LP_HPGL, LP_PS, LP_PDF, LP_FILM, LP_RASTER, LP_SVG };

/* One driver: a Locus device with its options. */
typedef struct {
	const char *name;           /* PAPPL driver name, e.g. "hpgl-7475a" */
	char description[128];      /* one line */
	int family;                 /* LP_* */
	const dev_ops_t *ops;       /* the Locus device */
	char options[96];           /* device options the driver always sets ("profile=7475a") */
	const char *format;         /* the native format (driver_data.format) */
	char device_id[128];        /* IEEE-1284 device ID it matches for auto-add, or "" */
	int dpi;                    /* raster jobs are rendered at this resolution */
} lp_driver_t;

/* The driver table (built once by lp_drivers_init) and lookup by name (lp_drivers.c). */
void lp_drivers_init(void);
size_t lp_driver_count(void);
const lp_driver_t *lp_driver_at(size_t k);
const lp_driver_t *lp_driver_find(const char *name);
/* The PAPPL callbacks of the driver table (lp_caps.c). */
bool lp_driver_cb(pappl_system_t *system, const char *driver_name, const char *device_uri,
		const char *device_id, pappl_pr_driver_data_t *data, ipp_t **attrs, void *cbdata);
const char *lp_autoadd_cb(const char *device_info, const char *device_uri, const char *device_id,
		void *cbdata);
void lp_create_cb(pappl_printer_t *printer, void *cbdata);
/* The driver of a job's printer. */
const lp_driver_t *lp_job_driver(pappl_job_t *job);

/* Register the job filters (meta and SVG to each native format, HP-GL to HP-GL) and the MIME
 * sniffer. */
void lp_filters_add(pappl_system_t *system);
/* Replay the meta file at path onto the job's device: the Locus device of the printer's
 * driver, with the job's options; the output goes to device (or, for serial:/hid: printers,
 * straight to the Locus link, journaled and resumed when the device comes back). count: set
 * the job's impressions from the file's pages (PAPPL counts raster jobs itself). true when
 * the job was delivered; false with the job's reasons and message set. */
bool lp_play_meta(pappl_job_t *job, pappl_device_t *device, const char *path, int count);
/* How long (seconds) a job on a serial:/hid: printer waits for its device to come back. */
void lp_set_resume_wait(int seconds);
/* The largest document (bytes, 0: no limit) a job may bring: server option max-document-size.
 * PAPPL spools the whole document before any of its callbacks sees the job, so a larger one
 * is aborted (job-state-message says why, job-state-reasons document-unprintable-error) before
 * anything is read or sent. */
#define LP_MAX_DOC_DEFAULT (100LL << 20)
void lp_set_max_document(long long bytes);
/* true when the job's document is within the limit; false with the job's message set. */
bool lp_job_size_ok(pappl_job_t *job);

/* The raster callbacks (IPP Everywhere: image/pwg-raster, image/urf). */
bool lp_rstartjob(pappl_job_t *job, pappl_pr_options_t *options, pappl_device_t *device);
bool lp_rstartpage(pappl_job_t *job, pappl_pr_options_t *options, pappl_device_t *device, unsigned page);
bool lp_rwriteline(pappl_job_t *job, pappl_pr_options_t *options, pappl_device_t *device, unsigned y,
		const unsigned char *line);
bool lp_rendpage(pappl_job_t *job, pappl_pr_options_t *options, pappl_device_t *device, unsigned page);
bool lp_rendjob(pappl_job_t *job, pappl_pr_options_t *options, pappl_device_t *device);

/* One device link open at a time, server-wide (lp_link.c says why): jobs, status probes and
 * PAPPL's writes through the schemes hold it. trylock: 1 when taken. */
void lp_link_lock(void);
int lp_link_trylock(void);
void lp_link_unlock(void);
/* The printer-state-reasons locus-printer keeps from a plotter's own answers. */
#define LP_PLOT_REASONS (PAPPL_PREASON_MEDIA_NEEDED | PAPPL_PREASON_OTHER)
/* A device's state (io/status.h, filled by the registered language: HP-GL's ESC.O, OS, OE) as
 * reasons: media-needed for no paper or the paper lever raised, other for a pause (VIEW) and
 * errors; st->words says it in words. */
pappl_preason_t lp_state_reasons(const io_devstate_t *st);
/* Ask the plotter on link (a Locus link name with flow=escb) for its state through the registered
 * language (io_device_state; HP-GL: ESC.O, OS, OE), the link opened with flow=none for those few
 * bytes (the caller holds the link lock): 1 with *reasons and
 * msg, 0 when the link cannot answer (no flow=escb), -1 when the device is not there or did
 * not answer (msg says which). */
int lp_link_probe(const char *link, pappl_preason_t *reasons, char *msg, size_t n);
/* PAPPL's status callback (driver data) for serial:/hid: printers: lp_link_probe when idle. */
bool lp_status_cb(pappl_printer_t *printer);

/* Locus's device links as PAPPL schemes: serial: and hid:. */
void lp_links_add(void);
/* 1 when the URI is one of them; then the Locus output name for it into name. */
int lp_link_name(const char *uri, char *name, size_t n);

/* The spool directory (set by the system callback), for journals and temporaries (lp_state.c). */
void lp_set_spool_dir(const char *dir);
const char *lp_spool_dir(void);
/* One device link replay at a time (the device framework's per-process hooks). */
void lp_lock(void);
void lp_unlock(void);

#endif
