/* test_contour_golden.c: a small contour map (bands + iso-lines) compared byte for byte with its fixture.
 *
 * The picture: fixtures/contour/trifocal.meta, described in fixtures/README.md.
 * Run with LOCUS_RECORD=1 in the environment to (re)write the fixture, then
 * look at it (locus-raster) before committing it.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "contour.h"
#include "golden.h"

#define GOLDEN "fixtures/contour/trifocal.meta"

/* 3-point distance sum on a 65 x 49 grid over [-3, 3] x [-2.25, 2.25], drawn
 * on a 260 x 196 page, 4 pixels per cell; a NaN hole at the lower right. */
static int render(membuf_t *m)
{
	enum { NX = 65, NY = 49, NL = 9 };
	static float z[NX * NY];
	static const double px[3] = { -1, 1, 0 }, py[3] = { 0, 0, 1.2 };
	for (int j = 0; j < NY; j++)
		for (int i = 0; i < NX; i++) {
			double x = -3 + 6.0 * i / (NX - 1), y = -2.25 + 4.5 * j / (NY - 1), s = 0;
			for (int k = 0; k < 3; k++)
				s += sqrt((x - px[k]) * (x - px[k]) + (y - py[k]) * (y - py[k]));
			z[j * NX + i] = (float)s;
		}
	for (int j = 6; j < 12; j++)
		for (int i = 48; i < 56; i++)
			z[j * NX + i] = NAN;
	double levels[NL];
	meta_rgb_t lines[NL], bands[NL + 1];
	for (int l = 0; l < NL; l++)
		levels[l] = 3.5 + 0.75 * l;
	contour_palette(lines, NL);
	contour_palette(bands, NL + 1);
	for (int k = 0; k <= NL; k++) /* bands: the palette mixed 1:3 with white */
		bands[k] = (((bands[k] >> 16 & 255) + 3 * 255) / 4) << 16 | (((bands[k] >> 8 & 255) + 3 * 255) / 4) << 8 |
		           ((bands[k] & 255) + 3 * 255) / 4;
	contour_grid_t g = { z, NX, NY, { 0 } };
	contour_map_rect(g.m, NX, NY, 2, 2, 258, 194);
	contour_style_t st = { lines, 1.5 };
	meta_writer_t *w = meta_writer_new(membuf_write, m, META_ENC_TEXT);
	int rc = w ? 0 : -1;
	if (rc == 0)
		rc = meta_page(w, 260, 196);
	if (rc == 0)
		rc = meta_clear(w, 0x404040);
	if (rc == 0)
		rc = contour_write_bands(w, &g, levels, NL, bands, 0x808080, 2, 2, 256, 192);
	if (rc == 0)
		rc = contour_write_meta(w, &g, levels, NL, &st, NULL);
	if (rc == 0)
		rc = meta_end_page(w);
	if (w && meta_writer_close(w) < 0)
		rc = -1;
	return rc;
}

int main(void)
{
	membuf_t m = { 0 };
	int rc = render(&m);
	CHECK(rc == 0, "the contour map renders (%s)", contour_error());
	golden_check(GOLDEN, &m);
	return UNIT_DONE();
}
