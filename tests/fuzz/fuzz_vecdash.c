/* fuzz_vecdash.c: libFuzzer harness of the vector devices' output bound: a meta file replayed
 * through SVG, HP-GL and PDF writes at most BOUND_BASE + BOUND_PER_BYTE bytes per input byte,
 * whatever its dash pattern and however far its lines run off the page (dash pieces are made
 * only where the page shows them). Inputs with lines wider than 100 px are left out (a wide
 * dashed line near the page really shows a piece per period of its width), and so are pages
 * above 96x96 pixels and arcs, circles and text whose flattening alone is large (fuzz_work
 * without the dash term). */
#include <sys/stat.h>
#include <unistd.h>
#include "fuzz.h"
#include "device/device.h"
#include "io/transport.h"

#ifndef FUZZ_ENTRY
#define FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

#define MAX_PIXELS (96 * 96)
#define MAX_WORK 200000.0
#define BOUND_BASE 262144.0
#define BOUND_PER_BYTE 4096.0

extern const dev_ops_t dev_svg_ops, dev_hpgl_ops, dev_pdf_ops;

/* The widest line the input asks for, pixels. */
static double widest(const uint8_t *data, size_t size)
{
	meta_reader_t *r = meta_reader_mem(data, size, "in");
	meta_cmd_t c;
	double w = 0;
	if (!r)
		return 1e30;
	while (meta_read(r, &c) > 0)
		if (c.op == META_WIDTH && c.f[0] / 1000.0 > w)
			w = c.f[0] / 1000.0;
	meta_reader_free(r);
	return w;
}

/* Replay into path: dev_play's status; the output's size in *bytes (0 when refused). */
static int replay(const uint8_t *data, size_t size, const dev_ops_t *ops, const char *path, double *bytes)
{
	char err[600];
	meta_reader_t *r = meta_reader_mem(data, size, "in");
	io_transport_t *t = io_open_write(path, err, sizeof err);
	FUZZ_ASSERT(r && t, "cannot start: %s", err);
	dev_device_t *d = dev_new(ops, t);
	FUZZ_ASSERT(d, "out of memory at start");
	int rc = dev_play(r, d);
	if (rc < 0)
		FUZZ_ASSERT(fuzz_one_line(dev_error(d)), "error not one line: '%s'", dev_error(d));
	io_close_err(t, rc < 0 ? IO_ABORT : IO_COMMIT, err, sizeof err);
	dev_free(d);
	meta_reader_free(r);
	struct stat st;
	*bytes = rc >= 0 && stat(path, &st) == 0 ? (double)st.st_size : 0;
	return rc;
}

int FUZZ_ENTRY(const uint8_t *data, size_t size);
int FUZZ_ENTRY(const uint8_t *data, size_t size)
{
	static const dev_ops_t *const devs[] = { &dev_svg_ops, &dev_hpgl_ops, &dev_pdf_ops };
	double w;
	if (size > 65536 || (w = fuzz_work_dash(data, size, MAX_PIXELS, NULL, 0)) < 0 || w > MAX_WORK
		|| widest(data, size) > 100)
		return 0;
	char path[96];
	snprintf(path, sizeof path, "/tmp/locus-fuzz-vecdash-%ld.out", (long)getpid());
	for (size_t k = 0; k < sizeof devs / sizeof devs[0]; k++) {
		double bytes;
		replay(data, size, devs[k], path, &bytes);
		FUZZ_ASSERT(bytes <= BOUND_BASE + BOUND_PER_BYTE * (double)size,
			"%s wrote %.0f bytes for %zu input bytes (bound %.0f + %.0f per byte)", devs[k]->name, bytes, size,
			BOUND_BASE, BOUND_PER_BYTE);
	}
	unlink(path);
	return 0;
}
