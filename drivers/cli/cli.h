/* cli.h: the options every Locus driver program shares, parsed once through getopt_long.
 *
 * A program fills a cli_t (its name, a usage text, and optionally a table of its own long
 * options with a callback), then calls cli_parse(). The shared options are:
 *   -o OUT, --output OUT     output name (a path, "-", or a transport name)
 *   -O KEY=VALUE[,...]       device options (appended to cli_t.options)
 *   --band-rows N            raster devices: rows per band
 *   --mem-budget MIB         raster devices: page buffer budget
 *   --antialias[=K]          raster devices: the device option antialias=K (default K 4;
 *                            `--antialias K` also works when K is all digits)
 *   --journal FILE           device links: journal=FILE in the output name (transport.h)
 *   --resume FILE            device links: resume=FILE in the output name; either one given
 *                            in the name too must say the same, else a usage error (64)
 *   -h, --help, --version
 * Program options can turn themselves into device options with cli_set_option(), so that
 * `locus-vga --mode 12h` and `locus-play -d vga -O mode=12h` are the same job.
 */
#ifndef LOCUS_CLI_H
#define LOCUS_CLI_H

#include <getopt.h>
#include <stddef.h>

/* The factor of a bare --antialias (4 x 4 samples a pixel), and the largest one taken
 * (device.h's DEV_AA_MAX; the framework checks it again). */
#define CLI_AA_DEFAULT 4
#define CLI_AA_DEFAULT_STR "4"
#define CLI_AA_MAX 16

/* cli_parse() returns this when the program should go on and run the job. */
#define CLI_RUN (-1)

typedef struct cli cli_t;
struct cli {
	const char *prog;            /* "locus-vga": message prefix and --version */
	const char *usage;           /* the whole --help text (printed as is) */
	const struct option *extra;  /* the program's own long options, {0} terminated, or NULL */
	const char *extra_short;     /* its short options in getopt syntax ("f:l"), or NULL */
	/* Called for each of the program's own options with getopt's value (a short option's
	 * letter or the long option's val) and its argument (or NULL). Returns CLI_RUN to go on,
	 * 0 to exit successfully now (e.g. after --list-modes), or an exit status (64). */
	int (*on_option)(cli_t *c, int key, const char *arg);
	void *user;                  /* free for the program */
	size_t max_inputs;           /* positional arguments allowed (0 means 1) */
	/* results */
	const char *in[4];           /* positional arguments; in[0] defaults to "-" */
	size_t nin;
	const char *out;             /* -o (with --journal/--resume folded in: outname), or NULL */
	const char *journal;         /* --journal FILE, or NULL */
	const char *resume;          /* --resume FILE, or NULL */
	char outname[1200];          /* the output name with journal=/resume= added */
	unsigned band_rows;          /* 0 = automatic */
	size_t budget;               /* bytes, 0 = default */
	char options[1024];          /* device options "k=v,k=v" (from -O and cli_set_option) */
};

/* Parse argv. Prints --help/--version output and usage errors itself (one line, naming the
 * program). Returns CLI_RUN, or the status to exit with. */
int cli_parse(cli_t *c, int argc, char **argv);
/* Append key=value to c->options (replacing an earlier value of the same key).
 * Returns 0, or 64 after printing a message when the options grow too long or hold ',' . */
int cli_set_option(cli_t *c, const char *key, const char *value);
/* Print "PROG: message" with a newline to stderr and return status (for usage errors). */
int cli_fail(const cli_t *c, int status, const char *fmt, ...)
#ifdef __GNUC__
	__attribute__((format(printf, 3, 4)))
#endif
	;
/* Parse a decimal unsigned number in [lo, hi]; 0 ok, -1 otherwise. */
int cli_number(const char *s, unsigned long lo, unsigned long hi, unsigned long *v);

#endif
