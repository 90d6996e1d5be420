/* lp_job.c: locus-printer's jobs: a meta or HP-GL document checked, rendered, then sent (resumably). */
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include "hpgl/hpgl.h"
#include "hpgl/read/hpgl_read.h"
#include "import/svg_import.h"
#include "printer/lp.h"
#include "cli/run.h"

static int resume_wait = 600;      /* seconds a job waits for a link device to come back */
static long long max_doc = LP_MAX_DOC_DEFAULT;   /* bytes; 0: no limit */

void lp_set_resume_wait(int seconds)
{
	resume_wait = seconds;
}

void lp_set_max_document(long long bytes)
{
	max_doc = bytes;
}

bool lp_job_size_ok(pappl_job_t *job)
{
	struct stat st;
	const char *path = papplJobGetFilename(job);
	if (!max_doc || !path || stat(path, &st) || (long long)st.st_size <= max_doc)
		return true;
	char msg[256];
	snprintf(msg, sizeof msg, "the document is %lld bytes, more than this server takes (max-document-size=%lld)",
		(long long)st.st_size, max_doc);
	papplLogJob(job, PAPPL_LOGLEVEL_ERROR, "%s", msg);
	papplJobSetMessage(job, "%s", msg);
	papplJobSetReasons(job, PAPPL_JREASON_DOCUMENT_UNPRINTABLE_ERROR, PAPPL_JREASON_NONE);
	return false;
}

/* What the first bytes of an application/octet-stream document say it is. */
static const char *sniff(const unsigned char *h, size_t n, void *data)
{
	(void)data;
	static const unsigned char bin[8] = { 0x8b, 0x4c, 0x4d, 0x42, 0x0d, 0x0a, 0x1a, 0x0a };
	if ((n >= 10 && !memcmp(h, "LOCUS-META", 10)) || (n >= 8 && !memcmp(h, bin, 8)))
		return LP_FMT_META;
	/* HP-GL: after blanks and device-control escapes, IN, DF, SP, PU, PA or a PCL frame */
	size_t k = 0;
	while (k < n && (h[k] == ' ' || h[k] == '\r' || h[k] == '\n' || h[k] == '\t'))
		k++;
	if (k + 3 <= n && h[k] == 0x1b && (h[k + 1] == '.' || h[k + 1] == '%' || h[k + 1] == 'E'))
		return LP_FMT_HPGL;
	static const char *const first[] = { "IN;", "IN\n", "IN\r", "DF;", "SP", "PU", "PA", "IP", "in;" };
	for (size_t i = 0; i < sizeof first / sizeof first[0]; i++)
		if (k + strlen(first[i]) <= n && !memcmp(h + k, first[i], strlen(first[i])))
			return LP_FMT_HPGL;
	/* SVG: XML (the importer's own test) with an <svg element in the first bytes PAPPL shows */
	for (size_t i = 0; svgimp_is(h, n) && i + 4 <= n; i++)
		if (!memcmp(h + i, "<svg", 4))
			return LP_FMT_SVG;
	return NULL;
}

/* The job failed for a reason of the document's own: it alone fails, the queue goes on. */
static bool doc_error(pappl_job_t *job, const char *msg)
{
	papplLogJob(job, PAPPL_LOGLEVEL_ERROR, "%s", msg);
	papplJobSetMessage(job, "%s", msg);
	papplJobSetReasons(job, PAPPL_JREASON_DOCUMENT_FORMAT_ERROR, PAPPL_JREASON_NONE);
	return false;
}

static bool job_error(pappl_job_t *job, const char *msg)
{
	papplLogJob(job, PAPPL_LOGLEVEL_ERROR, "%s", msg);
	papplJobSetMessage(job, "%s", msg);
	papplJobSetReasons(job, PAPPL_JREASON_ABORTED_BY_SYSTEM, PAPPL_JREASON_NONE);
	return false;
}

/* The pages of a meta file, read through once: the whole file is checked before a byte goes
 * to a device (a plotter must not draw half a broken job). -1 with the reader's line in err. */
static long meta_pages(const char *path, const char *name, char *err, size_t n)
{
	meta_reader_t *r = meta_reader_open(path, err, n);
	if (!r)
		return -1;
	meta_cmd_t c;
	long pages = 0;
	int rc;
	while ((rc = meta_read(r, &c)) > 0)
		pages += c.op == META_PAGE;
	if (rc < 0) {
		/* the reader names the spool file: name the document instead */
		const char *e = meta_reader_error(r);
		if (!strncmp(e, path, strlen(path)))
			snprintf(err, n, "%s%s", name, e + strlen(path));
		else
			snprintf(err, n, "%s", e);
	}
	meta_reader_free(r);
	return rc < 0 ? -1 : pages;
}

/* The job's device options: the driver's, and the paper its media names (HP-GL). */
static void job_options(pappl_job_t *job, const lp_driver_t *d, char *opts, size_t n)
{
	snprintf(opts, n, "%s", d->options);
	if (d->family != LP_HPGL)
		return;
	pappl_pr_options_t *po = papplJobCreatePrintOptions(job, 1, true);
	if (!po)
		return;
	static const struct { const char *pwg, *paper; } map[] = {
		{ "iso_a4_210x297mm", "a4" }, { "iso_a3_297x420mm", "a3" },
		{ "na_letter_8.5x11in", "letter" }, { "na_ledger_11x17in", "b" },
	};
	const hpgl_profile_t *p = hpgl_profile_find(d->options + strlen("profile="));
	for (size_t k = 0; p && k < sizeof map / sizeof map[0]; k++) {
		int q = hpgl_paper_find(map[k].paper);
		if (!strcmp(po->media.size_name, map[k].pwg) && q >= 0 && q != p->paper && p->has_paper[q])
			snprintf(opts + strlen(opts), n - strlen(opts), ",paper=%s", map[k].paper);
	}
	papplJobDeletePrintOptions(po);
}

/* A temporary in the spool directory (0700), removed at once: job data is never left behind. */
static int spool_temp(void)
{
	char path[1200];
	snprintf(path, sizeof path, "%s/locus-job-XXXXXX", lp_spool_dir());
	int fd = mkstemp(path);
	if (fd >= 0)
		unlink(path);
	return fd;
}

/* After a cancel, an HP-GL job ends at a command boundary with the pen lifted and parked. */
static size_t to_boundary(const char *buf, size_t n)
{
	const char *semi = memchr(buf, ';', n);
	return semi ? (size_t)(semi - buf) + 1 : n;
}
static const char park[] = "PU;SP0;";

/* Send the rendered job (fd) to a PAPPL device (usb:, socket:, file:). */
static bool send_device(pappl_job_t *job, int fd, pappl_device_t *dev, int hpgl)
{
	char buf[16384];
	ssize_t k;
	lseek(fd, 0, SEEK_SET);
	while ((k = read(fd, buf, sizeof buf)) > 0) {
		size_t n = (size_t)k;
		int cancel = papplJobIsCanceled(job);
		if (cancel && !hpgl)
			break;
		if (cancel)
			n = to_boundary(buf, n);
		if (papplDeviceWrite(dev, buf, n) < 0)
			return job_error(job, "the device took no more of the job (see the printer's log)");
		if (cancel) {
			papplDeviceWrite(dev, park, sizeof park - 1);
			break;
		}
	}
	papplDeviceFlush(dev);
	return k >= 0 || job_error(job, "cannot read the rendered job back from the spool directory");
}

/* The plotter's state between the chunks of a paced send (io_watch_state): its reasons on the
 * printer, the job's message while it holds; a plotter that holds (paper lever up, VIEW) is waited
 * for up to resume-wait seconds (its buffer stays full meanwhile), a canceled job stops the send. */
typedef struct {
	pappl_job_t *job;
	time_t held_since;  /* 0: not held */
} watch_t;

static int watch_state(void *user, const io_devstate_t *st)
{
	watch_t *w = user;
	pappl_printer_t *pr = papplJobGetPrinter(w->job);
	pappl_preason_t r = lp_state_reasons(st);
	papplPrinterSetReasons(pr, r, LP_PLOT_REASONS & ~r);
	if (!(st->flags & (IO_DEV_NO_MEDIA | IO_DEV_PAUSED))) {
		if (w->held_since) {
			papplLogJob(w->job, PAPPL_LOGLEVEL_INFO, "the plotter is ready again");
			papplJobSetMessage(w->job, "printing");
		}
		w->held_since = 0;
		return 0;
	}
	if (!w->held_since) {
		w->held_since = time(NULL);
		papplLogJob(w->job, PAPPL_LOGLEVEL_WARN, "mid-job: %s; waiting up to %d s", st->words, resume_wait);
		papplJobSetMessage(w->job, "waiting for the plotter: %s", st->words);
	}
	if (papplJobIsCanceled(w->job))
		return -1;   /* (a plotter that takes bytes gets the canceled job's pen-up and park) */
	return time(NULL) - w->held_since < resume_wait ? 1 : 0;
}

/* One try of a link job: the rendered bytes into the Locus link name with journal= (first try)
 * or resume= (after a failure): the journal skips what the device has. 0, 75 (the device went
 * away: try again), 74 (it could not be opened or failed otherwise), 1 canceled. */
static int send_link(pappl_job_t *job, int fd, const char *link, const char *jnl, int resume, int hpgl,
		char *err, size_t n)
{
	char name[2300];
	snprintf(name, sizeof name, "%s%c%s=%s", link, strchr(link, '?') ? '&' : '?', resume ? "resume" : "journal", jnl);
	lp_link_lock();
	io_transport_t *t = io_open_write(name, err, n);
	if (!t) {
		lp_link_unlock();
		return 74;
	}
	char buf[1024];
	ssize_t k;
	int st = 0;
	/* the plotter's state every 2 s during the send (flow=escb links: between ESC.B chunks) */
	watch_t w = { job, 0 };
	io_watch_state(watch_state, &w, 2000);
	lseek(fd, 0, SEEK_SET);
	while (!st && (k = read(fd, buf, sizeof buf)) > 0) {
		size_t m = (size_t)k;
		int cancel = papplJobIsCanceled(job);
		if (cancel && hpgl)
			m = to_boundary(buf, m);
		if (!(cancel && !hpgl) && (io_write(t, buf, m) < 0 || io_flush(t) < 0))
			break;
		if (cancel) {
			if (hpgl)
				io_write(t, park, sizeof park - 1);
			st = 1;
		}
	}
	if (!st && !io_failed(t))
		io_drain(t);
	if (io_failed(t)) {
		snprintf(err, n, "%s", io_error(t));
		st = io_temporary(t) ? 75 : 74;
	}
	if (io_close_err(t, st && st != 1 ? IO_ABORT : IO_COMMIT, st ? NULL : err, n) && !st)
		st = 74;
	io_watch_state(NULL, NULL, 0);
	lp_link_unlock();
	return st;
}

/* The journal's resume point ("safe N"), -1 when there is none. */
static long journal_safe(const char *path)
{
	FILE *f = fopen(path, "r");
	char line[256];
	long safe = -1;
	while (f && fgets(line, sizeof line, f))
		if (sscanf(line, "safe %ld", &safe) == 1)
			break;
	if (f)
		fclose(f);
	return safe;
}

/* The plotter's own state before a try (ESC.O, OS, OE: lp_link_probe) as the printer's reasons.
 * true when the job must wait: the paper lever is raised or VIEW is pressed (a plotter then
 * drops or holds what it gets); msg says why. */
static bool plotter_holds(pappl_printer_t *pr, const char *link, char *msg, size_t n)
{
	pappl_preason_t r;
	lp_link_lock();
	int rc = lp_link_probe(link, &r, msg, n);
	lp_link_unlock();
	if (rc <= 0)
		return false;   /* no answer: the try says what is wrong */
	papplPrinterSetReasons(pr, r, LP_PLOT_REASONS & ~r);
	return (r & PAPPL_PREASON_MEDIA_NEEDED) || ((r & PAPPL_PREASON_OTHER) && strstr(msg, "VIEW"));
}

/* A job on a serial: or hid: printer: journaled; when the device goes away mid-job the job waits
 * (printer offline, the job's message saying so) and resumes at the journal's point when the
 * device is back, so no stroke is lost or drawn twice. Before each try the plotter is asked for
 * its state (when its link answers, flow=escb): a raised paper lever shows as media-needed and
 * the job waits for it to be lowered. */
static bool play_link(pappl_job_t *job, int fd, const char *link, int hpgl)
{
	pappl_printer_t *pr = papplJobGetPrinter(job);
	char jnl[1200], err[1024], why[512];
	snprintf(jnl, sizeof jnl, "%s/%s-job%d.jnl", lp_spool_dir(), papplPrinterGetName(pr), papplJobGetID(job));
	unlink(jnl);
	time_t give_up = time(NULL) + resume_wait;
	int told = 0, held = 0, tries = 0, st = 74;
	snprintf(err, sizeof err, "the device did not come back");
	while (!papplJobIsCanceled(job)) {
		if (plotter_holds(pr, link, why, sizeof why)) {
			if (!held++)
				papplLogJob(job, PAPPL_LOGLEVEL_WARN, "%s; waiting up to %d s", why, resume_wait);
			papplJobSetMessage(job, "waiting for the plotter: %s", why);
			snprintf(err, sizeof err, "%s", why);
			if (time(NULL) >= give_up)
				break;
			sleep(1);
			continue;
		}
		if (held) {
			papplLogJob(job, PAPPL_LOGLEVEL_INFO, "the plotter is ready again");
			papplJobSetMessage(job, "printing");
			held = 0;
		}
		long safe = tries ? journal_safe(jnl) : -1;
		st = send_link(job, fd, link, jnl, safe >= 0, hpgl, err, sizeof err);
		if (tries++ && st != 74)
			papplLogJob(job, PAPPL_LOGLEVEL_INFO, "the device is back: %s at byte %ld of the job (the journal's point)",
				safe >= 0 ? "resumed" : "started again", safe >= 0 ? safe : 0);
		if ((st != 74 && st != 75) || time(NULL) >= give_up)
			break;
		papplPrinterSetReasons(pr, PAPPL_PREASON_OFFLINE, PAPPL_PREASON_NONE);
		papplJobSetMessage(job, "waiting for the device: %s", err);
		if (st == 75 || !told++)
			papplLogJob(job, PAPPL_LOGLEVEL_WARN, "%s; waiting up to %d s for the device to resume", err, resume_wait);
		sleep(1);
	}
	papplPrinterSetReasons(pr, PAPPL_PREASON_NONE, PAPPL_PREASON_OFFLINE);
	unlink(jnl);
	if (st == 1 || papplJobIsCanceled(job))
		return true;   /* PAPPL marks it canceled */
	if ((st == 74 || st == 75) && tries > 1) {
		char msg[1200];
		snprintf(msg, sizeof msg, "gave up after waiting resume-wait=%d s for the device: %s", resume_wait, err);
		return job_error(job, msg);
	}
	if (st)
		return job_error(job, err);
	papplJobSetMessage(job, "delivered");
	return true;
}

bool lp_play_meta(pappl_job_t *job, pappl_device_t *device, const char *path, int count)
{
	const lp_driver_t *d = lp_job_driver(job);
	if (!d)
		return job_error(job, "the printer's driver is not a Locus driver");
	char err[1024], opts[256], link[1024];
	long pages = meta_pages(path, papplJobGetName(job) ? papplJobGetName(job) : "document", err, sizeof err);
	if (pages < 0)
		return doc_error(job, err);
	if (count)
		papplJobSetImpressions(job, (int)pages);
	job_options(job, d, opts, sizeof opts);
	int fd = spool_temp();
	if (fd < 0)
		return job_error(job, "cannot make a temporary in the spool directory");
	char out[32];
	snprintf(out, sizeof out, "/dev/fd/%d", fd);
	dev_job_t dj = { path, out, d->ops, 0, 0, opts[0] ? opts : NULL };
	lp_lock();
	int st = dev_run(&dj, err, sizeof err);
	lp_unlock();
	bool ok;
	if (st == 65)
		ok = doc_error(job, err);
	else if (st)
		ok = job_error(job, err);
	else if (lp_link_name(papplPrinterGetDeviceURI(papplJobGetPrinter(job)), link, sizeof link))
		ok = play_link(job, fd, link, d->family == LP_HPGL);
	else
		ok = send_device(job, fd, device, d->family == LP_HPGL);
	close(fd);
	if (ok && count && !papplJobIsCanceled(job))
		papplJobSetImpressionsCompleted(job, (int)pages);
	return ok;
}

static bool meta_filter(pappl_job_t *job, pappl_device_t *device, void *data)
{
	(void)data;
	if (!lp_job_size_ok(job))
		return false;
	return lp_play_meta(job, device, papplJobGetFilename(job), 1);
}

/* An HP-GL document: read through by the HP-GL reader first (a broken file fails alone, before
 * anything reaches the plotter), then sent as it is, journaled on a Locus link. */
static bool hpgl_filter(pappl_job_t *job, pappl_device_t *device, void *data)
{
	(void)data;
	const lp_driver_t *d = lp_job_driver(job);
	const char *path = papplJobGetFilename(job), *name = papplJobGetName(job) ? papplJobGetName(job) : "document";
	if (!d || d->family != LP_HPGL)
		return doc_error(job, "HP-GL goes to HP-GL printers only");
	if (!lp_job_size_ok(job))
		return false;
	FILE *f = fopen(path, "rb");
	if (!f)
		return job_error(job, "cannot open the spooled document");
	hpgl_doc_t doc;
	char err[1024], link[1024];
	int rc = hpgl_read_stream(f, name, &doc, err, sizeof err);
	size_t strokes = doc.nstrokes;
	hpgl_doc_free(&doc);
	if (rc) {
		fclose(f);
		return doc_error(job, err);
	}
	papplLogJob(job, PAPPL_LOGLEVEL_INFO, "HP-GL document read: %lu strokes", (unsigned long)strokes);
	papplJobSetImpressions(job, 1);
	int fd = fileno(f);
	bool ok = lp_link_name(papplPrinterGetDeviceURI(papplJobGetPrinter(job)), link, sizeof link)
		? play_link(job, fd, link, 1) : send_device(job, fd, device, 1);
	fclose(f);
	if (ok && !papplJobIsCanceled(job))
		papplJobSetImpressionsCompleted(job, 1);
	return ok;
}

static int file_write(void *user, const void *buf, size_t n)
{
	return fwrite(buf, 1, n, user) == n ? 0 : -1;
}

/* An SVG document: imported by the SVG importer (drivers/import, as `locus-meta import` does
 * with its defaults: curves flattened to 0.0125 mm, one meta pixel per CSS px, pens by colour
 * from the 7475A's carousel) into a meta file in the spool directory, then replayed as any meta
 * job. A broken document fails alone with the importer's line (NAME:LINE:COL). */
static bool svg_filter(pappl_job_t *job, pappl_device_t *device, void *data)
{
	(void)data;
	const char *path = papplJobGetFilename(job), *name = papplJobGetName(job) ? papplJobGetName(job) : "document";
	if (!lp_job_size_ok(job))
		return false;
	FILE *in = fopen(path, "rb");
	struct stat st;
	if (!in || fstat(fileno(in), &st)) {
		if (in)
			fclose(in);
		return job_error(job, "cannot open the spooled document");
	}
	size_t n = (size_t)st.st_size;
	unsigned char *buf = malloc(n ? n : 1);
	size_t got = buf ? fread(buf, 1, n, in) : 0;
	fclose(in);
	if (!buf || got != n) {
		free(buf);
		return job_error(job, buf ? "cannot read the spooled document" : "out of memory reading the document");
	}
	char err[1024];
	if (!svgimp_is(buf, n)) {
		free(buf);
		snprintf(err, sizeof err, "%s: not an SVG document (expected XML: '<' after blanks at byte 0)", name);
		return doc_error(job, err);
	}
	char tmp[1200];
	snprintf(tmp, sizeof tmp, "%s/locus-svg-XXXXXX", lp_spool_dir());
	int fd = mkstemp(tmp);
	if (fd >= 0)
		unlink(tmp);
	FILE *f = fd >= 0 ? fdopen(fd, "w+") : NULL;
	if (!f) {
		if (fd >= 0)
			close(fd);
		free(buf);
		return job_error(job, "cannot make a temporary in the spool directory");
	}
	svgimp_opts_t o = { .tol_mm = 0.0125, .dpi = 96, .dedupe_mm = 0.05, .quiet = 1 };
	meta_writer_t *w = meta_writer_new(file_write, f, META_ENC_TEXT);
	int rc = -70;
	snprintf(err, sizeof err, "out of memory importing the SVG document");
	lp_lock();   /* the importer and libxml2 run one document at a time */
	if (w)
		rc = svgimp_import(buf, n, name, &o, w, err, sizeof err);
	lp_unlock();
	free(buf);
	if (w && meta_writer_close(w) < 0 && !rc) {
		rc = -74;
		snprintf(err, sizeof err, "cannot write the imported meta file in the spool directory");
	}
	if (fflush(f) && !rc) {
		rc = -74;
		snprintf(err, sizeof err, "cannot write the imported meta file in the spool directory");
	}
	bool ok;
	if (rc == -65)
		ok = doc_error(job, err);
	else if (rc)
		ok = job_error(job, err);
	else {
		char meta[32];
		snprintf(meta, sizeof meta, "/dev/fd/%d", fileno(f));
		papplLogJob(job, PAPPL_LOGLEVEL_INFO, "SVG document imported");
		ok = lp_play_meta(job, device, meta, 1);
	}
	fclose(f);
	return ok;
}

void lp_filters_add(pappl_system_t *system)
{
	papplSystemSetMIMECallback(system, sniff, NULL);
	for (size_t k = 0; k < lp_driver_count(); k++) {
		const char *f = lp_driver_at(k)->format;
		int seen = 0;
		for (size_t j = 0; j < k; j++)
			seen |= !strcmp(lp_driver_at(j)->format, f);
		if (!seen) {
			papplSystemAddMIMEFilter(system, LP_FMT_META, f, meta_filter, NULL);
			papplSystemAddMIMEFilter(system, LP_FMT_SVG, f, svg_filter, NULL);
		}
	}
	papplSystemAddMIMEFilter(system, LP_FMT_HPGL, LP_FMT_HPGL, hpgl_filter, NULL);
}
