/* hpgl_link.c: HP-GL as the language of device links (hpgl_link.h): the journal's checkpoints
 * through the tracker of hpgl/read/, and the plotter's handshakes on links that read replies. */
#include "hpgl/hpgl_link.h"
#include "hpgl/read/hpgl_track.h"

static void *track_new(void)
{
	return hpgl_track_new();
}

static void track_free(void *tr)
{
	hpgl_track_free(tr);
}

static size_t track(void *tr, const unsigned char *p, size_t n)
{
	size_t last = 0;
	for (size_t k = 0; k < n; k++)
		if (hpgl_track_byte(tr, p[k]))
			last = k + 1;
	return last;
}

static void restore(const void *tr, char *buf, size_t len)
{
	hpgl_track_restore(tr, buf, len);
}

static void resume(const void *tr, const unsigned char *rest, size_t len, size_t held, char *out, size_t outlen)
{
	hpgl_track_resume(tr, rest, len, held, out, outlen);
}

static unsigned long page(const void *tr)
{
	return hpgl_track_page(tr);
}

static unsigned long command(const void *tr)
{
	return hpgl_track_command(tr);
}

/* flow=escb at the open: learn the plotter's buffer (ESC.L), identify it (OI). */
static int hello(const io_chan_t *c, io_pace_t *p)
{
	if (c->ask(c->t, "\033.L", "ESC.L (buffer size)", 3000, &p->bufsize))
		return -1;
	if (p->bufsize < 2)
		return c->fail(c->t, "the plotter reports a buffer of %ld bytes", p->bufsize);
	c->discard(c->t);
	return c->put(c->t, "OI;", 3) || c->reply(c->t, "OI (identification)", p->ident, sizeof p->ident, 3000)
		? -1 : 0;
}

/* ESC.B: the free space in the plotter's buffer. */
static int room(const io_chan_t *c, long *out)
{
	return c->ask(c->t, "\033.B", "ESC.B (free buffer space)", 3000, out);
}

/* OE: the plotter's error at the end of the job. */
static int status(const io_chan_t *c, long *code)
{
	return c->ask(c->t, "OE;", "OE (error)", c->timeout_ms, code);
}

/* The words for OE's error numbers. */
static const char *status_words(long code)
{
	static const char *const oe_words[] = {
		"no error", "command not recognised", "wrong number of parameters",
		"bad parameter", "unknown error 4", "unknown character set", "position overflow",
		"unknown error 7", "vector received while the pinch wheels were raised",
	};
	return code > 0 && code < (long)(sizeof oe_words / sizeof oe_words[0]) ? oe_words[code] : "unknown";
}

const io_lang_t hpgl_link_lang = {
	.name = "HP-GL",
	.sniff = hpgl_sniff,
	.track_new = track_new,
	.track_free = track_free,
	.track = track,
	.restore = restore,
	.resume = resume,
	.page = page,
	.command = command,
	.checkpoint_words = "after a command or a whole coordinate pair",
	.hello = hello,
	.room = room,
	.status = status,
	.status_words = status_words,
};

void hpgl_link_register(void)
{
	io_set_lang(&hpgl_link_lang);
}
