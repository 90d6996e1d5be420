/* status.c: a device's state through the registered language (status.h): asked on an idle link
 * over the transport's own reads and writes, or watched between the chunks of a paced send. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "io/link.h"
#include "io/status.h"

/* ---- an idle link: the language's queries over io_write/io_read ---- */

static int idle_put(io_transport_t *t, const void *buf, size_t n)
{
	return io_write(t, buf, n) < 0 || io_flush(t) < 0 ? -1 : 0;
}

static int idle_reply(io_transport_t *t, const char *what, char *buf, size_t len, long ms)
{
	size_t k = 0;
	long long end = tr_now_ms() + ms;
	for (;;) {
		char c;
		long g = io_read(t, &c, 1);
		if (g < 0)
			return -1;
		if (tr_now_ms() > end)
			return io_link_fail(t, "no answer to %s within %ld ms", what, ms);
		if (g == 0) {
			struct timespec nap = { 0, 10000000L };
			nanosleep(&nap, NULL);
			continue;
		}
		if (c == '\r' || c == '\n') {
			if (k)
				break;
			continue;
		}
		if (k + 1 < len)
			buf[k++] = c;
	}
	buf[k] = 0;
	return 0;
}

static int idle_ask(io_transport_t *t, const char *q, const char *what, long ms, long *out)
{
	char r[32], *e;
	if (idle_put(t, q, strlen(q)) || idle_reply(t, what, r, sizeof r, ms))
		return -1;
	*out = strtol(r, &e, 10);
	return e == r ? io_link_fail(t, "%s: not a number: \"%s\"", what, r) : 0;
}

static void idle_discard(io_transport_t *t)
{
	char c;
	while (io_read(t, &c, 1) > 0)
		;
}

int io_device_state(io_transport_t *t, long ms, io_devstate_t *st)
{
	const io_lang_t *l = io_lang();
	memset(st, 0, sizeof *st);
	if (!l || !l->state)
		return 0;
	io_chan_t c = { t, idle_put, idle_ask, idle_reply, idle_discard, io_link_fail, ms };
	if (l->state(&c, 1, st)) {
		snprintf(st->words, sizeof st->words, "%s", io_error(t));
		return -1;
	}
	return 1;
}

/* ---- a paced send: the out-of-band query between chunks ---- */

static _Thread_local struct {
	io_state_fn *fn;
	void *user;
	long every;
	long long last;     /* when it was last asked, 0 never */
	int held;           /* the last answer said the device holds */
} watch;

void io_watch_state(io_state_fn *fn, void *user, long every_ms)
{
	watch.fn = fn;
	watch.user = user;
	watch.every = every_ms;
	watch.last = 0;
	watch.held = 0;
}

int tr_state_tick(const io_chan_t *c, int waiting, int *hold)
{
	const io_lang_t *l = io_lang();
	*hold = 0;
	if (!watch.fn || !l || !l->state)
		return 0;
	long long now = tr_now_ms();
	/* due every every ms, and at once when a held device takes bytes again (to clear it) */
	if (watch.last && now - watch.last < watch.every && !(watch.held && !waiting))
		return 0;
	io_devstate_t st;
	memset(&st, 0, sizeof st);
	if (l->state(c, 0, &st))
		return -1;
	watch.last = now ? now : 1;
	watch.held = (st.flags & (IO_DEV_NO_MEDIA | IO_DEV_PAUSED)) != 0;
	int r = watch.fn(watch.user, &st);
	if (r < 0)
		return io_link_tempfail(c->t, "stopped while the device held%s%s", st.words[0] ? ": " : "", st.words);
	*hold = r > 0;
	return 0;
}
