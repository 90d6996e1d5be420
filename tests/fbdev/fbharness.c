/* fbharness.c: a fake Linux framebuffer under umockdev for tests/t_fbdev.sh.
 *
 * usage: fbharness BPP XRES YRES WIDTH_MM HEIGHT_MM LINE_LENGTH OUT -- PROGRAM ARGS...
 *
 * Creates a umockdev testbed with a graphics device /dev/fb0 whose node file holds smem_len
 * bytes of the marker 0x5a (line_length * yres + 4096), answers the fbdev ioctls the program
 * makes (FBIOGET_VSCREENINFO, FBIOGET_FSCREENINFO, FBIOGETCMAP with a known grey colour map,
 * FBIOPUTCMAP recorded, FBIOPAN_DISPLAY and FBIOBLANK accepted, anything else ENOTTY), runs
 * PROGRAM under umockdev-wrapper, and afterwards writes OUT.mem (the node's bytes: what the
 * program wrote through its mmap), OUT.cmap (one line "index red green blue" per entry of the
 * last FBIOPUTCMAP, 16-bit values) and OUT.log (one line per ioctl). Screens: BPP 32 is
 * true colour with red at bit 0, green 8, blue 16 (the reverse of the usual order, so that a
 * program ignoring the bit fields shows); 24 is packed B, G, R bytes (red at bit 16); 16 is
 * 5-6-5; 8 is pseudo-colour.
 * With FBH_SIGNAL=INT|TERM in the environment, the harness sends that signal to the program
 * FBH_SIGNAL_MS milliseconds (default 300) after the program first changed the screen's top
 * row (an interrupt during --hold).
 * Exits with the program's status, 128 + the signal when a signal ended it (as a shell
 * reports it), or 70 when the harness itself fails.
 */
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <linux/fb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <signal.h>
#include <time.h>
#include <fcntl.h>
#include <umockdev.h>
#include <unistd.h>

static struct fb_var_screeninfo var;
static struct fb_fix_screeninfo fix;
static uint16_t last_cmap[3][256];
static unsigned last_start, last_len;
static int have_cmap;
static FILE *logfp;

static gboolean on_ioctl(UMockdevIoctlBase *base, UMockdevIoctlClient *client, gpointer user)
{
	(void)base;
	(void)user;
	gulong req = umockdev_ioctl_client_get_request(client);
	UMockdevIoctlData *arg = umockdev_ioctl_client_get_arg(client);
	GError *err = NULL;
	if (req == FBIOGET_VSCREENINFO || req == FBIOGET_FSCREENINFO) {
		int v = req == FBIOGET_VSCREENINFO;
		size_t n = v ? sizeof var : sizeof fix;
		UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0, n, &err);
		if (!d) {
			umockdev_ioctl_client_complete(client, -1, EFAULT);
			return TRUE;
		}
		memcpy(d->data, v ? (void *)&var : (void *)&fix, n);
		fprintf(logfp, "%s\n", v ? "FBIOGET_VSCREENINFO" : "FBIOGET_FSCREENINFO");
		umockdev_ioctl_client_complete(client, 0, 0);
		return TRUE;
	}
	if (req == FBIOPUTCMAP || req == FBIOGETCMAP) {
		int put = req == FBIOPUTCMAP;
		UMockdevIoctlData *cm = umockdev_ioctl_data_resolve(arg, 0, sizeof(struct fb_cmap), &err);
		if (!cm) {
			umockdev_ioctl_client_complete(client, -1, EFAULT);
			return TRUE;
		}
		struct fb_cmap c;
		memcpy(&c, cm->data, sizeof c);
		if (c.start + c.len > 256 || c.len == 0) {
			umockdev_ioctl_client_complete(client, -1, EINVAL);
			return TRUE;
		}
		size_t off[3] = { offsetof(struct fb_cmap, red), offsetof(struct fb_cmap, green), offsetof(struct fb_cmap, blue) };
		for (int k = 0; k < 3; k++) {
			UMockdevIoctlData *a = umockdev_ioctl_data_resolve(cm, off[k], c.len * sizeof(uint16_t), &err);
			if (!a) {
				umockdev_ioctl_client_complete(client, -1, EFAULT);
				return TRUE;
			}
			if (put) {
				memcpy(last_cmap[k] + c.start, a->data, c.len * sizeof(uint16_t));
			} else {
				uint16_t grey[256];
				for (unsigned i = 0; i < c.len; i++)
					grey[i] = (uint16_t)((c.start + i) * 257);   /* the console's map: a grey ramp */
				memcpy(a->data, grey, c.len * sizeof(uint16_t));
			}
		}
		if (put)
			last_start = c.start, last_len = c.len, have_cmap = 1;
		fprintf(logfp, "%s %u %u\n", put ? "FBIOPUTCMAP" : "FBIOGETCMAP", c.start, c.len);
		umockdev_ioctl_client_complete(client, 0, 0);
		return TRUE;
	}
	if (req == FBIOPAN_DISPLAY || req == FBIOBLANK) {
		fprintf(logfp, "%s\n", req == FBIOBLANK ? "FBIOBLANK" : "FBIOPAN_DISPLAY");
		umockdev_ioctl_client_complete(client, 0, 0);
		return TRUE;
	}
	fprintf(logfp, "ioctl 0x%lx refused\n", req);
	umockdev_ioctl_client_complete(client, -1, ENOTTY);
	return TRUE;
}

static void setup_screen(int bpp, unsigned xres, unsigned yres, unsigned wmm, unsigned hmm, unsigned ll)
{
	var.xres = var.xres_virtual = xres;
	var.yres = var.yres_virtual = yres;
	var.bits_per_pixel = (uint32_t)bpp;
	var.width = wmm, var.height = hmm;
	if (bpp == 32) {
		var.red = (struct fb_bitfield){ 0, 8, 0 };
		var.green = (struct fb_bitfield){ 8, 8, 0 };
		var.blue = (struct fb_bitfield){ 16, 8, 0 };
		var.transp = (struct fb_bitfield){ 24, 8, 0 };
	} else if (bpp == 24) {
		var.red = (struct fb_bitfield){ 16, 8, 0 };
		var.green = (struct fb_bitfield){ 8, 8, 0 };
		var.blue = (struct fb_bitfield){ 0, 8, 0 };
	} else if (bpp == 16) {
		var.red = (struct fb_bitfield){ 11, 5, 0 };
		var.green = (struct fb_bitfield){ 5, 6, 0 };
		var.blue = (struct fb_bitfield){ 0, 5, 0 };
	} else {
		var.red = var.green = var.blue = (struct fb_bitfield){ 0, 8, 0 };
	}
	snprintf(fix.id, sizeof fix.id, "locus-fake");
	fix.line_length = ll;
	fix.smem_len = ll * yres + 4096;
	fix.type = FB_TYPE_PACKED_PIXELS;
	fix.visual = bpp == 8 ? FB_VISUAL_PSEUDOCOLOR : FB_VISUAL_TRUECOLOR;
}

int main(int argc, char **argv)
{
	if (argc < 10 || strcmp(argv[8], "--") != 0) {
		fprintf(stderr, "usage: fbharness BPP XRES YRES WIDTH_MM HEIGHT_MM LINE_LENGTH OUT -- PROGRAM ARGS...\n");
		return 64;
	}
	setup_screen(atoi(argv[1]), (unsigned)atoi(argv[2]), (unsigned)atoi(argv[3]), (unsigned)atoi(argv[4]),
		(unsigned)atoi(argv[5]), (unsigned)atoi(argv[6]));
	const char *out = argv[7];
	char path[4096];
	snprintf(path, sizeof path, "%s.log", out);
	logfp = fopen(path, "w");
	if (!logfp)
		return 70;
	UMockdevTestbed *tb = umockdev_testbed_new();
	GError *err = NULL;
	if (!umockdev_testbed_add_from_string(tb,
			"P: /devices/platform/locusfb/graphics/fb0\nN: fb0=00\nE: DEVNAME=/dev/fb0\n"
			"E: SUBSYSTEM=graphics\nA: dev=29:0\n", &err)) {
		fprintf(stderr, "fbharness: %s\n", err->message);
		return 70;
	}
	char *root = umockdev_testbed_get_root_dir(tb);
	char node[4096];
	snprintf(node, sizeof node, "%s/dev/fb0", root);
	FILE *f = fopen(node, "wb");
	if (!f)
		return 70;
	for (size_t k = 0; k < fix.smem_len; k++)
		fputc(0x5a, f);
	fclose(f);
	UMockdevIoctlBase *handler = umockdev_ioctl_base_new();
	g_signal_connect(handler, "handle-ioctl", G_CALLBACK(on_ioctl), NULL);
	if (!umockdev_testbed_attach_ioctl(tb, "/dev/fb0", handler, &err)) {
		fprintf(stderr, "fbharness: %s\n", err->message);
		return 70;
	}
	pid_t pid = fork();
	if (pid == 0) {
		char **args = calloc((size_t)argc, sizeof *args);
		args[0] = "umockdev-wrapper";
		for (int k = 9; k < argc; k++)
			args[k - 8] = argv[k];
		execvp(args[0], args);
		_exit(127);
	}
	int status = 0;
	const char *sn = getenv("FBH_SIGNAL"), *sms = getenv("FBH_SIGNAL_MS");
	int sig = !sn ? 0 : !strcmp(sn, "INT") ? SIGINT : !strcmp(sn, "TERM") ? SIGTERM : 0;
	double delay = (sms ? atof(sms) : 300) / 1000, changed = -1;
	int nfd = sig ? open(node, O_RDONLY) : -1;
	unsigned char *top = malloc(fix.line_length ? fix.line_length : 1);
	while (waitpid(pid, &status, WNOHANG) == 0) {
		while (g_main_context_iteration(NULL, FALSE))
			;
		usleep(500);
		if (nfd < 0 || !top)
			continue;
		struct timespec ts;
		clock_gettime(CLOCK_MONOTONIC, &ts);
		double now = (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
		if (changed < 0 && pread(nfd, top, fix.line_length, 0) == (ssize_t)fix.line_length)
			for (unsigned k = 0; k < fix.line_length && changed < 0; k++)
				if (top[k] != 0x5a)
					changed = now;
		if (changed >= 0 && now - changed >= delay) {
			fprintf(logfp, "signal %s\n", sn);
			kill(pid, sig);
			close(nfd);
			nfd = -1;
		}
	}
	free(top);
	if (nfd >= 0)
		close(nfd);
	f = fopen(node, "rb");
	snprintf(path, sizeof path, "%s.mem", out);
	FILE *m = fopen(path, "wb");
	if (!f || !m)
		return 70;
	char buf[65536];
	size_t n;
	while ((n = fread(buf, 1, sizeof buf, f)) > 0)
		fwrite(buf, 1, n, m);
	fclose(f);
	fclose(m);
	snprintf(path, sizeof path, "%s.cmap", out);
	m = fopen(path, "w");
	if (!m)
		return 70;
	if (have_cmap)
		for (unsigned k = last_start; k < last_start + last_len; k++)
			fprintf(m, "%u %u %u %u\n", k, last_cmap[0][k], last_cmap[1][k], last_cmap[2][k]);
	fclose(m);
	fclose(logfp);
	umockdev_testbed_detach_ioctl(tb, "/dev/fb0", NULL);
	g_object_unref(handler);
	g_object_unref(tb);
	g_free(root);
	return WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 70;
}
