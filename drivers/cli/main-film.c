/* main-film.c: locus-film, meta file to film-recorder frames (DPX, Cineon, RLE) at film size. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "cli/cli.h"
#include "meta_frames.h"
#include "device/device.h"
#include "film/filmenc.h"
#include "cli/run.h"

static const char usage_text[] =
	"usage: locus-film [-o OUT] [-f dpx|dpx16|cineon|rle] [--preset NAME | --size WxH] [IN]\n"
	"Replay a Locus meta file (IN, default stdin) into film-recorder frames at the film's own\n"
	"resolution: the page is fitted with its aspect kept and scan-converted at frame size.\n"
	"OUT defaults to stdout; with several pages, page k goes to OUT with -00k before its suffix;\n"
	"OUT as a frame pattern (NAME-%04d.dpx) names each file by its frame number.\n"
	"  -f, --format F        dpx (DPX 2.0, 10-bit printing density, default), dpx16 (16-bit\n"
	"                        linear DPX), cineon (Cineon 4.5, 10-bit log), rle; default: OUT's suffix\n"
	"  --preset NAME         slide4k (4096x2730, default), slide8k, 2k, 4k, 6x7\n"
	"  --list-presets        print the presets and exit\n"
	"  --size WxH            a custom frame size in pixels\n"
	"  --endian big|little   byte order of a DPX file (default big)\n"
	"  --fit aspect|fill|stretch   how the page meets the frame (default aspect)\n"
	"  --letterbox #RRGGBB   colour of the bars around a fitted page (default #000000)\n"
	"  --antialias K         K x K samples per film pixel, averaged (default: exact, 1 sample)\n"
	"  --white N, --black N  reference white and black code values (685, 95)\n"
	"  --density D           printing density per code value (0.002)\n"
	"  --film-gamma G, --display-gamma G   (0.6, 1.7)\n"
	"  --calibration FILE    per-channel calibration curve applied before encoding (docs/film.md)\n"
	"  --separations[=files|planar]  red, green and blue exposures: three single-channel files\n"
	"                        OUT-r, OUT-g, OUT-b (default), or one planar file\n"
	"  --frame-rate R        frames a second in every header, with each frame's time code (24)\n"
	"  --first-frame N       the frame number of the first page (default: the input's frame\n"
	"                        records, as locus-render --frames writes them, else 1)\n"
	"  --skip-existing       with a frame pattern: leave each frame whose file is there and\n"
	"                        whole; only the others are scan-converted (a farm's rerun)\n"
	"  -O KEY=VALUE[,...]    device options (the long options above, as locus-play -d film takes)\n"
	"  --band-rows N, --mem-budget MIB   banding of the frame (default: an 8 MiB page buffer)\n"
	"  --help, --version\n"
	"SOURCE_DATE_EPOCH, when set, is the time stamp written into every header.\n";

enum { O_PRESET = 0x2000, O_LIST, O_SIZE, O_ENDIAN, O_FIT, O_LETTERBOX, O_WHITE, O_BLACK, O_DENSITY,
	O_FGAMMA, O_DGAMMA, O_CAL, O_SEP, O_AA, O_RATE, O_FIRST, O_SKIP };

static const struct option film_long[] = {
	{ "format", required_argument, NULL, 'f' },
	{ "preset", required_argument, NULL, O_PRESET },
	{ "list-presets", no_argument, NULL, O_LIST },
	{ "size", required_argument, NULL, O_SIZE },
	{ "endian", required_argument, NULL, O_ENDIAN },
	{ "fit", required_argument, NULL, O_FIT },
	{ "letterbox", required_argument, NULL, O_LETTERBOX },
	{ "white", required_argument, NULL, O_WHITE },
	{ "black", required_argument, NULL, O_BLACK },
	{ "density", required_argument, NULL, O_DENSITY },
	{ "film-gamma", required_argument, NULL, O_FGAMMA },
	{ "display-gamma", required_argument, NULL, O_DGAMMA },
	{ "calibration", required_argument, NULL, O_CAL },
	{ "separations", optional_argument, NULL, O_SEP },
	{ "frame-rate", required_argument, NULL, O_RATE },
	{ "first-frame", required_argument, NULL, O_FIRST },
	{ "skip-existing", no_argument, NULL, O_SKIP },
	{ NULL, 0, NULL, 0 }
};

/* The page buffer budget unless --mem-budget says otherwise: a frame is written in bands of
 * about 8 MiB (340 rows of 8192 pixels), so a whole process stays near 11 MiB at any preset;
 * measured no slower than one 64 MiB buffer (docs/film.md). */
#define FILM_BUDGET_MIB 8

typedef struct {
	const char *cal;
	int separations;          /* 0 none, 1 three files, 2 planar */
	int first_given;          /* --first-frame (or -O first-frame=) */
	int skip_existing;        /* --skip-existing */
} film_args_t;

static int on_option(cli_t *c, int key, const char *arg)
{
	film_args_t *a = c->user;
	unsigned w, h;
	switch (key) {
	case 'f':
		if (film_kind_by_name(arg) < 0)
			return cli_fail(c, 64, "unknown format '%s' (dpx, dpx16, cineon or rle)", arg);
		return cli_set_option(c, "format", arg) ? 64 : CLI_RUN;
	case O_LIST:
		for (const film_preset_t *p = film_presets; p->name; p++)
			printf("%-8s %5ux%-5u %6.2f x %5.2f mm  %s\n", p->name, p->width, p->height, p->width_mm,
				p->height_mm, p->description);
		return 0;
	case O_PRESET:
		if (!film_preset_find(arg))
			return cli_fail(c, 64, "unknown preset '%s' (--list-presets lists them)", arg);
		return cli_set_option(c, "preset", arg) ? 64 : CLI_RUN;
	case O_SIZE:
		if (film_parse_size(arg, &w, &h))
			return cli_fail(c, 64, "--size needs WxH with each side 1 to %d pixels, not '%s'",
				META_MAX_DIM, arg);
		return cli_set_option(c, "size", arg) ? 64 : CLI_RUN;
	case O_CAL:
		a->cal = arg;
		return cli_set_option(c, "calibration", arg) ? 64 : CLI_RUN;
	case O_RATE:
		return cli_set_option(c, "frame-rate", arg) ? 64 : CLI_RUN;
	case O_FIRST:
		a->first_given = 1;
		return cli_set_option(c, "first-frame", arg) ? 64 : CLI_RUN;
	case O_SKIP:
		a->skip_existing = 1;
		return CLI_RUN;
	case O_SEP:
		if (!arg || !strcmp(arg, "files"))
			a->separations = 1;
		else if (!strcmp(arg, "planar"))
			a->separations = 2;
		else
			return cli_fail(c, 64, "--separations takes files or planar, not '%s'", arg);
		return CLI_RUN;
	default: {
		static const char *const keys[] = { "endian", "fit", "letterbox", "white", "black", "density",
			"film-gamma", "display-gamma" };
		if (key >= O_ENDIAN && key <= O_DGAMMA)
			return cli_set_option(c, keys[key - O_ENDIAN], arg) ? 64 : CLI_RUN;
		return cli_fail(c, 64, "unhandled option");
	}
	}
}

/* "out.dpx", "r" -> "out-r.dpx" (malloc'd) */
static char *separation_name(const char *out, const char *tag)
{
	const char *dot = strrchr(out, '.'), *slash = strrchr(out, '/');
	if (!dot || (slash && dot < slash) || dot == out || (slash && dot == slash + 1))
		dot = out + strlen(out);
	size_t n = strlen(out) + strlen(tag) + 2;
	char *s = malloc(n);
	if (s)
		snprintf(s, n, "%.*s-%s%s", (int)(dot - out), out, tag, dot);
	return s;
}

static int report(int st, const char *err)
{
	if (st == 65)
		fprintf(stderr, "%s\n", err);   /* already "FILE:LINE:COL: ..." or "FILE: byte N: ..." */
	else if (st)
		fprintf(stderr, "locus-film: %s\n", err);
	return st;
}

/* The frame numbers of the input's pages from its frame records (locus-render --frames): the
 * first and the step between pages, and the page count (-1 when not known: stdin, no records).
 * A file with records is read here once more in full (their numbers and its page count).
 * Pages are numbered 1, 2, ... when the input says nothing. 0, or an exit status with err. */
static int frame_numbers(const char *in, long *first, long *step, long *npages, char *err, size_t errlen)
{
	*first = 1, *step = 1, *npages = -1;
	if (!strcmp(in, "-") || !meta_frames_probe(in))
		return 0;   /* no records: no second reading of a large file */
	meta_frames_t fs;
	if (meta_frames_scan(in, &fs, err, errlen))
		return 0;   /* a bad input is refused by the replay, with the message the other programs give */
	*npages = (long)fs.pages;
	int st = 0;
	if (fs.records && fs.pages != fs.n) {
		snprintf(err, errlen, "%s: %lu pages in %zu frames: a frame of several pages has no one frame number"
			" (number the pages with --first-frame)", in, fs.pages, fs.n);
		st = 65;
	} else if (fs.records) {
		*first = fs.frames[0];
		*step = fs.n > 1 ? fs.frames[1] - fs.frames[0] : 1;
		for (size_t k = 1; k < fs.n && !st; k++)
			if (fs.frames[k] - fs.frames[k - 1] != *step || *step < 1) {
				snprintf(err, errlen, "%s: frames %ld, %ld and %ld are not evenly spaced: split the file"
					" where the step changes (or number the pages with --first-frame)", in,
					fs.frames[k > 1 ? k - 2 : 0], fs.frames[k - 1], fs.frames[k]);
				st = 65;
			}
	}
	meta_frames_free(&fs);
	return st;
}

/* KEY=N of the device options (key "first-frame" or "frame-step"), when given there: *v, 0;
 * -1 when it is not a number 0 to 9999999. */
static int dev_frame_option(const char *opts, const char *key, long *v)
{
	size_t k = strlen(key);
	const char *p = opts;
	while ((p = strstr(p, key)) && ((p != opts && p[-1] != ',') || p[k] != '='))
		p += k;
	if (!p)
		return 0;
	char *e;
	errno = 0;
	long x = strtol(p + k + 1, &e, 10);
	if (errno || x < 0 || x > 9999999 || (*e && *e != ','))
		return -1;
	*v = x;
	return 0;
}

/* OUT a frame pattern: page k is frame first + k x step, in the file the pattern names. A single
 * page (the usual file of one frame from a farm) is written straight to its name; several go to
 * a private directory beside OUT and are renamed to their names when all replayed, each file
 * whole. */
static int run_pattern(cli_t *c, const char *in, const char *out, long first, long step, long npages, char *err,
		size_t errlen)
{
	if (npages == 1) {
		char *name = meta_frame_pattern_name(out, first);
		if (!name) {
			snprintf(err, errlen, "out of memory");
			return 70;
		}
		dev_job_t job = { in, name, &dev_film_ops, c->band_rows, c->budget, c->options };
		int st = dev_run(&job, err, errlen);
		free(name);
		return st;
	}
	const char *slash = strrchr(out, '/'), *dot = strrchr(out, '.');
	if (dot && slash && dot < slash)
		dot = NULL;
	size_t n = strlen(out) + 64;
	char *dir = malloc(n), *tmp = malloc(n);
	if (!dir || !tmp) {
		free(dir), free(tmp);
		snprintf(err, errlen, "out of memory");
		return 70;
	}
	snprintf(dir, n, "%.*s.locus-film.XXXXXX", slash ? (int)(slash - out + 1) : 0, out);
	if (!mkdtemp(dir)) {
		snprintf(err, errlen, "%s: cannot make a directory for the frames: %s", dir, strerror(errno));
		free(dir), free(tmp);
		return 74;
	}
	snprintf(tmp, n, "%s/frame%s", dir, dot ? dot : "");
	dev_job_t job = { in, tmp, &dev_film_ops, c->band_rows, c->budget, c->options };
	int st = dev_run(&job, err, errlen);
	/* the pages written: tmp alone, or tmp-001 ... */
	for (unsigned k = 1; st == 0; k++) {
		char *from = k == 1 && access(tmp, F_OK) == 0 ? strdup(tmp) : dev_page_name(tmp, k);
		char *to = meta_frame_pattern_name(out, first + (long)(k - 1) * step);
		if (!from || !to) {
			snprintf(err, errlen, "out of memory");
			st = 70;
		} else if (access(from, F_OK) != 0) {
			free(from), free(to);
			break;
		} else if (rename(from, to)) {
			snprintf(err, errlen, "%s: cannot rename into place: %s", to, strerror(errno));
			st = 74;
		}
		int single = k == 1 && from && !strcmp(from, tmp);
		free(from), free(to);
		if (single)
			break;
	}
	/* what a failure left behind */
	for (unsigned k = 1; k < 100000; k++) {
		char *f = dev_page_name(tmp, k);
		int gone = !f || (unlink(f) && errno == ENOENT);
		free(f);
		if (gone)
			break;
	}
	unlink(tmp);
	rmdir(dir);
	free(dir), free(tmp);
	return st;
}

static int fd_write(void *user, const void *buf, size_t n)
{
	FILE *f = user;
	return fwrite(buf, 1, n, f) == n ? 0 : -1;
}

static int meta_status(int rc)
{
	return rc == META_ENOMEM ? 70 : rc == META_EIO ? 74 : 65;
}

/* Pages k0 .. k1 (0-based) of the meta file in, as a binary meta file of their own at tmp. 0, or
 * an exit status with err. */
static int extract_pages(const char *in, long k0, long k1, const char *tmp, char *err, size_t errlen)
{
	meta_reader_t *r = meta_reader_open(in, err, errlen);
	if (!r)
		return errno == ENOMEM ? 70 : 66;
	FILE *f = fopen(tmp, "wb");
	meta_writer_t *w = f ? meta_writer_new(fd_write, f, META_ENC_BINARY) : NULL;
	int st = 0, rc = 0;
	long page = -1;
	int inside = 0;
	meta_cmd_t c;
	if (!w) {
		snprintf(err, errlen, "%s: cannot write: %s", tmp, f ? "out of memory" : strerror(errno));
		st = f ? 70 : 74;
	}
	while (!st && page <= k1 && (rc = meta_read(r, &c)) > 0) {
		if (c.op == META_PAGE)
			page++, inside = 1;
		if (inside && page >= k0 && page <= k1 && (rc = meta_write(w, &c)) < 0) {
			snprintf(err, errlen, "%s: %s", tmp, meta_writer_error(w));
			st = meta_status(rc);
		}
		if (c.op == META_END_PAGE)
			inside = 0;
	}
	if (!st && rc < 0) {
		snprintf(err, errlen, "%s", meta_reader_error(r));
		st = meta_status(rc);
	}
	if (w && meta_writer_close(w) < 0 && !st) {
		snprintf(err, errlen, "%s: write failed", tmp);
		st = 74;
	}
	if (f && fclose(f) && !st) {
		snprintf(err, errlen, "%s: write failed: %s", tmp, strerror(errno));
		st = 74;
	}
	meta_reader_free(r);
	return st;
}

/* --skip-existing with a frame pattern: page k is frame first + k x step; the frames whose files
 * are there and whole (film_file_complete) are left alone, each run of consecutive missing pages
 * is copied to a meta file of its own beside OUT and replayed with its own first frame, so the
 * headers carry the frame numbers one run of the whole file would have written. */
static int run_skipping(cli_t *c, const char *out, long first, long step, long npages, char *err, size_t errlen)
{
	if (npages < 0) {   /* the page count, when frame_numbers did not read it */
		meta_frames_t fs;
		int rc = meta_frames_scan(c->in[0], &fs, err, errlen);
		if (rc)
			return rc == -66 ? 66 : rc == -70 ? 70 : rc == -74 ? 74 : 65;
		npages = (long)fs.pages;
		meta_frames_free(&fs);
	}
	unsigned char *need = calloc((size_t)npages + 1, 1);
	if (!need) {
		snprintf(err, errlen, "out of memory");
		return 70;
	}
	long nneed = 0;
	char why[600];
	for (long k = 0; k < npages; k++) {
		long fr = first + k * step;
		char *name = meta_frame_pattern_name(out, fr);
		if (!name) {
			free(need);
			snprintf(err, errlen, "out of memory");
			return 70;
		}
		int done = film_file_complete(name, fr, why, sizeof why);
		if (done == 0)
			fprintf(stderr, "locus-film: frame %ld: %s: made again\n", fr, why);
		need[k] = done != 1;
		nneed += done != 1;
		free(name);
	}
	int st = 0;
	if (nneed == npages) {
		st = run_pattern(c, c->in[0], out, first, step, npages, err, errlen);
	} else if (nneed) {
		const char *slash = strrchr(out, '/');
		size_t n = strlen(out) + 64;
		char *tmp = malloc(n);
		if (!tmp) {
			free(need);
			snprintf(err, errlen, "out of memory");
			return 70;
		}
		for (long k = 0; k < npages && !st;) {
			if (!need[k]) {
				k++;
				continue;
			}
			long k1 = k;
			while (k1 + 1 < npages && need[k1 + 1])
				k1++;
			snprintf(tmp, n, "%.*s.locus-film-pages.XXXXXX", slash ? (int)(slash - out + 1) : 0, out);
			int fd = mkstemp(tmp);
			if (fd < 0) {
				snprintf(err, errlen, "%s: cannot make a file for the missing frames: %s", tmp, strerror(errno));
				st = 74;
				break;
			}
			close(fd);
			char v[24];
			st = extract_pages(c->in[0], k, k1, tmp, err, errlen);
			snprintf(v, sizeof v, "%ld", first + k * step);
			if (!st && cli_set_option(c, "first-frame", v))
				st = 64;
			snprintf(v, sizeof v, "%ld", step);
			if (!st && cli_set_option(c, "frame-step", v))
				st = 64;
			if (!st)
				st = run_pattern(c, tmp, out, first + k * step, step, k1 - k + 1, err, errlen);
			unlink(tmp);
			k = k1 + 1;
		}
		free(tmp);
	}
	if (!st)
		fprintf(stderr, "locus-film: %ld of %ld frames were there and whole, %ld made\n", npages - nneed, npages,
			nneed);
	free(need);
	return st;
}

int main(int argc, char **argv)
{
	film_args_t a = { NULL, 0, 0, 0 };
	cli_t c;
	memset(&c, 0, sizeof c);
	c.prog = "locus-film";
	c.usage = usage_text;
	c.extra = film_long;
	c.extra_short = "f:";
	c.on_option = on_option;
	c.user = &a;
	int st = cli_parse(&c, argc, argv);
	if (st != CLI_RUN)
		return st;
	const char *out = c.out ? c.out : "-";
	char err[700];
	if (!c.budget)
		c.budget = (size_t)FILM_BUDGET_MIB << 20;
	int has_format = !strncmp(c.options, "format=", 7) || strstr(c.options, ",format=");
	if (!has_format && strcmp(out, "-")) {   /* the suffix's format, known to the device from open() */
		static const char *const names[] = { "dpx", "dpx16", "cineon", "rle" };
		int k = film_kind_by_suffix(out);
		if (k >= 0 && cli_set_option(&c, "format", names[k]))
			return 64;
	}
	if (a.cal) {   /* checked here first so that a bad file is 65 (66: missing) naming only itself */
		film_cal_t *cal = NULL;
		int rc = film_cal_load(a.cal, &cal, err, sizeof err);
		film_cal_free(cal);
		if (rc) {
			fprintf(stderr, "%s\n", err);
			return rc == -66 ? 66 : rc == -70 ? 70 : 65;
		}
	}
	int64_t t;
	if (film_source_time(&t, err, sizeof err))
		return cli_fail(&c, 64, "%s", err);
	if (a.separations == 2 && cli_set_option(&c, "separations", "planar"))
		return 64;
	int pattern = meta_frame_pattern_check(out, err, sizeof err);
	if (pattern < 0)
		return cli_fail(&c, 64, "%s", err);
	if (pattern && a.separations == 1)
		return cli_fail(&c, 64, "--separations=files and a frame pattern: give one of them (or "
			"--separations=planar)");
	if (a.skip_existing && !pattern)
		return cli_fail(&c, 64, "--skip-existing works frame by frame: give -o a frame pattern (NAME-%%04d.dpx)");
	if (a.skip_existing && !strcmp(c.in[0], "-"))
		return cli_fail(&c, 64, "--skip-existing reads the input again for the missing frames: give a file, not stdin");
	long first = 1, step = 1, npages = -1;
	if (!a.first_given && !strstr(c.options, "first-frame=")) {
		st = frame_numbers(c.in[0], &first, &step, &npages, err, sizeof err);
		if (st)
			return report(st, err);
		char v[24];
		snprintf(v, sizeof v, "%ld", first);
		if (cli_set_option(&c, "first-frame", v))
			return 64;
		snprintf(v, sizeof v, "%ld", step);
		if (cli_set_option(&c, "frame-step", v))
			return 64;
	} else if (dev_frame_option(c.options, "first-frame", &first) || dev_frame_option(c.options, "frame-step", &step)
			|| step < 1) {
		return cli_fail(&c, 64, "--first-frame needs a frame number 0 to 9999999 (and frame-step 1 to 9999999)");
	}
	if (pattern && a.skip_existing)
		return report(run_skipping(&c, out, first, step, npages, err, sizeof err), err);
	if (pattern)
		return report(run_pattern(&c, c.in[0], out, first, step, npages, err, sizeof err), err);
	if (a.separations != 1) {
		dev_job_t job = { c.in[0], out, &dev_film_ops, c.band_rows, c.budget, c.options };
		return report(dev_run(&job, err, sizeof err), err);
	}
	if (!strcmp(out, "-"))
		return cli_fail(&c, 64, "--separations=files needs -o OUT (three files OUT-r, OUT-g, OUT-b);"
			" --separations=planar writes one file to stdout");
	if (!strcmp(c.in[0], "-"))
		return cli_fail(&c, 64, "--separations=files replays the input three times: give a file, not stdin");
	static const char *const tags[3] = { "r", "g", "b" };
	char *names[3] = { NULL, NULL, NULL };
	st = 0;
	int done = 0;
	for (int k = 0; k < 3 && st == 0; k++) {
		if (!(names[k] = separation_name(out, tags[k])) || cli_set_option(&c, "channel", tags[k])) {
			snprintf(err, sizeof err, "out of memory");
			st = 70;
			break;
		}
		dev_job_t job = { c.in[0], names[k], &dev_film_ops, c.band_rows, c.budget, c.options };
		st = dev_run(&job, err, sizeof err);
		done += st == 0;
	}
	for (int k = 0; k < 3; k++) {
		if (st && k < done)
			remove(names[k]);   /* no partial set of separations (single-page names) */
		free(names[k]);
	}
	return report(st, err);
}
