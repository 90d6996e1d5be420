/* test_meta_utf8.c: meta_utf8_next counts characters as a standard decoder does (the counts of
 * fixtures/spec/utf8-cases.txt, recorded from Python's decoder), the stroke font advances by the
 * same characters, and the writer keeps exactly the well-formed sequences raw. */
#include <stdlib.h>
#include "meta_int.h"
#include "geom/scan.h"
#include "unit.h"

static size_t unhex(const char *h, unsigned char *out, size_t cap)
{
	size_t n = 0;
	unsigned v;
	while (n < cap && sscanf(h + 2 * n, "%2x", &v) == 1)
		out[n++] = (unsigned char)v;
	return n;
}

int main(void)
{
	FILE *f = fopen("fixtures/spec/utf8-cases.txt", "r");
	CHECK(f != NULL, "fixtures/spec/utf8-cases.txt opened");
	if (!f)
		return UNIT_DONE();
	char line[256], hex[200];
	int cases = 0, wrong = 0, font_wrong = 0;
	double rep;
	scan_glyph_source(-1, &rep);
	while (fgets(line, sizeof line, f)) {
		unsigned want;
		if (line[0] == '#' || sscanf(line, "%199s %u", hex, &want) != 2)
			continue;
		unsigned char b[100];
		size_t n = unhex(hex, b, sizeof b), k = 0;
		unsigned got = 0;
		double adv = 0, a;
		while (k < n) {
			uint32_t cp;
			k += meta_utf8_next(b + k, n - k, &cp);
			got++;
			scan_glyph_source(cp >= 0x20 && cp <= 0x7e ? (int)cp : -1, &a);
			adv += a;
		}
		cases++;
		if (got != want) {
			if (!wrong)
				printf("# %s: %u characters, a standard decoder finds %u\n", hex, got, want);
			wrong++;
		}
		if (scan_text_advance((const char *)b, n) != adv)
			font_wrong++;
	}
	fclose(f);
	CHECK(cases >= 300 && wrong == 0, "%d byte strings: the decoder's character counts (%d differ)", cases, wrong);
	CHECK(font_wrong == 0, "the font advances by the same characters (%d differ)", font_wrong);
	/* meta_utf8_len: exactly the well-formed multi-byte sequences */
	CHECK(meta_utf8_len((const unsigned char *)"\xef\xbf\xbd", 3) == 3, "an encoded U+FFFD is well-formed");
	CHECK(meta_utf8_len((const unsigned char *)"\xed\xa0\x80", 3) == 0, "a surrogate is not");
	CHECK(meta_utf8_len((const unsigned char *)"\xe0\x80\xaf", 3) == 0, "an overlong form is not");
	CHECK(meta_utf8_len((const unsigned char *)"\xf4\x90\x80\x80", 4) == 0, "above U+10FFFF is not");
	CHECK(meta_utf8_len((const unsigned char *)"\xf0\x9f\x98\x80", 4) == 4, "U+1F600 is");
	return UNIT_DONE();
}
