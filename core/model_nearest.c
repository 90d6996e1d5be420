/* model_nearest.c: the nearest point of each kind of distance element (the setup frame). */
#include "model.h"

#include <math.h>
#include <string.h>

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double len3(const double *a) { return sqrt(dot3(a, a)); }

/* The point c of segment a b nearest to p; returns |p - c|. */
static double seg_nearest(const double *p, const double *a, const double *b, double c[3])
{
	double ba[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
	double pa[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
	double l2 = dot3(ba, ba), h = l2 > 0 ? dot3(pa, ba) / l2 : 0;
	h = h < 0 ? 0 : h > 1 ? 1 : h;
	for (int j = 0; j < 3; j++)
		c[j] = a[j] + h * ba[j];
	double d[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
	return len3(d);
}

double model_elem_nearest(const model_elem_t *e, const double *p, double *q)
{
	double best = INFINITY;
	switch (e->kind) {
	case MODEL_VORONOI: {
		/* e_k = d(p, N_k) - w_k; the estimate (e2 - e1)/2 has gradient (u2 - u1)/2
		 * with u the unit vectors from the nearest points of the two nuclei; q is
		 * placed so that (p - q) / estimate is that gradient */
		double e1 = INFINITY, e2 = INFINITY, n1[3] = {0, 0, 0}, n2[3] = {0, 0, 0}, d1 = 0, d2 = 0, m1 = 1, m2 = 1;
		/* the nucleus being gathered (a run of segments): its smallest e, nearest point, d, 1/M */
		double ce = INFINITY, cn[3] = {0, 0, 0}, cd = 0, cm = 1;
		for (size_t k = 0; k <= e->np; k++) {
			if (k == e->np || k == 0 || e->grp[k] != e->grp[k - 1]) {
				if (k > 0) {   /* fold the finished nucleus into the two smallest */
					if (ce < e1) {
						e2 = e1, d2 = d1, m2 = m1;
						memcpy(n2, n1, sizeof n1);
						e1 = ce, d1 = cd, m1 = cm;
						memcpy(n1, cn, sizeof cn);
					} else if (ce < e2) {
						e2 = ce, d2 = cd, m2 = cm;
						memcpy(n2, cn, sizeof cn);
					}
				}
				ce = INFINITY;
				if (k == e->np)
					break;
			}
			double c[3], d = seg_nearest(p, e->p + 6 * k, e->p + 6 * k + 3, c);
			double ev = d * e->nm[k] - e->nw[k];
			if (ev < ce) {
				ce = ev, cd = d, cm = e->nm[k];
				memcpy(cn, c, sizeof c);
			}
		}
		double est = (e2 - e1) / 2;
		for (int j = 0; j < 3; j++) {
			double u1 = d1 > 0 ? m1 * (p[j] - n1[j]) / d1 : 0, u2 = d2 > 0 ? m2 * (p[j] - n2[j]) / d2 : 0;
			q[j] = p[j] - est * (u2 - u1) / 2;
		}
		return est;
	}
	case MODEL_POINT: case MODEL_POINTS:
		for (size_t k = 0; k < e->np; k++) {
			const double *a = e->p + 3 * k;
			double d[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
			double l = len3(d);
			if (l < best) {
				best = l;
				memcpy(q, a, 3 * sizeof *q);
			}
		}
		return best;
	case MODEL_SEGMENT: case MODEL_POLYLINE:
		for (size_t k = 0; k + 1 < e->np; k++) {
			double c[3], l = seg_nearest(p, e->p + 3 * k, e->p + 3 * k + 3, c);
			if (l < best) {
				best = l;
				memcpy(q, c, sizeof c);
			}
		}
		return best;
	case MODEL_BOX:
		for (int j = 0; j < 3; j++) {
			double lo = fmin(e->p[j], e->p[3 + j]), hi = fmax(e->p[j], e->p[3 + j]);
			q[j] = p[j] < lo ? lo : p[j] > hi ? hi : p[j];
		}
		return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
	case MODEL_TRIANGLE: case MODEL_POLYGON: {
		const double *v = e->p, *n = e->p + 3 * e->np;
		double h = (p[0] - v[0]) * n[0] + (p[1] - v[1]) * n[1] + (p[2] - v[2]) * n[2];
		double pp[3] = {p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]};
		/* inside test in the plane: the crossing number along the axis pair the normal leaves */
		int ax = fabs(n[0]) >= fabs(n[1]) && fabs(n[0]) >= fabs(n[2]) ? 0 : fabs(n[1]) >= fabs(n[2]) ? 1 : 2;
		int i0 = (ax + 1) % 3, i1 = (ax + 2) % 3, in = 0;
		for (size_t k = 0, j = e->np - 1; k < e->np; j = k++) {
			const double *a = v + 3 * k, *b = v + 3 * j;
			if ((a[i1] > pp[i1]) != (b[i1] > pp[i1])
			    && pp[i0] < (b[i0] - a[i0]) * (pp[i1] - a[i1]) / (b[i1] - a[i1]) + a[i0])
				in = !in;
		}
		if (in) {
			memcpy(q, pp, sizeof pp);
			return fabs(h);
		}
		for (size_t k = 0; k < e->np; k++) {
			double c[3], l = seg_nearest(p, v + 3 * k, v + 3 * ((k + 1) % e->np), c);
			if (l < best) {
				best = l;
				memcpy(q, c, sizeof c);
			}
		}
		return best;
	}
	case MODEL_CIRCLE: {
		const double *a = e->p, *n = e->p + 3;
		double v[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
		double h = dot3(v, n);
		double rv[3] = {v[0] - h * n[0], v[1] - h * n[1], v[2] - h * n[2]}, rho = len3(rv);
		if (!(rho > 0)) {   /* on the axis: every ring point is nearest; take one */
			double t[3] = {fabs(n[0]) < 0.9 ? 1 : 0, fabs(n[0]) < 0.9 ? 0 : 1, 0}, k = dot3(t, n);
			for (int i = 0; i < 3; i++)
				rv[i] = t[i] - k * n[i];
			rho = len3(rv);
		}
		for (int i = 0; i < 3; i++)
			q[i] = a[i] + e->r / rho * rv[i];
		double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
		return len3(d);
	}
	case MODEL_LINE: case MODEL_PLANE: case MODEL_DISK: {
		const double *a = e->p, *n = e->p + 3;
		double v[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
		double h = dot3(v, n);
		if (e->kind == MODEL_LINE) {
			for (int i = 0; i < 3; i++)
				q[i] = a[i] + h * n[i];
		} else {
			double rv[3] = {v[0] - h * n[0], v[1] - h * n[1], v[2] - h * n[2]};
			double rho = len3(rv), s = 1;
			if (e->kind == MODEL_DISK && rho > e->r)
				s = e->r / rho;
			for (int i = 0; i < 3; i++)
				q[i] = a[i] + s * rv[i];
		}
		double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
		return len3(d);
	}
	}
	return 0;
}
