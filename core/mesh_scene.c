/* mesh_scene.c: the meshes of a scene's drawn objects, for `render mesh` pages and locus-render's STL/PLY/OBJ output. */
#include "mesh.h"
#include "scene_int.h"

#include <stdio.h>
#include <string.h>

/* Polygonise the drawn objects at the block's depth (coarsened within its tolerance);
 * -1/SCENE_ENOMEM with "FILE:L:C: ..." */
static int extract(const scene_t *s, const scene_render_t *r, mesh_t *m, mesh_stats_t *st,
                   char *err, size_t errlen)
{
	int depth = r ? r->depth : 6, any = 0;
	char e[400];
	m->tetrahedra = r && r->tetrahedra;
	for (size_t i = 0; i < s->nobjs; i++) {
		const scene_obj_t *o = &s->objs[i];
		if (!o->drawn)
			continue;
		any = 1;
		size_t v0 = m->nv, t0 = m->nt;
		int rc = r && r->adaptive > 0 ? mesh_extract_adaptive(o->shape, depth, r->adaptive, m, st, e, sizeof e)
		                               : mesh_extract(o->shape, depth, m, st, e, sizeof e);
		if (rc == 0 && r && r->tolerance > 0)
			rc = mesh_simplify(m, o->shape, v0, t0, r->tolerance, st ? &st->evals : NULL, e, sizeof e);
		if (rc < 0) {
			unsigned line = r && !strstr(e, "Lipschitz") ? r->line : o->line;
			unsigned col = r && !strstr(e, "Lipschitz") ? r->col : o->col;
			snprintf(err, errlen, "%.200s:%u:%u: %s (object '%s')", s->name, line, col, e, o->name);
			return strstr(e, "out of memory") ? SCENE_ENOMEM : -1;
		}
	}
	if (m->nt == 0) {
		snprintf(err, errlen, "%.200s:%u:%u: the mesh is empty: %s", s->name, r ? r->line : 1, r ? r->col : 1,
		         any ? "no drawn object has a surface inside its bound (check c against the distances)"
		             : "the scene draws no object (define one with 'object NAME ... end')");
		return -1;
	}
	return 0;
}

int mesh_scene(const scene_t *s, mesh_t *m, mesh_stats_t *st, const scene_render_t **block,
               char *err, size_t errlen)
{
	const scene_render_t *r = NULL;
	for (size_t i = 0; i < s->nrenders && !r; i++)
		if (s->renders[i].kind == SCENE_MESH)
			r = &s->renders[i];
	if (block)
		*block = r;
	return extract(s, r, m, st, err, errlen);
}

int mesh_scene_draw(scene_t *s, const scene_render_t *r, const cam_t *cam, meta_writer_t *w,
                    double xoff, uint64_t *segments, char *err, size_t errlen)
{
	mesh_t m;
	mesh_init(&m);
	int rc = extract(s, r, &m, NULL, err, errlen);
	if (rc == 0)
		rc = mesh_draw(w, cam, &m, r->hidden, r->line_width, scene_rgb(r->line_colour), xoff, segments, err, errlen);
	mesh_free(&m);
	return rc;
}
