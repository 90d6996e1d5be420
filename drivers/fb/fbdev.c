/* fbdev.c: a picture onto a Linux framebuffer node: screen info ioctls, mmap, colour map. */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <linux/fb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <time.h>
#include <unistd.h>
#include "fb/fbdev.h"

struct fbdev {
	char path[256];
	int fd;
	struct fb_var_screeninfo var;
	struct fb_fix_screeninfo fix;
	fbdev_info_t info;
	uint8_t *mem;
	size_t memlen;
	size_t start;                /* byte offset of the visible screen's top left pixel */
	uint8_t *saved;              /* the visible rows as they were */
	size_t savedlen;
	uint16_t cmap_saved[3][256];
	int have_cmap;               /* 1 if the colour map was read at open */
	int cmap_changed;
	int guarded;                 /* fbdev_guard(): the signals below are caught */
	struct sigaction old[3];     /* their actions before */
	int installed[3];
};

static const int guard_sig[3] = { SIGINT, SIGTERM, SIGHUP };
static volatile sig_atomic_t guard_caught;

static void on_guard(int sig)
{
	guard_caught = sig;          /* only noted: fbdev_hold() restores, then ends the program */
}

fbdev_t *fbdev_open(const char *path, char *err, size_t errlen)
{
	fbdev_t *fb = calloc(1, sizeof *fb);
	if (!fb) {
		snprintf(err, errlen, "%s: out of memory", path);
		return NULL;
	}
	snprintf(fb->path, sizeof fb->path, "%s", path);
	fb->fd = open(path, O_RDWR | O_CLOEXEC);
	if (fb->fd < 0) {
		snprintf(err, errlen, "%s: cannot open framebuffer: %s", path, strerror(errno));
		free(fb);
		return NULL;
	}
	if (ioctl(fb->fd, FBIOGET_VSCREENINFO, &fb->var) < 0 || ioctl(fb->fd, FBIOGET_FSCREENINFO, &fb->fix) < 0) {
		snprintf(err, errlen, "%s: not a framebuffer device (FBIOGET_VSCREENINFO: %s)", path, strerror(errno));
		goto fail;
	}
	fbdev_info_t *in = &fb->info;
	in->width = fb->var.xres, in->height = fb->var.yres, in->bits = fb->var.bits_per_pixel;
	in->pseudo = fb->fix.visual == FB_VISUAL_PSEUDOCOLOR;
	in->pixel_aspect = 1;
	if (fb->var.width > 0 && fb->var.height > 0 && fb->var.width != ~0u && fb->var.height != ~0u && in->width && in->height)
		in->pixel_aspect = ((double)fb->var.width / in->width) / ((double)fb->var.height / in->height);
	if (fb->fix.type != FB_TYPE_PACKED_PIXELS) {
		snprintf(err, errlen, "%s: framebuffer type %u is not packed pixels", path, fb->fix.type);
		goto fail;
	}
	if (in->pseudo ? in->bits != 8 : !(fb->fix.visual == FB_VISUAL_TRUECOLOR &&
			(in->bits == 16 || in->bits == 24 || in->bits == 32))) {
		snprintf(err, errlen, "%s: %u bits per pixel with visual %u: only 8-bit pseudo-colour and "
			"16/24/32-bit true colour are supported", path, in->bits, fb->fix.visual);
		goto fail;
	}
	if (in->width == 0 || in->height == 0 || fb->fix.line_length < in->width * (in->bits / 8)) {
		snprintf(err, errlen, "%s: bad geometry %ux%u, line_length %u", path, in->width, in->height, fb->fix.line_length);
		goto fail;
	}
	fb->start = (size_t)fb->var.yoffset * fb->fix.line_length + (size_t)fb->var.xoffset * (in->bits / 8);
	fb->savedlen = (size_t)in->height * fb->fix.line_length;
	fb->memlen = fb->fix.smem_len;
	if (fb->start + fb->savedlen > fb->memlen) {
		snprintf(err, errlen, "%s: the visible screen (%zu bytes at %zu) exceeds the video memory (%zu bytes)",
			path, fb->savedlen, fb->start, fb->memlen);
		goto fail;
	}
	fb->mem = mmap(NULL, fb->memlen, PROT_READ | PROT_WRITE, MAP_SHARED, fb->fd, 0);
	if (fb->mem == MAP_FAILED) {
		fb->mem = NULL;
		snprintf(err, errlen, "%s: cannot map the video memory: %s", path, strerror(errno));
		goto fail;
	}
	fb->saved = malloc(fb->savedlen);
	if (!fb->saved) {
		snprintf(err, errlen, "%s: out of memory", path);
		goto fail;
	}
	memcpy(fb->saved, fb->mem + fb->start, fb->savedlen);
	if (in->pseudo) {
		struct fb_cmap cm = { 0, 256, fb->cmap_saved[0], fb->cmap_saved[1], fb->cmap_saved[2], NULL };
		fb->have_cmap = ioctl(fb->fd, FBIOGETCMAP, &cm) == 0;
	}
	return fb;
fail:
	fbdev_close(fb);
	return NULL;
}

const fbdev_info_t *fbdev_info(const fbdev_t *fb)
{
	return &fb->info;
}

/* A true-colour pixel from 8-bit channels through the var-info bit fields. */
static uint32_t pack(const struct fb_var_screeninfo *v, const uint8_t *c)
{
	const struct fb_bitfield *f[3] = { &v->red, &v->green, &v->blue };
	uint32_t px = 0;
	for (int k = 0; k < 3; k++) {
		unsigned len = f[k]->length > 8 ? 8 : f[k]->length;
		uint32_t x = len ? (uint32_t)c[k] >> (8 - len) : 0;
		if (f[k]->length > 8)    /* wider fields: replicate the top bits */
			x = x << (f[k]->length - 8) | x >> (16 - f[k]->length);
		px |= x << f[k]->offset;
	}
	return px;
}

int fbdev_show(fbdev_t *fb, const uint8_t *idx, const quant_palette_t *pal, const uint8_t *rgb,
		unsigned w, unsigned h, char *err, size_t errlen)
{
	const fbdev_info_t *in = &fb->info;
	unsigned cw = w < in->width ? w : in->width, ch = h < in->height ? h : in->height;
	unsigned bpp = in->bits / 8;
	if (in->pseudo) {
		uint16_t r[256], g[256], b[256];
		unsigned n = pal->n;
		for (unsigned k = 0; k < n; k++) {
			unsigned top = pal->bits == 8 ? 255 : 63;
			r[k] = (uint16_t)(pal->dac[k][0] * 65535u / top);
			g[k] = (uint16_t)(pal->dac[k][1] * 65535u / top);
			b[k] = (uint16_t)(pal->dac[k][2] * 65535u / top);
		}
		struct fb_cmap cm = { 0, n, r, g, b, NULL };
		if (ioctl(fb->fd, FBIOPUTCMAP, &cm) < 0) {
			snprintf(err, errlen, "%s: FBIOPUTCMAP: %s", fb->path, strerror(errno));
			return -1;
		}
		fb->cmap_changed = 1;
	}
	for (unsigned y = 0; y < ch; y++) {
		uint8_t *dst = fb->mem + fb->start + (size_t)y * fb->fix.line_length;
		for (unsigned x = 0; x < cw; x++, dst += bpp) {
			size_t k = (size_t)y * w + x;
			if (in->pseudo) {
				*dst = idx[k];
				continue;
			}
			uint32_t px = pack(&fb->var, rgb + 3 * k);
			for (unsigned i = 0; i < bpp; i++)   /* the screen's byte order is the host's */
				dst[i] = (uint8_t)(px >> (8 * i));
		}
	}
	if (msync(fb->mem, fb->memlen, MS_SYNC) < 0 && errno != EINVAL && errno != ENOMEM) {
		snprintf(err, errlen, "%s: msync: %s", fb->path, strerror(errno));
		return -1;
	}
	return 0;
}

int fbdev_restore(fbdev_t *fb, char *err, size_t errlen)
{
	memcpy(fb->mem + fb->start, fb->saved, fb->savedlen);
	msync(fb->mem, fb->memlen, MS_SYNC);
	if (fb->cmap_changed && fb->have_cmap) {
		struct fb_cmap cm = { 0, 256, fb->cmap_saved[0], fb->cmap_saved[1], fb->cmap_saved[2], NULL };
		if (ioctl(fb->fd, FBIOPUTCMAP, &cm) < 0) {
			snprintf(err, errlen, "%s: FBIOPUTCMAP (restoring the colour map): %s", fb->path, strerror(errno));
			return -1;
		}
		fb->cmap_changed = 0;
	}
	return 0;
}

void fbdev_guard(fbdev_t *fb)
{
	if (fb->guarded)
		return;
	guard_caught = 0;
	for (int k = 0; k < 3; k++) {
		struct sigaction sa;
		fb->installed[k] = 0;
		if (sigaction(guard_sig[k], NULL, &fb->old[k]) < 0)
			continue;
		if (!(fb->old[k].sa_flags & SA_SIGINFO) && fb->old[k].sa_handler == SIG_IGN)
			continue;            /* ignored (nohup): stays ignored */
		memset(&sa, 0, sizeof sa);
		sa.sa_handler = on_guard;
		sigemptyset(&sa.sa_mask);
		fb->installed[k] = sigaction(guard_sig[k], &sa, NULL) == 0;
	}
	fb->guarded = 1;
}

int fbdev_hold(fbdev_t *fb, double seconds, char *err, size_t errlen)
{
	struct timespec t0, now;
	clock_gettime(CLOCK_MONOTONIC, &t0);
	/* short naps, so that a signal taken by another thread of the program ends the wait too */
	while (!guard_caught) {
		clock_gettime(CLOCK_MONOTONIC, &now);
		double left = seconds - ((double)(now.tv_sec - t0.tv_sec) + (double)(now.tv_nsec - t0.tv_nsec) * 1e-9);
		if (left <= 0)
			break;
		double nap = left < 0.05 ? left : 0.05;
		struct timespec ts = { 0, (long)(nap * 1e9) };
		nanosleep(&ts, NULL);
	}
	int rc = fbdev_restore(fb, err, errlen);
	int sig = guard_caught;
	if (fb->guarded) {
		for (int k = 0; k < 3; k++)
			if (fb->installed[k])
				sigaction(guard_sig[k], &fb->old[k], NULL);
		fb->guarded = 0;
	}
	if (sig) {
		guard_caught = 0;
		raise(sig);              /* its old action: default (ends the program) or the program's */
	}
	return rc;
}

void fbdev_close(fbdev_t *fb)
{
	if (!fb)
		return;
	if (fb->mem)
		munmap(fb->mem, fb->memlen);
	if (fb->fd >= 0)
		close(fb->fd);
	free(fb->saved);
	free(fb);
}
