/* mesh_mc.c: marching cubes on the octree's finest cells, slab by slab: F once per grid corner, one vertex per crossed grid edge (mesh.h, docs/mesh.md). */
#include "mesh.h"
#include "mesh_int.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

/* ---- the case table, made once from a face rule ----
 *
 * Corners: bit 1 = +x, 2 = +y, 4 = +z. Edge e joins mc_ea[e] to mc_eb[e] = mc_ea[e] | (1 << axis),
 * edges 0-3 along x, 4-7 along y, 8-11 along z. On every cube face the crossed edges are joined
 * in pairs by segments: two crossings, one segment; four (the face's diagonal corners alike, the
 * ambiguous face) two segments, each cutting off one inside corner. The rule reads only the
 * face's four corners, so the two cells that share a face draw the same segments there: the
 * surface has no crack. Each segment is directed so that the surface's normal (from the inside
 * corners towards the outside ones) turns it counter-clockwise seen from outside; every crossed
 * edge then has one segment in and one out, and the segments close into loops, each a polygon
 * of the surface (at most 4 loops, 12 vertices in all). */

typedef struct {
	uint16_t edges;          /* bit e: edge e is crossed */
	uint8_t nloops, len[4];  /* the loops and their lengths */
	int8_t v[12];            /* their edges, loop after loop, in counter-clockwise order */
} mc_case_t;

static mc_case_t mc_case[256];
static int mc_ea[12], mc_eb[12], mc_axis[12];
static pthread_once_t mc_once = PTHREAD_ONCE_INIT;
static int mc_table_ok;

static int edge_of(int a, int b)
{
	for (int e = 0; e < 12; e++)
		if ((mc_ea[e] == a && mc_eb[e] == b) || (mc_ea[e] == b && mc_eb[e] == a))
			return e;
	return -1;
}

static void corner_pos(int c, double p[3])
{
	for (int i = 0; i < 3; i++)
		p[i] = (c >> i) & 1;
}

static void edge_mid(int e, double p[3])
{
	double a[3], b[3];
	corner_pos(mc_ea[e], a);
	corner_pos(mc_eb[e], b);
	for (int i = 0; i < 3; i++)
		p[i] = (a[i] + b[i]) / 2;
}

/* Join edge ea to eb on the face with outward normal n, g pointing from the inside corners to
 * the outside ones: directed along g x n (the normal turns it counter-clockwise). */
static void segment(int *next, int ea, int eb, const double g[3], const double n[3])
{
	double t[3] = {g[1] * n[2] - g[2] * n[1], g[2] * n[0] - g[0] * n[2], g[0] * n[1] - g[1] * n[0]};
	double pa[3], pb[3];
	edge_mid(ea, pa);
	edge_mid(eb, pb);
	double d = (pb[0] - pa[0]) * t[0] + (pb[1] - pa[1]) * t[1] + (pb[2] - pa[2]) * t[2];
	if (d > 0)
		next[ea] = next[ea] < 0 ? eb : 99;
	else
		next[eb] = next[eb] < 0 ? ea : 99;
}

static void mc_make_table(void)
{
	int e = 0;
	for (int ax = 0; ax < 3; ax++)
		for (int c = 0; c < 8; c++)
			if (!(c & (1 << ax))) {
				mc_ea[e] = c;
				mc_eb[e] = c | 1 << ax;
				mc_axis[e] = ax;
				e++;
			}
	int ok = 1;
	for (int cfg = 0; cfg < 256; cfg++) {
		mc_case_t *k = &mc_case[cfg];
		memset(k, 0, sizeof *k);
		int next[12];
		for (int i = 0; i < 12; i++) {
			next[i] = -1;
			if (((cfg >> mc_ea[i]) & 1) != ((cfg >> mc_eb[i]) & 1))
				k->edges |= (uint16_t)(1u << i);
		}
		for (int ax = 0; ax < 3; ax++)
			for (int side = 0; side < 2; side++) {
				int j = (ax + 1) % 3, l = (ax + 2) % 3, base = side << ax;
				int q[4] = {base, base | 1 << j, base | 1 << j | 1 << l, base | 1 << l};
				double n[3] = {0, 0, 0};
				n[ax] = side ? 1 : -1;
				int in[4], nin = 0, cross[4], nc = 0;
				for (int p = 0; p < 4; p++)
					nin += in[p] = (cfg >> q[p]) & 1;
				for (int p = 0; p < 4; p++)
					if (in[p] != in[(p + 1) % 4])
						cross[nc++] = p;   /* the edge from q[p] to q[p + 1] */
				if (nc == 2) {
					double g[3] = {0, 0, 0}, cp[3];
					for (int p = 0; p < 4; p++) {
						corner_pos(q[p], cp);
						for (int i = 0; i < 3; i++)
							g[i] += in[p] ? -cp[i] / nin : cp[i] / (4 - nin);
					}
					segment(next, edge_of(q[cross[0]], q[(cross[0] + 1) % 4]),
					        edge_of(q[cross[1]], q[(cross[1] + 1) % 4]), g, n);
				} else if (nc == 4) {
					for (int p = 0; p < 4; p++) {
						if (!in[p])
							continue;   /* each inside corner cut off on its own */
						int e0 = edge_of(q[(p + 3) % 4], q[p]), e1 = edge_of(q[p], q[(p + 1) % 4]);
						double m0[3], m1[3], cp[3], g[3];
						edge_mid(e0, m0);
						edge_mid(e1, m1);
						corner_pos(q[p], cp);
						for (int i = 0; i < 3; i++)
							g[i] = (m0[i] + m1[i]) / 2 - cp[i];
						segment(next, e0, e1, g, n);
					}
				}
			}
		/* every crossed edge: one segment out (next) and one in */
		int indeg[12] = {0};
		for (int i = 0; i < 12; i++) {
			int crossed = (k->edges >> i) & 1;
			if (crossed != (next[i] >= 0) || next[i] == 99)
				ok = 0;
			if (crossed && next[i] >= 0 && next[i] < 12)
				indeg[next[i]]++;
		}
		for (int i = 0; i < 12; i++)
			if (((k->edges >> i) & 1) && indeg[i] != 1)
				ok = 0;
		if (!ok)
			break;
		int seen = 0, nv = 0;
		for (int i = 0; i < 12; i++) {
			if (!((k->edges >> i) & 1) || (seen >> i) & 1)
				continue;
			int len = 0;
			for (int v = i; !((seen >> v) & 1); v = next[v]) {
				seen |= 1 << v;
				k->v[nv++] = (int8_t)v;
				len++;
			}
			if (k->nloops == 4 || len < 3) {
				ok = 0;
				break;
			}
			k->len[k->nloops++] = (uint8_t)len;
		}
	}
	mc_table_ok = ok;
}

/* ---- the extraction ---- */

typedef struct {
	const model_shape_t *s;
	mesh_t *m;
	mesh_stats_t *st;
	int depth;
	double lo[3], cell, lip;
	int batch;               /* children tested by the float kernel first (not for estimates) */
	double span;             /* the root cube's largest coordinate */
	uint16_t *leaf;          /* the finest cells kept: x, y, z */
	size_t nleaf, leafcap;
	int oom, too_many;
} mc_t;

static void add_leaf(mc_t *x, const uint64_t g[3])
{
	if (x->nleaf == x->leafcap) {
		size_t cap = x->leafcap ? 2 * x->leafcap : 4096;
		uint16_t *q = realloc(x->leaf, 3 * cap * sizeof *q);
		if (!q) {
			x->oom = 1;
			return;
		}
		x->leaf = q;
		x->leafcap = cap;
	}
	uint16_t *l = x->leaf + 3 * x->nleaf++;
	for (int i = 0; i < 3; i++)
		l[i] = (uint16_t)g[i];
}

/* The signed distance to the box b (negative inside), as mesh_field takes it. */
static double box_dist(const double *b, const double p[3])
{
	double out = 0, in = -INFINITY;
	for (int i = 0; i < 3; i++) {
		double q = fabs(p[i] - (b[i] + b[3 + i]) / 2) - (b[3 + i] - b[i]) / 2;
		if (q > 0)
			out += q * q;
		if (q > in)
			in = q;
	}
	return out > 0 ? sqrt(out) : in < 0 ? in : 0;
}

/* Whether the cell of half-diagonal r around c may hold a zero of F (the test of mesh.c, on
 * the double-precision F), given F there. */
static int may_hold(const mc_t *x, double f, double r)
{
	return f == INFINITY || !(fabs(f) > x->lip * r * (1 + 1e-9) + 1e-12);
}

/* The octree descent of mesh.c: a cell is split only when its circumscribed sphere may hold a
 * zero of F; the finest cells that pass are kept. The 8 children of a cell are tested together:
 * f by the 8-lane float kernel (the ray tracer's), the box term in double; a child whose float
 * F is within a guard band of the threshold (a thousandth of it, plus 4e-6 of |F| and of L
 * times the root's largest coordinate: far above the float kernel's rounding) is tested again
 * in double, so every decision is the double test's. `cell` passed the test already. */
static void visit(mc_t *x, const uint64_t g[3], int level)
{
	if (level == x->depth) {
		x->st->leaves++;
		add_leaf(x, g);
		return;
	}
	uint64_t h = (uint64_t)1 << (x->depth - level - 1);
	double r = sqrt(3.0) / 2 * (double)h * x->cell;
	uint64_t q[8][3];
	double c[8][3], F[8];
	float fx[8], fy[8], fz[8], fv[8];
	for (int k = 0; k < 8; k++) {
		q[k][0] = g[0] + (k & 1 ? h : 0);
		q[k][1] = g[1] + (k & 2 ? h : 0);
		q[k][2] = g[2] + (k & 4 ? h : 0);
		for (int i = 0; i < 3; i++)
			c[k][i] = x->lo[i] + ((double)q[k][i] + h / 2.0) * x->cell;
		fx[k] = (float)c[k][0];
		fy[k] = (float)c[k][1];
		fz[k] = (float)c[k][2];
	}
	x->st->cells += 8;
	if (x->batch) {
		model_eval8(x->s, fx, fy, fz, fv);
		x->st->evals += 8;
	}
	double thr = x->lip * r * (1 + 1e-9) + 1e-12;
	for (int k = 0; k < 8; k++) {
		int pass;
		if (x->batch) {
			double f = fv[k], bd = x->lip * box_dist(x->s->box, c[k]);
			f = f > bd ? f : bd;
			double band = 1e-3 * thr + 4e-6 * (fabs(f) + x->lip * x->span);
			if (f == f && fabs(f) > thr + band)
				pass = 0;
			else if (f == f && fabs(f) < thr - band)
				pass = 1;
			else {
				x->st->evals++;
				pass = may_hold(x, mesh_field(x->s, c[k]), r);
			}
		} else {
			x->st->evals++;
			F[k] = mesh_field(x->s, c[k]);
			pass = may_hold(x, F[k], r);
		}
		if (pass && !x->oom)
			visit(x, q[k], level + 1);
	}
}

static double dist2(const double *a, const double *b)
{
	double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
	return d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
}

static void tri(mc_t *x, uint32_t a, uint32_t b, uint32_t c)
{
	int r = mesh_triangle(x->m, a, b, c);
	if (r == -2)
		x->too_many = 1;
	else if (r < 0)
		x->oom = 1;
}

/* Planes of grid points, two at a time (z and z + 1, by parity), entries stamped with the plane
 * they hold (z + 1; 0 = never): no clearing between slabs. */
typedef struct {
	double *val[2];
	uint32_t *vstamp[2];
	uint64_t *ex[2], *ey[2], *ez;   /* vertex of the edge from the point: stamp << 32 | index */
	void *base;              /* the mapping that holds them */
	size_t bytes;
} planes_t;

/* The planes live in one mapping, populated when it is made (MAP_POPULATE: one system call
 * instead of a page fault every 4 KiB on first touch, which perf found costing a tenth of the
 * extraction on the development VM); zeroed, so every stamp starts at 0 (never). */
static void planes_free(planes_t *p)
{
	if (p->base)
		munmap(p->base, p->bytes);
	memset(p, 0, sizeof *p);
}

static int planes_alloc(planes_t *p, size_t n2)
{
	memset(p, 0, sizeof *p);
	size_t bytes = n2 * (2 * sizeof(double) + 2 * sizeof(uint32_t) + 5 * sizeof(uint64_t));
#ifdef MAP_POPULATE
	int flags = MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE;
#else
	int flags = MAP_PRIVATE | MAP_ANONYMOUS;
#endif
	char *q = mmap(NULL, bytes, PROT_READ | PROT_WRITE, flags, -1, 0);
	if (q == MAP_FAILED)
		return -1;
	p->base = q;
	p->bytes = bytes;
	for (int i = 0; i < 2; i++) {   /* the 8-byte arrays first: all stay aligned */
		p->val[i] = (double *)q;
		q += n2 * sizeof(double);
		p->ex[i] = (uint64_t *)q;
		q += n2 * sizeof(uint64_t);
		p->ey[i] = (uint64_t *)q;
		q += n2 * sizeof(uint64_t);
	}
	p->ez = (uint64_t *)q;
	q += n2 * sizeof(uint64_t);
	for (int i = 0; i < 2; i++) {
		p->vstamp[i] = (uint32_t *)q;
		q += n2 * sizeof(uint32_t);
	}
	return 0;
}

/* Room in m for about as many more vertices and twice as many triangles as there are kept
 * cells (marching cubes make about 0.9 and 1.7 a cell on smooth surfaces), in one step rather
 * than by doublings that copy. Only a hint: the appends still grow the arrays as needed. */
static void reserve(mesh_t *m, size_t ncells)
{
	size_t nv = m->nv + ncells + 64, nt = m->nt + 2 * ncells + 64;
	if (nv > m->vcap) {
		double *q = realloc(m->v, 3 * nv * sizeof *q);
		if (q) {
			m->v = q;
			m->vcap = nv;
		}
	}
	if (nt > m->tcap && nt <= MESH_MAX_TRIANGLES) {
		uint32_t *q = realloc(m->t, 3 * nt * sizeof *q);
		if (q) {
			m->t = q;
			m->tcap = nt;
		}
	}
}

static void polygonise(mc_t *x, planes_t *pl)
{
	uint64_t n = (uint64_t)1 << x->depth, n1 = n + 1;
	/* the kept cells sorted by z (a counting sort: the slabs in order) */
	size_t *start = calloc(n + 2, sizeof *start);
	uint16_t *sorted = malloc((x->nleaf ? x->nleaf : 1) * 2 * sizeof *sorted);
	if (!start || !sorted) {
		free(start);
		free(sorted);
		x->oom = 1;
		return;
	}
	for (size_t i = 0; i < x->nleaf; i++)
		start[x->leaf[3 * i + 2] + 1]++;
	for (uint64_t z = 0; z < n; z++)
		start[z + 1] += start[z];
	for (size_t i = 0; i < x->nleaf; i++) {
		size_t at = start[x->leaf[3 * i + 2]]++;
		sorted[2 * at] = x->leaf[3 * i];
		sorted[2 * at + 1] = x->leaf[3 * i + 1];
	}
	for (uint64_t z = n; z > 0; z--)
		start[z] = start[z - 1];
	start[0] = 0;
	mesh_t *m = x->m;
	for (uint64_t z = 0; z < n && !x->oom && !x->too_many; z++) {
		for (size_t li = start[z]; li < start[z + 1] && !x->oom && !x->too_many; li++) {
			uint64_t gx = sorted[2 * li], gy = sorted[2 * li + 1];
			double cf[8];
			size_t cidx[8];
			int cfg = 0;
			for (int c = 0; c < 8; c++) {
				uint64_t qx = gx + (c & 1), qy = gy + ((c >> 1) & 1), qz = z + ((c >> 2) & 1);
				size_t idx = (size_t)(qy * n1 + qx);
				int par = (int)(qz & 1);
				cidx[c] = idx;
				if (pl->vstamp[par][idx] != (uint32_t)(qz + 1)) {
					double p[3] = {x->lo[0] + (double)qx * x->cell, x->lo[1] + (double)qy * x->cell,
					               x->lo[2] + (double)qz * x->cell};
					x->st->evals++;
					pl->val[par][idx] = mesh_field(x->s, p);
					pl->vstamp[par][idx] = (uint32_t)(qz + 1);
				}
				cf[c] = pl->val[par][idx];
				cfg |= (cf[c] < 0) << c;
			}
			const mc_case_t *k = &mc_case[cfg];
			if (!k->edges)
				continue;
			uint32_t vid[12];
			for (int e = 0; e < 12; e++) {
				if (!((k->edges >> e) & 1))
					continue;
				int a = mc_ea[e], b = mc_eb[e], ax = mc_axis[e];
				uint64_t az = z + ((a >> 2) & 1);
				uint64_t *slotp = ax == 0 ? &pl->ex[az & 1][cidx[a]] : ax == 1 ? &pl->ey[az & 1][cidx[a]] : &pl->ez[cidx[a]];
				uint64_t stamp = az + 1;
				if (*slotp >> 32 == stamp) {
					vid[e] = (uint32_t)*slotp;
					continue;
				}
				long i = mesh_vertex_slot(m);
				if (i < 0) {
					x->oom = 1;
					break;
				}
				m->nv++;
				double pa[3] = {x->lo[0] + (double)(gx + (a & 1)) * x->cell, x->lo[1] + (double)(gy + ((a >> 1) & 1)) * x->cell,
				                x->lo[2] + (double)az * x->cell};
				double pb[3] = {pa[0], pa[1], pa[2]};
				pb[ax] += x->cell;
				double *p = m->v + 3 * i;
				if (cf[a] < 0)
					mesh_refine_edge(x->s, x->lip, x->st, pa, pb, cf[a], cf[b], p);
				else
					mesh_refine_edge(x->s, x->lip, x->st, pb, pa, cf[b], cf[a], p);
				vid[e] = (uint32_t)i;
				*slotp = stamp << 32 | (uint64_t)(uint32_t)i;
			}
			if (x->oom)
				break;
			const int8_t *v = k->v;
			for (int l = 0; l < k->nloops; v += k->len[l], l++) {
				int len = k->len[l];
				if (len == 4) {   /* a quadrilateral: split along its shorter diagonal */
					const double *P = m->v;
					if (dist2(P + 3 * vid[v[0]], P + 3 * vid[v[2]]) <= dist2(P + 3 * vid[v[1]], P + 3 * vid[v[3]])) {
						tri(x, vid[v[0]], vid[v[1]], vid[v[2]]);
						tri(x, vid[v[0]], vid[v[2]], vid[v[3]]);
					} else {
						tri(x, vid[v[1]], vid[v[2]], vid[v[3]]);
						tri(x, vid[v[1]], vid[v[3]], vid[v[0]]);
					}
					continue;
				}
				for (int j = 1; j + 1 < len; j++)
					tri(x, vid[v[0]], vid[v[j]], vid[v[j + 1]]);
			}
		}
	}
	free(start);
	free(sorted);
}

int mesh_extract_cubes(const model_shape_t *s, int depth, mesh_t *m, mesh_stats_t *st, char *err, size_t errlen)
{
	pthread_once(&mc_once, mc_make_table);
	if (!mc_table_ok) {
		snprintf(err, errlen, "internal error: the marching-cubes table is inconsistent");
		return -1;
	}
	mc_t x;
	memset(&x, 0, sizeof x);
	x.s = s;
	x.m = m;
	x.st = st;
	x.depth = depth;
	x.lip = s->de ? 1 : s->lip;
	x.cell = mesh_root_cube(s, x.lo) / (double)((uint64_t)1 << depth);
	size_t nv0 = m->nv;
	double side = x.cell * (double)((uint64_t)1 << depth);
	for (int i = 0; i < 3; i++)
		x.span = fmax(x.span, fmax(fabs(x.lo[i]), fabs(x.lo[i] + side)));
	x.batch = !s->de;
	uint64_t g0[3] = {0, 0, 0};
	double c0[3] = {x.lo[0] + side / 2, x.lo[1] + side / 2, x.lo[2] + side / 2};
	st->cells++;
	st->evals++;
	if (may_hold(&x, mesh_field(s, c0), sqrt(3.0) / 2 * side))
		visit(&x, g0, 0);
	if (!x.oom && x.nleaf) {
		uint64_t n1 = ((uint64_t)1 << depth) + 1;
		planes_t pl;
		if (planes_alloc(&pl, (size_t)(n1 * n1)) < 0)
			x.oom = 1;
		else {
			reserve(m, x.nleaf);
			polygonise(&x, &pl);
			planes_free(&pl);
		}
	}
	free(x.leaf);
	return mesh_extract_end(m, nv0, x.oom, x.too_many, err, errlen);
}

/* mesh_extract (mesh.h): the checks, then marching cubes, or tetrahedra for a solid or when asked
 * (here rather than in mesh.c, so that mesh.c does not call back into this file). */
int mesh_extract(const model_shape_t *s, int depth, mesh_t *m, mesh_stats_t *st, char *err, size_t errlen)
{
	mesh_stats_t local;
	if (!st) {
		memset(&local, 0, sizeof local);
		st = &local;
	}
	if (depth < 1 || depth > MESH_MAX_DEPTH) {
		snprintf(err, errlen, "expected a mesh depth from 1 to %d", MESH_MAX_DEPTH);
		return -1;
	}
	if (mesh_can_extract(s, err, errlen) < 0)
		return -1;
	if (!m->want_solid && !m->tetrahedra)
		return mesh_extract_cubes(s, depth, m, st, err, errlen);
	return mesh_extract_tetra(s, depth, m, st, err, errlen);
}
