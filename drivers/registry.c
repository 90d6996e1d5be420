/* registry.c: the list of devices locus-play knows; add one line per new device. */
#include <string.h>
#include "device.h"

extern const dev_ops_t dev_png_ops, dev_ppm_ops, dev_rle_ops, dev_null_ops;
extern const dev_ops_t dev_hpgl_ops;

const dev_ops_t *const dev_registry[] = {
	&dev_png_ops,
	&dev_ppm_ops,
	&dev_rle_ops,
	&dev_null_ops,
	&dev_hpgl_ops,
	NULL
};

const dev_ops_t *dev_find(const char *name)
{
	for (size_t k = 0; dev_registry[k]; k++)
		if (strcmp(dev_registry[k]->name, name) == 0)
			return dev_registry[k];
	if (strcmp(name, "raster") == 0)
		return &dev_png_ops;
	return NULL;
}
