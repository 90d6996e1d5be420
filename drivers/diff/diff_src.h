/* diff_src.h: locus-diff's inputs: sniffed for their kind, read whole, or a picture a row at a time. */
#ifndef LOCUS_DIFF_SRC_H
#define LOCUS_DIFF_SRC_H

#include <pthread.h>
#include <stdio.h>
#include <sys/types.h>
#include "device/device.h"
#include "image/image.h"

/* What an input holds, told from its first bytes. */
enum { DSRC_RASTER, DSRC_META, DSRC_HPGL, DSRC_PS, DSRC_PDF };
/* Names of the kinds, for messages. */
extern const char *const dsrc_kind_name[];

/* One input, read a row at a time: an image file through the streaming reader, or a meta file
 * replayed by a thread of its own onto a capture device that hands over one band at a time, so
 * that memory stays one band (the device's budget) whatever the size of the page or the file. */
typedef struct {
	const char *name;
	io_transport_t *t;
	unsigned char head[64];
	int kind;
	uint64_t dump;              /* a framebuffer dump of this many bytes */
	FILE *pipe;                 /* Ghostscript's PPM (--render) */
	pid_t pid;
	size_t nhead, headpos;
	unsigned width, height;
	img_reader_t *img;
	uint8_t *row;
	/* meta files */
	int meta, started;
	meta_reader_t *mr;
	dev_device_t *dev;
	pthread_t thr;
	pthread_mutex_t mu;
	pthread_cond_t cv;
	unsigned want;
	int sized, done, quit, status;
	const render_band_t *band;
	unsigned band_at;
	char tmp[64];                /* the temporary copy Ghostscript reads */
	char err[600];
} dsrc_t;

/* Open path and read its first bytes to tell its kind (s->kind); 0 or an exit status (sysexits)
 * with the message in s->err. page is the page wanted of meta, PostScript and PDF inputs. */
int dsrc_sniff(dsrc_t *s, const char *path, unsigned page);
/* Read the whole input into memory (*buf, malloc'd); 0 or an exit status. */
int dsrc_slurp(dsrc_t *s, unsigned char **buf, size_t *len);
/* --render: Ghostscript turns the page of a PostScript/PDF input into a PPM read through a pipe
 * (the input copied to a temporary file first); then read it as a raster. 0 or an exit status. */
int dsrc_ghostscript(dsrc_t *s, unsigned dpi);
/* Start reading the picture (an image, or a meta file rendered by a thread of its own, banded as
 * band_rows/budget say); width and height are set. 0 or an exit status. */
int dsrc_open(dsrc_t *s, unsigned band_rows, size_t budget);
/* The next row (top first) in *row, valid until the next call; 0 or an exit status. */
int dsrc_row(dsrc_t *s, const uint8_t **row);
/* After the last row: the rest of the input must be good too. 0 or an exit status. */
int dsrc_finish(dsrc_t *s);
/* Stop and free everything (the player thread, Ghostscript, the temporary file). */
void dsrc_close(dsrc_t *s);
/* Rewrite a PDF held in buf, len (malloc'd) as qpdf's QDF form (streams uncompressed, objects
 * renumbered in order, no object streams), so that a text comparison sees the drawing operators;
 * 0, or -1 (qpdf missing or failing: the buffer is left as it was). */
int dsrc_qdf(unsigned char **buf, size_t *len);
/* Print the error of a source (one line) and return st. */
int dsrc_fail(const dsrc_t *s, int st);

#endif
