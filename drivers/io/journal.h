/* journal.h: the job journal of a device link (journal=FILE, resume=FILE in the output name, or
 * the programs' --journal FILE, --resume FILE):
 * how far the device acknowledged a job, at the last checkpoint (a point where it can go on
 * without redrawing or skipping a stroke) with what restores the device's state there, so that
 * the same job, produced again, resumes from that point. The checkpoints, the restore and the
 * check of the job's language are the registered language's (io/lang.h: HP-GL registers them,
 * hpgl/hpgl_link.h); the journal keeps them opaque. Without a registered language jn_create and
 * jn_resume refuse. The file is rewritten (through a temporary and a rename) after every
 * acknowledgement, so it is current after a crash too.
 */
#ifndef LOCUS_JOURNAL_H
#define LOCUS_JOURNAL_H

#include <stddef.h>

typedef struct jn jn_t;

/* A journal for a new job into the device named name; path is created (or replaced).
 * NULL with one line in err. */
jn_t *jn_create(const char *path, const char *name, char *err, size_t errlen);
/* Resume the job journaled in path: the first bytes of the job (as far as the device had them)
 * are checked and skipped, then the modal state is restored; journaling goes on in path.
 * NULL with one line in err (missing, malformed, or the job was complete). */
jn_t *jn_resume(const char *path, const char *name, char *err, size_t errlen);
/* Resume mode: of the job's next n bytes p, how many to skip (the device has them). When the
 * skip ends, *restore points to the language's state-restoring bytes to send first (else NULL). -1 when
 * the job differs from the journaled one (message in err). */
long jn_skip(jn_t *j, const void *p, size_t n, const char **restore, char *err, size_t errlen);
/* The job's first bytes p (n of them; called before any is sent): 0 when they are in the
 * registered language (or only blanks so far), -1 with one line in err when the job is another
 * (for HP-GL: PostScript, PDF, PCL, raster): a journal resumes its language only, and refuses
 * the others before a byte goes.
 * A journal refused so is removed at jn_close when this run created it. */
int jn_language(jn_t *j, const void *p, size_t n, char *err, size_t errlen);
/* Resume mode: the journal's acked count (how far the device had the job: the restore's closer
 * is made from the job's bytes between the point and there). */
unsigned long long jn_held(const jn_t *j);
/* 1 while bytes are still to be skipped. */
int jn_skipping(const jn_t *j);
/* The device acknowledged the job's next n bytes p. 0, or -1 when the file cannot be written. */
int jn_ack(jn_t *j, const void *p, size_t n);
/* Words for where the job stopped: "page P, command C (byte B of the job) reached; resume
 * with: CMD" (the command jn_set_command gave), or without one "...; resume with -o 'NAME'"
 * where NAME is the output name with journal= turned into resume=. */
void jn_where(const jn_t *j, char *buf, size_t len);
/* The command that resumes a job (copied, up to 1023 bytes); NULL or "" forgets it. */
void jn_set_command(const char *cmd);
/* End: done (1) marks the journal complete; 0 leaves it resumable. Frees j. 0 or -1. */
int jn_close(jn_t *j, int done);

#endif
