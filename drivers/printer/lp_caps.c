/* lp_caps.c: the drivers' IPP side: PAPPL's driver, create and auto-add callbacks (media,
 * resolutions, raster types, supplies, status) for the table of lp_drivers.c. */
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include "hpgl/hpgl.h"
#include "printer/lp.h"

/* The PWG media names of an HP-GL profile's papers. */
static const char *paper_media(int paper)
{
	switch (paper) {
	case HPGL_PAPER_A4: return "iso_a4_210x297mm";
	case HPGL_PAPER_A3: return "iso_a3_297x420mm";
	case HPGL_PAPER_LETTER: return "na_letter_8.5x11in";
	case HPGL_PAPER_B: return "na_ledger_11x17in";
	default: return NULL;
	}
}

static void set_media(pappl_media_col_t *m, const char *name, int lr, int bt)
{
	pwg_media_t *pwg = pwgMediaForPWG(name);
	memset(m, 0, sizeof *m);
	snprintf(m->size_name, sizeof m->size_name, "%s", name);
	if (pwg) {
		m->size_width = pwg->width;
		m->size_length = pwg->length;
	}
	m->left_margin = m->right_margin = lr;
	m->bottom_margin = m->top_margin = bt;
	snprintf(m->source, sizeof m->source, "main");
	snprintf(m->type, sizeof m->type, "stationery");
}

/* Identify-Printer: the devices have no panel of their own; the request shows in the log and
 * as the printer's state message (PAPPL's "display"). */
static void identify(pappl_printer_t *printer, pappl_identify_actions_t actions, const char *message)
{
	(void)actions;
	papplLogPrinter(printer, PAPPL_LOGLEVEL_INFO, "Identify-Printer: %s", message ? message : "(no message)");
}

bool lp_driver_cb(pappl_system_t *system, const char *driver_name, const char *device_uri,
		const char *device_id, pappl_pr_driver_data_t *data, ipp_t **attrs, void *cbdata)
{
	(void)device_id;
	(void)cbdata;
	const lp_driver_t *d = lp_driver_find(driver_name);
	if (!d) {
		papplLog(system, PAPPL_LOGLEVEL_ERROR, "No driver '%s' (locus-printer drivers lists them).", driver_name);
		return false;
	}
	data->rstartjob_cb = lp_rstartjob;
	data->rstartpage_cb = lp_rstartpage;
	data->rwriteline_cb = lp_rwriteline;
	data->rendpage_cb = lp_rendpage;
	data->rendjob_cb = lp_rendjob;
	data->format = d->format;
	snprintf(data->make_and_model, sizeof data->make_and_model, "Locus %.*s", (int)sizeof data->make_and_model - 7, d->description);
	data->ppm = 1;
	data->has_supplies = d->family == LP_HPGL;
	data->ppm_color = 1;
	data->kind = d->family == LP_HPGL ? PAPPL_KIND_DOCUMENT | PAPPL_KIND_LARGE_FORMAT : PAPPL_KIND_DOCUMENT;
	data->color_supported = PAPPL_COLOR_MODE_AUTO | PAPPL_COLOR_MODE_COLOR | PAPPL_COLOR_MODE_MONOCHROME;
	data->color_default = PAPPL_COLOR_MODE_COLOR;
	data->content_default = PAPPL_CONTENT_AUTO;
	data->quality_default = IPP_QUALITY_NORMAL;
	data->scaling_default = PAPPL_SCALING_AUTO;
	data->orient_default = IPP_ORIENT_PORTRAIT;
	data->identify_cb = identify;
	/* a plotter on a Locus link is asked for its state when idle (lp_link.c) */
	char link[1024];
	if (d->family == LP_HPGL && lp_link_name(device_uri, link, sizeof link))
		data->status_cb = lp_status_cb;
	data->identify_default = PAPPL_IDENTIFY_ACTIONS_DISPLAY;
	data->identify_supported = PAPPL_IDENTIFY_ACTIONS_DISPLAY;
	/* what IPP Everywhere asks for that PAPPL 1.3 leaves to the driver: no preferred-attributes
	 * answer, and colour is taken as it comes (no rendering intents) */
	if (attrs && (*attrs = ippNew()) != NULL) {
		ippAddBoolean(*attrs, IPP_TAG_PRINTER, "preferred-attributes-supported", 0);
		ippAddString(*attrs, IPP_TAG_PRINTER, IPP_CONST_TAG(IPP_TAG_KEYWORD), "print-rendering-intent-default", NULL, "auto");
		ippAddString(*attrs, IPP_TAG_PRINTER, IPP_CONST_TAG(IPP_TAG_KEYWORD), "print-rendering-intent-supported", NULL, "auto");
		ippAddString(*attrs, IPP_TAG_PRINTER, IPP_CONST_TAG(IPP_TAG_KEYWORD), "pwg-raster-document-sheet-back", NULL, "normal");
	}
	data->raster_types = PAPPL_PWG_RASTER_TYPE_BLACK_1 | PAPPL_PWG_RASTER_TYPE_BLACK_8 |
		PAPPL_PWG_RASTER_TYPE_SGRAY_8 | PAPPL_PWG_RASTER_TYPE_SRGB_8;
	data->sides_supported = PAPPL_SIDES_ONE_SIDED;
	data->sides_default = PAPPL_SIDES_ONE_SIDED;
	data->num_resolution = 1;
	data->x_resolution[0] = data->y_resolution[0] = d->dpi;
	data->x_default = data->y_default = d->dpi;
	data->num_source = 1;
	data->source[0] = "main";
	data->num_type = 1;
	data->type[0] = "stationery";
	const char *def = "iso_a4_210x297mm";
	if (d->family == LP_HPGL) {
		/* the profile's papers; margins are its hard-clip limits, near enough (5 mm) */
		const hpgl_profile_t *p = hpgl_profile_find(d->options + strlen("profile="));
		data->left_right = data->bottom_top = 500;
		for (int q = 0; p && q < HPGL_NPAPER; q++)
			if (p->has_paper[q] && paper_media(q))
				data->media[data->num_media++] = paper_media(q);
		if (p && paper_media(p->paper))
			def = paper_media(p->paper);
	} else {
		static const char *const office[] = { "iso_a4_210x297mm", "na_letter_8.5x11in", "iso_a3_297x420mm",
			"na_legal_8.5x14in", "iso_a5_148x210mm" };
		data->left_right = data->bottom_top = d->family == LP_PS ? 423 : 0;
		data->borderless = d->family != LP_PS;
		for (size_t k = 0; k < sizeof office / sizeof office[0]; k++)
			data->media[data->num_media++] = office[k];
	}
	set_media(&data->media_default, def, data->left_right, data->bottom_top);
	data->media_ready[0] = data->media_default;
	return true;
}

/* The supply colour nearest to a pen's ink. */
static pappl_supply_color_t supply_colour(uint32_t rgb)
{
	static const struct { uint32_t rgb; pappl_supply_color_t c; } ink[] = {
		{ 0x000000, PAPPL_SUPPLY_COLOR_BLACK }, { 0x808080, PAPPL_SUPPLY_COLOR_GRAY },
		{ 0xd02020, PAPPL_SUPPLY_COLOR_MAGENTA }, { 0x20a040, PAPPL_SUPPLY_COLOR_GREEN },
		{ 0x2050c0, PAPPL_SUPPLY_COLOR_CYAN }, { 0xe0d020, PAPPL_SUPPLY_COLOR_YELLOW },
		{ 0xf08020, PAPPL_SUPPLY_COLOR_ORANGE }, { 0x8030a0, PAPPL_SUPPLY_COLOR_VIOLET },
	};
	pappl_supply_color_t best = PAPPL_SUPPLY_COLOR_NO_COLOR;
	long bd = -1;
	for (size_t k = 0; k < sizeof ink / sizeof ink[0]; k++) {
		long dr = (long)(rgb >> 16 & 255) - (long)(ink[k].rgb >> 16 & 255);
		long dg = (long)(rgb >> 8 & 255) - (long)(ink[k].rgb >> 8 & 255);
		long db = (long)(rgb & 255) - (long)(ink[k].rgb & 255);
		long dd = dr * dr + dg * dg + db * db;
		if (bd < 0 || dd < bd) {
			bd = dd;
			best = ink[k].c;
		}
	}
	return best;
}

/* A new (or reloaded) printer: a plotter's supplies are the pens of its profile's carousel
 * (their levels are not known: a plotter cannot tell how much ink a pen has). */
void lp_create_cb(pappl_printer_t *printer, void *cbdata)
{
	(void)cbdata;
	const lp_driver_t *d = lp_driver_find(papplPrinterGetDriverName(printer));
	if (!d || d->family != LP_HPGL)
		return;
	const hpgl_profile_t *p = hpgl_profile_find(d->options + strlen("profile="));
	static hpgl_pens_t pens;   /* large: not on a thread's stack */
	static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
	char err[256];
	pappl_supply_t sup[PAPPL_MAX_SUPPLY];
	int n = 0;
	pthread_mutex_lock(&lock);
	if (p && !hpgl_pens_parse(p->pens, 0.3, &pens, err, sizeof err))
		for (size_t k = 0; k < pens.n && n < PAPPL_MAX_SUPPLY; k++, n++) {
			memset(&sup[n], 0, sizeof sup[n]);
			sup[n].color = supply_colour(pens.pen[k].rgb);
			snprintf(sup[n].description, sizeof sup[n].description, "Pen %d (%.2f mm, #%06x)", pens.pen[k].slot,
				pens.pen[k].width_mm, (unsigned)pens.pen[k].rgb);
			sup[n].is_consumed = true;
			sup[n].level = -1;
			sup[n].type = PAPPL_SUPPLY_TYPE_INK;
		}
	pthread_mutex_unlock(&lock);
	if (n)
		papplPrinterSetSupplies(printer, n, sup);
}

/* A device found by `devices` or at start-up: the driver whose model its IEEE-1284 ID names. */
const char *lp_autoadd_cb(const char *device_info, const char *device_uri, const char *device_id,
		void *cbdata)
{
	(void)device_info;
	(void)device_uri;
	(void)cbdata;
	if (!device_id)
		return NULL;
	const char *cmd = strstr(device_id, "CMD:");
	if (!cmd)
		cmd = strstr(device_id, "COMMAND SET:");
	if (!cmd)
		return NULL;
	if (strstr(cmd, "HPGL2") || strstr(cmd, "HP-GL/2"))
		return "hpgl-hpgl2";
	if (strstr(cmd, "HPGL") || strstr(cmd, "HP-GL")) {
		if (strstr(device_id, "7550"))
			return "hpgl-7550a";
		if (strstr(device_id, "DraftPro") || strstr(device_id, "DRAFTPRO"))
			return "hpgl-draftpro";
		return "hpgl-7475a";
	}
	if (strstr(cmd, "POSTSCRIPT") || strstr(cmd, "PostScript"))
		return "ps-level3";
	if (strstr(cmd, "PDF"))
		return "pdf";
	return NULL;
}
