/* dev_xga.c: the XGA device: 1024x768 with 256 colours, or 640x480 with 65,536 direct colours. */
#include "fb/fbmode.h"
#include "fb/fbout.h"

static const fbm_mode_t xga_modes[] = {
	{ "1024x768x256", "1024x768", 1024, 768, 256, 1.0, FBOUT_LINEAR8,
		"one byte per pixel, 256 of 262,144 colours (18-bit DAC)" },
	{ "640x480x565", "640x480", 640, 480, 65536, 1.0, FBOUT_DIRECT565,
		"direct colour, 16 bits per pixel 5-6-5, no palette" },
};

FBM_DEVICE(xga, "XGA framebuffer: 1024x768x256 or 640x480 5-6-5; dump, PNG, PCX, BMP, fbdev");
