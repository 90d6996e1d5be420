/* hpgl_link.c: HP-GL as the language of device links (hpgl_link.h): the journal's checkpoints
 * through the tracker of hpgl/read/, and the plotter's handshakes on links that read replies. */
#include <stdio.h>
#include <string.h>
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

/* The plotter's state for a display: ESC.O (bit 5, 32: the paper lever raised; bit 4, 16: VIEW
 * pressed), asked out of band at any time; idle also OS (bit 5, 32: an error) and OE (its code;
 * 8: a vector while the pinch wheels were raised), which enter the command stream. */
static int state(const io_chan_t *c, int in_band, io_devstate_t *st)
{
	long o = 0, os = 0, oe = 0, ms = c->timeout_ms < 3000 ? c->timeout_ms : 3000;
	size_t n = sizeof st->words;
	char *w = st->words;
	if (c->ask(c->t, "\033.O", "ESC.O (status)", ms, &o))
		return -1;
	if (in_band && (c->ask(c->t, "OS;", "OS (status)", ms, &os) || c->ask(c->t, "OE;", "OE (error)", ms, &oe)))
		return -1;
	st->flags = 0;
	st->error = oe;
	w[0] = 0;
	if ((o & 32) || oe == 8) {
		st->flags |= IO_DEV_NO_MEDIA;
		snprintf(w, n, "the paper lever is raised (load paper and lower it)");
	}
	if (o & 16) {
		st->flags |= IO_DEV_PAUSED;
		snprintf(w + strlen(w), n - strlen(w), "%sVIEW is pressed (the plotter is paused)", w[0] ? "; " : "");
	}
	if (oe > 0 && oe != 8) {
		st->flags |= IO_DEV_ERROR;
		snprintf(w + strlen(w), n - strlen(w), "%sthe plotter reports error %ld: %s", w[0] ? "; " : "", oe,
			status_words(oe));
	} else if ((os & 32) && !oe && !st->flags) {
		st->flags |= IO_DEV_ERROR;
		snprintf(w, n, "the plotter reports an error (OS 32)");
	}
	return 0;
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
	.state = state,
};

void hpgl_link_register(void)
{
	io_set_lang(&hpgl_link_lang);
}
