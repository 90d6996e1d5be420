/* lp_drivers.c: locus-printer's driver table: one driver per Locus device and HP-GL profile (their
 * IPP capabilities and PAPPL callbacks are in lp_caps.c). */
#include <stdio.h>
#include <string.h>
#include "hpgl/hpgl.h"
#include "printer/lp.h"

#define LP_MAX_DRIVERS 32

static lp_driver_t drivers[LP_MAX_DRIVERS];
static char names[LP_MAX_DRIVERS][40];
static size_t ndrivers;

/* Add one driver; ops by its registry name. */
static lp_driver_t *add(const char *name, const char *dev, int family, const char *format, int dpi,
		const char *options, const char *description)
{
	const dev_ops_t *ops = dev_find(dev);
	if (!ops || ndrivers == LP_MAX_DRIVERS)
		return NULL;
	lp_driver_t *d = &drivers[ndrivers];
	snprintf(names[ndrivers], sizeof names[0], "%s", name);
	d->name = names[ndrivers++];
	d->ops = ops;
	d->family = family;
	d->format = format;
	d->dpi = dpi;
	snprintf(d->options, sizeof d->options, "%s", options);
	snprintf(d->description, sizeof d->description, "%s", description);
	return d;
}

void lp_drivers_init(void)
{
	if (ndrivers)
		return;
	/* every built-in HP-GL profile: the 7475A is hpgl-7475a */
	for (size_t k = 0; k < hpgl_profile_count(); k++) {
		const hpgl_profile_t *p = hpgl_profile_builtin(k);
		char name[40], opt[64], desc[128];
		snprintf(name, sizeof name, "hpgl-%s", p->name);
		snprintf(opt, sizeof opt, "profile=%s", p->name);
		snprintf(desc, sizeof desc, "%s (%s)", p->description, p->dialect == HPGL_DIALECT_2 ? "HP-GL/2" : "HP-GL");
		lp_driver_t *d = add(name, "hpgl", LP_HPGL, LP_FMT_HPGL, 50, opt, desc);
		if (!d)
			continue;
		/* the IEEE-1284 ID a plotter of this model reports (USB, or a bridge's) */
		if (!strcmp(p->name, "7475a"))
			snprintf(d->device_id, sizeof d->device_id, "MFG:Hewlett-Packard;MDL:7475A;CMD:HPGL;");
		else if (!strcmp(p->name, "7550a"))
			snprintf(d->device_id, sizeof d->device_id, "MFG:Hewlett-Packard;MDL:7550A;CMD:HPGL;");
		else if (!strcmp(p->name, "draftpro"))
			snprintf(d->device_id, sizeof d->device_id, "MFG:Hewlett-Packard;MDL:DraftPro;CMD:HPGL;");
		else if (!strcmp(p->name, "hpgl2"))
			snprintf(d->device_id, sizeof d->device_id, "CMD:HPGL2;");
	}
	add("ps-level1", "ps", LP_PS, "application/postscript", 300, "level=1", "PostScript Level 1 printer (DSC 3.0, hex images)");
	add("ps-level2", "ps", LP_PS, "application/postscript", 300, "level=2", "PostScript Level 2 printer (ASCII85 and run-length images)");
	lp_driver_t *ps3 = add("ps-level3", "ps", LP_PS, "application/postscript", 300, "level=3",
		"PostScript 3 printer (Flate-compressed pages and images)");
	if (ps3)
		snprintf(ps3->device_id, sizeof ps3->device_id, "CMD:POSTSCRIPT;");
	lp_driver_t *pdf = add("pdf", "pdf", LP_PDF, "application/pdf", 300, "", "PDF 1.4 printer or file, one page per page");
	if (pdf)
		snprintf(pdf->device_id, sizeof pdf->device_id, "CMD:PDF;");
	add("film-dpx", "film", LP_FILM, "image/x-dpx", 300, "format=dpx",
		"film recorder: DPX 10-bit log printing density frames (slide 4K)");
	add("raster-png", "png", LP_RASTER, "image/png", 300, "", "24-bit PNG pages (the reference rendering)");
	add("raster-ppm", "ppm", LP_RASTER, "image/x-portable-pixmap", 300, "", "24-bit binary PPM pages");
}

size_t lp_driver_count(void)
{
	return ndrivers;
}

const lp_driver_t *lp_driver_at(size_t k)
{
	return k < ndrivers ? &drivers[k] : NULL;
}

const lp_driver_t *lp_driver_find(const char *name)
{
	for (size_t k = 0; name && k < ndrivers; k++)
		if (!strcmp(drivers[k].name, name))
			return &drivers[k];
	return NULL;
}

const lp_driver_t *lp_job_driver(pappl_job_t *job)
{
	return lp_driver_find(papplPrinterGetDriverName(papplJobGetPrinter(job)));
}

