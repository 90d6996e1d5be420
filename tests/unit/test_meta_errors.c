/* test_meta_errors.c: every reader error class, with its exact message and position, text and binary. */
#include <stdlib.h>
#include <string.h>
#include "unit.h"
#include "locus_meta.h"
#include "meta_int.h"

#define H "LOCUS-META 1\n"
#define P H "page 10 10\n"

/* Read all of data; the first error must be exactly want (NULL: valid). */
static void expect(const char *data, size_t len, const char *want, int code)
{
	meta_reader_t *r = meta_reader_mem(data, len, "t");
	meta_cmd_t c;
	int rc;
	while ((rc = meta_read(r, &c)) > 0)
		;
	if (!want) {
		CHECK(rc == 0, "valid input accepted (%s)", meta_reader_error(r));
	} else {
		CHECK_STR(meta_reader_error(r), want, "error: %s (got: %s)", want, meta_reader_error(r));
		CHECK(rc == code, "code %d for: %s (got %d)", code, want, rc);
		CHECK(meta_read(r, &c) == rc, "the error is sticky");
	}
	meta_reader_free(r);
}

#define T(text, want, code) expect(text, sizeof(text) - 1, want, code)

static void text_errors(void)
{
	T("", "t:1:1: expected 'LOCUS-META 1', found end of file", META_EVERSION);
	T("LOCUS-META 2\n", "t:1:12: unsupported meta-language version 2 (this reader knows 1)", META_EVERSION);
	T("LOCUS-META  17\r\n", "t:1:13: unsupported meta-language version 17 (this reader knows 1)", META_EVERSION);
	T("%!PS-Adobe\n", "t:1:1: expected 'LOCUS-META 1', found '%!PS-Adobe'", META_EVERSION);
	T(H, "t:2:1: expected 'page', found end of file (a file holds at least one page)", META_ESTATE);
	T(P "draw x1 2\n", "t:3:6: expected a number after 'draw', found 'x1'", META_ESYNTAX);
	T(P "stroke\nmove 1 nan\n", "t:4:8: expected a finite number for operand 2 of 'move', found 'nan'", META_ESYNTAX);
	T(P "width 1e3\n", "t:3:7: expected a plain (no exponent) number after 'width', found '1e3'", META_ESYNTAX);
	T(P "width -inf\n", "t:3:7: expected a finite number after 'width', found '-inf'", META_ESYNTAX);
	T(P "stroke\nmove 2000000 0\n", "t:4:6: expected a number from -1000000 to 1000000 after 'move', found '2000000'", META_ELIMIT);
	T(P "stroke\nmove 1\n", "t:4:7: expected a number for operand 2 of 'move', found end of line", META_ESYNTAX);
	T(P "end-page 5\n", "t:3:10: expected end of line after the operands of 'end-page', found '5'", META_ESYNTAX);
	T(P "frobnicate 1\n", "t:3:1: expected a statement keyword, found 'frobnicate'", META_ESYNTAX);
	T(P "colour red\n", "t:3:8: expected a colour #rrggbb after 'colour', found 'red'", META_ESYNTAX);
	T(P "cap flat\n", "t:3:5: expected 'butt', 'round' or 'square' after 'cap', found 'flat'", META_ESYNTAX);
	T(H "page 0 10\n", "t:2:6: expected a page width from 1 to 32768, found '0'", META_ELIMIT);
	T(H "page 10 99999\n", "t:2:9: expected a page height from 1 to 32768, found '99999'", META_ELIMIT);
	T(H "page 10 99999999999\n", "t:2:9: expected an integer below 2^32 for operand 2 of 'page', found '99999999999'", META_ELIMIT);
	T(H "page -5 10\n", "t:2:6: expected an unsigned integer (digits) after 'page', found '-5'", META_ESYNTAX);
	T(H "colour #000000\n", "t:2:1: expected 'page' before 'colour'", META_ESTATE);
	T(P "page 10 10\n", "t:3:1: expected 'end-page' before 'page'", META_ESTATE);
	T(P "clear #ffffff\nsize 10 10\n", "t:4:1: expected 'size' only directly after 'page', found it later", META_ESTATE);
	T(P "size 0 10\n", "t:3:6: expected a positive physical width for 'size', found '0'", META_ESYNTAX);
	T(P "stroke\ndraw 1 2\n", "t:4:1: expected 'move' before 'draw' (no current point)", META_ESTATE);
	T(P "stroke\ncircle 1 2 3\nclose\n", "t:5:1: expected 'move' before 'close' (no current point)", META_ESTATE);
	T(P "move 1 2\n", "t:3:1: expected 'stroke' or 'fill' before 'move'", META_ESTATE);
	T(P "stroke\nmove 1 1\ncolour #ff0000\n",
	  "t:5:1: expected a path statement or 'end', found 'colour' (state cannot change inside a path)", META_ESTATE);
	T(P "fill\nmove 1 1\nfill\n", "t:5:1: expected a path statement or 'end', found 'fill'", META_ESTATE);
	T(P "stroke\narc 1 1 0 0 90\n", "t:4:9: expected a radius > 0 for 'arc', found '0'", META_ESYNTAX);
	T(P "stroke\narc 1 1 1 0 361\n", "t:4:13: expected a sweep from -360 to 360 for 'arc', found '361'", META_ESYNTAX);
	T(P "width -1\n", "t:3:7: expected a width >= 0, found '-1'", META_ESYNTAX);
	T(P "miter-limit 0.5\n", "t:3:13: expected a miter limit >= 1, found '0.5'", META_ESYNTAX);
	T(P "dash 1 0 2\n", "t:3:8: expected dash lengths > 0, found '0'", META_ESYNTAX);
	T(P "dash 1 1 1 1 1 1 1 1 1 1 1 1 1 1 1 1 1\n", "t:3:38: expected at most 16 dash lengths, found more", META_ELIMIT);
	T(P "text 1 1 5 0 \"abc\n", "t:3:18: expected a closing '\"' of the string, found end of line", META_ESYNTAX);
	T(P "text 1 1 5 0 \"a\\qb\"\n", "t:3:16: expected an escape \\\\, \\\" or \\xHH, found '\\qb\"'", META_ESYNTAX);
	T(P "text 1 1 5 0 \"a\tb\"\n", "t:3:16: expected a printable character or an escape, found byte 0x09", META_ESYNTAX);
	T(P "text 1 1 5 0 \"a\\x00\"\n", "t:3:16: expected no NUL byte in a string, found '\\x00'", META_ESYNTAX);
	T(P "span 1 1 0 #000000\n", "t:3:10: expected a span length >= 1, found '0'", META_ESYNTAX);
	T(P "image 0 0 2 2\nrow 2 #000000\nend-page\n", "t:5:1: expected 'row' (1 more for the image), found 'end-page'", META_ESTATE);
	T(P "image 0 0 2 1\nrow 1 #000000 2 #ffffff\n",
	  "t:4:15: expected runs adding up to the image width 2, found 3 by run 2", META_ESYNTAX);
	T(P "image 0 0 2 1\nrow 1 #000000\n", "t:4:5: expected runs adding up to the image width 2, found 1", META_ESYNTAX);
	T(P "image 0 0 2 1\nrow -1 #000000\n", "t:4:5: expected a run count (1 or more) in 'row', found '-1'", META_ESYNTAX);
	T(P "image 0 0 2 1\nrow 0 #000000 2 #000000\n", "t:4:5: expected a run count (1 or more) in 'row', found '0'", META_ESYNTAX);
	T(P "image 0 0 0 1\n", "t:3:11: expected an image width from 1 to 32768, found '0'", META_ELIMIT);
	T(P "row 1 #000000\n", "t:3:1: expected 'image' before 'row'", META_ESTATE);
	T(P "end\n", "t:3:1: expected 'stroke' or 'fill' before 'end'", META_ESTATE);
	T(P, "t:3:1: expected 'end-page', found end of file (unterminated page)", META_ESTATE);
	T(P "stroke\nmove 1 1\n", "t:5:1: expected 'end' of the path, found end of file (truncated?)", META_ESTATE);
	T(P "image 0 0 1 3\nrow 1 #000000\n", "t:5:1: expected 2 more 'row' statements, found end of file (truncated?)", META_ESTATE);
	T(P "end-page", "t:4:1: expected a newline at the end of line 3, found end of file (truncated?)", META_ESYNTAX);
	/* valid corner cases */
	T(H "\n  \t\n# c\npage 1 1\r\n\tclear\t#ABCDEF  \n#\nend-page\n", NULL, 0);
	T(P "stroke\nend\nfill\nmove 1 1\nclose\nclose\nend\nend-page\n", NULL, 0);
	T(P "dash\nend-page\n", NULL, 0);
}

static void long_lines(void)
{
	size_t n = META_MAX_LINE + 40, i;
	char *p = malloc(n), *q;
	strcpy(p, P "# ");
	q = p + strlen(p);
	for (i = 0; q + i < p + n - 1; i++)
		q[i] = 'x';
	p[n - 1] = '\n';
	expect(p, n, "t:3:1048577: expected a line of at most 1048576 bytes, found 1048591 bytes", META_ELIMIT);
	memcpy(p + strlen(P), "# ", 2);
	expect(p, n - 1, "t:3:1048577: expected a line of at most 1048576 bytes, found a longer one", META_ELIMIT);
	strcpy(p, P "# ");
	memset(p + strlen(p), 'y', 4097);
	strcpy(p + strlen(P) + 2 + 4097, "\nend-page\n");
	expect(p, strlen(p), "t:3:3: expected a comment of at most 4096 bytes, found 4097 bytes", META_ELIMIT);
	free(p);
}

/* Binary: magic, version, then statements. */
#define MB "\x8bLMB\r\n\x1a\n\x01"
#define B(bytes, want, code) expect(bytes, sizeof(bytes) - 1, want, code)

static void binary_errors(void)
{
	B(MB "\x01\x0a\x0a\x04", NULL, 0);
	B(MB "\x01\x0a\x0a\x5c", "t: byte 12: unknown opcode 0x5c", META_ESYNTAX);
	B("\x8bLMB\n\x1a\n\x01", "t: byte 4: expected the binary magic 8b 4c 4d 42 0d 0a 1a 0a, found 0x0a here (damaged by a text-mode transfer?)", META_EVERSION);
	B("\x8bLMB\r\n\x1a\n\x02", "t: byte 8: unsupported meta-language version 2 (this reader knows 1)", META_EVERSION);
	B("\x8bLM", "t: byte 3: expected the binary magic 8b 4c 4d 42 0d 0a 1a 0a, found end of file", META_EVERSION);
	B(MB, "t: byte 9: expected 'page', found end of file (a file holds at least one page)", META_ESTATE);
	B(MB "\x01\x0a", "t: byte 11: expected the rest of 'page', found end of file (truncated?)", META_ESYNTAX);
	B(MB "\x01\x0a\x0a", "t: byte 12: expected 'end-page', found end of file (unterminated page)", META_ESTATE);
	B(MB "\x01\xc0\xb8\x02\x0a\x04", "t: byte 10: expected a page width from 1 to 32768, found '40000'", META_ELIMIT);
	B(MB "\x01\x8a\x00\x0a\x04", "t: byte 10: expected a canonical (shortest) varint in 'page', found 2 bytes", META_ESYNTAX);
	B(MB "\x01\xff\xff\xff\xff\x7f\x0a", "t: byte 10: expected a varint of at most 32 bits in 'page', found a longer one", META_ESYNTAX);
	/* move (0x22) by deltas: 1e9 then +1e9 leaves the range. zigzag(1e9) = 2e9 = 0x77359400 */
	B(MB "\x01\x0a\x0a\x20\x22\x80\xa8\xd6\xb9\x07\x00\x22\x80\xa8\xd6\xb9\x07\x00",
	  "t: byte 21: expected a coordinate from -1000000 to 1000000 in 'move', found '2000000' (reference plus delta)", META_ELIMIT);
	B(MB "\x01\x0a\x0a\x20\x23\x02\x02", "t: byte 13: expected 'move' before 'draw' (no current point)", META_ESTATE);
	B(MB "\x01\x0a\x0a\x13\x03", "t: byte 13: expected a keyword index below 3 in 'cap', found '3'", META_ESYNTAX);
	B(MB "\x01\x0a\x0a\x11\x82\xa8\xd6\xb9\x07", "t: byte 13: expected a number from -1000000 to 1000000 in 'width', found '1000000.001'", META_ELIMIT);
	B(MB "\x01\x0a\x0a\x12\x11", "t: byte 13: expected at most 16 dash lengths, found 17 lengths", META_ELIMIT);
	B(MB "\x01\x0a\x0a\x41\x00\x00\x02\x01\x42\x02\x01\x00\x00\x00\x02\x00\x00\x00",
	  "t: byte 23: expected runs adding up to the image width 2, found 3 by run 2", META_ESYNTAX);
	B(MB "\x01\x0a\x0a\x41\x00\x00\x02\x01\x42\x01\x00\x00\x00\x00",
	  "t: byte 19: expected a run count of 1 or more in 'row', found '0'", META_ESYNTAX);
	B(MB "\x01\x0a\x0a\x7f\x03" "a\nb\x04", "t: byte 15: expected no line-break byte in a comment, found 0x0a", META_ESYNTAX);
	B(MB "\x01\x0a\x0a\x30\x00\x00\x02\x00\x81\x20", "t: byte 17: expected a string of at most 4096 bytes in 'text', found 4097 bytes", META_ELIMIT);
	B(MB "\x01\x0a\x0a\x30\x00\x00\x02\x00\x05" "ab", "t: byte 20: expected the rest of 'text', found end of file (truncated?)", META_ESYNTAX);
}

static void path_limit(void)
{
	meta_check_t c;
	meta_cmd_t cmd;
	char msg[200];
	int where;
	memset(&c, 0, sizeof c);
	memset(&cmd, 0, sizeof cmd);
	c.in_page = c.any_page = c.in_path = c.has_point = 1;
	c.path_points = META_MAX_PATH_POINTS - 1;
	cmd.op = META_DRAW;
	CHECK(meta_check_cmd(&c, &cmd, &where, msg, sizeof msg) == 0, "the millionth point is allowed");
	CHECK(meta_check_cmd(&c, &cmd, &where, msg, sizeof msg) == META_ELIMIT, "one more is refused");
	CHECK_STR(msg, "expected at most 1000000 points in one path, found more", "path limit message");
}

int main(void)
{
	text_errors();
	long_lines();
	binary_errors();
	path_limit();
	return UNIT_DONE();
}
