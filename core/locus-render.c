/* locus-render.c: render a scene file into a meta file (ray tracing, octree, contours, Voronoi, wireframes). */
#include "mesh.h"
#include "scene.h"
#include "scene_lex.h"
#include "transport.h"
#include "run.h"

#include <errno.h>
#include <math.h>
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
	"usage: locus-render SCENE [-o OUT] [--binary] [--threads N] [--frames N|A-B] [--time-step DT]\n"
	"                    [--quiet] [--stats]\n"
	"Render the scene file SCENE ('-' = stdin) into a Locus meta file.\n"
	"  -o OUT       write OUT ('-' = stdout, the default) via a temporary file and rename;\n"
	"               OUT.stl, OUT.ply or OUT.obj: the drawn objects' triangle mesh instead\n"
	"               (binary STL, binary PLY, Wavefront OBJ; docs/mesh.md)\n"
	"  --binary     write the binary meta encoding (default: text)\n"
	"  --threads N  worker threads (default: all CPUs); the output does not depend on N\n"
	"  --frames N   an animation: frames 0..N-1 (or A-B: frames A..B), one set of pages\n"
	"               each, the scene parsed again for each with t = frame x DT\n"
	"  --time-step DT  the time between frames (default 1); without --frames t = 0\n"
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

/* One message line on stderr, control bytes escaped (a scene's text never reaches the terminal raw). */
static void say(const char *msg)
{
	char buf[2048];
	scene_escape(buf, sizeof buf, msg);
	fprintf(stderr, "%s\n", buf);
}

/* Sum the costs of one frame into the run's. */
static void add_stats(scene_stats_t *a, const scene_stats_t *b)
{
	a->rt.evals += b->rt.evals;
	a->rt.lane_evals += b->rt.lane_evals;
	a->rt.primary_evals += b->rt.primary_evals;
	a->rt.shadow_evals += b->rt.shadow_evals;
	a->rt.normal_evals += b->rt.normal_evals;
	a->rt.aa_evals += b->rt.aa_evals;
	a->rt.hits += b->rt.hits;
	a->rt.aa_pixels += b->rt.aa_pixels;
	a->oct_visited += b->oct_visited;
	a->oct_leaves += b->oct_leaves;
	a->oct_evals += b->oct_evals;
	a->oct_cubical_visited += b->oct_cubical_visited;
	a->oct_cubical_leaves += b->oct_cubical_leaves;
	a->seconds_cubical += b->seconds_cubical;
	a->wire_segments += b->wire_segments;
	a->contour_segments += b->contour_segments;
	a->seconds_trace += b->seconds_trace;
	a->pixels += b->pixels;
}

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* -o NAME.stl|.ply|.obj|.msh: the scene's mesh (.msh: its solid) in that format (docs/mesh.md); an exit status */
static int write_mesh(scene_t *sc, const char *out, int fmt, int stats, double t_start)
{
	mesh_t m;
	mesh_stats_t ms = {0, 0, 0, 0};
	char err[1024];
	mesh_init(&m);
	m.want_solid = fmt == MESH_MSH;   /* .msh: the solid's tetrahedra */
	int rc = mesh_scene(sc, &m, &ms, NULL, err, sizeof err), status = 0;
	if (rc < 0) {
		fprintf(stderr, "%s\n", err);
		mesh_free(&m);
		return rc == SCENE_ENOMEM ? EX_SOFTWARE : EX_DATAERR;
	}
	double t_mesh = now() - t_start;
	io_transport_t *f = io_open_write(out, err, sizeof err);
	if (!f) {
		fprintf(stderr, "%s\n", err);
		mesh_free(&m);
		return EX_IOERR;
	}
	if (mesh_write(&m, fmt, sc->name, write_cb, f, err, sizeof err) < 0) {
		fprintf(stderr, "%s\n", io_failed(f) ? io_error(f) : err);
		status = io_failed(f) ? EX_IOERR : EX_SOFTWARE;
	}
	if (io_close_err(f, status ? IO_ABORT : IO_COMMIT, err, sizeof err) < 0 && !status) {
		fprintf(stderr, "%s\n", err);
		status = EX_IOERR;
	}
	if (!status && stats) {
		double area, volume;
		mesh_measure(&m, &area, &volume);
		char solid[200] = "";
		mesh_solid_check_t sc_;
		if (m.ntet && mesh_solid_check(&m, &sc_) == 0)
			snprintf(solid, sizeof solid, " tetrahedra=%zu solid_volume=%.9g negative_tets=%zu flat_tets=%zu"
			         " inner_faces=%zu boundary_faces=%zu overused_faces=%zu", m.ntet, sc_.volume, sc_.negative,
			         sc_.flat, sc_.inner_faces, sc_.boundary_faces, sc_.overused_faces);
		fprintf(stderr, "stats: triangles=%zu vertices=%zu mesh_cells=%llu mesh_leaves=%llu evals=%llu"
		        " max_bracket=%.3g area=%.9g volume=%.9g%s mesh_ms=%.3f total_ms=%.3f\n", m.nt, m.nv,
		        (unsigned long long)ms.cells, (unsigned long long)ms.leaves, (unsigned long long)ms.evals,
		        ms.max_bracket, area, volume, solid, t_mesh * 1e3, (now() - t_start) * 1e3);
	}
	mesh_free(&m);
	return status;
}

int main(int argc, char **argv)
{
	const char *in = NULL, *out = "-";
	int binary = 0, quiet = 0, stats = 0;
	long threads = 0, frame0 = 0, frame1 = 0;
	double dt = 1;
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
		} else if (!strcmp(a, "--frames") && i + 1 < argc) {
			char *end;
			const char *v = argv[++i];
			long x = strtol(v, &end, 10), y;
			if (*end == '-' && end > v) {
				y = strtol(end + 1, &end, 10);
				if (*end || x < 0 || y < x || y > 9999999) {
					fprintf(stderr, "locus-render: --frames expects N or A-B with 0 <= A <= B, found '%s'\n", v);
					return EX_USAGE;
				}
				frame0 = x, frame1 = y;
			} else if (*end || x < 1 || x > 10000000) {
				fprintf(stderr, "locus-render: --frames expects N (1..10000000) or A-B, found '%s'\n", v);
				return EX_USAGE;
			} else {
				frame0 = 0, frame1 = x - 1;
			}
		} else if (!strcmp(a, "--time-step") && i + 1 < argc) {
			char *end;
			dt = strtod(argv[++i], &end);
			if (*end || !isfinite(dt) || end == argv[i]) {
				fprintf(stderr, "locus-render: --time-step expects a finite number, found '%s'\n", argv[i]);
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
	char *text;
	const char *name = strcmp(in, "-") ? in : "<stdin>";
	int rc = scene_read(in, &text, err, sizeof err);
	if (rc == 0 && (rc = scene_parse_frame(text, name, frame0 * dt, &sc, err, sizeof err)) < 0)
		free(text);
	if (rc < 0) {
		say(err);
		/* memory running out while opening or parsing is 70, whatever the parser returned:
		 * core/expr.c reports it as "expected memory for the expression" (code -1) */
		if (rc == SCENE_ENOMEM || dev_err_is_oom(err) || strstr(err, ": expected memory for "))
			return EX_SOFTWARE;
		return rc == -2 ? EX_NOINPUT : EX_DATAERR;
	}
	if (!quiet)
		for (size_t i = 0; i < sc->nwarnings; i++)
			say(sc->warnings[i]);
	size_t nw0 = sc->nwarnings;
	if (mesh_format_of(out) >= 0) {
		int status = write_mesh(sc, out, mesh_format_of(out), stats, t_start);
		scene_free(sc);
		free(text);
		return status;
	}

	/* a file via a new temporary renamed on success; a device or a pipe (e.g. /dev/null)
	 * written in place, never replaced (drivers/transport.h) */
	io_transport_t *f = io_open_write(out, err, sizeof err);
	if (!f) {
		say(err);
		scene_free(sc);
		free(text);
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
	} else {
		memset(&st, 0, sizeof st);
		/* frames are independent: each is the scene parsed at its t and rendered onto the
		 * same writer (its pages follow the previous frame's) */
		for (long fr = frame0; fr <= frame1 && !status; fr++) {
			scene_stats_t one;
			if (fr > frame0) {
				scene_t *next;
				if ((rc = scene_parse_frame(text, name, fr * dt, &next, err, sizeof err)) < 0) {
					say(err);
					status = rc == SCENE_ENOMEM || dev_err_is_oom(err) ? EX_SOFTWARE : EX_DATAERR;
					break;
				}
				scene_free(sc);
				sc = next;
			}
			if ((rc = scene_render(sc, w, &o, &one, err, sizeof err)) < 0) {
				say(io_failed(f) ? io_error(f) : err);
				status = io_failed(f) ? (dev_err_is_oom(io_error(f)) ? EX_SOFTWARE : EX_IOERR)
					: rc == SCENE_ENOMEM ? EX_SOFTWARE : EX_DATAERR;
				break;
			}
			add_stats(&st, &one);
			if (!quiet && frame1 > frame0) {
				if (fr > frame0 && sc->nwarnings)
					fprintf(stderr, "locus-render: frame %ld (t = %g):\n", fr, fr * dt);
				for (size_t i = fr > frame0 ? 0 : nw0; i < sc->nwarnings; i++)
					say(sc->warnings[i]);
			}
		}
	}
	if (w && meta_writer_close(w) < 0 && !status) {
		fprintf(stderr, "%s\n", io_failed(f) ? io_error(f) : "locus-render: write error");
		status = io_failed(f) && dev_err_is_oom(io_error(f)) ? EX_SOFTWARE : EX_IOERR;
	}
	if (io_close_err(f, status ? IO_ABORT : IO_COMMIT, err, sizeof err) < 0 && !status) {
		say(err);
		status = dev_err_is_oom(err) ? EX_SOFTWARE : EX_IOERR;
	}
	if (!status && !quiet && frame1 == frame0)
		for (size_t i = nw0; i < sc->nwarnings; i++)
			say(sc->warnings[i]);
	free(text);
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
