/* status.h: a device's own state (paper, pause, error) asked through the registered print
 * language (io/lang.h: its state operation), for a program that shows it, such as a printer
 * application's printer-state-reasons. io/ knows no language: the language fills the flags and
 * the words, io/ moves the bytes. */
#ifndef LOCUS_IO_STATUS_H
#define LOCUS_IO_STATUS_H

#include <stddef.h>
#include "io/transport.h"

enum {
	IO_DEV_NO_MEDIA = 1,        /* no paper, or the paper lever raised: the device holds */
	IO_DEV_PAUSED = 2,          /* paused at the device (a VIEW key): the device holds */
	IO_DEV_ERROR = 4            /* the device reports an error (code in error) */
};

typedef struct io_devstate {
	unsigned flags;             /* IO_DEV_* */
	long error;                 /* the language's error code, 0 none */
	char words[200];            /* the state in words, "" when fine */
} io_devstate_t;

/* Ask the device on t (a link that reads its replies: serial:, hid:; opened for writing, no job
 * under way) for its state through the registered language, each answer within ms. 1 with *st
 * filled; 0 when no language that can ask is registered; -1 with the words in st->words when
 * the device did not answer. Queries that go into the device's command stream (HP-GL OS, OE)
 * are allowed here. */
int io_device_state(io_transport_t *t, long ms, io_devstate_t *st);

/* Watch the state during this thread's paced sends (flow=escb on serial: and hid:): between two
 * chunks, where the link already waits for the device's room answer, the language's out-of-band
 * state query (HP-GL ESC.O; never bytes that enter the command stream, so the device's bytes and
 * the journal's counts are those of an unwatched send) is asked at most every every_ms, and once
 * more when a held device lets go, and fn hears each answer. fn returns 1 to keep waiting for a
 * device that holds (its buffer full because the paper lever is up: the link's timeout does not
 * run meanwhile), 0 to let the timeout run, -1 to stop the send (a temporary failure). fn NULL
 * ends the watch. */
typedef int io_state_fn(void *user, const io_devstate_t *st);
void io_watch_state(io_state_fn *fn, void *user, long every_ms);

/* pace.c, between chunks: the watch's query when it is due. *hold: 1 when fn asked to keep
 * waiting. 0, or -1 (message set: fn stopped the send, or the link failed). */
struct io_chan;
int tr_state_tick(const struct io_chan *c, int waiting, int *hold);

#endif
