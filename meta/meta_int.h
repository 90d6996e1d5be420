/* meta_int.h: internals shared by the files of the meta-language library (not installed). */
#ifndef LOCUS_META_INT_H
#define LOCUS_META_INT_H

#include <stdarg.h>
#include "locus_meta.h"

/* One row of the opcode table (derived from opcodes.def). */
typedef struct {
	const char *kw;              /* text keyword */
	unsigned char kwlen;         /* strlen(kw) */
	unsigned char code;          /* binary opcode */
	const char *sig;             /* operand signature letters */
	const char *const *words;    /* keyword operand spellings ('k'), or NULL */
	int nwords;
} meta_opinfo_t;

extern const meta_opinfo_t meta_ops[META_OP_COUNT];
/* Binary code -> op + 1 (0: no such opcode). */
extern const unsigned char meta_op_by_code[256];

/* The 8-byte binary magic. */
extern const unsigned char meta_magic[8];

/* Structural validator shared by reader and writer (spec section 4). */
typedef struct {
	int in_page;         /* between page and end-page */
	int any_page;        /* a page has been seen */
	int first;           /* no non-comment statement since page (size allowed) */
	int in_path;         /* between stroke/fill and end */
	int has_point;       /* the path has a current point */
	int closed;          /* the last subpath was closed and nothing followed (§4 close) */
	uint32_t path_points;
	uint64_t flat;       /* points of the path once flattened (§6) */
	uint32_t rows_left;  /* rows still owed to the current image */
	uint32_t image_w;
} meta_check_t;

/* Check one statement against the structure and value rules and update the
 * state. Returns 0 or a META_E* code with a message "expected ..., found ..."
 * in msg; *where is the operand index the error is about, or -1 for the
 * statement as a whole. */
int meta_check_cmd(meta_check_t *c, const meta_cmd_t *cmd, int *where, char *msg, size_t n);
/* Check that the input may end here. Returns 0 or META_ESTATE with msg. */
int meta_check_eof(const meta_check_t *c, char *msg, size_t n);

/* Parse a number token [p, e) in text syntax. Returns 0 and *out, or -1
 * (syntax; *why says what: 0 garbage, 1 exponent, 2 not finite) or -2 (range). */
int meta_fix_parse(const char *p, const char *e, meta_fix_t *out, int *why);

/* Length (2..4) of the well-formed UTF-8 sequence at s (n bytes available), 0 if none. */
int meta_utf8_len(const unsigned char *s, size_t n);

/* vsnprintf into buf, never failing. */
void meta_fmt(char *buf, size_t n, const char *fmt, ...)
#if defined(__GNUC__)
	__attribute__((format(printf, 3, 4)))
#endif
	;

/* ---- Reader internals (reader.c, read_buf.c, read_text.c, read_binary.c) */

#define META_READ_CHUNK (256 * 1024)

struct meta_reader {
	meta_read_fn fn;
	void *user;
	int fd;                   /* file opened by meta_reader_open, or -1 */
	const unsigned char *mem; /* meta_reader_mem: the whole input, no copy */
	char name[256];
	unsigned char *buf;       /* buffered input: [pos, end) unread */
	size_t cap, pos, end;
	uint64_t base;            /* file offset of buf[0] */
	int eof;                  /* the callback reported end of input */
	int state;                /* 0 not started, 1 reading, 2 done, <0 sticky error */
	int binary;
	uint64_t line;            /* text: number of the current line */
	uint64_t stmt_pos;        /* line (text) or offset (binary) of the last statement */
	uint64_t opos[8];         /* column (text) or offset (binary) of each operand */
	meta_check_t chk;
	meta_fix_t list[META_MAX_DASH];
	meta_run_t *runs;
	size_t runs_cap;
	char *str;                /* META_MAX_STRING + 1 bytes */
	int32_t refx, refy;       /* binary delta reference point */
	char err[600];
};

/* Refill: keep [pos, end), read more; returns bytes added (0 at end) or <0 with the error set. */
long meta_rd_fill(meta_reader_t *r);
/* Record an error: at a column of the current line (text) or a byte offset (binary). */
int meta_rd_fail(meta_reader_t *r, int code, uint64_t where, const char *fmt, ...)
#if defined(__GNUC__)
	__attribute__((format(printf, 4, 5)))
#endif
	;
/* Make room for n runs. Returns 0 or META_ENOMEM (error recorded at where). */
int meta_rd_runs(meta_reader_t *r, size_t n, uint64_t where);
/* Decode the next statement; 1 ok, 0 end of input, <0 error. */
int meta_read_text(meta_reader_t *r, meta_cmd_t *cmd);
int meta_read_binary(meta_reader_t *r, meta_cmd_t *cmd);
/* Text: check the header line. Binary: check magic and version. 0 or <0. */
int meta_text_header(meta_reader_t *r);
int meta_binary_header(meta_reader_t *r);

/* ---- Writer internals (writer.c, convenience.c) ------------------------ */

#define META_WRITE_BUF (64 * 1024)

struct meta_writer {
	meta_write_fn fn;
	void *user;
	int enc;                  /* META_TEXT or META_BINARY */
	int started;              /* header written */
	int state;                /* 0 or a sticky META_EIO */
	unsigned char *buf;
	size_t n;
	meta_check_t chk;
	int32_t refx, refy;       /* binary delta reference point */
	/* page state, for the eliding convenience calls */
	meta_rgb_t colour;
	meta_fix_t width, miter;
	int cap, join, rule;
	meta_fix_t dash[META_MAX_DASH];
	size_t ndash;
	meta_run_t *runs;
	size_t runs_cap;
	char err[512];
};

/* Reset the tracked page state to the defaults of spec section 1. */
void meta_wr_defaults(meta_writer_t *w);
/* Record a writer error "what: message" and return code. */
int meta_wr_fail(meta_writer_t *w, int code, const char *what, const char *fmt, ...)
#if defined(__GNUC__)
	__attribute__((format(printf, 4, 5)))
#endif
	;

#endif
