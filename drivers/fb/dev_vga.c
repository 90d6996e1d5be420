/* dev_vga.c: the VGA device: mode 13h (320x200, 256 colours) and mode 12h (640x480, 16 colours). */
#include "fb/fbmode.h"
#include "fb/fbout.h"

static const fbm_mode_t vga_modes[] = {
	{ "13h", "19", 320, 200, 256, 5.0 / 6.0, FBOUT_LINEAR8,
		"mode 19: linear 64,000 bytes at A000:0000, 256 of 262,144 colours (6-bit DAC)" },
	{ "12h", "18", 640, 480, 16, 1.0, FBOUT_PLANAR4,
		"mode 18: four bit planes of 38,400 bytes, 16 colours from the DAC" },
};

FBM_DEVICE(vga, "VGA framebuffer: mode 13h (320x200x256) or 12h (640x480x16); dump, PNG, PCX, BMP, fbdev");
