/* mesh.c: marching tetrahedra through the octree: closed, outward-wound triangle meshes of shapes (mesh.h). */
#include "mesh.h"
#include "mesh_int.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the extraction ---- */

typedef struct {
	const model_shape_t *s;
	mesh_t *m;
	mesh_stats_t *st;
	int depth;
	uint64_t n1;             /* grid points a side: 2^depth + 1 */
	double lo[3], cell;      /* root cube corner and the finest cell's side */
	double lip;
	mesh_table_t verts;           /* edge key -> vertex index */
	int solid;               /* also the solid's tetrahedra (m->want_solid) */
	mesh_table_t corners;         /* solid: grid point key -> vertex index */
	int oom, too_many, too_many_tets;
} ext_t;

/* The signed distance to the box b (negative inside) and, when g is not NULL, its gradient. */
static double box_distance(const double *b, const double p[3], double g[3])
{
	double out = 0, in = -INFINITY, q[3];
	int arg = 0;
	for (int i = 0; i < 3; i++) {
		double c = (b[i] + b[3 + i]) / 2, h = (b[3 + i] - b[i]) / 2;
		q[i] = fabs(p[i] - c) - h;
		if (q[i] > 0)
			out += q[i] * q[i];
		if (q[i] > in) {
			in = q[i];
			arg = i;
		}
	}
	double d = out > 0 ? sqrt(out) : in < 0 ? in : 0;
	if (g) {
		for (int i = 0; i < 3; i++) {
			double sg = p[i] < (b[i] + b[3 + i]) / 2 ? -1 : 1;
			g[i] = out > 0 ? (q[i] > 0 ? sg * q[i] / d : 0) : (i == arg ? sg : 0);
		}
	}
	return d;
}

/* f, or for a distance-estimated shape its estimate (bound 1): the sign of f, and no surface
 * within |value| of p; a point whose iteration never escaped is inside with no bound (a tiny
 * negative value: no bracket is narrowed by it). */
static double field_f(const model_shape_t *s, const double p[3])
{
	if (!s->de)
		return model_eval(s, p);
	double d;
	if (model_de_known(s, p, &d) || !(d == d))
		return d;
	return d < 0 ? -1e-300 : 1e-300;
}

double mesh_field(const model_shape_t *s, const double p[3])
{
	double L = s->de ? 1 : s->lip;
	double f = field_f(s, p), bd = L * box_distance(s->box, p, NULL);
	if (!(f == f))
		f = INFINITY;   /* an undefined value counts as outside */
	return f > bd ? f : bd;
}

void mesh_field_grad(const model_shape_t *s, const double p[3], double g[3])
{
	double L = s->de ? 1 : s->lip;
	double f = field_f(s, p), gb[3], bd = L * box_distance(s->box, p, gb);
	if (f == f && f >= bd) {
		model_grad(s, p, g);
		if (s->de) {   /* the estimate's slope is about 1: its direction, unit length */
			double n = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
			for (int i = 0; i < 3 && n > 0; i++)
				g[i] /= n;
		}
		return;
	}
	for (int i = 0; i < 3; i++)
		g[i] = L * gb[i];
}

/* F, counted. */
static double eval_f(ext_t *x, const double p[3])
{
	x->st->evals++;
	return mesh_field(x->s, p);
}

static void grid_point(const ext_t *x, const uint64_t g[3], double p[3])
{
	for (int i = 0; i < 3; i++)
		p[i] = x->lo[i] + (double)g[i] * x->cell;
}

/* F at grid point g (always the same value for the same point: no cache is needed for the
 * corners' signs to agree between the cells that share them) */
static double corner(ext_t *x, const uint64_t g[3])
{
	double p[3];
	grid_point(x, g, p);
	return eval_f(x, p);
}

#define REFINE_TOL 1e-7   /* bracket width to reach, in edge lengths */

/* F at a + t d, sorted into the bracket [lo, hi] (F(lo) < 0 <= F(hi)); 1 when it moved lo. */
static int probe(ext_t *x, const double a[3], const double d[3], double t, double *lo, double *flo,
                 double *hi, double *fhi)
{
	double q[3] = {a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]}, f = eval_f(x, q);
	if (f < 0) {
		*lo = t;
		*flo = f;
		return 1;
	}
	*hi = t;
	*fhi = f;
	return 0;
}

/* The zero of F on the segment from a (F = fa < 0) to b (F = fb >= 0), written to p. */
static void refine(ext_t *x, const double a[3], const double b[3], double fa, double fb, double p[3])
{
	double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
	double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), step = 1 / (x->lip * len);
	double lo = 0, hi = 1, flo = fa, fhi = fb, width = 2;
	int last = -1, again = 0;
	for (int it = 0; it < 100; it++) {
		/* no zero within |F| / L of either end: the narrowed bracket [l, h] holds every zero */
		double l = fmin(lo - flo * step, hi), h = fmax(hi - fhi * step, l);
		if (fhi == 0) {
			lo = hi;   /* an exact zero (a corner on the box, or one probe) */
			break;
		}
		if (h - l <= REFINE_TOL) {
			lo = l;
			hi = h;
			break;
		}
		/* a secant step inside [l, h] (Illinois: the end kept twice counts half), bisection
		 * when it falls outside or the bracket did not halve */
		double wl = flo, wh = fhi;
		if (again)
			*(last ? &wh : &wl) /= 2;
		double t = lo + (hi - lo) * (-wl) / (wh - wl);
		if (!(t > l && t < h) || (it >= 3 && h - l > width / 2))
			t = (l + h) / 2;
		width = h - l;
		int moved = probe(x, a, d, t, &lo, &flo, &hi, &fhi);
		again = moved == last;
		last = moved;
		/* when the secant puts the zero within the tolerance of t, test just across it: the
		 * bracket then closes in one evaluation instead of creeping up from one side */
		double s = lo + (hi - lo) * (-flo) / (fhi - flo), u = s + (moved ? 0.4 : -0.4) * REFINE_TOL;
		if (fabs(s - t) < 0.4 * REFINE_TOL && u > lo && u < hi)
			probe(x, a, d, u, &lo, &flo, &hi, &fhi);
	}
	double bracket = (hi - lo) * len;
	if (bracket > x->st->max_bracket)
		x->st->max_bracket = bracket;
	double t = (lo + hi) / 2;
	t = fmin(fmax(t, 1e-4), 1 - 1e-4);
	for (int i = 0; i < 3; i++)
		p[i] = a[i] + t * d[i];
}

void mesh_refine_edge(const model_shape_t *s, double lip, mesh_stats_t *st, const double a[3], const double b[3],
                      double fa, double fb, double p[3])
{
	ext_t x;
	memset(&x, 0, sizeof x);
	x.s = s;
	x.lip = lip;
	x.st = st;
	refine(&x, a, b, fa, fb, p);
}

/* Index of the vertex on the edge from grid point ga to gb (gb - ga in {0,1}^3). */
static uint32_t vertex(ext_t *x, const uint64_t ga[3], const uint64_t gb[3], double fa, double fb)
{
	unsigned dir = (unsigned)((gb[0] - ga[0]) | (gb[1] - ga[1]) << 1 | (gb[2] - ga[2]) << 2);
	uint64_t k = ((ga[2] * x->n1 + ga[1]) * x->n1 + ga[0]) * 8 + dir;
	double *p;
	long i = mesh_vertex_at(x->m, &x->verts, k, &p);
	if (i < 0) {
		x->oom = 1;
		return 0;
	}
	if (p) {
		double a[3], b[3];
		grid_point(x, ga, a);
		grid_point(x, gb, b);
		if (fa < 0)
			refine(x, a, b, fa, fb, p);
		else
			refine(x, b, a, fb, fa, p);
	}
	return (uint32_t)i;
}

/* Record a triangle append's result (mesh_triangle's -1 or -2). */
static void triangle_rc(ext_t *x, int r)
{
	if (r == -2)
		x->too_many = 1;
	else if (r < 0)
		x->oom = 1;
}

long mesh_vertex_at(mesh_t *m, mesh_table_t *t, uint64_t k, double **p)
{
	uint64_t v;
	size_t at;
	*p = NULL;
	int r = mesh_table_get(t, k, &v, &at);
	if (r < 0)
		return -1;
	if (r)
		return (long)v;
	if (mesh_vertex_slot(m) < 0)
		return -1;
	*p = m->v + 3 * m->nv;
	mesh_table_put(t, at, k, m->nv);
	return (long)m->nv++;
}

int mesh_triangle(mesh_t *m, uint32_t a, uint32_t b, uint32_t c)
{
	if (m->nt == MESH_MAX_TRIANGLES)
		return -2;
	if (m->nt == m->tcap) {
		size_t cap = m->tcap ? 2 * m->tcap : 8192;
		uint32_t *q = realloc(m->t, 3 * cap * sizeof *q);
		if (!q)
			return -1;
		m->t = q;
		m->tcap = cap;
	}
	uint32_t *t = m->t + 3 * m->nt++;
	t[0] = a;
	t[1] = b;
	t[2] = c;
	return 0;
}

/* The 6 tetrahedra of the Kuhn triangulation of a cube (corner bits: 1 = +x, 2 = +y, 4 = +z). */
static const int kuhn[6][4] = {
	{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Append the triangle on edges e0 e1 e2 (their midpoints mid[]) wound with its normal along
 * `out` (from the inside corners towards the outside ones). As mesh_triangle. */
static int oriented(mesh_t *m, const uint32_t *v, const double (*mid)[3], int e0, int e1, int e2, const double *out)
{
	double u[3], w[3], n[3];
	for (int i = 0; i < 3; i++) {
		u[i] = mid[e1][i] - mid[e0][i];
		w[i] = mid[e2][i] - mid[e0][i];
	}
	n[0] = u[1] * w[2] - u[2] * w[1];
	n[1] = u[2] * w[0] - u[0] * w[2];
	n[2] = u[0] * w[1] - u[1] * w[0];
	if (dot3(n, out) > 0)
		return mesh_triangle(m, v[e0], v[e1], v[e2]);
	return mesh_triangle(m, v[e0], v[e2], v[e1]);
}

static double dist2(const double *a, const double *b)
{
	double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
	return dot3(d, d);
}

/* The worse of two append results: -2 (too many) before -1 (memory) before 0. */
static int worse(int a, int b) { return a == -2 || b == -2 ? -2 : a < 0 ? a : b; }

int mesh_tet_surface(mesh_t *m, const double (*cp)[3], const int *ins, int ni, const int *outs, int no,
                     const uint32_t *v)
{
	/* from the inside corners' centroid to the outside ones' */
	double dir[3] = {0, 0, 0};
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < ni; j++)
			dir[i] -= cp[ins[j]][i] / ni;
		for (int j = 0; j < no; j++)
			dir[i] += cp[outs[j]][i] / no;
	}
	double mid[4][3];
	int ne = 0;
	for (int i = 0; i < ni; i++)
		for (int j = 0; j < no; j++, ne++)
			for (int c = 0; c < 3; c++)
				mid[ne][c] = (cp[ins[i]][c] + cp[outs[j]][c]) / 2;
	const double (*md)[3] = (const double (*)[3])mid;
	if (ne == 3)
		return oriented(m, v, md, 0, 1, 2, dir);
	/* edges 0 = a0b0, 1 = a0b1, 2 = a1b0, 3 = a1b1: the quad 0 1 3 2; split along the shorter
	 * of its diagonals 0-3 and 1-2 (by the refined vertices) */
	const double *P = m->v;
	int r;   /* two statements: the first triangle is appended first */
	if (dist2(P + 3 * v[0], P + 3 * v[3]) <= dist2(P + 3 * v[1], P + 3 * v[2])) {
		r = oriented(m, v, md, 0, 1, 3, dir);
		return worse(r, oriented(m, v, md, 0, 3, 2, dir));
	}
	r = oriented(m, v, md, 1, 3, 2, dir);
	return worse(r, oriented(m, v, md, 1, 2, 0, dir));
}

/* Record a failed tetrahedron append (mesh_tet's -1 or -2). */
static void tet_failed(ext_t *x, int rc)
{
	if (rc == -2)
		x->too_many_tets = 1;
	else
		x->oom = 1;
}

/* The solid's vertex at grid point g (an inside corner), made once. */
static uint32_t corner_vertex(ext_t *x, const uint64_t g[3])
{
	double *p;
	long i = mesh_vertex_at(x->m, &x->corners, (g[2] * x->n1 + g[1]) * x->n1 + g[0], &p);
	if (i < 0) {
		x->oom = 1;
		return 0;
	}
	if (p)
		grid_point(x, g, p);
	return (uint32_t)i;
}

/* The solid: the 6 Kuhn tetrahedra of the finest cell at g, all inside. */
static void whole_cell(ext_t *x, const uint64_t g[3])
{
	uint32_t id[8];
	for (int c = 0; c < 8; c++) {
		uint64_t q[3] = {g[0] + (c & 1), g[1] + ((c >> 1) & 1), g[2] + ((c >> 2) & 1)};
		id[c] = corner_vertex(x, q);
	}
	for (int k = 0; k < 6 && !x->oom && !x->too_many_tets; k++) {
		int rc = mesh_tet(x->m, id[kuhn[k][0]], id[kuhn[k][1]], id[kuhn[k][2]], id[kuhn[k][3]]);
		if (rc < 0)
			tet_failed(x, rc);
	}
}

/* The solid: every finest cell of the cell at g (size finest cells a side), all inside. */
static void fill_inside(ext_t *x, const uint64_t g[3], uint64_t size)
{
	for (uint64_t k = 0; k < size && !x->oom && !x->too_many_tets; k++)
		for (uint64_t j = 0; j < size && !x->oom && !x->too_many_tets; j++)
			for (uint64_t i = 0; i < size && !x->oom && !x->too_many_tets; i++) {
				uint64_t q[3] = {g[0] + i, g[1] + j, g[2] + k};
				whole_cell(x, q);
			}
}

/* Marching tetrahedra in the finest cell with lower grid corner g. */
static void leaf(ext_t *x, const uint64_t g[3])
{
	uint64_t cg[8][3];
	double cf[8], cp[8][3];
	int any_in = 0, any_out = 0;
	for (int c = 0; c < 8; c++) {
		for (int i = 0; i < 3; i++)
			cg[c][i] = g[i] + ((c >> i) & 1);
		cf[c] = corner(x, cg[c]);
		grid_point(x, cg[c], cp[c]);
		if (cf[c] < 0)
			any_in = 1;
		else
			any_out = 1;
	}
	if (x->solid && any_in && !any_out)
		whole_cell(x, g);
	if (!any_in || !any_out || x->oom)
		return;
	uint32_t cid[8];           /* solid: the inside corners' vertices */
	for (int c = 0; x->solid && c < 8; c++)
		cid[c] = cf[c] < 0 ? corner_vertex(x, cg[c]) : UINT32_MAX;
	uint32_t cache[64];      /* the cell's 19 edges (corner a * 8 + corner b): their vertices */
	memset(cache, 0xff, sizeof cache);
	for (int k = 0; k < 6 && !x->oom && !x->too_many; k++) {
		const int *q = kuhn[k];
		int in[4], nin = 0, ni = 0, no = 0, ins[4], outs[4];
		for (int i = 0; i < 4; i++) {
			in[i] = cf[q[i]] < 0;
			nin += in[i];
			if (in[i])
				ins[ni++] = q[i];
			else
				outs[no++] = q[i];
		}
		if (nin == 4 && x->solid) {
			int rc = mesh_tet(x->m, cid[q[0]], cid[q[1]], cid[q[2]], cid[q[3]]);
			if (rc < 0)
				tet_failed(x, rc);
		}
		if (nin == 0 || nin == 4)
			continue;
		/* the crossed edges: inside corner a to outside corner b (lower grid corner first) */
		uint32_t v[4];
		int ne = 0;
		for (int i = 0; i < ni; i++)
			for (int j = 0; j < no; j++) {
				int a = ins[i], b = outs[j], lo = a < b ? a : b, hi = a < b ? b : a;
				if (cache[lo * 8 + hi] == UINT32_MAX)
					cache[lo * 8 + hi] = vertex(x, cg[lo], cg[hi], cf[lo], cf[hi]);
				v[ne++] = cache[lo * 8 + hi];
			}
		if (x->oom)
			return;
		if (x->solid) {   /* the tetrahedron's inside part */
			uint32_t iv[3] = {cid[ins[0]], ni > 1 ? cid[ins[1]] : 0, ni > 2 ? cid[ins[2]] : 0};
			int rc = mesh_cut_tet(x->m, ni, iv, v);
			if (rc < 0)
				tet_failed(x, rc);
		}
		triangle_rc(x, mesh_tet_surface(x->m, (const double (*)[3])cp, ins, ni, outs, no, v));
	}
}

/* Descend into the cell of the given level with lower grid corner g (in finest-cell units). */
static void visit(ext_t *x, const uint64_t g[3], int level)
{
	uint64_t size = (uint64_t)1 << (x->depth - level);
	double c[3];
	for (int i = 0; i < 3; i++)
		c[i] = x->lo[i] + ((double)g[i] + size / 2.0) * x->cell;
	x->st->cells++;
	double f = eval_f(x, c), r = sqrt(3.0) / 2 * (double)size * x->cell;
	if (f != INFINITY && fabs(f) > x->lip * r * (1 + 1e-9) + 1e-12) {
		if (x->solid && f < 0)
			fill_inside(x, g, size);   /* all inside: the solid's tetrahedra, finest cells */
		return;   /* no zero of F in the cell's circumscribed sphere (an undefined f: kept) */
	}
	if (level == x->depth) {
		x->st->leaves++;
		leaf(x, g);
		return;
	}
	uint64_t h = size / 2;
	for (int k = 0; k < 8 && !x->oom && !x->too_many; k++) {
		uint64_t q[3] = {g[0] + (k & 1 ? h : 0), g[1] + (k & 2 ? h : 0), g[2] + (k & 4 ? h : 0)};
		visit(x, q, level + 1);
	}
}

void mesh_init(mesh_t *m)
{
	memset(m, 0, sizeof *m);
}

void mesh_free(mesh_t *m)
{
	free(m->v);
	free(m->t);
	free(m->tet);
	mesh_init(m);
}

int mesh_extract_tetra(const model_shape_t *s, int depth, mesh_t *m, mesh_stats_t *st, char *err, size_t errlen)
{
	ext_t x;
	memset(&x, 0, sizeof x);
	x.s = s;
	x.m = m;
	x.st = st;
	x.depth = depth;
	x.n1 = ((uint64_t)1 << depth) + 1;
	x.lip = s->de ? 1 : s->lip;   /* the estimate bounds the distance itself */
	x.cell = mesh_root_cube(s, x.lo) / (double)((uint64_t)1 << depth);
	size_t nv0 = m->nv;
	uint64_t g0[3] = {0, 0, 0};
	x.solid = m->want_solid;
	visit(&x, g0, 0);
	mesh_table_free(&x.verts);
	mesh_table_free(&x.corners);
	if (x.too_many_tets && !x.oom) {
		snprintf(err, errlen, "the solid has more than %zu tetrahedra: lower its depth", MESH_MAX_TETS);
		return -1;
	}
	return mesh_extract_end(m, nv0, x.oom, x.too_many, err, errlen);
}

int mesh_can_extract(const model_shape_t *s, char *err, size_t errlen)
{
	if (!s->has_lip && !s->de) {
		snprintf(err, errlen, "the mesh needs a Lipschitz bound or a distance estimate, and this shape's defining parameter has neither (draw it with raytrace, which brackets)");
		return -1;
	}
	return 0;
}

double mesh_root_cube(const model_shape_t *s, double lo[3])
{
	const double *r = s->root;
	double side = fmax(r[3] - r[0], fmax(r[4] - r[1], r[5] - r[2]));
	for (int i = 0; i < 3; i++)
		lo[i] = (r[i] + r[3 + i]) / 2 - side / 2;
	return side;
}

int mesh_extract_end(const mesh_t *m, size_t nv0, int oom, int too_many, char *err, size_t errlen)
{
	if (oom) {
		snprintf(err, errlen, "out of memory for the mesh (%zu triangles so far)", m->nt);
		return -1;
	}
	if (too_many) {
		snprintf(err, errlen, "the mesh has more than %zu triangles: lower its depth", MESH_MAX_TRIANGLES);
		return -1;
	}
	if (m->nv > UINT32_MAX || m->nv < nv0) {
		snprintf(err, errlen, "the mesh has too many vertices for 32-bit indices: lower its depth");
		return -1;
	}
	return 0;
}

void mesh_measure(const mesh_t *m, double *area, double *volume)
{
	double a = 0, v = 0;
	for (size_t i = 0; i < m->nt; i++) {
		const double *p = m->v + 3 * m->t[3 * i], *q = m->v + 3 * m->t[3 * i + 1], *r = m->v + 3 * m->t[3 * i + 2];
		double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, w[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
		double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
		a += sqrt(dot3(n, n)) / 2;
		v += dot3(p, n) / 6;   /* p . (q - p) x (r - p) = p . q x r */
	}
	*area = a;
	*volume = v;
}

int mesh_check(const mesh_t *m, mesh_check_t *out)
{
	memset(out, 0, sizeof *out);
	mesh_table_t e = {NULL, 0, 0};
	/* per undirected edge: count of uses a->b with a < b (low 32 bits) and b->a (high) */
	for (size_t i = 0; i < m->nt; i++) {
		const uint32_t *t = m->t + 3 * i;
		if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
			out->degenerate++;
		for (int j = 0; j < 3; j++) {
			uint32_t a = t[j], b = t[(j + 1) % 3];
			if (a == b)
				continue;
			uint64_t k = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a, c = 0;
			size_t at;
			int r = mesh_table_get(&e, k, &c, &at);
			if (r < 0) {
				mesh_table_free(&e);
				return -1;
			}
			uint64_t inc = a < b ? 1 : (uint64_t)1 << 32;
			if (r) {
				e.e[at].val = c + inc;
			} else {
				mesh_table_put(&e, at, k, inc);
			}
		}
	}
	for (size_t i = 0; i < e.cap; i++) {
		if (!e.e[i].key)
			continue;
		uint64_t fw = e.e[i].val & 0xffffffffu, bw = e.e[i].val >> 32;
		out->edges++;
		if (fw + bw == 1)
			out->open_edges++;
		else if (fw != 1 || bw != 1)
			out->bad_edges++;
	}
	mesh_table_free(&e);
	return 0;
}
