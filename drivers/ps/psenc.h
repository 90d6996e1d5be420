/* psenc.h: PostScript/PDF encoders over the device writer (hex, ASCII85, RunLength, Flate).
 *
 * PDF needs exact byte offsets for its cross-reference table: the writer's pos. A writer can
 * route its bytes through a Flate compressor (and then, for 7-bit PostScript, through ASCII85)
 * between pse_deflate_begin() and pse_deflate_end().
 * The image encoders work on whole buffers so that a device can try each and keep the smallest.
 */
#ifndef LOCUS_PSENC_H
#define LOCUS_PSENC_H

#include <stddef.h>
#include <stdint.h>
#include "device/writer.h"

#define PSE_ROW_MAX 32       /* the longest predictor row (bytes) */

/* The writer is the shared one (device/writer.h: buffer, byte offset, sticky error, printf and
 * numbers); this file adds PostScript's spool for EPS and the Flate/ASCII85/predictor stage,
 * which it puts in front of the writer's buffer as its filter while a stream is compressed. */

/* Send the bytes to a temporary file from now on: for EPS, whose bounding box heads the file
 * but is known only at its end. 0 or <0. */
int pse_spool(dev_writer_t *o);
/* Stop spooling: the spool (a FILE *) is returned for pse_spool_copy, NULL if none. */
void *pse_spool_end(dev_writer_t *o);
/* Write the spool's bytes through the writer (after what was written since) and close it. */
int pse_spool_copy(dev_writer_t *o, void *spool);

/* A compression level: Huffman coding only, no string matching. On the number text of paths
 * it is as small as level 1 (random walks: 1% smaller, contours 15% larger) at 2/3 the time. */
#define PSE_HUFFMAN (-2)
/* A compression level for content streams of number text: zlib's level 9 with filtered matching,
 * a shorter chain and lazy search (PDF workloads: 5-10% smaller than level 4 in 3.4 times its
 * time, where level 9 itself is 14 times slower). */
#define PSE_TEXT (-3)
/* A compression level for predicted samples of points (mostly zero bytes, whose hash chains are
 * long): level 9 filtered with a 64-step chain and lazy matches up to 16 (a contour map's
 * samples: 482 kB in 68 ms, where PSE_TEXT gives 501 kB in 52 ms and plain level 9 411 kB in
 * 1.2 s). */
#define PSE_ROWS (-4)
/* Compress what follows with zlib's deflate (the zlib format FlateDecode reads), written as
 * ASCII85 (ended by ~>) when a85 is 1; level 1..9, PSE_HUFFMAN, PSE_TEXT or PSE_ROWS.
 * Returns 0 or <0. */
int pse_deflate_begin(dev_writer_t *o, int a85, int level);
/* Change the compression level (1..9 or PSE_HUFFMAN) from here on (what is buffered is compressed
 * at the old one). */
int pse_deflate_level(dev_writer_t *o, int level);
/* End compression: flush the compressor (and the ASCII85 group); rows end (the last one must be
 * complete: pse_rows_end). *zlen, if not NULL, gets the
 * number of compressed bytes (before ASCII85). */
int pse_deflate_end(dev_writer_t *o, uint64_t *zlen);

/* ---- TIFF predictor 2 inside a Flate stream (/DecodeParms << /Predictor 2 /Colors W
 * /Columns C >>) ----
 * The data is then rows of C samples of W bytes (8-bit components), each byte of a sample but
 * the row's first written as its difference from the same byte of the sample before (the
 * decoder adds it back). Records laid out one a sample, in fixed columns, so become their
 * differences from the record before: the columns that repeat turn into zeros. Text may be
 * written anywhere in between (it decodes back to itself). */

/* Start predictor rows of `columns` samples of w bytes (1..PSE_ROW_MAX) after
 * pse_deflate_begin. Returns 0 or <0. */
int pse_rows_begin(dev_writer_t *o, unsigned w, unsigned columns);
/* Bytes written into the current sample (0: at a sample boundary). */
unsigned pse_rows_col(const dev_writer_t *o);
/* Write the byte c up to the end of the current sample (nothing at a boundary). */
int pse_rows_pad(dev_writer_t *o, char c);
/* Write the byte c up to the end of the current row (before pse_deflate_end: rows end whole). */
int pse_rows_end(dev_writer_t *o, char c);

/* ---- Whole-buffer encoders ---- */

/* RunLengthDecode data (PLRM 3.13.3) for n bytes into out, which must hold
 * pse_rle_bound(n) bytes; ends with the EOD byte 128. Returns the encoded length. */
size_t pse_rle_encode(const uint8_t *in, size_t n, uint8_t *out);
/* Worst-case size of pse_rle_encode's output. */
size_t pse_rle_bound(size_t n);
/* Flate (zlib format) of n bytes into a malloc'd buffer. 0, or <0 when out of memory. */
int pse_flate_encode(const uint8_t *in, size_t n, int level, uint8_t **out, size_t *outlen);
/* Exact number of bytes pse_a85_write writes for these n bytes (line breaks and ~> included). */
size_t pse_a85_size(const uint8_t *in, size_t n);
/* Write n bytes as ASCII85 lines of at most 75 characters, ended by ~> and a newline. */
int pse_a85_write(dev_writer_t *o, const uint8_t *in, size_t n);
/* Exact size of pse_hex_write's output for n bytes. */
size_t pse_hex_size(size_t n);
/* Write n bytes as hex lines of 78 digits, ended by a newline (Level 1 readhexstring data). */
int pse_hex_write(dev_writer_t *o, const uint8_t *in, size_t n);

#endif
