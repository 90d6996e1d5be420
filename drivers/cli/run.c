/* run.c: one replay job for the programs: input, device, per-page outputs, exit status. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "cli/run.h"

typedef struct {
	const dev_job_t *job;
	io_transport_t **pages;   /* kept temporaries, one per page (file output) */
	size_t npages, cap;
	io_transport_t *shared;   /* written in place (stdout, a device, a pipe): every page */
	char err[512];
} job_state_t;

char *dev_page_name(const char *out, unsigned page)
{
	const char *dot = strrchr(out, '.'), *slash = strrchr(out, '/');
	if (!dot || (slash && dot < slash) || dot == out || (slash && dot == slash + 1))
		dot = out + strlen(out);
	size_t n = strlen(out) + 16;
	char *s = malloc(n);
	if (s)
		snprintf(s, n, "%.*s-%03u%s", (int)(dot - out), out, page, dot);
	return s;
}

/* The status of a failure whose cause is the errno e (a rename's, a close's: transport.h leaves
 * it in errno): 70 when memory ran out, else 74. */
static int errno_status(int e)
{
	return e == ENOMEM ? 70 : 74;
}

/* The status of a failed transport, by its errno: 70 out of memory, 75 a failure that may pass
 * (a device away, busy, dropped, a signal: resumable), else 74. */
static int tr_status(const io_transport_t *t)
{
	return io_errno(t) == ENOMEM ? 70 : io_temporary(t) ? 75 : 74;
}

static int on_page(dev_device_t *d, const dev_page_t *pg, int end)
{
	job_state_t *js = d->user;
	(void)pg;
	if (js->shared || !js->job->out)
		return 0;
	if (end) {
		io_transport_t *t = d->out;
		d->out = NULL;
		if (io_close(t, IO_KEEP)) {
			int rc = dev_fail(d, dev_code_of_errno(io_errno(t)), "%s", io_error(t));
			io_finish(t, 0, NULL, NULL, 0);
			return rc;
		}
		js->pages[js->npages++] = t;
		return 0;
	}
	if (js->npages == js->cap) {
		size_t n = js->cap ? js->cap * 2 : 8;
		io_transport_t **p = realloc(js->pages, n * sizeof *p);
		if (!p)
			return dev_fail(d, META_ENOMEM, "out of memory");
		js->pages = p;
		js->cap = n;
	}
	char err[512];
	d->out = io_open_write(js->job->out, err, sizeof err);
	if (!d->out)
		return dev_fail(d, dev_code_of_errno(errno), "%s", err);
	if (io_in_place(d->out))
		js->shared = d->out;   /* no file per page to rename: pages follow one another */
	return 0;
}

static int status_of(int rc)
{
	switch (rc) {
	case META_ESYNTAX: case META_ELIMIT: case META_EVERSION: case META_ESTATE: return 65;
	case META_ENOMEM: return 70;
	case DEV_EUSAGE: return 64;
	default: return 74;
	}
}

/* The job runner of dev_run (one_output 0) and dev_run_document (1). */
static int run_job(const dev_job_t *job, int one_output, char *err, size_t errlen)
{
	job_state_t js;
	memset(&js, 0, sizeof js);
	js.job = job;
	int status = 0;
	meta_reader_t *r = meta_reader_open(job->in, err, errlen);
	if (!r)
		return errno == ENOMEM ? 70 : 66;
	dev_device_t *d = dev_new(job->ops, NULL);
	if (!d) {
		meta_reader_free(r);
		snprintf(err, errlen, "out of memory");
		return 70;
	}
	d->user = &js;
	d->on_page = on_page;
	d->band_rows = job->band_rows;
	if (job->budget)
		d->mem_budget = job->budget;
	d->options = job->options;
	if (job->out && (one_output || strcmp(job->out, "-") == 0)) {
		js.shared = io_open_write(job->out, err, errlen);
		if (!js.shared)
			status = errno == ENOMEM ? 70 : 74;
		d->out = js.shared;
	}
	if (status == 0) {
		int rc = dev_play(r, d);
		io_transport_t *out = d->out ? d->out : js.shared;
		if (rc) {
			status = status_of(rc);
			if (status == 74 && out && io_failed(out)) {
				snprintf(err, errlen, "%s", io_error(out));   /* names the output and the cause */
				status = tr_status(out);   /* 75: try again later, or --resume a journal */
			} else if (d->reader_error || status != 65) {
				snprintf(err, errlen, "%s", dev_error(d));
			} else {
				snprintf(err, errlen, "%s: %s", strcmp(job->in, "-") ? job->in : "<stdin>", dev_error(d));
			}
		}
	}
	if (d->out && d->out != js.shared)
		io_close(d->out, IO_ABORT);   /* a page that failed half-way */
	/* the last bytes of an in-place output (a device link) go out, and the device confirms them,
	 * before the close, so that a device that went away then (a printer that dropped the
	 * connection at the end) is still known to be a temporary failure (75) */
	if (js.shared && status == 0 && io_drain(js.shared)) {
		snprintf(err, errlen, "%s", io_error(js.shared));
		status = tr_status(js.shared);
	}
	if (js.shared && io_close_err(js.shared, status ? IO_ABORT : IO_COMMIT, status ? NULL : err, errlen)
		&& status == 0)
		status = errno_status(errno);
	/* every page replayed: name them all first (a name that cannot be made renames nothing),
	 * then rename them all, or remove them all */
	char **names = NULL;
	if (status == 0 && js.npages > 1) {
		names = calloc(js.npages, sizeof *names);
		for (size_t k = 0; names && k < js.npages; k++)
			if (!(names[k] = dev_page_name(job->out, (unsigned)k + 1))) {
				for (size_t j = 0; j < k; j++)
					free(names[j]);
				free(names);
				names = NULL;
			}
		if (!names) {
			snprintf(err, errlen, "%s: out of memory for the page names", job->out);
			status = 70;
		}
	}
	size_t done = 0;   /* pages renamed into place */
	for (size_t k = 0; k < js.npages; k++) {
		int commit = status == 0;
		if (io_finish(js.pages[k], commit, names ? names[k] : NULL, err, errlen) && commit)
			status = errno_status(errno);
		else if (commit)
			done++;
	}
	/* a page that could not be renamed (its name resolved out of memory, say) takes the pages
	 * before it away again: a job leaves all its pages or none */
	for (size_t k = 0; names && status && k < done; k++)
		unlink(names[k]);
	for (size_t k = 0; names && k < js.npages; k++)
		free(names[k]);
	free(names);
	free(js.pages);
	dev_free(d);
	meta_reader_free(r);
	return status;
}

int dev_run(const dev_job_t *job, char *err, size_t errlen)
{
	return run_job(job, 0, err, errlen);
}

int dev_run_document(const dev_job_t *job, char *err, size_t errlen)
{
	return run_job(job, 1, err, errlen);
}
