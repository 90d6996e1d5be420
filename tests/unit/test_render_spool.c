/* test_render_spool.c: the band spool stops at its limit, and a failed spool write names the
 * spool and the cause, instead of growing without bound or failing with "device error". */
#include <signal.h>
#include <stdlib.h>
#include <sys/resource.h>
#include "render/render.h"
#include "unit.h"

static int band_count(void *user, const render_band_t *b)
{
	(*(unsigned *)user) += b->nrows;
	return 0;
}

/* Stroke n diagonal lines on a banded 200 x 200 page; the first error or 0. */
static int stroke_lines(render_t *r, int n)
{
	scan_path_t p;
	memset(&p, 0, sizeof p);
	scan_style_t st = { 1000, META_CAP_BUTT, META_JOIN_MITER, 4000, NULL, 0 };
	int rc = 0;
	for (int k = 0; k < n && rc == 0; k++) {
		scan_path_reset(&p);
		scan_path_move(&p, 1000 * (k % 200), 0);
		scan_path_draw(&p, 199000 - 1000 * (k % 200), 199000);
		rc = render_stroke(r, &p, &st, 0x102030);
	}
	scan_path_free(&p);
	return rc;
}

int main(void)
{
	char err[320];
	/* within the default limit: a banded page renders */
	render_t *r = render_new(200, 200, 10, 0, err, sizeof err);
	CHECK(r && render_bands(r) == 20, "200 rows in bands of 10: spooled");
	CHECK(r && stroke_lines(r, 100) == 0, "100 strokes spooled under the default limit");
	unsigned rows = 0;
	CHECK(r && render_finish(r, band_count, &rows) == 0 && rows == 200, "and replayed");
	render_free(r);

	/* a limit of 4 KiB: refused with a message naming the spool and the limit */
	r = render_new(200, 200, 10, 0, err, sizeof err);
	render_set_spool_limit(r, 4096);
	int rc = stroke_lines(r, 1000);
	CHECK(rc == META_EIO, "1000 strokes over a 4 KiB spool limit: META_EIO (%d)", rc);
	CHECK(strstr(render_error(r), "band spool (a temporary file in ") &&
		strstr(render_error(r), "limit of 4096 bytes (LOCUS_SPOOL_MAX_MB)"), "message: %s",
		render_error(r));
	CHECK(render_finish(r, band_count, &rows) == META_EIO, "finish after the failure fails too");
	render_free(r);

	/* the environment sets the default limit */
	setenv("LOCUS_SPOOL_MAX_MB", "3", 1);
	CHECK(render_spool_default() == 3u << 20, "LOCUS_SPOOL_MAX_MB=3: 3 MiB");
	setenv("LOCUS_SPOOL_MAX_MB", "x", 1);
	CHECK(render_spool_default() == DEV_SPOOL_MAX_DEFAULT, "LOCUS_SPOOL_MAX_MB=x: the default");
	unsetenv("LOCUS_SPOOL_MAX_MB");

	/* the file system refuses the writes (a file size limit, as a full disk would): the
	 * message names the spool and strerror's cause */
	struct rlimit old, lim;
	getrlimit(RLIMIT_FSIZE, &old);
	lim = old;
	lim.rlim_cur = 65536;
	signal(SIGXFSZ, SIG_IGN);
	r = render_new(200, 200, 10, 0, err, sizeof err);
	CHECK(r != NULL, "spool created");
	setrlimit(RLIMIT_FSIZE, &lim);
	rc = stroke_lines(r, 20000);
	if (rc == 0)
		rc = render_finish(r, band_count, &rows);
	setrlimit(RLIMIT_FSIZE, &old);
	CHECK(rc == META_EIO && strstr(render_error(r), "band spool (a temporary file in ") &&
		strstr(render_error(r), ": cannot write it: File too large"), "write refused: %s",
		render_error(r));
	render_free(r);

	/* a spool directory that does not exist */
	setenv("TMPDIR", "/nonexistent-locus-dir", 1);
	r = render_new(200, 200, 10, 0, err, sizeof err);
	CHECK(!r && strstr(err, "band spool (a temporary file in /nonexistent-locus-dir): cannot create it: No such file"),
		"missing spool directory: %s", err);
	render_free(r);
	unsetenv("TMPDIR");
	return UNIT_DONE();
}
