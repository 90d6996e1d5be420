/* main-hpgl.c: locus-hpgl, a meta file to HP-GL or HP-GL/2 for pen plotters and cutters. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <unistd.h>
#include "cli/cli.h"
#include "hpgl/hpgl.h"
#include "hpgl/read/hpgl_read.h"
#include "cli/run.h"

extern const dev_ops_t dev_hpgl_ops;

static const char usage[] =
	"usage: locus-hpgl [-o OUT] [--profile NAME|FILE] [--paper P] [--pens SPEC|FILE] [options] [IN]\n"
	"       locus-hpgl --list-profiles\n"
	"Replay a Locus meta file (IN, default stdin) as HP-GL or HP-GL/2 into OUT (default stdout):\n"
	"integer plotter units (0.025 mm), pens grouped and paths ordered to cut pen-up travel.\n"
	"  --profile NAME|FILE  7475a (default), 7550a, draftpro, hpgl2, cutter, or a profile file\n"
	"  --list-profiles      print the built-in profiles and exit\n"
	"  --paper P            a4, a3, letter or b (default: the profile's)\n"
	"  --rotate DEG         0, 90, 180 or 270    --mirror none|x|y\n"
	"  --fit auto|yes|no    shrink when too big (auto), fill the paper, or physical size\n"
	"  --scale F            factor on the page's physical size (default 1)\n"
	"  --pens SPEC|FILE     carousel, e.g. 1=black,2=red:0.3mm,3=#008000 (or a file of such lines)\n"
	"  --no-optimize        keep the file's order, pens included, and stream (no page in memory)\n"
	"  --fill hatch|native|outline|none  --text strokes|label   --raster hatch|skip\n"
	"  --pen N:speed=CM/S,force=F,accel=A,pause  settings of pen N, sent with its SP (VS, FS, AS;\n"
	"                       FS/AS where the profile has them); repeat for more pens\n"
	"  --pause-at-pen N[,M] before pen N is loaded: pen up, everything sent, then ask on the\n"
	"                       terminal (/dev/tty) to load it: Enter goes on, s stops (exit 75;\n"
	"                       with --journal FILE, --resume FILE goes on with the new pen)\n"
	"  --pause-pens         a pause before every pen change (a plotter with one pen holder)\n"
	"  --no-prompt          ask nobody: a pause is a stop (batch jobs)\n"
	"  --estimate           print the expected plot time per pen and in total (no OUT: no HP-GL)\n"
	"  --stats, -v          print pen-up travel before/after, pen lifts and pen changes to stderr\n"
	"  --analyse            IN is HP-GL: print its pen-down length, pen-up travel, lifts, pen changes\n"
	"                       and the profile's plot-time estimate (hpgl_read); --length MM first scales\n"
	"                       it to that pen-down length (to compare files of other programs)\n"
	"  -O KEY=VALUE,...     device options (locus-play -d hpgl -O ...): profile paper rotate mirror\n"
	"                       fit scale pens optimize merge simplify budget fill hatch hatch-angle\n"
	"                       outline text raster background wide dash pcl knife overcut (docs/hpgl.md)\n"
	"  --help, --version\n";

enum { O_PROFILE = 0x2000, O_LIST, O_PAPER, O_ROTATE, O_MIRROR, O_FIT, O_SCALE, O_PENS, O_NOOPT,
	O_FILL, O_TEXT, O_RASTER, O_ESTIMATE, O_STATS, O_ANALYSE, O_LENGTH, O_PEN, O_PAUSE_AT, O_PAUSE_ALL,
	O_NOPROMPT };

static const struct option longopts[] = {
	{ "profile", required_argument, NULL, O_PROFILE },
	{ "list-profiles", no_argument, NULL, O_LIST },
	{ "paper", required_argument, NULL, O_PAPER },
	{ "rotate", required_argument, NULL, O_ROTATE },
	{ "mirror", required_argument, NULL, O_MIRROR },
	{ "fit", required_argument, NULL, O_FIT },
	{ "scale", required_argument, NULL, O_SCALE },
	{ "pens", required_argument, NULL, O_PENS },
	{ "no-optimize", no_argument, NULL, O_NOOPT },
	{ "fill", required_argument, NULL, O_FILL },
	{ "text", required_argument, NULL, O_TEXT },
	{ "raster", required_argument, NULL, O_RASTER },
	{ "estimate", no_argument, NULL, O_ESTIMATE },
	{ "stats", no_argument, NULL, O_STATS },
	{ "analyse", no_argument, NULL, O_ANALYSE },
	{ "length", required_argument, NULL, O_LENGTH },
	{ "pen", required_argument, NULL, O_PEN },
	{ "pause-at-pen", required_argument, NULL, O_PAUSE_AT },
	{ "pause-pens", no_argument, NULL, O_PAUSE_ALL },
	{ "no-prompt", no_argument, NULL, O_NOPROMPT },
	{ 0, 0, 0, 0 }
};

typedef struct {
	int estimate, stats, analyse;
	int no_prompt;              /* --no-prompt: a pause is a stop */
	double length;              /* --length MM, 0 = as is */
	char profile[1024];
	FILE *est;                  /* where the estimate goes */
	/* what goes to stderr while the job runs (warnings, --stats, an --estimate on stderr),
	 * held until it succeeds: a failing run prints only its one line of error */
	FILE *held;
	char *heldbuf;
	size_t heldlen;
} prog_t;

static void list_profiles(void)
{
	for (size_t k = 0; k < hpgl_profile_count(); k++) {
		const hpgl_profile_t *p = hpgl_profile_builtin(k);
		printf("%-9s %-6s %u pens, %u pairs/command, paper", p->name, p->dialect == 2 ? "HP-GL/2" : "HP-GL",
			p->npens, p->max_pairs);
		for (int q = 0; q < HPGL_NPAPER; q++)
			if (p->has_paper[q])
				printf(" %s%s %dx%d", hpgl_paper_name(q), q == p->paper ? "*" : "",
					p->clip[q][2] - p->clip[q][0], p->clip[q][3] - p->clip[q][1]);
		printf("  %s\n", p->description);
	}
}

/* --pens FILE: the file's pens joined by ';' (device option values hold no ','). */
static int pens_value(cli_t *c, const char *arg, char *out, size_t n)
{
	if (strchr(arg, '=')) {
		snprintf(out, n, "%s", arg);
	} else {
		FILE *f = fopen(arg, "r");
		if (!f)
			return cli_fail(c, 66, "--pens %s: %s", arg, strerror(errno));
		size_t k = fread(out, 1, n - 1, f);
		int big = !feof(f);
		fclose(f);
		if (big)
			return cli_fail(c, 65, "--pens %s: pen file longer than %zu bytes", arg, n - 1);
		out[k] = 0;
		if (memchr(out, 0, k))
			return cli_fail(c, 65, "--pens %s: NUL byte in the pen file", arg);
		/* comments off, lines joined */
		char *w = out;
		for (char *r = out; *r;) {
			if (*r == '#') {
				while (*r && *r != '\n')
					r++;
				continue;
			}
			*w++ = *r == '\n' || *r == '\r' ? ';' : *r;
			r++;
		}
		*w = 0;
	}
	for (char *p = out; *p; p++)
		if (*p == ',')
			*p = ';';
	hpgl_pens_t pens;
	char err[256];
	if (hpgl_pens_parse(out, 0.3, &pens, err, sizeof err))
		return cli_fail(c, strchr(arg, '=') ? 64 : 65, "%s%s%s", strchr(arg, '=') ? "" : arg,
			strchr(arg, '=') ? "" : ": ", err);
	return CLI_RUN;
}

static int on_option(cli_t *c, int key, const char *arg)
{
	prog_t *p = c->user;
	static char pens[1024];
	switch (key) {
	case O_PROFILE:
		snprintf(p->profile, sizeof p->profile, "%s", arg);
		return cli_set_option(c, "profile", arg) ? 64 : CLI_RUN;
	case O_ANALYSE: p->analyse = 1; return CLI_RUN;
	case O_LENGTH: {
		char *e;
		p->length = strtod(arg, &e);
		if (e == arg || *e || !(p->length > 0))
			return cli_fail(c, 64, "--length needs a pen-down length in mm, not '%s'", arg);
		return CLI_RUN;
	}
	case O_LIST: list_profiles(); return 0;
	case O_PAPER: return cli_set_option(c, "paper", arg) ? 64 : CLI_RUN;
	case O_ROTATE: return cli_set_option(c, "rotate", arg) ? 64 : CLI_RUN;
	case O_MIRROR: return cli_set_option(c, "mirror", arg) ? 64 : CLI_RUN;
	case O_FIT: return cli_set_option(c, "fit", arg) ? 64 : CLI_RUN;
	case O_SCALE: return cli_set_option(c, "scale", arg) ? 64 : CLI_RUN;
	case O_PENS: {
		int st = pens_value(c, arg, pens, sizeof pens);
		if (st != CLI_RUN)
			return st;
		return cli_set_option(c, "pens", pens) ? 64 : CLI_RUN;
	}
	case O_NOOPT: return cli_set_option(c, "optimize", "no") ? 64 : CLI_RUN;
	case O_FILL: return cli_set_option(c, "fill", arg) ? 64 : CLI_RUN;
	case O_TEXT: return cli_set_option(c, "text", arg) ? 64 : CLI_RUN;
	case O_RASTER: return cli_set_option(c, "raster", arg) ? 64 : CLI_RUN;
	case O_PEN: case O_PAUSE_AT: {
		/* repeated options add up: pen=N:..;../N:.. and pause=N;M (device option values hold no ',') */
		static char pen[1024], pause[512];
		char *buf = key == O_PEN ? pen : pause, one[512];
		size_t cap = key == O_PEN ? sizeof pen : sizeof pause;
		snprintf(one, sizeof one, "%s", arg);
		for (char *q = one; *q; q++)
			if (*q == ',' || *q == '/')
				*q = key == O_PEN && *q == '/' ? '/' : ';';
		hpgl_penset_t set[HPGL_MAX_PENS + 1];
		char err[300];
		int all = 0;
		memset(set, 0, sizeof set);
		if (key == O_PEN ? hpgl_penset_parse(one, set, err, sizeof err) : hpgl_pause_parse(one, set, &all, err, sizeof err))
			return cli_fail(c, 64, "--%s %s: %s", key == O_PEN ? "pen" : "pause-at-pen", arg, err);
		size_t n = strlen(buf);
		if (n + strlen(one) + 2 > cap)
			return cli_fail(c, 64, "--%s: too many settings", key == O_PEN ? "pen" : "pause-at-pen");
		snprintf(buf + n, cap - n, "%s%s", n ? (key == O_PEN ? "/" : ";") : "", one);
		return cli_set_option(c, key == O_PEN ? "pen" : "pause", buf) ? 64 : CLI_RUN;
	}
	case O_PAUSE_ALL: return cli_set_option(c, "pause", "all") ? 64 : CLI_RUN;
	case O_NOPROMPT: p->no_prompt = 1; return CLI_RUN;
	case O_ESTIMATE: p->estimate = 1; return CLI_RUN;
	case O_STATS: case 'v': p->stats = 1; return CLI_RUN;
	default: return 64;
	}
}

static void fmt_time(char *s, size_t n, double t)
{
	if (!(t < 1e9))
		t = 1e9;   /* a time beyond int (or NaN) would be undefined when cast: say 31 years */
	if (t >= 3600)
		snprintf(s, n, "%dh%02dm%02ds", (int)(t / 3600), (int)(t / 60) % 60, (int)t % 60);
	else if (t >= 60)
		snprintf(s, n, "%dm%04.1fs", (int)(t / 60), t - 60 * (int)(t / 60));
	else
		snprintf(s, n, "%.1fs", t);
}

static void report(void *user, const hpgl_report_t *r)
{
	prog_t *p = user;
	FILE *err = p->held ? p->held : stderr;
	FILE *est = p->est == stderr ? err : p->est;
	if (r->warning) {
		fprintf(err, "locus-hpgl: warning: %s\n", r->warning);
		return;
	}
	if (p->stats) {
		fprintf(err, "locus-hpgl: page %u (%s): pen-up travel %.1f mm -> %.1f mm (greedy %.1f mm, "
			"%.1fx less), %llu pen lifts, %llu pen changes, optimiser %.3f s, %llu bytes, box %.0f,%.0f,%.0f,%.0f\n",
			r->page + 1, r->profile, r->travel_before_mm, r->travel_after_mm, r->travel_greedy_mm,
			r->travel_after_mm > 0 ? r->travel_before_mm / r->travel_after_mm : 1.0,
			(unsigned long long)r->pen_lifts, (unsigned long long)r->pen_changes, r->optimise_s,
			(unsigned long long)r->bytes, r->box[0], r->box[1], r->box[2], r->box[3]);
		for (size_t k = 0; k < r->npens; k++)
			fprintf(err, "locus-hpgl:   pen %d: %zu paths -> %zu, travel %.1f mm -> %.1f mm\n",
				r->pen[k].slot, r->pen[k].paths_in, r->pen[k].paths_out, r->pen[k].travel_before_mm,
				r->pen[k].travel_after_mm);
	}
	if (p->estimate) {
		char t[32];
		for (size_t k = 0; k < r->npens; k++) {
			const hpgl_time_t *q = &r->pen[k].time;
			fmt_time(t, sizeof t, q->down_s + q->up_s + q->lift_s);
			fprintf(est, "estimate page %u pen %d: %s (drawing %.0f mm in %.1f s, travel %.0f mm in %.1f s, "
				"%llu lifts in %.1f s)\n", r->page + 1, r->pen[k].slot, t, q->down_mm, q->down_s, q->up_mm,
				q->up_s, (unsigned long long)q->lifts, q->lift_s);
		}
		fmt_time(t, sizeof t, r->plot_s);
		fprintf(est, "estimate page %u total: %s (%.1f s, %llu pen changes)\n", r->page + 1, t, r->plot_s,
			(unsigned long long)r->pen_changes);
	}
}

/* A pause before a pen: ask on the terminal (/dev/tty: standard input may be the meta file).
 * Enter goes on; s, the end of the terminal, an interrupt, no terminal or --no-prompt stop. */
static int ask_pen(void *user, const hpgl_pause_t *q, char *why, size_t whylen)
{
	const prog_t *p = user;
	if (p->no_prompt) {
		snprintf(why, whylen, "--no-prompt: a pause is a stop");
		return 1;
	}
	int fd = open("/dev/tty", O_RDWR | O_NOCTTY | O_CLOEXEC);
	if (fd < 0) {
		snprintf(why, whylen, "no terminal to ask on (/dev/tty: %s)", strerror(errno));
		return 1;
	}
	tcflush(fd, TCIFLUSH);   /* an Enter typed ahead does not answer for a pen not yet asked for */
	char ask[400], layer[240] = "";
	if (q->layer)
		snprintf(layer, sizeof layer, " (layer \"%.200s\")", q->layer);
	int n = snprintf(ask, sizeof ask, "locus-hpgl: load pen %d%s, then press Enter (or s and Enter to stop): ",
		q->slot, layer);
	if (n > 0 && write(fd, ask, (size_t)n < sizeof ask ? (size_t)n : sizeof ask - 1) < 0) {
		snprintf(why, whylen, "cannot ask on the terminal: %s", strerror(errno));
		close(fd);
		return 1;
	}
	char line[128];
	size_t k = 0;
	int stop = 0;
	for (;;) {
		char ch;
		ssize_t r = read(fd, &ch, 1);
		if (r == 1 && ch != '\n') {
			if (k < sizeof line - 1)
				line[k++] = ch;
			continue;
		}
		if (r == 1)
			break;
		snprintf(why, whylen, r == 0 ? "the terminal closed at the question" : errno == EINTR
			? "interrupted at the question" : "cannot read the answer");
		stop = 1;
		break;
	}
	line[k] = 0;
	size_t b = strspn(line, " \t\r");
	if (!stop && (line[b] == 's' || line[b] == 'S')) {
		snprintf(why, whylen, "stopped at the question, as asked");
		stop = 1;
	}
	if (write(fd, stop ? "stopping\n" : "going on\n", stop ? 9 : 9) < 0) {
		/* the answer stands */
	}
	close(fd);
	return stop;
}

/* --analyse: what a plotter would do with an HP-GL file, by the reader and the time model. */
static int analyse(const cli_t *c, const prog_t *p)
{
	hpgl_profile_t prof;
	char err[512];
	const char *name = p->profile[0] ? p->profile : "7475a";
	const hpgl_profile_t *bp = hpgl_profile_find(name);
	if (bp)
		prof = *bp;
	else if (hpgl_profile_load(name, &prof, err, sizeof err))
		return cli_fail(c, 64, "%s", err);
	const char *in = c->in[0];
	FILE *f = strcmp(in, "-") ? fopen(in, "rb") : stdin;
	if (!f)
		return cli_fail(c, 66, "%s: %s", in, strerror(errno));
	hpgl_doc_t doc;
	int rc = hpgl_read_stream(f, strcmp(in, "-") ? in : "<stdin>", &doc, err, sizeof err);
	if (f != stdin)
		fclose(f);
	if (rc) {
		hpgl_doc_free(&doc);
		fprintf(stderr, "%s\n", err);
		return 65;
	}
	double k = 1, down = hpgl_doc_length(&doc, -1);
	if (p->length > 0 && down > 0)
		k = p->length * HPGL_PU_PER_MM / down;
	hpgl_time_t t;
	memset(&t, 0, sizeof t);
	popt_pt_t *q = NULL, at = { prof.clip[prof.paper][0], prof.clip[prof.paper][1] };
	size_t cap = 0;
	unsigned changes = 0;
	int pen = -1;
	for (size_t s = 0; s < doc.nstrokes; s++) {
		const hpgl_rstroke_t *st = &doc.strokes[s];
		if (st->n > cap) {
			cap = st->n * 2;
			popt_pt_t *nq = realloc(q, cap * sizeof *q);
			if (!nq) {
				free(q);
				hpgl_doc_free(&doc);
				return cli_fail(c, 70, "out of memory");
			}
			q = nq;
		}
		for (size_t i = 0; i < st->n; i++)
			q[i] = (popt_pt_t){ (int32_t)lround(doc.pts[st->start + i].x * k), (int32_t)lround(doc.pts[st->start + i].y * k) };
		double dx = (double)q[0].x - at.x, dy = (double)q[0].y - at.y;
		hpgl_time_add(&t, &prof, sqrt(dx * dx + dy * dy), q, st->n);
		at = q[st->n - 1];
		changes += st->pen != pen;
		pen = st->pen;
	}
	double total = t.down_s + t.up_s + t.lift_s + changes * prof.t_change;
	printf("analyse %s: %zu commands, %zu strokes, pen-down %.1f mm, pen-up %.1f mm, %llu lifts, %u pen changes, "
		"estimate %.1f s (%s, scale %.4f)\n", in, doc.ncmds, doc.nstrokes, t.down_mm, t.up_mm,
		(unsigned long long)t.lifts, changes, total, prof.name, k);
	free(q);
	hpgl_doc_free(&doc);
	return 0;
}

int main(int argc, char **argv)
{
	prog_t p;
	memset(&p, 0, sizeof p);
	p.est = stderr;
	cli_t c;
	memset(&c, 0, sizeof c);
	c.prog = "locus-hpgl";
	c.usage = usage;
	c.extra = longopts;
	c.extra_short = "v";
	c.on_option = on_option;
	c.user = &p;
	int st = cli_parse(&c, argc, argv);
	if (st != CLI_RUN)
		return st;
	if (p.analyse)
		return analyse(&c, &p);
	const char *out = c.out;
	if (!out)
		out = p.estimate ? NULL : "-";
	if (p.estimate && !c.out)
		p.est = stdout;
	hpgl_set_reporter(report, &p);   /* warnings always; figures with --stats/--estimate */
	hpgl_set_pauser(ask_pen, &p);
	p.held = open_memstream(&p.heldbuf, &p.heldlen);   /* NULL: printed as they come */
	dev_job_t job = { c.in[0], out, &dev_hpgl_ops, 0, 0, c.options };
	char err[600];
	st = dev_run(&job, err, sizeof err);
	if (p.held) {
		fclose(p.held);
		p.held = NULL;
		if (st == 0)
			fwrite(p.heldbuf, 1, p.heldlen, stderr);   /* warnings are for runs that succeed */
		free(p.heldbuf);
	}
	if (st == 65)
		fprintf(stderr, "%s\n", err);
	else if (st)
		fprintf(stderr, "locus-hpgl: %s\n", err);
	return st;
}
