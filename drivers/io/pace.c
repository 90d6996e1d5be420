/* pace.c: flow=escb, the registered print language's own pacing (io/lang.h) for the links that
 * can read the device's replies: the link waits and counts, the language asks. */
#include <time.h>
#include "io/link.h"
#include "io/status.h"

int tr_pace_hello(const io_chan_t *c, io_pace_t *p)
{
	const io_lang_t *l = io_lang();
	p->space = -1;
	if (!l || !l->hello || !l->room)
		return io_link_fail(c->t, "flow=escb needs the pacing of the job's language, and this program "
			"registers none");
	return l->hello(c, p);
}

long tr_pace_write(const io_chan_t *c, io_pace_t *p, const void *buf, size_t n)
{
	const io_lang_t *l = io_lang();
	io_transport_t *t = c->t;
	size_t chunk = (size_t)p->bufsize / 2, want = n < chunk ? n : chunk;
	long long start = tr_now_ms();
	long room = p->space;
	p->space = -1;
	for (;;) {
		int hold;
		if (room < 0 && l->room(c, &room))
			return -1;
		if (tr_state_tick(c, room < (long)want, &hold))
			return -1;
		if (hold)
			start = tr_now_ms();   /* the device holds on purpose (paper lever up): no timeout */
		if (room >= (long)want)
			break;
		room = -1;
		if (tr_check_interrupt(t))
			return -1;
		if (tr_now_ms() - start > c->timeout_ms)
			return io_link_tempfail(t, "the plotter's buffer stayed full for %ld s (paused, or out "
				"of paper?)", c->timeout_ms / 1000);
		struct timespec ts = { 0, 20000000L };
		nanosleep(&ts, NULL);
	}
	if (c->put(t, buf, want) || l->room(c, &p->space))
		return -1;
	return (long)want;
}
