/* gen_workloads.c: deterministic benchmark drawings in Locus meta and in plotutils' portable metafile. */
/*
 * Usage: gen_workloads WORKLOAD FORMAT [-s SCALE] [-o OUT]
 *   WORKLOAD  a  random-walk polylines (10,000 x 100 points = 990,000 segments
 *                plus one 4-segment frame: about 1M segments), width-1 strokes
 *             b  10,000 filled star-shaped polygons of random colours
 *                (3..12 vertices, 75,000 vertices) on a 4-vertex background
 *             c  contour map: marching-squares contour lines of a smooth field
 *                (sum of Gaussian bumps), chained into polylines
 *   FORMAT    text | binary   Locus meta, written with the meta writer API
 *             plot            GNU plotutils portable metafile ("#PLOT 2")
 *   -s SCALE  multiply the number of polylines/polygons (a, b) or the number
 *             of contour levels (c) by SCALE (default 1)
 *
 * Both formats describe the same picture on a 1024x768 page: every
 * coordinate is first rounded to thousandths of a pixel (the meta-language's
 * grid) and the plotutils file maps user units to pixels with
 * "fspace 0 0 1024 768" and prints the same thousandths. Colours are 8-bit
 * values (plotutils gets v * 257 on its 16-bit scale), lines are 1 pixel
 * wide, fills have no outline (plotutils pentype 0). The PRNG is a fixed
 * xorshift64* so the files are identical on every machine.
 */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "locus_meta.h"

#define PAGE_W 1024
#define PAGE_H 768

enum { FMT_TEXT, FMT_BINARY, FMT_PLOT };

/* One output: either a meta writer or a plotutils text stream. */
typedef struct {
	int fmt;
	FILE *f;
	meta_writer_t *w;
	int err;              /* first error seen (sticky) */
	char msg[256];
	long segments;        /* segments written (for the summary line) */
	long vertices;        /* polygon vertices written */
	long paths;
	meta_rgb_t colour;    /* plotutils side: current pen/fill colour */
	int have_colour;
	int mode;             /* plotutils side: 0 none yet, 1 stroke, 2 fill */
} out_t;

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;

static uint64_t rng_next(void)
{
	uint64_t x = rng_state;
	x ^= x >> 12;
	x ^= x << 25;
	x ^= x >> 27;
	rng_state = x;
	return x * 0x2545f4914f6cdd1dull;
}

/* Uniform double in [0, 1). */
static double rng_unit(void)
{
	return (double)(rng_next() >> 11) * (1.0 / 9007199254740992.0);
}

static meta_rgb_t rng_colour(void)
{
	return (meta_rgb_t)(rng_next() >> 40) & 0xffffff;
}

/* Round to the thousandths grid, so both formats carry the same numbers. */
static long fix(double v)
{
	return lround(v * 1000.0);
}

static int meta_sink(void *user, const void *buf, size_t n)
{
	return fwrite(buf, 1, n, (FILE *)user) == n ? 0 : -1;
}

static void fail_meta(out_t *o, int rc)
{
	if (o->err == 0) {
		o->err = rc;
		snprintf(o->msg, sizeof o->msg, "%s", meta_writer_error(o->w));
	}
}

/* Print a thousandths value as plotutils reads it: shortest decimal form. */
static void plot_num(FILE *f, long v)
{
	unsigned long a = v < 0 ? (unsigned long)-v : (unsigned long)v;
	unsigned frac = (unsigned)(a % 1000);
	if (v < 0)
		fputc('-', f);
	if (frac == 0)
		fprintf(f, "%lu", a / 1000);
	else if (frac % 100 == 0)
		fprintf(f, "%lu.%u", a / 1000, frac / 100);
	else if (frac % 10 == 0)
		fprintf(f, "%lu.%02u", a / 1000, frac / 10);
	else
		fprintf(f, "%lu.%03u", a / 1000, frac);
}

static void out_begin(out_t *o)
{
	if (o->fmt == FMT_PLOT) {
		fprintf(o->f, "#PLOT 2\no\n* 0 0 %d %d\n0 1\n", PAGE_W, PAGE_H);
		return;
	}
	int rc = meta_page(o->w, PAGE_W, PAGE_H);
	if (rc < 0)
		fail_meta(o, rc);
}

static void out_end(out_t *o)
{
	if (o->fmt == FMT_PLOT) {
		fputs("x\n", o->f);
		return;
	}
	int rc = meta_end_page(o->w);
	if (rc < 0)
		fail_meta(o, rc);
}

static void plot_colour(out_t *o, meta_rgb_t c, int fill)
{
	unsigned r = (c >> 16) & 255, g = (c >> 8) & 255, b = c & 255;
	int mode = fill ? 2 : 1;
	if (o->mode != mode) {
		/* strokes: pen on, no fill; fills: fill on, no outline */
		fputs(fill ? "h 0\nL 1\n" : "h 1\nL 0\n", o->f);
		o->mode = mode;
	}
	if (!o->have_colour || o->colour != c) {
		fprintf(o->f, "- %u %u %u\nD %u %u %u\n", r * 257, g * 257, b * 257,
			r * 257, g * 257, b * 257);
		o->colour = c;
		o->have_colour = 1;
	}
}

/* One path from n points (thousandths): stroked polyline or filled polygon. */
static void out_path(out_t *o, meta_rgb_t c, int fill, const long *xy, size_t n)
{
	if (n < 2 || o->err)
		return;
	o->paths++;
	if (fill)
		o->vertices += (long)n;
	else
		o->segments += (long)n - 1;
	if (o->fmt == FMT_PLOT) {
		FILE *f = o->f;
		plot_colour(o, c, fill);
		fputs("$ ", f);
		plot_num(f, xy[0]);
		fputc(' ', f);
		plot_num(f, xy[1]);
		fputc('\n', f);
		for (size_t i = 1; i < n; i++) {
			fputs(") ", f);
			plot_num(f, xy[2 * i]);
			fputc(' ', f);
			plot_num(f, xy[2 * i + 1]);
			fputc('\n', f);
		}
		fputs("E\n", f);
		return;
	}
	meta_writer_t *w = o->w;
	int rc = meta_colour(w, c);
	if (rc >= 0)
		rc = fill ? meta_fill(w) : meta_stroke(w);
	if (rc >= 0)
		rc = meta_move(w, xy[0] / 1000.0, xy[1] / 1000.0);
	for (size_t i = 1; i < n && rc >= 0; i++)
		rc = meta_draw(w, xy[2 * i] / 1000.0, xy[2 * i + 1] / 1000.0);
	if (rc >= 0)
		rc = meta_end(w);
	if (rc < 0)
		fail_meta(o, rc);
}

/* The page frame, a 4-segment stroke, so every workload starts alike. */
static void frame(out_t *o)
{
	long xy[10] = { fix(0.5), fix(0.5), fix(PAGE_W - 0.5), fix(0.5),
			fix(PAGE_W - 0.5), fix(PAGE_H - 0.5), fix(0.5), fix(PAGE_H - 0.5),
			fix(0.5), fix(0.5) };
	out_path(o, 0x000000, 0, xy, 5);
}

/* Workload a: random walks that bounce off the page edges. */
static void workload_a(out_t *o, int scale)
{
	long xy[200];
	frame(o);
	for (long p = 0; p < 10000L * scale; p++) {
		double x = 8 + rng_unit() * (PAGE_W - 16), y = 8 + rng_unit() * (PAGE_H - 16);
		meta_rgb_t c = rng_colour();
		for (int i = 0; i < 100; i++) {
			if (i > 0) {
				double a = rng_unit() * 6.283185307179586, len = 1 + rng_unit() * 5;
				x += len * cos(a);
				y += len * sin(a);
				if (x < 1) x = 2 - x;
				if (x > PAGE_W - 1) x = 2 * (PAGE_W - 1) - x;
				if (y < 1) y = 2 - y;
				if (y > PAGE_H - 1) y = 2 * (PAGE_H - 1) - y;
			}
			xy[2 * i] = fix(x);
			xy[2 * i + 1] = fix(y);
		}
		out_path(o, c, 0, xy, 100);
	}
}

/* Workload b: star-shaped polygons (angles increasing, so always simple:
 * even-odd and non-zero agree) with 3..12 vertices, 7.5 on average. */
static void workload_b(out_t *o, int scale)
{
	long xy[24];
	long bg[8] = { 0, 0, fix(PAGE_W), 0, fix(PAGE_W), fix(PAGE_H), 0, fix(PAGE_H) };
	out_path(o, 0xf4f0e6, 1, bg, 4);
	for (long p = 0; p < 10000L * scale; p++) {
		int n = 3 + (int)(p % 10);
		double cx = rng_unit() * PAGE_W, cy = rng_unit() * PAGE_H;
		double rmax = 6 + rng_unit() * 34;
		double a0 = rng_unit() * 6.283185307179586;
		meta_rgb_t c = rng_colour();
		for (int i = 0; i < n; i++) {
			double a = a0 + 6.283185307179586 * (i + 0.2 + 0.6 * rng_unit()) / n;
			double r = rmax * (0.35 + 0.65 * rng_unit());
			xy[2 * i] = fix(cx + r * cos(a));
			xy[2 * i + 1] = fix(cy + r * sin(a));
		}
		out_path(o, c, 1, xy, (size_t)n);
	}
}

/* ---- workload c: contour lines --------------------------------------- */

#define CNX 512                 /* cells across: 2 pixels each */
#define CNY 384
#define CBUMPS 40

static double bump_x[CBUMPS], bump_y[CBUMPS], bump_a[CBUMPS], bump_s[CBUMPS];

static double field(double x, double y)
{
	double v = 0;
	for (int k = 0; k < CBUMPS; k++) {
		double dx = x - bump_x[k], dy = y - bump_y[k];
		v += bump_a[k] * exp(-(dx * dx + dy * dy) / (2 * bump_s[k] * bump_s[k]));
	}
	return v + 0.3 * sin(x / 97.0) * cos(y / 83.0);
}

/* Edge ids: horizontal edge (i,j)-(i+1,j) is j*CNX+i; vertical edge
 * (i,j)-(i,j+1) is HOFF + j*(CNX+1)+i. Each edge links at most 2 segments. */
#define HOFF ((CNY + 1) * CNX)
#define NEDGES (HOFF + CNY * (CNX + 1))

typedef struct {
	double *g;          /* grid values (CNX+1) x (CNY+1) */
	double *ex, *ey;    /* crossing point of each edge */
	int32_t (*link)[2]; /* the (up to) two other edges joined to each edge */
	unsigned char *used;
	long *xy;           /* polyline buffer */
	size_t cap;
} contour_t;

static void add_link(contour_t *c, int32_t a, int32_t b)
{
	if (c->link[a][0] < 0) c->link[a][0] = b; else c->link[a][1] = b;
	if (c->link[b][0] < 0) c->link[b][0] = a; else c->link[b][1] = a;
}

static void crossing(contour_t *c, int32_t e, double level)
{
	int i, j, i2, j2;
	if (e < HOFF) { j = e / CNX; i = e % CNX; i2 = i + 1; j2 = j; }
	else { int r = e - HOFF; j = r / (CNX + 1); i = r % (CNX + 1); i2 = i; j2 = j + 1; }
	double v0 = c->g[j * (CNX + 1) + i], v1 = c->g[j2 * (CNX + 1) + i2];
	double t = (level - v0) / (v1 - v0);
	c->ex[e] = 2.0 * (i + t * (i2 - i));
	c->ey[e] = 2.0 * (j + t * (j2 - j));
}

/* Follow a chain from edge e (coming from prev) and write it out. */
static void trace(out_t *o, contour_t *c, int32_t e, meta_rgb_t col)
{
	size_t n = 0;
	int32_t prev = -1, start = e;
	for (;;) {
		if (n == c->cap) {
			c->cap *= 2;
			long *nxy = realloc(c->xy, c->cap * 2 * sizeof *nxy);
			if (!nxy) { o->err = META_ENOMEM; snprintf(o->msg, sizeof o->msg, "out of memory"); return; }
			c->xy = nxy;
		}
		c->xy[2 * n] = fix(c->ex[e]);
		c->xy[2 * n + 1] = fix(c->ey[e]);
		n++;
		c->used[e] = 1;
		int32_t next = c->link[e][0] != prev && c->link[e][0] >= 0 && !c->used[c->link[e][0]]
			? c->link[e][0] : c->link[e][1];
		if (next < 0 || c->used[next]) {
			if (next == start && n > 2) { /* closed ring */
				c->xy[2 * n] = c->xy[0];
				c->xy[2 * n + 1] = c->xy[1];
				n++;
			}
			break;
		}
		prev = e;
		e = next;
	}
	out_path(o, col, 0, c->xy, n);
}

static void workload_c(out_t *o, int scale)
{
	contour_t c = { 0 };
	for (int k = 0; k < CBUMPS; k++) {
		bump_x[k] = rng_unit() * PAGE_W;
		bump_y[k] = rng_unit() * PAGE_H;
		bump_a[k] = (rng_unit() < 0.5 ? -1 : 1) * (0.4 + rng_unit());
		bump_s[k] = 25 + rng_unit() * 80;
	}
	c.g = malloc(sizeof *c.g * (CNX + 1) * (CNY + 1));
	c.ex = malloc(sizeof *c.ex * NEDGES);
	c.ey = malloc(sizeof *c.ey * NEDGES);
	c.link = malloc(sizeof *c.link * NEDGES);
	c.used = malloc(NEDGES);
	c.cap = 1024;
	c.xy = malloc(c.cap * 2 * sizeof *c.xy);
	if (!c.g || !c.ex || !c.ey || !c.link || !c.used || !c.xy) {
		o->err = META_ENOMEM;
		snprintf(o->msg, sizeof o->msg, "out of memory");
		goto done;
	}
	double lo = 1e300, hi = -1e300;
	for (int j = 0; j <= CNY; j++)
		for (int i = 0; i <= CNX; i++) {
			double v = field(2.0 * i, 2.0 * j);
			c.g[j * (CNX + 1) + i] = v;
			if (v < lo) lo = v;
			if (v > hi) hi = v;
		}
	frame(o);
	int nlev = 200 * scale;
	for (int l = 0; l < nlev && !o->err; l++) {
		/* levels strictly between the extremes, never equal to a grid value */
		double level = lo + (hi - lo) * (l + 0.5) / nlev + 1e-9;
		double t = (double)l / (nlev - 1 > 0 ? nlev - 1 : 1);
		meta_rgb_t col = ((meta_rgb_t)(40 + 200 * t) << 16) | ((meta_rgb_t)(60 + 60 * (1 - t)) << 8)
			| (meta_rgb_t)(220 - 200 * t);
		for (int32_t e = 0; e < NEDGES; e++) c.link[e][0] = c.link[e][1] = -1;
		memset(c.used, 0, NEDGES);
		for (int j = 0; j < CNY; j++)
			for (int i = 0; i < CNX; i++) {
				double v[4] = { c.g[j * (CNX + 1) + i], c.g[j * (CNX + 1) + i + 1],
					c.g[(j + 1) * (CNX + 1) + i + 1], c.g[(j + 1) * (CNX + 1) + i] };
				/* edges: bottom, right, top, left */
				int32_t ed[4] = { j * CNX + i, HOFF + j * (CNX + 1) + i + 1,
					(j + 1) * CNX + i, HOFF + j * (CNX + 1) + i };
				int32_t hit[4];
				int nh = 0;
				for (int s = 0; s < 4; s++) {
					int a = v[s] > level, b = v[(s + 1) % 4] > level;
					if (a != b) { hit[nh++] = ed[s]; crossing(&c, ed[s], level); }
				}
				if (nh == 2)
					add_link(&c, hit[0], hit[1]);
				else if (nh == 4) { /* saddle: decide by the centre value */
					double mid = (v[0] + v[1] + v[2] + v[3]) / 4;
					if ((mid > level) == (v[0] > level)) {
						add_link(&c, hit[0], hit[1]);
						add_link(&c, hit[2], hit[3]);
					} else {
						add_link(&c, hit[0], hit[3]);
						add_link(&c, hit[1], hit[2]);
					}
				}
			}
		/* open chains first (start at an end), then closed rings */
		for (int32_t e = 0; e < NEDGES && !o->err; e++)
			if (!c.used[e] && c.link[e][0] >= 0 && c.link[e][1] < 0)
				trace(o, &c, e, col);
		for (int32_t e = 0; e < NEDGES && !o->err; e++)
			if (!c.used[e] && c.link[e][0] >= 0)
				trace(o, &c, e, col);
	}
done:
	free(c.g); free(c.ex); free(c.ey); free(c.link); free(c.used); free(c.xy);
}

static int usage(FILE *f, int rc)
{
	fprintf(f, "usage: gen_workloads a|b|c text|binary|plot [-s SCALE] [-o OUT]\n"
		"Write a benchmark drawing (see tests/bench/gen_workloads.c) to OUT (default stdout).\n");
	return rc;
}

int main(int argc, char **argv)
{
	const char *wl = NULL, *fmt = NULL, *outname = "-";
	int scale = 1;
	for (int i = 1; i < argc; i++) {
		if (!strcmp(argv[i], "--help")) return usage(stdout, 0);
		if (!strcmp(argv[i], "--version")) { printf("gen_workloads %s\n", LOCUS_VERSION); return 0; }
		if (!strcmp(argv[i], "-s") && i + 1 < argc) scale = atoi(argv[++i]);
		else if (!strcmp(argv[i], "-o") && i + 1 < argc) outname = argv[++i];
		else if (!wl) wl = argv[i];
		else if (!fmt) fmt = argv[i];
		else return usage(stderr, 64);
	}
	if (!wl || !fmt || scale < 1 || scale > 64 || strlen(wl) != 1 || wl[0] < 'a' || wl[0] > 'c')
		return usage(stderr, 64);
	out_t o = { 0 };
	if (!strcmp(fmt, "text")) o.fmt = FMT_TEXT;
	else if (!strcmp(fmt, "binary")) o.fmt = FMT_BINARY;
	else if (!strcmp(fmt, "plot")) o.fmt = FMT_PLOT;
	else return usage(stderr, 64);

	/* write to OUT.tmp and rename, so a failure leaves no partial file */
	char tmp[4096];
	int to_stdout = !strcmp(outname, "-");
	if (to_stdout) o.f = stdout;
	else {
		snprintf(tmp, sizeof tmp, "%s.tmp", outname);
		o.f = fopen(tmp, "wb");
		if (!o.f) { fprintf(stderr, "gen_workloads: %s: %s\n", tmp, strerror(errno)); return 74; }
	}
	static char iobuf[1 << 16];
	setvbuf(o.f, iobuf, _IOFBF, sizeof iobuf);
	if (o.fmt != FMT_PLOT) {
		o.w = meta_writer_new(meta_sink, o.f, o.fmt == FMT_BINARY); /* 1 binary, 0 text */
		if (!o.w) { fprintf(stderr, "gen_workloads: out of memory\n"); return 74; }
	}
	out_begin(&o);
	if (wl[0] == 'a') workload_a(&o, scale);
	else if (wl[0] == 'b') workload_b(&o, scale);
	else workload_c(&o, scale);
	out_end(&o);
	if (o.w && meta_writer_close(o.w) < 0 && !o.err) {
		o.err = META_EIO;
		snprintf(o.msg, sizeof o.msg, "write failed");
	}
	if (fflush(o.f) != 0 && !o.err) { o.err = META_EIO; snprintf(o.msg, sizeof o.msg, "write failed"); }
	if (!to_stdout && fclose(o.f) != 0 && !o.err) { o.err = META_EIO; snprintf(o.msg, sizeof o.msg, "write failed"); }
	if (o.err) {
		fprintf(stderr, "gen_workloads: %s: %s\n", outname, o.msg);
		if (!to_stdout) remove(tmp);
		return o.err == META_EIO ? 74 : 70;
	}
	if (!to_stdout && rename(tmp, outname) != 0) {
		fprintf(stderr, "gen_workloads: %s: %s\n", outname, strerror(errno));
		remove(tmp);
		return 74;
	}
	fprintf(stderr, "gen_workloads: %s %s x%d: %ld paths, %ld segments, %ld polygon vertices\n",
		wl, fmt, scale, o.paths, o.segments, o.vertices);
	return 0;
}
