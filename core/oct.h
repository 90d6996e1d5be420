/* oct.h: implicit-to-octree conversion (thesis chapter 6) and painter's-algorithm drawing of the leaves.
 *
 * The root cube is the shape's `bound` box as given (else its clip box) made cubical. A cell of side a and
 * centre p is kept (subdivided, or a leaf at the final depth) when the
 * surface may cross it:
 *   spherical test  |f(p)| <= L * (sqrt(3)/2) * a   (the cell's circumscribed
 *                   sphere; one evaluation per cell)
 *   cubical test    0 lies in an interval enclosure of f over the cell: for
 *                   point elements the exact range of |P - A| over the cube,
 *                   for the other elements their Lipschitz enclosure
 *                   d(p) +- (sqrt(3)/2) a ||M^-1||; the defining parameter's
 *                   value over the cell is predicted (thesis section 6.4) by
 *                   interval arithmetic for expressions (expr_bound), exactly
 *                   for constants, and by c(p) +- G_c (sqrt(3)/2) a otherwise.
 *                   Tighter than the spherical test whenever points are
 *                   involved. Shapes of points with a constant c in a
 *                   translated frame take a float fast path (8 children at
 *                   once) with a small rounding margin.
 * A distance-estimated shape (s->de: an elementless smooth Mandelbrot or Julia process) has no
 * Lipschitz bound, but its estimate d(p) never exceeds the distance from p to the surface: with
 * either test a cell is kept unless |d| at its centre exceeds its half-diagonal (a centre whose
 * iteration never escaped has no bound and keeps its cell).
 * Without a Lipschitz bound or an estimate neither test is safe and oct_build refuses.
 * The root cell counts as visited; every cell tested counts as visited.
 */
#ifndef LOCUS_OCT_H
#define LOCUS_OCT_H

#include <stddef.h>
#include <stdint.h>
#include "camera.h"
#include "locus_meta.h"
#include "model.h"
#include "rt.h"

enum { OCT_SPHERICAL, OCT_CUBICAL };

/* A leaf cell: centre and half side. */
typedef struct {
	float c[3];
	float h;
} oct_leaf_t;

typedef struct {
	uint64_t visited, leaves, evals;
} oct_stats_t;

/* The most leaves oct_build keeps for drawing: with their faces about 300 MB. Drawing a
 * deeper conversion is refused with a message; counting (leaves == NULL) has no limit. */
#define OCT_MAX_LEAVES ((size_t)1 << 21)

/* Subdivide s to depth (1..12) with the given test; *leaves (malloc'd, the
 * caller frees) receives the leaves, or, with leaves NULL, they are only counted (memory
 * then does not grow with the depth). Returns 0 or -1 with a message. */
int oct_build(const model_shape_t *s, int depth, int test, oct_leaf_t **leaves, size_t *n,
              oct_stats_t *st, char *err, size_t errlen);

/* A projected face to paint. */
typedef struct {
	float x[4], y[4];
	float depth;
	meta_rgb_t rgb;
} oct_face_t;

/* Append the visible faces of the leaves (the three faces turned towards the
 * eye, minus those shared with another leaf, which can never show), shaded with
 * `shading`: RT_CONSTANT lights each face by its own normal (flat facets),
 * RT_GOURAUD by the surface normal grad f at the cell centre (smooth look).
 * *faces grows with realloc. Returns 0 or -1 (out of memory). */
int oct_faces(const cam_t *cam, const rt_object_t *mat, const rt_light_t *lights, size_t nlights,
              const oct_leaf_t *leaves, size_t n, int shading,
              oct_face_t **faces, size_t *nfaces, size_t *cap);

/* Sort faces far to near and paint them as filled quadrilaterals, shifted by
 * xoff pixels. Returns 0 or a meta error code. */
int oct_draw(meta_writer_t *w, oct_face_t *faces, size_t n, double xoff);

#endif
