/* hpgl_read_util.c: the HP-GL reader's messages and user-unit scaling, shared by the
 * parser (hpgl_read.c), the attributes (hpgl_read_attr.c) and the drawing (hpgl_read_draw.c). */
#include <stdarg.h>
#include <stdio.h>
#include "hpgl/read/hpgl_read_int.h"

int hpgl_rd_fail(hpgl_rd_t *r, size_t off, const char *fmt, ...)
{
	char m[256];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(m, sizeof m, fmt, ap);
	va_end(ap);
	snprintf(r->err, r->errlen, "%s: byte %zu: %s", r->name, off, m);
	r->fail_off = off;
	snprintf(r->fail_msg, sizeof r->fail_msg, "%.150s", m);
	return -1;
}

void hpgl_rd_warn(hpgl_rd_t *r, size_t off, const char *fmt, ...)
{
	hpgl_doc_t *d = r->doc;
	if (d->nwarns >= HPGL_MAX_WARNS || hpgl_rd_grow((void **)&d->warns, &d->capwarns, d->nwarns + 1, sizeof *d->warns)) {
		d->nwarns_more++;
		return;
	}
	char m[160];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(m, sizeof m, fmt, ap);
	va_end(ap);
	hpgl_rwarn_t *w = &d->warns[d->nwarns++];
	w->offset = off;
	snprintf(w->msg, sizeof w->msg, "%.200s: byte %zu: %s", r->name, off, m);
}

int hpgl_rd_nomem(hpgl_rd_t *r)
{
	r->nomem = 1;
	return hpgl_rd_fail(r, r->i, "out of memory");
}

/* User units to plotter units (SC in force). */
void hpgl_rd_user_to_pu(const hpgl_rd_t *r, double u, double v, double *x, double *y)
{
	if (r->sc) {
		*x = r->ox + (u - r->sc_xmin) * r->sx;
		*y = r->oy + (v - r->sc_ymin) * r->sy;
	} else {
		*x = u;
		*y = v;
	}
}

void hpgl_rd_user_len(const hpgl_rd_t *r, double u, double v, double *x, double *y)
{
	*x = r->sc ? u * r->sx : u;
	*y = r->sc ? v * r->sy : v;
}
