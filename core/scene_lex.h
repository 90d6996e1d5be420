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
/* Read a finite number token (what names it in the message). Returns 0 or -1. */
int scene_lex_number(scene_lex_t *lx, double *v, const char *what);
/* Read n finite numbers. */
int scene_lex_numbers(scene_lex_t *lx, double *v, int n, const char *what);
/* Require the end of the line. */
int scene_lex_eol(scene_lex_t *lx);

#endif
