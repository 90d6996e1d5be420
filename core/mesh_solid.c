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

/* Room for one more vertex; its index, or -1 out of memory. Here, beside mesh_tet, so that the
 * surface (mesh.c, mesh_mc.c) and the solid's prisms share it without a circle. */
long mesh_vertex_slot(mesh_t *m)
{
	if (m->nv == m->vcap) {
		size_t cap = m->vcap ? 2 * m->vcap : 4096;
		double *q = realloc(m->v, 3 * cap * sizeof *q);
		if (!q)
			return -1;
		m->v = q;
		m->vcap = cap;
	}
	return (long)m->nv;
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

/* The diagonal that cuts the quadrilateral q (q[0..3] in order round it), as its two ends: the
 * one from its smallest vertex index (Dompierre et al.'s rule, which the neighbour sharing the
 * face applies too), or f0-f1 when both are corners of q (the surface's own quadrilateral, which
 * no other tetrahedron shares). */
static void quad_diag(const uint32_t q[4], uint32_t f0, uint32_t f1, uint32_t d[2])
{
	int h0 = 0, h1 = 0, k = 0;
	for (int i = 0; i < 4; i++) {
		h0 |= q[i] == f0;
		h1 |= q[i] == f1;
		if (q[i] < q[k])
			k = i;
	}
	if (h0 && h1 && f0 != f1) {
		d[0] = f0;
		d[1] = f1;
	} else {
		d[0] = q[k];
		d[1] = q[(k + 2) % 4];
	}
}

static int is_end(const uint32_t d[2], uint32_t a, uint32_t b)
{
	return (d[0] == a && d[1] == b) || (d[0] == b && d[1] == a);
}

/* The prism p cut with the quadrilaterals' diagonals of quad_diag. Three tetrahedra from a
 * corner V0 that both its quadrilaterals' diagonals leave; when none does (the three diagonals
 * turn the same way round, which only a forced diagonal can cause), eight from a point added at
 * the prism's centroid, a cone over its five faces as they are cut. */
static int prism_cut(mesh_t *m, const uint32_t p[6], uint32_t f0, uint32_t f1)
{
	/* the prism renumbered so that corner k is V0 (bottom V0 V1 V2, top V3 V4 V5, Vi above
	 * Vi-3); the candidates in order of vertex index, so that without a forced diagonal the
	 * smallest corner is V0, as Dompierre et al.'s rule has it */
	static const int rot[6][6] = {{0, 1, 2, 3, 4, 5}, {1, 2, 0, 4, 5, 3}, {2, 0, 1, 5, 3, 4},
	                              {3, 5, 4, 0, 2, 1}, {4, 3, 5, 1, 0, 2}, {5, 4, 3, 2, 1, 0}};
	int order[6] = {0, 1, 2, 3, 4, 5};
	for (int i = 1; i < 6; i++)
		for (int j = i; j > 0 && p[order[j]] < p[order[j - 1]]; j--) {
			int t = order[j];
			order[j] = order[j - 1];
			order[j - 1] = t;
		}
	for (int c = 0; c < 6; c++) {
		uint32_t V[6], d01[2], d02[2], d12[2];
		for (int i = 0; i < 6; i++)
			V[i] = p[rot[order[c]][i]];
		uint32_t q01[4] = {V[0], V[1], V[4], V[3]}, q02[4] = {V[0], V[2], V[5], V[3]};
		uint32_t q12[4] = {V[1], V[2], V[5], V[4]};
		quad_diag(q01, f0, f1, d01);
		quad_diag(q02, f0, f1, d02);
		if (!is_end(d01, V[0], V[4]) || !is_end(d02, V[0], V[5]))
			continue;
		quad_diag(q12, f0, f1, d12);
		int rc;
		if (is_end(d12, V[1], V[5]))
			rc = mesh_tet(m, V[0], V[1], V[2], V[5]) | mesh_tet(m, V[0], V[1], V[5], V[4]);
		else
			rc = mesh_tet(m, V[0], V[1], V[2], V[4]) | mesh_tet(m, V[0], V[4], V[2], V[5]);
		return rc | mesh_tet(m, V[0], V[4], V[5], V[3]);
	}
	if (mesh_vertex_slot(m) < 0)
		return -1;
	size_t c = m->nv;
	double *P = m->v + 3 * c;
	for (int i = 0; i < 3; i++) {
		P[i] = 0;
		for (int k = 0; k < 6; k++)
			P[i] += m->v[3 * (size_t)p[k] + i] / 6;
	}
	m->nv++;
	uint32_t C = (uint32_t)c;
	int rc = mesh_tet(m, C, p[0], p[1], p[2]) | mesh_tet(m, C, p[3], p[4], p[5]);
	static const int quads[3][4] = {{0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
	for (int k = 0; k < 3; k++) {
		uint32_t q[4] = {p[quads[k][0]], p[quads[k][1]], p[quads[k][2]], p[quads[k][3]]}, d[2];
		quad_diag(q, f0, f1, d);
		if (is_end(d, q[0], q[2]))
			rc |= mesh_tet(m, C, q[0], q[1], q[2]) | mesh_tet(m, C, q[0], q[2], q[3]);
		else
			rc |= mesh_tet(m, C, q[1], q[2], q[3]) | mesh_tet(m, C, q[1], q[3], q[0]);
	}
	return rc;
}

int mesh_prism(mesh_t *m, const uint32_t p[6])
{
	return prism_cut(m, p, UINT32_MAX, UINT32_MAX);
}

/* The squared distance between vertices a and b of m. */
static double dist2v(const mesh_t *m, uint32_t a, uint32_t b)
{
	const double *A = m->v + 3 * (size_t)a, *B = m->v + 3 * (size_t)b;
	double x = A[0] - B[0], y = A[1] - B[1], z = A[2] - B[2];
	return x * x + y * y + z * z;
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
	 * with ends a0 e0 e1 and a1 e2 e3. Its face e0 e1 e3 e2 is the surface's quadrilateral,
	 * which the surface (mesh_tet_surface) splits along its shorter diagonal, 0-3 on a tie: the
	 * solid cuts it there too, so that its boundary is the surface mesh itself and the two
	 * volumes agree to rounding. (The other faces lie on the Kuhn tetrahedron's faces and keep
	 * the rule their neighbours apply.) */
	uint32_t p[6] = {in[0], e[0], e[1], in[1], e[2], e[3]};
	if (dist2v(m, e[0], e[3]) <= dist2v(m, e[1], e[2]))
		return prism_cut(m, p, e[0], e[3]);
	return prism_cut(m, p, e[1], e[2]);
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
