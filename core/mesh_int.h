/* mesh_int.h: internals shared by the mesh extractions (mesh.c, mesh_adapt.c, mesh_solid.c) and mesh_simplify.c (not part of the public API). */
#ifndef LOCUS_MESH_INT_H
#define LOCUS_MESH_INT_H

#include "mesh.h"
#include "model.h"

/* F(P) = max(f(P), L * b(P)): the shape clipped by its box (mesh.h); NaN counts as outside. */
double mesh_field(const model_shape_t *s, const double p[3]);
/* The gradient of F at p: the shape's where f is the larger term, else the box's. */
void mesh_field_grad(const model_shape_t *s, const double p[3], double g[3]);

/* Append the triangle a b c of m's vertices. 0, -1 out of memory, -2 over MESH_MAX_TRIANGLES. */
int mesh_triangle(mesh_t *m, uint32_t a, uint32_t b, uint32_t c);

/* Marching tetrahedra: append the surface triangle (ni or no is 1) or the two (ni = no = 2) of
 * a tetrahedron whose corners at positions cp[] are inside (ins[0..ni-1]) or outside
 * (outs[0..no-1]); v[] are the vertices of its crossed edges, inside corner i to outside corner
 * j in that order. Wound with the normal from the inside corners towards the outside ones; a quad
 * is split along its shorter diagonal. As mesh_triangle (the worse result of the two). */
int mesh_tet_surface(mesh_t *m, const double (*cp)[3], const int *ins, int ni, const int *outs, int no,
                     const uint32_t *v);

/* Append the tetrahedron a b c d of m's vertices, positively oriented (two corners swapped when
 * its volume is negative). 0, -1 out of memory, -2 over MESH_MAX_TETS. */
int mesh_tet(mesh_t *m, uint32_t a, uint32_t b, uint32_t c, uint32_t d);
/* Append the prism p (bottom p0 p1 p2, top p3 p4 p5, pi+3 above pi) as three tetrahedra, its
 * quadrilateral faces cut from their smallest vertex index (so neighbours agree). As mesh_tet. */
int mesh_prism(mesh_t *m, const uint32_t p[6]);
/* Append the inside part of a Kuhn tetrahedron with nin (1..3) inside corners in[] and the
 * crossing vertices e[] of its crossed edges (inside corner i to outside j, in that order, as
 * the marching tetrahedra visit them). As mesh_tet. */
int mesh_cut_tet(mesh_t *m, int nin, const uint32_t *in, const uint32_t e[4]);

/* A hash table from 64-bit keys to 64-bit values (open addressing); zeroed is empty. */
typedef struct {
	uint64_t key, val;       /* key 0 is free: stored keys are offset by one */
} mesh_entry_t;
typedef struct {
	mesh_entry_t *e;
	size_t n, cap;
} mesh_table_t;
void mesh_table_free(mesh_table_t *t);
/* Find key k: 1 with *val, or 0 and *at (the slot to fill with mesh_table_put). -1: out of memory. */
int mesh_table_get(mesh_table_t *t, uint64_t k, uint64_t *val, size_t *at);
void mesh_table_put(mesh_table_t *t, size_t at, uint64_t k, uint64_t val);

/* Room for one more vertex of m: its index (m->nv, not yet counted), or -1 out of memory. */
long mesh_vertex_slot(mesh_t *m);
/* The vertex of m stored under key k in t, made once: its index, or -1 out of memory. When it
 * is made now, *p points at its three coordinates for the caller to write; else *p is NULL. */
long mesh_vertex_at(mesh_t *m, mesh_table_t *t, uint64_t k, double **p);

/* 0 when shape s can be meshed (it has a Lipschitz bound or a distance estimate), else -1 with
 * the message in err. */
int mesh_can_extract(const model_shape_t *s, char *err, size_t errlen);
/* The cube the extractions grid: centred on s's root box, its side the box's largest (returned);
 * lo gets its lower corner. */
double mesh_root_cube(const model_shape_t *s, double lo[3]);
/* An extraction's result: -1 with the message when it ran out of memory (oom), made too many
 * triangles or too many vertices for 32-bit indices since it started at nv0 vertices; else 0. */
int mesh_extract_end(const mesh_t *m, size_t nv0, int oom, int too_many, char *err, size_t errlen);

/* Refine the surface vertex on the segment a (F = fa < 0) to b (F = fb >= 0) into p, as the
 * extraction does (bracketed with the bound lip; evaluations and max_bracket into *st). */
void mesh_refine_edge(const model_shape_t *s, double lip, mesh_stats_t *st, const double a[3], const double b[3],
                      double fa, double fb, double p[3]);

/* Marching tetrahedra on the octree (mesh.c), the surface and with m->want_solid the solid:
 * mesh_extract's other method, called by it (mesh_mc.c) after its checks; st not NULL. */
int mesh_extract_tetra(const model_shape_t *s, int depth, mesh_t *m, mesh_stats_t *st, char *err, size_t errlen);
/* Marching cubes on the finest cells (mesh_mc.c): mesh_extract's surface without a solid. */
int mesh_extract_cubes(const model_shape_t *s, int depth, mesh_t *m, mesh_stats_t *st, char *err, size_t errlen);

#endif
