/* import_svg_cli.c: `locus-meta import`'s options (pens, -O dedupe, --stats, tolerance) parsed
 * for every input kind, then the import run (drivers/import.c). */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hpgl/hpgl.h"
#include "import/meta_import.h"
#include "import/svg_import.h"

static const char import_usage[] =
	"usage: locus-meta import [IN] [-o OUT] [--pens SPEC|by-layer|by-colour] [--pen LAYER=N]...\n"
	"                         [-O occlude] [-O dedupe[=MM]] [--tolerance MM] [--dpi N]\n"
	"                         [--profile NAME] [--stats] [--json] [-v]\n"
	"Import an HP-GL, HP-GL/2, plotutils metafile or SVG drawing (told from its content) as a\n"
	"text meta file. SVG: curves flattened to --tolerance mm (0.0125, half a plotter unit),\n"
	"one meta pixel per CSS px (--dpi 96); --pens by-layer gives each Inkscape layer (or\n"
	"top-level group) a pen (a number in its label, --pen LABEL=N, else the next free one),\n"
	"by-colour each stroke colour (--pen '#rrggbb=N'), drawn in that pen's colour of the\n"
	"carousel (--pens SPEC as for HP-GL, or --profile's); -O occlude cuts strokes and fill\n"
	"outlines hidden under later fills (fills become outlines; white ones only hide);\n"
	"-O dedupe drops strokes retracing earlier ones of the same pen within MM (0.05);\n"
	"--stats prints pen-down length, pen-up\n"
	"travel, lifts, pen changes and plot time (--profile, 7475a) before and after; -v the pens.\n"
	"HP-GL: --pens SPEC gives the pens a file sets no PC/PW for (\"1=black:0.5mm,2=red\");\n"
	"--strict refuses HP-GL junk that is otherwise skipped with a warning.\n"
	"Exit status: 0, 64 usage, 65 bad input (one line: FILE:LINE:COL), 66, 70, 74.\n";

static int usage(const char *msg)
{
	if (msg)
		fprintf(stderr, "locus-meta: %s\n", msg);
	fputs(import_usage, stderr);
	return 64;
}

static int number(const char *s, double lo, double hi, double *v)
{
	char *e;
	*v = strtod(s, &e);
	return *e || e == s || !(*v >= lo && *v <= hi) ? -1 : 0;
}

int mimp_main(int argc, char **argv)
{
	static const struct option lo[] = {
		{ "help", no_argument, NULL, 'h' }, { "pens", required_argument, NULL, 'p' },
		{ "pen", required_argument, NULL, 'P' }, { "tolerance", required_argument, NULL, 't' },
		{ "dpi", required_argument, NULL, 'd' }, { "stats", no_argument, NULL, 's' },
		{ "json", no_argument, NULL, 'j' }, { "profile", required_argument, NULL, 'r' },
		{ "verbose", no_argument, NULL, 'v' }, { "version", no_argument, NULL, 'V' },
		{ "strict", no_argument, NULL, 'S' },
		{ NULL, 0, NULL, 0 }
	};
	svgimp_opts_t o = { .tol_mm = 0.0125, .dpi = 96, .dedupe_mm = 0.05 };
	const char *out = NULL, *in = NULL, *hpgl_pens = NULL;
	int c, svg_only = 0, strict = 0;
	opterr = 0;
	optind = 1;
	while ((c = getopt_long(argc, argv, ":o:O:v", lo, NULL)) != -1) {
		switch (c) {
		case 'h':
			fputs(import_usage, stdout);
			return fflush(stdout) ? 74 : 0;
		case 'V':
			printf("locus-meta %s\n", LOCUS_VERSION);
			return fflush(stdout) ? 74 : 0;
		case 'o':
			out = optarg;
			break;
		case 'p':
			if (!strcmp(optarg, "by-layer"))
				o.pens_mode = SVGP_LAYER, svg_only = 1;
			else if (!strcmp(optarg, "by-colour") || !strcmp(optarg, "by-color"))
				o.pens_mode = SVGP_COLOUR, svg_only = 1;
			else
				hpgl_pens = o.carousel = optarg;
			break;
		case 'P':
			if (o.npen_map == 32)
				return usage("at most 32 --pen options");
			if (!strchr(optarg, '='))
				return usage("--pen: expected LAYER=N or #rrggbb=N");
			o.pen_map[o.npen_map++] = optarg;
			svg_only = 1;
			break;
		case 'O': {   /* -O dedupe[=MM], -O occlude, or both: repeated or comma-separated */
			char buf[128];
			snprintf(buf, sizeof buf, "%s", optarg);
			for (char *save = NULL, *w = strtok_r(buf, ",", &save); w; w = strtok_r(NULL, ",", &save)) {
				if (!strncmp(w, "dedupe", 6) && (!w[6] || w[6] == '=')) {
					o.dedupe = 1;
					if (w[6] && number(w + 7, 1e-6, 100, &o.dedupe_mm))
						return usage("-O dedupe=MM: expected a tolerance in mm, 0 < MM <= 100");
				} else if (!strcmp(w, "occlude")) {
					o.occlude = 1;
				} else {
					fprintf(stderr, "locus-meta: -O %s: unknown (dedupe[=MM], occlude)\n", w);
					return usage(NULL);
				}
			}
			svg_only = 1;
			break;
		}
		case 't':
			if (number(optarg, 1e-4, 10, &o.tol_mm))
				return usage("--tolerance: expected mm, 0.0001 .. 10");
			svg_only = 1;
			break;
		case 'd':
			if (number(optarg, 1, 10000, &o.dpi))
				return usage("--dpi: expected 1 .. 10000");
			svg_only = 1;
			break;
		case 's': o.stats = 1, svg_only = 1; break;
		case 'j': o.json = 1; break;
		case 'v': o.verbose = 1; break;
		case 'S': strict = 1; break;   /* HP-GL: refuse what is otherwise skipped with a warning */
		case 'r':
			if (!hpgl_profile_find(optarg)) {
				fprintf(stderr, "locus-meta: --profile: unknown '%s' (7475a, 7550a, draftpro, hpgl2, cutter)\n", optarg);
				return usage(NULL);
			}
			o.profile = optarg;
			svg_only = 1;
			break;
		case ':':
			fprintf(stderr, "locus-meta: option '%s' needs an argument\n", argv[optind - 1]);
			return usage(NULL);
		default:
			fprintf(stderr, "locus-meta: unknown option '%s'\n", argv[optind - 1]);
			return usage(NULL);
		}
	}
	for (int i = optind; i < argc; i++) {
		if (in)
			return usage("too many file names");
		in = argv[i];
	}
	o.stats_out = out && strcmp(out, "-") ? stdout : stderr;
	return mimp_run_svg(in ? in : "-", out, hpgl_pens, &o, svg_only, strict);
}
