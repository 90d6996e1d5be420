/* test_meta.c: meta-language numbers, writer/reader round trips and state elision. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "unit.h"
#include "locus_meta.h"
#include "meta_int.h"

/* A growable memory sink for the writer. */
typedef struct {
	char *p;
	size_t n, cap;
	int fail_after; /* >0: fail the write that would pass this many bytes */
} sink_t;

static int sink_write(void *user, const void *buf, size_t n)
{
	sink_t *s = user;
	if (s->fail_after && s->n + n > (size_t)s->fail_after)
		return -1;
	if (s->n + n + 1 > s->cap) {
		s->cap = (s->n + n + 1) * 2;
		s->p = realloc(s->p, s->cap);
	}
	memcpy(s->p + s->n, buf, n);
	s->n += n;
	s->p[s->n] = 0;
	return 0;
}

static const char *fmt(meta_fix_t v)
{
	static char buf[16];
	meta_fix_format(v, buf);
	return buf;
}

static int parse(const char *s, meta_fix_t *v, int *why)
{
	return meta_fix_parse(s, s + strlen(s), v, why);
}

static void test_format(void)
{
	CHECK_STR(fmt(0), "0", "0 formats as 0");
	CHECK_STR(fmt(1000), "1", "1000 thousandths is 1");
	CHECK_STR(fmt(-500), "-0.5", "trailing zeros dropped");
	CHECK_STR(fmt(12500), "12.5", "12.5");
	CHECK_STR(fmt(3250), "3.25", "3.25");
	CHECK_STR(fmt(-1), "-0.001", "smallest negative");
	CHECK_STR(fmt(10), "0.01", "0.01");
	CHECK_STR(fmt(META_MAX_COORD), "1000000", "upper limit");
	CHECK_STR(fmt(-META_MAX_COORD), "-1000000", "lower limit");
	CHECK_STR(fmt(INT32_MIN), "-2147483.648", "INT32_MIN does not overflow the formatter");
}

static void test_from_double(void)
{
	int ok;
	meta_fix_t v = meta_fix_from_double(-0.0004, &ok);
	CHECK(ok && v == 0, "-0.0004 rounds to 0 (got %d)", v);
	CHECK_STR(fmt(v), "0", "-0.0004 prints as 0, never -0");
	CHECK(meta_fix_from_double(0.0625, &ok) == 63 && ok, "tie 62.5 thousandths rounds away from zero");
	CHECK(meta_fix_from_double(-0.0625, &ok) == -63 && ok, "negative tie rounds away from zero");
	CHECK(meta_fix_from_double(0.1874, &ok) == 187, "0.1874 -> 187");
	CHECK(meta_fix_from_double(1e6, &ok) == META_MAX_COORD && ok, "1e6 is in range");
	meta_fix_from_double(1000000.001, &ok);
	CHECK(!ok, "just above the range is refused");
	meta_fix_from_double(NAN, &ok);
	CHECK(!ok, "NaN is refused");
	meta_fix_from_double(-INFINITY, &ok);
	CHECK(!ok, "-inf is refused");
}

static void test_parse(void)
{
	meta_fix_t v = 12345;
	int why;
	CHECK(parse("1.0005", &v, &why) == 0 && v == 1001, "text tie 1.0005 rounds away from zero (%d)", v);
	CHECK(parse("-1.0005", &v, &why) == 0 && v == -1001, "text tie -1.0005 rounds away from zero (%d)", v);
	CHECK(parse("1.00049999", &v, &why) == 0 && v == 1000, "below the tie rounds down (%d)", v);
	CHECK(parse("0.9995", &v, &why) == 0 && v == 1000, "rounding carries into the integer part (%d)", v);
	CHECK(parse("-0.0004", &v, &why) == 0 && v == 0, "-0.0004 parses as 0");
	CHECK(parse("+5", &v, &why) == 0 && v == 5000, "plus sign");
	CHECK(parse(".5", &v, &why) == 0 && v == 500, "leading dot");
	CHECK(parse("5.", &v, &why) == 0 && v == 5000, "trailing dot");
	CHECK(parse("000012.50", &v, &why) == 0 && v == 12500, "leading and trailing zeros");
	CHECK(parse("1000000", &v, &why) == 0 && v == META_MAX_COORD, "limit");
	CHECK(parse("1000000.0004", &v, &why) == 0 && v == META_MAX_COORD, "rounds down to the limit");
	CHECK(parse("1000000.0005", &v, &why) == -2, "rounds above the limit: range error");
	CHECK(parse("99999999999999999999", &v, &why) == -2, "huge: range error, no overflow");
	CHECK(parse("1e5", &v, &why) == -1 && why == 1, "exponent refused as such");
	CHECK(parse("nan", &v, &why) == -1 && why == 2, "nan refused as not finite");
	CHECK(parse("-Inf", &v, &why) == -1 && why == 2, "-Inf refused as not finite");
	CHECK(parse("", &v, &why) == -1 && why == 0, "empty refused");
	CHECK(parse(".", &v, &why) == -1, "bare dot refused");
	CHECK(parse("-", &v, &why) == -1, "bare sign refused");
	CHECK(parse("1.2.3", &v, &why) == -1, "two dots refused");
	CHECK(parse("0x10", &v, &why) == -1, "hex refused");
	CHECK(parse("--1", &v, &why) == -1, "double sign refused");
}

/* Write every statement through the convenience calls. */
static int write_all(meta_writer_t *w)
{
	static const double dash[] = { 4, 2.5, 1 };
	meta_rgb_t px[5] = { 0xff0000, 0xff0000, 0x00ff00, 0x0000ff, 0x0000ff };
	int rc = 0;
	rc |= meta_comment(w, "round trip");
	rc |= meta_page(w, 100, 50);
	rc |= meta_page_size_mm(w, 26.4583, 13.229);
	rc |= meta_clear(w, 0xfafafa);
	rc |= meta_colour(w, 0x123456);
	rc |= meta_width(w, 2.25);
	rc |= meta_dash(w, dash, 3);
	rc |= meta_cap(w, META_CAP_SQUARE);
	rc |= meta_join(w, META_JOIN_ROUND);
	rc |= meta_fill_rule(w, META_RULE_EVEN_ODD);
	rc |= meta_miter_limit(w, 3);
	rc |= meta_stroke(w);
	rc |= meta_move(w, -10.5, 1000000);
	rc |= meta_draw(w, 1000000, -1000000);
	rc |= meta_arc(w, 50, 25, 10, 45, -360);
	rc |= meta_close(w);
	rc |= meta_circle(w, 1, 2, 0.001);
	rc |= meta_end(w);
	rc |= meta_fill(w);
	rc |= meta_end(w);
	rc |= meta_text(w, 3, 4, 12, 90, "a\"b\\c\x01\xc3\xa9\xff");
	rc |= meta_span(w, 0, 49, 100, 0xabcdef);
	rc |= meta_image(w, 1, 2, 5, 2);
	rc |= meta_row_pixels(w, px, 5);
	rc |= meta_comment(w, "between rows");
	rc |= meta_row_pixels(w, px + 1, 4) == META_ESYNTAX ? 0 : -100; /* wrong width refused */
	rc |= meta_row_pixels(w, px, 5);
	rc |= meta_end_page(w);
	rc |= meta_page(w, 1, 1);
	rc |= meta_move(w, 0, 0) == META_ESTATE ? 0 : -100; /* outside a path refused */
	rc |= meta_stroke(w);
	rc |= meta_move(w, 0.5, 0.5);
	rc |= meta_end(w);
	rc |= meta_end_page(w);
	return rc;
}

/* Read all of src and write it again in encoding enc; returns the bytes. */
static sink_t recode(const sink_t *src, int enc, int *rc)
{
	sink_t out = { 0 };
	meta_reader_t *r = meta_reader_mem(src->p, src->n, "mem");
	meta_writer_t *w = meta_writer_new(sink_write, &out, enc);
	meta_cmd_t c;
	int k;
	*rc = 0;
	while ((k = meta_read(r, &c)) > 0)
		if (meta_write(w, &c) < 0)
			*rc = -1;
	if (k < 0) {
		printf("# %s\n", meta_reader_error(r));
		*rc = k;
	}
	if (meta_writer_close(w) < 0)
		*rc = -2;
	meta_reader_free(r);
	return out;
}

static void test_round_trip(void)
{
	sink_t text = { 0 }, bin, text2, bin2;
	meta_writer_t *w = meta_writer_new(sink_write, &text, META_ENC_TEXT);
	int rc = write_all(w);
	CHECK(rc == 0, "every convenience call accepted (%d: %s)", rc, meta_writer_error(w));
	CHECK(meta_writer_close(w) == 0, "writer closes cleanly");
	CHECK(strstr(text.p, "text 3 4 12 90 \"a\\\"b\\\\c\\x01\xc3\xa9\\xff\"\n") != NULL,
	      "string escapes: quote, backslash, control byte, UTF-8 kept, stray byte escaped");
	CHECK(strstr(text.p, "size 26.458 13.229\n") != NULL, "doubles rounded to thousandths");
	CHECK(strstr(text.p, "row 2 #ff0000 1 #00ff00 2 #0000ff\n") != NULL, "row pixels run-length encoded");
	CHECK(strstr(text.p, "circle 1 2 0.001\n") != NULL, "smallest radius kept");
	bin = recode(&text, META_ENC_BINARY, &rc);
	CHECK(rc == 0 && bin.n > 9 && memcmp(bin.p, meta_magic, 8) == 0, "text -> binary (%zu bytes)", bin.n);
	CHECK(bin.n < text.n, "binary is smaller than text (%zu < %zu)", bin.n, text.n);
	text2 = recode(&bin, META_ENC_TEXT, &rc);
	CHECK(rc == 0 && text2.n == text.n && memcmp(text2.p, text.p, text.n) == 0, "text -> binary -> text identical");
	bin2 = recode(&text2, META_ENC_BINARY, &rc);
	CHECK(rc == 0 && bin2.n == bin.n && memcmp(bin2.p, bin.p, bin.n) == 0, "binary -> text -> binary identical");
	free(text.p), free(bin.p), free(text2.p), free(bin2.p);
}

static void test_elision(void)
{
	sink_t s = { 0 };
	meta_writer_t *w = meta_writer_new(sink_write, &s, META_ENC_TEXT);
	int rc = 0;
	rc |= meta_page(w, 10, 10);
	rc |= meta_colour(w, 0x000000); /* default: elided */
	rc |= meta_width(w, 1.0004);    /* rounds to the default 1: elided */
	rc |= meta_cap(w, META_CAP_BUTT);
	rc |= meta_join(w, META_JOIN_MITER);
	rc |= meta_fill_rule(w, META_RULE_NON_ZERO);
	rc |= meta_miter_limit(w, 10);
	rc |= meta_dash(w, NULL, 0);
	rc |= meta_colour(w, 0xff0000);
	rc |= meta_colour(w, 0xff0000); /* repeated: elided */
	rc |= meta_end_page(w);
	rc |= meta_page(w, 10, 10);
	rc |= meta_colour(w, 0xff0000); /* state does not carry over: written again */
	rc |= meta_end_page(w);
	CHECK(rc == 0, "calls accepted");
	CHECK(meta_writer_close(w) == 0, "closed");
	CHECK_STR(s.p ? s.p : "", "LOCUS-META 1\npage 10 10\ncolour #ff0000\nend-page\npage 10 10\ncolour #ff0000\nend-page\n",
	          "unchanged state elided, reset at each page");
	free(s.p);
}

static void test_writer_errors(void)
{
	sink_t s = { 0 };
	meta_writer_t *w = meta_writer_new(sink_write, &s, META_ENC_BINARY);
	meta_cmd_t c;
	CHECK(meta_page(w, 0, 10) == META_ELIMIT, "page width 0 refused");
	CHECK(strstr(meta_writer_error(w), "page width from 1 to 32768, found '0'") != NULL, "message: %s", meta_writer_error(w));
	CHECK(meta_move(w, NAN, 0) == META_EARG, "NaN coordinate refused");
	CHECK(meta_page(w, 10, 10) == 0, "page accepted after refusals");
	CHECK(meta_comment(w, "two\nlines") == META_ESYNTAX, "line break in a comment refused");
	memset(&c, 0, sizeof c);
	c.op = META_WIDTH;
	c.f[0] = META_MAX_COORD + 1;
	CHECK(meta_write(w, &c) == META_ELIMIT, "raw out-of-range number refused");
	c.op = META_OP_COUNT;
	CHECK(meta_write(w, &c) == META_EARG, "bad op refused");
	CHECK(meta_writer_close(w) == META_ESTATE, "closing inside a page reports an incomplete file");
	free(s.p);
	memset(&s, 0, sizeof s);
	s.fail_after = 5;
	w = meta_writer_new(sink_write, &s, META_ENC_TEXT);
	meta_page(w, 10, 10);
	meta_end_page(w);
	CHECK(meta_writer_close(w) == META_EIO, "a failing sink gives META_EIO at close");
	free(s.p);
}

static void test_names(void)
{
	CHECK_STR(meta_op_name(META_FILL_RULE), "fill-rule", "op name");
	CHECK_STR(meta_keyword_name(META_CAP, META_CAP_SQUARE), "square", "keyword name");
	CHECK(meta_keyword_name(META_CAP, 3) == NULL, "keyword out of range");
	CHECK(meta_op_by_code[0x23] == META_DRAW + 1 && meta_op_by_code[0x5c] == 0, "code table");
}

int main(void)
{
	test_format();
	test_from_double();
	test_parse();
	test_round_trip();
	test_elision();
	test_writer_errors();
	test_names();
	return UNIT_DONE();
}
