/* transport.h: where program output goes (and, later, device replies come from), chosen by name.
 *
 * Names: "-" is stdout (stdin for reading); device links (docs/transports.md):
 *   serial:/dev/X?baud=N&parity=none|even|odd&bits=5..8&stop=1|2&flow=xonxoff|rtscts|escb|none
 *   tcp:HOST[:PORT] (raw, port 9100), usb:VID:PID[:SERIAL] or usb:any (USB printer class),
 *   hid:VID:PID[:SERIAL]?baud=... (CP2110 HID UART bridge); each also takes journal=FILE or
 *   resume=FILE (journal.h: resumable jobs);
 * anything else is a path, and what it names decides how it is written:
 *   - a regular file, or a name that does not exist yet, is written to a new temporary beside
 *     it, TARGET.PID-K.tmp, created with O_EXCL|O_NOFOLLOW (an existing name, a symlink above
 *     all, is never opened: the next K is tried), and renamed over the target only when the job
 *     commits, so a failed job leaves the old file as it was and no partial file. The result
 *     gets the target's mode (new files: 0666 & ~umask). A symlink to a regular file stays a
 *     symlink: the file it leads to is replaced. (No fsync: this protects against failed jobs,
 *     not against power loss.)
 *   - a device node, FIFO, socket (AF_UNIX stream) or terminal is opened and written in place,
 *     never created, truncated or renamed over; /dev/stdout, /dev/stderr, /dev/fd/N and
 *     /proc/self/fd/N write to a copy of that descriptor.
 * While a temporary exists, SIGINT, SIGTERM and SIGHUP (unless ignored, or handled by the
 * program) remove every live temporary and then end the program with the signal (status
 * 128 + signal); exit() removes them too. While a device link is open for writing they stop the
 * job instead (io_open_write).
 * Every write, flush and close error is kept as one line, "NAME: what failed: cause", for
 * io_error(); standard output is named "<stdout>".
 */
#ifndef LOCUS_TRANSPORT_H
#define LOCUS_TRANSPORT_H

#include <stddef.h>

typedef struct io_transport io_transport_t;

/* How io_close ends a transport. */
enum {
	IO_COMMIT = 0,   /* flush; a file is renamed into place */
	IO_ABORT = 1,    /* discard: a file's temporary is removed (bytes already sent in place stay) */
	IO_KEEP = 2      /* flush and close, keep the temporary for io_finish() later */
};

/* Open name for writing. Returns NULL with a one-line message in err on failure, and errno
 * ENOMEM when memory ran out (else another errno, EIO when none fits). While a device link is
 * open for writing, SIGINT, SIGTERM and SIGHUP (unless ignored or handled by the program) stop
 * the job instead of the program: the next write or wait fails as a temporary failure
 * ("interrupted by SIGINT", io_errno EINTR) that says where the job stopped; a second signal
 * ends the program. */
io_transport_t *io_open_write(const char *name, char *err, size_t errlen);
/* Open name for reading ("-" = stdin). */
io_transport_t *io_open_read(const char *name, char *err, size_t errlen);
/* Write all n bytes (buffered). 0 or <0 (message in io_error). */
int io_write(io_transport_t *t, const void *buf, size_t n);
/* printf into the transport's buffer (no allocation unless one result is longer than the
 * whole buffer, which then grows). 0 or <0 (message in io_error). */
int io_printf(io_transport_t *t, const char *fmt, ...)
#ifdef __GNUC__
	__attribute__((format(printf, 2, 3)))
#endif
	;
/* Read up to n bytes: count, 0 at end, <0 on error. */
long io_read(io_transport_t *t, void *buf, size_t n);
/* Push buffered bytes to the device/file. 0 or <0. */
int io_flush(io_transport_t *t);
/* The job is complete: io_flush, then (device links) wait, bounded, until the device confirms
 * it has every byte (tcp: the printer's close after a half-close), so that a failure there is
 * still seen with io_temporary() and io_errno() before io_close. io_close does it too. 0 or <0. */
int io_drain(io_transport_t *t);
/* End the transport (see IO_*). Frees it unless IO_KEEP. 0 or <0 (message in io_error; on
 * IO_COMMIT and IO_ABORT the transport is freed anyway, so copy the message first with
 * io_close_err). After IO_KEEP the caller still owns t, failed or not: io_finish() frees it. */
int io_close(io_transport_t *t, int how);
/* io_close that copies the error line into err (when err is not NULL) before freeing. A failure
 * leaves errno the failure's code (as io_errno: ENOMEM when memory ran out), so that a program
 * decides 70 or 74 by value after the transport is gone. */
int io_close_err(io_transport_t *t, int how, char *err, size_t errlen);
/* For a transport closed with IO_KEEP: rename its temporary to target (NULL = the original
 * name; a target chosen now follows the same rules as at open: the mode of a file it replaces
 * is kept, a device or directory is refused) when commit is 1, else remove it; then free it.
 * 0, or <0 with one line in err (when not NULL) and errno the failure's code (as io_close_err). */
int io_finish(io_transport_t *t, int commit, const char *target, char *err, size_t errlen);
/* The last error, one line naming the transport ("" if none). */
const char *io_error(const io_transport_t *t);
/* 1 once a write, flush or close has failed. */
int io_failed(const io_transport_t *t);
/* 1 when the failure is one a later try may not meet: a device unplugged, off, busy or out of
 * paper, a line held too long, a dropped connection. A program then exits 75 (EX_TEMPFAIL)
 * rather than 74, and a job with journal= can be resumed (docs/transports.md). */
int io_temporary(const io_transport_t *t);
/* The errno of the failure (ENOMEM when memory ran out, EINTR after a signal, EIO for a link's
 * own failure, else the system call's), 0 while none: programs decide 70 or 74 by it. */
int io_errno(const io_transport_t *t);
/* 1 when name is a device link (serial:, tcp:, usb:, hid:), which takes journal= and resume=. */
int io_is_link_name(const char *name);
/* The command that resumes a journaled job (the program's command line with --journal turned
 * into --resume), for the line of a job that stopped; NULL or "" gives "-o NAME?resume=FILE". */
void io_set_resume_command(const char *cmd);
/* The name the transport was opened with. */
const char *io_name(const io_transport_t *t);
/* 1 if this transport is standard output/input. */
int io_is_std(const io_transport_t *t);
/* Write one line per attached USB printer-class device to out: its output name
 * (usb:VID:PID[:SERIAL]), one-way or bidirectional, and its IEEE-1284 device ID; then one per
 * CP2110 HID UART bridge (hid:VID:PID[:SERIAL], maker and product). 0, or -1. */
int io_list_devices(io_transport_t *out, char *err, size_t errlen);
/* 1 if it is written in place (stdout, a device, pipe, socket, terminal): one transport then
 * takes every page of a job, as there is no file per page to rename. */
int io_in_place(const io_transport_t *t);

#endif
