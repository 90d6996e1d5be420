/* link_escb.c: HP-GL's own pacing (flow=escb) for the links that can read the plotter's replies. */
#include <time.h>
#include "io/link.h"

long tr_escb_write(io_transport_t *t, const tr_escb_t *e, long *space, const void *buf, size_t n)
{
	size_t chunk = (size_t)e->bufsize / 2, want = n < chunk ? n : chunk;
	long long start = tr_now_ms();
	long room = *space;
	*space = -1;
	for (;;) {
		if (room < 0 && e->ask(t, "\033.B", "ESC.B (free buffer space)", 3000, &room))
			return -1;
		if (room >= (long)want)
			break;
		room = -1;
		if (tr_check_interrupt(t))
			return -1;
		if (tr_now_ms() - start > e->timeout_ms)
			return io_link_tempfail(t, "the plotter's buffer stayed full for %ld s (paused, or out "
				"of paper?)", e->timeout_ms / 1000);
		struct timespec ts = { 0, 20000000L };
		nanosleep(&ts, NULL);
	}
	if (e->put(t, buf, want) || e->ask(t, "\033.B", "ESC.B (free buffer space)", 3000, space))
		return -1;
	return (long)want;
}
