/* link_journal.c: a device link's bytes as the job journal hears of them: at once where a
 * write's count is the device's confirmation, as acknowledgements come where it is not (TCP),
 * and the journal's point added to the line of a job that stopped. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "io/journal.h"
#include "io/link.h"

/* The journal hears that the device has the job's next n bytes p. 0, or -1 (message set). */
static int journal_ack(io_transport_t *t, const unsigned char *p, size_t n)
{
	if (jn_ack(t->journal, p, n) == 0)
		return 0;
	int e = errno;
	io_link_fail(t, "cannot write the job journal: %s", strerror(e));
	t->io_errno = e;
	return -1;
}

/* Feed the journal what the device has confirmed of the pending bytes (links with acked). */
int tr_confirm(io_transport_t *t)
{
	if (!t->journal || !t->link || !t->link->acked || !t->npend)
		return 0;
	long long a = t->link->acked(t);
	if (a < 0 || (unsigned long long)a <= t->pend_at)
		return 0;
	unsigned long long k = (unsigned long long)a - t->pend_at;
	if (k > t->npend)
		k = t->npend;
	if (journal_ack(t, t->pend, (size_t)k))
		return -1;
	memmove(t->pend, t->pend + k, t->npend - (size_t)k);
	t->npend -= (size_t)k;
	t->pend_at += k;
	return 0;
}

/* The link took w job bytes p: the journal hears of them when the device confirms them (at once,
 * for a link whose write count is the confirmation). 0, or -1 (message set). */
int tr_took(io_transport_t *t, const unsigned char *p, size_t w)
{
	unsigned long long at = t->link_out;
	t->link_out += w;
	if (!t->journal)
		return 0;
	if (!t->link->acked)
		return journal_ack(t, p, w);
	if (t->npend + w > t->cappend) {
		size_t c = t->cappend ? t->cappend : 65536;
		while (c < t->npend + w)
			c *= 2;
		unsigned char *b = realloc(t->pend, c);
		if (!b) {
			errno = ENOMEM;
			return io_set_err(t, "cannot keep the unconfirmed bytes for the journal");
		}
		t->pend = b;
		t->cappend = c;
	}
	if (t->npend == 0)
		t->pend_at = at;
	memcpy(t->pend + t->npend, p, w);
	t->npend += w;
	return tr_confirm(t);
}

/* A link failed mid-job: the journal as far as the device confirmed, and where it says the job
 * stopped, added to the line (or that no journal was kept, after a signal). Returns -1. */
int tr_journal_where(io_transport_t *t)
{
	size_t n = strlen(t->err);
	if (t->journal) {
		char where[1400];
		int e = t->io_errno;
		int f = t->failed, tmp = t->temporary;
		char keep[sizeof t->err];
		memcpy(keep, t->err, sizeof keep);
		tr_confirm(t);   /* a journal that cannot be written keeps the first failure's line */
		memcpy(t->err, keep, sizeof keep);
		t->io_errno = e, t->failed = f, t->temporary = tmp;
		jn_where(t->journal, where, sizeof where);
		snprintf(t->err + n, sizeof t->err - n, "; %s", where);
	} else if (t->io_errno == EINTR) {
		snprintf(t->err + n, sizeof t->err - n, "; no journal was kept: send the job again (with "
			"--journal FILE it could be resumed)");
	}
	return -1;
}
