/* run.h: a replay job as the driver programs run it (input, device, outputs, exit status). */
#ifndef LOCUS_RUN_H
#define LOCUS_RUN_H

#include "device/device.h"

/* One job: replay the meta file in (path or "-") onto the device ops, writing out. */
typedef struct {
	const char *in;
	const char *out;            /* path or "-"; NULL for devices that write nothing */
	const dev_ops_t *ops;
	unsigned band_rows;         /* 0 = automatic */
	size_t budget;              /* page buffer budget in bytes, 0 = default (64 MiB) */
	const char *options;        /* device options */
} dev_job_t;

/* Run the job. A file output gets one file per page: out itself when the input has one page,
 * else out with -001, -002 ... before its suffix; all are written to temporaries and renamed
 * only when the whole input replayed without error (transport.h); every page name is made before
 * the first rename, and a page that cannot be renamed removes the pages renamed before it, so a
 * job leaves all its pages or none. An output written in place
 * (stdout, a device node, a FIFO, a socket) takes the pages one after another. Returns a
 * sysexits status (0 ok, 64 bad device option, 65 bad input, 66 no input, 70 out of memory,
 * 74 I/O: the message then names the output and the cause; 75 a device link's failure that may
 * pass, io_temporary(): resumable) with a one-line message in err. */
int dev_run(const dev_job_t *job, char *err, size_t errlen);
/* dev_run for a document format that holds every page in one output (PostScript, PDF): out,
 * a file too, is opened once and takes the pages one after another; the same statuses. */
int dev_run_document(const dev_job_t *job, char *err, size_t errlen);
/* "pic.png", 3 -> "pic-003.png" (malloc'd). */
char *dev_page_name(const char *out, unsigned page);

#endif
