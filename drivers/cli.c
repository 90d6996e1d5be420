/* cli.c: the shared option parsing of the driver programs (getopt_long). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"

enum { OPT_HELP = 0x1000, OPT_VERSION, OPT_BAND_ROWS, OPT_MEM_BUDGET };

static const struct option common[] = {
	{ "output", required_argument, NULL, 'o' },
	{ "help", no_argument, NULL, OPT_HELP },
	{ "version", no_argument, NULL, OPT_VERSION },
	{ "band-rows", required_argument, NULL, OPT_BAND_ROWS },
	{ "mem-budget", required_argument, NULL, OPT_MEM_BUDGET },
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
	if (st != CLI_RUN)
		return st;
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
