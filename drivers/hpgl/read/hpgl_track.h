/* hpgl_track.h: an HP-GL tracker fed one byte at a time (a job as it goes to a device): where
 * the job can go on without redrawing or skipping a stroke (after a command, or after a whole
 * coordinate pair of PU, PD, PA or PR), the modal state there (pen, velocity, line type, scaling,
 * position), and the HP-GL that brings a device back to it. The job journal of a device link
 * (io/journal.h) calls it through the HP-GL language (hpgl/hpgl_link.h).
 */
#ifndef LOCUS_HPGL_TRACK_H
#define LOCUS_HPGL_TRACK_H

#include <stddef.h>

typedef struct hpgl_track hpgl_track_t;

/* A tracker at the start of a job; NULL when out of memory. */
hpgl_track_t *hpgl_track_new(void);
void hpgl_track_free(hpgl_track_t *k);
/* The job's next byte: 1 when a checkpoint (a point where the job can go on) follows it; the
 * state there is kept as the tracker's last checkpoint. */
int hpgl_track_byte(hpgl_track_t *k, unsigned char c);
/* The HP-GL that restores the last checkpoint's modal state (SP, IP, SC, ... PU;PA x,y; ...). */
void hpgl_track_restore(const hpgl_track_t *k, char *buf, size_t len);
/* The resume prefix at the last checkpoint, which is where k stands: what ends the command the
 * device may hold unfinished (the job's own bytes after the held bytes of rest, up to where the
 * command may end, then ';'), then the restore. rest (len bytes) is the job from the checkpoint;
 * the device had its first held bytes. */
void hpgl_track_resume(const hpgl_track_t *k, const unsigned char *rest, size_t len, size_t held,
	char *out, size_t outlen);
/* The last checkpoint's page (0 before the first IN or PG) and count of whole commands. */
unsigned long hpgl_track_page(const hpgl_track_t *k);
unsigned long hpgl_track_command(const hpgl_track_t *k);
/* A job's first bytes: 0 when only blanks so far, 1 when HP-GL, -1 when another language (*what:
 * "a PDF document", "a PostScript document", ...). */
int hpgl_sniff(const unsigned char *p, size_t n, const char **what);

#endif
