/* scene_warn.c: the scene's warnings, positioned (parsers) or not (renderers), kept up to
 * SCENE_MAX_WARNINGS; below the parsers and the renderers, which all add to them. */
#include "scene_int.h"

#include <stdio.h>
#include <string.h>

void scene_warn(scene_t *sc, unsigned line, unsigned col, const char *msg)
{
	if (sc->nwarnings >= SCENE_MAX_WARNINGS)
		return;
	char *b = sc->warnbuf[sc->nwarnings], tmp[sizeof sc->warnbuf[0]];
	snprintf(tmp, sizeof tmp, "%.180s:%u:%u: warning: %.300s", sc->name, line, col, msg);
	memcpy(b, tmp, sizeof tmp);
	sc->warnings[sc->nwarnings++] = b;
}

void scene_add_warning(scene_t *s, const char *msg)
{
	if (s->nwarnings >= SCENE_MAX_WARNINGS)
		return;
	char tmp[sizeof s->warnbuf[0]];
	snprintf(tmp, sizeof tmp, "%.200s: warning: %.250s", s->name, msg);
	memcpy(s->warnbuf[s->nwarnings], tmp, sizeof tmp);
	s->warnings[s->nwarnings] = s->warnbuf[s->nwarnings];
	s->nwarnings++;
}
