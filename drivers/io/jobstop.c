/* jobstop.c: a job stopped on purpose, resumable from exactly that point (jobstop.h). */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include "io/jobstop.h"
#include "io/journal.h"
#include "io/link.h"

int io_stop(io_transport_t *t, const char *why)
{
	if (t->failed || io_drain(t))
		return -1;
	snprintf(t->err, sizeof t->err, "%s: %s", t->std ? "<stdout>" : t->name, why);
	t->failed = 1;
	t->temporary = 1;
	t->io_errno = EINTR;   /* interrupted, on purpose: 75, and "no journal was kept" without one */
	if (t->link)
		return tr_journal_where(t);
	return -1;
}

unsigned long long io_resume_held(const io_transport_t *t)
{
	return t->journal ? jn_held(t->journal) : 0;
}
