/* fbdev.h: showing a picture on a Linux framebuffer device (/dev/fbN) through ioctl and mmap.
 *
 * fbdev_open() asks the node for its variable and fixed screen information
 * (FBIOGET_VSCREENINFO, FBIOGET_FSCREENINFO), accepts 8-bit pseudo-colour and 16-, 24- and
 * 32-bit true colour (packed pixels), maps the whole video memory and keeps a copy of the
 * visible screen (and, for pseudo-colour, of the colour map) so that fbdev_restore() can put
 * back what the program changed. Pixels are written at the visible offset (xoffset, yoffset)
 * with the node's line_length as the row stride.
 */
#ifndef LOCUS_FBDEV_H
#define LOCUS_FBDEV_H

#include <stddef.h>
#include <stdint.h>
#include "quant/quant.h"

typedef struct fbdev fbdev_t;

/* What the screen is. */
typedef struct {
	unsigned width, height;      /* visible resolution */
	unsigned bits;               /* bits per pixel: 8, 16, 24 or 32 */
	int pseudo;                  /* 1: 8-bit palette (FB_VISUAL_PSEUDOCOLOR) */
	double pixel_aspect;         /* from the screen's size in mm when known, else 1 */
} fbdev_info_t;

/* Open and map the node. NULL with a one-line message in err (naming the node) when it cannot
 * be opened, is not a framebuffer, or has a pixel format this module does not write. */
fbdev_t *fbdev_open(const char *path, char *err, size_t errlen);
/* The screen's description. */
const fbdev_info_t *fbdev_info(const fbdev_t *fb);
/* Show a w x h picture at the top left of the screen (clipped to it). Pseudo-colour screens
 * take indices (idx) and the palette through FBIOPUTCMAP; true-colour screens take 8-bit RGB
 * (rgb, 3 bytes per pixel, row k at rgb + 3 * w * k). 0 or <0 with a message. */
int fbdev_show(fbdev_t *fb, const uint8_t *idx, const quant_palette_t *pal, const uint8_t *rgb,
		unsigned w, unsigned h, char *err, size_t errlen);
/* Put back the screen contents and colour map saved at open. 0 or <0 with a message. */
int fbdev_restore(fbdev_t *fb, char *err, size_t errlen);
/* Ctrl-C during --hold. fbdev_guard() (call it before fbdev_show) catches SIGINT, SIGTERM and
 * SIGHUP (those not ignored) from then on, only noting them. fbdev_hold() then waits seconds,
 * or until such a signal came (also one that came during the show), puts back the screen and
 * colour map (fbdev_restore), gives the signals their old actions back and, if one came,
 * raises it again, so the program ends as that signal ends it (exit status 128 + signal: 130
 * for Ctrl-C) with the screen as it was: the one way this module ends a program. 0, or <0
 * with a message when the restore failed. */
void fbdev_guard(fbdev_t *fb);
int fbdev_hold(fbdev_t *fb, double seconds, char *err, size_t errlen);
/* Unmap and close (does not restore). NULL is fine. */
void fbdev_close(fbdev_t *fb);

#endif
