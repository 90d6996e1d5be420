/* scene_int.h: internals shared by scene.c, scene_shape.c, scene_render.c, scene_2d.c and scene_warn.c (not part of the public API). */
#ifndef LOCUS_SCENE_INT_H
#define LOCUS_SCENE_INT_H

#include <math.h>
#include <time.h>

#include "scene.h"
#include "scene_lex.h"

/* Colour of a voronoi nucleus not given one (cell_colour() picks it at render time). */
#define SCENE_NO_COLOUR 0xff000000u

/* Parse a `shape NAME` or `object NAME` block (kw its keyword; drawn for an object) into a new
 * sc->objs entry, up to its `end`. */
int scene_parse_shape(scene_lex_t *lx, scene_t *sc, int drawn, const scene_tok_t *kw);
/* Add "NAME:LINE:COL: warning: MSG" to the scene's warnings (dropped beyond SCENE_MAX_WARNINGS). */
void scene_warn(scene_t *sc, unsigned line, unsigned col, const char *msg);

/* Parse a `render KIND` block (kw is the `render` token) into a new sc->renders entry. */
int scene_parse_render(scene_lex_t *lx, scene_t *sc, const scene_tok_t *kw);

/* Draw a contour or voronoi block into the page rectangle rect = x y w h. */
int scene_render_2d(scene_t *s, const scene_render_t *r, meta_writer_t *w, const scene_opts_t *o,
                    const unsigned rect[4], scene_stats_t *st, char *err, size_t errlen);

/* Add "NAME: warning: MSG" to the scene's warnings (dropped beyond SCENE_MAX_WARNINGS). */
void scene_add_warning(scene_t *s, const char *msg);

/* An RGB colour (components clamped to 0..1) as a meta colour. */
static inline meta_rgb_t scene_rgb(const double *c)
{
	unsigned v[3];
	for (int i = 0; i < 3; i++)
		v[i] = (unsigned)(fmin(fmax(c[i], 0), 1) * 255 + 0.5);
	return (meta_rgb_t)(v[0] << 16 | v[1] << 8 | v[2]);
}

/* Monotonic seconds, for the timing statistics. */
static inline double scene_now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + ts.tv_nsec * 1e-9;
}

#endif
