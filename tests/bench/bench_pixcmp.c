/* bench_pixcmp.c: raw-pixel PSNR and silhouette difference of two PPM pictures, for the surface benchmarks.
 *
 * usage: bench_pixcmp [-b R,G,B] A.ppm B.ppm [--help] [--version]
 *
 * Reads two binary PPM (P6, maxval 255) pictures of the same size and prints one line
 *   psnr_db=P silhouette_px=S diff_px=D max_diff=M
 * P: PSNR over all samples, 10 log10(255^2 / mean squared difference), "inf" when identical;
 * S: pixels that are background in one picture and not in the other (the outline of the
 * object moved); D: pixels with any channel different; M: largest channel difference.
 * The background colour is -b R,G,B, else the top-left pixel of A (both benchmark views have
 * background in their corners). The values are compared as stored: PPM has no gamma chunk,
 * which is why the bench asks POV-Ray for PPM (+FP) rather than PNG (its gAMA chunk makes
 * ImageMagick convert the values, about 12 dB off).
 * Exit: 0, 64 usage, 65 bad or mismatched pictures, 66 a file cannot be opened.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef LOCUS_VERSION
#define LOCUS_VERSION "unknown"
#endif

typedef struct {
	long w, h;
	unsigned char *px; /* w * h * 3 bytes */
} picture_t;

/* header_number: the next decimal number of a PPM header, skipping blanks and # comments; -1 if none */
static long header_number(FILE *f)
{
	int c = getc(f);
	for (;;) {
		while (c == ' ' || c == '\t' || c == '\n' || c == '\r')
			c = getc(f);
		if (c != '#')
			break;
		while (c != '\n' && c != EOF)
			c = getc(f);
	}
	if (c < '0' || c > '9')
		return -1;
	long v = 0;
	while (c >= '0' && c <= '9') {
		if (v > 100000000)
			return -1;
		v = v * 10 + (c - '0');
		c = getc(f);
	}
	/* exactly one blank ends the header's last number; others are skipped above */
	if (c != ' ' && c != '\t' && c != '\n' && c != '\r')
		return -1;
	return v;
}

/* read_ppm: load PATH into P; 0, or prints why and returns the exit code (65 or 66) */
static int read_ppm(const char *path, picture_t *p)
{
	FILE *f = fopen(path, "rb");
	if (!f) {
		fprintf(stderr, "bench_pixcmp: %s: %s\n", path, strerror(errno));
		return 66;
	}
	int rc = 65;
	const char *why = "not a binary PPM (P6)";
	p->px = NULL;
	if (getc(f) != 'P' || getc(f) != '6')
		goto done;
	p->w = header_number(f);
	p->h = header_number(f);
	long maxval = header_number(f);
	if (p->w < 1 || p->h < 1 || p->w * p->h > 100000000L) {
		why = "bad size in the PPM header";
		goto done;
	}
	if (maxval != 255) {
		why = "maxval is not 255 (only 8-bit PPM is compared)";
		goto done;
	}
	size_t n = (size_t)p->w * (size_t)p->h * 3;
	p->px = malloc(n);
	if (!p->px) {
		why = "out of memory";
		goto done;
	}
	if (fread(p->px, 1, n, f) != n) {
		why = "truncated pixel data";
		goto done;
	}
	rc = 0;
done:
	if (rc != 0) {
		fprintf(stderr, "bench_pixcmp: %s: %s\n", path, why);
		free(p->px);
		p->px = NULL;
	}
	fclose(f);
	return rc;
}

/* parse_rgb: "R,G,B" with 0..255 parts into BG; 0 or -1 */
static int parse_rgb(const char *s, unsigned char bg[3])
{
	int r, g, b;
	char end;
	if (sscanf(s, "%d,%d,%d%c", &r, &g, &b, &end) != 3 || r < 0 || r > 255 || g < 0 || g > 255 || b < 0 ||
	    b > 255)
		return -1;
	bg[0] = (unsigned char)r;
	bg[1] = (unsigned char)g;
	bg[2] = (unsigned char)b;
	return 0;
}

int main(int argc, char **argv)
{
	const char *name[2] = { NULL, NULL };
	unsigned char bg[3];
	int have_bg = 0, nname = 0;
	for (int a = 1; a < argc; a++) {
		if (!strcmp(argv[a], "--help")) {
			printf("usage: bench_pixcmp [-b R,G,B] A.ppm B.ppm\n"
			       "Raw-pixel PSNR, silhouette pixels (background in one picture only; background\n"
			       "colour -b, else A's top-left pixel), differing pixels and the largest channel\n"
			       "difference of two 8-bit P6 pictures of the same size.\n");
			return 0;
		} else if (!strcmp(argv[a], "--version")) {
			printf("bench_pixcmp %s\n", LOCUS_VERSION);
			return 0;
		} else if (!strcmp(argv[a], "-b") && a + 1 < argc) {
			if (parse_rgb(argv[++a], bg) < 0) {
				fprintf(stderr, "bench_pixcmp: -b wants R,G,B with parts 0..255, not '%s'\n", argv[a]);
				return 64;
			}
			have_bg = 1;
		} else if (argv[a][0] == '-' && argv[a][1] != '\0') {
			fprintf(stderr, "bench_pixcmp: unknown option '%s' (try --help)\n", argv[a]);
			return 64;
		} else if (nname < 2) {
			name[nname++] = argv[a];
		} else {
			fprintf(stderr, "bench_pixcmp: one picture too many: '%s' (try --help)\n", argv[a]);
			return 64;
		}
	}
	if (nname != 2) {
		fprintf(stderr, "bench_pixcmp: two pictures wanted (try --help)\n");
		return 64;
	}
	picture_t p[2];
	int rc = read_ppm(name[0], &p[0]);
	if (rc != 0)
		return rc;
	rc = read_ppm(name[1], &p[1]);
	if (rc != 0) {
		free(p[0].px);
		return rc;
	}
	if (p[0].w != p[1].w || p[0].h != p[1].h) {
		fprintf(stderr, "bench_pixcmp: %s is %ldx%ld but %s is %ldx%ld\n", name[0], p[0].w, p[0].h, name[1],
		        p[1].w, p[1].h);
		free(p[0].px);
		free(p[1].px);
		return 65;
	}
	if (!have_bg)
		memcpy(bg, p[0].px, 3);
	size_t n = (size_t)p[0].w * (size_t)p[0].h;
	double sq = 0;
	size_t silhouette = 0, differ = 0;
	int maxd = 0;
	for (size_t i = 0; i < n; i++) {
		const unsigned char *a = p[0].px + 3 * i, *b = p[1].px + 3 * i;
		int d2 = 0, worst = 0;
		for (int c = 0; c < 3; c++) {
			int d = abs(a[c] - b[c]);
			d2 += d * d;
			if (d > worst)
				worst = d;
		}
		sq += d2;
		differ += worst > 0;
		if (worst > maxd)
			maxd = worst;
		silhouette += !memcmp(a, bg, 3) != !memcmp(b, bg, 3);
	}
	if (sq == 0)
		printf("psnr_db=inf");
	else
		printf("psnr_db=%.2f", 10 * log10(255.0 * 255.0 * 3 * (double)n / sq));
	printf(" silhouette_px=%zu diff_px=%zu max_diff=%d\n", silhouette, differ, maxd);
	free(p[0].px);
	free(p[1].px);
	return 0;
}
