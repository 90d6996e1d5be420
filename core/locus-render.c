/* locus-render.c: render a scene file into a meta file (ray tracing, octree, contours, Voronoi, wireframes). */
#include "mesh.h"
#include "scene.h"
#include "scene_lex.h"
#include "io/transport.h"
#include "meta_frames.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>
#include <unistd.h>

#define EX_USAGE 64
#define EX_DATAERR 65
#define EX_NOINPUT 66
#define EX_SOFTWARE 70
#define EX_IOERR 74

static const char usage[] =
	"usage: locus-render SCENE [-o OUT] [--binary] [--threads N] [--frames LIST] [--time-step DT]\n"
	"                    [--chunk K [--task I]] [--skip-existing] [--fail-fast] [--list-frames]\n"
	"                    [--quiet] [--stats]\n"
	"Render the scene file SCENE ('-' = stdin) into a Locus meta file.\n"
	"  -o OUT       write OUT ('-' = stdout, the default) via a temporary file and rename;\n"
	"               OUT.lmb: the binary encoding; OUT.stl, OUT.ply or OUT.obj: the drawn\n"
	"               objects' triangle mesh instead (binary STL, binary PLY, Wavefront OBJ;\n"
	"               docs/mesh.md). A frame pattern (NAME-%04d.meta, %d or %0Nd once, %% a\n"
	"               percent sign) writes one file per frame, each renamed into place whole\n"
	"  --binary     write the binary meta encoding (default: text, or binary for OUT.lmb)\n"
	"  --threads N  worker threads (default: all CPUs); the output does not depend on N\n"
	"  --frames LIST  an animation, frame k the scene parsed again at t = k x DT: N alone is\n"
	"               frames 0..N-1; else a comma list of A, A-B and A-BxS (every S-th of A..B)\n"
	"  --time-step DT  the time between frames (default 1); without --frames t = 0\n"
	"  --chunk K    render only chunk I of the LIST cut into chunks of K frames (the last one\n"
	"               may be shorter); I from --task I, else $SLURM_ARRAY_TASK_ID (0-based)\n"
	"  --skip-existing  with a frame pattern: leave a frame whose file is there and complete\n"
	"  --fail-fast  with a frame pattern: stop at the first frame that fails (default: go on,\n"
	"               name the failed frames at the end)\n"
	"  --list-frames  print the frames this run would render, one a line, and exit\n"
	"  --quiet      no progress bar, no warnings, no notes on skipped frames\n"
	"  --stats      print one line of costs on stderr: pixels, distance evaluations\n"
	"               (per pixel, per ray kind), octree cells, times in milliseconds\n"
	"  --help, --version\n"
	"Exit status: 0 ok, 64 usage, 65 bad scene, 66 scene unreadable, 70 internal, 74 I/O; with a\n"
	"frame pattern, that of the first frame that failed. docs/farm.md: frames on Slurm, GNU parallel.\n"
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


/* ---- Is a frame's file there and complete? ------------------------------------------------ */

/* 1 complete, 0 there but not complete (why says so), -1 not there */
static int meta_complete(const char *path, long fr, int binary, char *why, size_t n)
{
	meta_frames_t fs;
	char err[600];
	int rc = meta_frames_scan(path, &fs, err, sizeof err);
	if (rc == -66)
		return errno == ENOENT ? -1 : (snprintf(why, n, "%s", err), 0);
	if (rc) {
		snprintf(why, n, "%s", err);
		return 0;
	}
	int ok = fs.records && fs.n == 1 && fs.frames[0] == fr;
	if (!ok)
		snprintf(why, n, "%s: expected the records of frame %ld alone, found %s", path, fr,
			!fs.records ? "none" : fs.n > 1 ? "several frames" : "another frame");
	else if (fs.binary != binary)
		snprintf(why, n, "%s: in the %s encoding, not the %s one asked for", path,
			fs.binary ? "binary" : "text", binary ? "binary" : "text"), ok = 0;
	meta_frames_free(&fs);
	return ok;
}

static uint32_t le32(const unsigned char *b)
{
	return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

/* A mesh file as mesh_write writes it: STL 84 + 50 bytes a triangle; PLY its header then 12 bytes
 * a vertex and 13 a triangle; OBJ the vertices and triangles its first line counts; MSH ending
 * with $EndElements. 1 complete, 0 not (why), -1 not there. */
static int mesh_complete(const char *path, int fmt, char *why, size_t n)
{
	FILE *f = fopen(path, "rb");
	if (!f) {
		if (errno == ENOENT)
			return -1;
		snprintf(why, n, "%s: cannot open: %s", path, strerror(errno));
		return 0;
	}
	struct stat sb;
	int ok = 0;
	char line[512];
	if (fstat(fileno(f), &sb) || !S_ISREG(sb.st_mode)) {
		snprintf(why, n, "%s: not a regular file", path);
	} else if (fmt == MESH_STL) {
		unsigned char h[84];
		ok = fread(h, 1, 84, f) == 84 && (uint64_t)sb.st_size == 84 + 50 * (uint64_t)le32(h + 80);
		if (!ok)
			snprintf(why, n, "%s: expected 84 + 50 bytes a triangle, found %lld bytes", path, (long long)sb.st_size);
	} else if (fmt == MESH_PLY) {
		unsigned long long nv = 0, nt = 0, head = 0;
		int end = 0;
		while (!end && fgets(line, sizeof line, f)) {
			head += strlen(line);
			sscanf(line, "element vertex %llu", &nv);
			sscanf(line, "element face %llu", &nt);
			end = !strcmp(line, "end_header\n");
		}
		ok = end && (uint64_t)sb.st_size == head + 12 * nv + 13 * nt;
		if (!ok)
			snprintf(why, n, "%s: expected a PLY header and %llu bytes after it, found %lld bytes in all", path,
				12 * nv + 13 * nt, (long long)sb.st_size);
	} else if (fmt == MESH_OBJ) {
		unsigned long long nv = 0, nt = 0, v = 0, t = 0;
		int last_nl = 1;
		if (fgets(line, sizeof line, f) && sscanf(line, "# Locus mesh of %*[^:]: %llu vertices, %llu triangles", &nv, &nt) == 2) {
			while (fgets(line, sizeof line, f)) {
				v += line[0] == 'v' && line[1] == ' ';
				t += line[0] == 'f' && line[1] == ' ';
				last_nl = strchr(line, '\n') != NULL;
			}
			ok = last_nl && v == nv && t == nt;
		}
		if (!ok)
			snprintf(why, n, "%s: expected the %llu vertices and %llu triangles its first line counts, found %llu and %llu",
				path, nv, nt, v, t);
	} else {
		static const char tail[] = "$EndElements\n";
		size_t k = sizeof tail - 1;
		ok = sb.st_size > (off_t)k && !fseek(f, -(long)k, SEEK_END) && fread(line, 1, k, f) == k && !memcmp(line, tail, k);
		if (!ok)
			snprintf(why, n, "%s: expected it to end with $EndElements", path);
	}
	fclose(f);
	return ok;
}

/* ---- Frames ------------------------------------------------------------------------------- */

typedef struct {
	const char *in, *name, *out;
	char *text;
	int binary, quiet, stats, fail_fast, skip_existing, records, pattern, mesh_fmt;
	double dt, t_start;
	scene_opts_t o;
	scene_stats_t st;
} job_t;

static int parse_status(int rc, const char *err)
{
	/* memory running out while parsing is 70, whatever the parser returned: core/expr.c
	 * reports it as "expected memory for the expression" (code -1) */
	if (rc == SCENE_ENOMEM || strstr(err, ": expected memory for "))
		return EX_SOFTWARE;
	return EX_DATAERR;
}

/* Parse frame fr; its warnings go out now (with a heading when the run has several frames) */
static int parse_frame(job_t *j, long fr, int many, scene_t **sc)
{
	char err[1024];
	int rc = scene_parse_frame(j->text, j->name, fr * j->dt, sc, err, sizeof err);
	if (rc < 0) {
		say(err);
		return parse_status(rc, err);
	}
	if (!j->quiet && many && (*sc)->nwarnings)
		fprintf(stderr, "locus-render: frame %ld (t = %g):\n", fr, fr * j->dt);
	if (!j->quiet)
		for (size_t i = 0; i < (*sc)->nwarnings; i++)
			say((*sc)->warnings[i]);
	return 0;
}

/* Render the parsed frame onto w (its records around it when asked); an exit status */
static int render_frame(job_t *j, scene_t *sc, long fr, meta_writer_t *w, io_transport_t *f, int many)
{
	char err[1024];
	scene_stats_t one;
	size_t nw0 = sc->nwarnings;
	if (j->records && meta_frame_begin(w, fr, fr * j->dt) < 0)
		goto wfail;
	int rc = scene_render(sc, w, &j->o, &one, err, sizeof err);
	if (rc < 0) {
		say(io_failed(f) ? io_error(f) : err);
		return io_failed(f) ? (io_errno(f) == ENOMEM ? EX_SOFTWARE : EX_IOERR)
			: rc == SCENE_ENOMEM ? EX_SOFTWARE : EX_DATAERR;
	}
	if (j->records && meta_frame_end(w, fr) < 0)
		goto wfail;
	add_stats(&j->st, &one);
	if (!j->quiet && many)
		for (size_t i = nw0; i < sc->nwarnings; i++)
			say(sc->warnings[i]);
	return 0;
wfail:
	fprintf(stderr, "%s\n", io_failed(f) ? io_error(f) : meta_writer_error(w));
	return io_failed(f) && io_errno(f) == ENOMEM ? EX_SOFTWARE : io_failed(f) ? EX_IOERR : EX_SOFTWARE;
}

/* Close w and f: commit when status is 0; the final status */
static int finish(meta_writer_t *w, io_transport_t *f, int status)
{
	char err[1024];
	if (w && meta_writer_close(w) < 0 && !status) {
		fprintf(stderr, "%s\n", io_failed(f) ? io_error(f) : "locus-render: write error");
		status = io_failed(f) && io_errno(f) == ENOMEM ? EX_SOFTWARE : EX_IOERR;
	}
	if (io_close_err(f, status ? IO_ABORT : IO_COMMIT, err, sizeof err) < 0 && !status) {
		status = errno == ENOMEM ? EX_SOFTWARE : EX_IOERR;   /* the close's cause (transport.h) */
		say(err);
	}
	return status;
}

/* Every frame into one file (or stdout): a failed frame fails the whole file. */
static int run_one_file(job_t *j, const long *frames, size_t nframes)
{
	char err[1024];
	int many = nframes > 1;
	scene_t *sc;
	int status = parse_frame(j, frames[0], many, &sc);
	if (status)
		return status;
	size_t nw0 = sc->nwarnings;
	if (j->mesh_fmt >= 0) {
		status = write_mesh(sc, j->out, j->mesh_fmt, j->stats, j->t_start);
		scene_free(sc);
		return status;
	}
	/* a file via a new temporary renamed on success; a device or a pipe (e.g. /dev/null)
	 * written in place, never replaced (drivers/transport.h) */
	io_transport_t *f = io_open_write(j->out, err, sizeof err);
	if (!f) {
		int st = errno == ENOMEM ? EX_SOFTWARE : EX_IOERR;   /* io_open_write's cause */
		say(err);
		scene_free(sc);
		return st;
	}
	meta_writer_t *w = meta_writer_new(write_cb, f, j->binary ? META_ENC_BINARY : META_ENC_TEXT);
	if (!w) {
		fprintf(stderr, "locus-render: out of memory\n");
		status = EX_SOFTWARE;
	}
	/* frames are independent: each is the scene parsed at its t and rendered onto the
	 * same writer (its pages follow the previous frame's) */
	for (size_t k = 0; k < nframes && !status; k++) {
		if (k > 0) {
			scene_free(sc);
			sc = NULL;
			if ((status = parse_frame(j, frames[k], many, &sc)))
				break;
		}
		status = render_frame(j, sc, frames[k], w, f, many);
	}
	status = finish(w, f, status);
	if (!status && !j->quiet && !many)
		for (size_t i = nw0; i < sc->nwarnings; i++)
			say(sc->warnings[i]);
	scene_free(sc);
	return status;
}

/* One file per frame, each renamed into place whole; failed frames named at the end. */
static int run_per_frame(job_t *j, const long *frames, size_t nframes)
{
	char err[1024], why[1024];
	int first_status = 0;
	size_t nfailed = 0, nskipped = 0, k;
	long *failed = malloc(nframes * sizeof *failed);
	if (!failed) {
		fprintf(stderr, "locus-render: out of memory\n");
		return EX_SOFTWARE;
	}
	for (k = 0; k < nframes; k++) {
		long fr = frames[k];
		char *path = meta_frame_pattern_name(j->out, fr);
		int status = 0;
		if (!path) {
			fprintf(stderr, "locus-render: out of memory\n");
			status = EX_SOFTWARE;
		} else if (j->skip_existing) {
			int c = j->mesh_fmt >= 0 ? mesh_complete(path, j->mesh_fmt, why, sizeof why)
				: meta_complete(path, fr, j->binary, why, sizeof why);
			if (c == 1) {
				if (!j->quiet)
					fprintf(stderr, "locus-render: frame %ld: %s is there and complete, skipped\n", fr, path);
				nskipped++;
				free(path);
				continue;
			}
			if (c == 0 && !j->quiet) {
				scene_escape(err, sizeof err, why);
				fprintf(stderr, "locus-render: frame %ld: rendered again: %s\n", fr, err);
			}
		}
		scene_t *sc = NULL;
		if (!status)
			status = parse_frame(j, fr, 1, &sc);
		if (!status && j->mesh_fmt >= 0) {
			status = write_mesh(sc, path, j->mesh_fmt, j->stats, j->t_start);
		} else if (!status) {
			io_transport_t *f = io_open_write(path, err, sizeof err);
			if (!f) {
				status = errno == ENOMEM ? EX_SOFTWARE : EX_IOERR;   /* before say() */
				say(err);
			} else {
				meta_writer_t *w = meta_writer_new(write_cb, f, j->binary ? META_ENC_BINARY : META_ENC_TEXT);
				if (!w) {
					fprintf(stderr, "locus-render: out of memory\n");
					status = EX_SOFTWARE;
				} else {
					status = render_frame(j, sc, fr, w, f, 1);
				}
				status = finish(w, f, status);
			}
		}
		scene_free(sc);
		free(path);
		if (status) {
			failed[nfailed++] = fr;
			if (!first_status)
				first_status = status;
			if (j->fail_fast) {
				k++;
				break;
			}
		}
	}
	if (nfailed) {
		fprintf(stderr, "locus-render: %zu of %zu frames failed:", nfailed, nframes);
		for (size_t i = 0; i < nfailed && i < 40; i++)
			fprintf(stderr, " %ld", failed[i]);
		if (nfailed > 40)
			fprintf(stderr, " ... %ld", failed[nfailed - 1]);
		if (k < nframes)
			fprintf(stderr, "; --fail-fast left %zu not rendered (%ld ... %ld)", nframes - k, frames[k],
				frames[nframes - 1]);
		fputc('\n', stderr);
	} else if (nskipped && !j->quiet) {
		fprintf(stderr, "locus-render: %zu of %zu frames were there and complete\n", nskipped, nframes);
	}
	free(failed);
	return first_status;
}

/* SLURM_ARRAY_TASK_ID, or -1 (message) when absent or not a number */
static long env_task(void)
{
	const char *v = getenv("SLURM_ARRAY_TASK_ID");
	char *end;
	if (!v || !*v) {
		fprintf(stderr, "locus-render: --chunk needs --task I or SLURM_ARRAY_TASK_ID in the environment\n");
		return -1;
	}
	errno = 0;
	long t = strtol(v, &end, 10);
	if (*end || errno || t < 0) {
		fprintf(stderr, "locus-render: SLURM_ARRAY_TASK_ID expects a task number 0 or more, found '%s'\n", v);
		return -1;
	}
	return t;
}

static long count_arg(const char *opt, const char *v, long lo, long hi)
{
	char *end;
	errno = 0;
	long x = strtol(v, &end, 10);
	if (*end || end == v || errno || x < lo || x > hi) {
		fprintf(stderr, "locus-render: %s expects %ld..%ld, found '%s'\n", opt, lo, hi, v);
		return -1;
	}
	return x;
}

int main(int argc, char **argv)
{
	job_t j;
	memset(&j, 0, sizeof j);
	j.out = "-";
	j.dt = 1;
	long threads = 0, chunk = 0, task = -1;
	int binary_opt = 0, list_only = 0;
	const char *spec = NULL;
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i];
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			fputs(usage, stdout);
			return 0;
		} else if (!strcmp(a, "--version")) {
			printf("locus-render %s\n", LOCUS_VERSION);
			return 0;
		} else if (!strcmp(a, "-o") && i + 1 < argc) {
			j.out = argv[++i];
		} else if (!strcmp(a, "--binary")) {
			binary_opt = 1;
		} else if (!strcmp(a, "--quiet")) {
			j.quiet = 1;
		} else if (!strcmp(a, "--stats")) {
			j.stats = 1;
		} else if (!strcmp(a, "--skip-existing")) {
			j.skip_existing = 1;
		} else if (!strcmp(a, "--fail-fast")) {
			j.fail_fast = 1;
		} else if (!strcmp(a, "--list-frames")) {
			list_only = 1;
		} else if (!strcmp(a, "--threads") && i + 1 < argc) {
			if ((threads = count_arg("--threads", argv[++i], 1, 64)) < 0)
				return EX_USAGE;
		} else if (!strcmp(a, "--chunk") && i + 1 < argc) {
			if ((chunk = count_arg("--chunk", argv[++i], 1, META_FRAME_MAX + 1)) < 0)
				return EX_USAGE;
		} else if (!strcmp(a, "--task") && i + 1 < argc) {
			if ((task = count_arg("--task", argv[++i], 0, META_FRAME_MAX)) < 0)
				return EX_USAGE;
		} else if (!strcmp(a, "--frames") && i + 1 < argc) {
			spec = argv[++i];
		} else if (!strcmp(a, "--time-step") && i + 1 < argc) {
			char *end;
			j.dt = strtod(argv[++i], &end);
			if (*end || !isfinite(j.dt) || end == argv[i]) {
				fprintf(stderr, "locus-render: --time-step expects a finite number, found '%s'\n", argv[i]);
				return EX_USAGE;
			}
		} else if (a[0] == '-' && a[1]) {
			fprintf(stderr, "locus-render: unknown option '%s' (try --help)\n", a);
			return EX_USAGE;
		} else if (!j.in) {
			j.in = a;
		} else {
			fprintf(stderr, "locus-render: one scene file expected, found a second: '%s'\n", a);
			return EX_USAGE;
		}
	}
	if (!j.in && !list_only) {
		fputs(usage, stderr);
		return EX_USAGE;
	}
	char err[1024];
	if ((j.pattern = meta_frame_pattern_check(j.out, err, sizeof err)) < 0) {
		fprintf(stderr, "locus-render: ");
		say(err);
		return EX_USAGE;
	}
	if (task >= 0 && !chunk) {
		fprintf(stderr, "locus-render: --task belongs to --chunk K\n");
		return EX_USAGE;
	}
	if (chunk && !spec) {
		fprintf(stderr, "locus-render: --chunk cuts a --frames list into chunks: give --frames\n");
		return EX_USAGE;
	}
	if ((j.skip_existing || j.fail_fast) && !j.pattern) {
		fprintf(stderr, "locus-render: %s works frame by frame: give -o a frame pattern (NAME-%%04d.meta)\n",
			j.skip_existing ? "--skip-existing" : "--fail-fast");
		return EX_USAGE;
	}
	/* the frames: --frames, or frame 0 alone; then this task's chunk of them */
	long *frames = NULL, zero = 0, *sel;
	size_t nframes = 1;
	if (spec) {
		int rc = meta_frame_list_parse(spec, (size_t)META_FRAME_MAX + 1, &frames, &nframes, err, sizeof err);
		if (rc < 0) {
			fprintf(stderr, "locus-render: --frames: %s\n", err);
			return rc == -3 ? EX_SOFTWARE : EX_USAGE;
		}
	}
	sel = frames ? frames : &zero;
	if (chunk) {
		if (task < 0 && (task = env_task()) < 0) {
			free(frames);
			return EX_USAGE;
		}
		size_t nchunks = (nframes + (size_t)chunk - 1) / (size_t)chunk;
		if ((size_t)task >= nchunks) {
			fprintf(stderr, "locus-render: task %ld is past the last chunk: --frames %s in chunks of %ld is %zu"
				" chunk%s, tasks 0 to %zu\n", task, spec, chunk, nchunks, nchunks > 1 ? "s" : "", nchunks - 1);
			free(frames);
			return EX_USAGE;
		}
		sel += (size_t)task * (size_t)chunk;
		nframes -= (size_t)task * (size_t)chunk;
		if (nframes > (size_t)chunk)
			nframes = (size_t)chunk;
	}
	if (list_only) {
		for (size_t k = 0; k < nframes; k++)
			printf("%ld\n", sel[k]);
		free(frames);
		return fflush(stdout) || ferror(stdout) ? EX_IOERR : 0;
	}
	j.records = spec != NULL || j.pattern;
	j.mesh_fmt = mesh_format_of(j.out);
	{
		size_t n = strlen(j.out);
		j.binary = binary_opt || (n > 4 && !strcmp(j.out + n - 4, ".lmb"));
	}
	if (j.mesh_fmt >= 0 && nframes > 1 && !j.pattern) {
		fprintf(stderr, "locus-render: a mesh file holds one frame: give -o a frame pattern (NAME-%%04d%s)"
			" for %zu frames\n", j.out + strlen(j.out) - 4, nframes);
		free(frames);
		return EX_USAGE;
	}
	j.t_start = now();
	j.name = strcmp(j.in, "-") ? j.in : "<stdin>";
	int rc = scene_read(j.in, &j.text, err, sizeof err);
	if (rc < 0) {
		say(err);
		free(frames);
		return rc == SCENE_ENOMEM ? EX_SOFTWARE : rc == -2 ? EX_NOINPUT : EX_DATAERR;
	}
	j.o.threads = (unsigned)threads;
	if (!j.quiet && isatty(2))
		j.o.progress = progress;
	int status = j.pattern ? run_per_frame(&j, sel, nframes) : run_one_file(&j, sel, nframes);
	free(j.text);
	free(frames);
	if (!status && j.stats && j.mesh_fmt < 0) {
		scene_stats_t st = j.st;
		double total = now() - j.t_start;
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
	return status;
}
