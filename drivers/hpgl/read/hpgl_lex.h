/* hpgl_lex.h: the HP-GL token layer shared by the two HP-GL lexers of hpgl/read/: the reader
 * (hpgl_read.c, a whole buffer) and the job tracker (hpgl_track.c, a byte at a time as a job goes
 * to a device). One definition of what a mnemonic letter, a separator, a number and the default
 * label terminator are, so the two cannot drift apart in those.
 *
 * What is not shared yet (each lexer keeps its own, and each differs from the other there on
 * purpose of keeping its output as it was): the tracker takes any letter as half a mnemonic (the
 * reader wants two), ends a label at ETX only (the reader follows DT), and skips nothing (the
 * reader reads ESC sequences, quoted strings and PE data).
 */
#ifndef LOCUS_HPGL_LEX_H
#define LOCUS_HPGL_LEX_H

#include <stddef.h>

/* The label terminator after IN, and after DT without a parameter: ETX. */
#define HPGL_LEX_TERM_DEFAULT 3

/* A mnemonic's letter (ASCII, either case). */
static inline int hpgl_lex_letter(unsigned char c)
{
	return (unsigned)((c | 0x20) - 'a') < 26u;
}

/* A mnemonic's letter in upper case (c a letter). */
static inline char hpgl_lex_upper(unsigned char c)
{
	return (char)(c & ~0x20);
}

static inline int hpgl_lex_digit(unsigned char c)
{
	return (unsigned)(c - '0') < 10u;
}

/* What may stand between parameters: blanks, line ends and ','. */
static inline int hpgl_lex_sep(unsigned char c)
{
	return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == ',';
}

/* A byte a number may begin with, and (to the tracker) a byte of a number: a digit, a sign, '.'. */
static inline int hpgl_lex_numchar(unsigned char c)
{
	return hpgl_lex_digit(c) || c == '-' || c == '+' || c == '.';
}

/* The coordinate commands: 0 PU, 1 PD, 2 PA, 3 PR; -1 any other mnemonic (mn upper case). */
static inline int hpgl_lex_coord(const char *mn)
{
	if (mn[0] != 'P')
		return -1;
	switch (mn[1]) {
	case 'U': return mn[2] ? -1 : 0;
	case 'D': return mn[2] ? -1 : 1;
	case 'A': return mn[2] ? -1 : 2;
	case 'R': return mn[2] ? -1 : 3;
	default: return -1;
	}
}

/* The number that begins at s[i] (s[i] a hpgl_lex_numchar; n bytes in all): an optional sign,
 * digits, an optional '.' and digits, and an exponent when a writer printed one (no HP-GL, but an
 * 'e' or 'E' followed by a digit or a sign is taken as one). Returns the end; *digits: how many
 * digits before the exponent (0: a malformed number). */
size_t hpgl_lex_number(const unsigned char *s, size_t n, size_t i, size_t *digits);

/* The value of a number's text p[0, len): what strtod makes of its first 63 bytes. */
double hpgl_lex_value(const unsigned char *p, size_t len);

#endif
