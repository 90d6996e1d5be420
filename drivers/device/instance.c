/* instance.c: device instances (dev_new, dev_free) and their error (dev_fail, dev_error): the bottom
 * of device/, which options.c, fit.c, vecsupply.c and the replay loop in device.c call
 * and which calls none of them. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include "device/device.h"

#define DEFAULT_BUDGET ((size_t)64 << 20)

dev_device_t *dev_new(const dev_ops_t *ops, io_transport_t *out)
{
	dev_device_t *d = calloc(1, sizeof *d);
	if (!d)
		return NULL;
	d->ops = ops;
	d->out = out;
	d->mem_budget = DEFAULT_BUDGET;
	if (ops->priv_size && !(d->priv = calloc(1, ops->priv_size))) {
		free(d);
		return NULL;
	}
	return d;
}

void dev_free(dev_device_t *d)
{
	if (!d)
		return;
	free(d->priv);
	free(d);
}

int dev_fail(dev_device_t *d, int code, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(d->err, sizeof d->err, fmt, ap);
	va_end(ap);
	return code;
}

const char *dev_error(const dev_device_t *d)
{
	return d->err;
}

int dev_code_of_errno(int e)
{
	return e == ENOMEM ? META_ENOMEM : META_EIO;
}

unsigned dev_caps(const dev_device_t *d)
{
	return d->caps ? d->caps : d->ops->caps;
}
