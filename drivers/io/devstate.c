/* devstate.c: io_device_state (status.h), a device's state asked through the registered language
 * on an idle link, over the transport's own io_write, io_flush and io_read. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "io/link.h"
#include "io/status.h"

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
