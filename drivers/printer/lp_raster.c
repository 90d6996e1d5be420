/* lp_raster.c: IPP Everywhere raster (PWG, Apple, JPEG, PNG) to a meta image, then onto the device. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "printer/lp.h"

/* A raster job being written as a meta file: one page per raster page, each a full-page image
 * whose rows are run-length coded as they arrive (top row first, as the meta image wants). */
typedef struct {
	FILE *f;                    /* the meta file, in the spool directory, already unlinked */
	char path[32];              /* /dev/fd/N: how the replay reads it back */
	unsigned width, bpp, cspace;
	int failed;
} lp_raster_t;

bool lp_rstartjob(pappl_job_t *job, pappl_pr_options_t *options, pappl_device_t *device)
{
	(void)options;
	(void)device;
	if (!lp_job_size_ok(job))
		return false;
	lp_raster_t *r = calloc(1, sizeof *r);
	char tmp[1200];
	snprintf(tmp, sizeof tmp, "%s/locus-raster-XXXXXX", lp_spool_dir());
	int fd = r ? mkstemp(tmp) : -1;
	if (fd < 0) {
		free(r);
		papplLogJob(job, PAPPL_LOGLEVEL_ERROR, "cannot make a temporary in the spool directory");
		return false;
	}
	unlink(tmp);
	r->f = fdopen(fd, "w+");
	if (!r->f) {
		close(fd);
		free(r);
		return false;
	}
	snprintf(r->path, sizeof r->path, "/dev/fd/%d", fd);
	fputs("LOCUS-META 1\n", r->f);
	papplJobSetData(job, r);
	return true;
}

/* thousandths as the meta file writes them */
static void put_mm(FILE *f, double mm)
{
	long v = (long)(mm * 1000 + 0.5);
	fprintf(f, " %ld.%03ld", v / 1000, v % 1000);
}

bool lp_rstartpage(pappl_job_t *job, pappl_pr_options_t *options, pappl_device_t *device, unsigned page)
{
	(void)device;
	(void)page;
	lp_raster_t *r = papplJobGetData(job);
	const cups_page_header2_t *h = &options->header;
	if (!r)
		return false;
	if (h->cupsWidth < 1 || h->cupsHeight < 1 || h->cupsWidth > 32768 || h->cupsHeight > 32768) {
		papplLogJob(job, PAPPL_LOGLEVEL_ERROR, "a raster page of %ux%u pixels (the meta language takes 1-32768)",
			h->cupsWidth, h->cupsHeight);
		papplJobSetReasons(job, PAPPL_JREASON_DOCUMENT_UNPRINTABLE_ERROR, PAPPL_JREASON_NONE);
		return false;
	}
	if (h->cupsBitsPerPixel != 1 && h->cupsBitsPerPixel != 8 && h->cupsBitsPerPixel != 24) {
		papplLogJob(job, PAPPL_LOGLEVEL_ERROR, "raster of %u bits per pixel", h->cupsBitsPerPixel);
		return false;
	}
	r->width = h->cupsWidth;
	r->bpp = h->cupsBitsPerPixel;
	r->cspace = h->cupsColorSpace;
	unsigned dx = h->HWResolution[0] ? h->HWResolution[0] : 300, dy = h->HWResolution[1] ? h->HWResolution[1] : dx;
	fprintf(r->f, "page %u %u\nsize", h->cupsWidth, h->cupsHeight);
	put_mm(r->f, h->cupsWidth * 25.4 / dx);
	put_mm(r->f, h->cupsHeight * 25.4 / dy);
	fprintf(r->f, "\nimage 0 0 %u %u\n", h->cupsWidth, h->cupsHeight);
	return !ferror(r->f);
}

/* One pixel as 0xRRGGBB. */
static unsigned long pixel(const lp_raster_t *r, const unsigned char *line, unsigned x)
{
	unsigned v;
	switch (r->bpp) {
	case 1:   /* black_1: a set bit is black */
		return line[x >> 3] & (0x80 >> (x & 7)) ? 0 : 0xffffff;
	case 8:   /* black_8 counts ink, sgray_8 light */
		v = line[x];
		if (r->cspace == CUPS_CSPACE_K)
			v = 255 - v;
		return (unsigned long)v << 16 | v << 8 | v;
	default:
		return (unsigned long)line[3 * x] << 16 | (unsigned long)line[3 * x + 1] << 8 | line[3 * x + 2];
	}
}

bool lp_rwriteline(pappl_job_t *job, pappl_pr_options_t *options, pappl_device_t *device, unsigned y,
		const unsigned char *line)
{
	(void)options;
	(void)device;
	(void)y;
	lp_raster_t *r = papplJobGetData(job);
	if (!r)
		return false;
	fputs("row", r->f);
	for (unsigned x = 0; x < r->width;) {
		unsigned long c = pixel(r, line, x);
		unsigned n = 1;
		while (x + n < r->width && pixel(r, line, x + n) == c)
			n++;
		fprintf(r->f, " %u #%06lx", n, c);
		x += n;
	}
	fputc('\n', r->f);
	return !ferror(r->f);
}

bool lp_rendpage(pappl_job_t *job, pappl_pr_options_t *options, pappl_device_t *device, unsigned page)
{
	(void)options;
	(void)device;
	(void)page;
	lp_raster_t *r = papplJobGetData(job);
	if (!r)
		return false;
	fputs("end-page\n", r->f);
	return !ferror(r->f);
}

/* The whole raster job is a meta file now: replay it as any meta job (lp_job.c). */
bool lp_rendjob(pappl_job_t *job, pappl_pr_options_t *options, pappl_device_t *device)
{
	(void)options;
	lp_raster_t *r = papplJobGetData(job);
	if (!r)
		return false;
	papplJobSetData(job, NULL);
	bool ok = fflush(r->f) == 0 && !ferror(r->f);
	if (!ok)
		papplLogJob(job, PAPPL_LOGLEVEL_ERROR, "cannot write the raster's meta file in the spool directory");
	else
		ok = lp_play_meta(job, device, r->path, 0);   /* PAPPL counts raster pages itself */
	fclose(r->f);
	free(r);
	return ok;
}
