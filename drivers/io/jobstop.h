/* jobstop.h: a job that stops on purpose at a point of its own choosing (a pen to be changed by
 * hand that nobody could change), resumable from exactly there, and how far a resumed job's
 * device already had it. */
#ifndef LOCUS_JOBSTOP_H
#define LOCUS_JOBSTOP_H

#include "io/transport.h"

/* Stop the job here: everything written so far is sent and confirmed by the device (io_drain),
 * the job journal (journal=, if any) records this point, and t fails as a temporary failure
 * with the line "NAME: WHY; page P, command C (byte B of the job) reached; resume with: CMD"
 * (without a journal: that none was kept), so that a program exits 75 and io_close leaves the
 * journal "interrupted". Returns -1 (as every failure; io_error has the line). */
int io_stop(io_transport_t *t, const char *why);
/* When t resumes a journaled job (resume=): the bytes of the job the device had when it stopped
 * (the journal's acked count); 0 for a new job or no journal. A point of the job at or before it
 * was passed in the run that stopped. */
unsigned long long io_resume_held(const io_transport_t *t);

#endif
