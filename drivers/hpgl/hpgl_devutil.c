/* hpgl_devutil.c: what the HP-GL device's collecting side (dev_hpgl.c), its page writer
 * (hpgl_page.c) and its pen changes (hpgl_pause.c) share: growing arrays, failures in one line,
 * and the program's reporter (warnings, page reports). It calls none of them. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "util/grow.h"
#include "hpgl/hpgl_dev.h"

int hpgl_dev_grow(void **p, size_t *cap, size_t need, size_t size)
{
	return dev_grow(p, cap, need, size, 64);
}

int hpgl_dev_nomem(dev_device_t *d)
{
	return dev_fail(d, META_ENOMEM, "hpgl: out of memory");
}

int hpgl_dev_need_tmp(hpgl_dev_t *h, size_t n)
{
	if (n <= h->captmp)
		return 0;
	return hpgl_dev_grow((void **)&h->tmp, &h->captmp, n, sizeof *h->tmp);
}

static void (*reporter)(void *, const hpgl_report_t *);
static void *reporter_user;

void hpgl_set_reporter(void (*fn)(void *user, const hpgl_report_t *r), void *user)
{
	reporter = fn;
	reporter_user = user;
}

void hpgl_dev_report(const hpgl_report_t *r)
{
	if (reporter)
		reporter(reporter_user, r);
}

void hpgl_dev_warn(int *flag, const char *msg)
{
	if (!*flag && reporter) {
		hpgl_report_t *r = calloc(1, sizeof *r);
		if (r) {
			r->warning = msg;
			reporter(reporter_user, r);
			free(r);
		}
	}
	*flag = 1;
}

int hpgl_dev_emit_fail(dev_device_t *d)
{
	hpgl_dev_t *h = d->priv;
	const char *e = hpgl_emit_error(h->em);
	return dev_fail(d, META_EIO, "%s", e[0] ? e : "hpgl: out of memory");
}
