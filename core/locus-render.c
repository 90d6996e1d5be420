/* locus-render.c: render a scene file into a meta file (ray tracing, octree, contours, Voronoi, wireframes). */
#include "scene.h"
#include "transport.h"
#include "run.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define EX_USAGE 64
#define EX_DATAERR 65
#define EX_NOINPUT 66
#define EX_SOFTWARE 70
#define EX_IOERR 74

static const char usage[] =
	"usage: locus-render SCENE [-o OUT] [--binary] [--threads N] [--quiet] [--stats]\n"
	"Render the scene file SCENE ('-' = stdin) into a Locus meta file.\n"
	"  -o OUT       write OUT ('-' = stdout, the default) via a temporary file and rename\n"
	"  --binary     write the binary meta encoding (default: text)\n"
	"  --threads N  worker threads (default: all CPUs); the output does not depend on N\n"
	"  --quiet      no progress bar and no warnings\n"
	"  --stats      print one line of costs on stderr: pixels, distance evaluations\n"
	"               (per pixel, per ray kind), octree cells, times in milliseconds\n"
	"  --help, --version\n"
	"Exit status: 0 ok, 64 usage, 65 bad scene, 66 scene unreadable, 70 internal, 74 I/O.\n"
	"The scene language is described in docs/scene-language.md.\n";

static int write_cb(void *user, const void *buf, size_t n)
{
	return io_write(user, buf, n);
}

static void progress(void *user, unsigned done, unsigned total)
{
	(void)user;
	int width = 40, k = total ? (int)((double)done * width / total) : width;
	fprintf(stderr, "\rlocus-render [%.*s%*s] %3u%%", k, "########################################",
	        width - k, "", total ? done * 100 / total : 100);
	if (done >= total)
		fputc('\n', stderr);
	fflush(stderr);
}

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + ts.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
	const char *in = NULL, *out = "-";
	int binary = 0, quiet = 0, stats = 0;
	long threads = 0;
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i];
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			fputs(usage, stdout);
			return 0;
		} else if (!strcmp(a, "--version")) {
			printf("locus-render %s\n", LOCUS_VERSION);
			return 0;
		} else if (!strcmp(a, "-o") && i + 1 < argc) {
			out = argv[++i];
		} else if (!strcmp(a, "--binary")) {
			binary = 1;
		} else if (!strcmp(a, "--quiet")) {
			quiet = 1;
		} else if (!strcmp(a, "--stats")) {
			stats = 1;
		} else if (!strcmp(a, "--threads") && i + 1 < argc) {
			char *end;
			threads = strtol(argv[++i], &end, 10);
			if (*end || threads < 1 || threads > 64) {
				fprintf(stderr, "locus-render: --threads expects 1..64, found '%s'\n", argv[i]);
				return EX_USAGE;
			}
		} else if (a[0] == '-' && a[1]) {
			fprintf(stderr, "locus-render: unknown option '%s' (try --help)\n", a);
			return EX_USAGE;
		} else if (!in) {
			in = a;
		} else {
			fprintf(stderr, "locus-render: one scene file expected, found a second: '%s'\n", a);
			return EX_USAGE;
		}
	}
	if (!in) {
		fputs(usage, stderr);
		return EX_USAGE;
	}
	double t_start = now();
	char err[1024];
	scene_t *sc;
	int rc = scene_load(in, &sc, err, sizeof err);
	if (rc < 0) {
		fprintf(stderr, "%s\n", err);
		/* memory running out while opening or parsing is 70, whatever scene_load returned:
		 * core/expr.c reports it as "expected memory for the expression" (code -1) */
		if (rc == SCENE_ENOMEM || dev_err_is_oom(err) || strstr(err, ": expected memory for "))
			return EX_SOFTWARE;
		return rc == -2 ? EX_NOINPUT : EX_DATAERR;
	}
	if (!quiet)
		for (size_t i = 0; i < sc->nwarnings; i++)
			fprintf(stderr, "%s\n", sc->warnings[i]);
	size_t nw0 = sc->nwarnings;

	/* a file via a new temporary renamed on success; a device or a pipe (e.g. /dev/null)
	 * written in place, never replaced (drivers/transport.h) */
	io_transport_t *f = io_open_write(out, err, sizeof err);
	if (!f) {
		fprintf(stderr, "%s\n", err);
		scene_free(sc);
		return dev_err_is_oom(err) ? EX_SOFTWARE : EX_IOERR;
	}
	meta_writer_t *w = meta_writer_new(write_cb, f, binary ? META_ENC_BINARY : META_ENC_TEXT);
	scene_opts_t o = {(unsigned)threads, NULL, NULL};
	if (!quiet && isatty(2))
		o.progress = progress;
	scene_stats_t st;
	int status = 0;
	if (!w) {
		fprintf(stderr, "locus-render: out of memory\n");
		status = EX_SOFTWARE;
	} else if ((rc = scene_render(sc, w, &o, &st, err, sizeof err)) < 0) {
		fprintf(stderr, "%s\n", io_failed(f) ? io_error(f) : err);
		status = io_failed(f) ? (dev_err_is_oom(io_error(f)) ? EX_SOFTWARE : EX_IOERR)
			: rc == SCENE_ENOMEM ? EX_SOFTWARE : EX_DATAERR;
	}
	if (w && meta_writer_close(w) < 0 && !status) {
		fprintf(stderr, "%s\n", io_failed(f) ? io_error(f) : "locus-render: write error");
		status = io_failed(f) && dev_err_is_oom(io_error(f)) ? EX_SOFTWARE : EX_IOERR;
	}
	if (io_close_err(f, status ? IO_ABORT : IO_COMMIT, err, sizeof err) < 0 && !status) {
		fprintf(stderr, "%s\n", err);
		status = dev_err_is_oom(err) ? EX_SOFTWARE : EX_IOERR;
	}
	if (!status && !quiet)
		for (size_t i = nw0; i < sc->nwarnings; i++)
			fprintf(stderr, "%s\n", sc->warnings[i]);
	if (!status && stats) {
		double total = now() - t_start;
		double px = st.pixels ? st.pixels : 1;
		fprintf(stderr, "stats: pixels=%u evals=%llu evals_per_pixel=%.3f primary=%.3f shadow=%.3f normal=%.3f"
		        " aa_pixels=%llu lane_evals=%llu oct_visited=%llu oct_leaves=%llu wire_segments=%llu"
		        " trace_ms=%.3f total_ms=%.3f",
		        st.pixels, (unsigned long long)st.rt.evals, st.rt.evals / px, st.rt.primary_evals / px,
		        st.rt.shadow_evals / px, st.rt.normal_evals / px, (unsigned long long)st.rt.aa_pixels,
		        (unsigned long long)st.rt.lane_evals, (unsigned long long)st.oct_visited,
		        (unsigned long long)st.oct_leaves, (unsigned long long)st.wire_segments,
		        st.seconds_trace * 1e3, total * 1e3);
		if (st.oct_cubical_visited)
			fprintf(stderr, " oct_cubical_visited=%llu oct_cubical_leaves=%llu oct_cubical_ms=%.3f",
			        (unsigned long long)st.oct_cubical_visited, (unsigned long long)st.oct_cubical_leaves,
			        st.seconds_cubical * 1e3);
		fputc('\n', stderr);
	}
	scene_free(sc);
	return status;
}
