/* fbmode.h: the display modes of the VGA and XGA devices and the device code they share.
 *
 * dev_vga.c and dev_xga.c each give a table of modes; everything else (options, the page
 * buffer, palette and dithering, the output formats and the Linux framebuffer) is here, so
 * the two devices behave alike. Device options (-O key=value): mode, format, palette, quant,
 * dither, fit, letterbox, fb, hold; see fbm_options and docs/framebuffer.md.
 */
#ifndef LOCUS_FBMODE_H
#define LOCUS_FBMODE_H

#include <stdio.h>
#include "device/device.h"

/* One display mode. */
typedef struct {
	const char *name;            /* "13h", "1024x768x256" ... */
	const char *alias;           /* another accepted name, or NULL */
	unsigned width, height;
	unsigned colours;            /* 16, 256, or 65536 (direct) */
	double pixel_aspect;         /* width / height of a pixel on a 4:3 screen */
	int layout;                  /* FBOUT_LINEAR8 / PLANAR4 / DIRECT565 */
	const char *description;     /* one line */
} fbm_mode_t;

/* A device's modes: the first is the default. */
typedef struct {
	const fbm_mode_t *modes;
	size_t n;
} fbm_modes_t;

/* The -O keys the framebuffer devices accept. */
extern const dev_option_t fbm_options[];
/* Private state bytes for dev_ops_t.priv_size (fbmode.c checks that its state fits). */
#define FBM_PRIV_SIZE 2048

/* The mode called name (or its alias) among the list, or NULL. */
const fbm_mode_t *fbm_find_mode(const fbm_modes_t *ml, const char *name);
/* One line describing a mode (for --list-modes), without the newline. */
void fbm_describe(const fbm_mode_t *m, char *buf, size_t n);

/* The device operations, given the device's mode list (dev_vga.c, dev_xga.c wrap them). */
int fbm_open(dev_device_t *d, const fbm_modes_t *ml);
int fbm_begin_page(dev_device_t *d, const dev_page_t *pg);
int fbm_write_band(dev_device_t *d, const render_band_t *b);
int fbm_end_page(dev_device_t *d, const dev_page_t *pg);
int fbm_close(dev_device_t *d);

/* The operations every framebuffer device shares (all but name, description and open). */
#define FBM_OPS_COMMON \
	.extension = ".png", .caps = DEV_CAP_RASTER, .colours = 256, .option_list = fbm_options, \
	.priv_size = FBM_PRIV_SIZE, .begin_page = fbm_begin_page, .write_band = fbm_write_band, \
	.end_page = fbm_end_page, .close = fbm_close

/* Define a framebuffer device from its table of modes `static const fbm_mode_t NAME_modes[]`
 * (dev_vga.c, dev_xga.c): the mode list NAME_mode_list, an open() that gives fbm_open() that
 * list, and the operations dev_NAME_ops registered as device "NAME". */
#define FBM_DEVICE(NAME, DESCRIPTION) \
	const fbm_modes_t NAME##_mode_list = { NAME##_modes, sizeof NAME##_modes / sizeof NAME##_modes[0] }; \
	static int NAME##_open(dev_device_t *d) { return fbm_open(d, &NAME##_mode_list); } \
	const dev_ops_t dev_##NAME##_ops = { .name = #NAME, .description = DESCRIPTION, .open = NAME##_open, \
		FBM_OPS_COMMON }

/* The two devices and their modes (dev_vga.c, dev_xga.c). */
extern const dev_ops_t dev_vga_ops, dev_xga_ops;
extern const fbm_modes_t vga_mode_list, xga_mode_list;

#endif
