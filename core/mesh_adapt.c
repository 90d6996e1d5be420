/* mesh_adapt.c: adaptive marching tetrahedra through the octree: fine cells where the surface curves, coarse where it is flat, crack-free (mesh.h). */
#include "mesh.h"
#include "mesh_int.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Points live on a grid of half the finest cell (so that every cell and face centre is a grid
 * point): integer coordinates 0..2^(depth+1) a side, keyed x + (n + 1)(y + (n + 1) z). */

typedef struct {
	uint64_t g[3];           /* lower corner, finest-cell units */
	uint64_t size;           /* side, finest-cell units */
} cell_t;

typedef struct {
	const model_shape_t *s;
	mesh_t *m;
	mesh_stats_t *st;
	int depth, minlevel;
	double tol, lip, lo[3], half;   /* half: the half-unit grid step */
	uint64_t n1;                    /* half-unit points a side: 2^(depth+1) + 1 */
	mesh_table_t f;                 /* point key -> F (bits) */
	mesh_table_t inner;             /* subdivided cells: (level, position) */
	mesh_table_t leafset;           /* leaf cells: (level, position) */
	mesh_table_t corners;           /* leaf corners and face-piece corners (point keys) */
	mesh_table_t verts;             /* edge (point key pair) -> vertex index */
	cell_t *leaves;
	size_t nleaves, lcap;
	int oom, too_many;
} ad_t;

static uint64_t pkey(const ad_t *x, const uint64_t h[3])
{
	return (h[2] * x->n1 + h[1]) * x->n1 + h[0];
}

static void ppos(const ad_t *x, const uint64_t h[3], double p[3])
{
	for (int i = 0; i < 3; i++)
		p[i] = x->lo[i] + (double)h[i] * x->half;
}

/* F at the half-unit point h, evaluated once. */
static double fat(ad_t *x, const uint64_t h[3])
{
	uint64_t k = pkey(x, h), v;
	size_t at;
	int r = mesh_table_get(&x->f, k, &v, &at);
	double f;
	if (r < 0) {
		x->oom = 1;
		return 0;
	}
	if (r) {
		memcpy(&f, &v, sizeof f);
		return f;
	}
	double p[3];
	ppos(x, h, p);
	f = mesh_field(x->s, p);
	x->st->evals++;
	memcpy(&v, &f, sizeof v);
	mesh_table_put(&x->f, at, k, v);
	return f;
}

static void set_add(ad_t *x, mesh_table_t *t, uint64_t k)
{
	uint64_t v;
	size_t at;
	int r = mesh_table_get(t, k, &v, &at);
	if (r < 0)
		x->oom = 1;
	else if (!r)
		mesh_table_put(t, at, k, 1);
}

static int set_has(ad_t *x, mesh_table_t *t, uint64_t k)
{
	uint64_t v;
	size_t at;
	int r = mesh_table_get(t, k, &v, &at);
	if (r < 0)
		x->oom = 1;
	return r == 1;
}

/* The key of the cell at lower corner g of the given size (the size fixes the level). */
static uint64_t ckey(const ad_t *x, const uint64_t g[3], uint64_t size)
{
	uint64_t n = ((uint64_t)1 << x->depth) + 1, lg = 0;
	while (((uint64_t)1 << lg) < size)
		lg++;   /* size is a power of two: its exponent */
	return ((g[2] * n + g[1]) * n + g[0]) * 16 + lg;
}

/* 1 when F is flat enough in the cell (centre half-unit point c, half side hh half-units): the
 * linear function through the centre with the central-difference gradient predicts F at the
 * corners, and the second differences along the axes stay, within tol of distance (the error
 * divided by |grad F|). */
static int flat(ad_t *x, const uint64_t c[3], uint64_t hh)
{
	double f0 = fat(x, c), g[3], err = 0, h = (double)hh * x->half;
	for (int i = 0; i < 3; i++) {
		uint64_t a[3] = {c[0], c[1], c[2]}, b[3] = {c[0], c[1], c[2]};
		a[i] += hh;
		b[i] -= hh;
		double fa = fat(x, a), fb = fat(x, b);
		g[i] = (fa - fb) / (2 * h);
		err = fmax(err, fabs(fa + fb - 2 * f0) / 2);
	}
	for (int k = 0; k < 8; k++) {
		uint64_t q[3];
		double pred = f0;
		for (int i = 0; i < 3; i++) {
			int up = (k >> i) & 1;
			q[i] = up ? c[i] + hh : c[i] - hh;
			pred += g[i] * (up ? h : -h);
		}
		err = fmax(err, fabs(fat(x, q) - pred));
	}
	double gl = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
	return gl > 0 && err / gl <= x->tol && err == err;
}

static void add_leaf(ad_t *x, const uint64_t g[3], uint64_t size)
{
	if (x->nleaves == x->lcap) {
		size_t cap = x->lcap ? 2 * x->lcap : 4096;
		cell_t *q = realloc(x->leaves, cap * sizeof *q);
		if (!q) {
			x->oom = 1;
			return;
		}
		x->leaves = q;
		x->lcap = cap;
	}
	cell_t *c = &x->leaves[x->nleaves++];
	memcpy(c->g, g, sizeof c->g);
	c->size = size;
	x->st->leaves++;
	set_add(x, &x->leafset, ckey(x, g, size));
	for (int k = 0; k < 8; k++) {
		uint64_t h[3] = {2 * (g[0] + (k & 1 ? size : 0)), 2 * (g[1] + (k & 2 ? size : 0)), 2 * (g[2] + (k & 4 ? size : 0))};
		set_add(x, &x->corners, pkey(x, h));
	}
}

/* The octree: cells that may hold the surface are split until flat (from minlevel on) or at
 * the finest depth. */
static void build(ad_t *x, const uint64_t g[3], int level)
{
	uint64_t size = (uint64_t)1 << (x->depth - level), c[3];
	for (int i = 0; i < 3; i++)
		c[i] = 2 * g[i] + size;
	x->st->cells++;
	double f = fat(x, c), r = sqrt(3.0) / 2 * (double)size * 2 * x->half;
	if (x->oom || (f != INFINITY && fabs(f) > x->lip * r * (1 + 1e-9) + 1e-12))
		return;
	if (level == x->depth || (level >= x->minlevel && flat(x, c, size))) {
		add_leaf(x, g, size);
		return;
	}
	set_add(x, &x->inner, ckey(x, g, size));
	uint64_t hs = size / 2;
	for (int k = 0; k < 8 && !x->oom; k++) {
		uint64_t q[3] = {g[0] + (k & 1 ? hs : 0), g[1] + (k & 2 ? hs : 0), g[2] + (k & 4 ? hs : 0)};
		build(x, q, level + 1);
	}
}

/* ---- the tetrahedra and their surface ---- */

/* Record a triangle append's result (mesh_triangle's -1 or -2). */
static void triangle_rc(ad_t *x, int r)
{
	if (r == -2)
		x->too_many = 1;
	else if (r < 0)
		x->oom = 1;
}

/* The surface vertex on the edge between half-unit points a (inside) and b (outside). */
static uint32_t vertex(ad_t *x, const uint64_t a[3], const uint64_t b[3], double fa, double fb)
{
	uint64_t ka = pkey(x, a), kb = pkey(x, b), lo = ka < kb ? ka : kb, hi = ka < kb ? kb : ka;
	uint64_t k = lo * x->n1 * x->n1 * x->n1 + hi;   /* depth <= 9: below 2^62 */
	double *p;
	long i = mesh_vertex_at(x->m, &x->verts, k, &p);
	if (i < 0) {
		x->oom = 1;
		return 0;
	}
	if (p) {
		double pa[3], pb[3];
		ppos(x, a, pa);
		ppos(x, b, pb);
		mesh_refine_edge(x->s, x->lip, x->st, pa, pb, fa, fb, p);
	}
	return (uint32_t)i;
}

/* Marching tetrahedra on the tetrahedron of half-unit points t[4]: one triangle or two. */
static void tet(ad_t *x, uint64_t t[4][3])
{
	double f[4], p[4][3];
	int ins[4], outs[4], ni = 0, no = 0;
	for (int i = 0; i < 4; i++) {
		f[i] = fat(x, t[i]);
		ppos(x, t[i], p[i]);
		if (f[i] < 0)
			ins[ni++] = i;
		else
			outs[no++] = i;
	}
	if (ni == 0 || no == 0 || x->oom)
		return;
	uint32_t v[4];
	int ne = 0;
	for (int i = 0; i < ni; i++)
		for (int j = 0; j < no; j++)
			v[ne++] = vertex(x, t[ins[i]], t[outs[j]], f[ins[i]], f[outs[j]]);
	if (x->oom)
		return;
	triangle_rc(x, mesh_tet_surface(x->m, (const double (*)[3])p, ins, ni, outs, no, v));
}

/* A square piece of a leaf's face: axis a, the face plane at half-unit coordinate w, lower
 * corner (u, v) on the other two axes (half units) and side s (half units). */
typedef struct {
	int a;
	uint64_t w, u, v, s;
} piece_t;

static void piece_point(const piece_t *q, uint64_t du, uint64_t dv, uint64_t h[3])
{
	int b = (q->a + 1) % 3, c = (q->a + 2) % 3;
	h[q->a] = q->w;
	h[b] = q->u + du;
	h[c] = q->v + dv;
}

/* Pass 1 (fan = 0): record the piece's corners; pass 2 (fan = 1): the tetrahedra from the cell
 * centre cc and the piece centre to each boundary segment, the boundary points being every
 * recorded corner along the piece's edges, so that both cells on a face and the pieces beside
 * one another cut their common edges at the same points. */
static void piece(ad_t *x, const piece_t *q, const uint64_t cc[3], int fan)
{
	if (!fan) {
		for (int k = 0; k < 4; k++) {
			uint64_t h[3];
			piece_point(q, k & 1 ? q->s : 0, k & 2 ? q->s : 0, h);
			set_add(x, &x->corners, pkey(x, h));
		}
		return;
	}
	uint64_t t[4][3], pc[3];
	piece_point(q, q->s / 2, q->s / 2, pc);
	/* walk the boundary: (0,0) -> (s,0) -> (s,s) -> (0,s) -> (0,0), in steps of 2 half units */
	static const int du0[4] = {0, 1, 1, 0}, dv0[4] = {0, 0, 1, 1}, ddu[4] = {1, 0, -1, 0}, ddv[4] = {0, 1, 0, -1};
	uint64_t prev[3];
	piece_point(q, 0, 0, prev);
	for (int e = 0; e < 4 && !x->oom && !x->too_many; e++) {
		for (uint64_t k = 2; k <= q->s; k += 2) {
			int64_t u = (int64_t)(du0[e] * q->s) + ddu[e] * (int64_t)k, v = (int64_t)(dv0[e] * q->s) + ddv[e] * (int64_t)k;
			uint64_t h[3];
			piece_point(q, (uint64_t)u, (uint64_t)v, h);
			if (k < q->s && !set_has(x, &x->corners, pkey(x, h)))
				continue;
			memcpy(t[0], cc, sizeof t[0]);
			memcpy(t[1], pc, sizeof t[1]);
			memcpy(t[2], prev, sizeof t[2]);
			memcpy(t[3], h, sizeof t[3]);
			tet(x, t);
			memcpy(prev, h, sizeof prev);
		}
	}
}

/* The face of a leaf (lower corner g, size in finest units) on axis a, side hi (0: low, 1:
 * high), cut into pieces where the cells across are subdivided (the cell across at the same
 * size, and inside it down to the leaves touching the face). */
static void face(ad_t *x, const uint64_t g[3], uint64_t size, int a, int hi, const uint64_t cc[3], int fan)
{
	int b = (a + 1) % 3, c = (a + 2) % 3;
	uint64_t across[3] = {g[0], g[1], g[2]}, full = (uint64_t)1 << x->depth;
	int inside_box = hi ? g[a] + size < full : g[a] >= size;
	if (inside_box)
		across[a] = hi ? g[a] + size : g[a] - size;
	/* a stack of regions across the face: subdivided ones give their 4 children on the face */
	struct { uint64_t g[3], size; } st[64];
	int n = 0;
	if (inside_box && set_has(x, &x->inner, ckey(x, across, size))) {
		memcpy(st[0].g, across, sizeof st[0].g);
		st[0].size = size;
		n = 1;
	} else {
		piece_t q = {a, 2 * (g[a] + (hi ? size : 0)), 2 * g[b], 2 * g[c], 2 * size};
		piece(x, &q, cc, fan);
		return;
	}
	while (n > 0 && !x->oom) {
		n--;
		uint64_t rg[3] = {st[n].g[0], st[n].g[1], st[n].g[2]}, rs = st[n].size / 2;
		for (int k = 0; k < 4; k++) {
			uint64_t q3[3] = {rg[0], rg[1], rg[2]};
			q3[a] = hi ? rg[a] : rg[a] + rs;   /* the children touching the face */
			q3[b] += k & 1 ? rs : 0;
			q3[c] += k & 2 ? rs : 0;
			if (rs > 1 && set_has(x, &x->inner, ckey(x, q3, rs)) && n < 63) {
				memcpy(st[n].g, q3, sizeof st[n].g);
				st[n].size = rs;
				n++;
			} else {
				piece_t q = {a, 2 * (g[a] + (hi ? size : 0)), 2 * q3[b], 2 * q3[c], 2 * rs};
				piece(x, &q, cc, fan);
			}
		}
	}
}

/* 1 when the face is one piece with no corner inside its edges (the cell across, if any, is
 * not subdivided and nothing finer touches the edges): then both cells on it cut it along the
 * diagonal from its lowest to its highest corner, as the Kuhn triangulation does. */
static int face_simple(ad_t *x, const uint64_t g[3], uint64_t size, int a, int hi)
{
	int b = (a + 1) % 3, c = (a + 2) % 3;
	uint64_t full = (uint64_t)1 << x->depth, across[3] = {g[0], g[1], g[2]};
	if (hi ? g[a] + size < full : g[a] >= size) {
		across[a] = hi ? g[a] + size : g[a] - size;
		if (set_has(x, &x->inner, ckey(x, across, size)))
			return 0;   /* finer cells across */
		for (uint64_t s2 = 2 * size; s2 <= full; s2 *= 2) {
			uint64_t up[3] = {across[0] / s2 * s2, across[1] / s2 * s2, across[2] / s2 * s2};
			if (set_has(x, &x->leafset, ckey(x, up, s2)))
				return 0;   /* a coarser leaf across: it fans this face as one of its pieces */
		}
	}
	piece_t q = {a, 2 * (g[a] + (hi ? size : 0)), 2 * g[b], 2 * g[c], 2 * size};
	for (uint64_t k = 2; k < q.s; k += 2) {
		uint64_t h[4][3];
		piece_point(&q, k, 0, h[0]);
		piece_point(&q, k, q.s, h[1]);
		piece_point(&q, 0, k, h[2]);
		piece_point(&q, q.s, k, h[3]);
		for (int i = 0; i < 4; i++)
			if (set_has(x, &x->corners, pkey(x, h[i])))
				return 0;
	}
	return 1;
}

/* The 6 tetrahedra of the Kuhn triangulation of a cube (corner bits: 1 = +x, 2 = +y, 4 = +z). */
static const int kuhn[6][4] = {
	{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

/* The tetrahedra of one leaf: the 6 Kuhn ones when all its faces are simple (they cut every
 * face along its low-high diagonal); else a cone from the cell centre over each face, a
 * simple face as its two triangles (the same diagonal), another as the fans of its pieces. */
static void leaf_tets(ad_t *x, const cell_t *c)
{
	uint64_t cc[3] = {2 * c->g[0] + c->size, 2 * c->g[1] + c->size, 2 * c->g[2] + c->size}, t[4][3];
	int simple[3][2], all = 1;
	for (int a = 0; a < 3; a++)
		for (int hi = 0; hi < 2; hi++)
			all &= simple[a][hi] = face_simple(x, c->g, c->size, a, hi);
	uint64_t cor[8][3];
	for (int k = 0; k < 8; k++)
		for (int i = 0; i < 3; i++)
			cor[k][i] = 2 * (c->g[i] + ((k >> i) & 1 ? c->size : 0));
	if (all) {
		for (int k = 0; k < 6 && !x->oom && !x->too_many; k++) {
			for (int j = 0; j < 4; j++)
				memcpy(t[j], cor[kuhn[k][j]], sizeof t[j]);
			tet(x, t);
		}
		return;
	}
	for (int a = 0; a < 3 && !x->oom && !x->too_many; a++)
		for (int hi = 0; hi < 2; hi++) {
			if (!simple[a][hi]) {
				face(x, c->g, c->size, a, hi, cc, 1);
				continue;
			}
			/* the face's corners: axis a fixed at hi, the other two bits free */
			int b = (a + 1) % 3, d = (a + 2) % 3, q[4];
			for (int k = 0; k < 4; k++)
				q[k] = (hi << a) | ((k & 1) << b) | ((k >> 1 & 1) << d);
			/* q[0] lowest, q[3] highest: triangles q0 q1 q3 and q0 q2 q3 */
			for (int tri = 0; tri < 2; tri++) {
				memcpy(t[0], cc, sizeof t[0]);
				memcpy(t[1], cor[q[0]], sizeof t[1]);
				memcpy(t[2], cor[q[tri ? 2 : 1]], sizeof t[2]);
				memcpy(t[3], cor[q[3]], sizeof t[3]);
				tet(x, t);
			}
		}
}

int mesh_extract_adaptive(const model_shape_t *s, int depth, double tol, mesh_t *m, mesh_stats_t *st,
                          char *err, size_t errlen)
{
	mesh_stats_t local;
	if (!st) {
		memset(&local, 0, sizeof local);
		st = &local;
	}
	if (depth < 1 || depth > MESH_MAX_ADAPTIVE_DEPTH) {
		snprintf(err, errlen, "expected an adaptive mesh depth from 1 to %d", MESH_MAX_ADAPTIVE_DEPTH);
		return -1;
	}
	if (!(tol > 0)) {
		snprintf(err, errlen, "expected a positive adaptive tolerance");
		return -1;
	}
	if (mesh_can_extract(s, err, errlen) < 0)
		return -1;
	if (m->want_solid) {
		snprintf(err, errlen, "expected no solid (.msh) from an adaptive mesh: its tetrahedra follow the uniform grid");
		return -1;
	}
	ad_t x;
	memset(&x, 0, sizeof x);
	x.s = s;
	x.m = m;
	x.st = st;
	x.depth = depth;
	x.minlevel = depth > 5 ? depth - 5 : 0;   /* cells at most 32 finest cells a side */
	x.tol = tol;
	x.lip = s->de ? 1 : s->lip;
	x.n1 = ((uint64_t)1 << (depth + 1)) + 1;
	x.half = mesh_root_cube(s, x.lo) / (double)((uint64_t)1 << (depth + 1));
	size_t nv0 = m->nv;
	uint64_t g0[3] = {0, 0, 0};
	build(&x, g0, 0);
	/* pass 1: every face piece's corners; pass 2: the tetrahedra and the surface */
	for (size_t i = 0; i < x.nleaves && !x.oom; i++) {
		const cell_t *c = &x.leaves[i];
		uint64_t cc[3] = {2 * c->g[0] + c->size, 2 * c->g[1] + c->size, 2 * c->g[2] + c->size};
		for (int a = 0; a < 3; a++)
			for (int hi = 0; hi < 2; hi++)
				face(&x, c->g, c->size, a, hi, cc, 0);
	}
	for (size_t i = 0; i < x.nleaves && !x.oom && !x.too_many; i++)
		leaf_tets(&x, &x.leaves[i]);
	mesh_table_free(&x.f);
	mesh_table_free(&x.inner);
	mesh_table_free(&x.leafset);
	mesh_table_free(&x.corners);
	mesh_table_free(&x.verts);
	free(x.leaves);
	return mesh_extract_end(m, nv0, x.oom, x.too_many, err, errlen);
}
