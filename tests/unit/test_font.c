/* test_font.c: the stroke font (spec §5.5): glyph table, advances, replacement, transform. */
#include <math.h>
#include <stdlib.h>
#include "geom/scan.h"
#include "unit.h"

/* The glyph table as markdown rows, as docs/stroke-font.md lists it. */
static void listing_row(int ch, char *buf, size_t n)
{
	double adv;
	const char *src = scan_glyph_source(ch, &adv);
	char name[16];
	if (ch < 0)
		snprintf(name, sizeof name, "replacement");
	else if (ch == '|')
		snprintf(name, sizeof name, "`\\|`");
	else if (ch == '`')
		snprintf(name, sizeof name, "`` ` ``");
	else if (ch == ' ')
		snprintf(name, sizeof name, "space");
	else
		snprintf(name, sizeof name, "`%c`", ch);
	snprintf(buf, n, "| %02x | %s | %g | `%s` |", ch < 0 ? 0 : ch, name, adv, *src ? src : " ");
}

/* Every row of the listing must be in the document, so doc and table cannot drift apart. */
static int doc_matches(void)
{
	FILE *f = fopen("docs/stroke-font.md", "r");
	if (!f)
		return -1;
	static char doc[200000];
	size_t n = fread(doc, 1, sizeof doc - 1, f);
	fclose(f);
	doc[n] = 0;
	int missing = 0;
	char row[300];
	for (int ch = 0x1f; ch <= 0x7e; ch++) {
		listing_row(ch == 0x1f ? -1 : ch, row, sizeof row);
		if (!strstr(doc, row)) {
			printf("# not in docs/stroke-font.md: %s\n", row);
			missing++;
		}
	}
	return missing;
}

int main(int argc, char **argv)
{
	if (argc > 1 && strcmp(argv[1], "--listing") == 0) {
		char row[300];
		printf("| hex | char | advance | strokes |\n|---|---|---|---|\n");
		for (int ch = 0x20; ch <= 0x7f; ch++) {
			listing_row(ch == 0x7f ? -1 : ch, row, sizeof row);
			printf("%s\n", row);
		}
		return 0;
	}
	int dm = doc_matches();
	CHECK(dm == 0, "docs/stroke-font.md lists every glyph exactly as drivers/geom/font.c (%d missing)", dm);
	/* every printable character has a parseable glyph inside the font grid */
	int ok = 1, strokes = 0;
	for (int ch = 0x20; ch <= 0x7e; ch++) {
		double adv;
		const char *src = scan_glyph_source(ch, &adv);
		ok &= src != NULL && adv >= 2 && adv <= 6;
		scan_path_t p = { 0 };
		char s[2] = { (char)ch, 0 };
		scan_text_path(&p, s, 1, 0, 0, 6000, 0);
		for (size_t k = 0; k < p.npts; k++)
			ok &= p.pts[k].x >= 0 && p.pts[k].x <= 5000 && p.pts[k].y >= -2000 && p.pts[k].y <= 6500;
		strokes += (int)p.nsubs;
		ok &= ch == ' ' ? p.nsubs == 0 : p.nsubs > 0;
		scan_path_free(&p);
	}
	CHECK(ok, "95 glyphs parse, have strokes (but space) and stay in the grid");
	CHECK(strokes == 147, "the font has %d strokes", strokes);

	/* distinct shapes for look-alikes */
	CHECK(strcmp(scan_glyph_source('0', NULL), scan_glyph_source('O', NULL)) != 0 &&
		strcmp(scan_glyph_source('1', NULL), scan_glyph_source('l', NULL)) != 0 &&
		strcmp(scan_glyph_source('I', NULL), scan_glyph_source('l', NULL)) != 0, "0/O and 1/l/I differ");

	/* advances: "Hi" = 5 + 2 units; a UTF-8 character is one replacement glyph; bad bytes each one */
	CHECK(scan_text_advance("Hi", 2) == 7, "advance of Hi is 7 units");
	double rep;
	scan_glyph_source(0x01, &rep);
	CHECK(scan_text_advance("\xc3\xa9", 2) == rep, "a 2-byte UTF-8 character draws one replacement glyph");
	CHECK(scan_text_advance("\xff\xfe", 2) == 2 * rep, "invalid bytes draw one replacement each");
	/* spec §5.5 counts as a standard decoder: a truncated sequence is one maximal subpart */
	CHECK(scan_text_advance("\xe2\x82", 2) == rep, "a truncated sequence: one replacement glyph");
	CHECK(scan_text_advance("\xed\xa0\x80", 3) == 3 * rep, "a surrogate: three (ED then two stray bytes)");

	/* transform: size 12 doubles the 6-unit grid; angle 90 rotates about the origin */
	scan_path_t p = { 0 };
	scan_text_path(&p, "L", 1, 100000, 50000, 12000, 0);
	CHECK(p.npts == 3 && p.pts[0].x == 100000 && p.pts[0].y == 62000 && p.pts[2].x == 108000 &&
		p.pts[2].y == 50000, "L at (100,50) size 12: from (100,62) down and 8 right");
	scan_path_reset(&p);
	scan_text_path(&p, "L", 1, 100000, 50000, 12000, 90000);
	CHECK(p.pts[0].x == 88000 && p.pts[0].y == 50000 && p.pts[2].x == 100000 && p.pts[2].y == 58000,
		"rotated 90 degrees: the L's top points to -x");
	scan_path_reset(&p);
	scan_text_path(&p, ".", 1, 0, 0, 6000, 0);
	CHECK(p.nsubs == 1 && p.subs[0].n == 5 && p.pts[0].x == p.pts[4].x, "a dot is a small closed square (visible at any size)");
	scan_path_free(&p);
	return UNIT_DONE();
}
