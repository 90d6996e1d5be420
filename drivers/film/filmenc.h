/* filmenc.h: film-recorder encoding: log printing density, calibration curves, DPX/Cineon files.
 *
 * The film device (dev_film.c) turns 24-bit RGB rows into what a film recorder takes:
 *  - a per-channel table from the 8-bit value to the file's code value (film_lut_t), built from
 *    the log parameters (film_log_t: Kodak's reference white/black, density per code value, film
 *    and display gamma) and an optional calibration curve file (film_cal_t) applied first;
 *  - the file's header (film_header: DPX 2.0 of SMPTE ST 268, or Kodak Cineon 4.5) and rows
 *    packed as the header says (film_pack_row), so a frame streams out band by band.
 * docs/film.md gives the formulas, the header offsets and the calibration file format.
 * Nothing here prints or exits: failures return <0 with a message in the caller's buffer.
 */
#ifndef LOCUS_FILMENC_H
#define LOCUS_FILMENC_H

#include <stddef.h>
#include <stdint.h>

/* File kinds. */
enum { FILM_DPX10 = 0, FILM_DPX16 = 1, FILM_CINEON = 2, FILM_RLE = 3 /* 24-bit archive (image.h) */ };

/* Bytes of the header before the first pixel, for every kind (DPX and Cineon alike). */
#define FILM_HEADER_SIZE 2048

/* Linear-to-log parameters (docs/film.md "Colour"). */
typedef struct {
	double white;           /* reference white code value (685): linear 1.0 */
	double black;           /* reference black code value (95): linear 0.0 */
	double density;         /* printing density per code value (0.002) */
	double film_gamma;      /* negative film gamma (0.6) */
	double display_gamma;   /* display gamma (1.7; 1.7 leaves the film's slope as it is) */
} film_log_t;

/* The defaults 685, 95, 0.002, 0.6, 1.7. */
void film_log_default(film_log_t *p);
/* 0 when the parameters make a usable curve (0 <= black < white <= 1023, density, gammas > 0),
 * else -1 with a one-line reason in err. */
int film_log_check(const film_log_t *p, char *err, size_t errlen);
/* Linear value (0 = black, 1 = reference white) to a 10-bit code, rounded and clamped. */
unsigned film_log_encode(const film_log_t *p, double linear);
/* A 10-bit code back to linear (the inverse of film_log_encode before rounding). */
double film_log_decode(const film_log_t *p, unsigned code);

/* A calibration curve: per channel, a monotone piecewise-linear map of [0, 1] onto [0, 1]. */
typedef struct film_cal film_cal_t;

/* Load and check a calibration file (docs/film.md "Calibration files"). Returns 0, -66 when it
 * cannot be opened, -65 when it is bad; err gets "FILE:LINE:COL: what was expected". */
int film_cal_load(const char *path, film_cal_t **cal, char *err, size_t errlen);
/* Parse a calibration file held in memory (name is for messages). Same returns. */
int film_cal_parse(const char *text, size_t n, const char *name, film_cal_t **cal, char *err,
		size_t errlen);
/* The value to expose for the wanted linear value x on channel ch (0 R, 1 G, 2 B). */
double film_cal_apply(const film_cal_t *cal, int ch, double x);
/* Free a curve (NULL is fine). */
void film_cal_free(film_cal_t *cal);

/* Code value per channel for each 8-bit input value. */
typedef struct {
	uint16_t code[3][256];
} film_lut_t;

/* The linear light of an 8-bit picture value: the sRGB decoding (IEC 61966-2-1) of v / 255, as
 * the framework treats pixel values (docs/drivers.md); 0 .. 1. */
double film_srgb_decode(unsigned v);
/* Fill lut for kind: DPX10 and Cineon get log codes 0..1023 (film_log_encode of the calibrated
 * linear light of v), DPX16 linear codes 0..65535 (round(65535 x the calibrated linear light)).
 * cal may be NULL. */
void film_lut_build(film_lut_t *lut, int kind, const film_log_t *log, const film_cal_t *cal);

/* What one file holds. */
typedef struct {
	int kind;               /* FILM_* */
	int little_endian;      /* DPX only: 1 writes the little-endian variant ("XPDS") */
	unsigned width, height; /* pixels */
	int channel;            /* -1: RGB; 0, 1, 2: a single R, G or B separation */
	int planar;             /* 1: three single-channel image elements R, G, B one after the other */
	film_log_t log;         /* stored in the header as the reference codes */
	const char *creator;    /* up to 99 bytes kept */
	int64_t time;           /* creation time, seconds since 1970 (UTC) */
	unsigned frame;         /* frame number: the animation's (frame records), else 1 for the first page */
	double frame_rate;      /* frames per second (24; 0: rate and time code undefined); the
	                         * time code counts frame / rate from 00:00:00:00 */
	double width_mm, height_mm;  /* physical size of the frame on film, 0 = unknown */
} film_frame_t;

/* Bytes of one packed row of one image element (or of the RGB element): 10-bit rows are whole
 * 32-bit words, 16-bit rows their samples with no padding (as ImageMagick and OpenImageIO read
 * them when the width is odd). */
size_t film_row_bytes(const film_frame_t *f);
/* Total file size, or 0 when the frame does not fit the 32-bit size fields (over 4 GiB). */
uint64_t film_file_size(const film_frame_t *f);
/* The SMPTE time code of frame at rate frames a second (rounded to whole frames a second, no drop
 * frame; it wraps at 24 hours) as DPX stores it: BCD digits hh mm ss ff, hours in the top byte. */
uint32_t film_timecode(unsigned frame, double rate);
/* Write the FILM_HEADER_SIZE header bytes into buf. Returns 0, or -1 with a message in err when
 * the frame cannot be described (zero or too large a size, a bad combination). */
int film_header(const film_frame_t *f, uint8_t *buf, char *err, size_t errlen);
/* Pack one row of width RGB pixels (3 bytes each) through lut into out (film_row_bytes bytes):
 * every channel for an RGB frame, else channel ch (0, 1, 2). */
void film_pack_row(const film_frame_t *f, const film_lut_t *lut, const uint8_t *rgb, int ch,
		uint8_t *out);

/* Film geometry presets (docs/film.md "Presets"). */
typedef struct {
	const char *name;
	unsigned width, height;
	double width_mm, height_mm;
	const char *description;
} film_preset_t;

/* The presets, terminated by a NULL name; and lookup by name (NULL when unknown). */
extern const film_preset_t film_presets[];
const film_preset_t *film_preset_find(const char *name);

/* For the film device and its program (dev_film.c). */
/* A format by name ("dpx", "dpx16", "cineon" or "cin", "rle"), or by a path's suffix (.dpx,
 * .cin, .rle); -1 when unknown. */
int film_kind_by_name(const char *name);
int film_kind_by_suffix(const char *path);
/* "WxH" with each side 1 .. META_MAX_DIM; 0 or -1. */
int film_parse_size(const char *s, unsigned *w, unsigned *h);
/* The creation time of frames: SOURCE_DATE_EPOCH when set (reproducible files), else now.
 * -1 with a message when SOURCE_DATE_EPOCH is not a plain count of seconds. */
int film_source_time(int64_t *t, char *err, size_t errlen);
/* Is path a whole frame of its kind? A DPX (either byte order) or Cineon file whose header's file
 * size is the file's and whose frame position is frame (any with frame < 0), or an RLE frame that
 * decodes to its last row with nothing after it. 1 whole, 0 there but not whole (why: one line
 * naming path), -1 no such file. For --skip-existing (filmdone.c). */
int film_file_complete(const char *path, long frame, char *why, size_t n);
/* The device (for locus-film; locus-play finds it as "film"). */
struct dev_ops;
extern const struct dev_ops dev_film_ops;

#endif
