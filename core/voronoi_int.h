/* voronoi_int.h: internals shared by the voronoi*.c files (not part of the public API). */
#ifndef LOCUS_VORONOI_INT_H
#define LOCUS_VORONOI_INT_H

#include <math.h>

#include "msq.h"
#include "voronoi.h"

/* The squared distance from p to the closed segment ab. */
static inline double voronoi_seg_dist2(const double *a, const double *b, const double p[3])
{
	double dx = p[0] - a[0], dy = p[1] - a[1], dz = p[2] - a[2];
	double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
	double uu = ux * ux + uy * uy + uz * uz;
	if (uu > 0) {
		double t = (dx * ux + dy * uy + dz * uz) / uu;
		t = t < 0 ? 0 : t > 1 ? 1 : t;
		dx -= t * ux;
		dy -= t * uy;
		dz -= t * uz;
	}
	return dx * dx + dy * dy + dz * dz;
}

/* d(P, N), inlined where it is hot; voronoi_distance() is this function, so
 * every caller gets bit-identical results (ISO C mode: no FMA contraction). */
static inline double voronoi_dist(const voronoi_nucleus_t *n, const double p[3])
{
	if (n->kind == VORONOI_SEGMENT)
		return sqrt(voronoi_seg_dist2(n->a, n->b, p));
	if (n->kind == VORONOI_POLYLINE) {
		double d2 = INFINITY;
		for (size_t i = 0; i + 1 < n->npts; i++) {
			double e = voronoi_seg_dist2(n->pts + 3 * i, n->pts + 3 * i + 3, p);
			d2 = e < d2 ? e : d2;
		}
		return sqrt(d2);
	}
	double dx = p[0] - n->a[0], dy = p[1] - n->a[1], dz = p[2] - n->a[2];
	return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Record a printf-style error message for voronoi_error() and return code. */
#define voronoi_fail msq_fail

/* The inverse of v->m: page point (px, py) to plane point (*X, *Y). */
typedef struct {
	double m0, m3;          /* page origin offsets */
	double a, b, c, d;      /* X = a (px - m0) + b (py - m3); Y = c (px - m0) + d (py - m3) */
} voronoi_inv_t;

/* Fill inv from v->m; returns VORONOI_EARG when m is singular. */
int voronoi_invert(const voronoi_t *v, voronoi_inv_t *inv);

/* Plane point of a page point, z = 0. */
static inline void voronoi_unmap(const voronoi_inv_t *inv, double px, double py, double p[3])
{
	double dx = px - inv->m0, dy = py - inv->m3;
	p[0] = inv->a * dx + inv->b * dy;
	p[1] = inv->c * dx + inv->d * dy;
	p[2] = 0;
}

#endif
