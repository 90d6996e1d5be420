/* lang.c: the print language registered for the jobs of device links (lang.h). */
#include "io/lang.h"

static const io_lang_t *registered;

void io_set_lang(const io_lang_t *l)
{
	registered = l;
}

const io_lang_t *io_lang(void)
{
	return registered;
}
