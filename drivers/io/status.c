/* status.c: a device's state through the registered language (status.h), watched between the
 * chunks of a paced send (pace.c calls it; it calls no link nor transport.c, which reach pace.c:
 * the idle query over the transport's reads and writes is devstate.c). */
#include <string.h>
#include "io/link.h"
#include "io/status.h"

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
