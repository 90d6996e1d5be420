/* hpgl_profile.c: built-in plotter and cutter profiles, the profile-file parser, pen carousels
 * (nearest pen in CIELAB) and the mapping of a model page onto the paper. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hpgl/hpgl.h"

static const char *const paper_names[HPGL_NPAPER] = { "a4", "a3", "letter", "b" };

/* Speeds, accelerations and pen times are model values (docs/hpgl.md says where they come
 * from); the 7475A and 7550A clip limits are the manuals' (../shared/notes/devices.md). */
static const hpgl_profile_t builtin[] = {
	{ .name = "7475a", .description = "HP 7475A six-pen plotter, HP-GL, A4/A3 (1 KB buffer)",
	  .dialect = HPGL_DIALECT_1, .has_paper = { 1, 1, 1, 1 },
	  .clip = { { 0, 0, 11040, 7721 }, { 0, 0, 16158, 11040 }, { 0, 0, 10365, 7962 }, { 0, 0, 16640, 10365 } },
	  .paper = HPGL_PAPER_A4, .max_pairs = 32, .buffer = 1024, .npens = 6,
	  .pens = "1=black;2=red;3=green;4=blue;5=magenta;6=cyan",
	  .v_down = 38.1, .v_up = 38.1, .accel = 12, .t_lift = 0.06, .t_change = 4 },
	{ .name = "7550a", .description = "HP 7550A eight-pen plotter with sheet feeder, HP-GL, A4/A3",
	  .dialect = HPGL_DIALECT_1, .has_paper = { 1, 1, 1, 1 },
	  .clip = { { 0, 0, 10870, 7600 }, { 0, 0, 15970, 10870 }, { 0, 0, 10170, 7840 }, { 0, 0, 16450, 10170 } },
	  .paper = HPGL_PAPER_A4, .max_pairs = 64, .buffer = 12288, .npens = 8,
	  .pens = "1=black;2=red;3=green;4=blue;5=magenta;6=cyan;7=yellow;8=brown",
	  .v_down = 80, .v_up = 80, .accel = 39, .t_lift = 0.03, .t_change = 2.5, .has_fs = 1, .has_as = 1 },
	{ .name = "draftpro", .description = "HP DraftPro (7570A) eight-pen drafting plotter, HP-GL",
	  .dialect = HPGL_DIALECT_1, .has_paper = { 1, 1, 1, 1 },
	  .clip = { { 0, 0, 10880, 7580 }, { 0, 0, 15980, 10880 }, { 0, 0, 10180, 7820 }, { 0, 0, 16460, 10180 } },
	  .paper = HPGL_PAPER_A3, .max_pairs = 64, .buffer = 4096, .npens = 8,
	  .pens = "1=black;2=red;3=green;4=blue;5=magenta;6=cyan;7=yellow;8=brown",
	  .v_down = 60, .v_up = 60, .accel = 20, .t_lift = 0.04, .t_change = 3, .has_fs = 1 },
	{ .name = "hpgl2", .description = "generic HP-GL/2 device: PE polylines, FP/PM fills, PW widths",
	  .dialect = HPGL_DIALECT_2, .has_paper = { 1, 1, 1, 1 },
	  .clip = { { 0, 0, 11480, 8000 }, { 0, 0, 16400, 11480 }, { 0, 0, 10776, 8236 }, { 0, 0, 16872, 10776 } },
	  .paper = HPGL_PAPER_A4, .max_pairs = 256, .buffer = 65536, .npens = 8,
	  .pens = "1=black;2=red;3=green;4=blue;5=magenta;6=cyan;7=yellow;8=brown",
	  .v_down = 50, .v_up = 80, .accel = 30, .t_lift = 0.02, .t_change = 1, .has_fs = 1, .has_as = 1 },
	{ .name = "cutter", .description = "generic vinyl cutter: HP-GL PU/PD, drag knife, newline after commands",
	  .dialect = HPGL_DIALECT_1, .cutter = 1, .has_paper = { 1, 1, 1, 1 },
	  .clip = { { 0, 0, 11880, 8400 }, { 0, 0, 16800, 11880 }, { 0, 0, 11176, 8636 }, { 0, 0, 17272, 11176 } },
	  .paper = HPGL_PAPER_A4, .max_pairs = 16, .buffer = 4096, .npens = 1,
	  .pens = "1=black:0.1mm",
	  .v_down = 20, .v_up = 40, .accel = 10, .t_lift = 0.08, .t_change = 0,
	  .knife_offset = 0.25, .overcut = 1.0, .newline = 1, .has_fs = 1 },
};

size_t hpgl_profile_count(void)
{
	return sizeof builtin / sizeof builtin[0];
}

const hpgl_profile_t *hpgl_profile_builtin(size_t k)
{
	return k < hpgl_profile_count() ? &builtin[k] : NULL;
}

const hpgl_profile_t *hpgl_profile_find(const char *name)
{
	for (size_t k = 0; k < hpgl_profile_count(); k++)
		if (strcmp(builtin[k].name, name) == 0)
			return &builtin[k];
	return NULL;
}

int hpgl_paper_find(const char *name)
{
	for (int k = 0; k < HPGL_NPAPER; k++)
		if (strcmp(paper_names[k], name) == 0)
			return k;
	return -1;
}

const char *hpgl_paper_name(int paper)
{
	return paper >= 0 && paper < HPGL_NPAPER ? paper_names[paper] : "?";
}

/* ---- profile files ---- */

typedef struct {
	const char *name;
	size_t line, col;
	char *err;
	size_t errlen;
} where_t;

static int perr(const where_t *w, const char *fmt, const char *a)
{
	char msg[256];
	snprintf(msg, sizeof msg, fmt, a);
	snprintf(w->err, w->errlen, "%s:%zu:%zu: %s", w->name, w->line, w->col, msg);
	return -1;
}

static int num(const char *v, double lo, double hi, double *out)
{
	char *e;
	errno = 0;
	double d = strtod(v, &e);
	if (e == v || *e || errno || !(d >= lo && d <= hi))
		return -1;
	*out = d;
	return 0;
}

static int yesno(const char *v, int *out)
{
	if (!strcmp(v, "yes") || !strcmp(v, "1") || !strcmp(v, "true"))
		*out = 1;
	else if (!strcmp(v, "no") || !strcmp(v, "0") || !strcmp(v, "false"))
		*out = 0;
	else
		return -1;
	return 0;
}

static int set_key(hpgl_profile_t *p, const char *k, const char *v, const where_t *w)
{
	double d;
	int b;
	if (!strcmp(k, "base")) {
		const hpgl_profile_t *q = hpgl_profile_find(v);
		if (!q)
			return perr(w, "unknown base profile '%s' (7475a, 7550a, draftpro, hpgl2, cutter)", v);
		char name[sizeof p->name];
		memcpy(name, p->name, sizeof name);
		*p = *q;
		if (name[0])
			memcpy(p->name, name, sizeof name);
	} else if (!strcmp(k, "name")) {
		if (!*v || strlen(v) >= sizeof p->name)
			return perr(w, "name must be 1 to 31 characters, not '%s'", v);
		snprintf(p->name, sizeof p->name, "%s", v);
	} else if (!strcmp(k, "description")) {
		snprintf(p->description, sizeof p->description, "%s", v);
	} else if (!strcmp(k, "dialect")) {
		if (!strcmp(v, "hpgl"))
			p->dialect = HPGL_DIALECT_1;
		else if (!strcmp(v, "hpgl2"))
			p->dialect = HPGL_DIALECT_2;
		else
			return perr(w, "dialect is hpgl or hpgl2, not '%s'", v);
	} else if (!strcmp(k, "cutter") || !strcmp(k, "newline") || !strcmp(k, "force-select") ||
			!strcmp(k, "accel-select") || !strcmp(k, "hand-fed")) {
		if (yesno(v, &b))
			return perr(w, "expected yes or no, not '%s'", v);
		*(k[0] == 'c' ? &p->cutter : k[0] == 'n' ? &p->newline : k[0] == 'f' ? &p->has_fs
			: k[0] == 'a' ? &p->has_as : &p->pause_all) = b;
	} else if (!strcmp(k, "pause-pens")) {
		char e2[200];
		if (hpgl_pause_parse(v, p->penset, &p->pause_all, e2, sizeof e2))
			return perr(w, "%s", e2);
	} else if (!strncmp(k, "pen.", 4)) {
		char *e;
		errno = 0;
		long slot = strtol(k + 4, &e, 10);
		char e2[200];
		if (e == k + 4 || *e || errno || slot < 1 || slot > HPGL_MAX_PENS)
			return perr(w, "pen.N takes a pen number N from 1 to 256, not '%s'", k);
		if (hpgl_penset_items(v, &p->penset[slot], e2, sizeof e2))
			return perr(w, "%s", e2);
	} else if (!strcmp(k, "paper")) {
		int q = hpgl_paper_find(v);
		if (q < 0)
			return perr(w, "unknown paper '%s' (a4, a3, letter, b)", v);
		p->paper = q;
	} else if (!strcmp(k, "papers")) {   /* the papers it takes, e.g. "a4 a3" */
		int has[HPGL_NPAPER] = { 0 };
		char list[256];
		snprintf(list, sizeof list, "%s", v);
		for (char *t = strtok(list, " \t,"); t; t = strtok(NULL, " \t,")) {
			int q = hpgl_paper_find(t);
			if (q < 0)
				return perr(w, "unknown paper '%s' (a4, a3, letter, b)", t);
			has[q] = 1;
		}
		memcpy(p->has_paper, has, sizeof has);
	} else if (!strncmp(k, "clip.", 5)) {
		int q = hpgl_paper_find(k + 5);
		long c[4];
		char *e;
		const char *s = v;
		if (q < 0)
			return perr(w, "unknown paper in '%s' (clip.a4, clip.a3, clip.letter, clip.b)", k);
		for (int i = 0; i < 4; i++) {
			errno = 0;
			c[i] = strtol(s, &e, 10);
			if (e == s || errno || labs(c[i]) > 1000000)
				return perr(w, "clip limits are four integers X0 Y0 X1 Y1 in plotter units, not '%s'", v);
			s = e;
		}
		while (*s == ' ' || *s == '\t')
			s++;
		if (*s || c[2] <= c[0] || c[3] <= c[1])
			return perr(w, "clip limits are four integers X0 Y0 X1 Y1 with X1 > X0, Y1 > Y0, not '%s'", v);
		for (int i = 0; i < 4; i++)
			p->clip[q][i] = (int32_t)c[i];
		p->has_paper[q] = 1;
	} else if (!strcmp(k, "pens")) {
		hpgl_pens_t pens;
		char e2[200];
		if (strlen(v) >= sizeof p->pens)
			return perr(w, "pens: list too long (%s)", "at most 255 characters");
		if (hpgl_pens_parse(v, 0.3, &pens, e2, sizeof e2))
			return perr(w, "%s", e2);
		snprintf(p->pens, sizeof p->pens, "%s", v);
	} else {
		static const struct { const char *k; double lo, hi; size_t off; int integer; } nums[] = {
			{ "max-pairs", 1, 100000, offsetof(hpgl_profile_t, max_pairs), 1 },
			{ "buffer", 0, 1e9, offsetof(hpgl_profile_t, buffer), 1 },
			{ "pen-count", 1, HPGL_MAX_PENS, offsetof(hpgl_profile_t, npens), 1 },
			{ "speed-down", 0.1, 1000, offsetof(hpgl_profile_t, v_down), 0 },
			{ "speed-up", 0.1, 1000, offsetof(hpgl_profile_t, v_up), 0 },
			{ "accel", 0.1, 1000, offsetof(hpgl_profile_t, accel), 0 },
			{ "lift-time", 0, 60, offsetof(hpgl_profile_t, t_lift), 0 },
			{ "change-time", 0, 600, offsetof(hpgl_profile_t, t_change), 0 },
			{ "knife-offset", 0, 10, offsetof(hpgl_profile_t, knife_offset), 0 },
			{ "overcut", 0, 100, offsetof(hpgl_profile_t, overcut), 0 },
		};
		for (size_t i = 0; i < sizeof nums / sizeof nums[0]; i++) {
			if (strcmp(k, nums[i].k))
				continue;
			if (num(v, nums[i].lo, nums[i].hi, &d) || (nums[i].integer && d != floor(d))) {
				char m[128];
				snprintf(m, sizeof m, "%s needs a %s in [%g, %g], not '%%s'", k,
					nums[i].integer ? "whole number" : "number", nums[i].lo, nums[i].hi);
				return perr(w, m, v);
			}
			if (nums[i].integer)
				*(unsigned *)((char *)p + nums[i].off) = (unsigned)d;
			else
				*(double *)((char *)p + nums[i].off) = d;
			return 0;
		}
		return perr(w, "unknown key '%s' (base, name, description, dialect, cutter, newline, paper, "
			"papers, clip.PAPER, pens, pen-count, max-pairs, buffer, speed-down, speed-up, accel, lift-time, "
			"change-time, knife-offset, overcut, force-select, accel-select, hand-fed, pause-pens, pen.N)", k);
	}
	return 0;
}

int hpgl_profile_parse(const char *text, size_t len, const char *name, hpgl_profile_t *p,
		char *err, size_t errlen)
{
	*p = builtin[3];   /* generic HP-GL/2 unless a base says otherwise */
	p->name[0] = 0;
	snprintf(p->description, sizeof p->description, "profile file %s", name);
	where_t w = { name, 0, 1, err, errlen };
	size_t i = 0;
	while (i < len) {
		size_t e = i;
		while (e < len && text[e] != '\n')
			e++;
		w.line++;
		char buf[512];
		size_t n = e - i;
		if (n && text[i + n - 1] == '\r')
			n--;
		if (n >= sizeof buf) {
			w.col = 1;
			return perr(&w, "line longer than %s bytes", "511");
		}
		memcpy(buf, text + i, n);
		buf[n] = 0;
		i = e + 1;
		if (memchr(buf, 0, n)) {
			w.col = strlen(buf) + 1;
			return perr(&w, "NUL byte in a profile %s", "file");
		}
		char *s = buf;
		while (*s == ' ' || *s == '\t')
			s++;
		if (!*s || *s == '#')
			continue;
		w.col = (size_t)(s - buf) + 1;
		char *eq = strchr(s, '=');
		if (!eq)
			return perr(&w, "expected KEY = VALUE, got '%.60s'", s);
		char *ke = eq;
		while (ke > s && (ke[-1] == ' ' || ke[-1] == '\t'))
			ke--;
		*ke = 0;
		char *v = eq + 1;
		while (*v == ' ' || *v == '\t')
			v++;
		char *ve = v + strlen(v);
		while (ve > v && (ve[-1] == ' ' || ve[-1] == '\t'))
			ve--;
		*ve = 0;
		if (!*s)
			return perr(&w, "expected a key before '%s'", "=");
		if (set_key(p, s, v, &w))
			return -1;
	}
	if (!p->name[0]) {
		w.line = 1;
		w.col = 1;
		return perr(&w, "the profile needs a name (name = ...)%s", "");
	}
	if (!p->has_paper[p->paper]) {
		w.col = 1;
		return perr(&w, "the default paper %s has no clip limits (clip.PAPER = X0 Y0 X1 Y1)", hpgl_paper_name(p->paper));
	}
	return 0;
}

int hpgl_profile_load(const char *path, hpgl_profile_t *p, char *err, size_t errlen)
{
	FILE *f = fopen(path, "rb");
	if (!f) {
		snprintf(err, errlen, "%s: %s", path, strerror(errno));
		return -1;
	}
	char *buf = NULL;
	size_t n = 0, cap = 0;
	for (;;) {
		if (n + 4096 > cap) {
			cap = cap ? 2 * cap : 8192;
			if (cap > (1u << 20)) {
				free(buf);
				fclose(f);
				snprintf(err, errlen, "%s: profile file larger than 1 MiB", path);
				return -1;
			}
			char *b = realloc(buf, cap);
			if (!b) {
				free(buf);
				fclose(f);
				snprintf(err, errlen, "%s: out of memory", path);
				return -1;
			}
			buf = b;
		}
		size_t k = fread(buf + n, 1, cap - n, f);
		n += k;
		if (k == 0)
			break;
	}
	int bad = ferror(f);
	fclose(f);
	if (bad) {
		free(buf);
		snprintf(err, errlen, "%s: read error", path);
		return -1;
	}
	int rc = hpgl_profile_parse(buf ? buf : "", n, path, p, err, errlen);
	free(buf);
	return rc;
}

/* ---- pens and colour ---- */

static const struct { const char *name; uint32_t rgb; } colour_names[] = {
	/* pen inks rather than screen primaries, so that ordinary colours find the pen a user expects */
	{ "black", 0x000000 }, { "red", 0xd02020 }, { "green", 0x20a040 }, { "blue", 0x2050c0 },
	{ "cyan", 0x00ffff }, { "magenta", 0xff00ff }, { "yellow", 0xffff00 }, { "brown", 0x8b4513 },
	{ "orange", 0xff8000 }, { "violet", 0x8000ff }, { "purple", 0x800080 }, { "grey", 0x808080 },
	{ "gray", 0x808080 }, { "white", 0xffffff },
};

static double srgb_lin(double c)
{
	return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static double lab_f(double t)
{
	return t > 216.0 / 24389 ? cbrt(t) : (24389.0 / 27 * t + 16) / 116;
}

/* srgb_lin of the 256 component values, made once (pow is most of a colour's conversion, and
 * a page of random colours converts one per path) */
static double lin_table[256];
static pthread_once_t lin_once = PTHREAD_ONCE_INIT;

static void lin_init(void)
{
	for (int v = 0; v < 256; v++)
		lin_table[v] = srgb_lin(v / 255.0);
}

void hpgl_rgb_to_lab(uint32_t rgb, double lab[3])
{
	pthread_once(&lin_once, lin_init);
	double r = lin_table[rgb >> 16 & 255], g = lin_table[rgb >> 8 & 255], b = lin_table[rgb & 255];
	double X = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
	double Y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
	double Z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
	double fx = lab_f(X), fy = lab_f(Y), fz = lab_f(Z);
	lab[0] = 116 * fy - 16;
	lab[1] = 500 * (fx - fy);
	lab[2] = 200 * (fy - fz);
}

static int parse_colour(const char *s, size_t n, uint32_t *rgb)
{
	if (n == 7 && s[0] == '#') {
		uint32_t v = 0;
		for (size_t i = 1; i < 7; i++) {
			if (!isxdigit((unsigned char)s[i]))
				return -1;
			v = v * 16 + (uint32_t)(isdigit((unsigned char)s[i]) ? s[i] - '0' : (tolower((unsigned char)s[i]) - 'a' + 10));
		}
		*rgb = v;
		return 0;
	}
	for (size_t k = 0; k < sizeof colour_names / sizeof colour_names[0]; k++)
		if (strlen(colour_names[k].name) == n && strncasecmp(colour_names[k].name, s, n) == 0) {
			*rgb = colour_names[k].rgb;
			return 0;
		}
	return -1;
}

int hpgl_pens_parse(const char *spec, double default_width_mm, hpgl_pens_t *pens,
		char *err, size_t errlen)
{
	pens->n = 0;
	const char *p = spec;
	while (*p) {
		while (*p == ',' || *p == ';' || *p == '\n' || *p == '\r' || *p == ' ' || *p == '\t')
			p++;
		if (*p == '#' && (p == spec || p[-1] == '\n' || p[-1] == ' ' || p[-1] == '\t')) {
			while (*p && *p != '\n')
				p++;
			continue;
		}
		if (!*p)
			break;
		const char *e = p;
		while (*e && *e != ',' && *e != ';' && *e != '\n' && *e != '\r')
			e++;
		size_t n = (size_t)(e - p);
		while (n && (p[n - 1] == ' ' || p[n - 1] == '\t'))
			n--;
		char item[64];
		snprintf(item, sizeof item, "%.*s", (int)(n < 60 ? n : 60), p);
		char *end;
		long slot = strtol(p, &end, 10);
		if (end == p || *end != '=' || slot < 1 || slot > HPGL_MAX_PENS) {
			snprintf(err, errlen, "pens: '%s': expected SLOT=COLOUR[:WIDTHmm] with SLOT 1..%d", item, HPGL_MAX_PENS);
			return -1;
		}
		const char *c = end + 1, *colon = memchr(c, ':', (size_t)(p + n - c));
		size_t cn = colon ? (size_t)(colon - c) : (size_t)(p + n - c);
		hpgl_pen_t pen = { (int)slot, 0, default_width_mm, { 0 } };
		if (parse_colour(c, cn, &pen.rgb)) {
			snprintf(err, errlen, "pens: '%s': unknown colour (a name such as black, red, blue, or #rrggbb)", item);
			return -1;
		}
		if (colon) {
			char wb[32];
			size_t wn = (size_t)(p + n - colon - 1);
			if (wn >= 2 && colon[wn - 1] == 'm' && colon[wn] == 'm')
				wn -= 2;
			snprintf(wb, sizeof wb, "%.*s", (int)(wn < 30 ? wn : 30), colon + 1);
			if (num(wb, 0.01, 20, &pen.width_mm)) {
				snprintf(err, errlen, "pens: '%s': the width is a number of mm in [0.01, 20]", item);
				return -1;
			}
		}
		for (size_t k = 0; k < pens->n; k++)
			if (pens->pen[k].slot == pen.slot) {
				snprintf(err, errlen, "pens: '%s': pen %ld given twice", item, slot);
				return -1;
			}
		if (pens->n == HPGL_MAX_PENS) {
			snprintf(err, errlen, "pens: more than %d pens", HPGL_MAX_PENS);
			return -1;
		}
		hpgl_rgb_to_lab(pen.rgb, pen.lab);
		size_t at = pens->n++;   /* keep slot order */
		while (at > 0 && pens->pen[at - 1].slot > pen.slot) {
			pens->pen[at] = pens->pen[at - 1];
			at--;
		}
		pens->pen[at] = pen;
		p = e;
	}
	if (pens->n == 0) {
		snprintf(err, errlen, "pens: no pen given (e.g. 1=black,2=red:0.5mm)");
		return -1;
	}
	return 0;
}

/* CIE94 colour difference (graphic arts: kL = 1, K1 = 0.045, K2 = 0.015) of sample b from
 * reference a: unlike CIE76 it does not send pure blue to a magenta pen. */
static double de94(const double *a, const double *b)
{
	double c1 = sqrt(a[1] * a[1] + a[2] * a[2]), c2 = sqrt(b[1] * b[1] + b[2] * b[2]);
	double dl = a[0] - b[0], dc = c1 - c2, da = a[1] - b[1], db = a[2] - b[2];
	double dh2 = da * da + db * db - dc * dc;
	if (dh2 < 0)
		dh2 = 0;
	double sc = 1 + 0.045 * c1, sh = 1 + 0.015 * c1;
	return dl * dl + dc * dc / (sc * sc) + dh2 / (sh * sh);   /* squared */
}

/* The pen nearest to the colour lab (CIE94). */
static size_t nearest_lab(const hpgl_pens_t *pens, const double lab[3])
{
	double best = INFINITY;
	size_t bi = 0;
	for (size_t k = 0; k < pens->n; k++) {
		double d = de94(lab, pens->pen[k].lab);
		if (d < best) {
			best = d;
			bi = k;
		}
	}
	return bi;
}

size_t hpgl_pens_nearest(const hpgl_pens_t *pens, uint32_t rgb)
{
	double lab[3];
	hpgl_rgb_to_lab(rgb, lab);
	return nearest_lab(pens, lab);
}

long hpgl_pens_pick(const hpgl_pens_t *pens, uint32_t rgb)
{
	double lab[3];
	static const double white[3] = { 100, 0, 0 };
	hpgl_rgb_to_lab(rgb, lab);
	size_t k = nearest_lab(pens, lab);
	return lab[0] >= 80 && de94(lab, white) < de94(lab, pens->pen[k].lab) ? -1 : (long)k;
}

/* ---- page mapping ---- */

int hpgl_map_page(const hpgl_profile_t *prof, const hpgl_place_t *pl, unsigned w, unsigned h,
		double wmm, double hmm, hpgl_map_t *m, char *err, size_t errlen)
{
	if (pl->paper < 0 || pl->paper >= HPGL_NPAPER || !prof->has_paper[pl->paper]) {
		snprintf(err, errlen, "profile %s has no paper %s", prof->name, hpgl_paper_name(pl->paper));
		return -1;
	}
	const int32_t *c = prof->clip[pl->paper];
	if (wmm <= 0 || hmm <= 0) {
		wmm = w * 25.4 / 96;
		hmm = h * 25.4 / 96;
	}
	int quarter = pl->rotate == 90 || pl->rotate == 270;
	/* the page's size in plotter units once rotated */
	double pw = (quarter ? hmm : wmm) * HPGL_PU_PER_MM * pl->scale,
		ph = (quarter ? wmm : hmm) * HPGL_PU_PER_MM * pl->scale;
	double cw = (double)c[2] - c[0], ch = (double)c[3] - c[1];
	double k = 1;
	if (pl->fit == 2 || (pl->fit == 1 && (pw > cw || ph > ch)))
		k = fmin(cw / pw, ch / ph);
	pw *= k;
	ph *= k;
	/* unit vectors of model x and y on the plotter, in thousandths of a pixel */
	double sx = pw / (quarter ? h : w) / 1000, sy = ph / (quarter ? w : h) / 1000;
	double ux[2], uy[2];
	switch (pl->rotate) {
	case 90: ux[0] = 0; ux[1] = sy; uy[0] = -sx; uy[1] = 0; break;
	case 180: ux[0] = -sx; ux[1] = 0; uy[0] = 0; uy[1] = -sy; break;
	case 270: ux[0] = 0; ux[1] = -sy; uy[0] = sx; uy[1] = 0; break;
	default: ux[0] = sx; ux[1] = 0; uy[0] = 0; uy[1] = sy; break;
	}
	if (pl->mirror == 1) {
		ux[0] = -ux[0];
		uy[0] = -uy[0];
	} else if (pl->mirror == 2) {
		ux[1] = -ux[1];
		uy[1] = -uy[1];
	}
	m->a = ux[0];
	m->b = uy[0];
	m->d = ux[1];
	m->e = uy[1];
	/* centre the page in the clip area */
	double cx = (c[0] + c[2]) / 2.0, cy = (c[1] + c[3]) / 2.0, mx = w * 500.0, my = h * 500.0;
	m->c = cx - (m->a * mx + m->b * my);
	m->f = cy - (m->d * mx + m->e * my);
	m->clip[0] = fmax(c[0], cx - pw / 2);
	m->clip[1] = fmax(c[1], cy - ph / 2);
	m->clip[2] = fmin(c[2], cx + pw / 2);
	m->clip[3] = fmin(c[3], cy + ph / 2);
	m->pu_per_px = (quarter ? sy : sx) * 1000;
	return 0;
}

void hpgl_map_point(const hpgl_map_t *m, int64_t x, int64_t y, double *X, double *Y)
{
	*X = m->a * (double)x + m->b * (double)y + m->c;
	*Y = m->d * (double)x + m->e * (double)y + m->f;
}
