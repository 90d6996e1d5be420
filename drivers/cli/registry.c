/* registry.c: the list of devices locus-play knows; add one line per new device. */
#include <string.h>
#include "device/device.h"

extern const dev_ops_t dev_png_ops, dev_ppm_ops, dev_rle_ops, dev_null_ops;
extern const dev_ops_t dev_film_ops;
extern const dev_ops_t dev_vga_ops, dev_xga_ops;
extern const dev_ops_t dev_svg_ops;
extern const dev_ops_t dev_hpgl_ops;
extern const dev_ops_t dev_eps_ops, dev_ps_ops, dev_pdf_ops;

const dev_ops_t *const dev_registry[] = {
	&dev_png_ops,
	&dev_ppm_ops,
	&dev_rle_ops,
	&dev_null_ops,
	&dev_film_ops,
	&dev_vga_ops,
	&dev_xga_ops,
	&dev_svg_ops,
	&dev_hpgl_ops,
	&dev_eps_ops,
	&dev_ps_ops,
	&dev_pdf_ops,
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
