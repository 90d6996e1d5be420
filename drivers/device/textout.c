/* textout.c: formatted output for text-format drivers (PostScript, HP-GL, SVG): printf through
 * the device's transport, and numbers that never print as -0. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include "device/device.h"

int dev_printf(dev_device_t *d, const char *fmt, ...)
{
	char small[512];
	va_list ap;
	va_start(ap, fmt);
	int n = vsnprintf(small, sizeof small, fmt, ap);
	va_end(ap);
	if (n < 0)
		return dev_fail(d, DEV_EDEVICE, "%s: bad output format", d->ops->name);
	if (!d->out)
		return dev_fail(d, DEV_EDEVICE, "%s: no output", d->ops->name);
	const char *buf = small;
	char *big = NULL;
	if ((size_t)n >= sizeof small) {
		if (!(big = malloc((size_t)n + 1)))
			return dev_fail(d, META_ENOMEM, "out of memory");
		va_start(ap, fmt);
		vsnprintf(big, (size_t)n + 1, fmt, ap);
		va_end(ap);
		buf = big;
	}
	int rc = io_write(d->out, buf, (size_t)n);
	free(big);
	return rc ? dev_fail(d, dev_code_of_errno(io_errno(d->out)), "%s", io_error(d->out)) : 0;
}

const char *dev_fmt_fix(char *buf, int64_t v, int scale, int decimals)
{
	static const int64_t pow10[7] = { 1, 10, 100, 1000, 10000, 100000, 1000000 };
	if (scale < 0)
		scale = 0;
	if (scale > 6)
		scale = 6;
	if (decimals < 0)
		decimals = 0;
	if (decimals > scale)
		decimals = scale;
	/* round v / 10^scale to decimals places, halves away from zero, in integers */
	int64_t drop = pow10[scale - decimals];
	int neg = v < 0;
	uint64_t a = neg ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
	a = (a + (uint64_t)drop / 2) / (uint64_t)drop;
	uint64_t unit = (uint64_t)pow10[decimals], ip = a / unit, fp = a % unit;
	char *w = buf;
	if (neg && a != 0)
		*w++ = '-';   /* a value that rounds to zero prints as 0, never -0 */
	w += sprintf(w, "%llu", (unsigned long long)ip);
	if (fp) {
		char f[24];
		snprintf(f, sizeof f, "%0*llu", decimals, (unsigned long long)fp);
		int len = decimals;
		while (len > 0 && f[len - 1] == '0')
			len--;
		f[len] = 0;
		sprintf(w, ".%s", f);
	} else {
		*w = 0;
	}
	return buf;
}
