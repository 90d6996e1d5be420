/* import.c: `locus-meta import`: the input read whole, told HP-GL (import_hpgl.c) or a plotutils
 * metafile (plotmeta.c) by its content, and the meta file written all or nothing. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "import/meta_import.h"
#include "import/plotmeta.h"
#include "import/svg_import.h"
#include "io/transport.h"

static int out_write(void *user, const void *buf, size_t n)
{
	return io_write(user, buf, n);
}

int mimp_run(const char *in, const char *out, const char *pens)
{
	svgimp_opts_t o = { .tol_mm = 0.0125, .dpi = 96, .dedupe_mm = 0.05, .carousel = pens };
	return mimp_run_svg(in, out, pens, &o, 0, 0);
}

int mimp_run_strict(const char *in, const char *out, const char *pens, int strict)
{
	svgimp_opts_t o = { .tol_mm = 0.0125, .dpi = 96, .dedupe_mm = 0.05, .carousel = pens };
	return mimp_run_svg(in, out, pens, &o, 0, strict);
}

int mimp_run_svg(const char *in, const char *out, const char *pens, const svgimp_opts_t *svg, int svg_only,
		int strict)
{
	char err[700];
	io_transport_t *t = io_open_read(in, err, sizeof err);
	if (!t) {
		fprintf(stderr, "%s\n", err);
		return 66;
	}
	const char *name = strcmp(in, "-") ? in : "<stdin>";
	size_t cap = 1 << 16, n = 0;
	unsigned char *buf = malloc(cap);
	for (;;) {
		if (buf && n == cap) {
			unsigned char *q = realloc(buf, cap * 2);
			if (!q)
				free(buf);
			buf = q;
			cap *= 2;
		}
		if (!buf) {
			io_close(t, IO_ABORT);
			fprintf(stderr, "locus-meta: out of memory reading %s\n", name);
			return 70;
		}
		long k = io_read(t, buf + n, cap - n);
		if (k < 0) {
			fprintf(stderr, "%s\n", io_error(t));
			io_close(t, IO_ABORT);
			free(buf);
			return 74;
		}
		if (k == 0)
			break;
		n += (size_t)k;
	}
	io_close(t, IO_ABORT);
	io_transport_t *o = io_open_write(out ? out : "-", err, sizeof err);
	if (!o) {
		fprintf(stderr, "%s\n", err);
		free(buf);
		return 74;
	}
	meta_writer_t *w = meta_writer_new(out_write, o, META_ENC_TEXT);
	int rc = w ? 0 : -70;
	snprintf(err, sizeof err, "out of memory");
	if (w && svgimp_is(buf, n)) {
		rc = svgimp_import(buf, n, name, svg, w, err, sizeof err);
	} else if (w && svg_only) {
		snprintf(err, sizeof err, "locus-meta: %s is not SVG: --pens by-layer/by-colour, --pen, -O, --stats, --tolerance, --dpi and --profile are SVG's", name);
		rc = -64;
	} else if (w && plotmeta_is(buf, n) && pens) {
		snprintf(err, sizeof err, "locus-meta: --pens: %s is a plotutils metafile, which has no pens", name);
		rc = -64;
	} else if (w && plotmeta_is(buf, n))
		rc = plotmeta_import(buf, n, name, w, err, sizeof err);
	else if (w)
		rc = mimp_hpgl_read(buf, n, name, 4.0, pens, strict, stderr, w, err, sizeof err);
	free(buf);
	if (w) {
		int c = meta_writer_close(w);
		if (!rc && c < 0) {
			snprintf(err, sizeof err, "%s", io_failed(o) ? io_error(o) : "cannot finish the meta file");
			rc = -74;
		}
	}
	if (rc == -64) {   /* a bad --pens spec: err is "pens: ..." */
		char msg[sizeof err];
		snprintf(msg, sizeof msg, "%s", err);
		if (strncmp(msg, "locus-meta: ", 12))
			snprintf(err, sizeof err, "locus-meta: --%.680s", msg);
	}
	if (rc) {
		if (io_failed(o))
			snprintf(err, sizeof err, "%s", io_error(o));
		fprintf(stderr, "%s\n", err);
		io_close(o, IO_ABORT);   /* no partial output */
		return -rc;
	}
	if (io_close_err(o, IO_COMMIT, err, sizeof err)) {
		fprintf(stderr, "%s\n", err);
		return 74;
	}
	return 0;
}
