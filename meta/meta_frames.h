/* meta_frames.h: frame records of an animation's meta file, and frame lists.
 *
 * locus-render --frames writes every frame as its pages between two comments, the frame
 * records (docs/farm.md, "Frame records"):
 *     # frame N t=T
 *     page ... end-page        (the frame's pages: one or more)
 *     # end frame N
 * so that a file of one frame, or of a range, says which frames it holds and that each is whole;
 * locus-render --skip-existing and locus-meta cat read them back here.
 */
#ifndef LOCUS_META_FRAMES_H
#define LOCUS_META_FRAMES_H

#include <stddef.h>
#include <stdint.h>
#include "locus_meta.h"

/* Largest frame number (7 digits, as --frames has always taken). */
#define META_FRAME_MAX 9999999L

/* Write the record that opens frame n at time t, and the one that closes it. 0 or <0. */
int meta_frame_begin(meta_writer_t *w, long n, double t);
int meta_frame_end(meta_writer_t *w, long n);

/* What meta_frames_scan found in one file. */
typedef struct {
	long *frames;      /* frame numbers in file order (malloc'd; free with meta_frames_free) */
	size_t n, cap;
	int binary;        /* the file's encoding */
	int records;       /* 1 when the file holds frame records at all */
	unsigned long pages;   /* pages in the file */
} meta_frames_t;

/* Read the whole file path and check it: valid meta-language to its end, and either no frame
 * record at all (records = 0) or every page inside a frame record pair, "# end frame N" closing
 * the frame "# frame N" opened, nothing outside them but comments, no frame open at the end.
 * Returns 0, or -65 (bad or incomplete: err "FILE: ..." or the reader's "FILE:LINE:COL: ..."),
 * -66 (cannot open), -70 (out of memory), -74 (read error). */
int meta_frames_scan(const char *path, meta_frames_t *out, char *err, size_t errlen);
void meta_frames_free(meta_frames_t *f);
/* 1 when path opens with a frame record before its first page (what locus-render --frames
 * writes), reading no further; 0 otherwise (also when it cannot be read). */
int meta_frames_probe(const char *path);

/* A frame list: "N" alone is frames 0..N-1; otherwise a comma list of items "A" (frame A),
 * "A-B" (A..B) and "A-BxS" (A, A+S, ... up to B). Frames are 0..META_FRAME_MAX. The result is
 * sorted ascending; a frame named twice is an error. Returns 0 with *list (malloc'd) and *n,
 * or -1 with a one-line reason in err (-3: out of memory). At most max_frames frames. */
int meta_frame_list_parse(const char *spec, size_t max_frames, long **list, size_t *n, char *err,
		size_t errlen);

/* Output names with a frame number: OUT holding one %d or %0Nd (N 1..9), and %% for a percent
 * sign. Returns 1 for such a pattern, 0 for a name without '%', -1 (reason in err: "-o 'OUT':
 * expected ...") for a malformed one. */
int meta_frame_pattern_check(const char *out, char *err, size_t errlen);
/* The name of frame fr in a checked pattern (malloc'd), NULL when out of memory. */
char *meta_frame_pattern_name(const char *pat, long fr);

#endif
