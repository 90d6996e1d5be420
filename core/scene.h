/* scene.h: the Locus scene language (docs/scene-language.md): parsed scenes and how they are rendered to meta files. */
#ifndef LOCUS_SCENE_H
#define LOCUS_SCENE_H

#include <stddef.h>
#include <stdint.h>
#include "camera.h"
#include "locus_meta.h"
#include "model.h"
#include "rt.h"
#include "voronoi.h"

#define SCENE_MAX_LIGHTS 16
#define SCENE_MAX_WARNINGS 16

/* Visualisations. */
enum { SCENE_RAYTRACE, SCENE_OCTREE, SCENE_CONTOUR, SCENE_VORONOI, SCENE_WIREFRAME, SCENE_MESH };
/* Stereo layouts. */
enum { SCENE_MONO, SCENE_STEREO_PAGES, SCENE_STEREO_SIDE };
/* Octree cell tests. */
enum { SCENE_SPHERICAL, SCENE_CUBICAL, SCENE_BOTH_TESTS };

/* A named shape; drawn when it came from an `object` block. */
typedef struct {
	char name[64];
	model_shape_t *shape;
	int drawn;
	rt_object_t mat;           /* material; mat.shape == shape */
	unsigned line, col;        /* where it was defined */
	int empty;                 /* model_prepare proved the surface empty (warned where it is drawn in 3D) */
	unsigned c_line;           /* the line of its `c` (0: none yet): a second one is refused */
	int through;               /* `c through X Y Z`: c set at `end` so that f(through_p) = 0 */
	double through_p[3];       /* that point, ACTUAL frame */
} scene_obj_t;

/* One `render` block: a page (two for stereo pages) of one visualisation. */
typedef struct {
	int kind;
	/* raytrace */
	double accuracy, step;
	int supersample;
	int refine;                /* raytrace: double-precision polish of hits (reference renders) */
	double threshold;
	/* octree */
	int depth, test, shading;  /* shading: RT_CONSTANT or RT_GOURAUD */
	int draw;                  /* octree: 0 = count cells only, draw nothing */
	/* wireframe */
	int slices, axis, resolution;
	int hidden;                /* mesh: draw only the edges of faces turned to the eye (core/mesh.h) */
	double tolerance;          /* mesh: coarsen within this distance of the surface (0: off) */
	double adaptive;           /* mesh: adaptive extraction, cells flat within this distance (0: uniform) */
	int tetrahedra;            /* mesh: `method tetrahedra` (marching tetrahedra) instead of cubes */
	double line_width;
	double line_colour[3];
	/* contour */
	char field[64];            /* object whose f is mapped ("" = the first object) */
	double window[4];          /* x0 y0 x1 y1 of the plane region (contour, voronoi) */
	double plane;              /* the plane z = plane */
	int has_on;                /* contour: `on`: the map plane is on[0..2] + s on[3..5] + t on[6..8] */
	double on[9];
	unsigned nlevels;
	double level_from, level_to;
	int bands;
	/* voronoi */
	voronoi_nucleus_t *nuclei;
	size_t nnuclei, cap;
	int metric, cells, boundaries;
	int nuclei_marks;          /* voronoi: draw the nuclei (discs, strokes) */
	/* contour, voronoi: drawn into the rectangle x y w h of the previous page */
	int has_inset;
	unsigned inset[4];
	unsigned line, col;
} scene_render_t;

/* A parsed scene. */
typedef struct {
	char name[256];            /* file name used in messages */
	double t;                  /* the time parameter it was parsed at (scene_parse_frame) */
	cam_t cam;
	int stereo;                /* SCENE_MONO or a stereo layout */
	double eye_separation;
	double background[3];
	rt_light_t lights[SCENE_MAX_LIGHTS];
	size_t nlights;
	scene_obj_t *objs;
	size_t nobjs, cap;
	scene_render_t *renders;
	size_t nrenders, rcap;
	const char *warnings[SCENE_MAX_WARNINGS]; /* static texts or owned strings in warnbuf */
	char warnbuf[SCENE_MAX_WARNINGS][512];
	size_t nwarnings;
} scene_t;

/* Returned (instead of -1) when the failure was an allocation: every such message of core/
 * says "out of memory", and the programs exit 70 for it rather than 65. */
#define SCENE_ENOMEM (-3)

/* Parse scene text (NUL-terminated); name is used in messages. Returns 0
 * with *out, or -1 with "name:line:col: expected ..." in err (SCENE_ENOMEM). */
int scene_parse(const char *text, const char *name, scene_t **out, char *err, size_t errlen);

/* The same with the time parameter `t` set to t: every number token that uses t (no blanks,
 * e.g. 2+0.5*t) and every c expression that does is evaluated with this value. scene_parse is
 * scene_parse_frame at t = 0. */
int scene_parse_frame(const char *text, const char *name, double t, scene_t **out, char *err, size_t errlen);

/* Read a scene file ("-" = stdin) into *text (NUL-terminated, malloc'd; free it). Returns 0,
 * -1 (not text: a NUL byte), -2 (cannot be read) or SCENE_ENOMEM (memory ran out, the open's
 * included), with a message. */
int scene_read(const char *path, char **text, char *err, size_t errlen);

/* Read and parse a file ("-" = stdin). Returns 0, -1 (syntax: err holds the
 * message), -2 (the file cannot be read) or SCENE_ENOMEM. */
int scene_load(const char *path, scene_t **out, char *err, size_t errlen);

/* Free a scene. */
void scene_free(scene_t *s);

/* What rendering cost, summed over the render blocks. */
typedef struct {
	rt_stats_t rt;
	uint64_t oct_visited, oct_leaves, oct_evals;
	uint64_t oct_cubical_visited, oct_cubical_leaves; /* `test both`: the cubical run */
	double seconds_cubical;    /* `test both`: its conversion time */
	uint64_t wire_segments, contour_segments;
	double seconds_trace;      /* time in the visualisation kernels (not writing) */
	unsigned pixels;
} scene_stats_t;

/* Options of one rendering run. */
typedef struct {
	unsigned threads;          /* 0: all CPUs */
	rt_progress_fn progress;
	void *progress_user;
} scene_opts_t;

/* Render every render block (none: one ray-traced page) to w. Returns 0 or
 * -1 (SCENE_ENOMEM) with a message. Warnings (e.g. an empty picture) are added to s. */
int scene_render(scene_t *s, meta_writer_t *w, const scene_opts_t *o, scene_stats_t *st,
                 char *err, size_t errlen);

#endif
