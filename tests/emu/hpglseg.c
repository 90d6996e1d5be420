/* hpglseg.c: print the pen-down segments of HP-GL files, one per line ("pen x1,y1 x2,y2" with
 * the ends in a fixed order), through the HP-GL reader, for multiset comparisons with sort:
 * pieces of a job delivered in parts must give the segments of the whole, none twice, none
 * missing. A file may end mid-command (a part cut at a journal's boundary): a trailing comma is
 * dropped and the command closed. A part that does not begin with a command (a resumed job
 * begins by ending the command the plotter held unfinished: the job's next bytes up to where
 * that command may end, then ';') is read from after its first ';', as a fresh plotter would
 * draw it.   hpgl-segments FILE...   (exit 65 on a read error) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hpgl/read/hpgl_read.h"

static int one(const char *path)
{
	FILE *f = fopen(path, "rb");
	if (!f) {
		perror(path);
		return 66;
	}
	size_t cap = 1 << 16, n = 0;
	char *buf = malloc(cap + 2);
	for (size_t r; buf && (r = fread(buf + n, 1, cap - n, f)) > 0;) {
		n += r;
		if (n == cap) {
			cap *= 2;
			buf = realloc(buf, cap + 2);
		}
	}
	fclose(f);
	if (!buf)
		return 70;
	size_t from = 0;
	while (from < n && (buf[from] == ' ' || buf[from] == '\r' || buf[from] == '\n'))
		from++;
	int cmd = from + 1 < n && ((buf[from] | 0x20) >= 'a' && (buf[from] | 0x20) <= 'z')
		&& ((buf[from + 1] | 0x20) >= 'a' && (buf[from + 1] | 0x20) <= 'z');
	if (from < n && !cmd && buf[from] != 27) {
		char *semi = memchr(buf + from, ';', n - from);
		if (semi) {
			from = (size_t)(semi + 1 - buf);
			memmove(buf, buf + from, n - from);
			n -= from;
		}
	}
	while (n > 0 && buf[n - 1] == ',')
		n--;
	buf[n++] = ';';
	hpgl_doc_t d;
	memset(&d, 0, sizeof d);
	char err[300];
	int rc = 0;
	if (hpgl_read_mem(buf, n, path, &d, err, sizeof err)) {
		fprintf(stderr, "%s\n", err);
		rc = 65;
	}
	for (size_t s = 0; s < d.nstrokes; s++)
		for (size_t k = 1; k < d.strokes[s].n; k++) {
			const hpgl_rpt_t *a = &d.pts[d.strokes[s].start + k - 1], *b = a + 1;
			if (a->x > b->x || (a->x == b->x && a->y > b->y)) {
				const hpgl_rpt_t *t = a;
				a = b;
				b = t;
			}
			printf("%d %.3f,%.3f %.3f,%.3f\n", d.strokes[s].pen, a->x, a->y, b->x, b->y);
		}
	hpgl_doc_free(&d);
	free(buf);
	return rc;
}

int main(int argc, char **argv)
{
	int rc = 0;
	for (int i = 1; i < argc; i++) {
		int r = one(argv[i]);
		if (r)
			rc = r;
	}
	return rc;
}
