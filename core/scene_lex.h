/* scene_lex.h: line-oriented tokenizer of the scene language with file:line:col error messages. */
#ifndef LOCUS_SCENE_LEX_H
#define LOCUS_SCENE_LEX_H

#include <stddef.h>

/* A token: a run of non-blank bytes on one line (never crossing '#'). */
typedef struct {
	const char *s;
	size_t len;
	unsigned line, col;      /* 1-based; col in bytes */
} scene_tok_t;

typedef struct {
	const char *text;
	const char *name;        /* file name for messages */
	size_t pos;              /* next byte on the current line */
	size_t line_start;
	unsigned line;
	char *err;
	size_t errlen;
	int failed;
	double t;                /* the scene's time parameter (the frame's value of `t`) */
} scene_lex_t;

/* Start lexing text. */
void scene_lex_init(scene_lex_t *lx, const char *text, const char *name, char *err, size_t errlen);
/* Move to the next line holding a token; 0 at the end of the text. */
int scene_lex_line(scene_lex_t *lx);
/* Next token of the current line: 1, or 0 at its end (t then marks the end). */
int scene_lex_tok(scene_lex_t *lx, scene_tok_t *t);
/* The rest of the current line up to '#' (trimmed), consumed. */
void scene_lex_rest(scene_lex_t *lx, scene_tok_t *t);
/* 1 when the token spells word. */
int scene_tok_is(const scene_tok_t *t, const char *word);
/* Record "name:line:col: expected WHAT, found 'TOKEN'" (first error only). Returns -1. */
int scene_lex_expected(scene_lex_t *lx, const scene_tok_t *t, const char *what);
/* Copy src to dst (NUL-terminated, truncated to dstlen) with every control byte (below 0x20,
 * and 0x7f) written as \xHH, so that echoed scene text cannot drive a terminal. Returns the length. */
size_t scene_escape(char *dst, size_t dstlen, const char *src);
/* Record "name:line:col: MESSAGE" (first error only, control bytes escaped). Returns -1. */
int scene_lex_error(scene_lex_t *lx, unsigned line, unsigned col, const char *msg);
/* 1 when the n bytes at s use the time parameter `t` (an identifier of its own). */
int scene_uses_t(const char *s, size_t n);
/* Copy the n bytes at s into dst (NUL-terminated) with every identifier `t` replaced by the
 * value (t) in parentheses. Returns 0, or -1 when it does not fit. */
int scene_subst_t(const char *s, size_t n, double t, char *dst, size_t dstlen);
/* Read a finite number token (what names it in the message); a token using `t` (no blanks
 * inside, e.g. 1+0.5*t) is a constant expression evaluated at the frame's t. Returns 0 or -1. */
int scene_lex_number(scene_lex_t *lx, double *v, const char *what);
/* Read n finite numbers. */
int scene_lex_numbers(scene_lex_t *lx, double *v, int n, const char *what);
/* Read numbers up to a token spelling one of the words stop[] (NULL-terminated; not consumed)
 * or the end of the line, as points of dims (2 or 3) coordinates into a new array *pts of x y z
 * triples (z = 0 when dims is 2); *nnum counts the numbers read (a last point may be partial:
 * the caller checks). More than max points (0: no limit) is an error with message maxmsg at the
 * token. Returns 0, or -1 with nothing allocated. */
int scene_lex_points(scene_lex_t *lx, int dims, const char *const *stop, size_t max, const char *maxmsg,
                     double **pts, size_t *nnum);
/* Require the end of the line. */
int scene_lex_eol(scene_lex_t *lx);
/* Read three colour components 0..1 into c. */
int scene_parse_colour(scene_lex_t *lx, double *c);

#endif
