/* cli.c: the shared option parsing of the driver programs (getopt_long). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli/cli.h"
#include "device/device.h"
#include "hpgl/hpgl_link.h"
#include "io/transport.h"

_Static_assert(CLI_AA_MAX == DEV_AA_MAX, "cli.h and device.h agree on the largest factor");

enum { OPT_HELP = 0x1000, OPT_VERSION, OPT_BAND_ROWS, OPT_MEM_BUDGET, OPT_ANTIALIAS, OPT_JOURNAL, OPT_RESUME };

static const struct option common[] = {
	{ "output", required_argument, NULL, 'o' },
	{ "help", no_argument, NULL, OPT_HELP },
	{ "version", no_argument, NULL, OPT_VERSION },
	{ "band-rows", required_argument, NULL, OPT_BAND_ROWS },
	{ "mem-budget", required_argument, NULL, OPT_MEM_BUDGET },
	{ "antialias", optional_argument, NULL, OPT_ANTIALIAS },
	{ "journal", required_argument, NULL, OPT_JOURNAL },
	{ "resume", required_argument, NULL, OPT_RESUME },
};
#define NCOMMON (sizeof common / sizeof common[0])

int cli_fail(const cli_t *c, int status, const char *fmt, ...)
{
	va_list ap;
	fprintf(stderr, "%s: ", c->prog);
	va_start(ap, fmt);
	vfprintf(stderr, fmt, ap);
	va_end(ap);
	fputc('\n', stderr);
	return status;
}

int cli_number(const char *s, unsigned long lo, unsigned long hi, unsigned long *v)
{
	char *e;
	if (!s || *s < '0' || *s > '9')
		return -1;
	unsigned long x = strtoul(s, &e, 10);
	if (*e || x < lo || x > hi)
		return -1;
	*v = x;
	return 0;
}

int cli_set_option(cli_t *c, const char *key, const char *value)
{
	if (strchr(value, ','))
		return cli_fail(c, 64, "option value '%s' for %s may not hold ','", value, key);
	/* drop an earlier key=... */
	size_t klen = strlen(key);
	char *p = c->options;
	while (*p) {
		char *end = strchr(p, ',');
		size_t n = end ? (size_t)(end - p) : strlen(p);
		if (n > klen && strncmp(p, key, klen) == 0 && p[klen] == '=') {
			memmove(p, end ? end + 1 : p + n, strlen(end ? end + 1 : p + n) + 1);
			continue;
		}
		p += n + (end != NULL);
	}
	size_t len = strlen(c->options);
	if (len && c->options[len - 1] == ',')
		c->options[--len] = 0;
	int w = snprintf(c->options + len, sizeof c->options - len, "%s%s=%s", len ? "," : "", key, value);
	if (w < 0 || (size_t)w >= sizeof c->options - len) {
		c->options[len] = 0;
		return cli_fail(c, 64, "device options too long");
	}
	return 0;
}

/* The help line of --antialias, printed after a usage text that does not describe it. */
static const char aa_help[] =
	"  --antialias[=K]  raster devices: K x K samples per pixel averaged in linear light\n"
	"                   (default K " CLI_AA_DEFAULT_STR "; 0 or 1 = exact, the default mode; at most 16)\n";

/* --antialias[=K] or --antialias K (a separate word only when it is all digits, so that
 * `--antialias in.meta` still reads in.meta): sets the device option antialias=K, which the
 * framework checks and takes (docs/drivers.md, "Anti-aliasing"). */
static int antialias(cli_t *c, int argc, char **argv)
{
	const char *k = optarg;
	if (!k && optind < argc && argv[optind][0] >= '0' && argv[optind][0] <= '9' &&
			strspn(argv[optind], "0123456789") == strlen(argv[optind]))
		k = argv[optind++];
	unsigned long v;
	if (!k)
		k = CLI_AA_DEFAULT_STR;
	else if (cli_number(k, 0, CLI_AA_MAX, &v))
		return cli_fail(c, 64, "--antialias takes 0 (exact) or 2 to %d samples a side, not '%s'", CLI_AA_MAX, k);
	return cli_set_option(c, "antialias", k) ? 64 : CLI_RUN;
}

/* The help lines of --journal and --resume, printed after a usage text that does not describe them. */
static const char journal_help[] =
	"  --journal FILE   device links: keep a job journal in FILE (as NAME?journal=FILE)\n"
	"  --resume FILE    device links: go on with the job FILE journaled (as NAME?resume=FILE)\n";

/* --journal FILE / --resume FILE: folded into the output name as journal=FILE / resume=FILE,
 * which the transport reads (transport.h); the name may say the same, not something else. */
static int fold_journal(cli_t *c)
{
	const char *key = c->resume ? "resume" : "journal", *file = c->resume ? c->resume : c->journal;
	if (!file)
		return CLI_RUN;
	if (c->resume && c->journal)
		return cli_fail(c, 64, "--journal and --resume: give one (a resumed job goes on journaling in its file)");
	if (!c->out || !io_is_link_name(c->out))
		return cli_fail(c, 64, "--%s needs a device link output (-o serial:..., tcp:..., usb:..., hid:...)", key);
	if (!file[0] || strpbrk(file, "&?"))
		return cli_fail(c, 64, "--%s FILE: the file name may not be empty or hold '&' or '?'", key);
	const char *q = strchr(c->out, '?');
	for (const char *p = q; p; p = strchr(p + 1, '&')) {
		size_t n = strcspn(p + 1, "&");
		for (int k = 0; k < 2; k++) {
			const char *w = k ? "resume=" : "journal=";
			if (strncmp(p + 1, w, strlen(w)))
				continue;
			if (!strcmp(w, c->resume ? "resume=" : "journal=") && n - strlen(w) == strlen(file)
				&& !strncmp(p + 1 + strlen(w), file, strlen(file)))
				return CLI_RUN;   /* the name says the same */
			return cli_fail(c, 64, "-o '%s' already says %.*s, and --%s %s: give one", c->out, (int)n, p + 1, key, file);
		}
	}
	int w = snprintf(c->outname, sizeof c->outname, "%s%c%s=%s", c->out, q ? '&' : '?', key, file);
	if (w < 0 || (size_t)w >= sizeof c->outname)
		return cli_fail(c, 64, "the output name with --%s is too long", key);
	c->out = c->outname;
	return CLI_RUN;
}

/* 1 when the character needs no quoting in a shell word. */
static int plain(char ch)
{
	return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || strchr("_./:=,@%+-", ch);
}

/* The command that resumes this one, for the line of a job that stopped (io_set_resume_command):
 * argv quoted for a shell, --journal turned into --resume and journal= of a link into resume=. */
static void resume_command(int argc, char **argv)
{
	char cmd[1024];
	size_t n = 0;
	for (int k = 0; k < argc && n < sizeof cmd; k++) {
		char word[600];
		const char *a = argv[k];
		if (!strcmp(a, "--journal"))
			a = "--resume";
		snprintf(word, sizeof word, "%s", a);
		if (!strncmp(word, "--journal=", 10))
			snprintf(word, sizeof word, "--resume=%s", a + 10);
		char *j = strstr(word, "journal=");
		if (j && j > word && (j[-1] == '?' || j[-1] == '&') && strchr(word, ':')) {
			memmove(j + 7, j + 8, strlen(j + 8) + 1);   /* journal= -> resume= */
			memcpy(j, "resume=", 7);
		}
		int quote = !word[0];
		for (const char *p = word; *p; p++)
			quote |= !plain(*p);
		n += (size_t)snprintf(cmd + n, sizeof cmd - n, "%s%s", k ? " " : "", quote ? "'" : "");
		for (const char *p = word; *p && n < sizeof cmd; p++)
			n += (size_t)snprintf(cmd + n, sizeof cmd - n, *p == '\'' ? "'\\''" : "%c", *p);
		if (quote && n < sizeof cmd)
			n += (size_t)snprintf(cmd + n, sizeof cmd - n, "'");
	}
	io_set_resume_command(n < sizeof cmd ? cmd : NULL);
}

/* -O a=1,b=2: each key=value through cli_set_option. */
static int add_options(cli_t *c, const char *arg)
{
	char buf[1024];
	if (strlen(arg) >= sizeof buf)
		return cli_fail(c, 64, "device options too long");
	strcpy(buf, arg);
	for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
		char *eq = strchr(tok, '=');
		if (!eq || eq == tok)
			return cli_fail(c, 64, "-O needs key=value pairs, not '%s'", tok);
		*eq = 0;
		int st = cli_set_option(c, tok, eq + 1);
		if (st != 0)
			return st;
	}
	return CLI_RUN;
}

int cli_parse(cli_t *c, int argc, char **argv)
{
	size_t nextra = 0;
	while (c->extra && c->extra[nextra].name)
		nextra++;
	struct option *opts = calloc(NCOMMON + nextra + 1, sizeof *opts);
	if (!opts)
		return cli_fail(c, 70, "out of memory");
	memcpy(opts, common, sizeof common);
	if (nextra)
		memcpy(opts + NCOMMON, c->extra, nextra * sizeof *opts);
	char shortopts[128];
	snprintf(shortopts, sizeof shortopts, ":ho:O:%s", c->extra_short ? c->extra_short : "");
	int st = CLI_RUN;
	opterr = 0;
	optind = 1;
	unsigned long v;
	for (int ch; st == CLI_RUN && (ch = getopt_long(argc, argv, shortopts, opts, NULL)) != -1;) {
		switch (ch) {
		case 'h': case OPT_HELP:
			fputs(c->usage, stdout);
			if (!strstr(c->usage, "--antialias"))
				fputs(aa_help, stdout);
			if (!strstr(c->usage, "--journal"))
				fputs(journal_help, stdout);
			st = 0;
			break;
		case OPT_VERSION:
			printf("%s %s\n", c->prog, LOCUS_VERSION);
			st = 0;
			break;
		case 'o':
			c->out = optarg;
			break;
		case 'O':
			st = add_options(c, optarg);
			break;
		case OPT_BAND_ROWS:
			if (cli_number(optarg, 1, 1000000000UL, &v))
				st = cli_fail(c, 64, "--band-rows needs a positive number, not '%s'", optarg);
			else
				c->band_rows = (unsigned)v;
			break;
		case OPT_MEM_BUDGET:
			if (cli_number(optarg, 1, 1UL << 20, &v))
				st = cli_fail(c, 64, "--mem-budget needs a size in MiB, not '%s'", optarg);
			else
				c->budget = (size_t)v << 20;
			break;
		case OPT_ANTIALIAS:
			st = antialias(c, argc, argv);
			break;
		case OPT_JOURNAL:
			c->journal = optarg;
			break;
		case OPT_RESUME:
			c->resume = optarg;
			break;
		case ':':
			st = cli_fail(c, 64, "option '%s' needs a value (try --help)", argv[optind - 1]);
			break;
		case '?':
			if (optopt && optopt < 0x100)
				st = cli_fail(c, 64, "unknown option '-%c' (try --help)", optopt);
			else
				st = cli_fail(c, 64, "unknown option '%s' (try --help)", argv[optind - 1]);
			break;
		default:
			st = c->on_option ? c->on_option(c, ch, optarg) : cli_fail(c, 64, "unhandled option");
			break;
		}
	}
	free(opts);
	if (st == CLI_RUN)
		st = fold_journal(c);
	if (st != CLI_RUN)
		return st;
	resume_command(argc, argv);
	hpgl_link_register();   /* the jobs sent to device links are HP-GL (or refused by its journal) */
	size_t max = c->max_inputs ? c->max_inputs : 1;
	if (max > sizeof c->in / sizeof c->in[0])
		max = sizeof c->in / sizeof c->in[0];
	for (int k = optind; k < argc; k++) {
		if (c->nin == max)
			return cli_fail(c, 64, "too many input files ('%s')", argv[k]);
		c->in[c->nin++] = argv[k];
	}
	if (c->nin == 0)
		c->in[0] = "-";
	return CLI_RUN;
}
