/* mesh_simplify.c: adaptive coarsening of a closed mesh by edge collapses that keep it closed, oriented and near the surface. */
#include "mesh.h"
#include "mesh_int.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#define DEAD UINT32_MAX

/* Zeroed memory for the pass's large arrays, populated in one system call (MAP_POPULATE) rather
 * than faulted in a page at a time on first touch; NULL when it cannot be had. */
static void *big_alloc(size_t bytes)
{
#ifdef MAP_POPULATE
	void *q = mmap(NULL, bytes ? bytes : 1, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
#else
	void *q = mmap(NULL, bytes ? bytes : 1, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
#endif
	return q == MAP_FAILED ? NULL : q;
}

static void big_free(void *p, size_t bytes)
{
	if (p)
		munmap(p, bytes ? bytes : 1);
}

/* The triangles around a vertex. */
typedef struct {
	uint32_t *t;
	uint32_t n, cap;
} ring_t;

typedef struct {
	mesh_t *m;
	const model_shape_t *s;
	double tol;
	size_t v0, t0;           /* the part of m being simplified: vertices >= v0, triangles >= t0 */
	ring_t *ring;            /* per vertex (index - v0) */
	unsigned char *alive;
	uint32_t *mark, stamp;   /* per vertex: the stamp of the last link test that saw it */
	double *nrm;             /* per vertex: unit normal (grad F), valid when nok is set */
	unsigned char *nok;
	uint64_t evals;
	int oom;
} simp_t;

static ring_t *ring_of(simp_t *x, uint32_t v) { return &x->ring[v - x->v0]; }

/* The rings start in one pool, RING0 entries a vertex side by side (a closed mesh's vertex has
 * about 6 triangles); one that outgrows it moves to its own allocation (cap > RING0). */
#define RING0 16

static int ring_add(ring_t *r, uint32_t t)
{
	if (r->n == r->cap) {
		uint32_t cap = 2 * r->cap;
		uint32_t *q = r->cap > RING0 ? realloc(r->t, cap * sizeof *q) : malloc(cap * sizeof *q);
		if (!q)
			return -1;
		if (r->cap <= RING0)
			memcpy(q, r->t, r->n * sizeof *q);
		r->t = q;
		r->cap = cap;
	}
	r->t[r->n++] = t;
	return 0;
}

static void ring_remove(ring_t *r, uint32_t t)
{
	for (uint32_t i = 0; i < r->n; i++)
		if (r->t[i] == t) {
			r->t[i] = r->t[--r->n];
			return;
		}
}

static void normal(const double *p, const double *q, const double *r, double n[3])
{
	double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, w[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
	n[0] = u[1] * w[2] - u[2] * w[1];
	n[1] = u[2] * w[0] - u[0] * w[2];
	n[2] = u[0] * w[1] - u[1] * w[0];
}

static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static int has(const uint32_t *t, uint32_t v) { return t[0] == v || t[1] == v || t[2] == v; }

/* The unit normal of the surface at vertex v (grad F, counted as one evaluation), made once
 * per position of v; NULL when F has no gradient there. */
static const double *vnormal(simp_t *x, uint32_t v)
{
	size_t i = v - x->v0;
	double *n = x->nrm + 3 * i;
	if (!x->nok[i]) {
		mesh_field_grad(x->s, x->m->v + 3 * (size_t)v, n);
		x->evals++;
		double l = sqrt(dot(n, n));
		if (!(l > 0))
			return NULL;
		for (int j = 0; j < 3; j++)
			n[j] /= l;
		x->nok[i] = 1;
	}
	return n;
}

/* Try to collapse the edge a-b into one vertex on the surface; 1 when done. */
static int collapse(simp_t *x, uint32_t a, uint32_t b)
{
	mesh_t *m = x->m;
	double *pa = m->v + 3 * a, *pb = m->v + 3 * b, p[3], g[3];
	const double *na = vnormal(x, a), *nb = vnormal(x, b);
	double k = 0, len = 0;
	if (na && nb) {
		/* the bend along a-b (the angle of the normals over the distance) as a curvature k: a
		 * triangle with corners on a surface of curvature k has its centre about
		 * k (sum of its squared sides) / 18 from it. The triangles a collapse makes around
		 * the merged vertex have sides of the edge's length and more: some triangle's squares
		 * add up to twice the edge's at the least; a collapse that fails even so is not tried
		 * (below, the triangles themselves, before any evaluation) */
		double cs = dot(na, nb), ang = acos(cs > 1 ? 1 : cs < -1 ? -1 : cs);
		double d[3] = {pa[0] - pb[0], pa[1] - pb[1], pa[2] - pb[2]};
		len = sqrt(dot(d, d));
		k = len > 0 ? ang / len : 0;
		if (k * 2 * len * len > 18 * x->tol)
			return 0;
	}
	ring_t *ra = ring_of(x, a), *rb = ring_of(x, b);
	uint32_t shared[2], opp[2];
	int ns = 0;
	for (uint32_t i = 0; i < ra->n; i++) {
		const uint32_t *t = m->t + 3 * ra->t[i];
		if (has(t, b)) {
			if (ns == 2)
				return 0;
			shared[ns] = ra->t[i];
			opp[ns++] = t[0] != a && t[0] != b ? t[0] : t[1] != a && t[1] != b ? t[1] : t[2];
		}
	}
	if (ns != 2 || opp[0] == opp[1])
		return 0;
	/* the link condition: a and b have no neighbour in common but the two opposite vertices
	 * (a's neighbours stamped, b's looked up); on a closed manifold a vertex has as many
	 * neighbours as triangles, and one of fewer than 4 would leave a pinched mesh */
	if (ra->n < 4 || rb->n < 4)
		return 0;
	uint32_t stamp = ++x->stamp;
	for (uint32_t i = 0; i < ra->n; i++)
		for (int j = 0; j < 3; j++)
			x->mark[m->t[3 * ra->t[i] + j] - x->v0] = stamp;
	for (uint32_t i = 0; i < rb->n; i++)
		for (int j = 0; j < 3; j++) {
			uint32_t w = m->t[3 * rb->t[i] + j];
			if (w != a && w != b && w != opp[0] && w != opp[1] && x->mark[w - x->v0] == stamp)
				return 0;
		}
	/* a collapse the surface's bend already forbids, told from the normals at a and b without
	 * evaluating: the arc between them rises tan(angle / 4) / 2 of the edge above its chord,
	 * and the triangles the collapse makes are wider than the edge, their centres farther */
	for (int i = 0; i < 3; i++)
		p[i] = (pa[i] + pb[i]) / 2;
	if (k > 0) {
		/* the same bound on the triangles around the midpoint */
		double lim = 18 * x->tol;
		for (int side = 0; side < 2; side++) {
			ring_t *r = side ? rb : ra;
			uint32_t v = side ? b : a;
			for (uint32_t i = 0; i < r->n; i++) {
				const uint32_t *t = m->t + 3 * r->t[i];
				if (r->t[i] == shared[0] || r->t[i] == shared[1])
					continue;
				const double *q[3];
				for (int j = 0; j < 3; j++)
					q[j] = t[j] == v ? p : m->v + 3 * t[j];
				double e2 = 0;
				for (int j = 0; j < 3; j++) {
					const double *u = q[j], *w = q[(j + 1) % 3];
					double dd[3] = {u[0] - w[0], u[1] - w[1], u[2] - w[2]};
					e2 += dot(dd, dd);
				}
				if (k * e2 > lim)
					return 0;
			}
		}
	}
	/* the new place: the midpoint, moved onto the surface by a Newton step along grad F */
	for (int it = 0; it < 2; it++) {
		double f = mesh_field(x->s, p);
		mesh_field_grad(x->s, p, g);
		x->evals += 2;
		double gg = dot(g, g);
		if (!(gg > 0) || !(f == f))
			return 0;
		for (int i = 0; i < 3; i++)
			p[i] -= f * g[i] / gg;
	}
	double glen = sqrt(dot(g, g));
	/* every triangle that moves: it must keep its side (no fold), then (a second loop, the
	 * one that evaluates) stay within the tolerance */
	for (int pass = 0; pass < 2; pass++)
	for (int side = 0; side < 2; side++) {
		ring_t *r = side ? rb : ra;
		uint32_t v = side ? b : a;
		for (uint32_t i = 0; i < r->n; i++) {
			uint32_t ti = r->t[i];
			if (ti == shared[0] || ti == shared[1])
				continue;
			const uint32_t *t = m->t + 3 * ti;
			const double *q[3], *nq[3];
			for (int j = 0; j < 3; j++) {
				q[j] = m->v + 3 * t[j];
				nq[j] = t[j] == v ? p : q[j];
			}
			if (pass == 0) {
				double n0[3], n1[3];
				normal(q[0], q[1], q[2], n0);
				normal(nq[0], nq[1], nq[2], n1);
				double l0 = sqrt(dot(n0, n0)), l1 = sqrt(dot(n1, n1));
				if (!(l1 > 0) || dot(n0, n1) < 0.5 * l0 * l1)
					return 0;   /* folds over, or turns by more than 60 degrees */
				continue;
			}
			double c[3];
			for (int j = 0; j < 3; j++)
				c[j] = (nq[0][j] + nq[1][j] + nq[2][j]) / 3;
			x->evals++;
			if (fabs(mesh_field(x->s, c)) > x->tol * glen)
				return 0;   /* its centre would lie farther than the tolerance (first order) */
		}
	}
	/* collapse: b's triangles move to a; the two shared ones go */
	memcpy(pa, p, sizeof p);
	x->nok[a - x->v0] = 0;   /* a moved: its normal is made again when asked */
	for (int k = 0; k < 2; k++) {
		uint32_t *t = m->t + 3 * shared[k];
		ring_remove(ra, shared[k]);
		ring_remove(rb, shared[k]);
		ring_remove(ring_of(x, opp[k]), shared[k]);
		t[0] = t[1] = t[2] = DEAD;
	}
	for (uint32_t i = 0; i < rb->n; i++) {
		uint32_t *t = m->t + 3 * rb->t[i];
		for (int j = 0; j < 3; j++)
			if (t[j] == b)
				t[j] = a;
		if (ring_add(ra, rb->t[i]) < 0) {
			x->oom = 1;
			return 0;
		}
	}
	rb->n = 0;
	x->alive[b - x->v0] = 0;
	return 1;
}

typedef struct {
	double len;
	uint32_t a, b;
} edge_t;

/* Edges are tried shortest first, by classes of length half an octave wide; within a
 * class in the order of their triangles, which the extraction made slab by slab, so that
 * neighbouring collapses touch memory the last ones brought in (a global sort by length
 * jumps across the whole mesh at every edge). */
#define LEN_CLASSES 128

static unsigned length_class(double len, double longest)
{
	if (!(len > 0))
		return 0;
	double c = LEN_CLASSES - 1 + 2 * log2(len / longest);
	return c <= 0 ? 0 : c >= LEN_CLASSES - 1 ? LEN_CLASSES - 1 : (unsigned)c;
}

/* One pass over the edges, shortest first; the number of collapses, or -1 (out of memory). */
static long pass(simp_t *x, edge_t *e, edge_t *o)
{
	mesh_t *m = x->m;
	size_t n = 0;
	size_t *start = calloc(LEN_CLASSES + 1, sizeof *start);
	if (!start)
		return -1;
	double longest = 0;
	for (size_t i = x->t0; i < m->nt; i++) {
		const uint32_t *t = m->t + 3 * i;
		if (t[0] == DEAD)
			continue;
		for (int j = 0; j < 3; j++) {
			uint32_t a = t[j], b = t[(j + 1) % 3];
			if (a < b) {   /* each edge of a closed mesh once */
				const double *p = m->v + 3 * a, *q = m->v + 3 * b;
				double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
				e[n++] = (edge_t){sqrt(dot(d, d)), a, b};
				longest = fmax(longest, e[n - 1].len);
			}
		}
	}
	/* a counting sort by class: stable, so each class keeps the triangles' order */
	for (size_t i = 0; i < n; i++)
		start[length_class(e[i].len, longest) + 1]++;
	for (unsigned c = 0; c < LEN_CLASSES; c++)
		start[c + 1] += start[c];
	for (size_t i = 0; i < n; i++)
		o[start[length_class(e[i].len, longest)]++] = e[i];
	free(start);
	long done = 0;
	for (size_t i = 0; i < n && !x->oom; i++)
		if (x->alive[o[i].a - x->v0] && x->alive[o[i].b - x->v0])
			done += collapse(x, o[i].a, o[i].b);
	return x->oom ? -1 : done;
}

int mesh_simplify(mesh_t *m, const model_shape_t *s, size_t v0, size_t t0, double tol,
                  uint64_t *evals, char *err, size_t errlen)
{
	if (m->want_solid) {   /* the tetrahedra hold the vertices a collapse would move */
		snprintf(err, errlen, "expected tolerance 0 for a solid (.msh): coarsening would tear its tetrahedra from the surface");
		return -1;
	}
	if (s->de) {   /* a small estimate does not make a small distance */
		snprintf(err, errlen, "expected tolerance 0 for a distance-estimated shape: its estimate bounds the distance "
		         "only from below, so no tolerance could be kept");
		return -1;
	}
	simp_t x;
	memset(&x, 0, sizeof x);
	x.m = m;
	x.s = s;
	x.tol = tol;
	x.v0 = v0;
	x.t0 = t0;
	size_t nv = m->nv - v0;
	x.ring = calloc(nv + 1, sizeof *x.ring);
	size_t pool_bytes = (nv + 1) * RING0 * sizeof(uint32_t), ecap = 3 * (m->nt - t0) + 1;
	size_t ebytes = ecap * sizeof(edge_t);
	uint32_t *pool = big_alloc(pool_bytes);
	edge_t *ebuf = big_alloc(ebytes), *obuf = big_alloc(ebytes);
	for (size_t i = 0; pool && x.ring && i < nv; i++) {
		x.ring[i].t = pool + i * RING0;
		x.ring[i].cap = RING0;
	}
	x.alive = malloc(nv + 1);
	x.mark = calloc(nv + 1, sizeof *x.mark);
	x.nrm = malloc(3 * (nv + 1) * sizeof *x.nrm);
	x.nok = calloc(nv + 1, 1);
	uint32_t *map = NULL;
	int rc = -1;
	if (!x.ring || !pool || !ebuf || !obuf || !x.alive || !x.mark || !x.nrm || !x.nok)
		goto done;
	memset(x.alive, 1, nv);
	for (size_t i = t0; i < m->nt; i++)
		for (int j = 0; j < 3; j++)
			if (ring_add(ring_of(&x, m->t[3 * i + j]), (uint32_t)i) < 0)
				goto done;
	for (int k = 0; k < 4; k++) {
		long c = pass(&x, ebuf, obuf);
		if (c < 0)
			goto done;
		if ((size_t)c * 20 < nv)
			break;   /* under 5% more: done (the first pass does nearly all) */
	}
	/* compact: live vertices renumbered in order, dead triangles dropped */
	map = malloc((nv + 1) * sizeof *map);
	if (!map)
		goto done;
	size_t w = v0;
	for (size_t i = 0; i < nv; i++)
		if (x.alive[i]) {
			map[i] = (uint32_t)w;
			memmove(m->v + 3 * w, m->v + 3 * (v0 + i), 3 * sizeof *m->v);
			w++;
		}
	m->nv = w;
	w = t0;
	for (size_t i = t0; i < m->nt; i++) {
		const uint32_t *t = m->t + 3 * i;
		if (t[0] == DEAD)
			continue;
		for (int j = 0; j < 3; j++)
			m->t[3 * w + j] = map[t[j] - v0];
		w++;
	}
	m->nt = w;
	rc = 0;
done:
	if (rc < 0)
		snprintf(err, errlen, "out of memory simplifying the mesh");
	if (x.ring)
		for (size_t i = 0; i < nv; i++)
			if (x.ring[i].cap > RING0)
				free(x.ring[i].t);
	free(x.ring);
	big_free(pool, pool_bytes);
	big_free(ebuf, ebytes);
	big_free(obuf, ebytes);
	free(x.alive);
	free(x.mark);
	free(x.nrm);
	free(x.nok);
	free(map);
	if (evals)
		*evals += x.evals;
	return rc;
}
