/* options.c: device options given as "key=value,key=value" (-O), looked up and checked. */
#include <stdio.h>
#include <string.h>
#include "device/device.h"

/* Find key in opts: pointer to its value and its length, or NULL. */
static const char *find(const char *opts, const char *key, size_t *len)
{
	size_t klen = strlen(key);
	for (const char *p = opts; p && *p;) {
		const char *end = strchr(p, ',');
		size_t n = end ? (size_t)(end - p) : strlen(p);
		if (n > klen && strncmp(p, key, klen) == 0 && p[klen] == '=') {
			*len = n - klen - 1;
			return p + klen + 1;
		}
		p += n + (end != NULL);
	}
	return NULL;
}

const char *dev_option(const dev_device_t *d, const char *key, char *buf, size_t n)
{
	size_t len;
	const char *v = find(d->options, key, &len);
	if (!v || len + 1 > n)
		return NULL;
	memcpy(buf, v, len);
	buf[len] = 0;
	return buf;
}

int dev_check_options(dev_device_t *d)
{
	for (const char *p = d->options; p && *p;) {
		const char *end = strchr(p, ',');
		size_t n = end ? (size_t)(end - p) : strlen(p);
		const char *eq = memchr(p, '=', n);
		size_t klen = eq ? (size_t)(eq - p) : n;
		int known = 0;
		for (const dev_option_t *o = d->ops->option_list; o && o->key && !known; o++)
			known = strlen(o->key) == klen && strncmp(o->key, p, klen) == 0;
		if (!known || !eq) {
			char list[256] = "";
			size_t used = 0;
			for (const dev_option_t *o = d->ops->option_list; o && o->key; o++) {
				int w = snprintf(list + used, sizeof list - used, "%s%s", used ? ", " : "", o->key);
				if (w < 0 || (size_t)w >= sizeof list - used)
					break;
				used += (size_t)w;
			}
			if (!eq && known)
				return dev_fail(d, DEV_EUSAGE, "device option '%.*s' needs a value (key=value)", (int)klen, p);
			return dev_fail(d, DEV_EUSAGE, "unknown option '%.*s' for device %s (%s%s)", (int)klen, p,
				d->ops->name, used ? "it takes: " : "it takes no options", list);
		}
		p += n + (end != NULL);
	}
	return 0;
}
