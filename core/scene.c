/* scene.c: parser of the scene language: view, lights, background and the file's blocks in order (shapes in scene_shape.c, render blocks in scene_render.c); loading and freeing scenes. */
#include "scene_int.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef scene_tok_t tok_t;

static int parse_view(scene_lex_t *lx, scene_t *sc)
{
	tok_t t;
	if (scene_lex_eol(lx) < 0)
		return -1;
	while (scene_lex_line(lx)) {
		scene_lex_tok(lx, &t);
		cam_t *c = &sc->cam;
		if (scene_tok_is(&t, "end"))
			return scene_lex_eol(lx);
		if (scene_tok_is(&t, "eye")) {
			if (scene_lex_numbers(lx, c->eye, 3, "an eye coordinate") < 0)
				return -1;
		} else if (scene_tok_is(&t, "look-at")) {
			if (scene_lex_numbers(lx, c->look, 3, "a look-at coordinate") < 0)
				return -1;
		} else if (scene_tok_is(&t, "direction")) {
			double d[3];
			if (scene_lex_numbers(lx, d, 3, "a direction component") < 0)
				return -1;
			for (int i = 0; i < 3; i++)
				c->look[i] = c->eye[i] + d[i];
		} else if (scene_tok_is(&t, "up")) {
			if (scene_lex_numbers(lx, c->up, 3, "an up component") < 0)
				return -1;
		} else if (scene_tok_is(&t, "fov")) {
			if (scene_lex_number(lx, &c->fov, "a field of view in degrees") < 0)
				return -1;
		} else if (scene_tok_is(&t, "window")) {
			if (scene_lex_number(lx, &c->window, "a window width") < 0)
				return -1;
		} else if (scene_tok_is(&t, "eye-separation")) {
			if (scene_lex_number(lx, &sc->eye_separation, "an eye separation") < 0)
				return -1;
		} else if (scene_tok_is(&t, "size")) {
			double w, h;
			if (scene_lex_number(lx, &w, "a width in pixels") < 0 || scene_lex_number(lx, &h, "a height in pixels") < 0)
				return -1;
			if (w < 1 || h < 1 || w > 32768 || h > 32768 || w != floor(w) || h != floor(h))
				return scene_lex_error(lx, t.line, t.col, "expected a viewport size of 1..32768 whole pixels each way");
			c->nxpix = (unsigned)w;
			c->nypix = (unsigned)h;
		} else if (scene_tok_is(&t, "projection")) {
			scene_lex_tok(lx, &t);
			if (scene_tok_is(&t, "perspective"))
				c->projection = CAM_PERSPECTIVE;
			else if (scene_tok_is(&t, "orthographic"))
				c->projection = CAM_ORTHOGRAPHIC;
			else if (scene_tok_is(&t, "stereoscopic")) {
				c->projection = CAM_PERSPECTIVE;
				if (sc->stereo == SCENE_MONO)
					sc->stereo = SCENE_STEREO_SIDE;
			} else
				return scene_lex_expected(lx, &t, "perspective, orthographic or stereoscopic");
		} else if (scene_tok_is(&t, "handedness")) {
			scene_lex_tok(lx, &t);
			if (scene_tok_is(&t, "left"))
				c->handedness = CAM_LEFT_HANDED;
			else if (scene_tok_is(&t, "right"))
				c->handedness = CAM_RIGHT_HANDED;
			else
				return scene_lex_expected(lx, &t, "left (the thesis' system, the default) or right");
		} else if (scene_tok_is(&t, "stereo-layout")) {
			scene_lex_tok(lx, &t);
			if (scene_tok_is(&t, "side-by-side"))
				sc->stereo = SCENE_STEREO_SIDE;
			else if (scene_tok_is(&t, "pages"))
				sc->stereo = SCENE_STEREO_PAGES;
			else
				return scene_lex_expected(lx, &t, "side-by-side or pages");
		} else {
			return scene_lex_expected(lx, &t, "a view setting (eye, look-at, direction, up, fov, projection, window, size, eye-separation, stereo-layout, handedness) or 'end'");
		}
		if (scene_lex_eol(lx) < 0)
			return -1;
	}
	return scene_lex_expected(lx, &(tok_t){"", 0, lx->line, 1}, "'end' closing the view block");
}

static int parse_light(scene_lex_t *lx, scene_t *sc)
{
	tok_t t;
	if (sc->nlights >= SCENE_MAX_LIGHTS)
		return scene_lex_error(lx, lx->line, 1, "expected at most 16 lights");
	rt_light_t *l = &sc->lights[sc->nlights];
	memset(l, 0, sizeof *l);
	l->colour[0] = l->colour[1] = l->colour[2] = 1;
	scene_lex_tok(lx, &t);
	if (scene_tok_is(&t, "point"))
		l->directional = 0;
	else if (scene_tok_is(&t, "directional"))
		l->directional = 1;
	else
		return scene_lex_expected(lx, &t, "point or directional");
	if (scene_lex_numbers(lx, l->pos, 3, l->directional ? "a direction towards the light" : "a light position") < 0)
		return -1;
	if (l->directional && l->pos[0] == 0 && l->pos[1] == 0 && l->pos[2] == 0)
		return scene_lex_error(lx, t.line, t.col, "expected a non-zero light direction");
	while (scene_lex_tok(lx, &t)) {
		if (scene_tok_is(&t, "shadows"))
			l->shadows = 1;
		else if (scene_tok_is(&t, "colour") || scene_tok_is(&t, "color")) {
			if (scene_parse_colour(lx, l->colour) < 0)
				return -1;
		} else
			return scene_lex_expected(lx, &t, "'colour', 'shadows' or the end of the line");
	}
	sc->nlights++;
	return 0;
}

/* A drawn object whose surface is proved empty is worth a warning only where a 3D picture (ray
 * tracing, octree, wireframe) would show that surface: a contour map of f (e.g. with c 0) is fine. */
static void empty_warnings(scene_t *sc)
{
	int in3d = sc->nrenders == 0;
	for (size_t i = 0; i < sc->nrenders; i++)
		in3d |= sc->renders[i].kind != SCENE_CONTOUR && sc->renders[i].kind != SCENE_VORONOI;
	for (size_t i = 0; in3d && i < sc->nobjs; i++) {
		const scene_obj_t *o = &sc->objs[i];
		if (!o->drawn || !o->empty)
			continue;
		char msg[400];
		snprintf(msg, sizeof msg, "'%s': the shape is empty: f = sum of weighted distances - c stays above 0 (c is below"
		         " the sum's minimum), so its 3D pictures show nothing of it; raise c to see a surface", o->name);
		scene_warn(sc, o->line, o->col, msg);
	}
}

int scene_parse(const char *text, const char *name, scene_t **out, char *err, size_t errlen)
{
	return scene_parse_frame(text, name, 0, out, err, errlen);
}

int scene_parse_frame(const char *text, const char *name, double time, scene_t **out, char *err, size_t errlen)
{
	scene_lex_t lx;
	tok_t t;
	scene_t *sc = calloc(1, sizeof *sc);
	*out = NULL;
	if (!sc) {
		snprintf(err, errlen, "%s: out of memory", name);
		return SCENE_ENOMEM;
	}
	snprintf(sc->name, sizeof sc->name, "%s", name);
	cam_t *c = &sc->cam;
	c->eye[2] = -6;
	c->up[1] = 1;
	c->fov = 40;
	c->nxpix = 320;
	c->nypix = 240;
	sc->eye_separation = 0.2;
	sc->background[0] = sc->background[1] = sc->background[2] = 1;
	unsigned view_line = 1, view_col = 1;
	scene_lex_init(&lx, text, name, err, errlen);
	lx.t = time;
	sc->t = time;
	while (!lx.failed && scene_lex_line(&lx)) {
		scene_lex_tok(&lx, &t);
		if (scene_tok_is(&t, "view")) {
			view_line = t.line;
			view_col = t.col;
			parse_view(&lx, sc);
		} else if (scene_tok_is(&t, "background")) {
			if (scene_parse_colour(&lx, sc->background) == 0)
				scene_lex_eol(&lx);
		} else if (scene_tok_is(&t, "light")) {
			parse_light(&lx, sc);
		} else if (scene_tok_is(&t, "object") || scene_tok_is(&t, "shape")) {
			scene_parse_shape(&lx, sc, t.s[0] == 'o', &t);
		} else if (scene_tok_is(&t, "render")) {
			scene_parse_render(&lx, sc, &t);
		} else {
			scene_lex_expected(&lx, &t, "view, background, light, shape, object or render");
		}
	}
	if (!lx.failed) {
		char e[200];
		if (cam_setup(c, e, sizeof e) < 0) {
			char msg[300];
			snprintf(msg, sizeof msg, "expected %s in the view", e);
			scene_lex_error(&lx, view_line, view_col, msg);
		}
	}
	size_t ndrawn = 0;
	for (size_t i = 0; i < sc->nobjs; i++)
		ndrawn += sc->objs[i].drawn;
	if (!lx.failed && ndrawn == 0 && sc->nrenders == 0)
		scene_lex_error(&lx, 1, 1, sc->nobjs ? "expected an 'object' block or a 'render' block: the scene defines only 'shape' blocks,"
		                " which are never drawn themselves, so it would render a blank page"
		                : "expected an 'object' block or a 'render' block: the scene is empty (no statement), so it would render a blank page");
	if (!lx.failed)
		empty_warnings(sc);
	if (lx.failed) {
		scene_free(sc);
		return strstr(err, "out of memory") ? SCENE_ENOMEM : -1;
	}
	*out = sc;
	return 0;
}

int scene_load(const char *path, scene_t **out, char *err, size_t errlen)
{
	char *buf;
	const char *name = strcmp(path, "-") ? path : "<stdin>";
	*out = NULL;
	int rc = scene_read(path, &buf, err, errlen);
	if (rc < 0)
		return rc;
	rc = scene_parse(buf, name, out, err, errlen);
	free(buf);
	return rc;
}

int scene_read(const char *path, char **text, char *err, size_t errlen)
{
	FILE *f = strcmp(path, "-") ? fopen(path, "rb") : stdin;
	const char *name = strcmp(path, "-") ? path : "<stdin>";
	*text = NULL;
	if (!f) {
		int e = errno;
		snprintf(err, errlen, "%s: cannot open: %s", path, strerror(e));
		return e == ENOMEM ? SCENE_ENOMEM : -2;
	}
	size_t cap = 1 << 16, n = 0;
	char *buf = malloc(cap);
	while (buf) {
		if (n + 1 >= cap) {
			if (cap >= (64u << 20))
				break;
			char *b = realloc(buf, cap * 2);
			if (!b) {
				free(buf);
				buf = NULL;
				break;
			}
			buf = b;
			cap *= 2;
		}
		size_t r = fread(buf + n, 1, cap - 1 - n, f);
		n += r;
		if (r == 0)
			break;
	}
	int bad = !buf || ferror(f) || n + 1 >= cap, nomem = !buf && n + 1 < cap;
	if (f != stdin)
		fclose(f);
	if (nomem) {
		snprintf(err, errlen, "%s: out of memory reading the scene", name);
		return SCENE_ENOMEM;
	}
	if (bad) {
		free(buf);
		snprintf(err, errlen, "%s: cannot read (I/O error, or larger than 64 MiB)", name);
		return -2;
	}
	buf[n] = 0;
	const char *nul = memchr(buf, 0, n);
	if (nul) {
		snprintf(err, errlen, "%s: byte %zu: expected text, found a NUL byte", name, (size_t)(nul - buf));
		free(buf);
		return -1;
	}
	*text = buf;
	return 0;
}

void scene_free(scene_t *s)
{
	if (!s)
		return;
	for (size_t i = 0; i < s->nobjs; i++)
		model_free(s->objs[i].shape);
	for (size_t i = 0; i < s->nrenders; i++) {
		for (size_t k = 0; k < s->renders[i].nnuclei; k++)
			free(s->renders[i].nuclei[k].pts);   /* polyline nuclei's points */
		free(s->renders[i].nuclei);
	}
	free(s->objs);
	free(s->renders);
	free(s);
}
