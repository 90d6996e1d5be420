/* test_mesh.c: polygonisation: closed, consistently oriented meshes whose area and volume match the analytic ones. */
#include "mesh.h"
#include "mesh_int.h"
#include "unit.h"

#include <math.h>
#include <stdlib.h>

/* The sum of distances to n points equal to c (one point: a sphere of radius c). */
static model_shape_t *foci(const double *pts, size_t n, double c)
{
	char err[200];
	model_shape_t *s = model_new();
	for (size_t i = 0; i < n; i++)
		model_add(s, MODEL_POINT, 1, pts + 3 * i, 1, 0, NULL, err, sizeof err);
	s->c.kind = MODEL_C_CONST;
	s->c.c0 = c;
	if (model_prepare(s, err, sizeof err, NULL) < 0)
		printf("# prepare: %s\n", err);
	return s;
}

/* Largest |distance to the surface| over the vertices, for a surface with an exact distance. */
static double worst_sphere(const mesh_t *m, const double *c, double r)
{
	double w = 0;
	for (size_t i = 0; i < m->nv; i++) {
		const double *p = m->v + 3 * i;
		double d = sqrt((p[0] - c[0]) * (p[0] - c[0]) + (p[1] - c[1]) * (p[1] - c[1]) + (p[2] - c[2]) * (p[2] - c[2]));
		w = fmax(w, fabs(d - r));
	}
	return w;
}

static void closed(const mesh_t *m, const char *what)
{
	mesh_check_t k;
	CHECK(mesh_check(m, &k) == 0 && k.open_edges == 0 && k.bad_edges == 0 && k.degenerate == 0
	      && m->nt > 0 && k.edges * 2 == m->nt * 3,
	      "%s: %zu triangles, %zu edges, %zu open, %zu wrongly oriented or shared, %zu degenerate",
	      what, m->nt, k.edges, k.open_edges, k.bad_edges, k.degenerate);
	/* a closed surface: V - E + F = 2 per sphere-like part */
	CHECK((long)m->nv - (long)k.edges + (long)m->nt == 2, "%s: Euler characteristic %ld (2: one sphere)",
	      what, (long)m->nv - (long)k.edges + (long)m->nt);
}

int main(void)
{
	char err[256];
	mesh_t m;
	mesh_stats_t st = {0};
	/* 1. a sphere of radius 1 off the origin: area 4 pi, volume 4/3 pi within 0.5% at depth 6 */
	{
		double c[3] = {0.3, -0.2, 0.1};
		model_shape_t *s = foci(c, 1, 1);
		mesh_init(&m);
		CHECK(mesh_extract(s, 6, &m, &st, err, sizeof err) == 0, "sphere depth 6: %s", m.nt ? "extracted" : err);
		closed(&m, "sphere");
		double a, v, A = 4 * M_PI, V = 4 * M_PI / 3;
		mesh_measure(&m, &a, &v);
		CHECK(fabs(a - A) / A < 0.005 && fabs(v - V) / V < 0.005, "sphere: area %.5f (exact %.5f, %.3f%%), volume %.5f (exact %.5f, %.3f%%)",
		      a, A, 100 * (a - A) / A, v, V, 100 * (v - V) / V);
		double w = worst_sphere(&m, c, 1);
		CHECK(w <= st.max_bracket + 1e-4 * 2.1 / 64 * sqrt(3.0) + 1e-12 && w < 1e-5,
		      "sphere: vertices within %.3g of the surface (proven bound %.3g)", w, st.max_bracket);
		CHECK(st.leaves < (uint64_t)64 * 64 * 64 / 4, "sphere: the octree visits %llu of %d finest cells",
		      (unsigned long long)st.leaves, 64 * 64 * 64);
		mesh_free(&m);
		model_free(s);
	}
	/* 2. the two-focus ellipsoid of test_rt: foci (+-0.8, 0, 0), sum 2.4: a prolate spheroid with
	 * A = 1.2, B = C = sqrt(A^2 - 0.64) */
	{
		double f[6] = {0.8, 0, 0, -0.8, 0, 0}, A = 1.2, B = sqrt(A * A - 0.64), e = sqrt(1 - B * B / (A * A));
		model_shape_t *s = foci(f, 2, 2 * A);
		mesh_init(&m);
		CHECK(mesh_extract(s, 6, &m, NULL, err, sizeof err) == 0, "ellipsoid depth 6");
		closed(&m, "ellipsoid");
		double a, v, Ea = 2 * M_PI * B * B * (1 + A / (B * e) * asin(e)), Ev = 4 * M_PI / 3 * A * B * B;
		mesh_measure(&m, &a, &v);
		CHECK(fabs(a - Ea) / Ea < 0.005 && fabs(v - Ev) / Ev < 0.005, "ellipsoid: area %.5f (exact %.5f, %.3f%%), volume %.5f (exact %.5f, %.3f%%)",
		      a, Ea, 100 * (a - Ea) / Ea, v, Ev, 100 * (v - Ev) / Ev);
		/* every vertex on the surface: |P - F1| + |P - F2| = 2A */
		double w = 0;
		for (size_t i = 0; i < m.nv; i++) {
			const double *p = m.v + 3 * i;
			double d = hypot(hypot(p[0] - 0.8, p[1]), p[2]) + hypot(hypot(p[0] + 0.8, p[1]), p[2]);
			w = fmax(w, fabs(d - 2 * A));
		}
		CHECK(w < 1e-5, "ellipsoid: vertex residual %.3g", w);
		/* a finer mesh is closer: error shrinks about 4x per depth */
		mesh_t m7;
		mesh_init(&m7);
		double a7, v7;
		CHECK(mesh_extract(s, 7, &m7, NULL, err, sizeof err) == 0, "ellipsoid depth 7");
		mesh_measure(&m7, &a7, &v7);
		CHECK(fabs(v7 - Ev) < fabs(v - Ev) / 2.5 && m7.nt > 3 * m.nt, "ellipsoid depth 7: volume error %.3g < %.3g / 2.5, %zu triangles",
		      fabs(v7 - Ev), fabs(v - Ev), m7.nt);
		mesh_free(&m7);
		mesh_free(&m);
		model_free(s);
	}
	/* 3. clipped by a box: a plane z = 0 thickened to |z| <= 0.5 inside bound [-1, 1]^3 is a
	 * closed slab 2 x 2 x 1 (the box faces close it); the extraction cuts its sharp edges by up
	 * to a cell (1/8 here), so it is a little smaller, never larger. Marching tetrahedra keep
	 * more of the area (their diagonals hug some edges); marching cubes chamfer each of the 20
	 * units of edge by up to a cell, (2 - sqrt 2) / 8 = 0.073 of area a unit, 1.46 in all, and a
	 * little more at the 8 corners */
	for (int tet = 0; tet < 2; tet++) {
		model_shape_t *s = model_new();
		double pl[6] = {0, 0, 0, 0, 0, 1};
		model_add(s, MODEL_PLANE, 1, pl, 2, 0, NULL, err, sizeof err);
		s->c.c0 = 0.5;
		double b[6] = {-1, -1, -1, 1, 1, 1};
		memcpy(s->box, b, sizeof b);
		s->user_box = 1;
		CHECK(model_prepare(s, err, sizeof err, NULL) == 0, "slab prepared");
		mesh_init(&m);
		m.tetrahedra = tet;
		CHECK(mesh_extract(s, 4, &m, NULL, err, sizeof err) == 0, "slab depth 4");
		closed(&m, tet ? "slab clipped by its box (tetrahedra)" : "slab clipped by its box (cubes)");
		double a, v;
		mesh_measure(&m, &a, &v);
		CHECK(v < 4 && v > 3.8 && a < 16 && a > (tet ? 15 : 14.4), "slab (%s): volume %.4f (4), area %.4f (16)",
		      tet ? "tetrahedra" : "cubes", v, a);
		mesh_free(&m);
		model_free(s);
	}
	/* 3b. coarsening: the sphere at depth 7 within 1e-4 keeps closed and outward, its vertices
	 * on the surface, area and volume within 0.05%, with far fewer triangles; the flat faces of
	 * the slab coarsen to a few triangles each. Marching tetrahedra's meshes (three times the
	 * triangles, with slivers) coarsen by 4x and 10x; marching cubes' by 1.9x and 5x */
	for (int tet = 0; tet < 2; tet++) {
		double c[3] = {0.3, -0.2, 0.1};
		model_shape_t *s = foci(c, 1, 1);
		mesh_init(&m);
		m.tetrahedra = tet;
		uint64_t ev = 0;
		CHECK(mesh_extract(s, 7, &m, NULL, err, sizeof err) == 0, "sphere depth 7");
		size_t n0 = m.nt;
		CHECK(mesh_simplify(&m, s, 0, 0, 1e-4, &ev, err, sizeof err) == 0, "sphere coarsened within 1e-4");
		closed(&m, "coarsened sphere");
		double a, v, A = 4 * M_PI, V = 4 * M_PI / 3;
		mesh_measure(&m, &a, &v);
		CHECK(fabs(a - A) / A < 5e-4 && fabs(v - V) / V < 5e-4 && v > 0, "coarsened sphere: area %.3f%%, volume %.3f%% off",
		      100 * (a - A) / A, 100 * (v - V) / V);
		CHECK(m.nt < (tet ? n0 / 4 : n0 * 10 / 19), "coarsened sphere (%s): %zu triangles of %zu",
		      tet ? "tetrahedra" : "cubes", m.nt, n0);
		CHECK(worst_sphere(&m, c, 1) < 1e-6, "coarsened sphere: vertices within %.3g of the surface", worst_sphere(&m, c, 1));
		mesh_free(&m);
		model_free(s);
		s = model_new();
		double pl[6] = {0, 0, 0, 0, 0, 1}, b[6] = {-1, -1, -1, 1, 1, 1};
		model_add(s, MODEL_PLANE, 1, pl, 2, 0, NULL, err, sizeof err);
		s->c.c0 = 0.5;
		memcpy(s->box, b, sizeof b);
		s->user_box = 1;
		model_prepare(s, err, sizeof err, NULL);
		mesh_init(&m);
		m.tetrahedra = tet;
		mesh_extract(s, 5, &m, NULL, err, sizeof err);
		n0 = m.nt;
		double a0, v0;
		mesh_measure(&m, &a0, &v0);
		CHECK(mesh_simplify(&m, s, 0, 0, 1e-3, NULL, err, sizeof err) == 0, "slab coarsened");
		closed(&m, "coarsened slab");
		mesh_measure(&m, &a, &v);
		CHECK(m.nt * (tet ? 10 : 5) < n0 && fabs(v - v0) < 0.01, "coarsened slab (%s): %zu triangles of %zu, volume %.4f (was %.4f)",
		      tet ? "tetrahedra" : "cubes", m.nt, n0, v, v0);
		mesh_free(&m);
		model_free(s);
	}
	/* 4. two spheres appended into one mesh: two parts, Euler characteristic 4 */
	{
		double c1[3] = {-1.5, 0, 0}, c2[3] = {1.5, 0, 0};
		model_shape_t *s1 = foci(c1, 1, 1), *s2 = foci(c2, 1, 0.5);
		mesh_init(&m);
		CHECK(mesh_extract(s1, 5, &m, NULL, err, sizeof err) == 0 && mesh_extract(s2, 5, &m, NULL, err, sizeof err) == 0,
		      "two spheres appended");
		mesh_check_t k;
		mesh_check(&m, &k);
		CHECK(k.open_edges == 0 && k.bad_edges == 0 && (long)m.nv - (long)k.edges + (long)m.nt == 4,
		      "two spheres: closed, Euler characteristic %ld", (long)m.nv - (long)k.edges + (long)m.nt);
		double a, v, V = 4 * M_PI / 3 * (1 + 0.125);
		mesh_measure(&m, &a, &v);
		CHECK(fabs(v - V) / V < 0.01, "two spheres: volume %.4f (exact %.4f)", v, V);
		mesh_free(&m);
		model_free(s1);
		model_free(s2);
	}
	/* 5. refusals: depth out of range, no Lipschitz bound */
	{
		double c[3] = {0, 0, 0};
		model_shape_t *s = foci(c, 1, 1);
		mesh_init(&m);
		CHECK(mesh_extract(s, 0, &m, NULL, err, sizeof err) < 0 && strstr(err, "depth"), "depth 0 refused: %s", err);
		CHECK(mesh_extract(s, MESH_MAX_DEPTH + 1, &m, NULL, err, sizeof err) < 0, "depth %d refused", MESH_MAX_DEPTH + 1);
		s->has_lip = 0;
		CHECK(mesh_extract(s, 4, &m, NULL, err, sizeof err) < 0 && strstr(err, "Lipschitz"), "no bound refused: %s", err);
		CHECK(m.nt == 0, "nothing appended on a refusal");
		mesh_free(&m);
		model_free(s);
	}
	/* 6. the solid's cut of a Kuhn tetrahedron with two inside corners: its surface
	 * quadrilateral is cut along the surface's own (shorter) diagonal, its other faces from
	 * their smallest vertex. Numbered so that these three diagonals turn the same way round
	 * the prism (e0 smallest, a0 smallest of its other quadrilateral, e1-e2 the shorter), which
	 * no three tetrahedra can fill: a point at the centroid and 8 tetrahedra. With the outside
	 * part cut the same way, the two fill the tetrahedron exactly, face to face. */
	{
		/* a0 (0,0,0) a1 (1,0,0) inside, b0 (0,1,0) b1 (0,0,1) outside */
		static const double P[8][3] = {
			{0, 0.5, 0},      /* 0: e0 on a0b0 */
			{0, 0, 0},        /* 1: a0 */
			{1, 0, 0},        /* 2: a1 */
			{0, 0, 0.2},      /* 3: e1 on a0b1 */
			{0.5, 0.5, 0},    /* 4: e2 on a1b0 */
			{0.5, 0, 0.5},    /* 5: e3 on a1b1 */
			{0, 1, 0},        /* 6: b0 */
			{0, 0, 1},        /* 7: b1 */
		};
		mesh_init(&m);
		for (int i = 0; i < 8; i++) {
			long k = mesh_vertex_slot(&m);
			CHECK(k == i, "vertex %d in slot %ld", i, k);
			for (int j = 0; j < 3; j++)
				m.v[3 * (size_t)k + j] = P[i][j];
			m.nv++;
		}
		uint32_t in[2] = {1, 2}, e[4] = {0, 3, 4, 5};
		CHECK(mesh_cut_tet(&m, 2, in, e) == 0, "inside part cut");
		CHECK(m.ntet == 8 && m.nv == 9, "a cyclic prism: %zu tetrahedra around %zu added point", m.ntet, m.nv - 8);
		mesh_solid_check_t k;
		mesh_solid_check(&m, &k);
		double inside = k.volume;
		CHECK(k.negative == 0 && k.flat == 0 && k.boundary_faces == 8 && k.inner_faces == 12 && k.overused_faces == 0,
		      "its 8 tetrahedra: %zu negative, %zu flat, %zu boundary and %zu inner faces, %zu overused",
		      k.negative, k.flat, k.boundary_faces, k.inner_faces, k.overused_faces);
		/* the outside part: corners b0 b1, crossings b0a0 b0a1 b1a0 b1a1 */
		uint32_t out[2] = {6, 7}, eo[4] = {0, 4, 3, 5};
		CHECK(mesh_cut_tet(&m, 2, out, eo) == 0, "outside part cut");
		mesh_solid_check(&m, &k);
		CHECK(k.negative == 0 && k.flat == 0 && k.overused_faces == 0 && fabs(k.volume - 1.0 / 6) < 1e-15 &&
		      k.boundary_faces == 4 + 2 + 2 + 2 + 2,
		      "inside %.6f + outside part = %.17g (the tetrahedron's 1/6), %zu boundary faces (its 4 faces as 12 triangles), %zu overused",
		      inside, k.volume, k.boundary_faces, k.overused_faces);
		mesh_free(&m);
	}
	/* 7. formats by suffix */
	CHECK(mesh_format_of("a.stl") == MESH_STL && mesh_format_of("B.PLY") == MESH_PLY && mesh_format_of("x/y.obj") == MESH_OBJ
	      && mesh_format_of("a.meta") < 0 && mesh_format_of("stl") < 0 && mesh_format_of("-") < 0, "formats from the suffix");
	return UNIT_DONE();
}
