/* mesh_solid.c: the solid as tetrahedra (thesis section 7.5): cut Kuhn tetrahedra split conformingly, and the volume mesh's checks. */
#include "mesh.h"
#include "mesh_int.h"

#include <stdlib.h>
#include <string.h>

/* Six times the signed volume of the tetrahedron a b c d of m's vertices. */
static double vol6(const mesh_t *m, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
	const double *A = m->v + 3 * (size_t)a, *B = m->v + 3 * (size_t)b, *C = m->v + 3 * (size_t)c, *D = m->v + 3 * (size_t)d;
	double u[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, v[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
	double w[3] = {D[0] - A[0], D[1] - A[1], D[2] - A[2]};
	return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

int mesh_tet(mesh_t *m, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
	if (m->ntet == MESH_MAX_TETS)
		return -2;
	if (m->ntet == m->tetcap) {
		size_t cap = m->tetcap ? 2 * m->tetcap : 8192;
		uint32_t *q = realloc(m->tet, 4 * cap * sizeof *q);
		if (!q)
			return -1;
		m->tet = q;
		m->tetcap = cap;
	}
	if (vol6(m, a, b, c, d) < 0) {   /* positively oriented (Gmsh's convention) */
		uint32_t t = c;
		c = d;
		d = t;
	}
	uint32_t *t = m->tet + 4 * m->ntet++;
	t[0] = a;
	t[1] = b;
	t[2] = c;
	t[3] = d;
	return 0;
}

int mesh_prism(mesh_t *m, const uint32_t p[6])
{
	/* Dompierre et al.'s rule: each quadrilateral face is cut by the diagonal from its
	 * smallest vertex index, the same choice the neighbour sharing the face makes, so the
	 * tetrahedra match across it. Renumber so that the smallest vertex is V0 (bottom V0 V1
	 * V2, top V3 V4 V5, Vi above Vi-3), then two ways to cut the face V1 V2 V5 V4. */
	static const int rot[6][6] = {{0, 1, 2, 3, 4, 5}, {1, 2, 0, 4, 5, 3}, {2, 0, 1, 5, 3, 4},
	                              {3, 5, 4, 0, 2, 1}, {4, 3, 5, 1, 0, 2}, {5, 4, 3, 2, 1, 0}};
	int k = 0;
	for (int i = 1; i < 6; i++)
		if (p[i] < p[k])
			k = i;
	uint32_t V[6];
	for (int i = 0; i < 6; i++)
		V[i] = p[rot[k][i]];
	uint32_t m15 = V[1] < V[5] ? V[1] : V[5], m24 = V[2] < V[4] ? V[2] : V[4];
	int rc;
	if (m15 < m24)
		rc = mesh_tet(m, V[0], V[1], V[2], V[5]) | mesh_tet(m, V[0], V[1], V[5], V[4]);
	else
		rc = mesh_tet(m, V[0], V[1], V[2], V[4]) | mesh_tet(m, V[0], V[4], V[2], V[5]);
	return rc | mesh_tet(m, V[0], V[4], V[5], V[3]);
}

int mesh_cut_tet(mesh_t *m, int nin, const uint32_t *in, const uint32_t e[4])
{
	if (nin == 1)       /* the inside corner and the three crossings of its edges */
		return mesh_tet(m, in[0], e[0], e[1], e[2]);
	if (nin == 3) {     /* the tetrahedron less the outside corner's: bottom a0 a1 a2, top the crossings */
		uint32_t p[6] = {in[0], in[1], in[2], e[0], e[1], e[2]};
		return mesh_prism(m, p);
	}
	/* two inside corners a0 a1, crossings e0 = a0b0, e1 = a0b1, e2 = a1b0, e3 = a1b1: the prism
	 * with ends a0 e0 e1 and a1 e2 e3 */
	uint32_t p[6] = {in[0], e[0], e[1], in[1], e[2], e[3]};
	return mesh_prism(m, p);
}

/* The three vertex indices of face f (the corner it omits) of tetrahedron t, sorted. */
static void face_of(const uint32_t *t, int f, uint32_t out[3])
{
	int n = 0;
	for (int i = 0; i < 4; i++)
		if (i != f)
			out[n++] = t[i];
	for (int i = 0; i < 2; i++)
		for (int j = 0; j < 2 - i; j++)
			if (out[j] > out[j + 1]) {
				uint32_t x = out[j];
				out[j] = out[j + 1];
				out[j + 1] = x;
			}
}

static int cmp_face(const void *a, const void *b)
{
	const uint32_t *x = a, *y = b;
	for (int i = 0; i < 3; i++)
		if (x[i] != y[i])
			return x[i] < y[i] ? -1 : 1;
	return 0;
}

int mesh_solid_check(const mesh_t *m, mesh_solid_check_t *out)
{
	memset(out, 0, sizeof *out);
	uint32_t *f = malloc(m->ntet * 4 * 3 * sizeof *f + 1);
	if (!f)
		return -1;
	for (size_t i = 0; i < m->ntet; i++) {
		const uint32_t *t = m->tet + 4 * i;
		double v = vol6(m, t[0], t[1], t[2], t[3]) / 6;
		out->volume += v;
		out->negative += v < 0;
		out->flat += v == 0;
		for (int k = 0; k < 4; k++)
			face_of(t, k, f + 3 * (4 * i + k));
	}
	size_t n = 4 * m->ntet;
	qsort(f, n, 3 * sizeof *f, cmp_face);
	for (size_t i = 0; i < n;) {
		size_t j = i + 1;
		while (j < n && cmp_face(f + 3 * i, f + 3 * j) == 0)
			j++;
		if (j - i == 1)
			out->boundary_faces++;
		else if (j - i == 2)
			out->inner_faces++;
		else
			out->overused_faces++;
		i = j;
	}
	free(f);
	return 0;
}
