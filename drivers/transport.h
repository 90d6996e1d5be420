/* transport.h: where device output goes (and, later, device replies come from), chosen by name.
 *
 * Names: "-" is stdout (stdin for reading); "serial:...", "usb:...", "hid:..." are reserved for
 * device links (not supported yet: a clear error); anything else is a file path. A file is
 * written to a temporary name in the same directory and renamed over the target only when the
 * job commits, so a failed job never leaves a partial file (no fsync: this protects against
 * failed jobs, not against power loss).
 */
#ifndef LOCUS_TRANSPORT_H
#define LOCUS_TRANSPORT_H

#include <stddef.h>

typedef struct io_transport io_transport_t;

/* How io_close ends a transport. */
enum {
	IO_COMMIT = 0,   /* flush; a file is renamed into place */
	IO_ABORT = 1,    /* discard: a file's temporary is removed */
	IO_KEEP = 2      /* flush and close, keep the temporary for io_finish() later */
};

/* Open name for writing. Returns NULL with a one-line message in err on failure. */
io_transport_t *io_open_write(const char *name, char *err, size_t errlen);
/* Open name for reading ("-" = stdin). */
io_transport_t *io_open_read(const char *name, char *err, size_t errlen);
/* Write all n bytes (buffered). 0 or <0. */
int io_write(io_transport_t *t, const void *buf, size_t n);
/* Read up to n bytes: count, 0 at end, <0 on error. */
long io_read(io_transport_t *t, void *buf, size_t n);
/* Push buffered bytes to the device/file. */
int io_flush(io_transport_t *t);
/* End the transport (see IO_*). Frees it unless IO_KEEP. 0 or <0 (message in io_error). */
int io_close(io_transport_t *t, int how);
/* For a transport closed with IO_KEEP: rename its temporary to target (NULL = the original
 * name) when commit is 1, else remove it; then free it. */
int io_finish(io_transport_t *t, int commit, const char *target);
/* The last error, one line naming the transport. */
const char *io_error(const io_transport_t *t);
/* The name the transport was opened with. */
const char *io_name(const io_transport_t *t);
/* 1 if this transport is standard output/input. */
int io_is_std(const io_transport_t *t);

#endif
