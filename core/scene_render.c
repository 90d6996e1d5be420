/* scene_render.c: render blocks of the scene language, and rendering a scene's pages to a meta writer. */
#include "scene_int.h"
#include "contour.h"
#include "mesh.h"
#include "oct.h"
#include "wire.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

typedef scene_tok_t tok_t;

static int yes_no(scene_lex_t *lx, int *v)
{
	tok_t t;
	scene_lex_tok(lx, &t);
	if (scene_tok_is(&t, "yes"))
		*v = 1;
	else if (scene_tok_is(&t, "no"))
		*v = 0;
	else
		return scene_lex_expected(lx, &t, "yes or no");
	return 0;
}

static int whole(scene_lex_t *lx, int *v, int lo, int hi, const char *what)
{
	double d;
	char msg[160];
	if (scene_lex_number(lx, &d, what) < 0)
		return -1;
	if (d < lo || d > hi || d != floor(d)) {
		snprintf(msg, sizeof msg, "expected %s: a whole number from %d to %d", what, lo, hi);
		return scene_lex_error(lx, lx->line, 1, msg);
	}
	*v = (int)d;
	return 0;
}

/* Points of one polyline nucleus at most (its work grows with them at every pixel). */
#define SCENE_MAX_POLY_POINTS 100000
#define SCENE_MAX_POLY_POINTS_S "100000"

static int polyline_points(scene_lex_t *lx, const tok_t *kw, voronoi_nucleus_t *n);
static int nucleus_options(scene_lex_t *lx, voronoi_nucleus_t *n);

/* One nucleus line of a voronoi block: point X Y, segment X1 Y1 X2 Y2 or polyline X Y X Y ...,
 * then its options. */
static int nucleus(scene_lex_t *lx, scene_render_t *r, const tok_t *kw)
{
	voronoi_nucleus_t n;
	memset(&n, 0, sizeof n);
	n.colour = SCENE_NO_COLOUR;
	n.weight = NAN;   /* not given: 0 (additive) or 1 (multiplicative), decided at rendering */
	n.kind = scene_tok_is(kw, "point") ? VORONOI_POINT : scene_tok_is(kw, "segment") ? VORONOI_SEGMENT : VORONOI_POLYLINE;
	if (n.kind == VORONOI_POLYLINE) {
		if (polyline_points(lx, kw, &n) < 0)
			return -1;
	} else if (scene_lex_numbers(lx, n.a, 2, "a nucleus coordinate (x y)") < 0)
		return -1;
	if (n.kind == VORONOI_SEGMENT && scene_lex_numbers(lx, n.b, 2, "the segment's second end (x y)") < 0)
		return -1;
	int rc = nucleus_options(lx, &n);
	if (rc == 0 && r->nnuclei == r->cap) {
		size_t cap = r->cap ? 2 * r->cap : 16;
		voronoi_nucleus_t *q = realloc(r->nuclei, cap * sizeof *q);
		if (!q)
			rc = scene_lex_error(lx, kw->line, kw->col, "out of memory");
		else {
			r->nuclei = q;
			r->cap = cap;
		}
	}
	if (rc < 0) {
		free(n.pts);
		return -1;
	}
	r->nuclei[r->nnuclei++] = n;
	return 0;
}

/* The x y pairs of a polyline nucleus, up to its first option word or the end of the line
 * (at least 2 points), into n->pts as x y 0 triples. */
static int polyline_points(scene_lex_t *lx, const tok_t *kw, voronoi_nucleus_t *n)
{
	static const char *const stop[] = {"weight", "z", "colour", "color", NULL};
	size_t k;
	double *p;
	if (scene_lex_points(lx, 2, stop, SCENE_MAX_POLY_POINTS,
	                     "expected at most " SCENE_MAX_POLY_POINTS_S " points in a polyline", &p, &k) < 0)
		return -1;
	if (k % 2 || k < 4) {
		free(p);
		return scene_lex_error(lx, kw->line, kw->col, k % 2 ? "expected x y pairs: a y coordinate is missing"
		                                                   : "expected at least 2 points (x y x y) in a polyline nucleus");
	}
	n->pts = p;
	n->npts = k / 2;
	n->a[0] = p[0], n->a[1] = p[1];
	return 0;
}

/* A nucleus line's options: weight, z (every point of it) and colour. */
static int nucleus_options(scene_lex_t *lx, voronoi_nucleus_t *n_)
{
	voronoi_nucleus_t n = *n_;
	tok_t t;
	while (scene_lex_tok(lx, &t)) {
		if (scene_tok_is(&t, "weight")) {
			if (scene_lex_number(lx, &n.weight, "a weight") < 0)
				return -1;
		} else if (scene_tok_is(&t, "z")) {
			/* a nucleus off the drawing plane z = 0 (a section of a 3D tessellation) */
			if (scene_lex_number(lx, &n.a[2], "a height z") < 0)
				return -1;
			n.b[2] = n.a[2];
			for (size_t i = 0; i < n.npts; i++)
				n.pts[3 * i + 2] = n.a[2];
		} else if (scene_tok_is(&t, "colour") || scene_tok_is(&t, "color")) {
			double c[3];
			if (scene_lex_numbers(lx, c, 3, "a colour component 0..1") < 0)
				return -1;
			n.colour = scene_rgb(c);
		} else
			return scene_lex_expected(lx, &t, "'weight', 'z', 'colour' or the end of the line");
	}
	*n_ = n;
	return 0;
}

int scene_parse_render(scene_lex_t *lx, scene_t *sc, const tok_t *kw)
{
	tok_t t;
	static const char *kinds[] = {"raytrace", "octree", "contour", "voronoi", "wireframe", "mesh"};
	scene_lex_tok(lx, &t);
	int kind = -1;
	for (int i = 0; i < 6; i++)
		if (scene_tok_is(&t, kinds[i]))
			kind = i;
	if (kind < 0)
		return scene_lex_expected(lx, &t, "raytrace, octree, contour, voronoi, wireframe or mesh");
	if (scene_lex_eol(lx) < 0)
		return -1;
	if (sc->nrenders == sc->rcap) {
		size_t cap = sc->rcap ? 2 * sc->rcap : 4;
		scene_render_t *q = realloc(sc->renders, cap * sizeof *q);
		if (!q)
			return scene_lex_error(lx, t.line, t.col, "out of memory");
		sc->renders = q;
		sc->rcap = cap;
	}
	scene_render_t *r = &sc->renders[sc->nrenders++];
	memset(r, 0, sizeof *r);
	r->kind = kind;
	r->line = kw->line;
	r->col = kw->col;
	r->accuracy = 1e-3;
	r->step = 0.5;
	r->threshold = 8;
	r->depth = 6;
	r->test = SCENE_SPHERICAL;
	r->shading = RT_GOURAUD;
	r->slices = 16;
	r->axis = 1;
	r->resolution = 96;
	r->line_width = 1;
	r->window[0] = r->window[1] = -3;
	r->window[2] = r->window[3] = 3;
	r->nlevels = 10;
	r->level_from = 1;
	r->level_to = 10;
	r->cells = r->boundaries = 1;
	r->draw = 1;
	r->hidden = 1;
	while (scene_lex_line(lx)) {
		scene_lex_tok(lx, &t);
		if (scene_tok_is(&t, "end"))
			return scene_lex_eol(lx);
		int rc = 0;
		if (scene_tok_is(&t, "accuracy")) {
			rc = scene_lex_number(lx, &r->accuracy, "an accuracy in pixels");
			if (!rc && !(r->accuracy >= 1e-6 && r->accuracy <= 1))
				rc = scene_lex_error(lx, t.line, t.col, "expected an accuracy from 1e-6 to 1 pixel");
		} else if (scene_tok_is(&t, "step")) {
			rc = scene_lex_number(lx, &r->step, "a fallback step in pixels");
			if (!rc && !(r->step >= 0.01 && r->step <= 100))
				rc = scene_lex_error(lx, t.line, t.col, "expected a step from 0.01 to 100 pixels");
		} else if (scene_tok_is(&t, "supersample")) {
			rc = whole(lx, &r->supersample, 0, 8, "supersample N");
		} else if (scene_tok_is(&t, "threshold")) {
			rc = scene_lex_number(lx, &r->threshold, "a colour difference 0..255");
		} else if (scene_tok_is(&t, "depth")) {
			rc = whole(lx, &r->depth, 1, 12, "an octree depth");
		} else if (scene_tok_is(&t, "test")) {
			scene_lex_tok(lx, &t);
			if (scene_tok_is(&t, "spherical"))
				r->test = SCENE_SPHERICAL;
			else if (scene_tok_is(&t, "cubical"))
				r->test = SCENE_CUBICAL;
			else if (scene_tok_is(&t, "both"))
				r->test = SCENE_BOTH_TESTS;
			else
				rc = scene_lex_expected(lx, &t, "spherical, cubical or both");
		} else if (scene_tok_is(&t, "shading")) {
			scene_lex_tok(lx, &t);
			if (scene_tok_is(&t, "constant"))
				r->shading = RT_CONSTANT;
			else if (scene_tok_is(&t, "gouraud"))
				r->shading = RT_GOURAUD;
			else
				rc = scene_lex_expected(lx, &t, "constant or gouraud");
		} else if (scene_tok_is(&t, "slices")) {
			rc = whole(lx, &r->slices, 1, 1000, "a number of slices");
		} else if (scene_tok_is(&t, "axis")) {
			scene_lex_tok(lx, &t);
			r->axis = scene_tok_is(&t, "x") ? 0 : scene_tok_is(&t, "y") ? 1 : scene_tok_is(&t, "z") ? 2 : -1;
			if (r->axis < 0)
				rc = scene_lex_expected(lx, &t, "x, y or z");
		} else if (scene_tok_is(&t, "resolution")) {
			rc = whole(lx, &r->resolution, 4, 4096, "a grid resolution");
		} else if (scene_tok_is(&t, "width")) {
			rc = scene_lex_number(lx, &r->line_width, "a line width in pixels");
			if (!rc && !(r->line_width > 0 && r->line_width <= 100))
				rc = scene_lex_error(lx, t.line, t.col, "expected a line width from 0 to 100 pixels");
		} else if (scene_tok_is(&t, "colour") || scene_tok_is(&t, "color")) {
			rc = scene_lex_numbers(lx, r->line_colour, 3, "a colour component 0..1");
		} else if (scene_tok_is(&t, "field")) {
			scene_lex_tok(lx, &t);
			if (!t.len || t.len >= sizeof r->field)
				rc = scene_lex_expected(lx, &t, "an object or shape name");
			else
				memcpy(r->field, t.s, t.len);
		} else if (scene_tok_is(&t, "window")) {
			rc = scene_lex_numbers(lx, r->window, 4, "window X0 Y0 X1 Y1");
			if (!rc && !(r->window[0] < r->window[2] && r->window[1] < r->window[3]))
				rc = scene_lex_error(lx, t.line, t.col, "expected window X0 Y0 X1 Y1 with X0 < X1 and Y0 < Y1");
		} else if (scene_tok_is(&t, "plane")) {
			rc = scene_lex_number(lx, &r->plane, "the z of the plane");
		} else if (scene_tok_is(&t, "on")) {
			rc = scene_lex_numbers(lx, r->on, 9, "on OX OY OZ UX UY UZ VX VY VZ (origin and the two axes of the plane)");
			double *u = r->on + 3, *v = r->on + 6;
			double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
			if (!rc && !(cx * cx + cy * cy + cz * cz > 1e-24))
				rc = scene_lex_error(lx, t.line, t.col, "expected two axes U and V that are not parallel (nor zero)");
			r->has_on = 1;
		} else if (scene_tok_is(&t, "levels")) {
			int n;
			rc = whole(lx, &n, 1, 1000, "a number of levels");
			if (!rc) {
				r->nlevels = (unsigned)n;
				tok_t a;
				scene_lex_tok(lx, &a);
				if (!scene_tok_is(&a, "from"))
					rc = scene_lex_expected(lx, &a, "'from'");
				else if (!(rc = scene_lex_number(lx, &r->level_from, "the first level"))) {
					scene_lex_tok(lx, &a);
					if (!scene_tok_is(&a, "to"))
						rc = scene_lex_expected(lx, &a, "'to'");
					else
						rc = scene_lex_number(lx, &r->level_to, "the last level");
				}
			}
		} else if (scene_tok_is(&t, "inset")) {
			int v[4];
			rc = whole(lx, &v[0], 0, 32767, "the inset's left pixel X");
			if (!rc)
				rc = whole(lx, &v[1], 0, 32767, "the inset's bottom pixel Y");
			if (!rc)
				rc = whole(lx, &v[2], 2, 32768, "the inset's width W (at least 2)");
			if (!rc)
				rc = whole(lx, &v[3], 2, 32768, "the inset's height H (at least 2)");
			if (!rc && kind != SCENE_CONTOUR && kind != SCENE_VORONOI)
				rc = scene_lex_error(lx, t.line, t.col, "expected 'inset' only in a contour or voronoi block");
			if (!rc && sc->nrenders < 2)
				rc = scene_lex_error(lx, t.line, t.col, "expected a render block before the one with an 'inset' (it draws on that page)");
			if (!rc) {
				r->has_inset = 1;
				for (int i = 0; i < 4; i++)
					r->inset[i] = (unsigned)v[i];
			}
		} else if (scene_tok_is(&t, "refine")) {
			rc = yes_no(lx, &r->refine);
		} else if (scene_tok_is(&t, "draw")) {
			rc = yes_no(lx, &r->draw);
		} else if (scene_tok_is(&t, "method") && kind == SCENE_MESH) {
			scene_lex_tok(lx, &t);
			if (scene_tok_is(&t, "cubes"))
				r->tetrahedra = 0;
			else if (scene_tok_is(&t, "tetrahedra"))
				r->tetrahedra = 1;
			else
				rc = scene_lex_expected(lx, &t, "cubes or tetrahedra");
		} else if (scene_tok_is(&t, "hidden") && kind == SCENE_MESH) {
			rc = yes_no(lx, &r->hidden);
		} else if (scene_tok_is(&t, "tolerance") && kind == SCENE_MESH) {
			rc = scene_lex_number(lx, &r->tolerance, "a distance to the surface");
			if (!rc && !(r->tolerance >= 0 && r->tolerance <= 1e6))
				rc = scene_lex_error(lx, t.line, t.col, "expected a tolerance of 0 (no coarsening) or a positive distance");
		} else if (scene_tok_is(&t, "adaptive") && kind == SCENE_MESH) {
			rc = scene_lex_number(lx, &r->adaptive, "a distance to the surface");
			if (!rc && !(r->adaptive >= 0 && r->adaptive <= 1e6))
				rc = scene_lex_error(lx, t.line, t.col, "expected an adaptive tolerance of 0 (uniform cells) or a positive distance");
			if (!rc && r->adaptive > 0 && r->depth > MESH_MAX_ADAPTIVE_DEPTH)
				rc = scene_lex_error(lx, t.line, t.col, "expected depth 9 or less for an adaptive mesh");
		} else if (scene_tok_is(&t, "bands")) {
			rc = yes_no(lx, &r->bands);
		} else if (scene_tok_is(&t, "metric")) {
			scene_lex_tok(lx, &t);
			if (scene_tok_is(&t, "additive"))
				r->metric = VORONOI_ADDITIVE;
			else if (scene_tok_is(&t, "multiplicative"))
				r->metric = VORONOI_MULTIPLICATIVE;
			else
				rc = scene_lex_expected(lx, &t, "additive or multiplicative");
		} else if (scene_tok_is(&t, "cells")) {
			rc = yes_no(lx, &r->cells);
		} else if (scene_tok_is(&t, "boundaries")) {
			rc = yes_no(lx, &r->boundaries);
		} else if (scene_tok_is(&t, "nuclei")) {
			rc = yes_no(lx, &r->nuclei_marks);
		} else if (scene_tok_is(&t, "point") || scene_tok_is(&t, "segment") || scene_tok_is(&t, "polyline")) {
			rc = nucleus(lx, r, &t);
		} else {
			rc = scene_lex_expected(lx, &t, "a render option or 'end'");
		}
		if (rc < 0 || scene_lex_eol(lx) < 0)
			return -1;
	}
	return scene_lex_expected(lx, &(tok_t){"", 0, lx->line, 1}, "'end' closing the render block");
}

/* ---- rendering ---- */

static int drawn_objects(const scene_t *s, rt_object_t *out)
{
	int n = 0;
	for (size_t i = 0; i < s->nobjs; i++)
		if (s->objs[i].drawn)
			out[n++] = s->objs[i].mat;
	return n;
}

static int write_failed(meta_writer_t *w, char *err, size_t errlen)
{
	snprintf(err, errlen, "%s", meta_writer_error(w));
	return -1;
}

/* The ray tracer's picture: mapped with transparent huge pages asked for, so that the first
 * write to its megabytes faults a few 2 MiB pages in instead of a 4 KiB page every 1024
 * pixels (on the development VM those faults were about a tenth of the trifocal's trace);
 * malloc when mapping fails. *mapped says which to free with image_free. */
static meta_rgb_t *image_alloc(size_t n, size_t *mapped)
{
	size_t bytes = n * sizeof(meta_rgb_t), huge = (size_t)2 << 20;
	*mapped = 0;
#ifdef MADV_HUGEPAGE
	if (bytes >= huge) {
		size_t len = (bytes + huge - 1) / huge * huge + huge;
		char *q = mmap(NULL, len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
		if (q != MAP_FAILED) {
			/* the picture starts on a 2 MiB boundary inside the mapping; the rest is unmapped */
			char *a = (char *)(((uintptr_t)q + huge - 1) / huge * huge), *end = q + len;
			size_t used = (bytes + huge - 1) / huge * huge;
			if (a > q)
				munmap(q, (size_t)(a - q));
			if (a + used < end)
				munmap(a + used, (size_t)(end - (a + used)));
			madvise(a, used, MADV_HUGEPAGE);
			*mapped = used;
			return (meta_rgb_t *)a;
		}
	}
#endif
	return malloc(bytes);
}

static void image_free(meta_rgb_t *img, size_t mapped)
{
	if (mapped)
		munmap(img, mapped);
	else
		free(img);
}

/* One view (an eye) of a 3D visualisation at page offset xoff. */
static int render_view(scene_t *s, const scene_render_t *r, const cam_t *cam, unsigned xoff,
                       meta_writer_t *w, const scene_opts_t *o, scene_stats_t *st, char *err, size_t errlen)
{
	rt_object_t *objs = malloc((s->nobjs + 1) * sizeof *objs);
	if (!objs) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	int nobj = drawn_objects(s, objs), rc = 0;
	double t0 = scene_now();
	if (r->kind == SCENE_RAYTRACE) {
		rt_params_t p;
		memset(&p, 0, sizeof p);
		p.cam = *cam;
		p.objects = objs;
		p.nobjects = (size_t)nobj;
		p.lights = s->lights;
		p.nlights = s->nlights;
		memcpy(p.background, s->background, sizeof p.background);
		p.accuracy = r->accuracy;
		p.step_pixels = r->step;
		p.supersample = r->supersample;
		p.refine = r->refine;
		p.aa_threshold = r->threshold;
		p.threads = o ? o->threads : 0;
		p.progress = o ? o->progress : NULL;
		p.progress_user = o ? o->progress_user : NULL;
		size_t n = (size_t)cam->nxpix * cam->nypix;
		size_t mapped;
		meta_rgb_t *img = image_alloc(n, &mapped);
		rt_stats_t rs;
		if (!img)
			rc = -1, snprintf(err, errlen, "out of memory for a %ux%u picture", cam->nxpix, cam->nypix);
		else if ((rc = rt_render(&p, img, &rs, err, errlen)) == 0) {
			st->seconds_trace += scene_now() - t0;
			st->pixels += (unsigned)n;
			st->rt.evals += rs.evals;
			st->rt.lane_evals += rs.lane_evals;
			st->rt.primary_evals += rs.primary_evals;
			st->rt.shadow_evals += rs.shadow_evals;
			st->rt.normal_evals += rs.normal_evals;
			st->rt.aa_evals += rs.aa_evals;
			st->rt.hits += rs.hits;
			st->rt.aa_pixels += rs.aa_pixels;
			if (rs.hits == 0 && nobj > 0)
				scene_add_warning(s, "no object is visible: the picture shows only the background");
			if (rt_write_image(w, img, cam->nxpix, cam->nypix, xoff, 0) < 0)
				rc = write_failed(w, err, errlen);
		}
		image_free(img, mapped);
	} else if (r->kind == SCENE_OCTREE) {
		oct_face_t *faces = NULL;
		size_t nf = 0, cap = 0;
		for (int i = 0; i < nobj && rc == 0; i++) {
			oct_leaf_t *leaves = NULL;
			size_t nl = 0;
			oct_stats_t os = {0, 0, 0};
			double tb = scene_now();
			rc = oct_build(objs[i].shape, r->depth, r->test == SCENE_CUBICAL ? OCT_CUBICAL : OCT_SPHERICAL,
			               r->draw ? &leaves : NULL, &nl, &os, err, errlen);
			st->seconds_trace += scene_now() - tb;   /* the conversion only, not the faces */
			st->oct_visited += os.visited;
			st->oct_leaves += os.leaves;
			st->oct_evals += os.evals;
			if (rc == 0 && r->test == SCENE_BOTH_TESTS) {
				/* the thesis' table 6.1: the same conversion with the cubical test */
				size_t n2 = 0;
				oct_stats_t o2 = {0, 0, 0};
				double tc = scene_now();
				rc = oct_build(objs[i].shape, r->depth, OCT_CUBICAL, NULL, &n2, &o2, err, errlen);
				st->seconds_cubical += scene_now() - tc;
				st->oct_cubical_visited += o2.visited;
				st->oct_cubical_leaves += o2.leaves;
			}
			if (rc == 0 && r->draw && oct_faces(cam, &objs[i], s->lights, s->nlights, leaves, nl, r->shading, &faces, &nf, &cap) < 0)
				rc = -1, snprintf(err, errlen, "out of memory for the octree faces");
			free(leaves);
		}
		if (rc == 0 && r->draw && nf == 0 && nobj > 0)
			scene_add_warning(s, "the octree has no leaves: the picture shows only the background");
		if (rc == 0 && oct_draw(w, faces, nf, xoff) < 0)
			rc = write_failed(w, err, errlen);
		free(faces);
	} else if (r->kind == SCENE_MESH) {
		rc = mesh_scene_draw(s, r, cam, w, xoff, &st->wire_segments, err, errlen);
		st->seconds_trace += scene_now() - t0;
	} else {
		meta_rgb_t c = scene_rgb(r->line_colour);
		for (int i = 0; i < nobj && rc == 0; i++)
			rc = wire_draw(w, cam, objs[i].shape, r->axis, r->slices, r->resolution, r->line_width,
			               c, xoff, &st->wire_segments, err, errlen);
		st->seconds_trace += scene_now() - t0;
	}
	free(objs);
	return rc;
}

/* Width of the pages of the 3D blocks (side-by-side stereo: both eyes). */
static unsigned page_width(const scene_t *s)
{
	return s->stereo == SCENE_STEREO_SIDE ? 2 * s->cam.nxpix : s->cam.nxpix;
}

/* One render block; its last page is left open when keep_open (an inset follows). */
static int render_block(scene_t *s, const scene_render_t *r, unsigned pw, unsigned ph, int keep_open,
                        meta_writer_t *w, const scene_opts_t *o, scene_stats_t *st, char *err, size_t errlen)
{
	const cam_t *cam = &s->cam;
	meta_rgb_t bg = scene_rgb(s->background);
	if (r->kind == SCENE_CONTOUR || r->kind == SCENE_VORONOI) {
		unsigned rect[4] = {0, 0, cam->nxpix, cam->nypix};
		if (r->has_inset) {
			memcpy(rect, r->inset, sizeof rect);
			if ((uint64_t)rect[0] + rect[2] > pw || (uint64_t)rect[1] + rect[3] > ph) {
				snprintf(err, errlen, "%s:%u:%u: expected an inset inside the %ux%u page, not %u %u %u %u",
				         s->name, r->line, r->col, pw, ph, rect[0], rect[1], rect[2], rect[3]);
				return -1;
			}
		} else if (meta_page(w, cam->nxpix, cam->nypix) < 0 || meta_clear(w, bg) < 0) {
			return write_failed(w, err, errlen);
		}
		if (scene_render_2d(s, r, w, o, rect, st, err, errlen) < 0)
			return -1;
		return keep_open || meta_end_page(w) >= 0 ? 0 : write_failed(w, err, errlen);
	}
	int views = s->stereo == SCENE_MONO ? 1 : 2;
	for (int v = 0; v < views; v++) {
		cam_t c = *cam;
		if (views == 2) {
			char e[200];
			c = cam_shifted(cam, (v == 0 ? -0.5 : 0.5) * s->eye_separation);
			if (cam_setup(&c, e, sizeof e) < 0) {
				snprintf(err, errlen, "%s: stereo eye: %s", s->name, e);
				return -1;
			}
		}
		int side = s->stereo == SCENE_STEREO_SIDE;
		if (v == 0 || !side) {
			if (meta_page(w, side ? 2 * cam->nxpix : cam->nxpix, cam->nypix) < 0)
				return write_failed(w, err, errlen);
			if (r->kind != SCENE_RAYTRACE && meta_clear(w, bg) < 0)
				return write_failed(w, err, errlen);
		}
		if (render_view(s, r, &c, side ? v * cam->nxpix : 0, w, o, st, err, errlen) < 0)
			return -1;
		if ((v == views - 1 || !side) && !(keep_open && v == views - 1) && meta_end_page(w) < 0)
			return write_failed(w, err, errlen);
	}
	return 0;
}

/* A failed block: its message gains the block's place (FILE:LINE:COL: of its `render` line) unless
 * it names one already; SCENE_ENOMEM when it was an allocation. */
static int block_failed(const scene_t *s, const scene_render_t *r, char *err, size_t errlen)
{
	size_t n = strlen(s->name);
	if (r->line && !(strncmp(err, s->name, n) == 0 && err[n] == ':')) {
		char msg[1024];
		snprintf(msg, sizeof msg, "%s:%u:%u: %s", s->name, r->line, r->col, err);
		snprintf(err, errlen, "%s", msg);
	}
	return strstr(err, "out of memory") ? SCENE_ENOMEM : -1;
}

int scene_render(scene_t *s, meta_writer_t *w, const scene_opts_t *o, scene_stats_t *st,
                 char *err, size_t errlen)
{
	scene_stats_t local;
	if (!st)
		st = &local;
	memset(st, 0, sizeof *st);
	if (s->nrenders == 0) {
		scene_render_t r;
		memset(&r, 0, sizeof r);
		r.kind = SCENE_RAYTRACE;
		r.accuracy = 1e-3;
		r.step = 0.5;
		r.threshold = 8;
		if (render_block(s, &r, 0, 0, 0, w, o, st, err, errlen) < 0)
			return block_failed(s, &r, err, errlen);
		return 0;
	}
	unsigned pw = 0, ph = 0;     /* size of the page drawn last */
	for (size_t i = 0; i < s->nrenders; i++) {
		const scene_render_t *r = &s->renders[i];
		int keep_open = i + 1 < s->nrenders && s->renders[i + 1].has_inset;
		if (render_block(s, r, pw, ph, keep_open, w, o, st, err, errlen) < 0)
			return block_failed(s, r, err, errlen);
		if (!r->has_inset) {
			int flat = r->kind == SCENE_CONTOUR || r->kind == SCENE_VORONOI;
			pw = flat ? s->cam.nxpix : page_width(s);
			ph = s->cam.nypix;
		}
	}
	return 0;
}
