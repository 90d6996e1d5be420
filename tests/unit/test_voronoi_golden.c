/* test_voronoi_golden.c: two small weighted tessellations compared byte for byte with their fixture.
 *
 * The pictures: fixtures/voronoi/weighted.meta (page 1 additive, page 2
 * multiplicative weights), described in fixtures/README.md. Run with
 * LOCUS_RECORD=1 in the environment to (re)write the fixture, then look at it
 * (locus-raster) before committing it.
 */
#include <stdio.h>
#include <stdlib.h>

#include "golden.h"
#include "voronoi.h"

#define GOLDEN "fixtures/voronoi/weighted.meta"

/* Plane window [0, 8] x [0, 6] on a 256 x 192 page. Nucleus 0 is the heavy
 * one (the thesis' "varying the weight of a nucleus"): on page 1 its additive
 * weight pushes its neighbours back, on page 2 its multiplicative weight
 * makes its cell swallow space and cuts the others into circle arcs. */
static const struct {
	int kind;
	double ax, ay, bx, by, wadd, wmul;
	meta_rgb_t colour;
} spec[] = {
	{ VORONOI_POINT, 4.0, 3.0, 0, 0, 0.9, 1.8, 0xf4a6a6 },
	{ VORONOI_POINT, 1.2, 1.0, 0, 0, 0.0, 1.0, 0xa6c8f4 },
	{ VORONOI_POINT, 6.8, 5.0, 0, 0, 0.2, 1.1, 0xb8e6a8 },
	{ VORONOI_POINT, 2.0, 4.8, 0, 0, 0.1, 0.9, 0xf4e3a6 },
	{ VORONOI_POINT, 7.0, 1.2, 0, 0, 0.0, 1.0, 0xd8b4f0 },
	{ VORONOI_SEGMENT, 0.5, 2.6, 1.6, 3.4, 0.0, 1.0, 0xa6ece6 },
	{ VORONOI_SEGMENT, 5.2, 0.6, 6.0, 2.2, 0.3, 1.2, 0xf0c8a0 },
	{ VORONOI_SEGMENT, 3.2, 5.4, 5.2, 5.4, 0.0, 1.0, 0xc8c8c8 },
	{ VORONOI_POINT, 3.0, 1.4, 0, 0, 0.0, 0.8, 0xe6f0a6 },
};
#define NN (sizeof spec / sizeof spec[0])

static int page(meta_writer_t *w, int metric)
{
	voronoi_nucleus_t nuc[NN];
	for (size_t k = 0; k < NN; k++) {
		nuc[k].kind = spec[k].kind;
		nuc[k].a[0] = spec[k].ax;
		nuc[k].a[1] = spec[k].ay;
		nuc[k].a[2] = 0;
		nuc[k].b[0] = spec[k].bx;
		nuc[k].b[1] = spec[k].by;
		nuc[k].b[2] = 0;
		nuc[k].weight = metric == VORONOI_ADDITIVE ? spec[k].wadd : spec[k].wmul;
		nuc[k].colour = spec[k].colour;
	}
	voronoi_t v = { nuc, NN, metric, { 0 } };
	voronoi_map_window(v.m, 0, 0, 8, 6, 0, 0, 256, 192);
	voronoi_rect_t r = { 0, 0, 256, 192 };
	voronoi_style_t st = { 1, 1, 0x202020, 1, 2, 1, 0x000000, 2.5 };
	int rc = meta_page(w, 256, 192);
	if (rc == 0)
		rc = voronoi_write_meta(w, &v, &r, &st, NULL);
	if (rc == 0)
		rc = meta_end_page(w);
	return rc;
}

int main(void)
{
	membuf_t m = { 0 };
	meta_writer_t *w = meta_writer_new(membuf_write, &m, META_ENC_TEXT);
	int rc = w ? page(w, VORONOI_ADDITIVE) : -1;
	if (rc == 0)
		rc = page(w, VORONOI_MULTIPLICATIVE);
	if (w && meta_writer_close(w) < 0)
		rc = -1;
	CHECK(rc == 0, "the tessellations render (%s)", voronoi_error());
	golden_check(GOLDEN, &m);
	return UNIT_DONE();
}
