/* emu_compare.c: what an emulator received against the HP-GL the job should have delivered:
 * the bytes, and the strokes through the HP-GL reader as multisets (none missing, none extra). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "emu.h"
#include "hpgl/read/hpgl_read.h"

/* Canonical text of each stroke, sorted, for a multiset comparison. */
static int cmp_str(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

static char **stroke_keys(const hpgl_doc_t *d)
{
	char **k = calloc(d->nstrokes + 1, sizeof *k);
	for (size_t i = 0; k && i < d->nstrokes; i++) {
		const hpgl_rstroke_t *s = &d->strokes[i];
		size_t cap = 32 + s->n * 40, n = 0;
		k[i] = malloc(cap);
		if (!k[i])
			exit(70);
		n += (size_t)snprintf(k[i] + n, cap - n, "%d %d", s->pen, s->kind);
		for (size_t j = 0; j < s->n; j++)
			n += (size_t)snprintf(k[i] + n, cap - n, " %.3f,%.3f", d->pts[s->start + j].x, d->pts[s->start + j].y);
	}
	if (k)
		qsort(k, d->nstrokes, sizeof *k, cmp_str);
	return k;
}

/* Compare the record with the expected HP-GL; prints the words; 0 when the same. */
int emu_compare(const unsigned char *got, size_t ng, const char *expect)
{
	FILE *f = fopen(expect, "rb");
	if (!f) {
		printf(" expect=unreadable");
		return 1;
	}
	hpgl_doc_t a, b;
	memset(&a, 0, sizeof a);
	memset(&b, 0, sizeof b);
	char err[300];
	if (hpgl_read_stream(f, expect, &a, err, sizeof err)) {
		printf(" expect=bad(%s)", err);
		fclose(f);
		return 1;
	}
	rewind(f);
	size_t ne = 0, first = (size_t)-1;
	int c;
	while ((c = getc(f)) != EOF) {
		if (ne < ng && got[ne] != c && first == (size_t)-1)
			first = ne;
		ne++;
	}
	fclose(f);
	if (first == (size_t)-1 && ne != ng)
		first = ne < ng ? ne : ng;
	int bad = first != (size_t)-1;
	if (bad)
		printf(" bytes=differ@%zu(expected %zu, got %zu)", first, ne, ng);
	else
		printf(" bytes=same");
	if (hpgl_read_mem(got, ng, "received", &b, err, sizeof err)) {
		printf(" strokes=unreadable(%s)", err);
		hpgl_doc_free(&a);
		hpgl_doc_free(&b);
		return 1;
	}
	char **ka = stroke_keys(&a), **kb = stroke_keys(&b);
	size_t i = 0, j = 0, missing = 0, extra = 0;
	while (i < a.nstrokes || j < b.nstrokes) {
		int d = i == a.nstrokes ? 1 : j == b.nstrokes ? -1 : strcmp(ka[i], kb[j]);
		if (d == 0) {
			i++;
			j++;
		} else if (d < 0) {
			missing++;
			i++;
		} else {
			extra++;
			j++;
		}
	}
	printf(" strokes=%s expected=%zu got=%zu missing=%zu extra=%zu", missing || extra ? "differ" : "same",
		a.nstrokes, b.nstrokes, missing, extra);
	for (size_t k = 0; k < a.nstrokes; k++)
		free(ka[k]);
	for (size_t k = 0; k < b.nstrokes; k++)
		free(kb[k]);
	free(ka);
	free(kb);
	hpgl_doc_free(&a);
	hpgl_doc_free(&b);
	return bad || missing || extra;
}
