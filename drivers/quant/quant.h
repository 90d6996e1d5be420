/* quant.h: colour quantisation for palette devices: histogram, palettes, mapping, dithering.
 *
 * Everything works at the precision of a VGA/XGA DAC: 6 bits per channel. A picture (24-bit
 * RGB rows) is first counted into a histogram of its 2^18 DAC colours (each bin keeps the
 * pixel count, the sum of the exact 24-bit values, and whether one 24-bit colour fills it).
 * A palette is built from the histogram by median cut (Heckbert 1982), octree (Gervautz and
 * Purgathofer 1988) or the default, median cut refined by weighted k-means passes; or it is a
 * fixed palette (VGA power-on, EGA 16, 6x6x6 cube, grey ramp) or a file. The picture is then
 * mapped to palette indices with no dithering, ordered (Bayer 8x8) or serpentine
 * Floyd-Steinberg dithering, errors measured against the DAC's colours.
 *
 * Flat colours: a histogram bin filled by one exact 24-bit colour on at least
 * quant_flat_threshold() pixels is "flat" (the fill, line or text colour of vector content).
 * Adaptive palettes give each flat colour (up to half the palette) an entry of its own, and the
 * mapping gives every pixel of a flat colour that entry without dithering, neither taking nor
 * spreading error, so flat areas and their edges stay clean.
 *
 * The module never prints; functions return 0 or <0 with a message in the caller's buffer.
 */
#ifndef LOCUS_QUANT_H
#define LOCUS_QUANT_H

#include <stddef.h>
#include <stdint.h>

#define QUANT_MAX 256

/* A palette: n entries of DAC values, R, G, B in that order: 6 bits (0..63) as on the VGA
 * and XGA, or 8 bits (0..255) when bits is 8 (a palette for today's indexed files, beyond the
 * hardware). bits 0 means 6. */
typedef struct {
	unsigned n;
	unsigned bits;
	uint8_t dac[QUANT_MAX][3];
} quant_palette_t;

/* Palette methods. QUANT_BEST (the default) is median cut refined by k-means. */
enum { QUANT_BEST = 0, QUANT_MEDIAN = 1, QUANT_OCTREE = 2 };
/* Dithering. */
enum { QUANT_DITHER_NONE = 0, QUANT_DITHER_ORDERED = 1, QUANT_DITHER_FS = 2 };
/* Fixed palettes. */
enum { QUANT_FIXED_VGA = 0, QUANT_FIXED_EGA = 1, QUANT_FIXED_CUBE = 2, QUANT_FIXED_GREY = 3 };

/* The 8-bit value a 6-bit DAC value shows (bit replication: 63 -> 255). */
static inline unsigned quant_dac8(unsigned v6) { return (v6 << 2) | (v6 >> 4); }
/* The nearest 6-bit DAC value of an 8-bit value. */
static inline unsigned quant_dac6(unsigned v8) { return (v8 * 63 + 127) / 255; }
/* The 8-bit value a palette value shows. */
static inline unsigned quant_show(const quant_palette_t *p, unsigned v)
{
	return p->bits == 8 ? v : quant_dac8(v);
}

typedef struct quant_hist quant_hist_t;

/* A new empty histogram (about 8 MiB, reused page after page). NULL when out of memory. */
quant_hist_t *quant_hist_new(void);
/* Free it (NULL is fine). */
void quant_hist_free(quant_hist_t *h);
/* Forget every count (cost proportional to the bins used, not to the table). */
void quant_hist_clear(quant_hist_t *h);
/* Count w x h pixels of 24-bit RGB, row k at rgb + k * stride. */
void quant_hist_add(quant_hist_t *h, const uint8_t *rgb, unsigned w, unsigned hgt, size_t stride);
/* Also count the exact 24-bit colours of the same pixels (call with every quant_hist_add),
 * up to 65,536 of them: 8-bit palettes are then made from the exact colours rather than the
 * DAC bins. More colours than that: the bins are used. 0, or <0 when out of memory. */
int quant_hist_exact(quant_hist_t *h, const uint8_t *rgb, unsigned w, unsigned hgt, size_t stride);
/* Number of distinct DAC colours counted. */
size_t quant_hist_colours(const quant_hist_t *h);
/* Pixels a bin must hold in one exact colour to count as flat, for the pixels counted so far. */
unsigned long quant_flat_threshold(const quant_hist_t *h);

/* Build an adaptive palette of at most ncolours (1..256) entries from the histogram by method
 * (QUANT_*). A histogram of at most ncolours DAC colours gives exactly those colours.
 * Returns 0, or <0 with a message. */
int quant_build(const quant_hist_t *h, int method, unsigned ncolours, quant_palette_t *pal,
		char *err, size_t errlen);
/* The same with a palette of bits (6 or 8) per channel: with 8, a histogram of at most
 * ncolours exact 24-bit colours gives exactly those. */
int quant_build_bits(const quant_hist_t *h, int method, unsigned ncolours, unsigned bits,
		quant_palette_t *pal, char *err, size_t errlen);
/* A fixed palette (QUANT_FIXED_*) of ncolours entries: VGA is 256 only, EGA 16 only, the cube
 * 216 (padded with black to 256), grey min(ncolours, 64) levels. 0 or <0 with a message. */
int quant_fixed(int which, unsigned ncolours, quant_palette_t *pal, char *err, size_t errlen);
/* Fixed palette by name ("vga", "ega", "cube", "grey"); -1 when the name is none of them. */
int quant_fixed_by_name(const char *name);
/* Parse a palette file's contents: up to 256 lines "#rrggbb" (8-bit values, rounded to the
 * DAC; blank lines and lines starting with ';' or '//' ignored) or exactly 768 bytes of a raw
 * DAC dump (6-bit values). name is for messages ("pal.txt:3:1: expected #rrggbb"). The palette
 * must hold between 1 and ncolours entries. 0 or <0 with a message. */
int quant_parse_palette(const unsigned char *buf, size_t n, const char *name, unsigned ncolours,
		quant_palette_t *pal, char *err, size_t errlen);
/* The same, "#rrggbb" lines kept at 8 bits when bits is 8 (a raw dump is always 6-bit). */
int quant_parse_palette_bits(const unsigned char *buf, size_t n, const char *name, unsigned ncolours,
		unsigned bits, quant_palette_t *pal, char *err, size_t errlen);

/* Map w x h pixels (24-bit RGB, row stride bytes) to palette indices (out, one byte per
 * pixel, row k at out + k * w) with the given dithering. h may be NULL (no flat colours);
 * otherwise it must be the histogram of this very picture. 0 or <0 (out of memory). */
int quant_map(const quant_palette_t *pal, const quant_hist_t *h, const uint8_t *rgb,
		unsigned w, unsigned hgt, size_t stride, int dither, uint8_t *out);
/* quant_map, calling done(ctx, y) as soon as row y of out is final, for a consumer of the
 * rows on another thread (a file written while the picture is mapped). The rows of each half
 * of a big picture come top to bottom, the two halves possibly from two threads at once:
 * done must be thread-safe. */
int quant_map_rows(const quant_palette_t *pal, const quant_hist_t *h, const uint8_t *rgb,
		unsigned w, unsigned hgt, size_t stride, int dither, uint8_t *out,
		void (*done)(void *ctx, unsigned y), void *ctx);
/* Map to 16-bit direct colour 5-6-5 (red in the top bits), same dithering and flat rule. */
int quant_map565(const quant_hist_t *h, const uint8_t *rgb, unsigned w, unsigned hgt,
		size_t stride, int dither, uint16_t *out);

/* 1 when a second thread can be expected to run beside this one: at least two processors
 * online, fewer threads runnable now than processors and a 1-minute load average below their
 * number plus a half (without the count of runnable threads: the load below their number less
 * a half). The parts of a mapping or of a k-means pass, and a file written while its page is
 * mapped, run on two threads only then (on a busy machine a second thread only adds work);
 * the answer never depends on it. */
int quant_spare_core(void);

/* Peak signal-to-noise ratio (dB) of the indexed picture against the 24-bit one (as shown by
 * the DAC); 99 when identical. */
double quant_psnr(const quant_palette_t *pal, const uint8_t *rgb, unsigned w, unsigned hgt,
		size_t stride, const uint8_t *idx);

#endif
