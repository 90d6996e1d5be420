/* mesh.h: polygonisation of a shape into a closed, consistently oriented triangle mesh (thesis section 7.5), and its export.
 *
 * Method: marching cubes (mesh_mc.c; marching tetrahedra with mesh_t.tetrahedra set, and for
 * the solid) over the finest cells of an octree (docs/mesh.md).
 *   - The root cube is the shape's octree root (its `bound` box as given,
 *     else its clip box) made cubical, and is cut into 2^depth cells a side.
 *   - The solid is F(P) = max(f(P), L * b(P)) < 0, with f the shape, L its
 *     Lipschitz bound and b the signed distance to the clip box (negative
 *     inside): the shape clipped by its box, so that the mesh closes on the
 *     box faces instead of leaving a hole. F is L-Lipschitz as well.
 *   - The octree descends only into cells whose circumscribed sphere may hold
 *     a zero of F (|F(centre)| <= L * sqrt(3)/2 * side): a cell whose corners
 *     differ in sign always passes, so every crossing is found, and the work
 *     grows with the area of the surface, not the volume of the box.
 *   - Marching cubes: F once per grid corner, the cells slab by slab; the cases from a table
 *     made from a face rule (an ambiguous face cuts off its inside corners), so the cells that
 *     share a face draw the same segments on it and every loop closes.
 *   - Marching tetrahedra: each finest cell is split into the 6 tetrahedra of its Kuhn
 *     (Freudenthal) triangulation, which matches across the faces of
 *     neighbouring cells; a corner is inside when F < 0. Each tetrahedron
 *     with corners of both signs gives one triangle (one corner apart) or two
 *     (two and two, split along the shorter diagonal). A vertex belongs to a
 *     grid edge and is shared by every tetrahedron around it, so the surface
 *     is closed; triangles are wound counter-clockwise seen from outside
 *     (normals point out of the solid), decided on the midpoints of the
 *     crossed edges (never degenerate), never on the refined vertices, so the
 *     order is consistent.
 *   - A vertex is refined onto the surface along its edge: the zero lies in
 *     the bracket between the inside and the outside end, and the Lipschitz
 *     bound narrows it from both ends without evaluating (no zero within
 *     |F(end)| / L of an end); secant steps inside the narrowed bracket, with
 *     bisection as the fallback, until it is below 1e-7 of the edge. The
 *     bracket's width is a proven bound on the vertex's distance to the
 *     surface (stats.max_bracket). A vertex is kept at least 1e-4 of its edge
 *     away from a grid corner, so that no two vertices coincide, even in the
 *     single precision of STL.
 * Coordinates are the shape's actual (model) frame, whatever the view.
 */
#ifndef LOCUS_MESH_H
#define LOCUS_MESH_H

#include <stddef.h>
#include <stdint.h>
#include "camera.h"
#include "locus_meta.h"
#include "model.h"
#include "scene.h"

/* Finest octree depth accepted: 2^10 cells a side. */
#define MESH_MAX_DEPTH 10
/* Most triangles one mesh may hold (about 1.2 GB with its vertices). */
#define MESH_MAX_TRIANGLES ((size_t)1 << 26)

/* Most tetrahedra one solid may hold (about 1 GB with its faces checked). */
#define MESH_MAX_TETS ((size_t)1 << 26)

/* A triangle mesh: nv vertices (3 doubles each), nt triangles (3 vertex indices each). With
 * want_solid set before mesh_extract, also the solid as ntet tetrahedra (4 vertex indices each,
 * positively oriented), over the same vertices and the grid corners inside (docs/mesh.md). */
typedef struct {
	double *v;
	size_t nv, vcap;
	uint32_t *t;
	size_t nt, tcap;
	int want_solid;
	int tetrahedra;          /* surface by marching tetrahedra (as the solid's) instead of cubes */
	uint32_t *tet;
	size_t ntet, tetcap;
} mesh_t;

/* Result of mesh_solid_check. */
typedef struct {
	double volume;           /* sum of the tetrahedra's signed volumes */
	size_t negative, flat;   /* tetrahedra of negative or zero volume */
	size_t inner_faces;      /* faces shared by exactly two tetrahedra */
	size_t boundary_faces;   /* faces of one tetrahedron (the solid's surface) */
	size_t overused_faces;   /* faces of three or more (never in a valid mesh) */
} mesh_solid_check_t;

/* What an extraction cost. */
typedef struct {
	uint64_t cells;          /* octree cells tested */
	uint64_t leaves;         /* finest cells that passed the test */
	uint64_t evals;          /* evaluations of F */
	double max_bracket;      /* largest proven vertex-to-surface bound, model units */
} mesh_stats_t;

/* Result of mesh_check: the properties admesh reports, on the indexed mesh. */
typedef struct {
	size_t edges;            /* distinct undirected edges */
	size_t open_edges;       /* edges used by only one triangle */
	size_t bad_edges;        /* edges used twice the same way (wrong orientation) or by more than two */
	size_t degenerate;       /* triangles with a repeated vertex */
} mesh_check_t;

/* An empty mesh. */
void mesh_init(mesh_t *m);
/* Free the arrays of m (not m itself) and empty it. */
void mesh_free(mesh_t *m);

/* Polygonise s at the given depth (1..MESH_MAX_DEPTH) as described above, APPENDING its
 * triangles to m (several shapes make one mesh). st (may be NULL) receives the costs, added
 * to what it holds. A distance-estimated shape (s->de: a smooth Mandelbrot or Julia process)
 * is extracted on its estimate, which bounds the distance to the surface as a Lipschitz bound
 * of 1 would (cells culled and brackets narrowed by it). Returns 0, or -1 with a message: no
 * Lipschitz bound or estimate, depth out of range, too many triangles, out of memory (the
 * message then says "out of memory"). */
int mesh_extract(const model_shape_t *s, int depth, mesh_t *m, mesh_stats_t *st, char *err, size_t errlen);

/* Finest depth of an adaptive extraction: 2^9 cells a side. */
#define MESH_MAX_ADAPTIVE_DEPTH 9

/* Polygonise s adaptively (docs/mesh.md), APPENDING to m as mesh_extract does: the octree
 * splits a cell that may hold the surface until F is flat in it within tol (the linear
 * function through its centre predicts F at its corners, and its second differences stay,
 * within tol of distance) or it is at the finest depth (1..MESH_MAX_ADAPTIVE_DEPTH), from
 * depth - 5 on. A leaf whose faces all meet leaves of its size is cut into its 6 Kuhn
 * tetrahedra; another into cones from its centre over its faces, each face cut into the
 * pieces the cells across it make, each piece fanned from its centre through every leaf
 * corner on its edges: tetrahedra that meet face to face, so the mesh is closed (no crack
 * where cell sizes change). Returns 0, or -1 with a message as mesh_extract. */
int mesh_extract_adaptive(const model_shape_t *s, int depth, double tol, mesh_t *m, mesh_stats_t *st,
                          char *err, size_t errlen);

/* Coarsen the part of m from vertex v0 and triangle t0 on (one closed mesh of s, as
 * mesh_extract appended it) where the surface allows: edges are collapsed shortest first into
 * their midpoint moved onto the surface (two Newton steps along grad F), each collapse only
 * when it keeps the mesh closed and manifold (the link condition: the two ends share no
 * neighbour but the two opposite vertices), turns no triangle by more than 60 degrees (no
 * fold, the winding stays right) and leaves the centre of every moved triangle within tol of
 * the surface (first order: |F| / |grad F|). Flat parts coarsen, curved ones keep their
 * triangles: the mesh becomes adaptive, and the slivers of marching tetrahedra (the shortest
 * edges) go first. Up to 4 passes, until one collapses under 5% of the vertices. Adds the
 * evaluations of F to *evals (a gradient counts as one). Returns 0, or -1 when out of memory
 * (the mesh is then unusable) or for a distance-estimated shape (its estimate does not bound
 * the distance from above, so the tolerance could not be kept). */
int mesh_simplify(mesh_t *m, const model_shape_t *s, size_t v0, size_t t0, double tol,
                  uint64_t *evals, char *err, size_t errlen);

/* Surface area and enclosed volume (divergence theorem; positive for outward normals). */
void mesh_measure(const mesh_t *m, double *area, double *volume);

/* Count open, wrongly oriented and non-manifold edges and degenerate triangles.
 * Returns 0, or -1 when out of memory. */
int mesh_check(const mesh_t *m, mesh_check_t *out);

/* Volume, orientation and face sharing of m's tetrahedra. Returns 0, or -1 when out of memory. */
int mesh_solid_check(const mesh_t *m, mesh_solid_check_t *out);

/* Output formats, chosen by the file name's suffix. */
enum { MESH_STL, MESH_PLY, MESH_OBJ, MESH_MSH };

/* MESH_STL, MESH_PLY, MESH_OBJ or MESH_MSH (the solid's tetrahedra, Gmsh MSH 2.2 ASCII) for a
 * name ending in .stl, .ply, .obj or .msh (any case), else -1 (the name is a meta file). */
int mesh_format_of(const char *name);

/* Writes n bytes; returns <0 on failure. */
typedef int (*mesh_write_fn)(void *user, const void *buf, size_t n);

/* Write m as binary STL (float vertices, one normal per facet), binary little-endian PLY
 * (float x y z, int vertex lists) or Wavefront OBJ (v and f lines) through wr; all three hold
 * the same single-precision vertices (OBJ prints each float exactly, in 9 digits). MESH_MSH
 * writes the solid (m->ntet > 0) as Gmsh MSH 2.2 ASCII: $Nodes (all vertices, 1-based,
 * 17 digits), $Elements (type 4, tags 1 1, positively oriented). `name` goes into the STL
 * header and the comments. Returns 0, or -1 with a message. */
int mesh_write(const mesh_t *m, int format, const char *name, mesh_write_fn wr, void *user,
               char *err, size_t errlen);

/* Draw m as a wireframe through cam, shifted by xoff pixels: every edge once as a stroke;
 * with `hidden` set, only the edges of triangles facing the eye (back faces culled).
 * Adds the drawn segments to *segments. Returns 0, or -1 with a message (write error). */
int mesh_draw(meta_writer_t *w, const cam_t *cam, const mesh_t *m, int hidden, double width,
              meta_rgb_t colour, double xoff, uint64_t *segments, char *err, size_t errlen);

/* The mesh of a scene: every drawn object polygonised at the depth of the scene's first
 * `render mesh` block (6 without one), appended into m; *block receives that block (NULL:
 * none). Returns 0, -1 with "FILE:LINE:COL: ..." (the object or block at fault; the whole
 * mesh empty is an error too) or SCENE_ENOMEM. */
int mesh_scene(const scene_t *s, mesh_t *m, mesh_stats_t *st, const scene_render_t **block,
               char *err, size_t errlen);

/* A `render mesh` block drawn as a wireframe page through cam (scene_render's part).
 * Returns 0 or -1 with a message. */
int mesh_scene_draw(scene_t *s, const scene_render_t *r, const cam_t *cam, meta_writer_t *w,
                    double xoff, uint64_t *segments, char *err, size_t errlen);

#endif
