/* lang.h: what a transport asks of the print language its jobs are in. io/ moves bytes and knows
 * no print language: the job journal keeps opaque checkpoints that the language's tracker finds,
 * and the links that read a device's replies (flow=escb on serial: and hid:) pace and ask for
 * status through the language's operations. A program registers its language (io_set_lang)
 * before it opens a link; hpgl/hpgl_link.h registers HP-GL. Without one, journal=, resume= and
 * flow=escb are refused at the open.
 */
#ifndef LOCUS_IO_LANG_H
#define LOCUS_IO_LANG_H

#include <stddef.h>
#include "io/status.h"
#include "io/transport.h"

/* A link that reads the device's replies, as a language's handshakes use it. */
typedef struct io_chan {
	io_transport_t *t;
	/* send all n bytes: 0, or -1 (message set) */
	int (*put)(io_transport_t *t, const void *buf, size_t n);
	/* send query q and read its number reply within ms: 0, or -1 (message set, naming what) */
	int (*ask)(io_transport_t *t, const char *q, const char *what, long ms, long *out);
	/* read one reply line (its terminator dropped) within ms: 0, or -1 (message set) */
	int (*reply)(io_transport_t *t, const char *what, char *buf, size_t len, long ms);
	/* forget what the device sent and nobody read */
	void (*discard)(io_transport_t *t);
	/* the link's failure line, "NAME: " + the words (sets failed): -1 */
	int (*fail)(io_transport_t *t, const char *fmt, ...)
#ifdef __GNUC__
		__attribute__((format(printf, 2, 3)))
#endif
		;
	long timeout_ms;            /* a device that takes nothing for this long: a temporary failure */
} io_chan_t;

/* A paced link's knowledge of its device, kept by the link and filled by the language. */
typedef struct io_pace {
	long bufsize;               /* the device's input buffer */
	long space;                 /* free space in the last answer not yet used, -1 when none */
	char ident[64];             /* the device's identification */
} io_pace_t;

typedef struct io_lang {
	const char *name;           /* "HP-GL": the journal's refusal says it keeps these jobs only */
	/* Journal. A job's first bytes: 0 when only blanks so far, 1 when in this language, -1 when
	 * not (*what: "a PostScript document" ...). */
	int (*sniff)(const unsigned char *p, size_t n, const char **what);
	/* A tracker at the start of a job (NULL: out of memory), and its end. */
	void *(*track_new)(void);
	void (*track_free)(void *tr);
	/* The job's next n bytes p: k when the last checkpoint among them follows p[k - 1] (the
	 * tracker keeps the state there), 0 when none does. */
	size_t (*track)(void *tr, const unsigned char *p, size_t n);
	/* What brings a device back to the last checkpoint's state (the journal's "restore" line). */
	void (*restore)(const void *tr, char *buf, size_t len);
	/* The bytes to send when a resumed job reaches its checkpoint (where tr stands): what ends
	 * the command the device may hold unfinished (its first held bytes of rest, the job from
	 * the checkpoint, len bytes), then the restore. */
	void (*resume)(const void *tr, const unsigned char *rest, size_t len, size_t held, char *out,
		size_t outlen);
	/* The last checkpoint's page (0 before the first) and count of whole commands. */
	unsigned long (*page)(const void *tr);
	unsigned long (*command)(const void *tr);
	/* What a checkpoint is, in words: "after a command or a whole coordinate pair". */
	const char *checkpoint_words;
	/* Links that read replies (flow=escb). At the open: learn the device's buffer size and
	 * identification into p. 0, or -1 (message set). */
	int (*hello)(const io_chan_t *c, io_pace_t *p);
	/* Ask the device how many bytes its buffer has room for now: 0, or -1 (message set). The
	 * link sends at most half the buffer once there is room for it, then asks again: the answer,
	 * read behind the chunk, confirms the chunk arrived (the journal counts it then). */
	int (*room)(const io_chan_t *c, long *room);
	/* At the end of a job: the device's error code (0: none). 0, or -1 (message set). */
	int (*status)(const io_chan_t *c, long *code);
	/* The words for an error code ("bad parameter"), or "unknown". */
	const char *(*status_words)(long code);
	/* The device's state now for a display (io/status.h): flags, error code, words. in_band 0
	 * (between the chunks of a send): only queries outside the command stream; 1 (idle): any.
	 * 0, or -1 (message set). NULL: the language cannot ask. */
	int (*state)(const io_chan_t *c, int in_band, io_devstate_t *st);
} io_lang_t;

/* The language of the jobs this program sends to device links (NULL: none). */
void io_set_lang(const io_lang_t *l);
const io_lang_t *io_lang(void);

#endif
