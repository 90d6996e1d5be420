/* diff_raster.c: pixel statistics of two pictures fed a row at a time, and their report. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "diff/diff.h"

#define FIRST_MAX 64

struct diff_raster {
	diff_opts_t o;
	unsigned width, height;
	uint64_t ndiff;
	unsigned maxc[3];
	double sse;
	unsigned x0, y0, x1, y1;        /* bounding box of the differing pixels (ndiff > 0) */
	unsigned nfirst;
	struct { unsigned x, y; uint8_t a[3], b[3]; } first[FIRST_MAX];
};

void diff_opts_default(diff_opts_t *o)
{
	memset(o, 0, sizeof *o);
	o->psnr_min = -1;
	o->hpgl_tol = 0.5;
	o->nfirst = 10;
}

void diff_json_str(FILE *out, const char *s)
{
	fputc('"', out);
	for (; *s; s++) {
		unsigned char c = (unsigned char)*s;
		if (c == '"' || c == '\\')
			fprintf(out, "\\%c", c);
		else if (c < 0x20)
			fprintf(out, "\\u%04x", c);
		else
			fputc(c, out);
	}
	fputc('"', out);
}

diff_raster_t *diff_raster_new(unsigned width, unsigned height, const diff_opts_t *o)
{
	diff_raster_t *d = calloc(1, sizeof *d);
	if (!d)
		return NULL;
	d->o = *o;
	if (d->o.nfirst > FIRST_MAX)
		d->o.nfirst = FIRST_MAX;
	d->width = width;
	d->height = height;
	return d;
}

void diff_raster_row(diff_raster_t *d, unsigned y, const uint8_t *a, const uint8_t *b, uint8_t *mark)
{
	for (unsigned x = 0; x < d->width; x++) {
		const uint8_t *p = a + 3 * x, *q = b + 3 * x;
		int differs = 0;
		for (int c = 0; c < 3; c++) {
			int dv = p[c] - q[c];
			unsigned ad = (unsigned)(dv < 0 ? -dv : dv);
			d->sse += (double)dv * dv;
			if (ad > d->maxc[c])
				d->maxc[c] = ad;
			if (ad > d->o.tol[c])
				differs = 1;
		}
		if (mark) {
			uint8_t *m = mark + 3 * x;
			if (differs)
				m[0] = 255, m[1] = 0, m[2] = 0;
			else   /* a quarter of A over white */
				for (int c = 0; c < 3; c++)
					m[c] = (uint8_t)(191 + (p[c] + 2) / 4);
		}
		if (!differs)
			continue;
		if (d->ndiff == 0) {
			d->x0 = d->x1 = x;
			d->y0 = d->y1 = y;
		} else {
			d->x0 = x < d->x0 ? x : d->x0;
			d->x1 = x > d->x1 ? x : d->x1;
			d->y1 = y;
		}
		if (d->nfirst < d->o.nfirst) {
			d->first[d->nfirst].x = x;
			d->first[d->nfirst].y = y;
			memcpy(d->first[d->nfirst].a, p, 3);
			memcpy(d->first[d->nfirst].b, q, 3);
			d->nfirst++;
		}
		d->ndiff++;
	}
}

int diff_raster_report(diff_raster_t *d, const char *a, const char *b, FILE *out)
{
	uint64_t npix = (uint64_t)d->width * d->height;
	double mse = d->sse / ((double)npix * 3);
	double psnr = mse > 0 ? 10.0 * log10(255.0 * 255.0 / mse) : INFINITY;
	unsigned maxc = d->maxc[0] > d->maxc[1] ? d->maxc[0] : d->maxc[1];
	maxc = d->maxc[2] > maxc ? d->maxc[2] : maxc;
	int same = d->ndiff <= d->o.maxpix || (d->o.psnr_min >= 0 && psnr >= d->o.psnr_min);
	if (d->o.psnr_min >= 0 && d->o.maxpix == 0)
		same = psnr >= d->o.psnr_min || d->ndiff == 0;
	char ps[32];
	if (isinf(psnr))
		snprintf(ps, sizeof ps, "inf");
	else
		snprintf(ps, sizeof ps, "%.2f", psnr);
	if (d->o.json) {
		fprintf(out, "{\"kind\":\"raster\",\"a\":");
		diff_json_str(out, a);
		fprintf(out, ",\"b\":");
		diff_json_str(out, b);
		fprintf(out, ",\"same\":%s,\"width\":%u,\"height\":%u,\"pixels\":%llu,\"differing\":%llu,"
			"\"max\":[%u,%u,%u],\"psnr\":%s", same ? "true" : "false", d->width, d->height,
			(unsigned long long)npix, (unsigned long long)d->ndiff, d->maxc[0], d->maxc[1],
			d->maxc[2], isinf(psnr) ? "null" : ps);
		if (d->ndiff)
			fprintf(out, ",\"bbox\":[%u,%u,%u,%u]", d->x0, d->y0, d->x1, d->y1);
		else
			fprintf(out, ",\"bbox\":null");
		fprintf(out, ",\"first\":[");
		for (unsigned k = 0; k < d->nfirst; k++) {
			const uint8_t *p = d->first[k].a, *q = d->first[k].b;
			fprintf(out, "%s{\"x\":%u,\"y\":%u,\"a\":\"#%02x%02x%02x\",\"b\":\"#%02x%02x%02x\"}",
				k ? "," : "", d->first[k].x, d->first[k].y, p[0], p[1], p[2], q[0], q[1], q[2]);
		}
		fprintf(out, "]}\n");
		free(d);
		return same ? 0 : 1;
	}
	fprintf(out, "%s %s: %llu of %llu pixels differ, max channel difference %u, PSNR %s dB",
		a, b, (unsigned long long)d->ndiff, (unsigned long long)npix, maxc, ps);
	if (d->ndiff)
		fprintf(out, ", in %ux%u at (%u,%u)", d->x1 - d->x0 + 1, d->y1 - d->y0 + 1, d->x0, d->y0);
	fputc('\n', out);
	if (d->o.verbose) {
		fprintf(out, "  size %ux%u; tolerance %u,%u,%u; max difference R %u G %u B %u\n",
			d->width, d->height, d->o.tol[0], d->o.tol[1], d->o.tol[2], d->maxc[0], d->maxc[1],
			d->maxc[2]);
		if (d->ndiff)
			fprintf(out, "  differences within x %u..%u, y %u..%u\n", d->x0, d->x1, d->y0, d->y1);
		for (unsigned k = 0; k < d->nfirst; k++) {
			const uint8_t *p = d->first[k].a, *q = d->first[k].b;
			fprintf(out, "  pixel (%u,%u): #%02x%02x%02x vs #%02x%02x%02x\n", d->first[k].x,
				d->first[k].y, p[0], p[1], p[2], q[0], q[1], q[2]);
		}
		if (d->ndiff > d->nfirst)
			fprintf(out, "  ... %llu more\n", (unsigned long long)(d->ndiff - d->nfirst));
	}
	free(d);
	return same ? 0 : 1;
}

int diff_raster_sizes(const char *a, const char *b, unsigned wa, unsigned ha, unsigned wb,
		unsigned hb, const diff_opts_t *o, FILE *out)
{
	if (o->json) {
		fprintf(out, "{\"kind\":\"raster\",\"a\":");
		diff_json_str(out, a);
		fprintf(out, ",\"b\":");
		diff_json_str(out, b);
		fprintf(out, ",\"same\":false,\"sizes\":[[%u,%u],[%u,%u]]}\n", wa, ha, wb, hb);
	} else {
		fprintf(out, "%s %s: sizes differ: %ux%u vs %ux%u (compare them with --scale)\n", a, b,
			wa, ha, wb, hb);
	}
	return 1;
}
