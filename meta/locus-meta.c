/* locus-meta.c: check, format, describe and convert Locus meta-language files. */
#include <errno.h>
#include <math.h>
#include <fcntl.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "locus_meta.h"
#include "io/transport.h"
#include "import/meta_import.h"
#include "meta_frames.h"

#define EX_USAGE 64
#define EX_DATAERR 65
#define EX_NOINPUT 66
#define EX_SOFTWARE 70
#define EX_IOERR 74
#define MAX_COLOURS 1024 /* info: distinct colours counted before saying "more than" */

static const char usage_text[] =
	"usage: locus-meta check FILE\n"
	"       locus-meta fmt [IN] [-o OUT]\n"
	"       locus-meta info FILE\n"
	"       locus-meta convert [IN] [-o OUT] [--text|--binary]\n"
	"       locus-meta import [IN] [-o OUT] [OPTIONS]   (HP-GL, HP-GL/2, plotutils metafiles\n"
	"         and SVG, told apart by their content; 'locus-meta import --help' lists OPTIONS)\n"
"       locus-meta cat FILES... [-o OUT] [--frames LIST] [--text|--binary]\n"
	"         join an animation's per-frame files (locus-render --frames -o NAME-%04d.meta)\n"
	"         into the file one run writes; every frame of LIST (default: the first found to\n"
	"         the last) there once and complete, else 65 naming it and no output (docs/farm.md)\n"
	"Check, canonically format, describe or convert a Locus meta-language file\n"
	"(docs/meta-language.md). IN and OUT default to '-' (stdin, stdout); an OUT\n"
	"file is written to a new temporary beside it and renamed only when the whole\n"
	"input was valid; a device or a pipe is written in place.\n"
	"Exit status: 0 ok, 64 usage, 65 invalid input (one line names file and\n"
	"place), 66 cannot open input, 70 out of memory, 74 I/O error.\n";

static int usage(const char *msg)
{
	if (msg)
		fprintf(stderr, "locus-meta: %s\n", msg);
	fputs(usage_text, stderr);
	return EX_USAGE;
}

/* After --help or --version on stdio: 0, or 74 with one line naming the cause. */
static int stdout_status(void)
{
	if (fflush(stdout) == 0 && !ferror(stdout))
		return 0;
	fprintf(stderr, "locus-meta: <stdout>: write failed: %s\n", strerror(errno));
	return EX_IOERR;
}

/* The status of an output failure whose cause is the errno e (transport.h: io_errno, or errno
 * after a failed open or close): 70 when memory ran out, else 74. */
static int io_status(int e)
{
	return e == ENOMEM ? EX_SOFTWARE : EX_IOERR;
}

/* Map a reader/writer error code to an exit status. */
static int status_of(int rc)
{
	return rc == META_EIO ? EX_IOERR : rc == META_ENOMEM ? EX_SOFTWARE : EX_DATAERR;
}

static meta_reader_t *open_in(const char *path, int *status)
{
	char err[512];
	meta_reader_t *r = meta_reader_open(path, err, sizeof err);
	if (!r) {
		*status = errno == ENOMEM ? EX_SOFTWARE : EX_NOINPUT;
		fprintf(stderr, "%s\n", err);
	}
	return r;
}

/* ---- Output: through the driver transport (drivers/transport.h): a file via a new temporary
 * renamed on success, a device or pipe in place; write errors name the output and the cause. */

static int out_write(void *user, const void *buf, size_t n)
{
	return io_write(user, buf, n);
}

static io_transport_t *out_open(const char *path, int *status)
{
	char err[600];
	io_transport_t *o = io_open_write(path ? path : "-", err, sizeof err);
	if (!o) {
		*status = io_status(errno);
		fprintf(stderr, "%s\n", err);
	}
	return o;
}

/* Finish the output: commit on success (status 0), discard otherwise; 74 if that fails. */
static int out_close(io_transport_t *o, int status)
{
	char err[600];
	if (io_close_err(o, status ? IO_ABORT : IO_COMMIT, err, sizeof err) < 0 && status == 0) {
		status = io_status(errno);
		fprintf(stderr, "%s\n", err);
	}
	return status;
}

/* ---- Subcommands -------------------------------------------------------- */

static int cmd_check(const char *path)
{
	meta_cmd_t c;
	int rc, status = 0;
	meta_reader_t *r = open_in(path, &status);
	if (!r)
		return status;
	while ((rc = meta_read(r, &c)) > 0)
		;
	if (rc < 0) {
		fprintf(stderr, "%s\n", meta_reader_error(r));
		status = status_of(rc);
	}
	meta_reader_free(r);
	return status;
}

/* Copy IN to OUT in the given encoding (-1: the other one than IN's). */
static int cmd_copy(const char *in, const char *outpath, int enc)
{
	meta_cmd_t c;
	meta_writer_t *w = NULL;
	int rc, status = 0;
	meta_reader_t *r = open_in(in, &status);
	if (!r)
		return status;
	io_transport_t *o = out_open(outpath, &status);
	if (!o) {
		meta_reader_free(r);
		return status;
	}
	while ((rc = meta_read(r, &c)) > 0) {
		if (!w) {
			if (enc < 0)
				enc = meta_reader_is_binary(r) ? META_ENC_TEXT : META_ENC_BINARY;
			w = meta_writer_new(out_write, o, enc);
			if (!w) {
				rc = META_ENOMEM;
				break;
			}
		}
		if ((rc = meta_write(w, &c)) < 0) {
			if (io_failed(o))
				fprintf(stderr, "%s\n", io_error(o));
			else
				fprintf(stderr, "%s: %s\n", io_is_std(o) ? "<stdout>" : io_name(o), meta_writer_error(w));
			status = io_failed(o) ? io_status(io_errno(o)) : status_of(rc);
			break;
		}
	}
	if (rc < 0 && !status) {
		fprintf(stderr, "%s\n", rc == META_ENOMEM && !w ? "locus-meta: out of memory" : meta_reader_error(r));
		status = status_of(rc);
	}
	if (w && (rc = meta_writer_close(w)) < 0 && !status) {
		fprintf(stderr, "%s\n", io_failed(o) ? io_error(o) : "locus-meta: write error");
		status = io_failed(o) ? io_status(io_errno(o)) : EX_IOERR;
	}
	meta_reader_free(r);
	return out_close(o, status);
}

typedef struct {
	meta_rgb_t set[2 * MAX_COLOURS]; /* open addressing; 0xffffffff = empty */
	size_t n;
	int overflow;
} colours_t;

static void colour_add(colours_t *s, meta_rgb_t c)
{
	size_t h = (c * 2654435761u) % (2 * MAX_COLOURS);
	while (s->set[h] != 0xffffffffu) {
		if (s->set[h] == c)
			return;
		h = (h + 1) % (2 * MAX_COLOURS);
	}
	if (s->n == MAX_COLOURS) {
		s->overflow = 1;
		return;
	}
	s->set[h] = c;
	s->n++;
}

static int cmp_rgb(const void *a, const void *b)
{
	meta_rgb_t x = *(const meta_rgb_t *)a, y = *(const meta_rgb_t *)b;
	return x < y ? -1 : x > y;
}

typedef struct {
	double x0, y0, x1, y1;
	int any;
} box_t;

static void box_add(box_t *b, double x0, double y0, double x1, double y1)
{
	if (!b->any || x0 < b->x0) b->x0 = x0;
	if (!b->any || y0 < b->y0) b->y0 = y0;
	if (!b->any || x1 > b->x1) b->x1 = x1;
	if (!b->any || y1 > b->y1) b->y1 = y1;
	b->any = 1;
}

/* Bounds of an arc: its end points and the axis points its sweep passes. */
static void arc_box(box_t *b, double cx, double cy, double r, double start, double sweep)
{
	const double rad = 3.14159265358979323846 / 180.0;
	double lo = sweep < 0 ? start + sweep : start, hi = sweep < 0 ? start : start + sweep, a;
	box_add(b, cx + r * cos(lo * rad), cy + r * sin(lo * rad), cx + r * cos(lo * rad), cy + r * sin(lo * rad));
	box_add(b, cx + r * cos(hi * rad), cy + r * sin(hi * rad), cx + r * cos(hi * rad), cy + r * sin(hi * rad));
	for (a = ceil(lo / 90.0) * 90.0; a <= hi; a += 90.0) {
		int q = ((int)fmod(a / 90.0, 4.0) + 4) % 4;
		double x = cx + (q == 0 ? r : q == 2 ? -r : 0), y = cy + (q == 1 ? r : q == 3 ? -r : 0);
		box_add(b, x, y, x, y);
	}
}

static void print_page(io_transport_t *o, unsigned page, const meta_cmd_t *pg, const meta_fix_t *size, unsigned long long nst, const box_t *b)
{
	char w[16], h[16];
	io_printf(o, "page %u: %u x %u px", page, pg->u[0], pg->u[1]);
	if (size[0]) {
		meta_fix_format(size[0], w);
		meta_fix_format(size[1], h);
		io_printf(o, ", %s x %s mm", w, h);
	}
	io_printf(o, ", %llu statements", nst);
	if (b->any)
		io_printf(o, ", geometry bounds x %.3f .. %.3f, y %.3f .. %.3f", b->x0, b->x1, b->y0, b->y1);
	else
		io_printf(o, ", no geometry");
	io_printf(o, "\n");
}

static int cmd_info(const char *path)
{
	static colours_t cs;
	unsigned long long count[META_OP_COUNT] = { 0 }, nst = 0;
	meta_cmd_t c, pg;
	meta_rgb_t cur = 0;
	meta_fix_t size[2] = { 0, 0 };
	box_t box = { 0, 0, 0, 0, 0 };
	unsigned pages = 0, imgx = 0, imgy = 0, imgw = 0, imgrow = 0, imgh = 0;
	int rc, status = 0, i;
	size_t k;
	meta_reader_t *r = open_in(path, &status);
	if (!r)
		return status;
	io_transport_t *o = out_open("-", &status);
	if (!o) {
		meta_reader_free(r);
		return status;
	}
	memset(cs.set, 0xff, sizeof cs.set);
	memset(&pg, 0, sizeof pg);
	while ((rc = meta_read(r, &c)) > 0) {
		double f0 = c.f[0] / 1000.0, f1 = c.f[1] / 1000.0, f2 = c.f[2] / 1000.0;
		count[c.op]++;
		nst++;
		switch (c.op) {
		case META_PAGE:
			if (!pages++)
				io_printf(o, "%s: %s encoding\n", path, meta_reader_is_binary(r) ? "binary" : "text");
			pg = c;
			cur = 0x000000; /* the default colour of every page */
			size[0] = size[1] = 0;
			memset(&box, 0, sizeof box);
			nst = 1;
			break;
		case META_SIZE: size[0] = c.f[0]; size[1] = c.f[1]; break;
		case META_END_PAGE: print_page(o, pages, &pg, size, nst, &box); break;
		case META_CLEAR: colour_add(&cs, c.rgb); break;
		case META_COLOUR: cur = c.rgb; break;
		case META_END: colour_add(&cs, cur); break; /* the colour a path is painted with */
		case META_MOVE: case META_DRAW: box_add(&box, f0, f1, f0, f1); break;
		case META_ARC: arc_box(&box, f0, f1, f2, c.f[3] / 1000.0, c.f[4] / 1000.0); break;
		case META_CIRCLE: box_add(&box, f0 - f2, f1 - f2, f0 + f2, f1 + f2); break;
		case META_TEXT:
			colour_add(&cs, cur);
			box_add(&box, f0, f1, f0, f1);
			break;
		case META_SPAN:
			colour_add(&cs, c.rgb);
			box_add(&box, c.u[0], c.u[1], (double)c.u[0] + c.u[2], c.u[1] + 1.0);
			break;
		case META_IMAGE:
			imgx = c.u[0], imgy = c.u[1], imgw = c.u[2], imgh = c.u[3], imgrow = 0;
			box_add(&box, imgx, imgy, (double)imgx + imgw, (double)imgy + imgh);
			break;
		case META_ROW:
			for (k = 0; k < c.nruns; k++)
				colour_add(&cs, c.runs[k].rgb);
			imgrow++;
			break;
		default: break;
		}
	}
	(void)imgrow;
	if (rc < 0) {
		status = io_flush(o) < 0 ? io_status(io_errno(o)) : status_of(rc);   /* what was read so far, first */
		fprintf(stderr, "%s\n", io_failed(o) ? io_error(o) : meta_reader_error(r));
		meta_reader_free(r);
		return out_close(o, status);
	}
	io_printf(o, "pages: %u\nstatements:", pages);
	for (i = 0; i < META_OP_COUNT; i++)
		if (count[i])
			io_printf(o, " %s %llu", i == META_COMMENT ? "comment" : meta_op_name((meta_op_t)i), count[i]);
	io_printf(o, "\n");
	if (cs.overflow) {
		io_printf(o, "colours: more than %d distinct\n", MAX_COLOURS);
	} else {
		meta_rgb_t list[MAX_COLOURS];
		size_t n = 0;
		for (k = 0; k < 2 * MAX_COLOURS; k++)
			if (cs.set[k] != 0xffffffffu)
				list[n++] = cs.set[k];
		qsort(list, n, sizeof *list, cmp_rgb);
		io_printf(o, "colours: %zu distinct", n);
		for (k = 0; k < n && k < 32; k++)
			io_printf(o, " #%06x", list[k]);
		io_printf(o, "%s\n", n > 32 ? " ..." : "");
	}
	meta_reader_free(r);
	return out_close(o, 0);
}

/* ---- cat: an animation's per-frame (or per-chunk) files joined into the file one locus-render
 * --frames run writes, byte for byte; every frame checked to be there once and whole before any
 * output is opened (docs/farm.md, "Joining") -------------------------------------------- */

typedef struct {
	const char *path;
	meta_frames_t fr;
} part_t;

typedef struct {
	long frame;
	size_t part;
} where_t;

static int cmp_where(const void *a, const void *b)
{
	const where_t *x = a, *y = b;
	if (x->frame != y->frame)
		return x->frame < y->frame ? -1 : 1;
	return x->part < y->part ? -1 : x->part > y->part;
}

static int cmp_part(const void *a, const void *b)
{
	const part_t *x = a, *y = b;
	return x->fr.frames[0] < y->fr.frames[0] ? -1 : x->fr.frames[0] > y->fr.frames[0];
}

static int scan_status(int rc)
{
	return rc == -66 ? EX_NOINPUT : rc == -70 ? EX_SOFTWARE : rc == -74 ? EX_IOERR : EX_DATAERR;
}

/* Pass 1: every file whole, with frame records; the frames there once each and, with a list,
 * exactly the list; the files ordered by their first frame, each continuing the one before. */
static int plan(part_t *parts, size_t nparts, const char *spec, size_t *nframes)
{
	char err[800];
	size_t total = 0;
	for (size_t i = 0; i < nparts; i++) {
		int rc = meta_frames_scan(parts[i].path, &parts[i].fr, err, sizeof err);
		if (rc) {
			fprintf(stderr, "%s\n", err);
			return scan_status(rc);
		}
		if (!parts[i].fr.records) {
			fprintf(stderr, "%s: expected frame records ('# frame N' before a frame's pages, as locus-render"
				" --frames writes them), found none\n", parts[i].path);
			return EX_DATAERR;
		}
		total += parts[i].fr.n;
	}
	where_t *w = malloc(total * sizeof *w);
	if (!w) {
		fprintf(stderr, "locus-meta: out of memory for %zu frames\n", total);
		return EX_SOFTWARE;
	}
	size_t k = 0;
	for (size_t i = 0; i < nparts; i++)
		for (size_t f = 0; f < parts[i].fr.n; f++)
			w[k].frame = parts[i].fr.frames[f], w[k++].part = i;
	qsort(w, total, sizeof *w, cmp_where);
	int status = 0;
	for (k = 1; k < total && !status; k++)
		if (w[k].frame == w[k - 1].frame) {
			if (w[k].part != w[k - 1].part && !strcmp(parts[w[k].part].path, parts[w[k - 1].part].path))
				fprintf(stderr, "locus-meta: frame %ld is duplicated: %s is given twice\n", w[k].frame, parts[w[k].part].path);
			else if (w[k].part == w[k - 1].part)
				fprintf(stderr, "locus-meta: frame %ld is duplicated: twice in %s\n", w[k].frame, parts[w[k].part].path);
			else
				fprintf(stderr, "locus-meta: frame %ld is duplicated: in %s and in %s\n", w[k].frame,
					parts[w[k - 1].part].path, parts[w[k].part].path);
			status = EX_DATAERR;
		}
	/* the frames expected: the list, else every one from the first to the last */
	long *want = NULL;
	size_t nwant = 0;
	if (!status && spec) {
		int rc = meta_frame_list_parse(spec, (size_t)META_FRAME_MAX + 1, &want, &nwant, err, sizeof err);
		if (rc) {
			fprintf(stderr, "locus-meta: --frames: %s\n", err);
			status = rc == -3 ? EX_SOFTWARE : EX_USAGE;
		}
	}
	if (!status) {
		size_t a = 0, b = 0;   /* merge the sorted found (w) and wanted lists */
		long next = w[0].frame;
		while (!status && (a < total || (spec ? b < nwant : 0))) {
			long found = a < total ? w[a].frame : -1;
			long expect = spec ? (b < nwant ? want[b] : -1) : next;
			if (found == expect) {
				a++, b++, next++;
			} else if (expect >= 0 && (found < 0 || found > expect)) {
				if (spec)
					fprintf(stderr, "locus-meta: frame %ld is missing (--frames %s)\n", expect, spec);
				else
					fprintf(stderr, "locus-meta: frame %ld is missing (between frames %ld and %ld)\n", expect,
						w[0].frame, w[total - 1].frame);
				status = EX_DATAERR;
			} else {
				fprintf(stderr, "locus-meta: frame %ld in %s is not in --frames %s\n", found, parts[w[a].part].path, spec);
				status = EX_DATAERR;
			}
		}
	}
	free(want);
	free(w);
	if (status)
		return status;
	qsort(parts, nparts, sizeof *parts, cmp_part);
	for (size_t i = 1; i < nparts; i++) {
		const meta_frames_t *p = &parts[i - 1].fr;
		if (p->frames[p->n - 1] > parts[i].fr.frames[0]) {
			fprintf(stderr, "locus-meta: the frames of %s and %s interleave (frame %ld comes before %ld):"
				" join files that each hold a run of frames\n", parts[i - 1].path, parts[i].path,
				parts[i].fr.frames[0], p->frames[p->n - 1]);
			return EX_DATAERR;
		}
		for (size_t f = 1; f < parts[i].fr.n; f++)
			if (parts[i].fr.frames[f] < parts[i].fr.frames[f - 1]) {
				fprintf(stderr, "%s: frame %ld comes after frame %ld: expected the frames in order\n", parts[i].path,
					parts[i].fr.frames[f], parts[i].fr.frames[f - 1]);
				return EX_DATAERR;
			}
	}
	*nframes = total;
	return 0;
}

static int cmd_cat(char *const *files, size_t nfiles, const char *spec, const char *out, int enc)
{
	part_t *parts = calloc(nfiles, sizeof *parts);
	if (!parts) {
		fprintf(stderr, "locus-meta: out of memory\n");
		return EX_SOFTWARE;
	}
	for (size_t i = 0; i < nfiles; i++)
		parts[i].path = files[i];
	size_t nframes = 0;
	int status = plan(parts, nfiles, spec, &nframes);
	io_transport_t *o = NULL;
	meta_writer_t *w = NULL;
	if (!status && !(o = out_open(out, &status)))
		status = status ? status : EX_IOERR;
	if (!status && !(w = meta_writer_new(out_write, o, enc >= 0 ? enc : parts[0].fr.binary ? META_ENC_BINARY
			: META_ENC_TEXT))) {
		fprintf(stderr, "locus-meta: out of memory\n");
		status = EX_SOFTWARE;
	}
	/* Pass 2: the statements of every file, in order; the records checked again as they pass (a
	 * file that changed in between is refused, not joined) */
	for (size_t i = 0; i < nfiles && !status; i++) {
		char err[600];
		meta_reader_t *r = meta_reader_open(parts[i].path, err, sizeof err);
		if (!r) {
			fprintf(stderr, "%s\n", err);
			status = errno == ENOMEM ? EX_SOFTWARE : EX_NOINPUT;
			break;
		}
		meta_cmd_t c;
		int rc;
		size_t f = 0;
		while ((rc = meta_read(r, &c)) > 0) {
			if (c.op == META_COMMENT && !strncmp(c.str, "frame ", 6) && c.str[6] >= '0' && c.str[6] <= '9') {
				if (f >= parts[i].fr.n || strtol(c.str + 6, NULL, 10) != parts[i].fr.frames[f]) {
					fprintf(stderr, "%s: changed while it was being joined\n", parts[i].path);
					status = EX_DATAERR;
					break;
				}
				f++;
			}
			if ((rc = meta_write(w, &c)) < 0) {
				if (io_failed(o))
					fprintf(stderr, "%s\n", io_error(o));
				else
					fprintf(stderr, "%s: %s\n", io_is_std(o) ? "<stdout>" : io_name(o), meta_writer_error(w));
				status = io_failed(o) ? io_status(io_errno(o)) : status_of(rc);
				break;
			}
		}
		if (rc < 0 && !status) {
			fprintf(stderr, "%s\n", meta_reader_error(r));
			status = status_of(rc);
		}
		if (!status && f != parts[i].fr.n) {
			fprintf(stderr, "%s: changed while it was being joined\n", parts[i].path);
			status = EX_DATAERR;
		}
		meta_reader_free(r);
	}
	if (w && meta_writer_close(w) < 0 && !status) {
		fprintf(stderr, "%s\n", io_failed(o) ? io_error(o) : "locus-meta: write error");
		status = io_failed(o) ? io_status(io_errno(o)) : EX_IOERR;
	}
	if (o)
		status = out_close(o, status);
	for (size_t i = 0; i < nfiles; i++)
		meta_frames_free(&parts[i].fr);
	free(parts);
	return status;
}

int main(int argc, char **argv)
{
	const char *in = NULL, *out = NULL, *frames = NULL, *sub;
	int enc = -1, c;
	static const struct option longopts[] = {
		{ "help", no_argument, NULL, 'h' },
		{ "version", no_argument, NULL, 'V' },
		{ "text", no_argument, NULL, 't' },
		{ "binary", no_argument, NULL, 'b' },
		{ "frames", required_argument, NULL, 'F' },
		{ NULL, 0, NULL, 0 }
	};
	if (argc >= 2 && strcmp(argv[1], "--help") == 0) {
		fputs(usage_text, stdout);
		return stdout_status();
	}
	if (argc >= 2 && strcmp(argv[1], "--version") == 0) {
		printf("locus-meta %s (meta-language version %d)\n", LOCUS_VERSION, META_VERSION);
		return stdout_status();
	}
	if (argc < 2)
		return usage("missing subcommand");
	if (strcmp(argv[1], "import") == 0)
		return mimp_main(argc - 1, argv + 1);   /* its own options: drivers/import_svg_cli.c */
	if (argv[1][0] == '-')
		return usage("the subcommand comes first");
	sub = argv[1];
	/* the subcommand's options and file names, parsed after it (argv[1] is getopt's name) */
	opterr = 0;
	optind = 1;
	while ((c = getopt_long(argc - 1, argv + 1, ":o:", longopts, NULL)) != -1) {
		switch (c) {
		case 'h':
			fputs(usage_text, stdout);
			return stdout_status();
		case 'V':
			printf("locus-meta %s (meta-language version %d)\n", LOCUS_VERSION, META_VERSION);
			return stdout_status();
		case 'o':
			out = optarg;
			break;
		case 't': case 'b':
			if (strcmp(sub, "convert") != 0 && strcmp(sub, "cat") != 0)
				return usage("--text and --binary belong to 'convert' and 'cat'");
			enc = c == 't' ? META_ENC_TEXT : META_ENC_BINARY;
			break;
		case 'F':
			if (strcmp(sub, "cat") != 0)
				return usage("--frames belongs to 'cat'");
			frames = optarg;
			break;
		case ':':
			fprintf(stderr, "locus-meta: option '%s' needs an argument\n", argv[optind]);
			return usage(NULL);
		default:
			fprintf(stderr, "locus-meta: unknown option '%s'\n", argv[optind]);
			return usage(NULL);
		}
	}
	if (strcmp(sub, "cat") == 0) {
		if (optind + 1 >= argc)
			return usage("cat: missing FILES");
		return cmd_cat(argv + optind + 1, (size_t)(argc - optind - 1), frames, out, enc);
	}
	for (int i = optind + 1; i < argc; i++) {
		if (in)
			return usage("too many file names");
		in = argv[i];
	}
	if (strcmp(sub, "check") == 0 || strcmp(sub, "info") == 0) {
		if (!in || out)
			return usage(out ? "-o does not apply here" : "missing FILE");
		return sub[0] == 'c' ? cmd_check(in) : cmd_info(in);
	}
	if (strcmp(sub, "fmt") == 0)
		return cmd_copy(in ? in : "-", out, META_ENC_TEXT);
	if (strcmp(sub, "convert") == 0)
		return cmd_copy(in ? in : "-", out, enc);
	fprintf(stderr, "locus-meta: unknown subcommand '%s'\n", sub);
	return usage(NULL);
}
