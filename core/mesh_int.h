/* mesh_int.h: internals shared by mesh.c and mesh_simplify.c (not part of the public API). */
#ifndef LOCUS_MESH_INT_H
#define LOCUS_MESH_INT_H

#include "model.h"

/* F(P) = max(f(P), L * b(P)): the shape clipped by its box (mesh.h); NaN counts as outside. */
double mesh_field(const model_shape_t *s, const double p[3]);
/* The gradient of F at p: the shape's where f is the larger term, else the box's. */
void mesh_field_grad(const model_shape_t *s, const double p[3], double g[3]);

#endif
