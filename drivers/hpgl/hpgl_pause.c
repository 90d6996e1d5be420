/* hpgl_pause.c: the device's side of per-pen settings (VS, FS, AS sent with SP) and of pauses
 * before pens loaded by hand: the pen lifted, everything before it sent, the program's pauser
 * asked; a stop ends the job as a temporary failure with the job journal exactly at the pen
 * change, so that a --resume goes on with the new pen. (Parsing: hpgl_penset.c.) It calls
 * only hpgl_devutil.c of the device's files, not dev_hpgl.c or hpgl_page.c, which call it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "io/jobstop.h"
#include "hpgl/hpgl_dev.h"

/* ---- the pauser ---- */

static int (*pauser)(void *, const hpgl_pause_t *, char *, size_t);
static void *pauser_user;

void hpgl_set_pauser(int (*fn)(void *user, const hpgl_pause_t *p, char *why, size_t whylen), void *user)
{
	pauser = fn;
	pauser_user = user;
}

/* ---- the device's side ---- */

int hpgl_dev_pen_options(dev_device_t *d)
{
	hpgl_dev_t *h = d->priv;
	char buf[1024], err[300];
	memcpy(h->penset, h->prof.penset, sizeof h->penset);
	h->pause_all = h->prof.pause_all;
	h->loaded = -1;
	if (dev_option(d, "pen", buf, sizeof buf) && hpgl_penset_parse(buf, h->penset, err, sizeof err))
		return dev_fail(d, DEV_EUSAGE, "%s", err);
	if (dev_option(d, "pause", buf, sizeof buf) && hpgl_pause_parse(buf, h->penset, &h->pause_all, err, sizeof err))
		return dev_fail(d, DEV_EUSAGE, "%s", err);
	if (hpgl_penset_check(&h->prof, h->penset, err, sizeof err))
		return dev_fail(d, DEV_EUSAGE, "%s", err);
	return 0;
}

void hpgl_dev_pen_free(hpgl_dev_t *h)
{
	for (int k = 0; k <= HPGL_MAX_PENS; k++) {
		free(h->layer[k]);
		h->layer[k] = NULL;
	}
}

int hpgl_dev_comment(dev_device_t *d, const char *text, size_t len)
{
	hpgl_dev_t *h = d->priv;
	/* locus-meta import --pens by-layer writes: pen 2: layer "Pen 2 red" */
	int slot, at = 0;
	if (len < 16 || sscanf(text, "pen %d: layer \"%n", &slot, &at) != 1 || at == 0 || slot < 1 ||
			slot > HPGL_MAX_PENS || text[len - 1] != '"' || (size_t)at >= len)
		return 0;
	size_t n = len - 1 - (size_t)at;
	char *s = malloc(n + 1);
	if (!s)
		return hpgl_dev_nomem(d);
	memcpy(s, text + at, n);
	s[n] = 0;
	free(h->layer[slot]);
	h->layer[slot] = s;
	return 0;
}

/* Set a modal value (VS, FS, AS) to want (0: the plotter's default, the command without a
 * parameter) when another is in force. */
static int modal(hpgl_emit_t *em, const char *cmd, double want, double *now)
{
	if (want == *now)
		return 0;
	*now = want;
	return want > 0 ? hpgl_emit_cmd(em, "%s%g", cmd, want) : hpgl_emit_cmd(em, "%s", cmd);
}

/* The pause before pen slot: PU, everything sent; then ask (unless a resumed job's device had
 * this point already: the pen was loaded before the resume). 0 to go on, or the stop's code. */
static int pause_before(dev_device_t *d, int slot)
{
	hpgl_dev_t *h = d->priv;
	if (hpgl_emit_cmd(h->em, "PU") || hpgl_emit_flush(h->em))
		return hpgl_dev_emit_fail(d);
	if (!d->out || !io_in_place(d->out))
		return 0;   /* a file is plotted later, whole (begin_page warned) */
	if (io_flush(d->out))
		return dev_fail(d, META_EIO, "%s", io_error(d->out));
	uint64_t at = h->job_base + hpgl_emit_bytes(h->em);
	if (at <= io_resume_held(d->out))
		return 0;
	hpgl_pause_t q = { slot, h->layer[slot], d->page ? d->page->index : 0 };
	char why[200] = "nothing asks for pens here (no pauser)", msg[600], layer[240] = "";
	if (pauser && !pauser(pauser_user, &q, why, sizeof why))
		return 0;
	if (q.layer)
		snprintf(layer, sizeof layer, " (layer \"%.200s\")", q.layer);
	snprintf(msg, sizeof msg, "stopped before pen %d%s: %s; load the pen, then resume", slot, layer, why);
	io_stop(d->out, msg);
	return dev_fail(d, META_EIO, "%s", io_error(d->out));
}

int hpgl_dev_pen(dev_device_t *d, size_t k)
{
	hpgl_dev_t *h = d->priv;
	int slot = h->pens.pen[k].slot;
	const hpgl_penset_t *ps = &h->penset[slot];
	if ((ps->pause || h->pause_all) && slot != h->loaded) {
		int rc = pause_before(d, slot);
		if (rc)
			return rc;
	}
	h->loaded = slot;
	h->tprof.v_down = ps->speed > 0 ? ps->speed : h->prof.v_down;   /* the plot-time model draws at it */
	if (hpgl_emit_pen(h->em, slot) ||
			(h->prof.dialect == HPGL_DIALECT_2 && hpgl_emit_cmd(h->em, "PW%.2f,%d", h->pens.pen[k].width_mm, slot)) ||
			modal(h->em, "VS", ps->speed > 0 ? ps->speed : h->vs_page, &h->vs_now) ||
			modal(h->em, "FS", ps->force, &h->fs_now) || modal(h->em, "AS", ps->accel, &h->as_now))
		return hpgl_dev_emit_fail(d);
	return 0;
}
