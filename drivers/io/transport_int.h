/* transport_int.h: the transport object, the link table's entry and the live-temporary table,
 * shared by the files of io/ (not public). */
#ifndef LOCUS_TRANSPORT_INT_H
#define LOCUS_TRANSPORT_INT_H

#include <signal.h>
#include <sys/types.h>
#include "io/transport.h"

/* One temporary that a signal must remove (tempfiles.c). */
typedef struct io_temp io_temp_t;

/* A listing line of io_list_devices: printf-like, to the listing's user. */
typedef void io_list_put_fn(void *user, const char *fmt, ...)
#ifdef __GNUC__
	__attribute__((format(printf, 2, 3)))
#endif
	;

/* A device link (serial:, usb:, hid:): the scheme's own open, byte moves and close. A link
 * whose open is NULL is reserved: naming it gives "not supported yet". write and read return
 * the bytes moved (write: > 0) or -1 with errno set; close returns 0 or -1 with errno. */
typedef struct io_link {
	const char *scheme;         /* "serial:" */
	int (*open)(io_transport_t *t, const char *rest, int writing, char *err, size_t errlen);
	long (*write)(io_transport_t *t, const void *buf, size_t n);
	long (*read)(io_transport_t *t, void *buf, size_t n);
	int (*close)(io_transport_t *t);
	/* Optional (NULL: what write returned is confirmed): the bytes, counted over every write
	 * since the open, that the device itself has confirmed, when that lags behind what the link
	 * took (TCP: the peer's acknowledgements). -1 when it cannot be known now. */
	long long (*acked)(io_transport_t *t);
	/* Optional: the job is complete; wait (bounded) until the device confirms all of it (TCP:
	 * half-close, then the peer's close). 0, or -1 with the message set. */
	int (*drain)(io_transport_t *t);
	/* Optional: one line per attached device this link can open (io_list_devices), through
	 * put(user, ...). 0, or -1 with a message in err (the listing stops there). */
	int (*list)(io_list_put_fn *put, void *user, char *err, size_t errlen);
} io_link_t;

struct io_transport {
	const io_link_t *link;      /* NULL: a descriptor (stdio, files, devices, pipes, sockets) */
	void *link_state;           /* the link's own */
	struct jn *journal;         /* journal=/resume= of a device link (journal.h), or NULL */
	int fd;
	int std;            /* standard output or input: never closed */
	int in_place;       /* written where it is (stdout, devices, pipes, sockets, /dev/fd/N) */
	int writing;
	char *name;         /* as given */
	char *target;       /* regular file: the path its temporary replaces */
	char *tmp;          /* that temporary, NULL once renamed or removed */
	io_temp_t *live;    /* the temporary's entry in the signal table */
	unsigned char *buf;
	size_t nbuf, cap;
	int failed;
	int temporary;      /* the failure may pass: device away, busy, dropped (io_temporary) */
	int io_errno;       /* the failure's errno (ENOMEM, EIO, EPIPE ...): io_errno() */
	int drained;        /* the link's drain ran (io_drain) */
	/* links with acked: job bytes the link took that the device has not confirmed yet, fed to
	 * the journal as confirmations come (at most the link's own send queue) */
	unsigned char *pend;
	size_t npend, cappend;
	unsigned long long pend_at;   /* the link offset of pend[0] */
	unsigned long long link_out;  /* bytes written through the link, restores included */
	char err[512];
};

/* Record errno's cause as the transport's error: "NAME: what: strerror" (io_errno = errno).
 * Returns -1. */
int io_set_err(io_transport_t *t, const char *what);

/* "NAME: out of memory" into err; the failed open leaves errno ENOMEM (io_open_write). -1. */
int io_oom(char *err, size_t errlen, const char *name);
/* link_util.c: the errno the open under way (io_open_write) leaves when it returns NULL: set to
 * ENOMEM by io_oom, 0 (then EIO) else. */
extern _Thread_local int io_open_errno;

/* file.c: open t->name for writing: a regular file (or a name that does not exist yet)
 * through a new temporary beside it, anything else in place. 0, or -1 with a message in err. */
int io_file_open(io_transport_t *t, char *err, size_t errlen);
/* Rename the (closed) temporary over target (NULL: the one chosen at open), keeping that
 * file's mode. 0, or -1 with the cause in t's error; the temporary is removed either way. */
int io_file_commit(io_transport_t *t, const char *target);
/* Remove the temporary, if any. */
void io_file_discard(io_transport_t *t);

/* tempfiles.c: register path (copied) as a live temporary: SIGINT, SIGTERM and SIGHUP (where
 * they are not ignored or handled by the program) remove every live temporary, then the
 * program dies of the signal. NULL when out of memory. Call with the signals blocked. */
io_temp_t *io_temp_add(const char *path);
/* The temporary is gone or renamed: the handlers leave it alone from now on. */
void io_temp_drop(io_temp_t *e);
/* Block SIGINT, SIGTERM and SIGHUP in this thread (old mask saved), and restore it. */
void io_signals_block(sigset_t *old);
void io_signals_restore(const sigset_t *old);

/* signals.c: the signal (SIGINT, SIGTERM, SIGHUP) that arrived during a device job, or 0.
 * While a device link is open for writing those signals only set it (unless the program ignores
 * or handles them): the link's waits end and the job stops with a temporary failure, its
 * journal current, instead of the program dying mid-transfer; a second one ends the program. */
int io_interrupted(void);

#endif
