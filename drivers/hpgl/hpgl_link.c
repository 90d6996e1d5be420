/* hpgl_link.c: HP-GL as the language of device links (hpgl_link.h). */
#include <time.h>
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

static int track(void *tr, unsigned char c)
{
	return hpgl_track_byte(tr, c);
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
};

void hpgl_link_register(void)
{
	io_set_lang(&hpgl_link_lang);
}
