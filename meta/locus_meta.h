/* locus_meta.h: the Locus meta-language library (reader, writer, limits).
 *
 * The meta-language is the device-independent picture description that the
 * renderer writes and every driver replays. docs/meta-language.md is the
 * normative spec; this header is its C binding.
 *
 * Numbers: every coordinate, length and angle is a fixed-point value in
 * thousandths (meta_fix_t, 1000 == 1.0). Fixed point makes the text and
 * binary encodings round-trip exactly and lets drivers decide pixel coverage
 * with integer arithmetic, so two drivers draw the same pixels.
 *
 * Errors: functions return 0 (or a positive count) on success and a negative
 * META_E* code on failure; meta_reader_error()/meta_writer_error() then give a
 * one-line message such as "scene.meta:12:7: expected a number after 'draw'"
 * or "pic.lmb: byte 1042: unknown opcode 0x5c". The library never prints and
 * never exits.
 *
 * Memory: the reader is streaming; its memory is bounded by the limits below,
 * never by the size of the file.
 */
#ifndef LOCUS_META_H
#define LOCUS_META_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define META_VERSION 1            /* the only version this library reads and writes */
#define META_FIX_ONE 1000         /* meta_fix_t value of 1.0 */

/* Limits, enforced by reader and writer with a clear error. */
#define META_MAX_DIM        32768     /* page width/height in pixels */
#define META_MAX_COORD      1000000000 /* |fixed| <= 1e9, i.e. 1,000,000.000 */
#define META_MAX_PATH_POINTS 1000000  /* points (move/draw/arc/circle) in one path */
#define META_MAX_FLAT_POINTS (1 << 25) /* points of one path once arcs and circles are flattened */
#define META_MAX_DASH       16        /* entries in a dash list */
#define META_MAX_STRING     4096      /* bytes in a text string or comment */
#define META_MAX_LINE       (1 << 20) /* bytes in one text line */

/* Chords of a full circle of radius r thousandths (spec §5.4): max(8, ceil(2 pi / acos(1 -
 * 0.25 / r_px))) above a quarter pixel, else 8; at most 8886 within the number range. */
int meta_circle_chords(int64_t r);
/* Chords of an arc of radius r and sweep thousandths of a degree (§5.4): max(1,
 * ceil(|sweep| * M / 360000)). */
int64_t meta_arc_chords(int64_t r, int64_t sweep);

/* The next character of the UTF-8 bytes buf[0, n), n >= 1, decoded as Unicode's "maximal
 * subpart" practice (the WHATWG decoder, Python's errors="replace"): a well-formed sequence is
 * one character (*cp its code point); an ill-formed one is one U+FFFD per maximal subpart (a
 * lead byte and the continuation bytes valid after it, stopping at the first that is not) or per
 * other byte. Overlong forms, surrogates and values above U+10FFFF are ill-formed. Returns the
 * bytes taken (1 to 4). The text encoding (§2) and the stroke font (§5.5) both count by it. */
size_t meta_utf8_next(const void *buf, size_t n, uint32_t *cp);

/* Error codes (negative). */
enum {
	META_EOK = 0,
	META_EIO = -1,        /* read/write failure of the underlying stream */
	META_ESYNTAX = -2,    /* malformed input: bad token, bad number, unknown opcode */
	META_ELIMIT = -3,     /* a limit above was exceeded */
	META_EVERSION = -4,   /* unknown magic or version */
	META_ESTATE = -5,     /* statement not allowed here (draw outside a path, row outside image...) */
	META_ENOMEM = -6,     /* allocation failed */
	META_EARG = -7        /* invalid argument from the caller (writer) */
};

typedef int32_t meta_fix_t;    /* thousandths: 1500 == 1.5 */
typedef uint32_t meta_rgb_t;   /* 0xRRGGBB */

/* The statement kinds, generated from opcodes.def. */
typedef enum {
#define META_OP(e, kw, code, sig) META_##e,
#include "opcodes.def"
#undef META_OP
	META_OP_COUNT
} meta_op_t;

/* Keyword operand values. */
enum { META_CAP_BUTT, META_CAP_ROUND, META_CAP_SQUARE };
enum { META_JOIN_MITER, META_JOIN_ROUND, META_JOIN_BEVEL };
enum { META_RULE_EVEN_ODD, META_RULE_NON_ZERO };

/* One run of an image row: count pixels of one colour. */
typedef struct {
	uint32_t count;
	meta_rgb_t rgb;
} meta_run_t;

/* One decoded statement. Which fields are meaningful depends on op:
 *   PAGE        u[0]=width u[1]=height (pixels)
 *   SIZE        f[0]=width f[1]=height (millimetres)
 *   CLEAR       rgb
 *   END_PAGE    -
 *   COLOUR      rgb
 *   WIDTH       f[0]
 *   DASH        list/nlist (nlist==0: solid)
 *   CAP/JOIN/FILL_RULE  k
 *   MITER_LIMIT f[0]
 *   STROKE/FILL/CLOSE/END  -
 *   MOVE/DRAW   f[0]=x f[1]=y
 *   ARC         f[0]=cx f[1]=cy f[2]=r f[3]=start f[4]=sweep (degrees)
 *   CIRCLE      f[0]=cx f[1]=cy f[2]=r
 *   TEXT        f[0]=x f[1]=y f[2]=size f[3]=angle, str/len
 *   SPAN        u[0]=x u[1]=y u[2]=n rgb
 *   IMAGE       u[0]=x u[1]=y u[2]=w u[3]=h
 *   ROW         runs/nruns
 *   COMMENT     str/len
 * Pointers (str, list, runs) belong to the reader and stay valid until the
 * next meta_read() call. */
typedef struct {
	meta_op_t op;
	uint32_t u[4];
	meta_fix_t f[5];
	meta_rgb_t rgb;
	int k;
	const char *str;   /* NUL-terminated; len excludes the NUL */
	size_t len;
	const meta_fix_t *list;
	size_t nlist;
	const meta_run_t *runs;
	size_t nruns;
} meta_cmd_t;

/* ---- Streams ---------------------------------------------------------- */

/* Read callback: fill buf with up to n bytes; return bytes read, 0 at end, <0 on error. */
typedef long (*meta_read_fn)(void *user, void *buf, size_t n);
/* Write callback: write all n bytes; return 0 on success, <0 on error. */
typedef int (*meta_write_fn)(void *user, const void *buf, size_t n);

/* ---- Reader ----------------------------------------------------------- */

typedef struct meta_reader meta_reader_t;

/* Create a reader over a callback stream. name is used in error messages
 * ("-" is shown as "<stdin>"). The encoding (text or binary) is detected from
 * the first bytes. Returns NULL only when out of memory. */
meta_reader_t *meta_reader_new(meta_read_fn fn, void *user, const char *name);
/* Convenience: open a path ("-" = stdin). On failure returns NULL and, if
 * err is non-NULL, copies a message into err (errlen bytes); errno is then
 * ENOMEM when memory ran out (exit 70), else the open's cause (exit 66). */
meta_reader_t *meta_reader_open(const char *path, char *err, size_t errlen);
/* Convenience: read from a memory buffer (not copied; it must outlive the
 * reader). name is used in messages (NULL: "<memory>"). NULL if out of memory. */
meta_reader_t *meta_reader_mem(const void *data, size_t len, const char *name);
/* Free the reader (closes a file opened by meta_reader_open). */
void meta_reader_free(meta_reader_t *r);

/* Pull the next statement. Returns 1 with *cmd filled, 0 at a clean end of
 * file, <0 on error (see meta_reader_error). The reader validates structure
 * as it goes: statements outside a page, paths not ended, rows that do not
 * match their image, limits, and an unterminated page at end of file are all
 * errors. */
int meta_read(meta_reader_t *r, meta_cmd_t *cmd);
/* The last error as one line: "NAME:LINE:COL: message" (text) or
 * "NAME: byte OFFSET: message" (binary). Empty string if none. */
const char *meta_reader_error(const meta_reader_t *r);
/* 1 if the input is the binary encoding, 0 if text (valid after the first read). */
int meta_reader_is_binary(const meta_reader_t *r);
/* Position of the statement just read: line (text, 1-based) or byte offset (binary). */
uint64_t meta_reader_position(const meta_reader_t *r);

/* ---- Writer ----------------------------------------------------------- */

typedef struct meta_writer meta_writer_t;

/* Encodings for meta_writer_new (META_TEXT is the op of the "text" statement). */
enum { META_ENC_TEXT = 0, META_ENC_BINARY = 1 };

/* Create a writer of the given encoding; the header is written on the first
 * statement. Returns NULL only when out of memory. */
meta_writer_t *meta_writer_new(meta_write_fn fn, void *user, int encoding);
/* Write one statement exactly as given (no state elision), validating it.
 * Returns 0 or <0 (see meta_writer_error). */
int meta_write(meta_writer_t *w, const meta_cmd_t *cmd);
/* Flush buffered output and free the writer. Returns <0 if the final flush
 * failed (META_EIO) or the output is incomplete (META_ESTATE: a page or path
 * left open, or no page at all after something was written). */
int meta_writer_close(meta_writer_t *w);
/* The last error of the writer as one line ("meta_write: 'page' operand 1:
 * expected a page width from 1 to 32768, found 0"); empty if none. A refused
 * statement writes nothing and the writer stays usable; a write failure of
 * the callback is sticky. */
const char *meta_writer_error(const meta_writer_t *w);

/* Convenience calls for producers (the renderer). State setters write a
 * statement only when the value differs from the current state of the page,
 * so that output is canonical and small (the state is tracked per page and
 * reset to the defaults by meta_page). Coordinates are in pixels (double)
 * and rounded to the nearest thousandth, ties away from zero; a NaN, infinite
 * or out-of-range value is refused with META_EARG. All return 0 or <0. */
int meta_page(meta_writer_t *w, unsigned width, unsigned height);          /* begin a page */
int meta_page_size_mm(meta_writer_t *w, double width_mm, double height_mm); /* directly after meta_page */
int meta_clear(meta_writer_t *w, meta_rgb_t rgb);                          /* paint the whole page */
int meta_end_page(meta_writer_t *w);                                       /* the device outputs the page */
int meta_colour(meta_writer_t *w, meta_rgb_t rgb);          /* state: colour of strokes, fills, text */
int meta_width(meta_writer_t *w, double width);             /* state: line width in pixels, >= 0 */
int meta_dash(meta_writer_t *w, const double *lengths, size_t n); /* state: dash lengths, n == 0 solid */
int meta_cap(meta_writer_t *w, int cap);                    /* state: META_CAP_* */
int meta_join(meta_writer_t *w, int join);                  /* state: META_JOIN_* */
int meta_fill_rule(meta_writer_t *w, int rule);             /* state: META_RULE_* */
int meta_miter_limit(meta_writer_t *w, double limit);       /* state: miter limit, >= 1 */
int meta_stroke(meta_writer_t *w);          /* begin a stroked path */
int meta_fill(meta_writer_t *w);            /* begin a filled path */
int meta_move(meta_writer_t *w, double x, double y);        /* begin a subpath at (x, y) */
int meta_draw(meta_writer_t *w, double x, double y);        /* segment to (x, y) */
/* Arc of centre (cx, cy), radius r > 0, from start_deg through sweep_deg (|sweep| <= 360). */
int meta_arc(meta_writer_t *w, double cx, double cy, double r, double start_deg, double sweep_deg);
int meta_circle(meta_writer_t *w, double cx, double cy, double r); /* a closed circular subpath */
int meta_close(meta_writer_t *w);           /* close the current subpath */
int meta_end(meta_writer_t *w);             /* end the path: draw it */
/* Stroke-font text s (NUL-terminated, at most 4096 bytes) at baseline origin (x, y). */
int meta_text(meta_writer_t *w, double x, double y, double size, double angle_deg, const char *s);
int meta_span(meta_writer_t *w, unsigned x, unsigned y, unsigned n, meta_rgb_t rgb); /* n pixels of a row */
/* Begin a width x height image at (x, y); then exactly height rows, top row first. */
int meta_image(meta_writer_t *w, unsigned x, unsigned y, unsigned width, unsigned height);
/* Write one image row from width RGB pixels (0xRRGGBB each), run-length encoded. */
int meta_row_pixels(meta_writer_t *w, const meta_rgb_t *pixels, size_t width);
/* A comment line (no line breaks; at most 4096 bytes). */
int meta_comment(meta_writer_t *w, const char *text);

/* ---- Numbers ---------------------------------------------------------- */

/* Canonical text of a fixed value: "12", "-0.5", "3.25"; never "-0". buf must
 * hold 16 bytes. Returns the length. */
int meta_fix_format(meta_fix_t v, char *buf);
/* Nearest fixed value of a double (ties away from zero); 0 if not finite or out of range. */
meta_fix_t meta_fix_from_double(double v, int *ok);
static inline double meta_fix_to_double(meta_fix_t v) { return v / 1000.0; }

/* Keyword spelling of a statement kind ("fill-rule"; "#" for comments; "?" if unknown). */
const char *meta_op_name(meta_op_t op);
/* Spelling of keyword operand k of op ("square" for META_CAP, META_CAP_SQUARE); NULL if none. */
const char *meta_keyword_name(meta_op_t op, int k);

#ifdef __cplusplus
}
#endif
#endif
