/* dev-vga.c: the VGA device: mode 13h (320x200, 256 colours) and mode 12h (640x480, 16 colours). */
#include "fbmode.h"
#include "fbout.h"

static const fbm_mode_t vga_modes[] = {
	{ "13h", "19", 320, 200, 256, 5.0 / 6.0, FBOUT_LINEAR8,
		"mode 19: linear 64,000 bytes at A000:0000, 256 of 262,144 colours (6-bit DAC)" },
	{ "12h", "18", 640, 480, 16, 1.0, FBOUT_PLANAR4,
		"mode 18: four bit planes of 38,400 bytes, 16 colours from the DAC" },
};

const fbm_modes_t vga_mode_list = { vga_modes, sizeof vga_modes / sizeof vga_modes[0] };

static int vga_open(dev_device_t *d)
{
	return fbm_open(d, &vga_mode_list);
}

const dev_ops_t dev_vga_ops = {
	.name = "vga", .description = "VGA framebuffer: mode 13h (320x200x256) or 12h (640x480x16); dump, PNG, PCX, BMP, fbdev",
	.extension = ".png", .caps = DEV_CAP_RASTER, .colours = 256, .option_list = fbm_options,
	.priv_size = FBM_PRIV_SIZE,
	.open = vga_open, .begin_page = fbm_begin_page, .write_band = fbm_write_band,
	.end_page = fbm_end_page, .close = fbm_close,
};
